"""Hand an expanded description to yourdfpy (extra `yourdfpy`): its `URDF` object for forward
kinematics, scenes and its viewer, with every `<mesh filename>` resolved by robotdesc's own
package resolver (`mesh/locate.py`), so no ROS lookup happens.

yourdfpy reads the clean URDF text (as `robotdesc expand` writes it); its `filename_handler`
maps each mesh filename of the model to the file robotdesc found. A filename robotdesc cannot
resolve is passed on unchanged (yourdfpy then warns and leaves that mesh out).
"""

from __future__ import annotations

import io
from collections.abc import Callable, Sequence
from typing import Any

from robotdesc.errors import UsageError
from robotdesc.expansion.result import Expanded
from robotdesc.mesh.locate import MeshLocator
from robotdesc.model.elements import Collision, MeshRef, Robot, Visual
from robotdesc.model.write import urdf_text

#: How to install the extra.
YOURDFPY_HINT = "install it with: pip install '.[yourdfpy]' (in a clone of robotdesc)"


def mesh_filename_handler(robot: Robot, locator: MeshLocator) -> Callable[[str], str]:
    """A yourdfpy `filename_handler`: a `<mesh filename>` of `robot` -> the file it
    resolves to (absolute path), or the filename unchanged when it does not resolve."""
    found: dict[str, str] = {}
    for link in robot.links:
        shapes: list[Visual | Collision] = [*link.visuals, *link.collisions]
        for geometry in (shape.geometry for shape in shapes):
            if isinstance(geometry, MeshRef) and geometry.filename not in found:
                path = locator.path(geometry)
                if path is not None:
                    found[geometry.filename] = path

    def handler(fname: str) -> str:  # yourdfpy passes the name as `fname=`
        return found.get(fname, fname)

    return handler


def yourdfpy_urdf(expanded: Expanded, robot: Robot, *, package_paths: Sequence[str] = (),
                  package_map: Sequence[tuple[str, str]] = (), allow_absolute: bool = False,
                  **options: Any) -> Any:
    """A `yourdfpy.URDF` of an expansion.

    Args:
        expanded: the expansion (its clean URDF text is what yourdfpy reads).
        robot: its parsed model (the meshes to resolve).
        package_paths: folders searched for ROS packages first.
        package_map: (package, folder) pairs of the config.
        allow_absolute: accept `file://` URIs and absolute mesh paths (config policy).
        **options: passed to `yourdfpy.URDF.load` (`load_meshes`, `build_scene_graph`,
            `load_collision_meshes`, ...).

    Raises:
        UsageError: yourdfpy is not installed.
    """
    try:
        import yourdfpy
    except ImportError:
        raise UsageError(f"yourdfpy is not installed; {YOURDFPY_HINT}") from None
    locator = MeshLocator.for_robot(robot, package_paths, package_map,
                                    allow_absolute=allow_absolute, origin=expanded.source)
    text = urdf_text(expanded.xml, expanded.source)
    return yourdfpy.URDF.load(io.BytesIO(text),
                              filename_handler=mesh_filename_handler(robot, locator),
                              **options)
