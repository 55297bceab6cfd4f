# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # robotdesc in a notebook: the Servosila Engineer
#
# This tutorial walks through the Engineer description shipped in
# `robots/engineer_description`: load it, lint it, look at the inertia of each link against
# its geometry (and at the equivalent inertia boxes in 3D), generate collision meshes and
# compare them with the visual ones. It needs no ROS and no network.
#
# Open `docs/tutorial.ipynb` in Jupyter (it is generated from `docs/tutorial.py` by
# `python scripts/tutorial_notebook.py`, without outputs), or run all its cells with
# `python docs/tutorial.py` (robotdesc's worker processes never run your script again, so a
# script needs no `if __name__ == "__main__":` guard for them). Either works from any working
# folder of a clone where robotdesc is installed; elsewhere, point `$ROBOTDESC_ENGINEER` at
# `engineer.urdf.xacro`. The test suite runs both (tests/test_tutorial.py), so every cell here
# works. Pages it writes go to `$ROBOTDESC_TUTORIAL_OUT` (default: a new temporary folder).

# %%
import importlib.util
import os
import tempfile
from collections import Counter
from pathlib import Path

import robotdesc

WHERE = Path("robots", "engineer_description", "urdf", "engineer.urdf.xacro")


def find_engineer():
    """The Engineer's xacro: $ROBOTDESC_ENGINEER, else in the clone this file, the working
    folder or robotdesc itself (an editable install) lies in."""
    if os.environ.get("ROBOTDESC_ENGINEER"):
        return Path(os.environ["ROBOTDESC_ENGINEER"]).resolve()
    spec = importlib.util.find_spec("robotdesc")
    starts = [Path(globals().get("__file__", "tutorial.py")).resolve(), Path.cwd().resolve()]
    if spec is not None and spec.origin:
        starts.append(Path(spec.origin).resolve())
    for start in starts:
        for folder in (start, *start.parents):
            if (folder / WHERE).is_file():
                return folder / WHERE
    raise FileNotFoundError(f"{WHERE} is in a clone of robotdesc: run this from the clone, or "
                            "set ROBOTDESC_ENGINEER to the file's path")


ENGINEER = find_engineer()
OUT = Path(os.environ.get("ROBOTDESC_TUTORIAL_OUT") or tempfile.mkdtemp(prefix="robotdesc-"))
OUT.mkdir(parents=True, exist_ok=True)

# %% [markdown]
# ## 1. Load
#
# `robotdesc.load` expands the xacro (in a sandboxed worker, packages found without ROS) and
# parses the URDF strictly into frozen dataclasses. Every element knows where it was
# written: file, line, and the chain of macro calls that produced it.

# %%
robot = robotdesc.load(str(ENGINEER))
print(f"{robot.name}: {len(robot.links)} links, {len(robot.joints)} joints")
print("joint types:", dict(Counter(joint.type for joint in robot.joints)))
head = robot.link("head_link")
print("head_link is written at", head.where.span)
robot  # noqa: B018 (a notebook shows a short summary: counts, mass, DoF, the top of the tree)

# %% [markdown]
# `robotdesc.to_urdf` gives the expanded URDF as plain text, as `robotdesc expand` writes
# it (without robotdesc's internal provenance attributes).

# %%
urdf = robotdesc.to_urdf(str(ENGINEER))
(OUT / "engineer.urdf").write_text(urdf, encoding="utf-8")
print(urdf.splitlines()[0], f"... ({len(urdf.splitlines())} lines)")

# %% [markdown]
# ## 2. Lint
#
# `robotdesc.lint` runs every rule, as `robotdesc lint` does. In Jupyter the result renders
# as a table; here we count the findings per rule and read a few.

# %%
result = robotdesc.lint(str(ENGINEER))
print(result)
for (code, name), count in Counter((d.code, d.name) for d in result.diagnostics).most_common():
    print(f"  {code} {name}: {count}")
for diagnostic in result.diagnostics[:3]:  # the bundled Engineer has none
    print(f"\n{diagnostic.where.span}: {diagnostic.message}")
result  # noqa: B018 (displayed by the notebook)

# %% [markdown]
# ## 3. Inertia against the geometry
#
# For each link: the declared mass and principal moments against those of its collision
# geometry at uniform density and the same mass. A mismatch of more than 50 % is worth a
# look; robotdesc names the likely cause (a unit slip, a swapped sign) when it recognises
# one.

# %%
inertia = robotdesc.mesh_inertia(str(ENGINEER))
# Links whose lint finding is suppressed with a reason (the track wheels carry their
# drivetrain's inertia on purpose) are marked `suppressed` and left out here, as lint does.
worst = sorted((r for r in inertia.rows if r.error is not None and not r.suppressed),
               key=lambda r: -r.error)[:6]
for row in worst:
    print(f"{row.link:24s} mass {row.declared_mass:.3f} kg   moments differ by "
          f"{100 * row.error:.0f} %" + (f"   ({row.cause})" if row.cause else ""))
inertia  # noqa: B018 (a notebook shows the whole table)

# %% [markdown]
# ### The equivalent inertia boxes
#
# Gazebo's inertia view draws, for each link, the box of uniform density with the link's
# mass and principal moments. A box much larger than the link's geometry means an inertia
# too large for the body (the Engineer paper's Fig. 5 shows one three times the size of the
# head). Here are the boxes of the links above: from the declared moments, and from the
# moments of the geometry at the same mass.


# %%
def box_size(mass, moments):
    """Edges (m) of the uniform box with this mass (kg) and principal moments (kg m^2)."""
    a, b, c = moments
    return sorted(max(0.0, 6 * (p + q - r) / mass) ** 0.5 for p, q, r in
                  ((b, c, a), (a, c, b), (a, b, c)))


for row in worst:
    if not (row.declared_mass and row.declared_moments and row.derived_moments):
        continue
    declared = box_size(row.declared_mass, row.declared_moments)
    geometry = box_size(row.declared_mass, row.derived_moments)
    print(f"{row.link:24s} box {' x '.join(f'{1000 * e:.0f}' for e in declared)} mm"
          f"   geometry {' x '.join(f'{1000 * e:.0f}' for e in geometry)} mm")

# %% [markdown]
# The same boxes in 3D, with the links that have findings in red. `robotdesc.show` returns a
# view that Jupyter displays inline; `.save()` writes a self-contained page (no network
# needed to open it). Untick "visual geometry" to see the boxes alone.

# %%
view = robotdesc.show(result, {"left_flipper": 0.5, "shoulder": 0.4},
                      visible=("visual", "inertia", "findings"))
page = view.save(OUT / "engineer.html")
print(view, "->", page, f"({os.path.getsize(page) / 1e6:.1f} MB)")
view  # noqa: B018 (displayed by the notebook)

# %% [markdown]
# ## 4. Collision meshes
#
# The Engineer's collision geometry is a set of boxes. `generate_collision` makes new
# collision geometry from the visual meshes (here convex hulls of two links; "decimate",
# "coacd" and "primitive" are the other methods) and measures each result against its input:
# faces before and after, volume ratio, and the distances between the surfaces. The robot is
# not modified; the work runs in worker processes.

# %%
collision = robotdesc.generate_collision(
    robot, "hull", links=["head_link", "left_flipper_link"], jobs=2)
print(collision.totals())
collision  # noqa: B018 (a notebook shows the per-link table)

# %% [markdown]
# ## 5. Compare, in one report
#
# The HTML report puts it together: findings grouped by link, the 3D view, the inertia
# table, the collision tables (as described, and as generated above) and plots of declared
# against geometry moments and of triangles per link. From the command line:
# `robotdesc report engineer.urdf.xacro -o report.html [--collision hull]`.

# %%
report = OUT / "report.html"
report.write_text(robotdesc.html_report(result, collision), encoding="utf-8")
print(f"wrote {report} ({report.stat().st_size / 1e6:.1f} MB)")
for outcome in collision.outcomes:
    r = outcome.report
    print(f"{r.link:18s} visual {r.faces_before:6d} -> hull {r.faces_after:4d} faces, "
          f"volume x{r.volume_ratio:.2f}")
