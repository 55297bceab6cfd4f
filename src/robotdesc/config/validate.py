"""A parsed `[tool.robotdesc]` table checked key by key and turned into a `Config`; every
error names the key's TOML line (`Locator`)."""

from __future__ import annotations

import dataclasses
import os
import typing
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from robotdesc.config.coerce import coerce
from robotdesc.config.locate import Locator
from robotdesc.config.schema import KEYS, Config, SimSettings, TargetSpec
from robotdesc.diagnostics import Severity
from robotdesc.mesh.settings import MeshSettings
from robotdesc.rules.index import known_names
from robotdesc.rules.select import Named, find_rule, unknown_selectors
from robotdesc.trust import is_broad_folder, leaves_tree

if TYPE_CHECKING:
    from robotdesc.rules.registry import Rule


def config_from_mapping(table: Mapping[str, Any], path: str, *, text: str = "",
                        prefix: str = "", rules: Sequence[Rule] | None = None,
                        tree: str | None = None) -> Config:
    """Validate a robotdesc config table (already parsed from TOML).

    Args:
        table: the `[tool.robotdesc]` table (or robotdesc.toml's top level).
        path: the config file, for messages and for resolving relative package paths.
        text: the file's text, used to point messages at a line (best effort).
        prefix: the table's dotted prefix in the file, for messages.
        rules: the known rules (default: every registered rule).
        tree: for a config found inside a scanned tree (not the user's own `--config`),
            that tree's folder: its `packages` and `targets` may only name paths inside it,
            and never a home folder or `/` as a whole (the scanned repository does not
            decide what the xacro worker may read).

    Raises:
        ConfigError: an unknown key or a bad value, at its line.
    """
    where = Locator(path, text, prefix)
    table = {_snake(key): value for key, value in table.items()}
    if rules is None and any(key in table for key in _CONFIGURING_RULES):
        from robotdesc.rules.catalog import all_rules  # every rule module, lxml among them

        rules = all_rules()
    known = list(rules or ())  # no key configures a rule: the registry is not needed
    # selectors need codes and names only: the rule index has them (no rule module imported)
    names: Sequence[Named] = known if rules is not None else (
        known_names() if any(key in table for key in _SELECTING_RULES) else ())

    unknown = sorted(set(table) - set(KEYS))
    if unknown:
        raise where.error(unknown[0], f"unknown key '{prefix}{unknown[0]}' "
                                      f"(known: {', '.join(k.replace('_', '-') for k in KEYS)})")
    select = table.get("select")
    return Config(
        path=path,
        select=None if select is None else _selectors(select, "select", where, names),
        ignore=_selectors(table.get("ignore", []), "ignore", where, names),
        per_file_ignores=_per_file_ignores(table.get("per_file_ignores", {}), where, names),
        rule_options=_rule_options(table.get("rules", {}), where, known),
        severity=_severities(table.get("severity", {}), where, known),
        fail_on=_severity_value(table.get("fail_on", "info"), "fail-on", where),
        packages=_packages(table.get("packages", {}), where, tree),
        args=_string_table(table.get("args", {}), "args", where),
        meshes=_mesh_settings(table.get("meshes", {}), where),
        targets=_targets(table.get("targets", []), where, tree),
        sim=_sim_settings(table.get("sim", {}), where),
    )


#: The keys whose values select rules (checked against their codes and names).
_SELECTING_RULES = ("select", "ignore", "per_file_ignores")
#: The keys whose values configure rules (checked against the registry: options, codes).
_CONFIGURING_RULES = ("rules", "severity")


def _snake(key: str) -> str:
    return key.replace("-", "_")


def _selectors(value: Any, key: str, where: Locator, rules: Sequence[Named]
               ) -> tuple[str, ...]:
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise where.error(key, f"'{key}' must be a list of rule codes, prefixes or names")
    bad = unknown_selectors(value, rules)
    if bad:
        raise where.error(bad[0], f"'{key}' names no known rule: '{bad[0]}'")
    return tuple(v.strip() for v in value)


def _per_file_ignores(value: Any, where: Locator,
                      rules: Sequence[Named]) -> tuple[tuple[str, tuple[str, ...]], ...]:
    if not isinstance(value, dict):
        raise where.error("per_file_ignores", "'per-file-ignores' must be a table "
                                              "of glob = [codes]")
    return tuple((glob, _selectors(codes, glob, where, rules)) for glob, codes in value.items())


def _rule_code(key: str, section: str, where: Locator, rules: list[Rule]) -> Rule:
    found: Rule | None = find_rule(rules, key)
    if found is None:
        raise where.error(key, f"'{section}.{key}': no rule has this code or name")
    return found


def _rule_options(value: Any, where: Locator,
                  rules: list[Rule]) -> tuple[tuple[str, Any], ...]:
    if not isinstance(value, dict):
        raise where.error("rules", "'rules' must be a table of rule tables")
    result = []
    for key, settings in value.items():
        found = _rule_code(key, "rules", where, rules)
        if not isinstance(settings, dict):
            raise where.error(key, f"'rules.{key}' must be a table of options")
        result.append((found.code, _build_options(found, settings, key, where)))
    return tuple(result)


def _build_options(rule: Rule, settings: dict[str, Any], key: str, where: Locator) -> Any:
    """The rule's options dataclass with the configured values (None: it has no options)."""
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
            values[field_name] = coerce(raw, hints.get(field_name, Any))
        except (TypeError, ValueError) as exc:
            raise where.error(name, f"rules.{key}.{name}: {exc}") from None
    try:
        return dataclasses.replace(rule.options(), **values)  # its defaults, then these
    except (TypeError, ValueError) as exc:
        raise where.error(key, f"rules.{key}: {exc}") from None


def _severity_value(value: Any, key: str, where: Locator) -> Severity:
    if not isinstance(value, str):
        raise where.error(key, f"'{key}' must be \"error\", \"warning\" or \"info\"")
    try:
        return Severity.parse(value)
    except ValueError as exc:
        raise where.error(key, f"'{key}': {exc}") from None


def _severities(value: Any, where: Locator,
                rules: list[Rule]) -> tuple[tuple[str, Severity], ...]:
    if not isinstance(value, dict):
        raise where.error("severity", "'severity' must be a table of CODE = \"error\"|...")
    return tuple((_rule_code(key, "severity", where, rules).code,
                  _severity_value(level, key, where)) for key, level in value.items())


def _string_table(value: Any, key: str, where: Locator) -> tuple[tuple[str, str], ...]:
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


def _mesh_settings(value: Any, where: Locator) -> MeshSettings:
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
            values[field_name] = coerce(raw, hints[field_name])
        except (TypeError, ValueError) as exc:
            raise where.error(name, f"meshes.{name}: {exc}") from None
    try:
        return MeshSettings(**values)
    except ValueError as exc:
        raise where.error("meshes", f"meshes: {exc}") from None


def _sim_settings(value: Any, where: Locator) -> SimSettings:
    """`[sim]`: `separation-multiplier = { engine = multiplier, ... }` (engines are checked
    by `robotdesc sim`, which knows them)."""
    if not isinstance(value, dict):
        raise where.error("sim", "'sim' must be a table of sim settings")
    unknown = sorted(set(map(_snake, value)) - {"separation_multiplier"})
    if unknown:
        raise where.error(unknown[0], f"unknown key 'sim.{unknown[0]}' (known: "
                                      "separation-multiplier)")
    table: Any = next((v for k, v in value.items() if _snake(k) == "separation_multiplier"), {})
    if not isinstance(table, dict):
        raise where.error("separation-multiplier", "'sim.separation-multiplier' must be a "
                          "table of engine = multiplier")
    pairs = []
    for engine, raw in table.items():
        if isinstance(raw, bool) or not isinstance(raw, (int, float)) or not raw > 0 \
                or raw != raw or raw == float("inf"):
            raise where.error("separation-multiplier",
                              f"sim.separation-multiplier.{engine} must be a positive number")
        pairs.append((str(engine), float(raw)))
    return SimSettings(tuple(pairs))


def _packages(value: Any, where: Locator, tree: str | None) -> tuple[tuple[str, str], ...]:
    base = os.path.dirname(where.path)
    pairs = tuple((name, os.path.normpath(os.path.join(base, os.path.expanduser(directory))))
                  for name, directory in _string_table(value, "packages", where))
    for name, folder in pairs:
        _inside_tree(folder, f"packages.{name}", name, where, tree)
    return pairs


def _inside_tree(path: str, what: str, key: str, where: Locator, tree: str | None) -> None:
    """Refuse a path a config found in the scanned tree may not name (see `tree`)."""
    if tree is None:
        return
    if is_broad_folder(path) or leaves_tree(path, tree):
        raise where.error(key, f"{what} names '{path}', outside the repository that holds "
                               f"this config ({tree}); a config inside the scanned tree may "
                               "only name folders inside it. Name other folders with "
                               "--package-path, ROS_PACKAGE_PATH/AMENT_PREFIX_PATH or your "
                               "own --config")


def _targets(value: Any, where: Locator, tree: str | None) -> tuple[TargetSpec, ...]:
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
        _inside_tree(path, "targets.file", file, where, tree)
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
