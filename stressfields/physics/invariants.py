"""Stress invariants of a symmetric 3x3 stress tensor given by its six components.

Von Mises equivalent stress, eq. (30) of E. Willert, F. Forsbach, V. L. Popov, "Stress tensor and
gradient of hydrostatic pressure in the contact plane of axisymmetric bodies under normal and
tangential loading": sqrt(3 J2) (the paper's prose says "square root of the second invariant"; its
formula, like the standard definition, is sqrt(3 J2)).  Principal stresses are the eigenvalues.

Arrays broadcast against each other; any non-finite component gives NaN at that point (an
infinite component leaves the invariants undefined without the limit process), never an error.
"""
from __future__ import annotations

import numpy as np

__all__ = ["von_mises", "principal_stresses"]

_CHUNK = 1 << 16


def von_mises(sxx, syy, szz, sxy, sxz, syz):
    """sqrt(3 J2) = sqrt(((sxx-syy)^2 + (syy-szz)^2 + (szz-sxx)^2)/2 + 3 (sxy^2 + sxz^2 + syz^2)),
    eq. (30).  NaN where any component is not finite."""
    comps = np.broadcast_arrays(*(np.asarray(s, dtype=float) for s in (sxx, syy, szz, sxy, sxz, syz)))
    sxx, syy, szz, sxy, sxz, syz = comps
    with np.errstate(invalid="ignore", over="ignore"):
        j = 0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) + 3.0 * (sxy ** 2 + sxz ** 2 + syz ** 2)
        out = np.sqrt(j)
    bad = ~np.isfinite(sxx)
    for s in comps[1:]:
        bad |= ~np.isfinite(s)
    return np.where(bad, np.nan, out)


def principal_stresses(sxx, syy, szz, sxy, sxz, syz):
    """Principal stresses (s1, s2, s3), s1 >= s2 >= s3, each of the broadcast shape.

    Eigenvalues of the symmetric tensor by ``numpy.linalg.eigvalsh`` on stacked 3x3 matrices (the
    tensor is well conditioned; the values are accurate to a few ulps of its norm).  NaN where any
    component is not finite."""
    comps = np.broadcast_arrays(*(np.asarray(s, dtype=float) for s in (sxx, syy, szz, sxy, sxz, syz)))
    shape = comps[0].shape
    flat = [c.ravel() for c in comps]
    n = flat[0].size
    bad = np.zeros(n, dtype=bool)
    for c in flat:
        bad |= ~np.isfinite(c)
    out = np.full((n, 3), np.nan)
    good = np.flatnonzero(~bad)
    xx, yy, zz, xy, xz, yz = (c[good] for c in flat)
    # eigvalsh works in place per matrix; chunks keep the stacked array in cache
    for s in range(0, good.size, _CHUNK):
        sl = slice(s, s + _CHUNK)
        m = np.empty((min(_CHUNK, good.size - s), 3, 3))
        m[:, 0, 0], m[:, 1, 1], m[:, 2, 2] = xx[sl], yy[sl], zz[sl]
        m[:, 0, 1] = m[:, 1, 0] = xy[sl]
        m[:, 0, 2] = m[:, 2, 0] = xz[sl]
        m[:, 1, 2] = m[:, 2, 1] = yz[sl]
        out[good[sl]] = np.linalg.eigvalsh(m)[:, ::-1]  # ascending -> descending
    return tuple(out[:, k].reshape(shape) for k in range(3))
