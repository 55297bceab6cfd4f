"""The inline (notebook) form of a view: its meshes reduced to a small face budget, and the
viewer and the scene document DEFLATE-compressed inside the iframe's page (unpacked there,
synchronously, by a small decoder, inflate.js; then the viewer starts as on the full page),
so that a notebook stays small (the Engineer's page is 1.4 MB; its preview about 170 KB).
`View.save()` keeps the full page.
"""

from __future__ import annotations

import base64
import html
import zlib
from functools import lru_cache
from importlib import resources
from typing import Any

from robotdesc.view.html import embedded_json, inline_script, viewer_script

#: Faces per mesh file in the notebook preview.
PREVIEW_MAX_FACES = 1000
INFLATE_RESOURCE = "inflate.js"

#: Unpacks the viewer and the scene's JSON (one string, a NUL between them: JSON escapes its
#: own), fills the data element and runs the viewer, which mounts the element.
_UNPACK = ("(function(){var b=atob('{packed}'),a=new Uint8Array(b.length);"
           "for(var i=0;i<b.length;i++)a[i]=b.charCodeAt(i);"
           "var t=new TextDecoder().decode(rdInflate(a)),cut=t.indexOf('\\u0000');"
           "document.getElementById('robotdesc-view-data').textContent=t.slice(cut+1);"
           "var v=document.createElement('script');v.textContent=t.slice(0,cut);"
           "document.body.appendChild(v);})();")
_HEAD = ("<!DOCTYPE html><html><head><meta charset=\"utf-8\"><style>html,body{margin:0;"
         "height:100%;overflow:hidden}</style></head><body>"
         "<script type=\"application/json\" id=\"robotdesc-view-data\"></script>"
         "<div id=\"robotdesc-view\" class=\"robotdesc-view\" "
         "data-robotdesc-scene=\"robotdesc-view-data\" style=\"height:100vh\"></div>")


@lru_cache(maxsize=1)
def inflate_script() -> str:
    """The DEFLATE decoder's JavaScript (package data of robotdesc.view)."""
    return resources.files("robotdesc.view").joinpath(INFLATE_RESOURCE).read_text("utf-8")


def deflate_base64(text: str) -> str:
    """`text` as raw DEFLATE (what inflate.js reads), base64'd."""
    packer = zlib.compressobj(9, zlib.DEFLATED, -15)
    return base64.b64encode(packer.compress(text.encode("utf-8")) + packer.flush()).decode()


def preview_document(document: dict[str, Any], max_faces: int = PREVIEW_MAX_FACES
                     ) -> dict[str, Any]:
    """`document` with every mesh above `max_faces` faces reduced (primitives kept)."""
    import numpy as np

    from robotdesc.view.encode import b64_array
    from robotdesc.view.simplify import reduce_faces

    geometries = []
    for geometry in document["geometries"]:
        if geometry["faces"] <= max_faces or geometry.get("primitive"):
            geometries.append(geometry)
            continue
        dtype = "<u4" if geometry["index_type"] == "uint32" else "<u2"
        vertices = np.frombuffer(base64.b64decode(geometry["positions"]), "<f4").reshape(-1, 3)
        faces = np.frombuffer(base64.b64decode(geometry["indices"]), dtype).reshape(-1, 3)
        vertices, faces = reduce_faces(vertices.astype(float), faces.astype(np.int64), max_faces)
        wide = len(vertices) > 65535
        geometries.append({**geometry, "faces": len(faces),
                           "positions": b64_array(vertices, "<f4"),
                           "indices": b64_array(faces, "<u4" if wide else "<u2"),
                           "index_type": "uint32" if wide else "uint16"})
    return {**document, "geometries": geometries}


def preview_page(document: dict[str, Any]) -> str:
    """The preview page of a scene document (its meshes reduced, everything compressed)."""
    packed = deflate_base64(viewer_script() + "\0" + embedded_json(preview_document(document)))
    return (_HEAD + inline_script(inflate_script() + "\n" + _UNPACK.replace("{packed}", packed))
            + "</body></html>")


def preview_iframe(document: dict[str, Any], height: str) -> str:
    """An iframe showing the preview page in its `srcdoc` (scripts run in the frame only)."""
    return (f'<iframe srcdoc="{html.escape(preview_page(document), quote=True)}" '
            f'style="width:100%;height:{html.escape(height)};border:0" '
            'sandbox="allow-scripts"></iframe>')
