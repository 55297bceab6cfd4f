"""Method auto: per-link candidates, the robot-wide choice under a tolerance in the robot's
scale and a triangle budget, and its report."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from mesh.builders import write_binary_stl

from collision.conftest import write_urdf
from robotdesc.cli import main
from robotdesc.collision.choose import choose_auto, no_contact_outcome
from robotdesc.collision.link import LinkTask, run_link
from robotdesc.collision.methods import METHOD_TABLE
from robotdesc.collision.options import DEFAULT_BUDGET, METHODS, CollisionOptions
from robotdesc.collision.result import LinkOutcome, LinkReport, MeshPart
from robotdesc.collision.tessellate import primitive_mesh
from robotdesc.model.elements import Cylinder


def _subdivide(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """A triangle soup with each triangle split in four (same surface, 4x the faces)."""
    corners = vertices[faces]
    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
    ab, bc, ca = (a + b) / 2, (b + c) / 2, (c + a) / 2
    return np.concatenate([np.stack(t, axis=1) for t in
                           ((a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca))])


def _truncated_cube(edge: float = 0.1, cut: float = 0.3) -> tuple[np.ndarray, np.ndarray]:
    """A convex part that no primitive fits: a cube with its corners cut off deeply."""
    from robotdesc.collision.hull import convex_hull

    h, k = edge / 2, edge / 2 * (1 - cut)
    points = []
    for sx in (-1, 1):
        for sy in (-1, 1):
            for sz in (-1, 1):
                points += [(sx * k, sy * h, sz * h), (sx * h, sy * k, sz * h),
                           (sx * h, sy * h, sz * k)]
    hull = convex_hull(np.array(points))
    return hull.vertices, hull.faces


def _chosen(soup: np.ndarray, name: str, **options: object) -> LinkOutcome:
    outcome = run_link(LinkTask(name, soup, CollisionOptions("auto", **options), key=name))
    [chosen] = choose_auto([outcome], CollisionOptions("auto", **options))
    return chosen


def test_the_method_table_is_the_one_list_of_methods():
    from robotdesc.collision.link import MAKERS

    assert METHODS == tuple(m.name for m in METHOD_TABLE)
    assert METHODS[0] == "auto" and CollisionOptions().method == "auto"
    assert set(MAKERS) == set(METHODS) - {"auto"}


def test_a_wheel_mesh_becomes_a_cylinder():
    wheel = primitive_mesh(Cylinder(0.007, 0.02))
    chosen = _chosen(wheel.vertices[wheel.faces], "wheel")
    assert chosen.report.method == "primitive:cylinder", chosen.report.detail
    assert chosen.report.faces_after == 0
    assert "cheapest of" in chosen.report.detail
    assert {a.report.method.split(":")[0] for a in chosen.alternatives} >= {"primitive",
                                                                            "hull", "decimate"}


def test_a_convex_part_becomes_its_hull():
    vertices, faces = _truncated_cube()
    once = _subdivide(vertices, faces)
    soup = _subdivide(once.reshape(-1, 3), np.arange(len(once) * 3).reshape(-1, 3))
    chosen = _chosen(soup, "bracket")
    assert chosen.report.method == "hull", chosen.report.detail
    assert chosen.report.percent(chosen.report.hausdorff) < 0.01
    assert chosen.report.faces_after < len(soup)
    assert chosen.report.status == "ok"


def _candidate(link: str, method: str, faces: int, distance: float) -> LinkOutcome:
    part = MeshPart(np.zeros((3, 3)), np.zeros((max(faces, 1), 3), dtype=np.int64))
    report = LinkReport(link, method, "ok", faces_before=10_000, faces_after=faces,
                        forward_max=distance, backward_max=distance, diagonal=0.5)
    return LinkOutcome(report, (part,), link)


def _link(name: str, key: str, menu: list[tuple[str, int, float]]) -> LinkOutcome:
    alternatives = tuple(_candidate(name, *item) for item in menu)
    return LinkOutcome(alternatives[0].report, alternatives[0].parts, key, alternatives)


MENU_A = [("decimate", 2000, 0.001), ("decimate", 500, 0.003), ("hull", 100, 0.02)]
MENU_B = [("decimate", 800, 0.002), ("decimate", 200, 0.004), ("hull", 60, 0.05)]


def test_the_budget_is_honoured_trading_the_least_distance_per_triangle():
    outcomes = [_link("a", "ka", MENU_A), _link("b1", "kb", MENU_B), _link("b2", "kb", MENU_B)]
    tolerance = {"target_percent": 0.5}  # 2.5 mm of the largest diagonal, 0.5 m
    free = choose_auto(outcomes, CollisionOptions("auto", budget_triangles=0, **tolerance))
    assert [o.report.faces_after for o in free] == [2000, 800, 800]
    cheap = choose_auto(outcomes, CollisionOptions("auto", budget_triangles=0))  # 5 mm
    assert [o.report.faces_after for o in cheap] == [500, 200, 200]
    chosen = choose_auto(outcomes, CollisionOptions("auto", budget_triangles=1000,
                                                    **tolerance))
    faces = [o.report.faces_after for o in chosen]
    assert sum(faces) <= 1000  # identical links counted each time
    assert faces == [500, 200, 200]
    assert all(o.report.status == "ok" for o in chosen)
    for outcome in chosen:
        [finding] = outcome.report.findings
        assert finding.code == "budget" and finding.severity == "info"
        assert "budget of 1,000 triangles" in outcome.report.detail
    assert chosen[1].report.link == "b1" and chosen[2].report.link == "b2"


def test_a_budget_out_of_reach_is_a_warning_naming_the_option():
    outcomes = [_link("a", "ka", MENU_A), _link("b", "kb", MENU_B)]
    chosen = choose_auto(outcomes, CollisionOptions("auto", budget_triangles=50))
    assert sum(o.report.faces_after for o in chosen) == 160
    codes = [f.code for o in chosen for f in o.report.findings]
    assert "over-budget" in codes
    message = next(f.message for o in chosen for f in o.report.findings
                   if f.code == "over-budget")
    assert "--budget 160" in message


def test_no_candidate_within_the_tolerance_is_a_warning():
    outcomes = [_link("a", "ka", [("hull", 100, 0.02)])]
    [chosen] = choose_auto(outcomes, CollisionOptions("auto", target_percent=0.5))
    [finding] = chosen.report.findings
    assert finding.code == "target-not-met" and "--target 4" in finding.message


def test_a_link_left_out_of_contact_gets_no_collision():
    outcome = no_contact_outcome(_link("belt", "k", MENU_A))
    assert outcome.written and outcome.parts == ()
    assert outcome.report.method == "none" and "--no-contact" in outcome.report.detail


@pytest.fixture
def crawler(tmp_path: Path) -> Path:
    """A package with a wheel mesh used by three links and a convex body mesh."""
    root = tmp_path / "demo"
    (root / "meshes").mkdir(parents=True)
    (root / "urdf").mkdir()
    (root / "package.xml").write_text("<package format='3'><name>demo</name></package>")
    wheel = primitive_mesh(Cylinder(0.02, 0.01))
    write_binary_stl(root / "meshes" / "wheel.stl", wheel.vertices[wheel.faces])
    vertices, faces = _truncated_cube(0.3)
    write_binary_stl(root / "meshes" / "body.stl", _subdivide(vertices, faces))
    return write_urdf(root, {"body": "body.stl", "wheel_1": "wheel.stl",
                             "wheel_2": "wheel.stl", "wheel_3": "wheel.stl"})


def test_the_command_reports_each_choice(crawler: Path, tmp_path: Path, capsys):
    cache = ["--no-cache"]
    assert main(["collision", str(crawler), "--dry-run", *cache]) == 0
    out = capsys.readouterr().out
    assert "auto chose:" in out
    assert "wheel_1 (+2 identical): primitive:cylinder, 0 triangles, Hausdorff" in out
    assert "body: hull, " in out and "cheapest of" in out
    assert "3 primitives" in out
    assert main(["collision", str(crawler), "--dry-run", "--no-contact", "wheel_*", *cache]) == 0
    out = capsys.readouterr().out
    assert "wheel_1 (+2 identical): none, 0 triangles" in out
    assert main(["collision", str(crawler), "--dry-run", "--no-contact", "tyre", *cache]) == 2
    assert "--no-contact 'tyre' matches no link" in capsys.readouterr().err


def test_the_default_budget_is_under_the_papers_hand_made_collision():
    assert 2000 <= DEFAULT_BUDGET <= 5644


def test_links_left_out_of_contact_lose_their_collision_in_the_output(crawler: Path,
                                                                       tmp_path: Path, capsys):
    out = tmp_path / "out"
    assert main(["collision", str(crawler), "--out", str(out), "--no-contact", "wheel_2,wheel_3",
                 "--no-cache"]) == 0
    urdf = (out / "demo.collision.urdf").read_text()
    from robotdesc.model.parse import parse_urdf

    robot = parse_urdf(urdf, str(out / "demo.collision.urdf"))
    by_name = {link.name: link for link in robot.links}
    assert by_name["wheel_2"].collisions == () and by_name["wheel_3"].collisions == ()
    assert len(by_name["wheel_1"].collisions) == 1 and by_name["body"].collisions
    assert main(["collision", str(crawler), "--out", str(out), "--no-contact", "wheel_2,wheel_3",
                 "--no-cache", "--check"]) == 0


def test_the_config_can_leave_links_out_of_contact(crawler: Path, capsys):
    (crawler.parent.parent / "robotdesc.toml").write_text('[meshes]\nno-contact = ["wheel_3"]\n')
    assert main(["collision", str(crawler), "--dry-run", "--no-cache", "--no-contact",
                 "wheel_2"]) == 0
    out = capsys.readouterr().out
    assert "wheel_1: primitive:cylinder" in out
    assert "wheel_2 (+1 identical): none, 0 triangles" in out
