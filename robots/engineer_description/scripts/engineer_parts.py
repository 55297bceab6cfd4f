"""The Engineer's parts, one builder per visual mesh, each in its own link frame (metres).

Every builder takes the numeric properties of urdf/properties.xacro (`g`) and returns one
closed manifold3d solid.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np
from manifold3d import CrossSection, Manifold

from engineer_cad import (SEG_BIG, SEG_MID, SEG_SMALL, Belt, belt_solid, box, cyl_x, cyl_y, cyl_z,
                 extrude_xz, rounded_box, sprocket, stadium, union)

def chassis(g: dict[str, float]) -> Manifold:
    """base_link: the hull with track guards, axle housings, handle and deck details."""
    L, W, zb, zt = g["hull_half_length"], g["hull_half_width"], g["hull_bottom"], g["hull_top"]
    r = 0.012
    ball = Manifold.sphere(r, SEG_MID)
    corners = []
    for sx in (-1, 1):
        for sy in (-1, 1):
            corners.append((sx * (L - 0.035 - r), sy * (W - r), zb + r))
            corners.append((sx * (L - r), sy * (W - r), zt - r))
    hull = Manifold.batch_hull([ball.translate(list(c)) for c in corners])
    # deck: recessed service panel, vent slots, bolts
    panel = rounded_box((-0.09, -0.06, zt - 0.003), (0.17, 0.06, zt + 0.01), 0.006)
    lid = rounded_box((-0.085, -0.055, zt - 0.006), (0.165, 0.055, zt - 0.001), 0.004)
    vents = union([cyl_y(0.003, -0.035, 0.035, -0.07 + 0.012 * k, zt - 0.0008, SEG_SMALL)
                   for k in range(8)])
    hull = (hull - panel) + lid - vents
    parts = [hull]
    for k in range(10):
        x = -0.08 + 0.0275 * k
        for y in (-0.05, 0.05):
            if -0.02 < x < 0.02 and y < 0:
                continue  # leave room for the sealed connector
            parts.append(cyl_z(0.0035, zt - 0.001, zt + 0.0015, x, y, SEG_SMALL))
    # turntable race for the waist
    parts.append(cyl_z(0.062, zt - 0.001, zt + 0.003, g["waist_x"], 0.0, SEG_BIG))
    gl, gw, gt, th = g["guard_half_length"], g["guard_width"], g["guard_top"], g["guard_thickness"]
    for s in (-1, 1):
        yc = s * g["track_offset_y"]
        y0, y1 = sorted((yc - s * gw / 2, yc + s * gw / 2))
        # fender profile in x-z: flat top with ends bent down
        pts = [(-gl - 0.02, gt - 0.035), (-gl, gt), (gl, gt), (gl + 0.02, gt - 0.035),
               (gl + 0.02 - th, gt - 0.035), (gl - th * 0.4, gt - th), (-gl + th * 0.4, gt - th),
               (-gl - 0.02 + th, gt - 0.035)]
        fender = extrude_xz(CrossSection([np.array(pts[::-1])]), y0, y1)  # counter-clockwise
        parts.append(fender)
        # side rail joining hull and fender, outer lip with bolts
        ri0, ri1 = sorted((s * (W - 0.01), s * (W + 0.006)))
        parts.append(rounded_box((-L + 0.01, ri0, zt - 0.015), (L - 0.01, ri1, gt - th / 2), 0.003, SEG_SMALL))
        lo0, lo1 = sorted((s * (g["track_offset_y"] + gw / 2 - 0.004), s * (g["track_offset_y"] + gw / 2)))
        parts.append(rounded_box((-gl, lo0, gt - 0.022), (gl, lo1, gt), 0.0015, SEG_SMALL))
        for k in range(12):
            x = -gl + 0.02 + k * (2 * gl - 0.04) / 11
            yb = s * (g["track_offset_y"] + gw / 2)
            parts.append(cyl_y(0.003, min(yb, yb + s * 0.002), max(yb, yb + s * 0.002), x, gt - 0.011, SEG_SMALL))
        # axle housings between hull side and track
        for x in (-g["track_half_span"], g["track_half_span"]):
            ya, yb2 = sorted((s * (W - 0.005), s * (g["track_offset_y"] - g["track_width"] / 2 - 0.002)))
            parts.append(cyl_y(0.022, ya, yb2, x, 0.0, SEG_BIG))
            ya, yb2 = sorted((s * (W - 0.005), s * (W + 0.004)))
            parts.append(cyl_y(0.028, ya, yb2, x, 0.0, SEG_BIG))
    # rear handle: two posts and a bar
    hx = -L - 0.03
    for y in (-0.05, 0.05):
        parts.append(cyl_x(0.006, hx, -L + 0.015, y, 0.035, SEG_MID))
        parts.append(Manifold.sphere(0.006, SEG_MID).translate([hx, y, 0.035]))
    parts.append(cyl_y(0.006, -0.05, 0.05, hx, 0.035, SEG_MID))
    # front: two driving lights
    for y in (-0.05, 0.05):
        parts.append(cyl_x(0.011, L - 0.02, L + 0.004, y, 0.03, SEG_MID))
        parts.append(Manifold.sphere(0.009, SEG_MID).scale([0.4, 1, 1]).translate([L + 0.004, y, 0.03]))
    return union(parts)


def main_track(g: dict[str, float]) -> Manifold:
    """A main track (left and right share it; symmetric about its mid-plane)."""
    R, hs, hw = g["track_radius"], g["track_half_span"], g["track_width"] / 2
    t = g["track_belt_thickness"]
    outer_r = R - 0.004  # cleats stand 4 mm proud, up to R
    belt = belt_solid(Belt(-hs, 2 * hs, outer_r, outer_r), t, hw, 0.012)
    inner = outer_r - t
    parts = [belt]
    for x in (-hs, hs):
        parts.append(sprocket(x, inner - 0.007, inner + 0.0005, 18, 0.016, 0.02, 6))
    road = 0.015
    for x in (-0.105, -0.035, 0.035, 0.105):
        z = -inner + road
        rim = cyl_y(road, -0.017, 0.017, x, z, SEG_MID) - cyl_y(road + 0.001, -0.004, 0.004, x, z, SEG_MID)
        spokes = union([cyl_y(0.0028, -0.02, 0.02, x + 0.0095 * math.cos(a), z + 0.0095 * math.sin(a), SEG_SMALL)
                        for a in np.arange(6) * (math.pi / 3)])
        parts.append(rim + cyl_y(road - 0.004, -0.004, 0.004, x, z, SEG_MID) - spokes)
        parts.append(cyl_y(0.005, -0.021, 0.021, x, z, SEG_SMALL))
    frame = extrude_xz(stadium([(-hs, 0.0, 0.018), (hs, 0.0, 0.018)]), -0.004, 0.004)
    frame = frame - union([cyl_y(0.008, -1, 1, x, 0.0, SEG_MID) for x in (-0.1, -0.05, 0.0, 0.05, 0.1)])
    parts.append(frame)
    for x in (-0.105, -0.035, 0.035, 0.105):
        parts.append(extrude_xz(stadium([(x, 0.0, 0.006), (x, -inner + road, 0.006)], SEG_SMALL), -0.003, 0.003))
    return union(parts)


def flipper(g: dict[str, float]) -> Manifold:
    """A flipper (sub-crawler), frame on the root pulley axis, pointing forward (+x)."""
    R, rt, span, hw = g["track_radius"], g["flipper_tip_radius"], g["flipper_span"], g["flipper_width"] / 2
    t = 0.008
    belt = belt_solid(Belt(0.0, span, R - 0.004, rt - 0.004), t, hw, 0.012)
    parts = [belt]
    parts.append(sprocket(0.0, R - 0.004 - t - 0.007, R - 0.004 - t + 0.0005, 18, 0.013, 0.022, 6))
    parts.append(sprocket(span, rt - 0.004 - t - 0.005, rt - 0.004 - t + 0.0005, 10, 0.013, 0.01, 4))
    plate = extrude_xz(stadium([(0.0, 0.0, 0.034), (span, 0.0, 0.016)]), -0.004, 0.004)
    holes = union([cyl_y(rad, -1, 1, x, 0.0, SEG_MID) for x, rad in ((0.09, 0.014), (0.16, 0.011), (0.225, 0.008))])
    parts.append(plate - holes)
    for x in np.linspace(0.07, span - 0.04, 5):
        rad = 0.0095 - 0.014 * float(x) / span * 0.3
        z = -(R - 0.004 - t) + (R - rt) * float(x) / span + rad
        parts.append(cyl_y(rad, -0.014, 0.014, float(x), z, SEG_MID))
    parts.append(cyl_y(0.024, -hw - 0.002, hw + 0.002, 0.0, 0.0, SEG_BIG))
    return union(parts)


def cronstain(g: dict[str, float]) -> Manifold:
    """waist_link, the "cronstain" (bracket): turntable and two cheeks carrying the shoulder."""
    h = g["shoulder_height"]
    parts = [cyl_z(0.055, 0.0, 0.012, segments=SEG_BIG), cyl_z(0.055, 0.012, 0.016, segments=SEG_BIG, radius_end=0.05)]
    for k in range(12):
        a = 2 * math.pi * k / 12
        parts.append(cyl_z(0.0035, 0.015, 0.019, 0.045 * math.cos(a), 0.045 * math.sin(a), SEG_SMALL))
    cheek = stadium([(-0.03, 0.016, 0.004), (0.03, 0.016, 0.004), (0.0, h, 0.028)])
    cheek = cheek - CrossSection.circle(0.009, SEG_MID).translate([0.0, 0.028])
    for s in (-1, 1):
        y0, y1 = sorted((s * 0.035, s * 0.045))
        parts.append(extrude_xz(cheek, y0, y1))
        y0, y1 = sorted((s * 0.045, s * 0.053))
        parts.append(cyl_y(0.019, y0, y1, 0.0, h, SEG_BIG))
        y0, y1 = sorted((s * 0.053, s * 0.056))
        parts.append(cyl_y(0.012, y0, y1, 0.0, h, SEG_MID))
    parts.append(cyl_y(0.018, -0.035, 0.035, -0.038, 0.034, SEG_BIG))  # motor between the cheeks
    parts.append(box((-0.05, -0.035, 0.012), (-0.026, 0.035, 0.024)))
    return union(parts)


def _arm_beam(length: float, r0: float, r1: float, half_width: float) -> Manifold:
    """A tapered stadium beam along +x with pockets on both sides."""
    beam = extrude_xz(stadium([(0.0, 0.0, r0), (length, 0.0, r1)]), -half_width, half_width)
    pocket = stadium([(0.045, 0.0, r0 * 0.5), (length - 0.045, 0.0, r1 * 0.5)])
    for s in (-1, 1):
        y0, y1 = sorted((s * (half_width - 0.005), s * (half_width + 0.01)))
        beam = beam - extrude_xz(pocket, y0, y1)
    return beam


def shoulder(g: dict[str, float]) -> Manifold:
    """shoulder_link: the upper arm from the shoulder axis to the elbow axis (+x)."""
    L = g["shoulder_length"]
    parts = [_arm_beam(L, 0.024, 0.02, 0.022), cyl_y(0.02, -0.035, 0.035, 0.0, 0.0, SEG_BIG)]
    parts.append(cyl_y(0.026, -0.03, 0.03, L, 0.0, SEG_BIG))
    for s in (-1, 1):
        y0, y1 = sorted((s * 0.03, s * 0.0315))
        parts.append(cyl_y(0.02, y0, y1, L, 0.0, SEG_BIG))
        for k in range(8):
            a = 2 * math.pi * k / 8
            parts.append(cyl_y(0.0022, y0 - 0.001, y1 + 0.001, L + 0.016 * math.cos(a), 0.016 * math.sin(a), SEG_SMALL))
    parts.append(cyl_x(0.005, 0.03, L - 0.035, 0.0, 0.024, SEG_MID))  # cable duct
    for x in np.linspace(0.045, L - 0.05, 4):
        parts.append(rounded_box((float(x) - 0.004, -0.008, 0.016), (float(x) + 0.004, 0.008, 0.031), 0.002, SEG_SMALL))
    return union(parts)


def forearm(g: dict[str, float]) -> Manifold:
    """forearm_link: fork round the elbow, beam to the head axis (+x)."""
    L = g["forearm_length"]
    parts = [_arm_beam(L - 0.05, 0.018, 0.016, 0.018).translate([0.05, 0.0, 0.0])]
    fork = stadium([(0.0, 0.0, 0.024), (0.065, 0.0, 0.017)])
    for s in (-1, 1):
        y0, y1 = sorted((s * 0.032, s * 0.04))
        parts.append(extrude_xz(fork, y0, y1))
        y0, y1 = sorted((s * 0.04, s * 0.044))
        parts.append(cyl_y(0.016, y0, y1, 0.0, 0.0, SEG_BIG))
    parts.append(rounded_box((0.045, -0.04, -0.015), (0.075, 0.04, 0.015), 0.004, SEG_MID))
    parts.append(cyl_y(0.02, -0.024, 0.024, L, 0.0, SEG_BIG))
    for s in (-1, 1):
        y0, y1 = sorted((s * 0.024, s * 0.026))
        parts.append(cyl_y(0.014, y0, y1, L, 0.0, SEG_MID))
    parts.append(cyl_x(0.004, 0.08, L - 0.03, 0.0, 0.018, SEG_MID))
    return union(parts)


def head(g: dict[str, float]) -> Manifold:
    """head_link: body with camera bumps, lantern, LRF, fins, neck fork and gripper mount."""
    x0, x1, hw, z0, z1 = g["head_x_min"], g["head_x_max"], g["head_half_width"], g["head_z_min"], g["head_z_max"]
    body = rounded_box((x0, -hw, z0), (x1, hw, z1), 0.012, SEG_BIG)
    # visor ridge over the front cameras
    body = body + rounded_box((x1 - 0.03, -hw + 0.004, z1 - 0.006), (x1 + 0.008, hw - 0.004, z1), 0.003, SEG_MID)
    parts = [body]
    bump = g["camera_bump"]

    def camera(y: float, z: float, front: bool) -> Manifold:
        sign = 1.0 if front else -1.0
        xa, xb = (x1 - 0.004, x1 + bump) if front else (x0 - bump, x0 + 0.004)
        housing = cyl_x(0.011, xa, xb, y, z, SEG_MID)
        face = xb if front else xa
        recess = cyl_x(0.0075, min(face - sign * 0.004, face + sign * 0.01), max(face - sign * 0.004, face + sign * 0.01), y, z, SEG_MID)
        lens = Manifold.sphere(0.0065, SEG_MID).scale([0.6, 1, 1]).translate([face - sign * 0.004, y, z])
        return housing - recess + lens

    for y, z in ((g["camera_side_y"], g["camera_side_z"]), (0.0, g["camera_centre_z"]),
                 (-g["camera_side_y"], g["camera_side_z"])):
        parts.append(camera(y, z, True))
    parts.append(camera(g["camera_rear_y"], g["camera_rear_z"], False))
    # lantern: bezel, reflector, emitter
    zl = g["lantern_z"]
    bezel = cyl_x(0.016, x1 - 0.004, x1 + 0.008, 0.0, zl, SEG_BIG)
    reflector = cyl_x(0.007, x1 + 0.0005, x1 + 0.0081, 0.0, zl, SEG_BIG, radius_end=0.0135)
    parts.append(bezel - reflector + Manifold.sphere(0.004, SEG_MID).translate([x1 + 0.002, 0.0, zl]))
    # LRF on top
    xl, rl, hl = g["lrf_x"], g["lrf_radius"], g["lrf_height"]
    parts += [cyl_z(rl + 0.002, z1 - 0.002, z1 + 0.004, xl, 0.0, SEG_BIG),
              cyl_z(rl, z1 + 0.004, z1 + 0.022, xl, 0.0, SEG_BIG),
              cyl_z(rl - 0.003, z1 + 0.022, z1 + 0.032, xl, 0.0, SEG_BIG),
              cyl_z(rl, z1 + 0.032, z1 + hl, xl, 0.0, SEG_BIG, radius_end=rl - 0.004)]
    # cooling fins on both sides
    for s in (-1, 1):
        for k in range(8):
            z = z0 + 0.012 + k * (z1 - z0 - 0.024) / 7
            y0, y1 = sorted((s * (hw - 0.002), s * (hw + 0.006)))
            parts.append(rounded_box((x0 + 0.025, y0, z - 0.0012), (x1 - 0.025, y1, z + 0.0012), 0.0011, 12))
    # neck fork round the forearm hub
    fork = stadium([(0.0, 0.0, 0.02), (0.035, 0.0, 0.02), (0.035, 0.02, 0.012)])
    for s in (-1, 1):
        y0, y1 = sorted((s * 0.026, s * 0.034))
        parts.append(extrude_xz(fork, y0, y1))
    # gripper mount under the front, with pivot pins
    zm = g["gripper_mount_z"]
    parts.append(rounded_box((x1 - 0.035, -0.042, zm - 0.018), (x1 + 0.004, 0.042, z0 + 0.004), 0.005, SEG_MID))
    for y in (-g["gripper_pivot_x"], g["gripper_pivot_x"]):
        parts.append(cyl_z(0.0045, zm - 0.02, z0 + 0.002, x1, y, SEG_MID))
        parts.append(cyl_z(0.0065, zm - 0.022, zm - 0.018, x1, y, SEG_MID))
    return union(parts)


def _bar(length: float, half_x: float, half_y: float, hub: float, slot: bool) -> Manifold:
    """A gripper bar along +z, symmetric in x, with hubs (axis y) at both ends."""
    bar = extrude_xz(stadium([(0.0, 0.0, half_x), (0.0, length, half_x)], SEG_MID), -half_y, half_y)
    if slot:
        bar = bar - extrude_xz(stadium([(0.0, 0.03, 0.0025), (0.0, length - 0.03, 0.0025)], SEG_SMALL), -1, 1)
    parts = [bar]
    for z in (0.0, length):
        parts.append(cyl_y(hub, -half_y - 0.0015, half_y + 0.0015, 0.0, z, SEG_MID)
                     - cyl_y(0.002, -1, 1, 0.0, z, SEG_SMALL))
    return union(parts)


def gripper_part_one(g: dict[str, float]) -> Manifold:
    """part_one_<side>: the driven bar (p1 joint at its root, p3 joint at its tip)."""
    return _bar(g["gripper_bar_length"], 0.006, 0.003, 0.0075, True)


def gripper_part_two(g: dict[str, float]) -> Manifold:
    """part_two_<side>: the parallel bar beside part_one. In reality it closes the loop at the
    jaw; in the tree model it ends short of the jaw (the mimic joints keep the loop)."""
    return _bar(g["gripper_parallel_bar_length"], 0.0045, 0.0025, 0.006, False)


def gripper_part_three(g: dict[str, float]) -> Manifold:
    """part_three_<side>: the jaw, hinged on part_one's tip and spanning both bars; its +z
    points at the other jaw."""
    jl, dy = g["gripper_jaw_length"], 2 * g["gripper_bar_y"]
    plate = extrude_xz(stadium([(0.0, 0.0, 0.008), (0.0, jl, 0.006)], SEG_MID), -dy - 0.008, 0.008)
    grooves = union([box((sx * 0.0045 if sx > 0 else -1, -1, jl - 0.004 - 0.005 * k),
                         (1 if sx > 0 else sx * 0.0045, 1, jl - 0.0025 - 0.005 * k))
                     for k in range(4) for sx in (-1, 1)])
    inner_cut = box((-1, -0.0055, -0.012), (1, 0.0055, 0.0095))
    jaw = plate - grooves - inner_cut
    pins = union([cyl_y(0.0022, -dy - 0.009, 0.009, 0.0, 0.0, SEG_SMALL)])
    pad = rounded_box((-0.0035, -dy - 0.006, jl - 0.001), (0.0035, 0.006, jl + 0.006), 0.0025, SEG_SMALL)
    return union([jaw, pins, pad])


PARTS: dict[str, Callable[[dict[str, float]], Manifold]] = {
    "chassis": chassis,
    "main_track": main_track,
    "flipper": flipper,
    "cronstain": cronstain,
    "shoulder": shoulder,
    "forearm": forearm,
    "head": head,
    "gripper_part_one": gripper_part_one,
    "gripper_part_two": gripper_part_two,
    "gripper_part_three": gripper_part_three,
}
