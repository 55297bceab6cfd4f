"""Make tests/mesh/data/meshlab_reference.json: MeshLab's mass properties of a few
watertight example-robot-data meshes, the reference the mesh tests compare against.

pymeshlab is a reference, not a dependency of robotdesc: run this by hand after
`pip install pymeshlab` (the bench extra) and commit the JSON it writes.

    python tests/mesh/data/make_meshlab_reference.py

Each mesh is opened by MeshLab's own importer (so the loaders are checked too) and measured
after "Remove Duplicate Vertices", with "Compute Geometric Measures"
(`get_geometric_measures`): volume (m^3), centre of mass
(m) and the inertia tensor about it for density 1 (m^5, products of inertia negated, as URDF).
"""

from __future__ import annotations

import json
import sys
from importlib import metadata
from pathlib import Path

import pymeshlab

#: Paths below example-robot-data's robots/ directory: watertight STL, COLLADA and OBJ meshes
#: of a range of sizes (12 to 56k triangles).
MESHES = (
    "finger_edu_description/meshes/base_top.stl",
    "talos_data/meshes/arm/arm_7_collision.STL",
    "g1_description/meshes/left_wrist_pitch_link.STL",
    "xarm_description/meshes/xarm7/visual/link_base.stl",
    "z1_description/meshes/collision/z1_Link01.STL",
    "ur_description/meshes/ur5/visual/wrist3.dae",
    "ur_description/meshes/ur5/visual/shoulder.dae",
    "solo_description/meshes/obj/with_foot/solo_upper_leg_left_side.obj",
    "alexander_description/meshes/Foot.obj",
)


def robots_dir() -> Path:
    """example-robot-data's robots/ directory (installed by the cmeel wheel)."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
    from support import example_robot_data_dir

    root = example_robot_data_dir()
    if root is None:
        sys.exit("example-robot-data is not installed")
    return root


def measure(path: Path) -> dict:
    meshes = pymeshlab.MeshSet()
    meshes.load_new_mesh(str(path))
    if meshes.mesh_number() > 1:  # a multi-body file: one layer per body
        meshes.generate_by_merging_visible_meshes()
    # MeshLab's COLLADA and OBJ importers split vertices along normal/UV seams; a MeshLab
    # user merges them before measuring (its STL importer already does).
    meshes.meshing_remove_duplicate_vertices()
    measures = meshes.get_geometric_measures()
    return {
        "volume": float(measures["mesh_volume"]),
        "center_of_mass": [float(v) for v in measures["center_of_mass"]],
        "inertia": [[float(v) for v in row] for row in measures["inertia_tensor"]],
        "faces": int(meshes.current_mesh().face_number()),
    }


def main() -> int:
    root = robots_dir()
    reference = {
        "generator": "tests/mesh/data/make_meshlab_reference.py",
        "pymeshlab": metadata.version("pymeshlab"),
        "units": {"volume": "m^3", "center_of_mass": "m", "inertia": "m^5 (density 1)"},
        "meshes": {name: measure(root / name) for name in MESHES},
    }
    target = Path(__file__).with_name("meshlab_reference.json")
    target.write_text(json.dumps(reference, indent=1) + "\n", encoding="utf-8")
    print(f"wrote {target} ({len(MESHES)} meshes)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
