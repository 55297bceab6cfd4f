"""The notebook form of a view: meshes reduced, the page gzip'd inside the iframe."""

from __future__ import annotations

import base64
import gzip
import html
import re
from pathlib import Path

from view.browser import drawn_pixels, screenshot
from view.robots import write_demo_package

import robotdesc
from robotdesc.view.html import view_page
from robotdesc.view.preview import preview_document, preview_iframe


def _payload(frame: str) -> str:
    srcdoc = html.unescape(re.search(r'srcdoc="([^"]*)"', frame).group(1))
    data = re.search(r"atob\('([A-Za-z0-9+/=]+)'\)", srcdoc).group(1)
    return gzip.decompress(base64.b64decode(data)).decode("utf-8")


def test_the_preview_unpacks_to_the_page_with_reduced_meshes(tmp_path: Path) -> None:
    view = robotdesc.show(write_demo_package(tmp_path), lint=False)
    small = preview_document(view.document, max_faces=4)
    meshes = [(g, s) for g, s in zip(view.document["geometries"], small["geometries"])
              if not g.get("primitive") and g["faces"] > 4]
    assert meshes and all(s["faces"] < g["faces"] for g, s in meshes)
    frame = view._repr_html_()
    assert _payload(frame) == view_page(preview_document(view.document))
    assert 'sandbox="allow-scripts"' in frame and "DecompressionStream" in frame


def test_the_preview_draws_the_robot(tmp_path: Path) -> None:
    view = robotdesc.show(write_demo_package(tmp_path), lint=False)
    page = tmp_path / "preview.html"
    page.write_text(f"<!DOCTYPE html><html><body style='margin:0'>"
                    f"{preview_iframe(view.document, '760px')}</body></html>")
    assert drawn_pixels(screenshot(page, tmp_path / "preview.png")) > 0.02
