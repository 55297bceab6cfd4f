"""The Engineer papers' table, measured fresh: real-time factor with the visual meshes used as
collision, with robotdesc's default generated collision, and with the collision as written,
in DART and MuJoCo, for the Engineer, the UR5 and the Panda (example-robot-data).

The papers (001, Table II) measured in Gazebo a real-time factor of about 0.2 with the visual
meshes used for collision, against about 1 with simple collision meshes: a ratio of about 5.
Each robot and engine here is one `robotdesc.sim.compare.compare_variants` run (the same scene
as `robotdesc sim FILE --engine E --compare visual,generated,as-is`: dropped on a plane, joints
held), the variants one after the other in this process; the ratio is each variant's RTF by
CPU time over the visual one's, in the same run. CPU time is what to compare on a shared
machine (wall time counts the waits for a core); the load average is printed beside.

Run: python benchmarks/bench_sim.py [--robots engineer,ur5,panda] [--engines dart,mujoco]
     [--seconds 0.2] [--write]
`--write` puts the table into docs/sim.md and benchmarks/README.md, between the lines
`<!-- bench_sim: begin -->` and `<!-- bench_sim: end -->`, so the figures there are this run's.
Needs the extras sim and dart (pip install '.[sim,dart]') and example-robot-data for the arms.
"""

from __future__ import annotations

import argparse
import datetime
import logging
import os
import re
import sys
import sysconfig
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
ENGINEER = REPO / "robots/engineer_description/urdf/engineer.urdf.xacro"
ERD = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix/share/example-robot-data"
#: name -> (label, the description: absolute, or under example-robot-data/robots)
ROBOTS = {"engineer": ("Engineer (212 wheels)", str(ENGINEER)),
          "ur5": ("UR5", "ur_description/urdf/ur5_robot.urdf"),
          "panda": ("Panda", "panda_description/urdf/panda.urdf")}
VARIANTS = ("visual", "generated", "as-is")
BEGIN, END = "<!-- bench_sim: begin -->", "<!-- bench_sim: end -->"
TARGETS = (REPO / "docs/sim.md", REPO / "benchmarks/README.md")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", default="engineer,ur5,panda")
    parser.add_argument("--engines", default="dart,mujoco")
    parser.add_argument("--seconds", type=float, default=0.2, help="simulated s per variant")
    parser.add_argument("--write", action="store_true",
                        help="put the table into docs/sim.md and benchmarks/README.md")
    ns = parser.parse_args(argv)
    sys.path.insert(0, str(REPO / "src"))
    logging.basicConfig(level=logging.WARNING, format="%(message)s")

    from robotdesc.collision.options import DEFAULT_BUDGET
    from robotdesc.expansion import ExpandOptions
    from robotdesc.progress import Progress
    from robotdesc.sim.compare import compare_variants
    from robotdesc.sim.engine import engine as engine_named
    from robotdesc.sim.load import load_sim_input
    from robotdesc.sim.scene import SceneOptions

    load_before = os.getloadavg()
    rows: list[tuple[str, str, Any]] = []
    for key in ns.robots.split(","):
        label, path = ROBOTS[key]
        if not Path(path).is_absolute():
            path = str(ERD / "robots" / path)
        options = ExpandOptions(package_map=(("example-robot-data", str(ERD)),))
        loaded = load_sim_input(path, expand_options=options)
        package_map = tuple(options.package_map)
        for name in ns.engines.split(","):
            engine = engine_named(name)
            with Progress(f"{key} {name}", unit="s simulated") as bar:
                def progress(variant: str, simulated: float, total: float, wall: float,
                             bar: Progress = bar) -> None:
                    bar.update(simulated, total)
                    if simulated > 0:
                        bar.note(f"{variant}: {simulated:.1f} of {total:g} s simulated "
                                 f"in {wall:.1f} s")

                comparison = compare_variants(
                    engine, loaded.robot, loaded.meshes, VARIANTS,
                    SceneOptions(timestep=engine.default_timestep), ns.seconds,
                    package_map=package_map, progress=progress, note=bar.note)
            rows.append((label, name, comparison))
    load_after = os.getloadavg()
    table = _table(rows, ns.seconds, load_before, load_after, DEFAULT_BUDGET)
    sys.stdout.write(table)
    if ns.write:
        for target in TARGETS:
            _write_block(target, table)
            sys.stderr.write(f"written into {target.relative_to(REPO)}\n")
    return 0


def _versions() -> str:
    import dartpy
    import mujoco

    return f"MuJoCo {mujoco.__version__}, dartpy {getattr(dartpy, '__version__', '?')}"


def _table(rows: list[tuple[str, str, Any]], seconds: float, before: tuple[float, ...],
           after: tuple[float, ...], budget: int) -> str:
    """The markdown block: how it was measured, then one row per robot, engine, variant."""
    today = datetime.date.today().isoformat()
    how = (f"Measured {today} by `python benchmarks/bench_sim.py --write` ({os.cpu_count()} "
           f"cores, load average {before[0]:.1f} before and {after[0]:.1f} after: a shared "
           f"machine, so read the CPU-time figures; {_versions()}; {seconds:g} s simulated "
           f"per variant; `generated` = `robotdesc collision`'s default, method auto with its "
           f"budget of {budget:,} triangles). Ratio: the variant's RTF by CPU time over the "
           "visual meshes', same run; the papers' Gazebo ratio is 5 (0.2 against 1).")
    header = ("| robot | engine | collision | triangles | primitives | RTF (CPU) | RTF (wall) "
              "| ratio to visual |")
    lines = [how, "", header, "|---|---|---|---|---|---|---|---|"]
    for label, engine, comparison in rows:
        visual = next((v for v in comparison.variants if v.label == "visual"),
                      comparison.variants[0])
        for v in comparison.variants:
            ratio = v.rtf_cpu / visual.rtf_cpu if visual.rtf_cpu > 0 else float("inf")
            strong = "**" if v.label == "generated" else ""
            triangles = f"{v.triangles:,}" + (" (hull faces)" if engine == "mujoco" else "")
            lines.append(f"| {label} | {engine} | {v.label} | {triangles} | {v.primitives} | "
                         f"{v.rtf_cpu:.3g} | {v.rtf_wall:.3g} | {strong}{ratio:.1f}x{strong} |")
    return "\n".join(lines) + "\n"


def _write_block(path: Path, table: str) -> None:
    """Replace the text between BEGIN and END in `path` by `table`."""
    text = path.read_text(encoding="utf-8")
    pattern = re.compile(re.escape(BEGIN) + r".*?" + re.escape(END), re.DOTALL)
    if not pattern.search(text):
        raise SystemExit(f"{path}: no {BEGIN} ... {END} block to fill")
    path.write_text(pattern.sub(lambda _: f"{BEGIN}\n{table}{END}", text), encoding="utf-8")


if __name__ == "__main__":
    raise SystemExit(main())
