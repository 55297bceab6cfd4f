"""robotdesc's expansion is xacro's: the same document as the plain xacro package produces.

The worker patches xacro (line tags, call chains, a linear-time `replace_node`); once the
provenance attribute is stripped, the output must be byte-identical to plain xacro's.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
import xacro

from robotdesc.expansion import ExpandOptions, expand_file, hooks
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


@pytest.mark.parametrize("text", ["", "plain", "a b\n  c", "$", "$$", "x$", "$x", "${1+2}",
                                  "$(arg a)", "$${x}", "a ${1} b", "$$(x)",
                                  "0:12;1:3*2|link.name@0:4"])
def test_the_eval_text_shortcut_answers_as_xacro_does(text):
    symbols = xacro.Table()
    quick = hooks.plain_text_first(xacro.eval_text)
    try:
        expected = xacro.eval_text(text, symbols)
    except Exception as exc:  # noqa: BLE001 -- the same failure either way
        with pytest.raises(type(exc)):
            quick(text, symbols)
        return
    assert quick(text, symbols) == expected
    assert type(quick(text, symbols)) is type(expected)


def test_an_expression_compiled_once_evaluates_with_each_call_s_symbols():
    compile_ = hooks.compiling_once(compile)
    first = compile_("a + 1", "<expression>", "eval")
    assert compile_("a + 1", "<expression>", "eval") is first
    assert eval(first, {"a": 1}) == 2 and eval(first, {"a": 41}) == 42
    with pytest.raises(SyntaxError):
        compile_("a +", "<expression>", "eval")
    with pytest.raises(SyntaxError):  # not kept: fails again
        compile_("a +", "<expression>", "eval")
