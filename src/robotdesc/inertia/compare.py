"""Compare a declared inertia with the one derived from the link's geometry, and name the
likely cause of a mismatch when the numbers say so.

Units: kg, m, kg*m^2. Both tensors are about the centre of mass, in link-frame axes.
Plain Python (`robotdesc.spatial`): it runs on every lint with mesh rules.
"""

from __future__ import annotations

import functools
import itertools
import math
from dataclasses import dataclass

from robotdesc.mesh.properties import MassProperties
from robotdesc.model.elements import Inertial
from robotdesc.spatial import Mat3, Vec3, difference, frobenius, principal_moments, rotated

#: Powers of ten that a unit slip of the tensor produces, and the slip that gives each.
UNIT_SLIPS = {
    9: "the tensor looks like g*mm^2 (1e9 times kg*m^2)",
    7: "the tensor looks like g*cm^2 (1e7 times kg*m^2)",
    6: "the tensor looks like kg*mm^2 (1e6 times kg*m^2)",
    4: "the tensor looks like kg*cm^2 (1e4 times kg*m^2)",
    3: "the tensor looks like g*m^2, or it was computed with the mass in grams (1e3 times)",
    -3: "the tensor is 1e3 times too small: was the mass divided by 1000 twice?",
    -6: "the geometry is about 1000 times too large: a mesh in millimetres (at a fixed mass, "
        "moments grow with the square of the length)",
    -4: "the geometry is about 100 times too large: a mesh in centimetres",
}
#: How close log10 of the ratio must be to the power of ten.
SLIP_SLACK = 0.15


@dataclass(frozen=True)
class InertiaComparison:
    """A declared inertia against the geometry's.

    Attributes:
        declared: declared tensor about the COM, link-frame axes (kg*m^2).
        derived: geometry tensor at the declared mass, about its COM, link axes (kg*m^2).
        declared_moments: principal moments of `declared`, ascending (kg*m^2).
        derived_moments: principal moments of `derived`, ascending (kg*m^2).
        moment_errors: per principal moment, |declared - derived| / derived.
        tensor_error: ||declared - derived|| / ||derived|| (Frobenius norms).
        cause: the likely cause of the mismatch, when the numbers point to one.
    """

    declared: Mat3
    derived: Mat3
    declared_moments: Vec3
    derived_moments: Vec3
    moment_errors: Vec3
    tensor_error: float
    cause: str | None = None

    def mismatch(self, tolerance: float) -> bool:
        """Whether the tensors differ beyond `tolerance` (relative)."""
        return max(self.moment_errors) > tolerance or self.tensor_error > tolerance


def declared_tensor(inertial: Inertial) -> Mat3:
    """The declared tensor rotated from the `<inertial><origin rpy>` frame into link axes.

    Raises:
        ValueError: the `<inertial>` has no `<inertia>` (callers check that it has).
    """
    inertia = inertial.inertia
    if inertia is None:
        raise ValueError("the <inertial> declares no <inertia>")
    # + 0.0: -0.0 and 0.0 are one key; the tensor is computed from the key's zeros
    roll, pitch, yaw = inertial.origin.rpy
    return _rotated((inertia.ixx + 0.0, inertia.ixy + 0.0, inertia.ixz + 0.0,
                     inertia.iyy + 0.0, inertia.iyz + 0.0, inertia.izz + 0.0),
                    (roll + 0.0, pitch + 0.0, yaw + 0.0))


@functools.lru_cache(maxsize=4096)
def _rotated(moments: tuple[float, float, float, float, float, float],
             rpy: tuple[float, float, float]) -> Mat3:
    """`declared_tensor` on values (ixx, ixy, ixz, iyy, iyz, izz in kg*m^2; rpy in rad):
    links made by one macro declare the same numbers."""
    ixx, ixy, ixz, iyy, iyz, izz = moments
    return rotated(((ixx, ixy, ixz), (ixy, iyy, iyz), (ixz, iyz, izz)), rpy)


def compare_inertia(inertial: Inertial, geometry: MassProperties,
                    tolerance: float) -> InertiaComparison:
    """Compare a declared inertial (with positive mass) with the geometry at that mass.

    Args:
        inertial: the declared `<inertial>` (mass and inertia present).
        geometry: the link's geometry at density 1 (link frame).
        tolerance: the relative tolerance the cause analysis uses.

    Raises:
        ValueError: the `<inertial>` declares no mass or no `<inertia>`.
    """
    if inertial.mass is None:
        raise ValueError("the <inertial> declares no mass")
    return _compared(inertial.mass, declared_tensor(inertial), geometry, tolerance)


@functools.lru_cache(maxsize=4096)
def _compared(mass: float, declared: Mat3, geometry: MassProperties,
              tolerance: float) -> InertiaComparison:
    """`compare_inertia` on values: links made by one macro (the Engineer's 212 track
    wheels) compare the same numbers, and are compared once."""
    derived = geometry.scaled_to_mass(mass).inertia
    dm = principal_moments(declared)
    gm = principal_moments(derived)
    errors = (_relative(dm[0], gm[0]), _relative(dm[1], gm[1]), _relative(dm[2], gm[2]))
    norm = frobenius(derived)
    tensor_error = frobenius(difference(declared, derived)) / norm if norm > 0 else math.inf
    result = InertiaComparison(declared, derived, dm, gm, errors, tensor_error)
    if not result.mismatch(tolerance):
        return result
    return InertiaComparison(declared, derived, dm, gm, errors, tensor_error,
                             likely_cause(declared, derived, dm, gm, tolerance))


def _relative(declared: float, derived: float) -> float:
    """|declared - derived| / derived; infinite when `derived` is not positive."""
    return abs(declared - derived) / derived if derived > 0 else math.inf


def likely_cause(declared: Mat3, derived: Mat3, declared_moments: Vec3, derived_moments: Vec3,
                 tolerance: float) -> str | None:
    """Name the slip that turns `derived` into `declared`, if one does (see UNIT_SLIPS)."""
    if not any(v for row in declared for v in row):
        return "the declared tensor is zero (a point mass)"
    slip = unit_slip(declared_moments, derived_moments)
    if slip is not None:
        return UNIT_SLIPS[slip]
    flipped = sign_flip(declared, derived, tolerance * frobenius(derived))
    if flipped:
        return (f"the sign of {', '.join(flipped)} is swapped: URDF's products are "
                "-integral(x*y dm), while CAD tools (SolidWorks, Onshape, Fusion) list "
                "+integral(x*y dm)")
    moment_errors = [abs(d - g) / g for d, g in zip(declared_moments, derived_moments) if g > 0]
    if moment_errors and max(moment_errors) <= tolerance:
        return ("the principal moments agree but the axes do not: the tensor is given in a "
                "rotated frame (check <inertial><origin rpy>, or the CAD output frame)")
    return None


def unit_slip(declared_moments: Vec3, derived_moments: Vec3) -> int | None:
    """The power of ten k with declared ~ 10^k * derived for all three moments, if it is a
    known slip."""
    if min(derived_moments) <= 0 or min(declared_moments) <= 0:
        return None
    logs = [math.log10(d / g) for d, g in zip(declared_moments, derived_moments)]
    power = round(sum(logs) / 3)
    if power in UNIT_SLIPS and all(abs(v - power) <= SLIP_SLACK for v in logs):
        return power
    return None


def sign_flip(declared: Mat3, derived: Mat3, slack: float) -> tuple[str, ...]:
    """The products of inertia whose sign, flipped, makes `declared` match `derived`."""
    names = {(0, 1): "ixy", (0, 2): "ixz", (1, 2): "iyz"}
    best: tuple[float, tuple[str, ...]] = (frobenius(difference(declared, derived)), ())
    for count in (1, 2, 3):
        for chosen in itertools.combinations(names, count):
            candidate = [list(row) for row in declared]
            for i, j in chosen:
                candidate[i][j] = candidate[j][i] = -candidate[i][j]
            error = frobenius(difference(candidate, derived))
            if error < best[0]:
                best = (error, tuple(names[c] for c in chosen))
    if best[1] and best[0] <= slack:
        indices = {name: index for index, name in names.items()}
        return tuple(n for n in best[1] if abs(declared[indices[n][0]][indices[n][1]]) > 0)
    return ()


def mirror_partner(name: str, names: set[str]) -> str | None:
    """The name of the left/right mirror of a link, when the robot has one."""
    pairs = (("left", "right"), ("Left", "Right"), ("LEFT", "RIGHT"), ("l_", "r_"),
             ("_l_", "_r_"), ("_l", "_r"), ("L_", "R_"), ("_L", "_R"), ("lf", "rf"),
             ("lh", "rh"), ("Left", "Right"))
    for a, b in pairs:
        for this, that in ((a, b), (b, a)):
            if this in name:
                candidate = name.replace(this, that, 1)
                if candidate != name and candidate in names:
                    return candidate
    return None
