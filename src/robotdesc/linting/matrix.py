"""Argument matrices of config targets: every combination is one variant, named after it.

A config target such as ``matrix = { ur_type = ["ur5e", "ur10e"], hand = [true, false] }``
gives four variants, linted and reported apart as ``ur.urdf.xacro[ur_type=ur5e,hand=true]``.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

Variant = tuple[tuple[str, str], ...]


def matrix_variants(matrix: Sequence[tuple[str, Sequence[str]]]) -> list[Variant]:
    """Every combination of the matrix values, in declaration order (one empty variant for
    an empty matrix).

    Args:
        matrix: (argument name, values) pairs.
    """
    names = [name for name, _ in matrix]
    return [tuple(zip(names, values)) for values in itertools.product(*(v for _, v in matrix))]


def variant_label(variant: Variant) -> str:
    """``[name=value,...]`` for a variant; empty for none."""
    if not variant:
        return ""
    return "[" + ",".join(f"{name}={value}" for name, value in variant) + "]"
