"""What a check sees: its options as its own options dataclass (`RuleContext.options_as`), and
mesh access as the `MeshAccess` protocol that the mesh layer's `MeshContext` satisfies."""

from __future__ import annotations

import inspect
from dataclasses import dataclass

import pytest

from robotdesc.inertia.mesh_access import MeshAccess
from robotdesc.mesh.context import MeshContext
from robotdesc.rules.catalog import all_rules
from robotdesc.rules.joints import AxisOptions
from robotdesc.rules.registry import RuleContext


@dataclass(frozen=True)
class OtherOptions:
    tolerance: float = 0.5


def test_no_options_give_the_defaults() -> None:
    assert RuleContext().options_as(AxisOptions) == AxisOptions()


def test_given_options_come_back_typed() -> None:
    options = AxisOptions(tolerance=0.25)
    assert RuleContext(options=options).options_as(AxisOptions) is options


def test_options_of_another_rule_are_a_bug() -> None:
    with pytest.raises(TypeError, match="type OtherOptions, expected AxisOptions"):
        RuleContext(options=OtherOptions()).options_as(AxisOptions)


def test_every_rule_reads_its_registered_defaults() -> None:
    for rule_ in all_rules():
        if rule_.options is not None:
            defaults = rule_.default_options()
            assert RuleContext(options=defaults).options_as(rule_.options) is defaults


def test_mesh_context_has_every_member_of_the_protocol() -> None:
    """mypy checks it where the rules take a MeshContext as MeshAccess; this keeps the
    signatures in step at run time too."""
    members = [name for name in vars(MeshAccess) if not name.startswith("_")]
    assert set(members) == {"settings", "find_package", "lookup", "meshes", "link_geometry"}
    for name in members:
        if name == "settings":
            continue  # an instance attribute of MeshContext
        wanted = inspect.signature(getattr(MeshAccess, name))
        have = inspect.signature(getattr(MeshContext, name))
        assert list(wanted.parameters) == list(have.parameters), name
