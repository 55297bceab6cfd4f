"""Expansion speed on the real corpus (issue 13, item 9): robotdesc against the xacro CLI.

For every case of benchmarks/corpus/manifest.toml that both tools expand, three whole-process
timings, each the median of --repeat runs, measured in this run:

- baseline: the PyPI xacro command (benchmarks/corpus/xacro_find.py: xacro's own CLI with
            `$(find)` answered from the case's package folders), output to a file;
- cold:     `robotdesc expand FILE --package-path ... --no-cache -o OUT` (default sandbox);
- warm:     the same without --no-cache, the expansion cache filled by a previous run.

Printed: per-case seconds and ratios, then the corpus' medians: the median of the per-case
ratios (the aim's measure) and the ratio of the median times. Aims (issue 13): cold <= 1.5 x
the xacro CLI, warm <= 0.25 x.

The corpus is extracted first if needed (see docs/corpus.md). Both commands run with the same
interpreter (sys.executable), so neither pays for a launcher shim the other does not, and with
compiled bytecode kept in a scratch folder (PYTHONPYCACHEPREFIX), as a wheel install has it:
--no-bytecode-cache keeps an environment's PYTHONDONTWRITEBYTECODE=1, under which robotdesc's
modules are compiled again in every process. Each case gets one untimed run of each tool first.

Usage: python benchmarks/bench_corpus.py [--repeat N] [--only SUBSTR ...] [--corpus DIR]
                                         [--fetch-root DIR]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent / "corpus"))

import run_corpus  # noqa: E402  (benchmarks/corpus/run_corpus.py)


@dataclass
class Timing:
    case: str
    xacro: float
    cold: float
    warm: float


def time_case(case: run_corpus.Case, corpus: Path, env: dict[str, str], out_dir: Path,
              repeat: int) -> Timing | str:
    """Median timings of one case, or why it was not timed (a tool did not expand it)."""
    xacro_cmd = run_corpus.xacro_command(case, corpus, out_dir / "xacro.urdf")
    expand = run_corpus.robotdesc_command("expand", case, corpus)
    expand += ["-o", str(out_dir / "robotdesc.urdf")]
    run_corpus.warm_up(xacro_cmd, expand, env, corpus)
    xacro = run_corpus.median_run(xacro_cmd, env, corpus, repeat)
    if not xacro.ok:
        return "xacro: " + run_corpus.first_line(xacro.stderr)
    cold = run_corpus.median_run(expand + ["--no-cache"], env, corpus, repeat)
    run_corpus.run(expand, env, corpus)  # fill the cache
    warm = run_corpus.median_run(expand, env, corpus, repeat)
    for label, result in (("cold", cold), ("warm", warm)):
        if not result.ok:
            message = run_corpus.first_line(result.stderr)
            return f"robotdesc ({label}, exit {result.code}): {message}"
    return Timing(case.name, xacro.seconds, cold.seconds, warm.seconds)


def interpreter_floor(env: dict[str, str], cwd: Path, repeat: int) -> float:
    """The start-up and exit of the interpreter alone: no Python command goes below it."""
    return run_corpus.median_run([sys.executable, "-c", "pass"], env, cwd, max(repeat, 5)).seconds


def report(timings: list[Timing], skipped: list[str], floor: float) -> None:
    """Per-case figures, then the medians; `skipped` holds "case: reason" lines."""
    heads = ("xacro s", "cold s", "warm s")
    columns = " ".join(f"{h:>8s}" for h in heads)
    print(f"{'case':34s} {columns} {'cold/x':>7s} {'warm/x':>7s}")
    for t in timings:
        print(f"{t.case:34s} {t.xacro:8.3f} {t.cold:8.3f} {t.warm:8.3f} "
              f"{t.cold / t.xacro:7.2f} {t.warm / t.xacro:7.2f}")
    if skipped:
        print("\nnot timed:\n  " + "\n  ".join(skipped))
    if not timings:
        return
    xacro = statistics.median(t.xacro for t in timings)
    cold = statistics.median(t.cold for t in timings)
    warm = statistics.median(t.warm for t in timings)
    cold_ratio = statistics.median(t.cold / t.xacro for t in timings)
    warm_ratio = statistics.median(t.warm / t.xacro for t in timings)
    print(f"\n{len(timings)} cases, whole processes, medians:")
    print(f"{'xacro CLI (baseline)':32s} {xacro:7.3f} s")
    print(f"{'robotdesc expand --no-cache':32s} {cold:7.3f} s   median ratio {cold_ratio:5.2f} "
          f"(ratio of medians {cold / xacro:5.2f}; aim <= 1.50)")
    print(f"{'robotdesc expand, warm cache':32s} {warm:7.3f} s   median ratio {warm_ratio:5.2f} "
          f"(ratio of medians {warm / xacro:5.2f}; aim <= 0.25)")
    print(f"{'python -c pass (floor)':32s} {floor:7.3f} s   = "
          f"{floor / xacro:4.2f} x the median xacro run")
    above = [t for t in timings if t.xacro > floor]
    if above:
        cold_above = statistics.median((t.cold - floor) / (t.xacro - floor) for t in above)
        warm_above = statistics.median((t.warm - floor) / (t.xacro - floor) for t in above)
        print(f"time above the floor, median ratios: cold {cold_above:5.2f}, "
              f"warm {warm_above:5.2f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--only", action="append", default=[],
                        help="cases whose name contains this (repeatable)")
    parser.add_argument("--manifest", type=Path, default=run_corpus.DEFAULT_MANIFEST)
    parser.add_argument("--corpus", type=Path, default=Path("/work/corpus"))
    parser.add_argument("--fetch-root", type=Path, default=Path("/work/.mirror"))
    parser.add_argument("--no-bytecode-cache", action="store_true",
                        help="keep the environment's PYTHONDONTWRITEBYTECODE (robotdesc's "
                             "modules are then compiled in every process)")
    options = parser.parse_args()

    manifest = run_corpus.load_manifest(options.manifest)
    corpus = options.corpus.resolve()
    run_corpus.extract_all(manifest.commits, options.fetch_root, corpus)
    timings, skipped = [], []
    floor_env = run_corpus.process_env(Path(tempfile.gettempdir()))
    floor = interpreter_floor(floor_env, corpus, options.repeat)
    with tempfile.TemporaryDirectory(prefix="robotdesc-bench-corpus-") as scratch:
        out_dir = Path(scratch)
        env = run_corpus.process_env(out_dir, not options.no_bytecode_cache)
        for case in run_corpus.select(manifest.cases, options.only):
            timing = time_case(case, corpus, env, out_dir, options.repeat)
            if isinstance(timing, str):
                skipped.append(f"{case.name}: {timing}")
            else:
                timings.append(timing)
            print(f"{case.name}: {timing if isinstance(timing, str) else 'timed'}", file=sys.stderr)
    report(timings, skipped, floor)


if __name__ == "__main__":
    main()
