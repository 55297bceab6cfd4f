"""Without MuJoCo, the physics checks say how to install it (the import failure simulated)."""

from __future__ import annotations

import sys

import pytest

from robotdesc.cli import main
from robotdesc.errors import SimUnavailable
from robotdesc.sim import backend
from robotdesc.sim.backend import INSTALL_HINT, MUJOCO_REQUIREMENT

from .sim_support import FIXTURES


@pytest.fixture
def no_mujoco(monkeypatch):
    monkeypatch.setitem(sys.modules, "mujoco", None)  # makes `import mujoco` fail


def test_import_failure_raises_input_error_with_install_hint(no_mujoco) -> None:
    with pytest.raises(SimUnavailable) as caught:
        backend.import_mujoco()
    assert 'pip install ".[sim]"' in str(caught.value)
    assert MUJOCO_REQUIREMENT in str(caught.value)


def test_sim_command_without_mujoco_exits_2_and_says_how_to_install(no_mujoco, capsys) -> None:
    code = main(["sim", str(FIXTURES / "slip_arm.urdf")])
    captured = capsys.readouterr()
    assert code == 2
    assert INSTALL_HINT in captured.err
    assert "Traceback" not in captured.err
