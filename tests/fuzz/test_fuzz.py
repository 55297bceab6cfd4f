"""The fuzzing campaign as tests: a bounded run in the default suite, a long one marked slow.

See tests/fuzz/run_campaign.py for the command-line run whose figures are in
docs/reliability.md.
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest

from fuzz.campaign import ENGINEER, Seed, campaign, example_robot_data_share, seeds
from fuzz.harness import prepare_case, run_case
from fuzz.mutate import DESCRIPTION_MUTATIONS, bad_mesh, mutate

#: The bounded run: small plain seeds, in-process lint/expand (well under a minute).
BOUNDED_MUTANTS = 200
BOUNDED_SEED = 20


def _small_seeds() -> list[Seed]:
    found = []
    share = example_robot_data_share()
    if share is not None:
        for relative in ("solo_description/robots/solo12.urdf",
                         "ur_description/urdf/ur5_robot.urdf"):
            path = share / "robots" / relative
            if path.is_file():
                found.append(Seed(path.name, path.read_bytes(), (str(share.parent),)))
    top = ENGINEER / "urdf" / "engineer.urdf.xacro"
    # a plain seed made from the Engineer's own sources, without expanding (fast)
    found.append(Seed("engineer-arm", (ENGINEER / "urdf" / "arm.xacro").read_bytes(), ()))
    assert top.is_file()
    return found


def test_the_mutator_is_deterministic() -> None:
    data = (ENGINEER / "urdf" / "arm.xacro").read_bytes()
    first = [mutate(data, random.Random(7)) for _ in range(3)]
    again = [mutate(data, random.Random(7)) for _ in range(3)]
    assert first == again
    for name, mutation in DESCRIPTION_MUTATIONS.items():
        assert isinstance(mutation(data, random.Random(1)), bytes), name
    assert {bad_mesh(random.Random(n))[0] for n in range(200)} >= {
        "empty.stl", "lying.stl", "nan.stl", "zero.dae", "entity.dae", "latin1.obj",
        "noextension"}


def test_bounded_campaign_lint_and_expand() -> None:
    tally = campaign(BOUNDED_MUTANTS, BOUNDED_SEED, commands=["lint", "lint-text", "expand"],
                     seed_list=_small_seeds(), xacro_share=0.0, timeout_s=60)
    assert tally.mutants == BOUNDED_MUTANTS
    assert not tally.failures, tally.summary() + "\n" + "\n".join(
        f"{kind} {command}: {outcome.problems} {outcome.output[-800:]}"
        for kind, command, outcome, _ in tally.failures[:5])
    assert set(tally.exits) <= {"0", "1", "2"}


def test_a_sample_as_subprocesses(tmp_path: Path) -> None:
    rng = random.Random(BOUNDED_SEED)
    seed = _small_seeds()[-1]
    for index in range(2):
        root = tmp_path / f"s{index}"
        target = prepare_case(root, mutate(seed.data, rng))
        outcome = run_case(root, "lint", target, list(seed.package_paths), timeout_s=120,
                           subprocess_run=True)
        assert outcome.ok, (outcome.problems, outcome.output[-800:])


@pytest.mark.slow
def test_long_campaign_every_command() -> None:
    tally = campaign(1000, 21, seed_list=seeds(), xacro_share=0.05, subprocess_every=50)
    assert not tally.failures, tally.summary()
