"""Argument matrices: every combination, named after its values."""

from __future__ import annotations

from robotdesc.linting.matrix import matrix_variants, variant_label


def test_every_combination_in_declaration_order() -> None:
    variants = matrix_variants([("ur_type", ("ur5e", "ur10e")), ("hand", ("true", "false"))])
    assert variants == [(("ur_type", "ur5e"), ("hand", "true")),
                        (("ur_type", "ur5e"), ("hand", "false")),
                        (("ur_type", "ur10e"), ("hand", "true")),
                        (("ur_type", "ur10e"), ("hand", "false"))]
    assert variant_label(variants[1]) == "[ur_type=ur5e,hand=false]"


def test_empty_matrix_is_one_unnamed_variant() -> None:
    assert matrix_variants([]) == [()]
    assert variant_label(()) == ""
