"""One self-contained HTML page (or a fragment of one) holding a scene and the viewer.

The scene document is embedded as JSON in a `<script type="application/json">` element and
the viewer (viewer.js, package data) is inlined: the page opens from disk with no network.
"""

from __future__ import annotations

import html
import json
from collections.abc import Mapping
from functools import lru_cache
from importlib import resources

VIEWER_RESOURCE = "viewer.js"


@lru_cache(maxsize=1)
def viewer_script() -> str:
    """The viewer's JavaScript source (package data of robotdesc.view)."""
    return resources.files("robotdesc.view").joinpath(VIEWER_RESOURCE).read_text("utf-8")


def embedded_json(document: Mapping[str, object]) -> str:
    """`document` as JSON safe inside a `<script>` element (no `</` sequence, no U+2028/9)."""
    text = json.dumps(document, separators=(",", ":"), ensure_ascii=False, allow_nan=False)
    return (text.replace("<", "\\u003c").replace("\u2028", "\\u2028")
            .replace("\u2029", "\\u2029"))


def inline_script(source: str) -> str:
    """JavaScript source inside a `<script>` element (a literal `</script` is split)."""
    return "<script>\n" + source.replace("</script", "<\\/script") + "\n</script>"


def view_fragment(document: Mapping[str, object], element_id: str = "robotdesc-view", height: str = "560px",
                  include_viewer: bool = True) -> str:
    """A `<div>` that becomes the viewer, its data, and (unless already on the page) the
    viewer script.

    Args:
        document: the scene document (see encode.py).
        element_id: the id of the viewer's element (its data gets `<id>-data`).
        height: CSS height of the viewer.
        include_viewer: inline viewer.js (False when the page already holds it).
    """
    data_id = f"{element_id}-data"
    parts = [(f'<script type="application/json" id="{html.escape(data_id)}">'
              f"{embedded_json(document)}</script>"),
             (f'<div id="{html.escape(element_id)}" class="robotdesc-view" '
              f'data-robotdesc-scene="{html.escape(data_id)}" '
              f'style="height:{html.escape(height)}"></div>')]
    if include_viewer:
        parts.append(inline_script(viewer_script()))
    return "\n".join(parts)


def view_page(document: Mapping[str, object], title: str | None = None) -> str:
    """A complete HTML page showing the scene full-window."""
    heading = html.escape(title or f"{document.get('robot', 'robot')} - robotdesc view")
    return ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            f"<title>{heading}</title>\n"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
            "<meta name=\"generator\" content=\"robotdesc\">\n"
            "<style>html,body{margin:0;height:100%;overflow:hidden}</style>\n"
            "</head>\n<body>\n" + view_fragment(document, height="100vh") + "\n</body>\n</html>\n")
