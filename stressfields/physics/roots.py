"""The one vectorised root finder of the physics layer: bisection on arrays.

Every element is bracketed independently and halved the same number of times, so a whole block
of points costs one function call per step, and the result is reproducible to the bit whatever
the chunking (a Newton or Brent iteration would stop at different steps for different points).
"""
from __future__ import annotations

from typing import Callable

import numpy as np


def bisect(root_above: Callable[[np.ndarray], np.ndarray], lo, hi, iterations: int, *,
           geometric: bool = False) -> np.ndarray:
    """The point where ``root_above`` switches from True to False, inside [lo, hi].

    ``root_above(x)`` says, per element, whether the root lies above ``x`` (e.g. ``g(x) < target``
    for an increasing g). After ``iterations`` halvings the bracket is ``(hi - lo) 2^-iterations``
    wide and its midpoint is returned; ``geometric=True`` halves ``log(hi/lo)`` instead (roots
    spread over decades; lo > 0). ``lo`` and ``hi`` broadcast against each other.
    """
    lo, hi = (np.array(v, dtype=float) for v in np.broadcast_arrays(lo, hi))
    if geometric:
        lo, hi = np.log(lo), np.log(hi)
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        up = root_above(np.exp(mid) if geometric else mid)
        lo, hi = np.where(up, mid, lo), np.where(up, hi, mid)
    mid = 0.5 * (lo + hi)
    return np.exp(mid) if geometric else mid
