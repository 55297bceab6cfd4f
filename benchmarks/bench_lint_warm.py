"""What a user waits for when linting: warm and cold `robotdesc lint`, against the bare
interpreter and the xacro CLI, in one run (issue 31, items 2 and 3).

Every figure is the median wall time of whole processes, interleaved (one round times every
command once, so a change of the machine's load hits every figure alike), measured beside:

- `python -c pass`: the bare interpreter (the floor of any Python command);
- the xacro CLI on TIAGo (benchmarks/corpus/xacro_find.py: xacro's own command with `$(find)`
  answered from the case's package folders), when the corpus case `tiago_default` is there.

For each robotdesc source folder given (`--src`, e.g. an older checkout's src to compare
before and after in one run; default: this checkout's):

- Engineer warm: `robotdesc lint robots/engineer_description/urdf/engineer.urdf.xacro` (its
  three config variants) with the caches filled by an untimed run;
- TIAGo cold (`--no-cache`) and warm lint.

"Warm" is what a user gets from the third identical run on: the replay of the last one
(commands/lint_replay.py). "From the result cache" is a warm run that cannot be a replay (its
environment differs in one variable each round, as after a new shell): the second run after
a change, read from the whole-result cache.

The processes keep compiled bytecode in a scratch folder (PYTHONPYCACHEPREFIX) and drop
PYTHONDONTWRITEBYTECODE, as a wheel install has it; each source gets its own cache folder.
Aims (issue 31): Engineer warm <= 6x the interpreter; TIAGo warm <= 0.3x and cold <= 2x the
xacro CLI.

Usage: python benchmarks/bench_lint_warm.py [--repeat N] [--src DIR ...] [--corpus DIR]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
ENGINEER = REPO / "robots" / "engineer_description" / "urdf" / "engineer.urdf.xacro"
sys.path.insert(0, str(HERE / "corpus"))

import run_corpus  # noqa: E402  (benchmarks/corpus/run_corpus.py)


def wall_time(command: list[str], env: dict[str, str]) -> float:
    start = time.perf_counter()
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env,
                          cwd=REPO)
    elapsed = time.perf_counter() - start
    if done.returncode not in (0, 1):
        raise SystemExit(f"{' '.join(command)} failed ({done.returncode}):\n"
                         f"{done.stderr.decode()[-2000:]}")
    return elapsed


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--cold-repeat", type=int, default=7)  # at most --repeat; cold runs vary most
    parser.add_argument("--src", action="append", default=[])
    parser.add_argument("--corpus", type=Path, default=Path("/work/corpus"))
    options = parser.parse_args()
    sources = options.src or [str(REPO / "src")]
    manifest = run_corpus.load_manifest(run_corpus.DEFAULT_MANIFEST)
    tiago = next(c for c in manifest.cases if c.name == "tiago_default")
    have_tiago = run_corpus.top_file(tiago, options.corpus).is_file()
    with tempfile.TemporaryDirectory(prefix="robotdesc-bench-") as scratch:
        base = dict(os.environ, PYTHONPYCACHEPREFIX=str(Path(scratch) / "pycache"))
        base.pop("PYTHONDONTWRITEBYTECODE", None)
        commands: dict[str, tuple[list[str], dict[str, str]]] = {
            "python -c pass": ([sys.executable, "-c", "pass"], base)}
        if have_tiago:
            commands["xacro CLI, TIAGo"] = (run_corpus.xacro_command(
                tiago, options.corpus, Path(scratch) / "xacro.urdf"), base)
        cold: dict[str, tuple[list[str], dict[str, str]]] = {}
        for number, src in enumerate(sources):
            env = dict(base, PYTHONPATH=src, ROBOTDESC_CACHE_DIR=str(Path(scratch) / str(number)))
            engineer = [sys.executable, "-m", "robotdesc", "lint", str(ENGINEER)]
            commands[f"{src}: Engineer warm"] = (engineer, env)
            commands[f"{src}: Engineer result cache"] = (engineer, env)
            if have_tiago:
                lint = run_corpus.robotdesc_command("lint", tiago, options.corpus)
                commands[f"{src}: TIAGo warm"] = (lint, env)
                commands[f"{src}: TIAGo result cache"] = (lint, env)
                cold[f"{src}: TIAGo cold"] = (lint + ["--no-cache"], env)
        for command, env in [*commands.values(), *cold.values()]:  # fill caches, compile
            wall_time(command, env)
        times: dict[str, list[float]] = {name: [] for name in [*commands, *cold]}
        for round_ in range(options.repeat):
            for name, (command, env) in commands.items():
                if name.endswith("result cache"):  # another environment: never a replay
                    env = dict(env, ROBOTDESC_BENCH_ROUND=str(round_))
                times[name].append(wall_time(command, env))
            if round_ < options.cold_repeat:
                for name, (command, env) in cold.items():
                    times[name].append(wall_time(command, env))
    median = {name: statistics.median(values) for name, values in times.items()}
    bare = median["python -c pass"]
    xacro = median.get("xacro CLI, TIAGo")
    print(f"{'python -c pass (baseline)':44s} {bare:7.3f} s")
    if xacro:
        print(f"{'xacro CLI, TIAGo (baseline)':44s} {xacro:7.3f} s")
    else:
        print(f"TIAGo not found under {options.corpus} (benchmarks/corpus/run_corpus.py "
              "--extract-only): Engineer only")
    for src in sources:
        print(f"source: {src}")
        for kind in ("warm", "result cache"):
            value = median[f"{src}: Engineer {kind}"]
            print(f"  {'Engineer lint, ' + kind + ' (3 variants)':42s} {value:7.3f} s   "
                  f"{value / bare:5.2f}x interpreter (aim <= 6)")
        if xacro:
            for kind, aim in (("warm", 0.3), ("result cache", 0.3), ("cold", 2.0)):
                value = median[f"{src}: TIAGo {kind}"]
                print(f"  {'TIAGo lint, ' + kind:42s} {value:7.3f} s   "
                      f"{value / xacro:5.2f}x xacro CLI (aim <= {aim})")


if __name__ == "__main__":
    main()
