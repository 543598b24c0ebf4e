"""The validity flag every family writes beside its fields (docs/theory/README.md, conventions)."""
from __future__ import annotations

import numpy as np


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
