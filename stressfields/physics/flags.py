"""The validity flag every family writes beside its fields (docs/theory/README.md, conventions)."""
from __future__ import annotations

import functools

import numpy as np


def quiet(kernel):
    """Run ``kernel`` with floating-point warnings off.

    A kernel's overflow, 0/0 or inf - inf is not news for its caller: the value it produces (+-inf
    where the exact limit is infinite, NaN where it depends on the direction) is the report, and the
    validity flag names its cause. Warnings would only repeat that, once per dask block.
    """
    @functools.wraps(kernel)
    def silent(*args, **kwargs):
        with np.errstate(all="ignore"):
            return kernel(*args, **kwargs)
    return silent


def validity_flag(*arrays: np.ndarray) -> np.ndarray:
    """Per point: 0 every value finite, 1 some value unbounded (+-inf: the exact limit is infinite),
    2 some value undefined (NaN: the limit depends on the direction of approach); ``np.int8(0)``
    for no arrays."""
    if not arrays:
        return np.int8(0)
    shape = np.broadcast_shapes(*(np.shape(v) for v in arrays))
    flag = np.zeros(shape, dtype=np.int8)
    for v in arrays:
        flag = np.maximum(flag, np.where(np.isinf(np.broadcast_to(v, shape)), 1, 0).astype(np.int8))
    for v in arrays:
        flag = np.where(np.isnan(np.broadcast_to(v, shape)), np.int8(2), flag)
    return flag
