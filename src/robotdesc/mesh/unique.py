"""The sorted distinct values of a 1-D array, as `np.unique` gives them, without its import
of `numpy.ma` (about 14 ms of CPU the first time `np.unique` is called in a process: a cold
lint would pay it for nothing)."""

from __future__ import annotations

import numpy as np

__all__ = ["unique", "unique_inverse"]


def unique(values: np.ndarray) -> np.ndarray:
    """The distinct values of `values` (1-D), ascending (`np.unique(values)`)."""
    ordered = np.sort(values)
    distinct: np.ndarray = ordered[_firsts(ordered)]
    return distinct


def unique_inverse(values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The distinct values of `values` (1-D), ascending, and for each value the index of
    its own among them (`np.unique(values, return_inverse=True)`)."""
    order = np.argsort(values, kind="stable")
    ordered = values[order]
    firsts = _firsts(ordered)
    inverse = np.empty(len(values), dtype=np.intp)
    inverse[order] = np.cumsum(firsts) - 1
    return ordered[firsts], inverse


def _firsts(ordered: np.ndarray) -> np.ndarray:
    """Where each run of equal values of a sorted array starts."""
    firsts = np.empty(len(ordered), dtype=bool)
    firsts[:1] = True
    np.not_equal(ordered[1:], ordered[:-1], out=firsts[1:])
    return firsts
