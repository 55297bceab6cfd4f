"""The options' cache/manifest key holds what the method reads, and only that."""

from __future__ import annotations

import pytest

from robotdesc.collision.options import CollisionOptions
from robotdesc.errors import CollisionOptionError


def test_a_decimation_parameter_leaves_coacd_and_hull_keys_alone():
    for method in ("coacd", "hull", "primitive"):
        base = CollisionOptions(method=method)
        assert base.key_fields() == CollisionOptions(method=method, ratio=0.1,
                                                     decimator="fast-simplification",
                                                     faces=500).key_fields()


@pytest.mark.parametrize("method, change", [
    ("decimate", {"ratio": 0.1}), ("decimate", {"decimator": "fast-simplification"}),
    ("coacd", {"threshold": 0.2}), ("primitive", {"primitives": ("box",)}),
    ("hull", {"target_percent": 2.0}), ("auto", {"ratio": 0.1}),
    ("auto", {"auto_order": ("hull",)}), ("coacd", {"seed": 3})])
def test_a_parameter_the_method_reads_changes_its_key(method, change):
    base = CollisionOptions(method=method)
    assert base.key_fields() != CollisionOptions(method=method, **change).key_fields()


def test_unknown_decimator_is_an_option_error_naming_it():
    with pytest.raises(CollisionOptionError, match="unknown decimator") as caught:
        CollisionOptions(decimator="blender").validated()
    assert (caught.value.option, caught.value.value) == ("decimator", "blender")


def test_the_cli_offers_exactly_the_methods_and_decimators():
    """The CLI spells the choices out (importing the collision package at start-up would
    slow every command); they must stay the options' own."""
    import argparse

    from robotdesc.collision.options import DECIMATORS, METHODS
    from robotdesc.commands import collision

    common, expansion = argparse.ArgumentParser(add_help=False), argparse.ArgumentParser(
        add_help=False)
    parser = argparse.ArgumentParser()
    collision.register(parser.add_subparsers(), common=common, expansion=expansion)
    [sub] = parser._subparsers._group_actions[0].choices.values()
    choices = {action.dest: tuple(action.choices) for action in sub._actions if action.choices}
    assert choices["method"] == METHODS
    assert choices["decimator"] == DECIMATORS
