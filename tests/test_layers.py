"""The house's layers hold: read off the source with `ast`, imports at any depth included.

core (source, errors, diagnostics, model, spatial, the writer, caches' root, ...) -> expansion
-> mesh -> inertia -> kinematics -> srdf -> collision -> sim -> rules -> linting and config ->
report / view -> commands / server -> cli -> the package's public API (`robotdesc/__init__.py`,
which imports each part on first use so that `import robotdesc` stays cheap). A module imports only from its
own layer or lower ones, even inside a function; an import inside a function is for a heavy or
optional backend only; the first-party import graph, module by module, has no cycle.
"""

from __future__ import annotations

import ast
from collections.abc import Iterator
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "robotdesc"

#: Each top-level module or package of robotdesc and its layer (lower imports nothing higher).
LAYERS: dict[str, int] = {
    **dict.fromkeys(("_version", "code_stamp", "source", "errors", "diagnostics", "model",
                     "spatial", "atomic", "output", "cache_dir", "digest", "xml_input", "xml_text", "progress", "forked",
                     "trust", "printable", "lazy"), 0),
    "expansion": 1, "edit": 1, "mesh": 2, "inertia": 3, "kinematics": 4, "srdf": 5, "collision": 6,
    "sim": 7, "rules": 8, "linting": 9, "config": 9, "report": 10, "view": 10, "commands": 11,
    "server": 11, "cli": 12, "__main__": 13, "": 13,
}
#: Packages that may be imported inside a function (heavy or optional backends).
LAZY_ALLOWED = frozenset({
    "numpy", "scipy", "trimesh", "coacd", "pinocchio", "coal", "hppfcl", "mujoco", "dartpy",
    "dask", "distributed", "manifold3d", "fast_simplification", "meshoptimizer", "collada",
    "matplotlib", "pygls", "lsprotocol", "rich", "xacro", "pyseccomp", "lxml", "yaml",
    "resource", "fcntl", "termios", "ctypes", "multiprocessing", "concurrent", "subprocess",
    "traceback", "pymeshlab", "PIL", "jsonschema", "cProfile", "pstats", "IPython",
    "tomllib", "tomli",  # whichever the Python version has
    "yourdfpy",
    "asyncio",  # 14 ms of imports: only the Dask paths need it (a warm lint must not pay)
})
#: The public API imports each part of robotdesc on first use, so that `import robotdesc`
#: (every notebook's first line, and every submodule's parent) stays cheap.
FACADE = "robotdesc"
#: The start-up path of `robotdesc --version`, `--help`, `rules`, `rule`: these may import
#: anything inside a function, to stay within 2x the bare interpreter (tests/test_startup.py).
START_UP = frozenset({FACADE, "robotdesc.cli", "robotdesc.commands.rules"})


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(SRC.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


MODULES = {_module_name(p): p for p in sorted(SRC.rglob("*.py"))}


def _imports(name: str, path: Path, types: bool = True) -> Iterator[tuple[str, int, bool]]:
    """(imported module, line, inside a function) for each first-party import of a module;
    `types=False` leaves out the imports under `if TYPE_CHECKING:`, which never run (the
    import graph's cycles are counted without them)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    parents: dict[ast.AST, ast.AST] = {}
    for node in ast.walk(tree):
        for child in ast.iter_child_nodes(node):
            parents[child] = node

    def nested(node: ast.AST) -> bool:
        while node in parents:
            node = parents[node]
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                return True
        return False

    def for_types_only(node: ast.AST) -> bool:
        """Under `if TYPE_CHECKING:`: never run, so no edge of the import graph."""
        while node in parents:
            node = parents[node]
            if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
                return True
        return False

    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    for node in ast.walk(tree):
        if not types and isinstance(node, (ast.Import, ast.ImportFrom)) \
                and for_types_only(node):
            continue
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name, node.lineno, nested(node)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module or ""
            for alias in node.names:
                full = f"{module}.{alias.name}"
                yield (full if full in MODULES else module), node.lineno, nested(node)


def _first_party(target: str) -> str | None:
    while target and target not in MODULES:
        target = target.rpartition(".")[0]
    return target or None


def _layer(module: str) -> int:
    parts = module.split(".")
    return LAYERS[parts[1] if len(parts) > 1 else ""]


def test_every_module_has_a_layer() -> None:
    unknown = sorted({m.split(".")[1] for m in MODULES if "." in m} - set(LAYERS))
    assert not unknown, f"add these to LAYERS in tests/test_layers.py: {unknown}"


def test_no_module_imports_a_higher_layer() -> None:
    wrong = []
    for name, path in MODULES.items():
        for target, line, _ in _imports(name, path):
            found = _first_party(target) if target.startswith("robotdesc") else None
            if found and _layer(found) > _layer(name):
                wrong.append(f"{path.relative_to(SRC.parent)}:{line}: {name} -> {found}")
    assert not wrong, "imports from a higher layer:\n" + "\n".join(wrong)


def _heavy_modules() -> set[str]:
    """First-party modules that import a heavy or optional backend at module level, themselves
    or through the first-party modules they import at module level. An import under
    `if TYPE_CHECKING:` never runs, so it makes no module heavy."""
    top_level = {name: [(t, inside) for t, _, inside in _imports(name, path, types=False)]
                 for name, path in MODULES.items()}
    heavy = {name for name, found in top_level.items()
             if any(not inside and t.split(".")[0] in LAZY_ALLOWED for t, inside in found)}
    changed = True
    while changed:
        changed = False
        for name, found in top_level.items():
            parents = [name.rsplit(".", depth)[0] for depth in range(1, name.count("."))]
            if name not in heavy and (
                    any(parent in heavy for parent in parents)  # importing a.b imports a first
                    or any(not inside and _first_party(t) in heavy
                           for t, inside in found if t.startswith("robotdesc"))):
                heavy.add(name)
                changed = True
    return heavy


def test_imports_inside_functions_are_for_heavy_or_optional_backends_only() -> None:
    """A first-party module counts as heavy when importing it imports such a backend."""
    heavy = _heavy_modules()
    wrong = []
    for name, path in MODULES.items():
        for target, line, inside in _imports(name, path):
            if not inside or name in START_UP:
                continue
            if target.startswith("robotdesc"):
                if _first_party(target) not in heavy and name != FACADE:
                    wrong.append(f"{path.relative_to(SRC.parent)}:{line}: {target}")
            elif target.split(".")[0] not in LAZY_ALLOWED:
                wrong.append(f"{path.relative_to(SRC.parent)}:{line}: {target}")
    assert not wrong, "imports inside functions that are not heavy backends:\n" + "\n".join(wrong)


def test_the_module_import_graph_has_no_cycle() -> None:
    graph = {name: {found for target, _, _ in _imports(name, path, types=False)
                    if target.startswith("robotdesc")
                    and (found := _first_party(target)) and found != name}
             for name, path in MODULES.items()}
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        stack.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                return stack[stack.index(nxt):] + [nxt]
            if nxt not in state and (cycle := visit(nxt)):
                return cycle
        stack.pop()
        state[node] = 2
        return None

    for start in sorted(graph):
        if start not in state and (cycle := visit(start)):
            pytest.fail("import cycle: " + " -> ".join(cycle))
