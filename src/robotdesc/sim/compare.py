"""The Engineer papers' table: the real-time factor with different collision geometry.

For each variant ("as-is", "visual", "generated"), the same scene (dropped on the ground, joints
held) is built in one engine and stepped for the same simulated time; measured are the
triangles the engine collides, the real-time factor by CPU time of the process and by wall
time, and the wall time of one collision pass (the mean over a few passes at the last state).
Ratios are each variant's CPU-time RTF over the first variant's. The papers measured, in
Gazebo: 0.2 with the visual meshes used for collision, about 1 with simple collision meshes.
"""

from __future__ import annotations

import logging
import time
from dataclasses import dataclass
from typing import Any, Callable, Mapping, Sequence

from robotdesc.collision.methods import DEFAULT_METHOD
from robotdesc.errors import SimOptionError
from robotdesc.model.elements import Robot
from robotdesc.sim.engine import Engine, EngineScene
from robotdesc.sim.hold import HoldOptions
from robotdesc.sim.meshes import MeshAssets
from robotdesc.sim.native_log import NativeMessage
from robotdesc.sim.scene import SceneOptions
from robotdesc.sim.variants import COLLISION_MODES, generated_parts, visual_as_collision

log = logging.getLogger(__name__)

#: The papers' figures (001, Table II; Gazebo): RTF with visual meshes, with simple ones.
PAPER_VISUAL_RTF, PAPER_SIMPLE_RTF = 0.2, 1.0
#: Progress is reported each time this much more time is simulated (s).
PROGRESS_SIMULATED = 0.1

#: progress(label, simulated s, total s, wall s so far)
Progress = Callable[[str, float, float, float], None]
#: note(text): a line about what starts now (a variant built, collision generated)
Note = Callable[[str], None]


@dataclass(frozen=True)
class VariantTiming:
    """One collision variant, timed.

    Attributes:
        label: "as-is", "visual" or "generated".
        engine: the engine's name.
        geoms: collision shapes of the robot.
        triangles: triangles the engine collides (MuJoCo: of convex hulls).
        simulated: simulated time (s); steps: time steps taken.
        cpu: CPU time of the process while stepping (s); wall: wall time (s).
        collision_per_step: wall time of one collision pass (s).
        build: wall time spent building the scene (s).
        lowest: the robot's lowest point at the end (m).
        primitives: collision shapes that are primitives.
        messages: what the engine's native code printed (DART's warnings), per kind with
            the links named.
    """

    label: str
    engine: str
    geoms: int
    triangles: int
    simulated: float
    steps: int
    cpu: float
    wall: float
    collision_per_step: float
    build: float
    lowest: float
    primitives: int = 0
    messages: tuple[NativeMessage, ...] = ()

    @property
    def warnings(self) -> int:
        """Native messages printed in all."""
        return sum(m.count for m in self.messages)

    @property
    def rtf_cpu(self) -> float:
        """Simulated seconds per CPU second."""
        return self.simulated / self.cpu if self.cpu > 0 else float("inf")

    @property
    def rtf_wall(self) -> float:
        """Simulated seconds per wall second."""
        return self.simulated / self.wall if self.wall > 0 else float("inf")

    @property
    def step_wall(self) -> float:
        """Wall time per step (s)."""
        return self.wall / self.steps if self.steps else 0.0


@dataclass(frozen=True)
class Comparison:
    """Variants timed in one engine, the first one the reference of the ratios."""

    engine: str
    timestep: float
    variants: tuple[VariantTiming, ...]

    def ratio(self, variant: VariantTiming) -> float:
        """variant's CPU-time RTF / the first variant's."""
        first = self.variants[0].rtf_cpu
        return variant.rtf_cpu / first if first > 0 else float("inf")

    def as_dict(self) -> dict[str, Any]:
        """Every figure, for JSON output."""
        return {"engine": self.engine, "timestep": self.timestep,
                "paper": {"visual_rtf": PAPER_VISUAL_RTF, "simple_rtf": PAPER_SIMPLE_RTF,
                          "ratio": PAPER_SIMPLE_RTF / PAPER_VISUAL_RTF},
                "variants": [{"label": v.label, "geoms": v.geoms, "triangles": v.triangles,
                              "simulated_s": v.simulated, "steps": v.steps, "cpu_s": v.cpu,
                              "wall_s": v.wall, "rtf_cpu": v.rtf_cpu, "rtf_wall": v.rtf_wall,
                              "collision_per_step_s": v.collision_per_step,
                              "step_wall_s": v.step_wall, "build_s": v.build,
                              "lowest_m": v.lowest, "ratio_to_first": self.ratio(v),
                              "primitives": v.primitives,
                              "native_messages": [{"text": m.text, "count": m.count,
                                                   "links": dict(m.links)}
                                                  for m in v.messages]}
                             for v in self.variants]}


def parse_variants(text: str) -> tuple[str, ...]:
    """"visual,generated" -> ("visual", "generated").

    Raises:
        SimOptionError: an unknown variant, or fewer than one.
    """
    variants = tuple(part.strip() for part in text.split(",") if part.strip())
    unknown = [v for v in variants if v not in COLLISION_MODES]
    if not variants or unknown:
        raise SimOptionError("compare", text, f"--compare takes a comma-separated list of "
                             f"{', '.join(COLLISION_MODES)}"
                             + (f"; unknown: {', '.join(unknown)}" if unknown else ""))
    return variants


def build_variant(engine: Engine, robot: Robot, meshes: MeshAssets, label: str,
                  options: SceneOptions, hold: HoldOptions = HoldOptions(),
                  generate_method: str = DEFAULT_METHOD,
                  package_map: Sequence[tuple[str, str]] = (),
                  parts: Mapping[str, Sequence[Any]] | None = None,
                  generate: Mapping[str, Any] | None = None) -> EngineScene:
    """The scene with one collision variant (`parts`: generated collision, made when None
    with `generate_method` and the `generate_collision` options in `generate`)."""
    if label == "visual":
        robot = visual_as_collision(robot)
    elif label == "generated":
        if parts is None:
            parts = generated_parts(robot, method=generate_method, package_map=package_map,
                                    **(generate or {}))
        return engine.build(robot, meshes, options, hold, parts)
    return engine.build(robot, meshes, options, hold)


def time_scene(scene: EngineScene, label: str, seconds: float, build: float = 0.0,
               progress: Progress | None = None, collision_passes: int = 5) -> VariantTiming:
    """Step a (reset) scene for `seconds` of simulated time and time it."""
    scene.reset()
    steps = max(1, round(seconds / scene.timestep))
    chunk = max(1, min(steps, round(0.01 / scene.timestep)))  # 10 ms of simulated time
    every = max(1, round(PROGRESS_SIMULATED / scene.timestep))
    wall_start, cpu_start = time.perf_counter(), time.process_time()
    done = 0
    while done < steps:
        count = min(chunk, steps - done, every - done % every)
        scene.step(count)
        done += count
        if progress is not None and (done % every == 0 or done == steps):
            progress(label, done * scene.timestep, steps * scene.timestep,
                     time.perf_counter() - wall_start)
    wall, cpu = time.perf_counter() - wall_start, time.process_time() - cpu_start
    passes = [scene.collision_seconds() for _ in range(collision_passes)]
    timing = VariantTiming(label, scene.engine, scene.geoms, scene.triangles,
                           steps * scene.timestep, steps, cpu, wall,
                           sum(passes) / len(passes), build, scene.lowest_point(),
                           scene.primitives, scene.native_messages())
    log.info("%s %s: RTF %.3g (CPU) %.3g (wall), %d triangles", scene.engine, label,
             timing.rtf_cpu, timing.rtf_wall, timing.triangles)
    return timing


def compare_variants(engine: Engine, robot: Robot, meshes: MeshAssets,
                     variants: Sequence[str], options: SceneOptions, seconds: float,
                     hold: HoldOptions = HoldOptions(), generate_method: str = DEFAULT_METHOD,
                     package_map: Sequence[tuple[str, str]] = (),
                     progress: Progress | None = None, note: Note | None = None,
                     generate: Mapping[str, Any] | None = None) -> Comparison:
    """Time each collision variant in `engine`, one after the other, in this process
    (`note` gets a line as each variant starts and ends)."""
    timings = []
    for number, label in enumerate(variants, 1):
        started = time.perf_counter()
        if note is not None:
            what = f" (collision generated: method {generate_method})" \
                if label == "generated" else ""
            note(f"variant {number} of {len(variants)}: {label}{what}, building the scene")
        if progress is not None:  # a new variant: nothing simulated yet
            progress(label, 0.0, seconds, 0.0)
        generating = dict(generate or {})
        if note is not None and label == "generated":
            generating["progress"] = _generation_notes(note)
        scene = build_variant(engine, robot, meshes, label, options, hold, generate_method,
                              package_map, generate=generating)
        built = time.perf_counter() - started
        if note is not None:
            note(f"{label}: {scene.triangles:,} triangles, {scene.primitives} primitives, "
                 f"built in {built:.1f} s; simulating {seconds:g} s")
        timing = time_scene(scene, label, seconds, built, progress)
        timings.append(timing)
        if note is not None:
            note(f"{label}: RTF {timing.rtf_cpu:.3g} by CPU time, {timing.rtf_wall:.3g} by "
                 f"wall time, {timing.warnings} engine warnings")
    return Comparison(engine.name, options.timestep, tuple(timings))


#: While collision is generated, a line at most this often (wall s).
GENERATION_NOTE_PERIOD = 5.0


def _generation_notes(note: Note) -> Callable[[int, int, str], None]:
    """A `generate_collision` progress callback writing a note at most every few seconds."""
    last = [time.perf_counter()]

    def progress(done: int, total: int, link: str) -> None:
        now = time.perf_counter()
        if done == total or now - last[0] >= GENERATION_NOTE_PERIOD:
            last[0] = now
            note(f"generated: collision of {done} of {total} links made"
                 + (f" ({link})" if link else ""))
    return progress
