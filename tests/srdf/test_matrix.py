import pytest

pytest.importorskip("pinocchio")

from kinematics.robots import ARM, INERTIA, robot  # noqa: E402

import robotdesc.srdf.matrix as matrix_module  # noqa: E402
from robotdesc.srdf.matrix import Reason, compute_matrix  # noqa: E402

#: b (a small sphere) always sits inside a's box; "orbit" slides through it half the time;
#: m carries a sphere far above, so a and b are not adjacent. "far" hangs on a (locked)
#: revolute joint: on a fixed one it would be welded to a, making a and orbit adjacent.
ALWAYS = f"""<robot name="r">
  <link name="a"><collision><geometry><box size="1 1 1"/></geometry></collision></link>
  <link name="m"><inertial><mass value="1"/>{INERTIA}</inertial>
    <collision><origin xyz="0 0 3"/><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="b"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="far"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="orbit"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="n"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="m"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="k" type="fixed"><parent link="m"/><child link="n"/><origin xyz="0 0 0.1"/></joint>
  <joint name="mb" type="continuous"><parent link="n"/><child link="b"/></joint>
  <joint name="far_joint" type="revolute"><parent link="a"/><child link="far"/><origin xyz="5 0 0"/>
    <axis xyz="0 0 1"/><limit lower="0" upper="0" effort="1" velocity="1"/></joint>
  <joint name="slide" type="prismatic"><parent link="far"/><child link="orbit"/>
    <axis xyz="1 0 0"/><limit lower="-5" upper="-3.6" effort="1" velocity="1"/></joint>
</robot>"""


def reasons(matrix) -> dict[tuple[str, str], Reason | None]:
    return {(p.link1, p.link2): p.reason for p in matrix.pairs}


def test_arm_pairs_are_classified() -> None:
    matrix = compute_matrix(robot(ARM), lambda mesh: None, samples=300, seed=1, workers=1)
    found = reasons(matrix)
    assert found[("base", "upper")] is Reason.ADJACENT
    assert found[("fore", "hand")] is Reason.ADJACENT  # through the geometry-less wrist
    assert found[("base", "fore")] is Reason.DEFAULT
    assert found[("base", "hand")] is Reason.NEVER
    assert matrix.links_without_geometry == ("wrist", "twin")


def test_always_and_sometimes() -> None:
    matrix = compute_matrix(robot(ALWAYS), lambda mesh: None, samples=200, seed=0, workers=1,
                            always_fraction=0.95)
    found = reasons(matrix)
    assert found[("a", "b")] is Reason.DEFAULT  # default wins over always
    assert found[("a", "far")] is Reason.ADJACENT
    assert found[("b", "far")] is Reason.NEVER
    assert found[("a", "orbit")] is None  # sometimes: left enabled
    pair = next(p for p in matrix.pairs if (p.link1, p.link2) == ("a", "b"))
    assert pair.fraction == 1.0 and pair.at_default
    sometimes = next(p for p in matrix.pairs if (p.link1, p.link2) == ("a", "orbit"))
    assert 0.35 < sometimes.fraction < 0.65


def test_parallel_workers_give_the_same_counts(monkeypatch) -> None:
    monkeypatch.setattr(matrix_module, "PARALLEL_MIN_SAMPLES", 10)
    sliding = robot(ALWAYS)
    one = compute_matrix(sliding, lambda mesh: None, samples=400, seed=5, workers=1)
    two = compute_matrix(sliding, lambda mesh: None, samples=400, seed=5, workers=2)
    assert one.pairs == two.pairs
    assert any(p.reason is None and 0 < p.collisions < 400 for p in one.pairs)


WELDED = f"""<robot name="w">
  <link name="link7"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="hand"><collision><origin xyz="0 0 0.2"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="hand_sc"><collision><geometry><sphere radius="0.15"/></geometry></collision></link>
  <link name="finger"><inertial><mass value="1"/>{INERTIA}</inertial>
    <collision><origin xyz="0 0 0.3"/><geometry><box size="0.05 0.05 0.1"/></geometry></collision></link>
  <joint name="j8" type="fixed"><parent link="link7"/><child link="hand"/></joint>
  <joint name="sc" type="fixed"><parent link="hand"/><child link="hand_sc"/></joint>
  <joint name="f" type="prismatic"><parent link="hand"/><child link="finger"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.04" effort="1" velocity="1"/></joint>
</robot>"""


def test_links_welded_by_fixed_joints_are_adjacent_as_in_moveit() -> None:
    matrix = compute_matrix(robot(WELDED), lambda mesh: None, samples=50, seed=0, workers=1)
    found = reasons(matrix)
    assert found[("hand_sc", "link7")] is Reason.ADJACENT  # one rigid body
    assert found[("finger", "link7")] is Reason.ADJACENT  # a joint connects the bodies


def test_counts_equal_checking_every_pair_in_every_sample() -> None:
    """The broad phase, the pairs that cannot meet and the rigid pairs change nothing: the
    counts of the pairs sampled to the end are those of checking each sample with coal."""
    from robotdesc.srdf.matrix import collisions_at, prepare_scene
    from robotdesc.srdf.sampling import sample_positions
    from srdf.test_reach import ROVER

    for text in (ALWAYS, ROVER, ARM):
        model = robot(text)
        matrix = compute_matrix(model, lambda mesh: None, samples=120, seed=3, workers=1,
                                adaptive=False)
        prepared = prepare_scene(model, lambda mesh: None)
        names, positions = sample_positions(model, 120, 3)
        brute: dict[tuple[str, str], int] = {}
        for row in positions:
            for pair in collisions_at(prepared, dict(zip(names, row.tolist()))):
                brute[pair] = brute.get(pair, 0) + 1
        for pair in matrix.pairs:
            if pair.reason is Reason.ADJACENT or pair.samples < 120:
                continue  # adjacent: not checked; fewer samples: left the rounds early
            assert pair.collisions == brute.get((pair.link1, pair.link2), 0), pair


def test_pairs_that_cannot_meet_are_never_with_every_sample_counted() -> None:
    from srdf.test_reach import ROVER

    matrix = compute_matrix(robot(ROVER), lambda mesh: None, samples=100, seed=0, workers=1)
    far = next(p for p in matrix.pairs if (p.link1, p.link2) == ("far", "wheel"))
    assert far.reason is Reason.NEVER and far.samples == 100 and far.collisions == 0


def test_adaptive_sampling_stops_once_the_classes_stay_the_same() -> None:
    from srdf.test_reach import ROVER

    seen = []
    matrix = compute_matrix(robot(ROVER), lambda mesh: None, samples=50000, seed=0, workers=1,
                            progress=seen.append)
    assert matrix_module.ADAPTIVE_MIN_SAMPLES <= matrix.samples < 50000
    assert seen[-1].samples == matrix.samples and seen[-1].limit == 50000
    assert matrix.samples - seen[-1].changed_at >= matrix.samples / 2
    full = compute_matrix(robot(ROVER), lambda mesh: None, samples=8000, seed=0, workers=1,
                          adaptive=False)
    assert full.samples == 8000
    assert [p.reason for p in full.pairs] == [p.reason for p in matrix.pairs]
