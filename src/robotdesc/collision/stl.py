"""Binary STL bytes of a mesh part: deterministic (fixed header, float32, computed normals)."""

from __future__ import annotations

import numpy as np

from robotdesc.collision.result import MeshPart

HEADER = b"robotdesc collision mesh".ljust(80, b" ")


def stl_bytes(part: MeshPart) -> bytes:
    """The part as a binary STL (metres)."""
    corners = part.vertices[part.faces]
    normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    length = np.linalg.norm(normal, axis=1, keepdims=True)
    normal = np.divide(normal, length, out=np.zeros_like(normal), where=length > 0)
    records = np.zeros(len(corners), dtype=[("normal", "<f4", (3,)),
                                            ("vertices", "<f4", (3, 3)), ("attr", "<u2")])
    records["normal"] = normal
    records["vertices"] = corners
    return HEADER + len(corners).to_bytes(4, "little") + records.tobytes()
