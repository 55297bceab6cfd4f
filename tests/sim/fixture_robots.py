"""A small arm on a base, written as URDF with inertias from solid-body formulas.

`arm_urdf(slip=...)` multiplies the wrist roll link's inertia by `slip`: 1e-6 is the slip of
an inertia converted from kg*mm^2 to kg*m^2 twice. Run this module to rewrite the fixtures:
    python tests/sim/fixture_robots.py
"""

from __future__ import annotations

from pathlib import Path

FIXTURES = Path(__file__).parent / "fixtures"

# name: (shape, dimensions (m), mass (kg), z offset of the shape's centre in the link (m))
_LINKS = {
    "base_link": ("box", (0.30, 0.30, 0.10), 4.0, 0.05),
    "shoulder_link": ("cylinder", (0.05, 0.10), 1.0, 0.05),
    "upper_arm_link": ("box", (0.06, 0.06, 0.30), 1.2, 0.15),
    "forearm_link": ("box", (0.05, 0.05, 0.25), 0.8, 0.125),
    "wrist_roll_link": ("cylinder", (0.03, 0.08), 0.3, 0.04),
    "left_finger_link": ("box", (0.01, 0.02, 0.06), 0.01, 0.03),
    "right_finger_link": ("box", (0.01, 0.02, 0.06), 0.01, 0.03),
}
# name, type, parent, child, xyz, axis, lower, upper, mimic
_JOINTS = [
    ("shoulder_yaw", "revolute", "base_link", "shoulder_link", (0, 0, 0.10), (0, 0, 1), -3, 3,
     None),
    ("shoulder_pitch", "revolute", "shoulder_link", "upper_arm_link", (0, 0, 0.10), (0, 1, 0),
     -1.5, 1.5, None),
    ("elbow", "revolute", "upper_arm_link", "forearm_link", (0, 0, 0.30), (0, 1, 0), -2, 2,
     None),
    ("wrist_roll", "continuous", "forearm_link", "wrist_roll_link", (0, 0, 0.25), (0, 0, 1),
     None, None, None),
    ("left_finger", "prismatic", "wrist_roll_link", "left_finger_link", (0.01, 0, 0.08),
     (1, 0, 0), 0.0, 0.03, None),
    ("right_finger", "prismatic", "wrist_roll_link", "right_finger_link", (-0.01, 0, 0.08),
     (-1, 0, 0), 0.0, 0.03, "left_finger"),
]


def solid_inertia(shape: str, dims: tuple[float, ...], mass: float) -> tuple[float, float, float]:
    """Principal moments (kg*m^2) of a solid box (x, y, z) or cylinder (radius, length) along z."""
    if shape == "box":
        x, y, z = dims
        return (mass * (y * y + z * z) / 12, mass * (x * x + z * z) / 12,
                mass * (x * x + y * y) / 12)
    radius, length = dims
    side = mass * (3 * radius * radius + length * length) / 12
    return side, side, mass * radius * radius / 2


def arm_urdf(slip: float = 1.0, slipped_link: str = "wrist_roll_link") -> str:
    """The arm's URDF; `slipped_link`'s inertia is multiplied by `slip`."""
    lines = ['<?xml version="1.0"?>', '<robot name="slip_arm">']
    for name, (shape, dims, mass, z) in _LINKS.items():
        ixx, iyy, izz = (v * (slip if name == slipped_link else 1.0)
                         for v in solid_inertia(shape, dims, mass))
        geometry = (f'<box size="{dims[0]} {dims[1]} {dims[2]}"/>' if shape == "box"
                    else f'<cylinder radius="{dims[0]}" length="{dims[1]}"/>')
        lines += [f'  <link name="{name}">',
                  '    <inertial>',
                  f'      <origin xyz="0 0 {z}"/>',
                  f'      <mass value="{mass}"/>',
                  f'      <inertia ixx="{ixx:.6g}" ixy="0" ixz="0" iyy="{iyy:.6g}" iyz="0" '
                  f'izz="{izz:.6g}"/>',
                  '    </inertial>',
                  f'    <visual><origin xyz="0 0 {z}"/><geometry>{geometry}</geometry></visual>',
                  f'    <collision><origin xyz="0 0 {z}"/><geometry>{geometry}</geometry>'
                  '</collision>',
                  '  </link>']
    for name, kind, parent, child, xyz, axis, lower, upper, mimic in _JOINTS:
        lines += [f'  <joint name="{name}" type="{kind}">',
                  f'    <parent link="{parent}"/>', f'    <child link="{child}"/>',
                  f'    <origin xyz="{xyz[0]} {xyz[1]} {xyz[2]}"/>',
                  f'    <axis xyz="{axis[0]} {axis[1]} {axis[2]}"/>']
        limit = f'lower="{lower}" upper="{upper}" ' if lower is not None else ""
        lines.append(f'    <limit {limit}effort="20" velocity="2"/>')
        if kind == "revolute":  # the wrist and the fingers run free (no gearbox drag)
            lines.append('    <dynamics damping="0.05" friction="0.01"/>')
        if mimic:
            lines.append(f'    <mimic joint="{mimic}" multiplier="1" offset="0"/>')
        lines.append('  </joint>')
    lines.append('</robot>')
    return "\n".join(lines) + "\n"


def main() -> None:
    FIXTURES.mkdir(exist_ok=True)
    (FIXTURES / "slip_arm.urdf").write_text(arm_urdf(), encoding="utf-8")
    (FIXTURES / "slip_arm_unit_slip.urdf").write_text(arm_urdf(slip=1e-6), encoding="utf-8")


if __name__ == "__main__":
    main()
