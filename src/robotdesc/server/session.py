"""The editor session: which descriptions a file belongs to, their findings per file, and
the source edits of a finding's fix. No LSP here (see lsp.py)."""

from __future__ import annotations

import dataclasses
import logging
import os
from collections.abc import Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from robotdesc.diagnostics import Diagnostic
from robotdesc.errors import InputError
from robotdesc.expansion import ExpandOptions
from robotdesc.expansion.packages import enclosing_package
from robotdesc.linting.driver import lint_expanded
from robotdesc.linting.fix.engine import FIXED, FixOutcome, plan_fixes
from robotdesc.linting.matrix import Variant
from robotdesc.linting.parallel import cached_result, lint_target
from robotdesc.linting.targets import LintTarget, discover_targets
from robotdesc.rules.fixes import Applicability
from robotdesc.server.edits import literal_changes, patch_document

if TYPE_CHECKING:
    from robotdesc.linting.result import LintResult

log = logging.getLogger(__name__)

SUFFIXES = (".urdf", ".xacro")

#: A linted description: (target path, its xacro arguments: the config target's and its
#: matrix variant's). Not the variant alone: config targets that differ only in their
#: fixed `args` (the Engineer's three) have no variant.
TargetKey = tuple[str, Variant]


def target_key(target: LintTarget) -> TargetKey:
    """The key of a target in the session."""
    return (target.path, tuple(target.args) + tuple(target.variant))


@dataclass(frozen=True)
class TextEdit:
    """Replace the text between two (0-based line, UTF-16 column) positions of a file."""

    path: str
    start: tuple[int, int]
    end: tuple[int, int]
    text: str


@dataclass(frozen=True)
class FixAction:
    """One finding's fix, as the editor applies it."""

    title: str
    diagnostic: Diagnostic
    safe: bool
    edits: tuple[TextEdit, ...]


class Session:
    """The descriptions linted so far, their results, and what was published where."""

    def __init__(self, expand_options: Any = None) -> None:
        self.expand_options = expand_options
        self.results: dict[TargetKey, LintResult] = {}
        self.targets: dict[TargetKey, LintTarget] = {}
        self.failures: dict[TargetKey, InputError] = {}
        #: per linted description: its sources' bytes and its inputs' file states, as the
        #: expansion in `results` saw them (what a save's edit is compared with)
        self.snapshots: dict[TargetKey, dict[str, bytes]] = {}
        self.states: dict[TargetKey, dict[str, FileState | None]] = {}

    # -- linting ------------------------------------------------------------------------

    def targets_for(self, path: str) -> list[LintTarget]:
        """The top-level descriptions `path` takes part in: those of its package (or its
        folder) whose expansion read it, else the file itself when it is one."""
        path = os.path.abspath(path)
        known = [self.targets[key] for key, result in self.results.items()
                 if path in _sources(result)]
        if known:
            return known
        package = enclosing_package(path)
        folder = str(package[1]) if package else os.path.dirname(path)
        try:
            candidates = list(discover_targets(folder).targets)
        except InputError:
            candidates = []
        if any(t.path == path for t in candidates):
            return [t for t in candidates if t.path == path]
        return candidates

    def lint(self, path: str) -> dict[str, list[Diagnostic]]:
        """Lint the descriptions `path` belongs to; findings per file (every file that had
        or has one in them, and `path` itself, so that the caller can clear stale ones and
        say that a clean file is clean). A description none of whose inputs changed (a
        variant that does not include the saved file) is read from the result cache."""
        path = os.path.abspath(path)
        touched: set[str] = {path}
        for target in self.targets_for(path):
            key = target_key(target)
            old = self.results.get(key)
            if old is not None:
                touched.update(_finding_paths(old.diagnostics))
            try:
                result = self._edited(key, target, path) \
                    or cached_result(target, {}, self._options(), None, ()) \
                    or self._linted(key, target)
            except InputError as error:
                self.failures[key] = error
                self.results.pop(key, None)
                continue
            self.failures.pop(key, None)
            self.targets[key], self.results[key] = target, result
            touched.update(_finding_paths(result.diagnostics))
        return {file: self.findings(file) for file in touched}

    def _linted(self, key: TargetKey, target: LintTarget) -> LintResult:
        """A full lint (expansion included), remembered with its sources' text."""
        result = lint_target(target, {}, self._options(), None, ())
        expanded = result.expanded
        self.snapshots[key] = {file: data for file in (expanded.files if expanded else ())
                               if (data := _read(file)) is not None}
        self.states[key] = {item.path: _state(item.path) for item in
                            (result.inputs.items if result.inputs is not None else ())}
        return result

    def _edited(self, key: TargetKey, target: LintTarget, path: str) -> LintResult | None:
        """The lint of a save that changed only literal attribute values of `path`, on the
        previous expansion edited in place (`robotdesc.server.edits`); None when the save is
        not such an edit, or another input changed too."""
        old, snapshot = self.results.get(key), self.snapshots.get(key, {})
        if old is None or old.expanded is None or path not in snapshot:
            return None
        states = self.states.get(key, {})
        real = os.path.realpath(path)
        if any(_state(file) != state for file, state in states.items() if file != real):
            return None  # something else changed as well: expand again
        data = _read(path)
        if data is not None and data == snapshot[path] and _state(real) == states.get(real):
            return old  # saved without a change: nothing to do
        changes = None if data is None else literal_changes(snapshot[path], data)
        if data is None or changes is None:
            return None
        xml = patch_document(old.expanded.xml, old.expanded.files, path, changes)
        if xml is None:
            return None
        options = self._options()
        options = dataclasses.replace(options, package_map=tuple(options.package_map)
                                      + tuple(target.config.packages))
        result = lint_expanded(target.path, dataclasses.replace(old.expanded, xml=xml),
                               target.config, options)
        log.info("%s: %d value(s) changed in %s, linted without expanding again",
                 target.name(), len(changes), os.path.basename(path))
        snapshot[path] = data
        states[real] = _state(real)
        return dataclasses.replace(result, variant=target.variant, inputs=old.inputs)

    def findings(self, path: str) -> list[Diagnostic]:
        """The findings of every linted description at `path`, each once (matrix variants
        repeat them)."""
        seen: set[tuple[str, int, str]] = set()
        found: list[Diagnostic] = []
        for result in self.results.values():
            for diagnostic in result.diagnostics:
                span = diagnostic.where.span if diagnostic.where else None
                key = (diagnostic.code, span.line if span else 0, diagnostic.message)
                if span is not None and span.path == path and key not in seen:
                    seen.add(key)
                    found.append(diagnostic)
        return found

    def errors(self, path: str) -> list[InputError]:
        """Input errors (expansion or parse) located in `path`."""
        return [e for e in self.failures.values()
                if e.span is not None and e.span.path == path]

    # -- fixes --------------------------------------------------------------------------

    def fix_actions(self, path: str, lines: tuple[int, int], unsafe: bool = True
                    ) -> list[FixAction]:
        """The fixes of the findings at `path` whose line is within `lines` (1-based)."""
        wanted = [d for d in self.findings(path)
                  if d.where is not None and lines[0] <= d.where.span.line <= lines[1]]
        if not wanted:
            return []
        actions: list[FixAction] = []
        for outcome in self._outcomes(unsafe):
            diagnostic = outcome.diagnostic
            if outcome.status == FIXED and any(_same(diagnostic, w) for w in wanted) \
                    and not any(_same(diagnostic, a.diagnostic) for a in actions):
                actions.append(_action(outcome))
        return actions

    def fix_all(self, path: str) -> list[FixAction]:
        """The safe fixes of every finding of the descriptions `path` belongs to."""
        keys = {target_key(t) for t in self.targets_for(path)}
        return [_action(o) for o in self._outcomes(False, keys) if o.status == FIXED]

    def _outcomes(self, unsafe: bool, keys: Iterable[TargetKey] | None = None
                  ) -> list[FixOutcome]:
        chosen = [k for k in self.results if keys is None or k in keys]
        for key in chosen:  # a result read from the cache has no expansion: lint it now
            if self.results[key].expanded is None:
                self.results[key] = lint_target(self.targets[key], {}, self._options(),
                                                None, ())
        results = [self.results[k] for k in chosen]
        return list(plan_fixes(results, unsafe=unsafe).outcomes)

    def _options(self) -> Any:
        return self.expand_options if self.expand_options is not None else ExpandOptions()


#: A file's state as `os.stat` gives it: size, modification time (ns), inode.
FileState = tuple[int, int, int]


def _state(path: str) -> FileState | None:
    try:
        info = os.stat(path)
    except OSError:
        return None
    return (info.st_size, info.st_mtime_ns, info.st_ino)


def _read(path: str) -> bytes | None:
    try:
        with open(path, "rb") as stream:
            return stream.read()
    except OSError:
        return None


def _sources(result: LintResult) -> set[str]:
    """The files a result depends on, as given and as real paths."""
    expanded = result.expanded
    files = {result.target, *result.files_read}
    if expanded is not None:
        files.update(expanded.files)
        files.update(expanded.files_read)
    return files | {os.path.realpath(f) for f in files}


def _finding_paths(diagnostics: Iterable[Diagnostic]) -> set[str]:
    return {d.where.span.path for d in diagnostics if d.where is not None}


def _same(a: Diagnostic, b: Diagnostic) -> bool:
    return (a.code, a.element, a.message) == (b.code, b.element, b.message)


def _action(outcome: FixOutcome) -> FixAction:
    diagnostic = outcome.diagnostic
    safe = outcome.applicability is Applicability.SAFE
    title = f"Fix {diagnostic.code} ({diagnostic.name})" + ("" if safe else " [unsafe]")
    texts: dict[str, str] = {}
    edits = []
    for edit in outcome.edits:
        if edit.path not in texts:
            with open(edit.path, "rb") as handle:
                texts[edit.path] = handle.read().decode("utf-8")
        text = texts[edit.path]
        edits.append(TextEdit(edit.path, position(text, edit.start), position(text, edit.end),
                              edit.text))
    return FixAction(title, diagnostic, safe, tuple(edits))


def position(text: str, offset: int) -> tuple[int, int]:
    """The LSP position (0-based line, UTF-16 code units) of a string offset."""
    line, begin, index = 0, 0, 0
    while True:
        found = min((i for i in (text.find("\r", index, offset), text.find("\n", index, offset))
                     if i >= 0), default=-1)
        if found < 0:
            break
        step = 2 if text.startswith("\r\n", found) and found + 1 < offset else 1
        line, begin, index = line + 1, found + step, found + step
    return line, len(text[begin:offset].encode("utf-16-le")) // 2
