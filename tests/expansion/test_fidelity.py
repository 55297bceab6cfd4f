"""robotdesc's expansion is xacro's: the same document as the plain xacro package produces.

The worker patches xacro (line tags, call chains, a linear-time `replace_node`); once the
provenance attribute is stripped, the output must be byte-identical to plain xacro's.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from robotdesc.expansion import ExpandOptions, expand_file
from robotdesc.source import strip_provenance

HERE = Path(__file__).parent
REPO = HERE.parents[1]
CASES = [
    (HERE / "fixtures" / "features" / "features.urdf.xacro", {}),
    (HERE / "fixtures" / "features" / "features.urdf.xacro", {"with_tool": "false"}),
    (REPO / "benchmarks" / "data" / "crawler_212.urdf.xacro", {"main_wheels": "9", "flipper_wheels": "4"}),
]


def _plain_xacro(path: Path, args: dict[str, str]) -> bytes:
    script = ("import sys, xacro\n"
              "doc = xacro.process_file(sys.argv[1], mappings=dict(a.split(':=', 1) for a in sys.argv[2:]))\n"
              "sys.stdout.buffer.write(doc.documentElement.toxml().encode('utf-8'))\n")
    done = subprocess.run([sys.executable, "-c", script, str(path),
                           *(f"{k}:={v}" for k, v in args.items())],
                          capture_output=True, check=True, timeout=120)
    return done.stdout


@pytest.mark.parametrize("path, args", CASES, ids=lambda c: str(c)[-40:] if isinstance(c, Path) else str(c))
def test_output_matches_plain_xacro(path, args):
    ours = expand_file(path, args, options=ExpandOptions(use_cache=False))
    assert strip_provenance(ours.xml) == _plain_xacro(path, args)
