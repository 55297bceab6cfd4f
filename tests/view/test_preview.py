"""The notebook form of a view: meshes reduced, viewer and scene DEFLATE'd inside the iframe
and unpacked there by inflate.js."""

from __future__ import annotations

import base64
import html
import os
import re
import shutil
import subprocess
import time
import zlib
from pathlib import Path

import pytest

import robotdesc
from robotdesc.view.html import embedded_json, viewer_script
from robotdesc.view.preview import INFLATE_RESOURCE, preview_document, preview_iframe
from view.browser import drawn_pixels, screenshot
from view.robots import write_demo_package

INFLATE = Path(robotdesc.__file__).parent / "view" / INFLATE_RESOURCE


def _payload(frame: str) -> str:
    srcdoc = html.unescape(re.search(r'srcdoc="([^"]*)"', frame).group(1))
    data = re.search(r"atob\('([A-Za-z0-9+/=]+)'\)", srcdoc).group(1)
    return zlib.decompress(base64.b64decode(data), -15).decode("utf-8")


def test_the_preview_unpacks_to_the_viewer_and_the_reduced_scene(tmp_path: Path) -> None:
    view = robotdesc.show(write_demo_package(tmp_path), lint=False)
    small = preview_document(view.document, max_faces=4)
    meshes = [(g, s) for g, s in zip(view.document["geometries"], small["geometries"])
              if not g.get("primitive") and g["faces"] > 4]
    assert meshes and all(s["faces"] < g["faces"] for g, s in meshes)
    frame = view._repr_html_()
    assert _payload(frame) == viewer_script() + "\0" + embedded_json(
        preview_document(view.document))
    assert 'sandbox="allow-scripts"' in frame and "rdInflate" in frame


@pytest.mark.skipif(shutil.which("node") is None, reason="Node.js is not installed")
def test_inflate_js_decodes_what_zlib_deflates(tmp_path: Path) -> None:
    samples = [b"", b"a" * 1000, os.urandom(40_000), viewer_script().encode() * 2]
    for number, data in enumerate(samples):
        for level in (0, 1, 9):
            packer = zlib.compressobj(level, zlib.DEFLATED, -15)
            (tmp_path / f"{number}_{level}.z").write_bytes(packer.compress(data) + packer.flush())
            (tmp_path / f"{number}.raw").write_bytes(data)
    script = (f"{INFLATE.read_text()}\nconst fs = require('fs'); let bad = 0;\n"
              f"for (let n = 0; n < {len(samples)}; n++) for (const l of [0, 1, 9]) {{\n"
              f"  const z = fs.readFileSync('{tmp_path}/' + n + '_' + l + '.z');\n"
              f"  const raw = fs.readFileSync('{tmp_path}/' + n + '.raw');\n"
              "  if (Buffer.compare(Buffer.from(rdInflate(new Uint8Array(z))), raw)) bad++; }\n"
              "console.log('bad ' + bad);")
    done = subprocess.run(["node", "-e", script], capture_output=True, text=True, timeout=60)
    assert done.stdout.strip() == "bad 0", done.stderr


@pytest.mark.slow  # a headless browser, as tests/view/test_browser.py
def test_the_preview_draws_the_robot_in_a_sandboxed_frame(tmp_path: Path) -> None:
    view = robotdesc.show(write_demo_package(tmp_path), lint=False)
    page = tmp_path / "preview.html"
    page.write_text(f"<!DOCTYPE html><html><body style='margin:0'>"
                    f"{preview_iframe(view.document, '760px')}</body></html>")
    # the frame inflates its meshes asynchronously (DecompressionStream), which Chromium's
    # virtual time does not always wait for on a loaded machine: up to five screenshots,
    # each with more virtual time
    drawn = 0.0
    for attempt in range(5):
        drawn = drawn_pixels(screenshot(page, tmp_path / f"preview{attempt}.png",
                                        budget_ms=4000 * (attempt + 1)))
        if drawn > 0.02:
            break
        time.sleep(0.5 * attempt)
    assert drawn > 0.02
