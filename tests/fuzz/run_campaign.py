"""Run the fuzzing campaign from the command line and print its seed and counts.

    python tests/fuzz/run_campaign.py --count 5000 --seed 20 --keep /tmp/fuzz-failures

Exit status 1 when any run failed (exit 3, a traceback, a hang or a file written outside the
output folder); the failing cases are copied to --keep for minimising.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # tests/: `fuzz`, `support`

from fuzz.campaign import campaign  # noqa: E402
from fuzz.harness import COMMANDS  # noqa: E402


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=5000)
    parser.add_argument("--seed", type=int, default=20)
    parser.add_argument("--commands", help=f"comma-separated subset of {', '.join(COMMANDS)}")
    parser.add_argument("--xacro-share", type=float, default=0.05)
    parser.add_argument("--subprocess-every", type=int, default=50)
    parser.add_argument("--timeout", type=float, default=120.0)
    parser.add_argument("--keep", type=Path, help="copy failing cases here")
    ns = parser.parse_args()
    import os
    import tempfile

    os.environ.setdefault("ROBOTDESC_CACHE_DIR", tempfile.mkdtemp(prefix="robotdesc-cache-"))
    tally = campaign(ns.count, ns.seed, commands=ns.commands.split(",") if ns.commands else None,
                     xacro_share=ns.xacro_share, subprocess_every=ns.subprocess_every,
                     timeout_s=ns.timeout, keep_dir=ns.keep, progress=True)
    print(tally.summary())
    print("  mutations: " + ", ".join(f"{k}: {n}" for k, n in sorted(tally.kinds.items())))
    for kind, command, outcome, kept in tally.failures[:50]:
        first = outcome.output.strip().splitlines()[-1:] or [""]
        print(f"  FAIL {command} {kind}: {'; '.join(outcome.problems)} | {first[0][:200]}"
              + (f" | {kept}" if kept else ""))
    return 1 if tally.failures else 0


if __name__ == "__main__":
    sys.exit(main())
