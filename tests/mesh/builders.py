"""Tiny meshes and mesh files for the mesh tests."""

from __future__ import annotations

from pathlib import Path

import numpy as np


def box_triangles(size=(1.0, 2.0, 3.0), center=(0.0, 0.0, 0.0)) -> np.ndarray:
    """A closed, outward-wound box as a (12, 3, 3) soup."""
    half = np.asarray(size, dtype=float) / 2
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)],
                       dtype=float) * half + np.asarray(center, dtype=float)
    # corner index = 4*ix + 2*iy + iz; each quad listed counter-clockwise seen from outside
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    faces = []
    for a, b, c, d in quads:
        faces += [(a, b, c), (a, c, d)]
    return corners[np.array(faces)]


def write_binary_stl(path: Path, triangles: np.ndarray, header: bytes = b"robotdesc test",
                     count: int | None = None) -> Path:
    """Write a binary STL; `count` overrides the triangle count in the header."""
    records = np.zeros(len(triangles), dtype=[("normal", "<f4", (3,)),
                                              ("vertices", "<f4", (3, 3)), ("attr", "<u2")])
    records["vertices"] = triangles
    with open(path, "wb") as stream:
        stream.write(header.ljust(80, b" ")[:80])
        stream.write(int(len(triangles) if count is None else count).to_bytes(4, "little"))
        stream.write(records.tobytes())
    return path


def write_ascii_stl(path: Path, triangles: np.ndarray) -> Path:
    lines = ["solid test"]
    for tri in triangles:
        lines += ["  facet normal 0 0 0", "    outer loop"]
        lines += [f"      vertex {float(x)!r} {float(y)!r} {float(z)!r}" for x, y, z in tri]
        lines += ["    endloop", "  endfacet"]
    lines.append("endsolid test")
    path.write_text("\n".join(lines) + "\n")
    return path


def write_collada(path: Path, triangles: np.ndarray, unit_meter: float | None = None,
                  matrix: np.ndarray | None = None, instantiate: bool = True,
                  material: str | None = None, image: str | None = None) -> Path:
    """Write a one-geometry COLLADA 1.4.1 file (indexed as a soup) placed by one node.

    Args:
        unit_meter: value of `<unit meter>`; None writes no `<unit>`.
        matrix: the node's 4x4 transform (identity when None).
        instantiate: place the geometry in the scene (False: define it only).
        material: bind the triangles to this material target (e.g. "#m"), which the file
            does not define (a broken reference).
        image: declare a texture image with this file path.
    """
    flat = np.asarray(triangles, dtype=float).reshape(-1, 3)
    positions = " ".join(repr(float(v)) for v in flat.reshape(-1))
    indices = " ".join(str(i) for i in range(len(flat)))
    node_matrix = np.identity(4) if matrix is None else np.asarray(matrix, dtype=float)
    node_text = " ".join(repr(float(v)) for v in node_matrix.reshape(-1))
    unit = "" if unit_meter is None else f'<unit name="u" meter="{unit_meter}"/>'
    binding = ("" if material is None else '<bind_material><technique_common>'
               f'<instance_material symbol="mat" target="{material}"/>'
               '</technique_common></bind_material>')
    instance = f'<instance_geometry url="#g">{binding}</instance_geometry>' if instantiate else ""
    images = ("" if image is None else
              f'<library_images><image id="tex"><init_from>{image}</init_from></image>'
              '</library_images>')
    path.write_text(f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset>{unit}<up_axis>Z_UP</up_axis></asset>{images}
  <library_geometries>
    <geometry id="g" name="g"><mesh>
      <source id="g-pos">
        <float_array id="g-pos-array" count="{flat.size}">{positions}</float_array>
        <technique_common><accessor source="#g-pos-array" count="{len(flat)}" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common>
      </source>
      <vertices id="g-vtx"><input semantic="POSITION" source="#g-pos"/></vertices>
      <triangles count="{len(triangles)}"{' material="mat"' if material else ''}>
        <input semantic="VERTEX" source="#g-vtx" offset="0"/>
        <p>{indices}</p>
      </triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="s" name="s">
      <node id="n" name="n"><matrix>{node_text}</matrix>{instance}</node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
""")
    return path


def write_obj(path: Path, vertices: np.ndarray, faces: np.ndarray) -> Path:
    lines = [f"v {float(x)!r} {float(y)!r} {float(z)!r}" for x, y, z in vertices]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in faces]
    path.write_text("\n".join(lines) + "\n")
    return path
