"""Inertia against the geometry (I2xx): the declared `<inertial>` compared with the mass
properties of the link's collision (or visual) geometry at uniform density.

These rules need meshes: the lint driver hands them a `robotdesc.mesh.context.MeshContext`
as `ctx.meshes`. numpy is imported inside the checks, so registering them costs nothing.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from robotdesc.diagnostics import Finding, Severity
from robotdesc.inertia.links import has_mass, link_element
from robotdesc.model.elements import Link, Robot
from robotdesc.rules.registry import RuleContext, rule

FAMILY = "inertia"
NEEDS = ("meshes",)


def _measured(robot: Robot, ctx: RuleContext) -> Iterator[tuple[Link, object]]:
    """Links with a positive declared mass whose geometry could be measured exactly."""
    if ctx.meshes is None:
        return
    for link in robot.links:
        if not has_mass(link):
            continue
        geometry = ctx.meshes.link_geometry(link)
        if geometry.trusted:
            yield link, geometry


def _fix(link: Link, geometry) -> str:
    from robotdesc.inertia.suggest import suggest_inertial

    return suggest_inertial(link, geometry.properties).block


@dataclass(frozen=True)
class InertiaMismatchOptions:
    """Options of I201.

    Attributes:
        tolerance: relative difference allowed per principal moment, and for the whole
            tensor (a real link is not of uniform density: motors and shells shift it).
    """

    tolerance: float = 0.5


@rule("I201", "inertia-differs-from-geometry", family=FAMILY, severity=Severity.WARNING,
      options=InertiaMismatchOptions, needs=NEEDS)
def inertia_differs_from_geometry(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a declared inertia tensor that differs from the one of the link's geometry
    (collision by default, at uniform density and the declared mass) by more than the
    tolerance, per principal moment or as a whole.

    The message names the likely cause when the numbers show one: a unit slip (a factor
    of 1e3, 1e6 or 1e9: grams, millimetres), a rotated tensor (same principal moments,
    other axes), products of inertia with the CAD sign convention, or a left/right mirror
    link that agrees with its own geometry. The fix is the `<inertial>` computed from the
    geometry, at the declared mass.

    Why is this bad?
    The tensor decides how the link responds to torque. Values typed by hand, converted
    from CAD units, or copied from another link make simulation and model-based control
    wrong, often without any visible error.

    Example
    ```xml
    <link name="forearm">
      <inertial>
        <mass value="1.5"/>
        <!-- from CAD, in g*mm^2 -->
        <inertia ixx="8400" ixy="0" ixz="0" iyy="8400" iyz="0" izz="1200"/>
      </inertial>
      <collision><geometry><mesh filename="package://arm/meshes/forearm.stl"/></geometry></collision>
    </link>
    ```

    Use instead (`robotdesc inertia --suggest` prints it):
    ```xml
    <link name="forearm">
      <inertial>
        <origin xyz="0 0 0.12" rpy="0 0 0"/>
        <mass value="1.5"/>
        <inertia ixx="8.4e-06" ixy="0" ixz="0" iyy="8.4e-06" iyz="0" izz="1.2e-06"/>
      </inertial>
      <collision><geometry><mesh filename="package://arm/meshes/forearm.stl"/></geometry></collision>
    </link>
    ```
    """
    from robotdesc.inertia.compare import compare_inertia, mirror_partner

    tolerance = ctx.options.tolerance if ctx.options else InertiaMismatchOptions.tolerance
    measured = {link.name: (link, geometry) for link, geometry in _measured(robot, ctx)}
    results = {}
    for name, (link, geometry) in measured.items():
        if link.inertial.inertia is None:
            continue
        results[name] = compare_inertia(link.inertial, geometry.properties, tolerance)
    for name, comparison in results.items():
        if not comparison.mismatch(tolerance):
            continue
        link, geometry = measured[name]
        cause = comparison.cause
        partner = mirror_partner(name, set(results))
        if partner and not results[partner].mismatch(tolerance):
            mirror = f"its mirror link '{partner}' agrees with its geometry"
            cause = f"{cause}; {mirror}" if cause else f"left/right links disagree: {mirror}"
        worst = max(comparison.moment_errors)
        yield Finding(
            f"link '{name}': declared principal moments {_fmt(comparison.declared_moments)} "
            f"kg*m^2 differ from its {geometry.source} geometry's "
            f"{_fmt(comparison.derived_moments)} at {link.inertial.mass:g} kg by up to "
            f"{_percent(worst)} (tensor {_percent(comparison.tensor_error)}, tolerance "
            f"{_percent(tolerance)})" + (f"; likely cause: {cause}" if cause else ""),
            link.inertial.inertia.where or link.inertial.where, link_element(link),
            _fix(link, geometry))


@dataclass(frozen=True)
class CenterOfMassOptions:
    """Options of I202.

    Attributes:
        margin: slack around the geometry's bounding box, as a fraction of its size
            along each axis.
    """

    margin: float = 0.1


@rule("I202", "center-of-mass-outside-geometry", family=FAMILY, severity=Severity.WARNING,
      options=CenterOfMassOptions, needs=NEEDS)
def center_of_mass_outside_geometry(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a declared centre of mass (`<inertial><origin xyz>`) outside the bounding box
    of the link's geometry.

    Why is this bad?
    A link's centre of mass lies inside the convex hull of its material, so inside its
    bounding box. One outside usually comes from a COM given in another frame (the CAD
    assembly's, or the parent joint's), or in millimetres.

    Example
    ```xml
    <link name="forearm">
      <inertial>
        <origin xyz="0 0 120"/>  <!-- millimetres -->
        <mass value="1.5"/>
        <inertia ixx="0.0084" ixy="0" ixz="0" iyy="0.0084" iyz="0" izz="0.0012"/>
      </inertial>
      <collision><geometry><mesh filename="package://arm/meshes/forearm.stl"/></geometry></collision>
    </link>
    ```

    Use instead:
    ```xml
    <link name="forearm">
      <inertial>
        <origin xyz="0 0 0.12"/>
        <mass value="1.5"/>
        <inertia ixx="0.0084" ixy="0" ixz="0" iyy="0.0084" iyz="0" izz="0.0012"/>
      </inertial>
      <collision><geometry><mesh filename="package://arm/meshes/forearm.stl"/></geometry></collision>
    </link>
    ```
    """
    margin = ctx.options.margin if ctx.options else CenterOfMassOptions.margin
    if ctx.meshes is None:
        return
    for link in robot.links:
        if not has_mass(link):
            continue
        geometry = ctx.meshes.link_geometry(link)
        if geometry.bounds is None or not geometry.complete:
            continue
        low, high = geometry.bounds
        com = link.inertial.origin.xyz
        outside = []
        for axis, value, lo, hi in zip("xyz", com, low, high):
            slack = margin * (hi - lo) + 1e-4
            if value < lo - slack or value > hi + slack:
                outside.append(f"{axis}={value:.4g} not in [{lo:.4g}, {hi:.4g}]")
        if outside:
            hint = ""
            if any(abs(v) > 1.0 for v in com) and all(abs(v) / 1000 <= max(abs(lo), abs(hi))
                                                     + 1e-3 for v, lo, hi in zip(com, low, high)):
                hint = "; the values look like millimetres"
            yield Finding(f"link '{link.name}': declared centre of mass ({_fmt(com)}) m lies "
                          f"outside its {geometry.source} geometry's bounds: "
                          f"{'; '.join(outside)}{hint}",
                          link.inertial.origin.where or link.inertial.where, link_element(link),
                          _fix(link, geometry) if geometry.trusted else None)


@dataclass(frozen=True)
class DensityOptions:
    """Options of I203.

    Attributes:
        min_density: lowest plausible mass / volume (kg/m^3); hollow shells and foam are
            light, but not lighter than this.
        max_density: highest plausible mass / volume (kg/m^3), a little above osmium.
    """

    min_density: float = 50.0
    max_density: float = 25_000.0


@rule("I203", "implausible-density", family=FAMILY, severity=Severity.WARNING,
      options=DensityOptions, needs=NEEDS)
def implausible_density(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a link whose declared mass divided by its geometry's volume is not the density
    of any material a robot is made of.

    The likely cause is named when a factor of 1e3 (mass in grams), 1e6 (a mesh in
    centimetres) or 1e9 (a mesh in millimetres) brings the density into range.

    Why is this bad?
    Either the mass or the geometry is off by a unit: the simulated robot is then a
    thousand times too heavy, or its collision shapes are a thousand times too large.

    Example
    ```xml
    <link name="forearm">
      <inertial>
        <mass value="1500"/>  <!-- grams -->
        <inertia ixx="0.0084" ixy="0" ixz="0" iyy="0.0084" iyz="0" izz="0.0012"/>
      </inertial>
      <collision><geometry><cylinder radius="0.04" length="0.3"/></geometry></collision>
    </link>
    ```

    Use instead:
    ```xml
    <link name="forearm">
      <inertial>
        <mass value="1.5"/>
        <inertia ixx="0.0084" ixy="0" ixz="0" iyy="0.0084" iyz="0" izz="0.0012"/>
      </inertial>
      <collision><geometry><cylinder radius="0.04" length="0.3"/></geometry></collision>
    </link>
    ```
    """
    options = ctx.options or DensityOptions()
    for link, geometry in _measured(robot, ctx):
        density = link.inertial.mass / geometry.properties.volume
        if options.min_density <= density <= options.max_density:
            continue
        cause = _density_cause(density, options)
        yield Finding(f"link '{link.name}': {link.inertial.mass:g} kg in "
                      f"{geometry.properties.volume:.4g} m^3 of {geometry.source} geometry is "
                      f"{density:.4g} kg/m^3, outside [{options.min_density:g}, "
                      f"{options.max_density:g}]" + (f"; likely cause: {cause}" if cause else ""),
                      link.inertial.where, link_element(link))


def _density_cause(density: float, options: DensityOptions) -> str | None:
    causes = ((1e-3, "the mass looks like grams"),
              (1e9, "the geometry looks like millimetres (volume 1e9 times too large)"),
              (1e6, "the geometry looks like centimetres (volume 1e6 times too large)"),
              (1e-9, ("the geometry looks 1000 times too small (a scale of 0.001 on a mesh "
                      "already in metres?)")))
    for factor, cause in causes:
        if options.min_density <= density * factor <= options.max_density:
            return cause
    return None


def _fmt(values) -> str:
    return "(" + ", ".join(f"{v:.4g}" for v in values) + ")"


def _percent(value: float) -> str:
    return f"{100 * value:.3g}%" if value < 1e6 else f"{value:.3g}x"
