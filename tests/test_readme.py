"""The README's Quick start is what CI runs, and its main command works."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys

from support import REPO

README = (REPO / "README.md").read_text()
CI_RUN = (REPO / ".ci" / "run").read_text()


def _quick_start_commands() -> list[str]:
    section = README.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    return [block.strip() for block in re.findall(r"```bash\n(.*?)```", section, re.S)]


def test_quick_start_has_exactly_two_commands():
    commands = _quick_start_commands()
    assert len(commands) == 2
    assert all("\n" not in command for command in commands)


def test_ci_runs_the_readme_test_command():
    test_command = _quick_start_commands()[1]
    ci_lines = [line.strip() for line in CI_RUN.splitlines()
                if line.strip() and not line.lstrip().startswith("#")]
    assert test_command in ci_lines


def test_main_command_lints_the_bundled_description_cleanly():
    main = _quick_start_commands()[0]
    install, _, lint = main.partition(" && ")
    assert install.startswith("python -m pip install .")
    argv = shlex.split(lint)
    assert argv[:2] == ["robotdesc", "lint"]
    result = subprocess.run([sys.executable, "-m", "robotdesc", *argv[1:]], cwd=REPO,
                            capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stdout + result.stderr
