"""Spatial math of the core: 3-vectors, rotations, poses and symmetric 3x3 inertia tensors.

The one implementation of this small per-link math: the structural inertia rules, the
mesh-derived link properties, the comparisons, forward kinematics, the viewer, the simulators
and the collision tools all use it. The per-link functions are plain Python (they run on every
lint, which must not import numpy); `rpy_matrix` and `pose_matrix` give numpy arrays for array
code and import numpy when called. Units: lengths in m, angles in rad, inertia in kg*m^2.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Protocol

if TYPE_CHECKING:
    import numpy as np

Vec3 = tuple[float, float, float]
Mat3 = tuple[Vec3, Vec3, Vec3]
#: A unit quaternion (w, x, y, z), MuJoCo's order.
Quat = tuple[float, float, float, float]


class Origin(Protocol):
    """What `pose_matrix` reads of an `<origin>` (`robotdesc.model.elements.Pose`, which is
    not imported: the model imports this module, through its tree)."""

    @property
    def xyz(self) -> Sequence[float]: ...

    @property
    def rpy(self) -> Sequence[float]: ...

#: The zero tensor.
ZERO: Mat3 = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
#: The densest element (osmium, kg/m^3): no solid is denser.
MAX_MATERIAL_DENSITY = 22_600.0


def principal_moments(matrix: Sequence[Sequence[float]]) -> Vec3:
    """Eigenvalues of a symmetric 3x3 matrix, ascending (closed form, trigonometric method).

    Accurate to rounding for distinct eigenvalues; a repeated pair (an axisymmetric body)
    comes out split by about 1e-8 of its size, as acos is ill-conditioned there: far below
    any tolerance the checks use, and the pair's sum stays exact.

    Args:
        matrix: rows ((Ixx, Ixy, Ixz), (Ixy, Iyy, Iyz), (Ixz, Iyz, Izz)) in kg*m^2.
    """
    (a, d, e), (_, b, f), (_, _, c) = matrix
    off = d * d + e * e + f * f
    if off == 0.0:
        x, y, z = sorted((float(a), float(b), float(c)))
        return (x, y, z)
    q = (a + b + c) / 3.0
    p2 = (a - q) ** 2 + (b - q) ** 2 + (c - q) ** 2 + 2.0 * off
    p = math.sqrt(p2 / 6.0)
    if p == 0.0:
        return (q, q, q)
    # B = (A - q I) / p; r = det(B) / 2, clamped to [-1, 1] against rounding
    ba, bb, bc, bd, be, bf = (a - q) / p, (b - q) / p, (c - q) / p, d / p, e / p, f / p
    det = (ba * (bb * bc - bf * bf) - bd * (bd * bc - bf * be) + be * (bd * bf - bb * be))
    r = max(-1.0, min(1.0, det / 2.0))
    phi = math.acos(r) / 3.0
    largest = q + 2.0 * p * math.cos(phi)
    smallest = q + 2.0 * p * math.cos(phi + 2.0 * math.pi / 3.0)
    middle = 3.0 * q - largest - smallest
    x, y, z = sorted((smallest, middle, largest))
    return (x, y, z)


def triangle_violation(moments: Sequence[float]) -> float:
    """How much the largest principal moment exceeds the sum of the other two (kg*m^2);
    zero or negative when the triangle inequality holds."""
    small, middle, large = sorted(moments)
    return large - (small + middle)


def minimum_trace(mass: float, max_density: float = MAX_MATERIAL_DENSITY) -> float:
    """The smallest trace (Ixx + Iyy + Izz, kg*m^2) any solid of `mass` (kg) can have when no
    part of it is denser than `max_density` (kg/m^3).

    The trace is 2 * integral(r^2 dm) about the centre of mass; at a bounded density it is
    smallest for a ball of uniform maximal density: 6/5 * m * R^2, R = (3m / (4 pi rho))^(1/3).
    """
    if mass <= 0 or max_density <= 0:
        return 0.0
    radius = math.pow(3.0 * mass / (4.0 * math.pi * max_density), 1.0 / 3.0)
    return 1.2 * mass * radius * radius


def rotated(matrix: Sequence[Sequence[float]], rpy: Sequence[float]) -> Mat3:
    """R M R^T with R from URDF roll-pitch-yaw (rad): R = Rz(yaw) Ry(pitch) Rx(roll)."""
    return conjugated(matrix, rpy_rotation(rpy))


def conjugated(matrix: Sequence[Sequence[float]], rotation: Sequence[Sequence[float]]) -> Mat3:
    """R M R^T: a tensor given in a rotated frame, expressed in the parent frame."""
    (m00, m01, m02), (m10, m11, m12), (m20, m21, m22) = matrix
    rm = [(r0 * m00 + r1 * m10 + r2 * m20, r0 * m01 + r1 * m11 + r2 * m21,
           r0 * m02 + r1 * m12 + r2 * m22) for r0, r1, r2 in rotation]  # rows of R M
    return _mat3([[a[0] * r[0] + a[1] * r[1] + a[2] * r[2] for r in rotation] for a in rm])


def rpy_rotation(rpy: Sequence[float]) -> Mat3:
    """URDF's rotation matrix from roll, pitch, yaw (rad): R = Rz(yaw) Ry(pitch) Rx(roll)."""
    roll, pitch, yaw = (float(v) for v in rpy)
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return _mat3([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                  [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                  [-sp, cp * sr, cp * cr]])


def rotation_rpy(rotation: Sequence[Sequence[float]]) -> Vec3:
    """URDF roll, pitch, yaw (rad) of a rotation matrix, R = Rz(yaw) Ry(pitch) Rx(roll): the
    inverse of `rpy_rotation`; in gimbal lock (pitch +-pi/2) roll is 0 and yaw takes it all."""
    r = rotation
    pitch = math.asin(max(-1.0, min(1.0, -float(r[2][0]))))
    if abs(r[2][0]) < 1 - 1e-12:
        roll = math.atan2(r[2][1], r[2][2])
        yaw = math.atan2(r[1][0], r[0][0])
    else:  # roll and yaw share one axis
        roll = 0.0
        yaw = math.atan2(-r[0][1], r[1][1])
    return (roll, pitch, yaw)


def rpy_quaternion(rpy: Sequence[float]) -> Quat:
    """URDF roll, pitch, yaw (rad) as a unit quaternion (w, x, y, z) of the same rotation."""
    r, p, y = (float(v) / 2 for v in rpy)
    cr, sr, cp, sp, cy, sy = (math.cos(r), math.sin(r), math.cos(p), math.sin(p),
                              math.cos(y), math.sin(y))
    return (cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy)


def rotation_quaternion(rotation: Sequence[Sequence[float]]) -> Quat:
    """A rotation matrix as a unit quaternion (w, x, y, z), computed as MuJoCo's
    `mju_mat2Quat` does (from the largest component, then normalized)."""
    (m0, m1, m2), (m3, m4, m5), (m6, m7, m8) = ((float(v) for v in row) for row in rotation)
    if m0 + m4 + m8 > 0:
        w = 0.5 * math.sqrt(1 + m0 + m4 + m8)
        q = (w, 0.25 * (m7 - m5) / w, 0.25 * (m2 - m6) / w, 0.25 * (m3 - m1) / w)
    elif m0 > m4 and m0 > m8:
        x = 0.5 * math.sqrt(1 + m0 - m4 - m8)
        q = (0.25 * (m7 - m5) / x, x, 0.25 * (m1 + m3) / x, 0.25 * (m2 + m6) / x)
    elif m4 > m8:
        y = 0.5 * math.sqrt(1 - m0 + m4 - m8)
        q = (0.25 * (m2 - m6) / y, 0.25 * (m1 + m3) / y, y, 0.25 * (m5 + m7) / y)
    else:
        z = 0.5 * math.sqrt(1 - m0 - m4 + m8)
        q = (0.25 * (m3 - m1) / z, 0.25 * (m2 + m6) / z, 0.25 * (m5 + m7) / z, z)
    length = math.sqrt(sum(v * v for v in q))
    return (q[0] / length, q[1] / length, q[2] / length, q[3] / length)


def rotate(rotation: Sequence[Sequence[float]], vector: Sequence[float]) -> Vec3:
    """R v."""
    x, y, z = vector
    a, b, c = (row[0] * x + row[1] * y + row[2] * z for row in rotation)
    return (a, b, c)


def compose(first: Sequence[Sequence[float]], second: Sequence[Sequence[float]]) -> Mat3:
    """The matrix product first @ second."""
    columns = list(zip(*second))
    return _mat3([[a[0] * c[0] + a[1] * c[1] + a[2] * c[2] for c in columns] for a in first])


def add(a: Sequence[float], b: Sequence[float]) -> Vec3:
    """a + b."""
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def subtract(a: Sequence[float], b: Sequence[float]) -> Vec3:
    """a - b."""
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a: Sequence[float], b: Sequence[float]) -> Vec3:
    """a x b."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def perpendicular_axes(axis: Sequence[float]) -> tuple[Vec3, Vec3]:
    """Two unit vectors u, v with (u, v, axis) a right-handed orthonormal frame; `axis` is a
    unit vector."""
    helper = (1.0, 0.0, 0.0) if abs(axis[0]) < 0.9 else (0.0, 1.0, 0.0)
    u = cross(axis, helper)
    length = norm(u)
    u = (u[0] / length, u[1] / length, u[2] / length)
    return u, cross(axis, u)


def norm(values: Sequence[float]) -> float:
    """Euclidean length of a vector."""
    return math.sqrt(sum(v * v for v in values))


def frobenius(matrix: Sequence[Sequence[float]]) -> float:
    """The Frobenius norm of a 3x3 matrix: sqrt of the sum of its squared entries."""
    return math.sqrt(sum(v * v for row in matrix for v in row))


def scaled(matrix: Sequence[Sequence[float]], factor: float) -> Mat3:
    """factor * M."""
    return _mat3([[factor * v for v in row] for row in matrix])


def difference(a: Sequence[Sequence[float]], b: Sequence[Sequence[float]]) -> Mat3:
    """A - B."""
    return _mat3([[x - y for x, y in zip(ra, rb)] for ra, rb in zip(a, b)])


def summed(matrices: Iterable[Sequence[Sequence[float]]]) -> Mat3:
    """The sum of 3x3 matrices (zero for none)."""
    rows = [[0.0] * 3 for _ in range(3)]
    for matrix in matrices:
        for i in range(3):
            for j in range(3):
                rows[i][j] += matrix[i][j]
    return _mat3(rows)


def parallel_axis(inertia: Sequence[Sequence[float]], mass: float,
                  offset: Sequence[float]) -> Mat3:
    """A body's inertia about a point `offset` (m) away from its centre of mass:
    I + m (|d|^2 E - d d^T) (the parallel-axis theorem; kg, kg*m^2)."""
    d = offset
    square = d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
    return _mat3([[inertia[i][j] + mass * ((square if i == j else 0.0) - d[i] * d[j])
                   for j in range(3)] for i in range(3)])


def _mat3(rows: Sequence[Sequence[float]]) -> Mat3:
    return tuple((float(r[0]), float(r[1]), float(r[2])) for r in rows)  # type: ignore[return-value]


def rpy_matrix(rpy: Sequence[float]) -> np.ndarray:
    """URDF's rotation from roll, pitch, yaw (rad, fixed axes x, y, z) as a (3, 3) array:
    `rpy_rotation` as numpy, for array code."""
    import numpy as np

    return np.array(rpy_rotation(rpy))


def pose_matrix(pose: Origin) -> np.ndarray:
    """The 4x4 homogeneous transform of an `<origin>` (child frame in the parent frame; xyz in
    m, rpy in rad, URDF's fixed-axis convention)."""
    import numpy as np

    matrix = np.identity(4)
    matrix[:3, :3] = rpy_matrix(pose.rpy)
    matrix[:3, 3] = pose.xyz
    return matrix


def principal_axes(tensor: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Principal moments (kg*m^2, ascending) and axes (the columns, a proper rotation) of an
    inertia tensor given as a (3, 3) array; NaN moments and the identity when it is not
    finite."""
    import numpy as np

    if not np.all(np.isfinite(tensor)):
        return np.full(3, np.nan), np.identity(3)
    moments, axes = np.linalg.eigh((tensor + tensor.T) / 2)
    if np.linalg.det(axes) < 0:
        axes[:, 2] = -axes[:, 2]
    return moments, axes
