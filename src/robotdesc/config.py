"""robotdesc's configuration: `[tool.robotdesc]` in pyproject.toml, or robotdesc.toml.

The configuration that applies to a file is the first one found walking up from the file's
directory: in each directory robotdesc.toml (its top-level table) wins over pyproject.toml
(its `[tool.robotdesc]` table; a pyproject.toml without that table is skipped). The walk stops
after a directory that holds a VCS root (`.git`, `.hg`, `.svn`) or at the filesystem root.

Example (pyproject.toml)::

    [tool.robotdesc]
    select = ["ALL"]
    ignore = ["G"]                 # codes, prefixes ("J", "J1") or rule names
    fail-on = "warning"            # error | warning | info (default: info, any finding)
    [tool.robotdesc.per-file-ignores]
    "vendor/*.xacro" = ["S"]
    [tool.robotdesc.rules.X101]    # a rule's options, checked against its options dataclass
    max_depth = 8
    [tool.robotdesc.severity]
    J107 = "error"
    [tool.robotdesc.packages]      # package name -> directory, relative to this file
    my_robot_description = "src/my_robot_description"
    [tool.robotdesc.args]          # default xacro arguments
    use_gazebo = "false"
    [tool.robotdesc.meshes]        # mesh and inertia settings (see MeshSettings)
    inertia-source = "collision"   # or "visual": the geometry mass properties come from
    expected-mass = 16.3           # kg, checked by B101 (mass-budget)
    mass-tolerance = 0.05          # relative
    allow-absolute-paths = false   # accept file:// and absolute mesh paths
    collision-triangle-budget = 10000
    cache = true                   # cache mesh summaries (see docs/meshes.md)
    [[tool.robotdesc.targets]]     # what a directory lint checks; each matrix variant apart
    file = "urdf/ur.urdf.xacro"
    args = { safety_limits = "true" }
    matrix = { ur_type = ["ur5e", "ur10e"] }
"""

from __future__ import annotations

import dataclasses
import enum
import os
import re
import types
import typing
from dataclasses import dataclass
from typing import Any, Mapping, Sequence

from robotdesc.diagnostics import Severity
from robotdesc.errors import ConfigError
from robotdesc.linting.select import find_rule, unknown_selectors
from robotdesc.mesh.settings import MeshSettings
from robotdesc.source import Span

CONFIG_FILES = ("robotdesc.toml", "pyproject.toml")
VCS_MARKERS = (".git", ".hg", ".svn")
_KEYS = ("select", "ignore", "per_file_ignores", "rules", "severity", "fail_on", "packages",
         "args", "meshes", "targets")


@dataclass(frozen=True)
class TargetSpec:
    """A description the config asks `lint` to check, with its argument matrix.

    Attributes:
        file: the description (absolute path).
        args: fixed xacro arguments as (name, value) pairs.
        matrix: (argument, values) pairs; every combination is linted as its own variant.
    """

    file: str
    args: tuple[tuple[str, str], ...] = ()
    matrix: tuple[tuple[str, tuple[str, ...]], ...] = ()


@dataclass(frozen=True)
class Config:
    """The settings that apply to one linted file.

    Attributes:
        path: the config file these settings come from (None: built-in defaults).
        select: rule selectors to enable (None: all rules).
        ignore: rule selectors to disable.
        per_file_ignores: (glob, selectors) pairs; globs are relative to the config's directory.
        rule_options: (code, options instance) pairs for rules configured in `rules.CODE`.
        severity: (code, severity) overrides.
        fail_on: the lowest severity that makes `lint` exit with 1.
        packages: (package name, absolute directory) pairs.
        args: default xacro arguments as (name, value) pairs.
        meshes: mesh and inertia settings.
        targets: the descriptions a directory lint checks (empty: discover them).
    """

    path: str | None = None
    select: tuple[str, ...] | None = None
    ignore: tuple[str, ...] = ()
    per_file_ignores: tuple[tuple[str, tuple[str, ...]], ...] = ()
    rule_options: tuple[tuple[str, Any], ...] = ()
    severity: tuple[tuple[str, Severity], ...] = ()
    fail_on: Severity = Severity.INFO
    packages: tuple[tuple[str, str], ...] = ()
    args: tuple[tuple[str, str], ...] = ()
    meshes: MeshSettings = MeshSettings()
    targets: tuple[TargetSpec, ...] = ()

    @property
    def root(self) -> str:
        """The directory relative paths in this config are resolved against."""
        return os.path.dirname(self.path) if self.path else os.getcwd()

    def options_for(self, code: str) -> Any | None:
        """The configured options instance of rule `code`, or None when not configured."""
        return dict(self.rule_options).get(code)

    def severity_for(self, code: str, default: Severity) -> Severity:
        """The effective severity of rule `code`."""
        return dict(self.severity).get(code, default)


def find_config_file(start: str) -> str | None:
    """The first config file that configures robotdesc, walking up from `start`.

    Args:
        start: a file or directory; the walk begins at its directory.
    """
    directory = os.path.abspath(start)
    if not os.path.isdir(directory):
        directory = os.path.dirname(directory)
    while True:
        for name in CONFIG_FILES:
            candidate = os.path.join(directory, name)
            if os.path.isfile(candidate) and _configures_robotdesc(candidate):
                return candidate
        parent = os.path.dirname(directory)
        if parent == directory or any(os.path.exists(os.path.join(directory, marker))
                                      for marker in VCS_MARKERS):
            return None
        directory = parent


def discover_config(target: str, rules: Sequence[Any] | None = None) -> Config:
    """The config for linting `target` (defaults when no config file is found).

    Args:
        target: the linted file.
        rules: the known rules (default: every registered rule).
    """
    found = find_config_file(target)
    return load_config(found, rules) if found else Config()


def load_config(path: str, rules: Sequence[Any] | None = None) -> Config:
    """Read and validate one config file (robotdesc.toml or pyproject.toml).

    Raises:
        ConfigError: unreadable TOML, unknown keys, bad values; the message names the file.
    """
    path = os.path.abspath(path)
    text = _read_text(path)
    document = _parse_toml(text, path)
    if os.path.basename(path) == "pyproject.toml":
        table = document.get("tool", {}).get("robotdesc", {})
        prefix = "tool.robotdesc."
    else:
        table = document
        prefix = ""
    return config_from_mapping(table, path, text=text, prefix=prefix, rules=rules)


def config_from_mapping(table: Mapping[str, Any], path: str, *, text: str = "",
                        prefix: str = "", rules: Sequence[Any] | None = None) -> Config:
    """Validate a robotdesc config table (already parsed from TOML).

    Args:
        table: the `[tool.robotdesc]` table (or robotdesc.toml's top level).
        path: the config file, for messages and for resolving relative package paths.
        text: the file's text, used to point messages at a line (best effort).
        prefix: the table's dotted prefix in the file, for messages.
        rules: the known rules (default: every registered rule).
    """
    where = _Locator(path, text, prefix)
    if rules is None:
        from robotdesc.rules.catalog import all_rules  # every rule module, lxml among them

        rules = all_rules()
    known = list(rules)

    table = {_snake(key): value for key, value in table.items()}
    unknown = sorted(set(table) - set(_KEYS))
    if unknown:
        raise where.error(unknown[0], f"unknown key '{prefix}{unknown[0]}' "
                                      f"(known: {', '.join(k.replace('_', '-') for k in _KEYS)})")
    select = table.get("select")
    return Config(
        path=path,
        select=None if select is None else _selectors(select, "select", where, known),
        ignore=_selectors(table.get("ignore", []), "ignore", where, known),
        per_file_ignores=_per_file_ignores(table.get("per_file_ignores", {}), where, known),
        rule_options=_rule_options(table.get("rules", {}), where, known),
        severity=_severities(table.get("severity", {}), where, known),
        fail_on=_severity_value(table.get("fail_on", "info"), "fail-on", where),
        packages=_packages(table.get("packages", {}), where),
        args=_string_table(table.get("args", {}), "args", where),
        meshes=_mesh_settings(table.get("meshes", {}), where),
        targets=_targets(table.get("targets", []), where),
    )


# --- validation helpers -------------------------------------------------------------------


class _Locator:
    """Builds ConfigErrors that point at the line of a key, when it can be found."""

    def __init__(self, path: str, text: str, prefix: str) -> None:
        self.path, self.lines, self.prefix = path, text.splitlines(), prefix

    def error(self, key: str, message: str) -> ConfigError:
        return ConfigError(f"invalid configuration: {message}", Span(self.path, self._line(key)))

    def _line(self, key: str) -> int:
        variants = {key, key.replace("_", "-")}
        pattern = re.compile(r"^\s*(\[+[^\]]*)?[\"']?(%s)[\"']?\s*(=|\]|\.)"
                             % "|".join(re.escape(v) for v in variants))
        header = re.compile(r"^\s*\[[^\]]*\b(%s)\b" % "|".join(re.escape(v) for v in variants))
        quoted = re.compile(r"[\"'](%s)[\"']" % "|".join(re.escape(v) for v in variants))
        for regex in ((pattern, header), (quoted,)):
            for number, line in enumerate(self.lines, 1):
                if any(r.search(line) for r in regex):
                    return number
        return 0


def _snake(key: str) -> str:
    return key.replace("-", "_")


def _selectors(value: Any, key: str, where: _Locator, rules: list) -> tuple[str, ...]:
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise where.error(key, f"'{key}' must be a list of rule codes, prefixes or names")
    bad = unknown_selectors(value, rules)
    if bad:
        raise where.error(bad[0], f"'{key}' names no known rule: '{bad[0]}'")
    return tuple(v.strip() for v in value)


def _per_file_ignores(value: Any, where: _Locator,
                      rules: list) -> tuple[tuple[str, tuple[str, ...]], ...]:
    if not isinstance(value, dict):
        raise where.error("per_file_ignores", "'per-file-ignores' must be a table "
                                              "of glob = [codes]")
    return tuple((glob, _selectors(codes, glob, where, rules)) for glob, codes in value.items())


def _rule_code(key: str, section: str, where: _Locator, rules: list) -> Any:
    found = find_rule(rules, key)
    if found is None:
        raise where.error(key, f"'{section}.{key}': no rule has this code or name")
    return found


def _rule_options(value: Any, where: _Locator, rules: list) -> tuple[tuple[str, Any], ...]:
    if not isinstance(value, dict):
        raise where.error("rules", "'rules' must be a table of rule tables")
    result = []
    for key, settings in value.items():
        found = _rule_code(key, "rules", where, rules)
        if not isinstance(settings, dict):
            raise where.error(key, f"'rules.{key}' must be a table of options")
        result.append((found.code, _build_options(found, settings, key, where)))
    return tuple(result)


def _build_options(rule: Any, settings: dict, key: str, where: _Locator) -> Any:
    if rule.options is None:
        if settings:
            raise where.error(key, f"rule {rule.code} ({rule.name}) has no options")
        return None
    hints = typing.get_type_hints(rule.options)
    fields = {f.name: f for f in dataclasses.fields(rule.options)}
    values = {}
    for name, raw in settings.items():
        field_name = _snake(name)
        if field_name not in fields:
            known = ", ".join(fields) or "none"
            raise where.error(name, f"rule {rule.code} has no option '{name}' (options: {known})")
        try:
            values[field_name] = _coerce(raw, hints.get(field_name, Any))
        except (TypeError, ValueError) as exc:
            raise where.error(name, f"rules.{key}.{name}: {exc}") from None
    try:
        return dataclasses.replace(rule.default_options(), **values)
    except (TypeError, ValueError) as exc:
        raise where.error(key, f"rules.{key}: {exc}") from None


def _coerce(value: Any, hint: Any) -> Any:
    """Check a TOML value against a type hint; convert lists to tuples and ints to floats."""
    origin = typing.get_origin(hint)
    if hint is Any:
        return value
    if origin in (typing.Union, types.UnionType):
        if value is None and type(None) in typing.get_args(hint):
            return None
        for option in typing.get_args(hint):
            if option is type(None):
                continue
            try:
                return _coerce(value, option)
            except (TypeError, ValueError):
                continue
        raise TypeError(f"expected {_describe(hint)}, got {value!r}")
    if origin is typing.Literal:
        if value not in typing.get_args(hint):
            raise ValueError(f"expected one of {', '.join(map(repr, typing.get_args(hint)))}, "
                             f"got {value!r}")
        return value
    if origin in (tuple, list, frozenset, set):
        if not isinstance(value, list):
            raise TypeError(f"expected a list, got {value!r}")
        args = typing.get_args(hint)
        if origin is tuple and args and args[-1] is not Ellipsis:
            if len(args) != len(value):
                raise ValueError(f"expected {len(args)} values, got {len(value)}")
            return tuple(_coerce(v, a) for v, a in zip(value, args, strict=True))
        item = args[0] if args else Any
        return origin(_coerce(v, item) for v in value)
    if hint is bool:
        if not isinstance(value, bool):
            raise TypeError(f"expected true or false, got {value!r}")
        return value
    if hint is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise TypeError(f"expected an integer, got {value!r}")
        return value
    if hint is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise TypeError(f"expected a number, got {value!r}")
        return float(value)
    if hint is str:
        if not isinstance(value, str):
            raise TypeError(f"expected a string, got {value!r}")
        return value
    if isinstance(hint, type) and issubclass(hint, enum.Enum):
        try:
            return hint(value)
        except ValueError:
            return hint[str(value).upper()]
    if isinstance(hint, type) and not isinstance(value, hint):
        raise TypeError(f"expected {_describe(hint)}, got {value!r}")
    return value


def _describe(hint: Any) -> str:
    return getattr(hint, "__name__", None) or str(hint).replace("typing.", "")


def _severity_value(value: Any, key: str, where: _Locator) -> Severity:
    if not isinstance(value, str):
        raise where.error(key, f"'{key}' must be \"error\", \"warning\" or \"info\"")
    try:
        return Severity.parse(value)
    except ValueError as exc:
        raise where.error(key, f"'{key}': {exc}") from None


def _severities(value: Any, where: _Locator,
                rules: list) -> tuple[tuple[str, Severity], ...]:
    if not isinstance(value, dict):
        raise where.error("severity", "'severity' must be a table of CODE = \"error\"|...")
    return tuple((_rule_code(key, "severity", where, rules).code,
                  _severity_value(level, key, where)) for key, level in value.items())


def _string_table(value: Any, key: str, where: _Locator) -> tuple[tuple[str, str], ...]:
    if not isinstance(value, dict):
        raise where.error(key, f"'{key}' must be a table of name = \"value\"")
    result = []
    for name, item in value.items():
        if isinstance(item, bool):
            item = "true" if item else "false"
        if not isinstance(item, (str, int, float)):
            raise where.error(name, f"'{key}.{name}' must be a string")
        result.append((name, str(item)))
    return tuple(result)


def _mesh_settings(value: Any, where: _Locator) -> MeshSettings:
    if not isinstance(value, dict):
        raise where.error("meshes", "'meshes' must be a table of mesh settings")
    hints = typing.get_type_hints(MeshSettings)
    known = {f.name for f in dataclasses.fields(MeshSettings)}
    values = {}
    for name, raw in value.items():
        field_name = _snake(name)
        if field_name not in known:
            raise where.error(name, f"unknown key 'meshes.{name}' (known: "
                                    f"{', '.join(k.replace('_', '-') for k in sorted(known))})")
        try:
            values[field_name] = _coerce(raw, hints[field_name])
        except (TypeError, ValueError) as exc:
            raise where.error(name, f"meshes.{name}: {exc}") from None
    try:
        return MeshSettings(**values)
    except ValueError as exc:
        raise where.error("meshes", f"meshes: {exc}") from None


def _packages(value: Any, where: _Locator) -> tuple[tuple[str, str], ...]:
    base = os.path.dirname(where.path)
    return tuple((name, os.path.normpath(os.path.join(base, os.path.expanduser(directory))))
                 for name, directory in _string_table(value, "packages", where))


def _targets(value: Any, where: _Locator) -> tuple[TargetSpec, ...]:
    """`[[targets]]` tables: `file` (relative to the config), optional `args` and `matrix`."""
    if not isinstance(value, list) or not all(isinstance(item, dict) for item in value):
        raise where.error("targets", "'targets' must be an array of tables "
                                     "([[tool.robotdesc.targets]] with file = \"...\")")
    base = os.path.dirname(where.path)
    specs = []
    for item in value:
        unknown = sorted(set(item) - {"file", "args", "matrix"})
        if unknown:
            raise where.error(unknown[0], f"unknown key 'targets.{unknown[0]}' "
                                          "(known: file, args, matrix)")
        file = item.get("file")
        if not isinstance(file, str) or not file:
            raise where.error("targets", "each target needs file = \"path/to/robot.urdf.xacro\"")
        path = os.path.normpath(os.path.join(base, os.path.expanduser(file)))
        if not os.path.isfile(path):
            raise where.error(file, f"target file '{file}' does not exist")
        matrix = item.get("matrix", {})
        if not isinstance(matrix, dict):
            raise where.error("matrix", "'targets.matrix' must be a table of name = [values]")
        axes = []
        for name, values in matrix.items():
            if not isinstance(values, list) or not values:
                raise where.error(name, f"'targets.matrix.{name}' must be a non-empty list")
            table = _string_table({str(i): v for i, v in enumerate(values)}, f"matrix.{name}",
                                  where)
            axes.append((name, tuple(v for _, v in table)))
        specs.append(TargetSpec(path, _string_table(item.get("args", {}), "args", where),
                                tuple(axes)))
    return tuple(specs)


# --- file reading -------------------------------------------------------------------------


def _read_text(path: str) -> str:
    try:
        with open(path, encoding="utf-8") as handle:
            return handle.read()
    except OSError as exc:
        raise ConfigError(f"cannot read config file: {exc.strerror}", Span(path)) from None
    except UnicodeDecodeError:
        raise ConfigError("config file is not UTF-8 text", Span(path)) from None


def _parse_toml(text: str, path: str) -> dict:
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        import tomli as tomllib
    _check_nesting(text, path)
    try:
        return tomllib.loads(text)
    except RecursionError:  # not reached after _check_nesting; kept as a last guard
        raise ConfigError(f"invalid TOML: arrays or tables nested deeper than "
                          f"{MAX_TOML_DEPTH} levels", Span(path)) from None
    except tomllib.TOMLDecodeError as exc:
        found = re.search(r"\(at line (\d+), column (\d+)\)", str(exc))
        message = re.sub(r"\s*\(at (line \d+, column \d+|end of document)\)", "", str(exc))
        if found:
            span = Span(path, int(found.group(1)), int(found.group(2)))
        elif "end of document" in str(exc):
            span = Span(path, text.count("\n") + 1)
        else:
            span = Span(path)
        raise ConfigError(f"invalid TOML: {message}", span) from None


#: Deepest nesting of arrays and inline tables accepted in a config (tomllib recurses per
#: level; no robotdesc setting needs more than two).
MAX_TOML_DEPTH = 32

_TOML_TOKENS = re.compile(r'''"""(?:[^"\\]|\\.|"(?!""))*"""|\'\'\'.*?\'\'\'|"(?:[^"\\\n]|\\.)*"|'[^'\n]*'|#[^\n]*|[\[\]{}\n]''',
                          re.DOTALL)


def _check_nesting(text: str, path: str) -> None:
    """Refuse arrays or inline tables nested deeper than MAX_TOML_DEPTH, at their line
    (linear time; strings and comments are skipped)."""
    depth, line = 0, 1
    for match in _TOML_TOKENS.finditer(text):
        token = match.group(0)
        if token in "[{":
            depth += 1
            if depth > MAX_TOML_DEPTH:
                raise ConfigError(f"invalid TOML: arrays or tables nested deeper than "
                                  f"{MAX_TOML_DEPTH} levels", Span(path, line))
        elif token in "]}":
            depth = max(0, depth - 1)
        line += token.count("\n")


def _configures_robotdesc(path: str) -> bool:
    """robotdesc.toml always does; pyproject.toml only with a [tool.robotdesc] table."""
    if os.path.basename(path) != "pyproject.toml":
        return True
    try:
        with open(path, encoding="utf-8", errors="replace") as handle:
            text = handle.read()
    except OSError:
        return False
    if "robotdesc" not in text:
        return False
    return "robotdesc" in _parse_toml(text, path).get("tool", {})
