"""The inline (notebook) form of a view: its meshes reduced to a small face budget and the
page gzip-compressed inside the iframe, so that a notebook stays small (the Engineer's page
is 1.4 MB; its preview about 170 KB). `View.save()` keeps the full page.
"""

from __future__ import annotations

import base64
import gzip
import html
from typing import Any

from robotdesc.view.html import view_page

#: Faces per mesh file in the notebook preview.
PREVIEW_MAX_FACES = 1000

#: Unpacks the gzip'd page in the frame (DecompressionStream: Chrome 80, Firefox 113,
#: Safari 16.4) and replaces the frame's document with it.
_LOADER = ("<script>(async()=>{{const b=Uint8Array.from(atob('{data}'),c=>c.charCodeAt(0));"
           "const t=await new Response(new Blob([b]).stream().pipeThrough("
           "new DecompressionStream('gzip'))).text();"
           "document.open();document.write(t);document.close();}})()</script>")


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


def preview_iframe(document: dict[str, Any], height: str) -> str:
    """An iframe showing the preview page, compressed in its `srcdoc`."""
    page = view_page(preview_document(document)).encode("utf-8")
    data = base64.b64encode(gzip.compress(page, 9, mtime=0)).decode("ascii")
    return (f'<iframe srcdoc="{html.escape(_LOADER.format(data=data), quote=True)}" '
            f'style="width:100%;height:{html.escape(height)};border:0" '
            'sandbox="allow-scripts"></iframe>')
