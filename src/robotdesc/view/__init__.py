"""3D views of a robot: a display scene (world transforms of every visual and collision
geometry at a configuration, equivalent inertia boxes), encoded into one self-contained HTML
page with a small WebGL viewer (viewer.js, no network).

    import robotdesc
    view = robotdesc.show("robot.urdf.xacro", {"elbow": 0.5})   # displays inline in Jupyter
    view.save("robot.html")

Modules: forward (kinematics), shapes (primitive meshes), simplify (display reduction),
inertia_box, scene, findings, encode, html, show (meshes are found by `robotdesc.mesh.locate`).
"""

from __future__ import annotations

from typing import Any

__all__ = ["View", "build_scene", "show"]


def show(*args: Any, **kwargs: Any) -> Any:
    """See `robotdesc.view.show.show`."""
    from robotdesc.view.show import show as run

    return run(*args, **kwargs)


def build_scene(*args: Any, **kwargs: Any) -> Any:
    """See `robotdesc.view.scene.build_scene`."""
    from robotdesc.view.scene import build_scene as run

    return run(*args, **kwargs)


def __getattr__(name: str) -> Any:
    if name == "View":
        from robotdesc.view.show import View

        return View
    raise AttributeError(name)
