"""The imports a lint needs after its expansion, done ahead in a background thread while the
xacro worker expands (the parent only waits for the worker's answer then; with a core free
the imports and the expansion overlap). The thread starts once the worker runs
(`expand_file(on_worker_start=)`), so that it never delays the worker's start, and not at all
when the expansion comes from its cache or the file is a plain URDF.

`ImportsAhead` imports module after module until the caller stops it; `stop()` waits for the
module being imported to finish, so that after it no import runs in two threads. An import
that fails here is forgotten: the lint imports the module again where it needs it, and fails
there exactly as it would have without this (Python does not keep a failed module).
"""

from __future__ import annotations

import importlib
import importlib.util
import logging
import sys
import threading
from collections.abc import Callable, Iterable, Iterator, Sequence

from robotdesc.mesh.prefetch import forks_here
from robotdesc.rules.select import select_rules

log = logging.getLogger(__name__)

#: What the parse and the rules import (lxml with the model parser, every rule module).
_ALWAYS = ("robotdesc.model.parse", "robotdesc.rules.catalog")
#: What reading meshes imports: numpy and the readers, the summary (numpy.ma: np.unique).
_MESHES = ("robotdesc.mesh.summary", "numpy.ma")
#: What summarizing meshes may import when the summaries are computed (no mesh cache, or an
#: empty one): pycollada for .dae files; last, since it may not be needed at all, and not
#: where a forked child shares the summaries (`robotdesc.mesh.prefetch`: the COLLADA files
#: are the child's, which imports it). (The hull of an open surface is numpy's,
#: `robotdesc.mesh.hull`: a lint never imports scipy.)
_MESH_ANALYSIS = ("collada",)


class ImportsAhead:
    """Imports the modules `plan` yields, in a daemon thread, until `stop()`.

    Args:
        plan: yields module names; runs in the thread (it may import to decide).
    """

    def __init__(self, plan: Callable[[], Iterable[str]]) -> None:
        self._plan = plan
        self._stopped = threading.Event()
        self._started = False
        self._thread = threading.Thread(target=self._run, name="robotdesc-imports-ahead",
                                        daemon=True)

    def start(self) -> None:
        """Start importing (once; nothing happens when no thread can be started)."""
        if self._started:
            return
        self._started = True
        try:
            self._thread.start()
        except RuntimeError as error:  # no thread to be had: the lint imports as it goes
            log.debug("not importing ahead: %s", error)

    def stop(self) -> None:
        """Import nothing more, and wait for the module being imported."""
        self._stopped.set()
        if self._thread.is_alive():
            self._thread.join()

    def _run(self) -> None:
        try:
            for name in self._plan():
                if self._stopped.is_set():
                    return
                _import(name)
        except Exception as error:  # a plan that fails: the lint decides again itself
            log.debug("importing ahead stopped: %s: %s", type(error).__name__, error)


def _import(name: str) -> None:
    """Import `name` when it is installed and not imported yet; a failure is only logged
    (the lint imports it again where it needs it)."""
    if name in sys.modules:
        return
    try:
        if importlib.util.find_spec(name) is not None:
            importlib.import_module(name)
    except Exception as error:
        log.debug("importing %s ahead failed: %s: %s", name, type(error).__name__, error)


def lint_imports(select: Sequence[str] | None, ignore: Sequence[str],
                 analyze_meshes: bool) -> Iterator[str]:
    """The modules a lint imports after its expansion, most certainly needed first.

    Args:
        select, ignore: the selection that applies (as `select_rules` takes it).
        analyze_meshes: mesh files will be summarized, not read from a cache (none, or an
            empty one): pycollada may be needed.
    """
    yield from _ALWAYS
    from robotdesc.rules.catalog import all_rules

    needs = {need for rule in select_rules(all_rules(), select, ignore) for need in rule.needs}
    if "meshes" in needs:
        yield from _MESHES
    if "pinocchio" in needs:
        yield "pinocchio"
    if "meshes" in needs and analyze_meshes and not forks_here():
        yield from _MESH_ANALYSIS  # else the child that shares the summaries imports them
