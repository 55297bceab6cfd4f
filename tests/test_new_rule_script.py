"""scripts/new_rule.py scaffolds a rule that imports, registers and carries its three-part docs."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def test_the_scaffold_writes_a_rule_a_fixture_and_a_test(tmp_path: Path) -> None:
    for part in ("src/robotdesc/rules", "tests/rules/fixtures"):
        (tmp_path / part).mkdir(parents=True)
    done = subprocess.run([sys.executable, str(REPO / "scripts" / "new_rule.py"), "J199",
                           "joint-scaffolded", "--family", "joints", "--root", str(tmp_path)],
                          capture_output=True, text=True, check=True)
    assert "catalog.py" in done.stdout
    module = tmp_path / "src/robotdesc/rules/joint_scaffolded.py"
    text = module.read_text()
    assert '@rule("J199", "joint-scaffolded", family=FAMILY' in text
    assert "Why is this bad?" in text and "Use instead:" in text
    assert "expect: J199" in (tmp_path / "tests/rules/fixtures/joints/joint_scaffolded.urdf").read_text()
    assert (tmp_path / "tests/rules/test_joint_scaffolded.py").is_file()
    compile(text, str(module), "exec")
