"""The mesh and inertia rules over a fixture package with deliberate mistakes: each marked
line gets its code AND its cause; every other line stays clean.

A marker reads `<!-- expect: CODE[, CODE] [cause: TEXT] -->`; TEXT must appear in the
message of the finding(s) on that line. The mesh files are written here (tiny, generated),
into a copy of tests/rules/mesh_fixtures/mesh_pkg.
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import numpy as np
import pytest
from mesh.builders import box_triangles, write_binary_stl, write_collada

from robotdesc.mesh.context import MeshContext
from robotdesc.mesh.settings import MeshSettings
from robotdesc.model.parse import parse_urdf
from robotdesc.rules.catalog import all_rules
from robotdesc.rules.registry import RuleContext, run_rule

PACKAGE = Path(__file__).parent / "mesh_fixtures" / "mesh_pkg"
MARKER = re.compile(r"<!--\s*expect:\s*([A-Z0-9,\s]+?)\s*(?:cause:\s*(.*?))?\s*-->")
#: The families these fixtures are about (other families have their own fixtures).
FAMILIES = ("inertia", "meshes", "budget")
SETTINGS = MeshSettings(expected_mass=50.0, collision_triangle_budget=100, cache=False)


def cylinder_triangles(radius: float = 0.05, length: float = 0.2, segments: int = 64):
    """A closed, outward-wound prism around z with 4 * segments triangles."""
    angles = np.linspace(0, 2 * np.pi, segments, endpoint=False)
    ring = np.stack([radius * np.cos(angles), radius * np.sin(angles)], axis=1)
    low, high = -length / 2, length / 2
    faces = []
    for i in range(segments):
        a, b = ring[i], ring[(i + 1) % segments]
        a0, b0, a1, b1 = [*a, low], [*b, low], [*a, high], [*b, high]
        faces += [(a0, b0, b1), (a0, b1, a1), ([0, 0, high], a1, b1), ([0, 0, low], b0, a0)]
    return np.asarray(faces, dtype=float)


def write_meshes(package: Path) -> None:
    meshes = package / "meshes"
    meshes.mkdir()
    (meshes / "subdir").mkdir()
    box = box_triangles((0.1, 0.2, 0.4))
    write_binary_stl(meshes / "box.stl", box)
    write_binary_stl(meshes / "rod.stl", box_triangles((0.05, 0.5, 0.05)))
    write_binary_stl(meshes / "box_mm.stl", box * 1000)
    write_binary_stl(meshes / "Cronstain.stl", box)
    (meshes / "lfs.stl").write_text("version https://git-lfs.github.com/spec/v1\n"
                                    "oid sha256:" + "0" * 64 + "\nsize 123456\n")
    write_binary_stl(meshes / "inverted.stl", box[:, ::-1])
    data = write_binary_stl(meshes / "truncated.stl", box).read_bytes()
    (meshes / "truncated.stl").write_bytes(data[:-70])
    write_binary_stl(meshes / "huge_header.stl", box, count=2 ** 31)
    nan = box.copy()
    nan[3, 1, 2] = np.nan
    write_binary_stl(meshes / "nan.stl", nan)
    write_binary_stl(meshes / "open.stl", box[:-2])
    misoriented = box.copy()
    misoriented[0] = misoriented[0][::-1]
    write_binary_stl(meshes / "misoriented.stl", misoriented)
    degenerate = np.concatenate([box, box[:1, [0, 0, 1]]])
    write_binary_stl(meshes / "degenerate.stl", degenerate)
    write_binary_stl(meshes / "fine.stl", cylinder_triangles())
    cracked = box.copy()
    cracked[4] += 1e-7  # one face 0.1 um off its neighbours (float32 keeps it): rounding
    write_binary_stl(meshes / "cracked.stl", cracked)
    write_collada(meshes / "broken_material.dae", box, material="#nowhere-material")
    write_binary_stl(package.parent / "outside.stl", box)


@pytest.fixture(scope="module")
def fixture_urdf(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("mesh_fixture")
    package = root / "mesh_pkg"
    shutil.copytree(PACKAGE, package)
    write_meshes(package)
    return package / "urdf" / "mistakes.urdf"


def expected(text: str) -> tuple[set[tuple[str, int]], dict[int, str]]:
    pairs, causes = set(), {}
    for number, line in enumerate(text.splitlines(), start=1):
        for match in MARKER.finditer(line):
            pairs.update((c.strip(), number) for c in match.group(1).split(",") if c.strip())
            if match.group(2):
                causes[number] = match.group(2)
    return pairs, causes


def lint(path: Path) -> list[tuple[str, int, str, str | None]]:
    robot = parse_urdf(path.read_bytes(), str(path))
    packages = {"mesh_pkg": str(path.parents[1])}
    meshes = MeshContext(robot, SETTINGS, packages.get)
    found = []
    for rule_ in (r for r in all_rules() if r.family in FAMILIES):
        ctx = RuleContext(options=rule_.default_options(),
                          meshes=meshes if "meshes" in rule_.needs else None)
        for finding in run_rule(rule_, robot, ctx):
            assert finding.where is not None and finding.element
            found.append((rule_.code, finding.where.span.line, finding.message, finding.fix))
    return found


def test_each_mistake_gives_its_code_on_its_line(fixture_urdf: Path) -> None:
    pairs, _ = expected(fixture_urdf.read_text())
    found = {(code, line) for code, line, _, _ in lint(fixture_urdf)}
    assert sorted(found - pairs) == [], "unexpected findings (code, line)"
    assert sorted(pairs - found) == [], "expected findings not reported (code, line)"


def test_each_mistake_names_its_cause(fixture_urdf: Path) -> None:
    _, causes = expected(fixture_urdf.read_text())
    messages: dict[int, list[str]] = {}
    for _code, line, message, _fix in lint(fixture_urdf):
        messages.setdefault(line, []).append(message)
    for line, cause in causes.items():
        assert all(cause in m for m in messages.get(line, [""])), (line, cause, messages.get(line))


def test_inertia_mismatches_carry_the_suggested_block(fixture_urdf: Path) -> None:
    fixes = {message.split("'")[1]: fix for code, _, message, fix in lint(fixture_urdf)
             if code in ("I201", "I204")}
    assert set(fixes) == {"grams_mm2", "rotated", "swapped_sign", "right_leg", "millimetres"}
    assert 'ixx="0.0166667"' in fixes["grams_mm2"] and '<mass value="1"/>' in fixes["grams_mm2"]
    assert 'ixy="0.0103125"' in fixes["swapped_sign"]
    # the mesh in millimetres: the block is that of the mesh scaled by 0.001, and says so
    assert 'ixx="0.0166667"' in fixes["millimetres"] and "scale=" in fixes["millimetres"]


def test_fixture_marks_every_mesh_rule() -> None:
    pairs, _ = expected((PACKAGE / "urdf" / "mistakes.urdf").read_text())
    mesh_rules = {r.code for r in all_rules() if "meshes" in r.needs and r.family in FAMILIES}
    assert sorted(mesh_rules - {code for code, _ in pairs}) == []
