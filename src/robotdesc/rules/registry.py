"""The rule registry: every rule registers its code, name, severity, family and options.

A rule is a generator function `check(robot, ctx)` yielding `Finding`s; its docstring is its
user documentation, in three parts separated by headings "Why is this bad?" and "Example"
(the first paragraph is the summary). See docs/rules.md (generated from this registry).
"""

from __future__ import annotations

import dataclasses
import inspect
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, TypeVar

from robotdesc.diagnostics import Finding, Severity
from robotdesc.expansion.result import ExpansionNote, MacroRecursion

if TYPE_CHECKING:
    from _typeshed import DataclassInstance

    from robotdesc.inertia.mesh_access import MeshAccess  # annotations only: a lint imports
    from robotdesc.model.elements import Robot  # them anyway, a config check need not
    from robotdesc.rules.package_files import PackageFiles

#: A rule's options: an instance of the frozen dataclass it registered (`rule(options=...)`).
OptionsT = TypeVar("OptionsT", bound="DataclassInstance")


@dataclass(frozen=True)
class ExpansionFacts:
    """What the expansion learned that the URDF alone does not show.

    Attributes:
        package_folders: the folders `$(find pkg)` resolved to (absolute), where a path
            the expansion wrote was made on this machine rather than written in the source.
    """

    macro_recursion: tuple[MacroRecursion, ...] = ()
    files_read: tuple[str, ...] = ()
    from_xacro: bool = False
    notes: tuple[ExpansionNote, ...] = ()
    package_folders: tuple[str, ...] = ()


@dataclass(frozen=True)
class SourceDocument:
    """The URDF text the model was parsed from, for rules that judge raw elements.

    Attributes:
        xml: the (expanded) document.
        path: the file it came from.
        files: the expansion's file table (empty for a plain URDF), which the private
            provenance attribute indexes.
    """

    xml: bytes = b""
    path: str = ""
    files: tuple[str, ...] = ()


@dataclass(frozen=True)
class RuleContext:
    """What a check sees besides the robot.

    Attributes:
        options: the rule's options (an instance of its options dataclass, or None: its
            defaults); a check reads them with `options_as`.
        expansion: facts from the xacro expansion (empty for plain URDF).
        meshes: mesh access for rules that declare `needs={"meshes"}` (None otherwise): a
            `robotdesc.mesh.context.MeshContext` in a lint.
        document: the source document for rules that declare `needs={"document"}`
            (None otherwise).
        package: the files beside the description (launch, YAML, worlds, hooks) for rules
            that declare `needs={"package"}` (None otherwise, and outside a lint).
    """

    options: DataclassInstance | None = None
    expansion: ExpansionFacts = field(default_factory=ExpansionFacts)
    meshes: MeshAccess | None = None
    document: SourceDocument | None = None
    package: PackageFiles | None = None

    def options_as(self, kind: type[OptionsT]) -> OptionsT:
        """The rule's options as its options dataclass `kind` (its defaults when none were
        given).

        Raises:
            TypeError: the options are of another type (a bug: the rule registered `kind`).
        """
        if self.options is None:
            return kind()
        if not isinstance(self.options, kind):
            raise TypeError(f"rule options of type {type(self.options).__name__}, "
                            f"expected {kind.__name__}")
        return self.options


CheckFunction = Callable[["Robot", "RuleContext"], Iterable[Finding]]


@dataclass(frozen=True)
class Rule:
    """A registered rule.

    Attributes:
        code: stable code, a family letter and three digits ("J101").
        name: kebab-case name of the problem ("revolute-without-limit").
        family: the family ("structure", "joints", ...).
        severity: default severity.
        check: the generator function.
        options: the frozen dataclass type of its options (None when it has none).
        needs: what it reads besides the model: "expansion", "meshes".
        opt_in: off by default; runs only when a selector of --select or the config's
            `select` names it (its code, a prefix of it, its name, or "ALL").
    """

    code: str
    name: str
    family: str
    severity: Severity
    check: CheckFunction
    options: type[DataclassInstance] | None = None
    needs: frozenset[str] = frozenset()
    opt_in: bool = False

    @property
    def doc(self) -> str:
        return inspect.cleandoc(self.check.__doc__ or "")

    @property
    def summary(self) -> str:
        return self.doc.split("\n\n", 1)[0].replace("\n", " ").strip()

    def default_options(self) -> Any:
        """An instance of its options dataclass with the defaults (None: it has none).
        Typed Any: `config.validate` hands it to `dataclasses.replace` after checking
        `options`."""
        return self.options() if self.options else None

    def option_fields(self) -> list[dataclasses.Field[Any]]:
        return list(dataclasses.fields(self.options)) if self.options else []


_REGISTRY: dict[str, Rule] = {}


#: Every rule family and the code prefix its rules carry (a new family is declared here).
FAMILIES: dict[str, str] = {
    "structure": "S", "joints": "J1", "mimic": "J2", "transmissions": "T", "gazebo": "G",
    "visual": "V", "paths": "P", "xacro": "X", "meta": "RD", "inertia": "I", "meshes": "M",
    "budget": "B", "sim": "D", "kinematics": "K", "consumers": "C", "ros2": "R1",
}


def rule(code: str, name: str, *, family: str, severity: Severity | str = Severity.ERROR,
         options: type[DataclassInstance] | None = None, needs: Iterable[str] = (),
         opt_in: bool = False) -> Callable[[CheckFunction], CheckFunction]:
    """Register `check` under `code`; used as a decorator."""

    def register(check: CheckFunction) -> CheckFunction:
        prefix = FAMILIES.get(family)
        if prefix is None or not code.startswith(prefix):
            raise RuntimeError(f"rule {code}: family '{family}' is not declared in "
                               f"rules.registry.FAMILIES with the code's prefix")
        if code in _REGISTRY:
            raise RuntimeError(f"rule code {code} registered twice")
        if any(r.name == name for r in _REGISTRY.values()):
            raise RuntimeError(f"rule name {name} registered twice")
        level = Severity.parse(severity) if isinstance(severity, str) else severity
        _REGISTRY[code] = Rule(code, name, family, level, check, options, frozenset(needs),
                               opt_in)
        return check

    return register


def registered_rules() -> list[Rule]:
    """The rules registered so far, sorted by code (`robotdesc.rules.catalog.all_rules` loads
    every rule module first)."""
    return sorted(_REGISTRY.values(), key=lambda r: r.code)


def find_registered(code_or_name: str) -> Rule | None:
    """The registered rule with this code (case-insensitive) or kebab-case name, or None."""
    key = code_or_name.strip()
    found = _REGISTRY.get(key.upper())
    return found or next((r for r in _REGISTRY.values() if r.name == key), None)


def run_rule(rule_: Rule, robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Run one rule's check (a thin seam for tests and the lint driver)."""
    yield from rule_.check(robot, ctx)
