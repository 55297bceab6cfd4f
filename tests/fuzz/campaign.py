"""The fuzzing campaign: seeds, mutants, commands, and the tally.

Seeds are the bundled Engineer (its expanded URDF, and for a share of the mutants one of its
xacro sources) and example-robot-data robots when that is installed. Used by the bounded test
in the default suite, the slow test and `tests/fuzz/run_campaign.py`.
"""

from __future__ import annotations

import collections
import logging
import os
import random
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

from fuzz.harness import FUZZ_PACKAGE, Outcome, pick_command, prepare_case, run_case
from fuzz.mutate import Mutant, mutate

log = logging.getLogger(__name__)

REPO = Path(__file__).resolve().parents[2]
ENGINEER = REPO / "robots" / "engineer_description"
#: example-robot-data robots used as seeds (relative to its robots/ folder).
ERD_SEEDS = ("solo_description/robots/solo12.urdf", "panda_description/urdf/panda.urdf",
             "ur_description/urdf/ur5_robot.urdf")


@dataclass(frozen=True)
class Seed:
    """A description to mutate.

    Attributes:
        name: a short name.
        data: its bytes.
        package_paths: folders to pass as --package-path.
        xacro_package: for a xacro seed, the package folder to copy (the mutant replaces
            `relative`), else None.
        relative: the seed's path inside `xacro_package`.
    """

    name: str
    data: bytes
    package_paths: tuple[str, ...]
    xacro_package: Path | None = None
    relative: str = ""


@dataclass
class Tally:
    """Counts of a campaign."""

    seed: int
    mutants: int = 0
    runs: int = 0
    exits: collections.Counter = field(default_factory=collections.Counter)
    commands: collections.Counter = field(default_factory=collections.Counter)
    kinds: collections.Counter = field(default_factory=collections.Counter)
    tracebacks: int = 0
    hangs: int = 0
    written_outside: int = 0
    subprocess_runs: int = 0
    failures: list[tuple[str, str, Outcome, Path | None]] = field(default_factory=list)
    seconds: float = 0.0
    command_seconds: collections.Counter = field(default_factory=collections.Counter)

    def add(self, kind: str, outcome: Outcome, kept: Path | None) -> None:
        self.runs += 1
        self.command_seconds[outcome.command] += outcome.seconds
        self.commands[outcome.command] += 1
        self.exits[str(outcome.exit_code)] += 1
        self.tracebacks += any("Traceback" in p or "internal error" in p or "bug" in p
                               for p in outcome.problems)
        self.hangs += outcome.exit_code is None
        self.written_outside += bool(outcome.written_outside)
        if not outcome.ok:
            self.failures.append((kind, outcome.command, outcome, kept))

    def summary(self) -> str:
        exits = ", ".join(f"{code}: {n}" for code, n in sorted(self.exits.items()))
        commands = ", ".join(f"{c}: {n} ({self.command_seconds[c] / n:.1f} s each)"
                             for c, n in sorted(self.commands.items()))
        return (f"seed {self.seed}: {self.mutants} mutants, {self.runs} runs "
                f"({self.subprocess_runs} as subprocesses) in {self.seconds:.0f} s\n"
                f"  exit codes: {exits}\n  commands: {commands}\n"
                f"  failures: {len(self.failures)} (exit 3 or other: "
                f"{sum(1 for f in self.failures if f[2].exit_code not in (0, 1, 2, None))}, "
                f"tracebacks/internal errors: {self.tracebacks}, hangs: {self.hangs}, "
                f"written outside the output folder: {self.written_outside})")


def example_robot_data_share() -> Path | None:
    """The folder holding the example-robot-data package (its package.xml), if installed."""
    from support import example_robot_data_dir

    robots = example_robot_data_dir()
    return robots.parent if robots else None


def seeds(expanded_engineer: bytes | None = None, *, with_xacro: bool = True) -> list[Seed]:
    """The seeds available here."""
    robots_dir = str(REPO / "robots")
    found = []
    if expanded_engineer is None:
        expanded_engineer = expand_engineer()
    found.append(Seed("engineer.urdf", expanded_engineer, (robots_dir,)))
    if with_xacro:
        for relative in ("urdf/engineer.urdf.xacro", "urdf/arm.xacro", "urdf/gripper.xacro",
                         "urdf/inertials.generated.xacro"):
            found.append(Seed(f"engineer:{relative}", (ENGINEER / relative).read_bytes(),
                              (), ENGINEER, relative))
    share = example_robot_data_share()
    if share is not None:
        parent = str(share.parent)
        for relative in ERD_SEEDS:
            path = share / "robots" / relative
            if path.is_file():
                found.append(Seed(path.name, path.read_bytes(), (parent,)))
    return found


def expand_engineer() -> bytes:
    """The Engineer's expanded URDF (without robotdesc's private attributes)."""
    from robotdesc.expansion import expand_file
    from robotdesc.model.write import urdf_text

    expanded = expand_file(ENGINEER / "urdf" / "engineer.urdf.xacro")
    return urdf_text(expanded.xml, expanded.source)


def _link_tree(source: Path, target: Path) -> None:
    """Copy a package folder by hard links (copies where links fail); meshes are shared."""
    def link(src: str, dst: str) -> None:
        try:
            os.link(src, dst)
        except OSError:
            shutil.copy2(src, dst)
    shutil.copytree(source, target, copy_function=link)


def run_one(seed: Seed, mutant: Mutant, command: str, root: Path, *, subprocess_run: bool,
            timeout_s: float) -> Outcome:
    """Prepare the case folder for `mutant` of `seed` and run `command` on it."""
    if seed.xacro_package is None:
        target = prepare_case(root, mutant)
        return run_case(root, command, target, list(seed.package_paths),
                        timeout_s=timeout_s, subprocess_run=subprocess_run)
    prepare_case(root, Mutant(mutant.kind, b"", mutant.mesh), name="unused")
    package = root / "case" / seed.xacro_package.name
    _link_tree(seed.xacro_package, package)
    target = package / seed.relative
    target.unlink()
    target.write_bytes(mutant.data.replace(b"package://" + FUZZ_PACKAGE.encode(),
                                           b"package://" + FUZZ_PACKAGE.encode()))
    top = package / "urdf" / "engineer.urdf.xacro"
    return run_case(root, command, top, [], timeout_s=timeout_s,
                    subprocess_run=subprocess_run)


def campaign(count: int, seed: int, *, commands: list[str] | None = None,
             seed_list: list[Seed] | None = None, xacro_share: float = 0.1,
             subprocess_every: int = 0, timeout_s: float = 120.0,
             keep_dir: Path | None = None, progress: bool = False) -> Tally:
    """Run `count` mutants, each through one command drawn by weight.

    Args:
        count: number of mutants.
        seed: the random seed (the same seed gives the same mutants and commands).
        commands: the commands to draw from (default: all of `harness.COMMANDS`).
        seed_list: the seeds (default: `seeds()`).
        xacro_share: fraction of mutants made from a xacro source (slower: a worker each).
        subprocess_every: run every n-th case as a subprocess (0: never).
        timeout_s: a run longer than this is a hang.
        keep_dir: copy the case folder of each failure here.
        progress: print a line every 100 mutants.
    """
    rng = random.Random(seed)
    seed_list = seed_list if seed_list is not None else seeds()
    plain = [s for s in seed_list if s.xacro_package is None]
    xacro = [s for s in seed_list if s.xacro_package is not None]
    tally = Tally(seed)
    started = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="robotdesc-fuzz-") as scratch:
        for index in range(count):
            use_xacro = xacro and rng.random() < xacro_share
            chosen = rng.choice(xacro if use_xacro else plain)
            mutant = mutate(chosen.data, rng)
            command = pick_command(rng, commands)
            root = Path(scratch) / f"m{index:05d}"
            as_subprocess = bool(subprocess_every) and index % subprocess_every == 0
            outcome = run_one(chosen, mutant, command, root, subprocess_run=as_subprocess,
                              timeout_s=timeout_s)
            tally.mutants += 1
            tally.subprocess_runs += as_subprocess
            tally.kinds[mutant.kind.split("+")[0].split(":")[0]] += 1
            kept = None
            if not outcome.ok and keep_dir is not None:
                kept = keep_dir / f"{seed}-{index:05d}-{chosen.name.replace('/', '_')}"
                shutil.copytree(root, kept, dirs_exist_ok=True)
                (kept / "FAILURE.txt").write_text(
                    f"{command}: {'; '.join(outcome.problems)}\n{outcome.output}\n")
            tally.add(mutant.kind, outcome, kept)
            shutil.rmtree(root, ignore_errors=True)
            if progress and (index + 1) % 100 == 0:
                print(f"{index + 1}/{count} mutants, {len(tally.failures)} failures, "
                      f"{time.monotonic() - started:.0f} s", file=sys.stderr, flush=True)
    tally.seconds = time.monotonic() - started
    return tally
