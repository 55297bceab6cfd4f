"""The scene document, the page that embeds it, and `show()`."""

from __future__ import annotations

import base64
import json
import re
from pathlib import Path

import numpy as np
import pytest

import robotdesc
from robotdesc.errors import UsageError
from robotdesc.view.encode import scene_document
from robotdesc.view.html import embedded_json, view_fragment, view_page, viewer_script
from robotdesc.view.scene import build_scene
from robotdesc.view.show import View, show

from .robots import write_demo_package


@pytest.fixture
def urdf(tmp_path: Path) -> Path:
    return write_demo_package(tmp_path)


def _document_in(page: str) -> dict:
    match = re.search(r'<script type="application/json" id="robotdesc-view-data">(.*?)</script>',
                      page, re.DOTALL)
    assert match, "the page embeds the scene document"
    return json.loads(match.group(1))


def test_arrays_round_trip_through_base64(urdf: Path) -> None:
    scene = build_scene(robotdesc.load(str(urdf)))
    document = scene_document(scene)
    for shape, encoded in zip(scene.geometries, document["geometries"]):
        positions = np.frombuffer(base64.b64decode(encoded["positions"]), "<f4").reshape(-1, 3)
        dtype = "<u2" if encoded["index_type"] == "uint16" else "<u4"
        indices = np.frombuffer(base64.b64decode(encoded["indices"]), dtype).reshape(-1, 3)
        assert np.array_equal(positions, shape.vertices)
        assert np.array_equal(indices, shape.faces)
    instance = document["instances"][0]
    matrix = np.array(instance["matrix"]).reshape(4, 4).T  # column-major
    assert np.allclose(matrix, scene.instances[0].transform, atol=1e-7)
    assert document["links"][0] == {"name": "base", "visual_faces": 12, "collision_faces": 12,
                                    "findings": []}


def test_embedded_json_cannot_close_its_script() -> None:
    text = embedded_json({"message": "</script><script>alert(1)</script>\u2028"})
    assert "</" not in text and "\u2028" not in text
    assert json.loads(text) == {"message": "</script><script>alert(1)</script>\u2028"}


def test_the_page_is_self_contained(urdf: Path) -> None:
    page = view_page(scene_document(build_scene(robotdesc.load(str(urdf)))))
    assert viewer_script().strip()[:40] in page
    assert not re.search(r'(src|href)\s*=\s*["\']?(https?:)?//', page), "no network resources"
    assert "http://" not in page.replace("http://www.w3.org", "")
    assert page.count("<script") == page.count("</script>") == 2
    assert _document_in(page)["robot"] == "demo"


def test_a_fragment_without_the_viewer() -> None:
    fragment = view_fragment({"robot": "r"}, element_id="v1", include_viewer=False)
    assert 'data-robotdesc-scene="v1-data"' in fragment and "RobotdescViewer" not in fragment


def test_show_lints_a_file_and_marks_the_links_with_findings(urdf: Path) -> None:
    view = show(str(urdf), {"grip": 0.02}, visible=("visual", "inertia"))
    document = view.to_dict()
    flagged = {link["name"] for link in document["links"] if link["findings"]}
    assert "finger_right" in flagged  # its missing mesh (M101)
    assert "base" not in {link["name"] for link in document["links"]
                          if any(f["code"].startswith("M") for f in link["findings"])}
    assert document["show"] == {"visual": True, "collision": False, "inertia": True,
                                "findings": False}
    assert document["configuration"]["grip_mirror"] == pytest.approx(-0.02)
    assert "links with findings" in repr(view)


def test_show_takes_a_robot_or_a_lint_result(urdf: Path) -> None:
    result = robotdesc.lint(str(urdf))
    from_result = show(result).to_dict()
    assert sum(len(link["findings"]) for link in from_result["links"]) >= 1
    from_robot = show(result.robot).to_dict()
    assert all(not link["findings"] for link in from_robot["links"])
    with pytest.raises(TypeError, match="not int"):
        show(3)


def test_show_rejects_unknown_options(urdf: Path) -> None:
    with pytest.raises(UsageError, match="unknown view option 'wireframe'"):
        show(str(urdf), visible=("wireframe",))


def test_notebook_display_is_an_iframe_of_the_page(urdf: Path, tmp_path: Path) -> None:
    view = show(str(urdf), lint=False)
    assert isinstance(view, View)
    markup = view._repr_html_()  # a compressed preview (tests/view/test_preview.py)
    assert markup.startswith("<iframe srcdoc=\"") and 'sandbox="allow-scripts"' in markup
    assert "&lt;script&gt;" in markup and "<script" not in markup  # all escaped
    saved = Path(view.save(tmp_path / "demo.html"))
    assert saved.read_text(encoding="utf-8") == view.html()


def test_robotdesc_show_is_public(urdf: Path) -> None:
    assert robotdesc.show is not None
    assert isinstance(robotdesc.show(str(urdf), lint=False), View)
