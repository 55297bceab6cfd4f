"""Procedural CAD helpers for the Engineer's meshes (manifold3d), in metres.

Solids are built in a link frame (x forward, y left, z up); profiles drawn "in the x-z plane"
use (x, z) as the 2-D coordinates and are extruded along y.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from manifold3d import CrossSection, Manifold, OpType

# Level of detail: segments of a full circle, by feature size.
SEG_BIG = 320      # pulleys, turntable, head body corners
SEG_MID = 160      # hubs, actuators, lenses
SEG_SMALL = 48     # bolts, cleats, pins


def rot_y(angle: float) -> np.ndarray:
    """Rotation matrix about +y by `angle` radians."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def place(solid: Manifold, rotation: np.ndarray, xyz: tuple[float, float, float]) -> Manifold:
    """Rotate `solid` by `rotation` (3x3) then translate it by `xyz` (m)."""
    matrix = np.hstack([rotation, np.asarray(xyz, dtype=float).reshape(3, 1)])
    return solid.transform(matrix)


def union(parts: list[Manifold]) -> Manifold:
    """Boolean union of `parts`."""
    return Manifold.batch_boolean(parts, OpType.Add)


def box(lo: tuple[float, float, float], hi: tuple[float, float, float]) -> Manifold:
    """Axis-aligned box between corners `lo` and `hi` (m)."""
    size = [h - l for l, h in zip(lo, hi)]
    return Manifold.cube(size).translate(list(lo))


def rounded_box(lo, hi, radius: float, segments: int = SEG_MID) -> Manifold:
    """Box between `lo` and `hi` with edges rounded by `radius` (hull of 8 spheres)."""
    ball = Manifold.sphere(radius, segments)
    corners = [(x, y, z)
               for x in (lo[0] + radius, hi[0] - radius)
               for y in (lo[1] + radius, hi[1] - radius)
               for z in (lo[2] + radius, hi[2] - radius)]
    return Manifold.batch_hull([ball.translate(list(c)) for c in corners])


def cyl_x(radius, x0, x1, y=0.0, z=0.0, segments=SEG_MID, radius_end=-1.0) -> Manifold:
    """Cylinder (or cone) along x from x0 to x1."""
    return (Manifold.cylinder(x1 - x0, radius, radius_end, segments)
            .rotate([0, 90, 0]).translate([x0, y, z]))


def cyl_y(radius, y0, y1, x=0.0, z=0.0, segments=SEG_MID) -> Manifold:
    """Cylinder along y from y0 to y1."""
    return Manifold.cylinder(y1 - y0, radius, -1.0, segments).rotate([-90, 0, 0]).translate([x, y0, z])


def cyl_z(radius, z0, z1, x=0.0, y=0.0, segments=SEG_MID, radius_end=-1.0) -> Manifold:
    """Cylinder (or cone) along z from z0 to z1."""
    return Manifold.cylinder(z1 - z0, radius, radius_end, segments).translate([x, y, z0])


def extrude_xz(profile: CrossSection, y0: float, y1: float) -> Manifold:
    """Extrude a profile drawn in the x-z plane (as X, Y) along y from y0 to y1."""
    return Manifold.extrude(profile, y1 - y0).rotate([90, 0, 0]).translate([0, y1, 0])


def stadium(points_radii: list[tuple[float, float, float]], segments=SEG_BIG) -> CrossSection:
    """Convex hull of circles (x, z, r) in the x-z plane."""
    return CrossSection.batch_hull([CrossSection.circle(r, segments).translate([x, z])
                                    for x, z, r in points_radii])


def toothed_disc(root: float, tip: float, teeth: int, samples_per_tooth: int = 32) -> CrossSection:
    """Sprocket outline centred at the origin (x-z plane): `teeth` rounded teeth."""
    n = teeth * samples_per_tooth
    angles = np.arange(n) * (2.0 * math.pi / n)
    wave = np.clip(1.6 * np.cos(teeth * angles), -1.0, 1.0)
    radii = root + (tip - root) * 0.5 * (1.0 + wave)
    return CrossSection([np.column_stack([radii * np.cos(angles), radii * np.sin(angles)])])


# ----------------------------------------------------------------------------- track belts

@dataclass(frozen=True)
class Belt:
    """A belt around two pulleys on the x axis: centre path radii ra at x0 and rb at x0 + d (m).

    The same parametrisation as the wheel loop of urdf/track_wheels.xacro: arc length from the
    bottom tangent point of pulley a, running forward along the bottom.
    """

    x0: float
    d: float
    ra: float
    rb: float

    @property
    def beta(self) -> float:
        return math.asin((self.ra - self.rb) / self.d)

    @property
    def perimeter(self) -> float:
        b = self.beta
        return 2 * self.d * math.cos(b) + self.rb * (math.pi - 2 * b) + self.ra * (math.pi + 2 * b)

    def at(self, s: float) -> tuple[float, float, float]:
        """Point (x, z) and outward normal angle (rad from +x toward +z) at arc length s."""
        b, t = self.beta, self.d * math.cos(self.beta)
        arc_b = self.rb * (math.pi - 2 * b)
        if s < t:
            return (self.x0 + self.ra * math.sin(b) + s * math.cos(b),
                    -self.ra * math.cos(b) + s * math.sin(b), b - math.pi / 2)
        if s < t + arc_b:
            phi = b - math.pi / 2 + (s - t) / self.rb
            return self.x0 + self.d + self.rb * math.cos(phi), self.rb * math.sin(phi), phi
        if s < 2 * t + arc_b:
            u = s - t - arc_b
            return (self.x0 + self.d + self.rb * math.sin(b) - u * math.cos(b),
                    self.rb * math.cos(b) + u * math.sin(b), math.pi / 2 - b)
        phi = math.pi / 2 - b + (s - 2 * t - arc_b) / self.ra
        return self.x0 + self.ra * math.cos(phi), self.ra * math.sin(phi), phi


def belt_solid(belt: Belt, thickness: float, half_width: float, cleat_pitch: float) -> Manifold:
    """A rubber belt (ring) with rounded cleats, outer surface on the path offset by thickness."""
    outer = stadium([(belt.x0, 0.0, belt.ra), (belt.x0 + belt.d, 0.0, belt.rb)])
    inner = stadium([(belt.x0, 0.0, belt.ra - thickness), (belt.x0 + belt.d, 0.0, belt.rb - thickness)])
    ring = extrude_xz(outer - inner, -half_width, half_width)
    cleat_profile = stadium([(-0.003, 0.0, 0.0025), (0.003, 0.0, 0.0025)], SEG_SMALL)
    cleat = extrude_xz(cleat_profile, -half_width + 0.002, half_width - 0.002)
    count = int(belt.perimeter // cleat_pitch)
    cleats = []
    for k in range(count):
        x, z, phi = belt.at((k + 0.5) * belt.perimeter / count)
        # local +z (radial) onto the outward normal, local +x along the belt
        rotation = rot_y(math.pi / 2 - phi)
        cleats.append(place(cleat, rotation, (x, 0.0, z)))
    return union([ring] + cleats)


def sprocket(x: float, root: float, tip: float, teeth: int, half_width: float, hub: float,
             holes: int) -> Manifold:
    """A toothed pulley on the y axis at (x, 0) with lightening holes and hub bolts."""
    disc = extrude_xz(toothed_disc(root, tip, teeth).translate([x, 0.0]), -half_width, half_width)
    cuts = [cyl_y(0.18 * root, -1, 1, x + 0.58 * root * math.cos(2 * math.pi * k / holes),
                  0.58 * root * math.sin(2 * math.pi * k / holes), SEG_MID) for k in range(holes)]
    disc = disc - union(cuts)
    parts = [disc, cyl_y(hub, -half_width - 0.004, half_width + 0.004, x, 0.0, SEG_BIG)]
    for k in range(6):
        a = 2 * math.pi * k / 6
        bx, bz = x + 0.65 * hub * math.cos(a), 0.65 * hub * math.sin(a)
        parts.append(cyl_y(0.0028, -half_width - 0.0065, half_width + 0.0065, bx, bz, SEG_SMALL))
    return union(parts)
