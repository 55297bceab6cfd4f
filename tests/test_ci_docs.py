"""docs/ci.md: its workflow files are valid YAML, invoke robotdesc commands that exist (each
is parsed by robotdesc's own argument parser, then run on the workspace fixture) and hand
the reports they write to the CI systems."""

from __future__ import annotations

import json
import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import jsonschema
import pytest
import yaml

from robotdesc.cli import build_parser

REPO = Path(__file__).resolve().parents[1]
DOC = (REPO / "docs" / "ci.md").read_text(encoding="utf-8")
WORKSPACE = REPO / "tests" / "fixtures" / "ci_workspace"
KNOWN_ACTIONS = {"actions/checkout", "actions/setup-python", "actions/cache",
                 "github/codeql-action/upload-sarif"}


def yaml_blocks() -> list[dict]:
    return [yaml.safe_load(block) for block in re.findall(r"```yaml\n(.*?)```", DOC, re.DOTALL)]


def workflow(kind: str) -> dict:
    for block in yaml_blocks():
        if kind == "github" and "jobs" in block:
            return block
        if kind == "gitlab" and "robotdesc" in block:
            return block["robotdesc"]
        if kind == "pre-commit" and "repos" in block:
            return block
    raise AssertionError(f"no {kind} YAML block in docs/ci.md")


def robotdesc_commands(lines: list[str]) -> list[list[str]]:
    """The robotdesc command lines, cut at the first shell operator."""
    commands = []
    for line in lines:
        words = shlex.split(line)
        if words and words[0] == "robotdesc":
            ends = [i for i, w in enumerate(words) if w in ("||", "&&", ";", "|")]
            commands.append(words[1:ends[0] if ends else None])
    return commands


def github_commands() -> list[list[str]]:
    steps = workflow("github")["jobs"]["lint"]["steps"]
    return robotdesc_commands([s["run"] for s in steps if "run" in s])


def run(argv: list[str], cwd: Path) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(REPO / "src"), NO_COLOR="1")
    return subprocess.run([sys.executable, "-m", "robotdesc", *argv], cwd=cwd, env=env,
                          capture_output=True, text=True, check=False)


def test_every_yaml_block_parses() -> None:
    assert len(yaml_blocks()) == 3


def test_github_workflow_structure() -> None:
    document = workflow("github")
    triggers = document.get("on", document.get(True))  # YAML 1.1 reads `on` as true
    assert "pull_request" in triggers
    assert document["permissions"]["security-events"] == "write"
    steps = document["jobs"]["lint"]["steps"]
    assert all(("uses" in s) != ("run" in s) for s in steps)
    for step in steps:
        if "uses" in step:
            action, _, version = step["uses"].partition("@")
            assert action in KNOWN_ACTIONS and re.fullmatch(r"v\d+", version)
    assert any(s.get("run", "").startswith('python -m pip install "git+https://') for s in steps)
    upload = next(s for s in steps if s.get("uses", "").startswith("github/codeql-action"))
    sarif_out = next(c for c in github_commands() if "sarif" in c)
    assert upload["with"]["sarif_file"] == sarif_out[sarif_out.index("--output-file") + 1]


def test_gitlab_job_reports_the_files_it_writes() -> None:
    job = workflow("gitlab")
    written = {c[c.index("--format") + 1]: c[c.index("--output-file") + 1]
               for c in robotdesc_commands(job["script"])}
    assert job["artifacts"]["reports"] == {"junit": written["junit"],
                                           "codequality": written["gitlab"]}
    assert job["artifacts"]["when"] == "always"


def test_precommit_snippet_names_the_shipped_hook() -> None:
    hooks = yaml.safe_load((REPO / ".pre-commit-hooks.yaml").read_text())
    (repo,) = workflow("pre-commit")["repos"]
    assert [h["id"] for h in repo["hooks"]] == [h["id"] for h in hooks]
    build_parser().parse_args(["lint", *repo["hooks"][0]["args"]])


@pytest.mark.parametrize("argv", github_commands()
                         + robotdesc_commands(workflow("gitlab")["script"]),
                         ids=lambda argv: " ".join(argv))
def test_documented_commands_exist_and_work(tmp_path, argv: list[str]) -> None:
    build_parser().parse_args(argv)  # every option exists (exits on an unknown one)
    workspace = tmp_path / "ws"
    shutil.copytree(WORKSPACE, workspace)
    proc = run(argv, workspace)
    assert proc.returncode == 1, proc.stderr  # the fixture has findings: the gate closes
    if "--output-file" in argv:
        out = workspace / argv[argv.index("--output-file") + 1]
        text = out.read_text(encoding="utf-8")
        if "sarif" in argv:
            schema = json.loads((REPO / "tests" / "report" / "data" /
                                 "sarif-schema-2.1.0.json").read_text())
            jsonschema.validate(json.loads(text), schema)
        elif "gitlab" in argv:
            assert json.loads(text)[0]["location"]["path"].startswith("src/")
        else:
            assert text.startswith("<?xml")
    else:
        assert proc.stdout.startswith("::error file=src/arm_description/")
