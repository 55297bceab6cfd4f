#!/usr/bin/env python3
"""Build the Engineer's visual meshes.

Deterministic procedural CAD (manifold3d booleans, no randomness): every part is built in its
own link frame, in metres, from the dimensions in urdf/properties.xacro, so that meshes and
kinematics share one source. Writes

  meshes/visual/<part>.stl           binary STL, one closed solid per part

The collision meshes are made from these by `robotdesc collision` and the inertials from the
collision geometry by scripts/make_inertials.py (see the README, "Regenerating").

Usage: python scripts/make_meshes.py [--out DIR]   (DIR defaults to the package root)
Needs: numpy, manifold3d.
"""

from __future__ import annotations

import argparse
import logging
import struct
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from manifold3d import Manifold

from engineer_parts import PARTS
from package_properties import PACKAGE, PROPERTIES, read_properties

LOG = logging.getLogger("make_meshes")
STL_HEADER = b"engineer_description scripts/make_meshes.py (binary STL, metres)"


# ----------------------------------------------------------------------------- output

@dataclass(frozen=True)
class MeshData:
    """A triangle mesh: float32 vertices (m) and int faces, outward winding."""

    vertices: np.ndarray
    faces: np.ndarray


def to_mesh(solid: Manifold) -> MeshData:
    """Vertices (as the STL stores them: float32) and faces of `solid`, in canonical order.

    manifold3d works in parallel, so the order of its output varies between runs while the
    geometry does not: vertices are sorted by (x, y, z), each face is rotated to start at its
    lowest vertex index (winding kept), and faces are sorted, so the bytes are reproducible.
    """
    mesh = solid.to_mesh()
    vertices = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3].astype(np.float32)
    faces = np.asarray(mesh.tri_verts, dtype=np.int64)
    order = np.lexsort((vertices[:, 2], vertices[:, 1], vertices[:, 0]))
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    faces = rank[faces]
    first = np.argmin(faces, axis=1)
    faces = np.stack([faces[np.arange(len(faces)), (first + k) % 3] for k in range(3)], axis=1)
    faces = faces[np.lexsort((faces[:, 2], faces[:, 1], faces[:, 0]))]
    return MeshData(vertices[order], faces)


def stl_bytes(mesh: MeshData) -> bytes:
    """Binary STL of `mesh` with a fixed header (so output is byte-for-byte reproducible)."""
    tri = mesh.vertices[mesh.faces].astype(np.float32)
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]).astype(np.float64)
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = (normals / np.where(lengths > 0, lengths, 1.0)).astype(np.float32)
    record = np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    data = np.zeros(len(tri), dtype=record)
    data["n"], data["v"] = normals, tri
    return STL_HEADER.ljust(80, b" ") + struct.pack("<I", len(tri)) + data.tobytes()


def build(out: Path, properties: Path) -> dict[str, MeshData]:
    """Build every part, write its mesh under `out`; return the meshes."""
    g = read_properties(properties)
    mesh_dir = out / "meshes" / "visual"
    mesh_dir.mkdir(parents=True, exist_ok=True)
    meshes: dict[str, MeshData] = {}
    for name, builder in PARTS.items():
        solid = builder(g)
        if solid.status().name != "NoError":
            raise RuntimeError(f"{name}: manifold status {solid.status()}")
        if len(solid.decompose()) != 1:
            raise RuntimeError(f"{name}: {len(solid.decompose())} disconnected bodies, expected one")
        mesh = to_mesh(solid)
        (mesh_dir / f"{name}.stl").write_bytes(stl_bytes(mesh))
        meshes[name] = mesh
        LOG.info("%-20s %8d triangles", name, len(mesh.faces))
    return meshes


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=PACKAGE, help="output root (default: the package)")
    parser.add_argument("--properties", type=Path, default=PROPERTIES)
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    meshes = build(args.out, args.properties)
    LOG.info("%-20s %8d triangles", "total (files)", sum(len(m.faces) for m in meshes.values()))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
