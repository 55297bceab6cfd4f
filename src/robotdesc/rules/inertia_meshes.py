"""Inertia against the geometry (I2xx): the declared `<inertial>` compared with the mass
properties of the link's collision (or visual) geometry at uniform density.

These rules need meshes: the lint driver hands them a `robotdesc.mesh.context.MeshContext`
as `ctx.meshes` (typed as what the rules read of it,
`robotdesc.inertia.mesh_access.MeshAccess`). numpy is imported inside the checks, so
registering them costs nothing.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from lxml import etree

from robotdesc.diagnostics import Finding, Severity
from robotdesc.inertia.compare import compare_inertia, declared_tensor, mirror_partner, sign_flip
from robotdesc.inertia.links import has_mass, link_element, mass_of
from robotdesc.inertia.mesh_access import MeshAccess
from robotdesc.inertia.suggest import suggest_for_link
from robotdesc.mesh.context import LinkGeometry
from robotdesc.mesh.properties import MassProperties, Vec3
from robotdesc.model.elements import Inertial, Link, Robot
from robotdesc.rules.registry import RuleContext, SourceDocument, rule
from robotdesc.source import Provenance
from robotdesc.spatial import frobenius

if TYPE_CHECKING:
    from robotdesc.inertia.compare import InertiaComparison

FAMILY = "inertia"
NEEDS = ("meshes",)

#: An impossible axis: (axis name, declared spread sigma (m), largest possible (m)).
Axis = tuple[str, float, float]
#: Axis-aligned bounds (lower corner, upper corner), m, link frame.
Bounds = tuple[Vec3, Vec3]


def _meshes(ctx: RuleContext) -> MeshAccess:
    """The lint's mesh access; callers have checked that there is one (the driver hands
    one to every rule that needs meshes)."""
    if ctx.meshes is None:
        raise ValueError("this rule needs meshes and was given no mesh access")
    return ctx.meshes


def _inertial(link: Link) -> Inertial:
    """The link's `<inertial>`; callers have checked that it declares a mass."""
    if link.inertial is None:
        raise ValueError(f"link '{link.name}' has no <inertial>")
    return link.inertial


def _properties(geometry: LinkGeometry) -> MassProperties:
    """The measured mass properties; callers have checked that the geometry is trusted."""
    if geometry.properties is None:
        raise ValueError(f"link '{geometry.link}': its geometry was not measured")
    return geometry.properties


def _bounds(geometry: LinkGeometry) -> Bounds:
    """The measured bounds; callers have checked that the geometry is complete."""
    if geometry.bounds is None:
        raise ValueError(f"link '{geometry.link}': its geometry has no bounds")
    return geometry.bounds


def _tensor_where(link: Link) -> Provenance | None:
    """Where the declared tensor is written (else its `<inertial>`)."""
    inertial = _inertial(link)
    return (inertial.inertia.where if inertial.inertia else None) or inertial.where


def _measured(robot: Robot, ctx: RuleContext) -> Iterator[tuple[Link, LinkGeometry]]:
    """Links with a positive declared mass whose geometry could be measured exactly."""
    if ctx.meshes is None:
        return
    for link in robot.links:
        if not has_mass(link):
            continue
        geometry = _meshes(ctx).link_geometry(link)
        if geometry.trusted:
            yield link, geometry


def _fix(robot: Robot, ctx: RuleContext, link: Link) -> str | None:
    """The suggested `<inertial>` block (meshes in millimetres scaled first)."""

    found = suggest_for_link(robot, _meshes(ctx), link)
    return found.block if found is not None else None


def _both_sources(ctx: RuleContext, link: Link) -> list[LinkGeometry]:
    """The link's collision and visual geometry (each once; a link with only one kind
    gives it once), measured completely, or [] when a part could not be measured."""
    found: list[LinkGeometry] = []
    seen: set[str] = set()
    for source in ("collision", "visual"):
        geometry = _meshes(ctx).link_geometry(link, source)
        if not geometry.source or geometry.source in seen:
            continue
        seen.add(geometry.source)
        if not geometry.complete or geometry.bounds is None:
            return []
        found.append(geometry)
    return found


def _union_bounds(geometries: Sequence[LinkGeometry]) -> Bounds | None:
    """The axis-aligned box (m, link frame) around every geometry given, None for none."""
    if not geometries:
        return None
    low = [min(_bounds(g)[0][i] for g in geometries) for i in range(3)]
    high = [max(_bounds(g)[1][i] for g in geometries) for i in range(3)]
    return (low[0], low[1], low[2]), (high[0], high[1], high[2])


def _spread(link: Link) -> tuple[float, float, float]:
    """Second moments of the declared mass about its centre along the link's x, y, z axes
    (m^2): Sigma = (trace(I) / 2 - I) / m, from the declared tensor in link axes."""

    tensor = declared_tensor(_inertial(link))
    half_trace = (tensor[0][0] + tensor[1][1] + tensor[2][2]) / 2.0
    mass = mass_of(link)
    return ((half_trace - tensor[0][0]) / mass, (half_trace - tensor[1][1]) / mass,
            (half_trace - tensor[2][2]) / mass)


#: Relative slack on the certain bound: values written with few digits, rounded meshes.
_BOUND_SLACK = 0.02


def _impossible_axes(link: Link, bounds: Bounds) -> list[Axis]:
    """(axis, declared spread sigma (m), largest possible (m)) for every link axis along which
    the declared tensor spreads the mass wider than any distribution inside `bounds` can:
    the variance of a quantity confined to an interval of width w is at most (w/2)^2."""
    low, high = bounds
    out: list[Axis] = []
    for axis, second, lo, hi in zip("xyz", _spread(link), low, high):
        limit = ((hi - lo) / 2.0) ** 2
        if second > limit * (1.0 + _BOUND_SLACK) ** 2 + 1e-12:
            out.append((axis, second ** 0.5, limit ** 0.5))
    return out


def _certain_violation(ctx: RuleContext, link: Link) -> tuple[list[Axis], Bounds] | None:
    """(the impossible axes, the geometry's bounds) when I204 or I206 applies to the link.

    Links of a gram or less carry token values, and geometry under 5 mm across is a stand-in
    (a marker sphere), not the body: neither is judged.
    """
    if link.inertial is None or link.inertial.inertia is None or not has_mass(link) \
            or (link.inertial.mass or 0.0) <= PLACEHOLDER_MASS:
        return None
    bounds = _union_bounds(_both_sources(ctx, link))
    if bounds is None or max(h - lo for lo, h in zip(*bounds)) < PLACEHOLDER_SIZE:
        return None
    axes = _impossible_axes(link, bounds)
    return (axes, bounds) if axes else None


#: A typed-in diag(I, I, I) whose tensor is this many times larger than the geometry allows
#: (the largest (sigma / bound)^2 over the impossible axes) is certain, not a deliberate
#: inflation: I204 reports it by default; below it, it is I206's (opt-in) gray band.
CERTAIN_FACTOR = 10.0


def excess_factor(axes: list[Axis]) -> float:
    """How many times too large the declared tensor is along its worst axis: the declared
    spread's square over the largest the geometry allows ((sigma / bound)^2)."""
    return max(((sigma / bound) ** 2 if bound > 0 else math.inf) for _axis, sigma, bound in axes)


#: Words of a comment next to a typed-in tensor that say it is inflated on purpose (PAL's
#: hey5 hand: `<inertia .../> <!-- To stabilize simulation -->`).
ON_PURPOSE_WORDS = ("stabil", "on purpose", "deliberate", "intentional")


def explained_tensors(document: SourceDocument | None) -> frozenset[str]:
    """Links whose `<inertia>` has a comment right before or after it (in the expanded
    document) saying the value is meant: a tensor inflated to steady a simulation, which
    I204 leaves to I206's gray band however far it is off."""
    if document is None or b"<!--" not in document.xml:
        return frozenset()
    lowered = document.xml.lower()
    if not any(word.encode() in lowered for word in ON_PURPOSE_WORDS):
        return frozenset()  # no comment can say it: the document is not parsed again
    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                             remove_comments=False, remove_pis=True)
    try:
        root = etree.fromstring(document.xml, parser)
    except (etree.XMLSyntaxError, ValueError):
        return frozenset()
    found = set()
    for inertia in root.iterfind("link/inertial/inertia"):
        near = (inertia.getprevious(), inertia.getnext())
        said = " ".join(str(c.text or "") for c in near if isinstance(c, etree._Comment))
        if any(word in said.lower() for word in ON_PURPOSE_WORDS):
            name = inertia.getparent().getparent().get("name")
            if name is not None:
                found.add(name)
    return frozenset(found)


def is_isotropic(link: Link) -> bool:
    """Whether the declared tensor is diag(I, I, I): a value typed in, not computed (a
    placeholder, or a tensor inflated on purpose to steady a simulation)."""
    inertia = link.inertial.inertia if link.inertial else None
    if inertia is None or inertia.ixx <= 0.0:
        return False
    equal = all(abs(value - inertia.ixx) <= 1e-9 * inertia.ixx
                for value in (inertia.iyy, inertia.izz))
    return equal and inertia.ixy == inertia.ixz == inertia.iyz == 0.0


@rule("I204", "inertia-impossible-for-geometry", family=FAMILY, severity=Severity.WARNING,
      needs=(*NEEDS, "document"))
def inertia_impossible_for_geometry(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a declared inertia tensor that no mass distribution inside the link's geometry
    (visual and collision together, with their scales) could have.

    The declared tensor and mass give the spread of the mass along each link axis,
    sigma^2 = (trace(I) / 2 - I_aa) / m; a mass confined to an interval of width w has a
    spread of at most w / 2. The message names the axis, the declared spread and that bound.
    A tensor that implies a negative spread (negative density) is I104's. A typed-in
    diag(I, I, I) is reported here only when it is 10 times or more too large (certain: a
    placeholder nobody revisited) and no comment next to it says it is meant ("To stabilize
    simulation"); the others are I206's gray band (opt-in).

    Why is this bad?
    It is certain, not a uniform-density guess: whatever the material inside, this tensor
    belongs to a larger body. Typical causes are a tensor in g*mm^2 or kg*cm^2, one copied
    from a bigger link, or one computed about another point.

    Example
    ```xml
    <link name="finger">
      <inertial>
        <mass value="0.05"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.001"/>
      </inertial>
      <collision><geometry><box size="0.02 0.02 0.06"/></geometry></collision>
    </link>
    ```

    Use instead (`robotdesc inertia --suggest` prints it):
    ```xml
    <link name="finger">
      <inertial>
        <mass value="0.05"/>
        <inertia ixx="1.66667e-05" ixy="0" ixz="0" iyy="1.66667e-05" iyz="0" izz="3.33333e-06"/>
      </inertial>
      <collision><geometry><box size="0.02 0.02 0.06"/></geometry></collision>
    </link>
    ```
    """
    if ctx.meshes is None:
        return
    explained = explained_tensors(ctx.document)
    for link in robot.links:
        found = _certain_violation(ctx, link)
        if found is None:
            continue
        if not is_isotropic(link):
            yield _impossible_finding(robot, ctx, link, found, "")
        elif excess_factor(found[0]) >= CERTAIN_FACTOR and link.name not in explained:
            yield _impossible_finding(robot, ctx, link, found,
                                      f"typed-in tensor diag(I, I, I), "
                                      f"{excess_factor(found[0]):.3g} times too large: ")


@rule("I206", "placeholder-inertia-impossible", family=FAMILY, severity=Severity.INFO,
      needs=(*NEEDS, "document"), opt_in=True)
def placeholder_inertia_impossible(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a typed-in tensor diag(I, I, I) that no mass distribution inside the link's
    geometry could have, but less than 10 times too large: I204's test, for the gray band
    I204 leaves out (I204 reports a typed-in tensor 10 times or more too large).

    Equal moments with no products are a value typed in, not computed: a placeholder, or a
    tensor inflated on purpose because a physics engine steps small links badly (TIAGo's hand
    links say "To stabilize simulation"). Opt-in: on real packages most are deliberate.

    Why is this bad?
    A placeholder that nobody revisited gives a simulation the wrong dynamics: the link
    turns as if it were far larger. A deliberate one is better said with a suppression and
    its reason, so that a reader knows.

    Example
    ```xml
    <link name="finger">
      <inertial>
        <mass value="0.05"/>
        <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/>
      </inertial>
      <collision><geometry><box size="0.02 0.02 0.06"/></geometry></collision>
    </link>
    ```

    Use instead (the tensor of the geometry, `robotdesc inertia --suggest`, or keep the
    value with `<!-- robotdesc: ignore I206 inflated to steady the simulation -->`):
    ```xml
    <link name="finger">
      <inertial>
        <mass value="0.05"/>
        <inertia ixx="1.66667e-05" ixy="0" ixz="0" iyy="1.66667e-05" iyz="0" izz="3.33333e-06"/>
      </inertial>
      <collision><geometry><box size="0.02 0.02 0.06"/></geometry></collision>
    </link>
    ```
    """
    if ctx.meshes is None:
        return
    explained = explained_tensors(ctx.document)
    for link in robot.links:
        found = _certain_violation(ctx, link)
        if found is not None and is_isotropic(link) and (
                excess_factor(found[0]) < CERTAIN_FACTOR or link.name in explained):
            yield _impossible_finding(robot, ctx, link, found,
                                      "typed-in tensor diag(I, I, I): ")


def _impossible_finding(robot: Robot, ctx: RuleContext, link: Link,
                        found: tuple[list[Axis], Bounds], kind: str) -> Finding:
    """I204's and I206's message: each impossible axis, its declared spread and the bound;
    the fix only when the geometry it is computed from spans the body the bound saw."""
    axes, bounds = found
    detail = "; ".join(f"along {axis} the declared tensor spreads the mass by "
                       f"sigma = {sigma:.4g} m, but the geometry allows at most "
                       f"{bound:.4g} m (half its {2 * bound:.4g} m width)"
                       for axis, sigma, bound in axes)
    cause = _unit_cause(ctx, link)
    return Finding(f"link '{link.name}': {kind}no mass distribution inside its visual and "
                   f"collision geometry has the declared inertia at "
                   f"{mass_of(link):g} kg: {detail}"
                   + (f"; likely cause: {cause}" if cause else ""),
                   _tensor_where(link), link_element(link),
                   _fix(robot, ctx, link) if _spans(ctx, link, bounds) else None)


#: The suggestion's geometry must be at least this fraction of the bound's width per axis.
_SPAN_FRACTION = 0.5


def _spans(ctx: RuleContext, link: Link, bounds: Bounds) -> bool:
    """Whether the geometry a suggestion is computed from (the configured source) spans at
    least half of `bounds` along every axis: a 1 mm collision sphere under a 20 cm visual
    mesh (Baxter's head) would suggest a tensor a thousand times too small."""
    geometry = _meshes(ctx).link_geometry(link)
    if geometry.bounds is None:
        return False
    low, high = _bounds(geometry)
    return all(h - lo >= _SPAN_FRACTION * (bh - bl)
               for lo, h, bl, bh in zip(low, high, bounds[0], bounds[1]))


def _unit_cause(ctx: RuleContext, link: Link) -> str | None:
    """What relates the declared tensor to the geometry's (a unit slip, a rotation, a sign
    convention), if the numbers show it."""

    geometry = _meshes(ctx).link_geometry(link)
    if not geometry.trusted:
        return None
    return compare_inertia(_inertial(link), _properties(geometry),
                           DeviationOptions.tolerance).cause


@dataclass(frozen=True)
class InertiaMismatchOptions:
    """Options of I201.

    Attributes:
        factor: a principal moment this many times larger or smaller than the geometry's is
            reported.
    """

    factor: float = 10.0


#: Link name -> (link, its geometry, the comparison of its declared tensor with it).
Comparisons = dict[str, tuple[Link, LinkGeometry, "InertiaComparison"]]


def _comparisons(robot: Robot, ctx: RuleContext, tolerance: float) -> Comparisons:
    """Link name -> (link, geometry, comparison) for links whose geometry can be trusted,
    leaving out those whose tensor is impossible for their geometry (I204's)."""

    results: Comparisons = {}
    for link, geometry in _measured(robot, ctx):
        if _inertial(link).inertia is None or _certain_violation(ctx, link) is not None \
                or _placeholder(geometry):
            continue
        results[link.name] = (link, geometry, compare_inertia(_inertial(link),
                                                              _properties(geometry), tolerance))
    return results


def _factor(comparison: InertiaComparison) -> float:
    """The largest ratio, either way, between a declared and a derived principal moment."""
    worst = 1.0
    for declared, derived in zip(comparison.declared_moments, comparison.derived_moments):
        if declared <= 0 or derived <= 0:
            return float("inf")
        worst = max(worst, declared / derived, derived / declared)
    return worst


#: A sign or rotation cause is named only when, undone, the tensors agree this closely
#: (relative Frobenius error, or per principal moment): a fit, not a 50% resemblance.
EXACT_FIT = 0.1


def _fitting_cause(comparison: InertiaComparison) -> str | None:
    """The comparison's cause, dropped when it is a products-sign swap or a rotation that
    does not fit within `EXACT_FIT` (those then count as plain deviations)."""

    cause = comparison.cause
    if cause is None:
        return None
    if cause.startswith("the sign of"):
        slack = EXACT_FIT * frobenius(comparison.derived)
        return cause if sign_flip(comparison.declared, comparison.derived, slack) else None
    if cause.startswith("the principal moments agree"):
        return cause if max(comparison.moment_errors) <= EXACT_FIT else None
    return cause


#: I201, I203 and I204 leave links of at most this mass (kg) alone: a gram's tensor moves
#: nothing, and such links carry placeholder values (a frame given a token mass, as in M115).
PLACEHOLDER_MASS = 1e-3


def _mismatch_findings(robot: Robot, ctx: RuleContext, tolerance: float,
                       keep: Callable[[InertiaComparison, str], bool],
                       min_mass: float = 0.0) -> Iterator[Finding]:
    results = _comparisons(robot, ctx, tolerance)
    for name, (link, geometry, comparison) in results.items():
        if not comparison.mismatch(tolerance) or mass_of(link) <= min_mass:
            continue
        cause = _fitting_cause(comparison)
        partner = mirror_partner(name, set(results))
        if partner and not results[partner][2].mismatch(tolerance):
            mirror = f"its mirror link '{partner}' agrees with its geometry"
            cause = f"{cause}; {mirror}" if cause else f"left/right links disagree: {mirror}"
        if not keep(dataclasses.replace(comparison, cause=cause), name):
            continue
        worst = max(comparison.moment_errors)
        yield Finding(
            f"link '{name}': declared principal moments {_fmt(comparison.declared_moments)} "
            f"kg*m^2 differ from its {geometry.source} geometry's "
            f"{_fmt(comparison.derived_moments)} at {mass_of(link):g} kg by up to "
            f"{_percent(worst)} (tensor {_percent(comparison.tensor_error)})"
            + (f"; likely cause: {cause}" if cause else ""),
            _tensor_where(link), link_element(link), _fix(robot, ctx, link))


@rule("I201", "inertia-differs-from-geometry", family=FAMILY, severity=Severity.WARNING,
      options=InertiaMismatchOptions, needs=NEEDS, opt_in=True)
def inertia_differs_from_geometry(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a declared inertia tensor that differs from the one of the link's geometry
    (collision by default, at uniform density and the declared mass) by a factor of 10 or
    more in a principal moment, or in a way that has a recognised cause.

    Opt-in since issue 29: on the blind part 4 of 5 sampled (11 of all 14) were worth fixing;
    the others compare a measured tensor with geometry that is not the whole body (RotorS'
    central box under a hexacopter's arms) or a 10 g camera on a fixed joint
    (docs/precision.md). I204 keeps the certain part: a tensor no mass inside the geometry
    can have.

    The factor is that of the largest principal moment, which dominates how the link
    turns. The recognised causes: a unit slip (a factor of 1e3, 1e6 or 1e9: grams, millimetres),
    a rotated tensor (the same principal moments within 10%, other axes), products of
    inertia with the CAD sign convention (flipping their signs matches the geometry within
    10%). A left/right mirror link that agrees with its own geometry is named too.
    The fix is the `<inertial>` computed from the geometry, at the declared mass (with a mesh
    diagnosed as millimetres scaled by 0.001 first). Smaller deviations without a cause are
    I205's (off by default): a real link is not of uniform density. Without a recognised
    cause the tensor must be 10x off the estimate of every geometry the link has, visual and
    collision (a collision proxy, such as a small disc standing for an arm segment, does not
    condemn a tensor its visual mesh agrees with). Links of a gram or less and geometry under
    5 mm (placeholders), singular tensors (a point mass, a rod: I103 judges those) and
    typed-in diag(I, I, I) tensors larger than the geometry's (inflated to steady a
    simulation, see I206) are left alone.

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
    factor = ctx.options_as(InertiaMismatchOptions).factor
    tolerance = DeviationOptions.tolerance
    links = {link.name: link for link in robot.links}

    def keep(comparison: InertiaComparison, name: str) -> bool:
        if _singular(comparison) or (is_isotropic(links[name]) and max(
                comparison.declared_moments) > max(comparison.derived_moments)):
            return False  # I103's; or typed in larger, as to steady a simulation (I206)
        if _has_cause(comparison):
            return True
        return (_largest_factor(comparison) >= factor
                and _off_from_every_source(ctx, links[name], factor, tolerance))

    yield from _mismatch_findings(robot, ctx, tolerance, keep, min_mass=PLACEHOLDER_MASS)


def _singular(comparison: InertiaComparison) -> bool:
    """A declared point mass, rod or plate (a principal moment zero, to rounding): I103
    judges those."""
    return min(comparison.declared_moments) <= 1e-9 * max(comparison.derived_moments)


def _largest_factor(comparison: InertiaComparison) -> float:
    """The ratio, either way, of the declared and derived largest principal moments: the one
    that dominates how the link turns (a rod's tiny moment about its own axis does not)."""
    declared, derived = max(comparison.declared_moments), max(comparison.derived_moments)
    if declared <= 0 or derived <= 0:
        return float("inf")
    return max(declared / derived, derived / declared)


def _off_from_every_source(ctx: RuleContext, link: Link, factor: float,
                           tolerance: float) -> bool:
    """Whether the declared moments are `factor` off the uniform-density estimate of each of
    the link's geometries: a collision proxy (a small disc standing for an arm segment, as
    on Unitree H1) must not condemn a tensor that its visual mesh agrees with."""

    for geometry in _both_sources(ctx, link):
        if not geometry.trusted:
            continue
        other = compare_inertia(_inertial(link), _properties(geometry), tolerance)
        if _largest_factor(other) < factor:
            return False
    return True


def _has_cause(comparison: InertiaComparison) -> bool:
    """The comparison names a cause (set by `_mismatch_findings` for mirror links too)."""
    return comparison.cause is not None


@dataclass(frozen=True)
class DeviationOptions:
    """Options of I205.

    Attributes:
        tolerance: relative difference allowed per principal moment, and for the whole
            tensor (a real link is not of uniform density: motors and shells shift it).
    """

    tolerance: float = 0.5


@rule("I205", "inertia-deviates-from-uniform-density", family=FAMILY,
      severity=Severity.INFO, options=DeviationOptions, needs=NEEDS, opt_in=True)
def inertia_deviates_from_uniform_density(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a declared inertia tensor that differs from the one of the link's geometry at
    uniform density by more than the tolerance but less than I201's factor, with no
    recognised cause.

    Off by default: a real link is not of uniform density (motors, gears, hollow shells), so
    a deviation of 50% or 3x is often right. Turn it on (`--select I205`) to review the
    inertia of a description whose links are nearly uniform (3D-printed parts, simple
    shapes).

    Why is this bad?
    It may not be: it is a hint to compare the tensor with CAD or an identification. A
    tensor estimated by hand is often off by this much.

    Example
    ```xml
    <link name="arm">
      <inertial><mass value="1"/>
        <inertia ixx="0.004" ixy="0" ixz="0" iyy="0.004" iyz="0" izz="0.004"/></inertial>
      <collision><geometry><box size="0.1 0.1 0.3"/></geometry></collision>
    </link>
    ```

    Use instead:
    ```xml
    <link name="arm">
      <inertial><mass value="1"/>
        <inertia ixx="0.00833333" ixy="0" ixz="0" iyy="0.00833333" iyz="0" izz="0.00166667"/></inertial>
      <collision><geometry><box size="0.1 0.1 0.3"/></geometry></collision>
    </link>
    ```
    """
    tolerance = ctx.options_as(DeviationOptions).tolerance
    factor = InertiaMismatchOptions.factor
    yield from _mismatch_findings(
        robot, ctx, tolerance,
        lambda c, _name: _factor(c) < factor and not _has_cause(c))


@dataclass(frozen=True)
class CenterOfMassOptions:
    """Options of I202.

    Attributes:
        margin: slack around the geometry's bounding box, as a fraction of its size
            along each axis.
    """

    margin: float = 0.1


@rule("I202", "center-of-mass-outside-geometry", family=FAMILY, severity=Severity.WARNING,
      options=CenterOfMassOptions, needs=NEEDS, opt_in=True)
def center_of_mass_outside_geometry(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a declared centre of mass (`<inertial><origin xyz>`) outside the bounding box
    of the link's geometry, visual and collision together.

    Opt-in since issue 29: on the blind part 3 of 5 were worth fixing (the others: sensor
    frames on fixed joints; docs/precision.md).

    A collision geometry is often simplified (contact spheres on a foot, a box on a sensor):
    the centre of mass is judged against everything the link is drawn and collides with.

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
    margin = ctx.options_as(CenterOfMassOptions).margin
    if ctx.meshes is None:
        return
    for link in robot.links:
        if not has_mass(link) or mass_of(link) <= PLACEHOLDER_MASS:
            continue
        geometries = _both_sources(ctx, link)
        bounds = _union_bounds(geometries)
        if bounds is None:
            continue
        low, high = bounds
        kinds = " and ".join(g.source for g in geometries)
        inertial = _inertial(link)
        com = inertial.origin.xyz
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
            yield Finding(f"link '{link.name}': declared centre of mass {_fmt(com)} m lies "
                          f"outside the bounds of its {kinds} geometry together: "
                          f"{'; '.join(outside)}{hint}",
                          inertial.origin.where or inertial.where, link_element(link),
                          _fix(robot, ctx, link))


@dataclass(frozen=True)
class DensityOptions:
    """Options of I203.

    Attributes:
        min_density: lowest plausible mass / volume (kg/m^3); hollow shells and foam are
            light, but not lighter than this.
        max_density: highest plausible mass / volume (kg/m^3), a little above osmium.
        factor: how far outside that range (a factor, either way) the density must be to be
            reported (1: any density outside it; 10 keeps the unit slips, a factor of 1000).
    """

    min_density: float = 50.0
    max_density: float = 25_000.0
    factor: float = 1.0


@rule("I203", "implausible-density", family=FAMILY, severity=Severity.WARNING,
      options=DensityOptions, needs=NEEDS, opt_in=True)
def implausible_density(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a link whose declared mass divided by its geometry's volume is not the density
    of any material a robot is made of (option `factor`: report only densities that many
    times outside [50, 25000] kg/m^3).

    Opt-in (`--select I203`): on real packages nearly all of its findings are token masses on
    frames and virtual links (a 10 g torso column, a 0.1 kg tool frame with a marker shape)
    or collision proxies (a rotor's swept disc), not unit slips; see docs/precision.md. A
    mesh in millimetres is M108's, a tensor in the wrong units I201's, on by default.

    Both the collision and the visual geometry are measured; the link is reported only when
    neither gives a plausible density (a collision geometry is often a simplification, like
    the contact spheres of a foot). Placeholders are skipped: links lighter than a gram and
    geometry smaller than 5 mm. The likely cause is named only when exactly one unit factor
    (1e3: mass in grams; 1e6: a mesh in centimetres; 1e9: a mesh in millimetres) lands the
    density among the materials robots are made of (100 to 20 000 kg/m^3), and never for
    geometry smaller than 2 cm (a stand-in shape says nothing about units).

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
    options = ctx.options_as(DensityOptions)
    if ctx.meshes is None:
        return
    for link in robot.links:
        mass = mass_of(link)
        if not has_mass(link) or mass <= PLACEHOLDER_MASS:
            continue
        measured: list[LinkGeometry] = []
        for source in ("collision", "visual"):
            geometry = _meshes(ctx).link_geometry(link, source)
            if geometry.trusted and geometry.source not in {g.source for g in measured}:
                measured.append(geometry)
        if not measured or any(_placeholder(g) for g in measured):
            continue
        densities = [mass / _properties(g).volume for g in measured]
        # a relative slack of 1e-6: 1 kg in 0.02 m^3 is 50 kg/m^3, not 49.99999
        low = options.min_density / options.factor * (1 - 1e-6)
        high = options.max_density * options.factor * (1 + 1e-6)
        if any(low <= d <= high for d in densities):
            continue  # one of the geometries is plausible: the other is a simplification
        geometry, density = measured[0], densities[0]
        small = max(_extent(g) for g in measured) < CAUSE_MIN_SIZE
        cause = None if small else _density_cause(density)
        also = (f" (its {measured[1].source} geometry gives {densities[1]:.4g} kg/m^3)"
                if len(measured) > 1 else "")
        yield Finding(f"link '{link.name}': {mass:g} kg in "
                      f"{_properties(geometry).volume:.4g} m^3 of {geometry.source} geometry is "
                      f"{density:.4g} kg/m^3{also}, "
                      + (f"more than {options.factor:g}x " if options.factor > 1 else "")
                      + f"outside [{options.min_density:g}, {options.max_density:g}]"
                      + (f"; likely cause: {cause}" if cause else ""),
                      _inertial(link).where, link_element(link))


#: Geometry whose largest extent is below this (m) is a placeholder (a 1 mm cube).
PLACEHOLDER_SIZE = 0.005
#: Below this largest extent (m) the geometry may be a stand-in: no unit cause is named.
CAUSE_MIN_SIZE = 0.02
#: Densities (kg/m^3) of what robots are made of, from hollow plastic shells to tungsten: a
#: unit factor is named only when it lands the density here.
TYPICAL_DENSITY = (100.0, 20_000.0)


def _extent(geometry: LinkGeometry) -> float:
    low, high = _bounds(geometry)
    return max(h - lo for lo, h in zip(low, high))


def _placeholder(geometry: LinkGeometry) -> bool:
    return _extent(geometry) < PLACEHOLDER_SIZE


def _density_cause(density: float) -> str | None:
    """The unit slip whose factor lands the density among typical materials, if exactly one
    does."""
    causes = ((1e-3, "the mass looks like grams (1e3 times too large)"),
              (1e3, ("the mass looks 1000 times too small (kg written as tonnes, or divided "
                     "by 1000 twice)")),
              (1e9, "the geometry looks like millimetres (volume 1e9 times too large)"),
              (1e6, "the geometry looks like centimetres (volume 1e6 times too large)"),
              (1e-9, ("the geometry looks 1000 times too small (a scale of 0.001 on a mesh "
                      "already in metres?)")))
    low, high = TYPICAL_DENSITY
    fitting = [cause for factor, cause in causes if low <= density * factor <= high]
    return fitting[0] if len(fitting) == 1 else None


def _fmt(values: Sequence[float]) -> str:
    return "(" + ", ".join(f"{v:.4g}" for v in values) + ")"


def _percent(value: float) -> str:
    return f"{100 * value:.3g}%" if value < 1e6 else f"{value:.3g}x"
