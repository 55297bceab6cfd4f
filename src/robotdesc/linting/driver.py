"""The lint pipeline for one file: expand -> parse -> rules -> ignores -> suppressions.

I/O happens here (reading the description and its sources); the rules stay pure.
"""

from __future__ import annotations

import dataclasses
import fnmatch
import logging
import os
import sys
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from robotdesc.cache_dir import cache_folder
from robotdesc.config import Config, discover_config
from robotdesc.diagnostics import Diagnostic, Finding, Severity
from robotdesc.errors import RobotdescError, RuleCrashed
from robotdesc.expansion import Expanded, ExpandOptions, expand_file
from robotdesc.kinematics.optional import pinocchio_available
from robotdesc.kinematics.verdict import Verdict, start_verdict
from robotdesc.linting import rule_cache
from robotdesc.linting.package_reader import named_controller_files, read_package_files
from robotdesc.linting.result import LintResult
from robotdesc.linting.suppress import Suppression, apply_suppressions, scan_files, unused_codes
from robotdesc.linting.warmup import import_ahead, lint_imports, pinocchio_in_child, verdict_users
from robotdesc.mesh.cache import MeshCache
from robotdesc.mesh.context import MeshContext
from robotdesc.mesh.resolve import PackageLookup
from robotdesc.model.elements import Robot
from robotdesc.rules.registry import ExpansionFacts, Rule, RuleContext, SourceDocument, run_rule
from robotdesc.rules.select import is_selected, select_rules
from robotdesc.source import Provenance, Span

if TYPE_CHECKING:
    from _typeshed import DataclassInstance

log = logging.getLogger(__name__)

UNUSED_SUPPRESSION = "RD001"

__all__ = ["LintResult", "RuleCrashed", "lint_expanded", "lint_file"]


def lint_file(path: str, config: Config | None = None, *,
              args: Mapping[str, str] | None = None,
              expand_options: ExpandOptions | None = None,
              select: Sequence[str] | None = None, ignore: Sequence[str] = (),
              find_package: PackageLookup | None = None) -> LintResult:
    """Lint one description (.urdf, .urdf.xacro, .xacro).

    Args:
        path: the file to lint.
        config: the settings (default: discovered by walking up from `path`).
        args: xacro arguments; they override the config's `args`.
        expand_options: the expansion settings; the config's packages are added to its
            `package_map` after the explicit ones.
        select: rule selectors that replace the config's `select`.
        ignore: rule selectors added to the config's `ignore`.
        find_package: the run's package lookup (`expansion.packages.package_lookup` of
            `path`, `--package-path` and the package map with the config's packages), when
            the caller built it to use it again; None: built here when a rule needs meshes.

    Raises:
        InputError: the file could not be expanded or parsed (exit code 2).
        RuleCrashed: a rule raised (a bug, exit code 3).
    """
    target = os.path.abspath(path)
    config = config if config is not None else discover_config(target)
    options = expand_options or ExpandOptions()
    options = dataclasses.replace(options, package_map=tuple(options.package_map)
                                  + tuple(config.packages))
    merged_args = {**dict(config.args), **dict(args or {})}
    options = dataclasses.replace(options, unchecked_args=tuple(
        name for name, _ in config.args if name not in (args or {})))
    chosen_select, chosen_ignore = _selection(config, select, ignore)
    verdicts: list[Verdict] = []

    def while_expanding() -> None:  # this process has nothing else to do meanwhile
        import_ahead(lint_imports(chosen_select, chosen_ignore,
                                  analyze_meshes=_meshes_analyzed(config, options)))
        try:
            from robotdesc.rules.catalog import all_rules

            rules = select_rules(all_rules(), chosen_select, chosen_ignore)
        except Exception as error:  # the lint selects again, and fails there if it must
            log.debug("no work ahead: %s: %s", type(error).__name__, error)
            return
        if pinocchio_in_child(rules) and "pinocchio" not in sys.modules \
                and pinocchio_available():
            verdict = start_verdict()
            if verdict is not None:
                verdicts.append(verdict)

    try:
        expanded = expand_file(target, merged_args, options=options,
                               while_expanding=while_expanding)
        return lint_expanded(target, expanded, config, options, select=select, ignore=ignore,
                             find_package=find_package,
                             verdict=verdicts[0] if verdicts else None)
    finally:
        for verdict in verdicts:
            verdict.close()


def _selection(config: Config, select: Sequence[str] | None, ignore: Sequence[str]
               ) -> tuple[Sequence[str] | None, tuple[str, ...]]:
    """The selectors that apply: the caller's `select` (else the config's), and the
    config's `ignore` with the caller's."""
    return (tuple(select) if select is not None else config.select,
            tuple(config.ignore) + tuple(ignore))


def _meshes_analyzed(config: Config, options: ExpandOptions) -> bool:
    """Whether this lint's mesh summaries will be computed rather than read: no mesh cache,
    or one that holds nothing yet (a first run, a fresh CI machine)."""
    folder = cache_folder(config.meshes.cache and options.use_cache, options.cache_dir)
    return folder is None or MeshCache(folder).is_empty()


def lint_expanded(target: str, expanded: Expanded, config: Config, options: ExpandOptions, *,
                  select: Sequence[str] | None = None, ignore: Sequence[str] = (),
                  find_package: PackageLookup | None = None,
                  verdict: Verdict | None = None) -> LintResult:
    """Lint an expansion of `target` (parse, rules, ignores, suppressions): `lint_file`
    after its expansion, also for a document the caller changed (the language server's
    edit of a literal value).

    Args:
        target: the linted file (absolute).
        expanded: its expansion.
        config: the settings that apply.
        options: the expansion settings it was made with (`package_map` with the config's
            packages: the meshes resolve through them).
        select, ignore, find_package: as `lint_file`.
        verdict: a child started to decide Pinocchio's verdict (`lint_file`): given the
            model when the rule cache does not hold the findings that need it.

    Raises:
        InputError: the document could not be parsed (exit code 2).
        RuleCrashed: a rule raised (a bug, exit code 3).
    """
    from robotdesc.model.parse import parse_urdf
    from robotdesc.rules.catalog import all_rules

    robot = parse_urdf(expanded.xml, expanded.source, expanded.files)

    chosen_select, chosen_ignore = _selection(config, select, ignore)
    registered = all_rules()
    rules = select_rules(registered, chosen_select, chosen_ignore)
    facts = ExpansionFacts(expanded.macro_recursion, expanded.files_read, expanded.from_xacro,
                           notes=expanded.notes,
                           package_folders=tuple(p.path for p in expanded.packages))
    fallback = robot.where or Provenance(Span(expanded.source))
    document = SourceDocument(expanded.xml, expanded.source, tuple(expanded.files))

    meshes = _mesh_context(rules, robot, target, config, options, find_package)
    found: dict[str, list[Diagnostic]] = {}
    if meshes is not None:
        meshes.summarize_ahead()  # first: the longest work beside this process
    if verdict is not None and _verdict_wanted(rules, robot, expanded, config, options):
        verdict.submit(robot)  # decided beside the other rules, which take it last
    elif verdict is not None:
        verdict.close()
        verdict = None
    try:  # the rules that read no mesh first, those that take a child's verdict last
        package = (read_package_files(target, tuple((p.name, p.path) for p in expanded.packages),
                                      named_controller_files(expanded.xml))
                   if any("package" in rule.needs for rule in rules) else None)
        for rule in sorted(rules, key=lambda rule: _waits_for(rule, verdict)):
            context = RuleContext(options=_rule_options(rule, config), expansion=facts,
                                  meshes=meshes if "meshes" in rule.needs else None,
                                  document=document if "document" in rule.needs else None,
                                  package=package if "package" in rule.needs else None)
            try:
                findings = _run_cached(rule, robot, context, expanded, options)
            except RobotdescError:
                raise
            except Exception as exc:  # a crashing rule is a bug: report it, naming the rule
                raise RuleCrashed(rule.code, rule.name, target, exc) from exc
            severity = config.severity_for(rule.code, rule.severity)
            found[rule.code] = [_diagnostic(rule, severity, f, fallback, target)
                                for f in findings]
    finally:
        if meshes is not None:
            meshes.close()
        if verdict is not None:
            verdict.close()
    diagnostics = [d for rule in rules for d in found[rule.code]]  # in the rules' order

    ignored = [d for d in diagnostics if _ignored_for_file(d, config)]
    diagnostics = [d for d in diagnostics if not _ignored_for_file(d, config)]
    sources = (expanded.source, *expanded.files_read, *expanded.files)
    suppressions = scan_files(p for p in sources if p and os.path.isfile(p))
    outcome = apply_suppressions(diagnostics, suppressions)
    kept = list(outcome.kept)
    unused_rule = next((r for r in registered if r.code == UNUSED_SUPPRESSION), None)
    if unused_rule is not None and unused_rule in rules:
        ran = {r.code for r in rules} | {r.name for r in rules}
        known = {r.code for r in registered} | {r.name for r in registered}
        severity = config.severity_for(unused_rule.code, unused_rule.severity)
        unused = (_diagnostic(unused_rule, severity, finding, fallback, target)
                  for finding in _unused_findings(suppressions, outcome.used, ran, known))
        kept.extend(d for d in unused if not _ignored_for_file(d, config))
    log.debug("%s: %d rules ran, %d diagnostics, %d suppressed", target, len(rules), len(kept),
              len(outcome.suppressed))
    return LintResult(target=target, diagnostics=tuple(sorted(kept, key=Diagnostic.sort_key)),
                      expanded=expanded, robot=robot, suppressed=len(outcome.suppressed),
                      suppressed_by_config=len(ignored),
                      config_path=config.path, rules_run=tuple(r.code for r in rules),
                      hidden=tuple(outcome.suppressed) + tuple(ignored))


def _run_cached(rule: Rule, robot: Robot, context: RuleContext, expanded: Expanded,
                options: ExpandOptions) -> list[Finding]:
    """Run one rule; the findings of expensive rules come from the rule cache when valid."""
    if not (options.use_cache and rule_cache.is_cached(rule)):
        return list(run_rule(rule, robot, context))
    folder, key, found = _cached(rule, context.options, robot, expanded, options,
                                 _mesh_files(context))
    if found is None:
        found = list(run_rule(rule, robot, context))
        rule_cache.store(folder, key, found)
    return found


def _cached(rule: Rule, rule_options: DataclassInstance | None, robot: Robot,
            expanded: Expanded, options: ExpandOptions, mesh_files: Sequence[str]
            ) -> tuple[Path | None, str, list[Finding] | None]:
    """The rule cache's folder, the rule's key there, and its findings when stored."""
    folder = cache_folder(options.use_cache, options.cache_dir)
    key = rule_cache.rule_key(rule, rule_options, expanded.xml, mesh_files,
                              source=robot.source or "")
    sources = frozenset((expanded.source, *expanded.files, *expanded.files_read))
    return folder, key, rule_cache.load(folder, key, sources)


def _rule_options(rule: Rule, config: Config) -> DataclassInstance | None:
    """The rule's options: the config's, else its defaults."""
    configured: DataclassInstance | None = config.options_for(rule.code)
    return configured if configured is not None else rule.default_options()


def _waits_for(rule: Rule, verdict: Verdict | None) -> int:
    """How late a rule runs: 0 for those that read no mesh, 1 for those that do (meanwhile a
    forked child may summarize the meshes), 2 for those that take the verdict a child is
    deciding (meanwhile it imports Pinocchio, if it has not yet)."""
    if verdict is not None and "pinocchio" in rule.needs:
        return 2
    return 1 if "meshes" in rule.needs else 0


def _verdict_wanted(rules: Sequence[Rule], robot: Robot, expanded: Expanded, config: Config,
                    options: ExpandOptions) -> bool:
    """Whether the model goes to the child that decides Pinocchio's verdict: the rules that
    need Pinocchio need nothing else of it (`verdict_users`), and the rule cache does not
    hold all their findings already."""
    users = verdict_users(rules)
    if not users:
        return False
    return not options.use_cache or any(
        _cached(rule, _rule_options(rule, config), robot, expanded, options, ())[2] is None
        for rule in users)


def _mesh_files(context: RuleContext) -> list[str]:
    """The resolved files of every `<mesh>` (for rules that read meshes)."""
    if context.meshes is None:
        return []
    return [context.meshes.lookup(ref).resolution.path or ref.filename
            for _link, _kind, _index, _element, ref in context.meshes.meshes()]


def _mesh_context(rules: Sequence[Rule], robot: Robot, target: str, config: Config,
                  options: ExpandOptions, find_package: PackageLookup | None
                  ) -> MeshContext | None:
    """The mesh access for rules that need meshes; None otherwise (nothing is read before a
    rule asks)."""
    if not any("meshes" in rule.needs for rule in rules):
        return None
    return MeshContext.for_file(robot, target, config.meshes, tuple(options.package_paths),
                                tuple(options.package_map), use_cache=options.use_cache,
                                cache_dir=options.cache_dir, find_package=find_package)


def _diagnostic(rule: Rule, severity: Severity, finding: Finding, fallback: Provenance,
                target: str) -> Diagnostic:
    return Diagnostic(code=rule.code, name=rule.name, severity=severity,
                      message=finding.message, where=finding.where or fallback,
                      element=finding.element, fix=finding.fix, target=target,
                      changes=finding.changes, unfixable=finding.unfixable)


def _unused_findings(suppressions: Iterable[Suppression],
                     used: frozenset[tuple[Suppression, str]], ran: set[str],
                     known: set[str]) -> Iterable[Finding]:
    """RD001 findings: comments naming no code, unknown codes, and codes that hit nothing.

    A code of a rule that did not run (not selected) is not reported: it cannot be judged.
    """
    written = list(suppressions)
    for suppression in written:
        where = Provenance(Span(suppression.path, suppression.line, suppression.col))
        if not suppression.codes:
            yield Finding("suppression comment names no rule code "
                          "(write `robotdesc: ignore CODE`)", where, "comment")
    for suppression, code in unused_codes(written, used):
        where = Provenance(Span(suppression.path, suppression.line, suppression.col))
        if code not in known:
            yield Finding(f"suppression names unknown rule '{code}'", where, f"comment:{code}")
        elif code in ran:
            yield Finding(f"unused suppression: no {code} finding on this line or the next",
                          where, f"comment:{code}")


def _ignored_for_file(diagnostic: Diagnostic, config: Config) -> bool:
    """Whether a per-file ignore of the config matches the finding's file or the target."""
    if not config.per_file_ignores:
        return False
    paths = {diagnostic.target}
    if diagnostic.where is not None:
        paths.add(diagnostic.where.span.path)
    for glob, selectors in config.per_file_ignores:
        if is_selected(diagnostic.code, diagnostic.name, selectors) and any(
                _glob_matches(glob, p, config.root) for p in paths if p):
            return True
    return False


def _glob_matches(glob: str, path: str, root: str) -> bool:
    """Match `path` against a per-file-ignores glob relative to the config's directory.

    A glob without "/" matches the file name anywhere; a leading "**/" may match nothing.
    """
    absolute = os.path.abspath(path)
    relative = os.path.relpath(absolute, root).replace(os.sep, "/")
    pattern = glob.replace(os.sep, "/")
    if "/" not in pattern:
        return fnmatch.fnmatch(os.path.basename(absolute), pattern)
    candidates = {pattern, pattern.removeprefix("**/")}
    return any(fnmatch.fnmatch(relative, p) or fnmatch.fnmatch(absolute, p) for p in candidates)
