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
    module = tmp_path / "src/robotdesc/rules/joints.py"  # the family has no module yet
    text = module.read_text()
    assert '@rule("J199", "joint-scaffolded", family=FAMILY' in text
    assert "Why is this bad?" in text and "Use instead:" in text
    assert "expect: J199" in (tmp_path / "tests/rules/fixtures/joints/joint_scaffolded.urdf").read_text()
    assert (tmp_path / "tests/rules/test_joint_scaffolded.py").is_file()
    compile(text, str(module), "exec")


def test_a_rule_goes_into_its_familys_module_with_its_fix(tmp_path: Path) -> None:
    rules = tmp_path / "src/robotdesc/rules"
    rules.mkdir(parents=True)
    (tmp_path / "tests/rules/fixtures").mkdir(parents=True)
    for name in ("joints", "inertia", "fixes"):
        (rules / f"{name}.py").write_text((REPO / "src/robotdesc/rules" / f"{name}.py").read_text())
    done = subprocess.run([sys.executable, str(REPO / "scripts" / "new_rule.py"), "J199",
                           "joint-scaffolded", "--family", "joints", "--fix", "safe",
                           "--root", str(tmp_path)], capture_output=True, text=True, check=True)
    assert "catalog.py" not in done.stdout and "ValueChange" in done.stdout
    text = (rules / "joints.py").read_text()
    assert text.startswith((REPO / "src/robotdesc/rules/joints.py").read_text().rstrip("\n"))
    assert '@rule("J199", "joint-scaffolded", family=FAMILY' in text
    compile(text, "joints.py", "exec")
    fixes = (rules / "fixes.py").read_text()
    assert '    "J107": Applicability.SAFE,    # the same axis at unit length\n    "J199": ' \
        'Applicability.SAFE,\n    "M102"' in fixes
    compile(fixes, "fixes.py", "exec")
    assert not (rules / "joint_scaffolded.py").exists()
    several = subprocess.run([sys.executable, str(REPO / "scripts" / "new_rule.py"), "I299",
                              "inertia-scaffolded", "--family", "inertia", "--root",
                              str(tmp_path)], capture_output=True, text=True, check=True)
    assert "inertia.py" in several.stdout
