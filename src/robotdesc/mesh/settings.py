"""What the mesh and inertia rules are told by the config (`[meshes]` in robotdesc.toml)."""

from __future__ import annotations

import typing
from dataclasses import dataclass

from robotdesc.errors import SettingError


@dataclass(frozen=True)
class MeshSettings:
    """How meshes are read and what the mesh and inertia rules expect.

    Attributes:
        inertia_source: the geometry that mesh-derived mass properties come from:
            "collision" (default) or "visual"; the other is used when a link has none.
        expected_mass: the robot's expected total mass (kg), checked by B101; None: unchecked.
        mass_tolerance: relative tolerance of the total mass against `expected_mass`.
        allow_absolute_paths: accept `file://` URIs and absolute mesh paths (off: such a
            description works only on the machine that wrote it).
        collision_triangle_budget: the most triangles one collision mesh should have.
        no_contact: links (shell patterns) that `robotdesc collision` (method auto) and
            `robotdesc sim`'s generated collision leave out of contact, e.g. a track's belt
            that touches the ground only through its wheels (`no-contact = ["*_track_link"]`).
        cache: keep mesh summaries in the mesh cache (docs/meshes.md); off: recompute.

    Raises:
        SettingError: a value out of range (also a ValueError; the config reader adds
            the file and line).
    """

    inertia_source: typing.Literal["collision", "visual"] = "collision"
    expected_mass: float | None = None
    mass_tolerance: float = 0.05
    allow_absolute_paths: bool = False
    collision_triangle_budget: int = 10_000
    cache: bool = True
    no_contact: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.expected_mass is not None and not self.expected_mass > 0:
            raise SettingError("expected-mass", self.expected_mass,
                               f"expected-mass must be positive, got {self.expected_mass}")
        if not 0 <= self.mass_tolerance < 1:
            raise SettingError("mass-tolerance", self.mass_tolerance,
                               f"mass-tolerance must be in [0, 1), got {self.mass_tolerance}")
        if self.collision_triangle_budget < 1:
            raise SettingError("collision-triangle-budget", self.collision_triangle_budget,
                               "collision-triangle-budget must be at least 1, got "
                               f"{self.collision_triangle_budget}")
