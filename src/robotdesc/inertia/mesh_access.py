"""What the inertia functions and the lint rules read of a robot's meshes, as a protocol:
`robotdesc.mesh.context.MeshContext` is one (the lint driver and the commands build it); a
test may hand in another. Units: m, and mass properties at density 1 kg/m^3.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Protocol

from robotdesc.mesh.context import LinkGeometry, MeshLookup
from robotdesc.mesh.settings import MeshSettings
from robotdesc.model.elements import Collision, Link, MeshRef, Visual

#: One `<mesh>` of the robot: (link, "visual" | "collision", index, element, reference).
MeshUse = tuple[Link, str, int, Visual | Collision, MeshRef]


class MeshAccess(Protocol):
    """Mesh access for one robot: resolved and summarized `<mesh>` references, and each
    link's geometry measured in the link frame."""

    @property
    def settings(self) -> MeshSettings:
        """The config's mesh settings (`[tool.robotdesc.meshes]`)."""
        ...

    def find_package(self, name: str) -> str | None:
        """The root directory of package `name`, or None when it is unknown."""
        ...

    def lookup(self, ref: MeshRef) -> MeshLookup:
        """One `<mesh>` resolved and (when it resolved) summarized."""
        ...

    def meshes(self) -> Iterator[MeshUse]:
        """Every `<mesh>` of the robot."""
        ...

    def link_geometry(self, link: Link, source: str | None = None) -> LinkGeometry:
        """The link's geometry measured at density 1 kg/m^3, in the link frame.

        Args:
            source: "collision" or "visual"; None: the configured `inertia_source`.
        """
        ...
