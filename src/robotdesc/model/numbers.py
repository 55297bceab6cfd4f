"""The numbers a URDF may hold: finite, and within a magnitude no real robot exceeds.

The model is the one place numbers are validated: a value that is not finite (`inf`, `nan`,
`1e400`) or absurdly large (a 1e308 inertia, a 1e36 rad angle) becomes a `ValueIssue` at its
line (a finding of rule S110, unreadable-value) and is replaced like an unreadable value, so no rule ever
does arithmetic on it. The bounds are generous: orders of magnitude beyond any robot, small
enough that sums, products and squares of model values stay finite.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class NumberLimits:
    """Largest magnitude accepted per kind of quantity (SI units).

    Attributes:
        length: positions, sizes, radii (m).
        angle: rpy angles and angular limits (rad).
        mass: masses (kg).
        inertia: inertia tensor entries (kg m^2).
        scale: mesh scale factors.
        other: every other number (efforts, velocities, damping, reductions, ...).
        smallest_scale: smallest magnitude of a non-zero mesh scale factor.
        tiny: smallest magnitude of any non-zero number (below it, squares underflow to 0
            and a non-zero axis would have length 0).
    """

    length: float = 1e6
    angle: float = 1e6
    mass: float = 1e9
    inertia: float = 1e12
    scale: float = 1e6
    other: float = 1e30
    smallest_scale: float = 1e-9
    tiny: float = 1e-100


DEFAULT_LIMITS = NumberLimits()
DEFAULT_TINY = DEFAULT_LIMITS.tiny


def check_number(value: float, bound: float, tiny: float = DEFAULT_TINY) -> str | None:
    """What is wrong with `value` ("is not finite", "is out of range ..."), or None."""
    if not math.isfinite(value):
        return "is not a finite number"
    if abs(value) > bound:
        return f"is out of range (more than {bound:g} in magnitude)"
    if value and abs(value) < tiny:
        return f"is too close to zero to compute with (below {tiny:g} in magnitude, not 0)"
    return None


def check_vector(values: tuple[float, ...], bound: float,
                 tiny: float = DEFAULT_TINY) -> str | None:
    """What is wrong with any of `values`, or None."""
    for value in values:
        problem = check_number(value, bound, tiny)
        if problem:
            return problem
    return None
