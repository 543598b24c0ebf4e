"""Stress invariants of a symmetric 3x3 stress tensor given by its six components.

Von Mises equivalent stress, eq. (30) of E. Willert, F. Forsbach, V. L. Popov, "Stress tensor and
gradient of hydrostatic pressure in the contact plane of axisymmetric bodies under normal and
tangential loading": sqrt(3 J2) (the paper's prose says "square root of the second invariant"; its
formula, like the standard definition, is sqrt(3 J2)).  Principal stresses are the eigenvalues.

Arrays broadcast against each other; any non-finite component gives NaN at that point (an
infinite component leaves the invariants undefined without the limit process), never an error.
``singular_limits`` gives that limit where the caller knows how the components grow.
"""
from __future__ import annotations

import numpy as np

__all__ = ["von_mises", "principal_stresses", "singular_limits"]

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


def singular_limits(lead, rest):
    """Limits of the invariants of a tensor lam * lead + rest + o(1) as lam -> +inf: the exact
    values at a singular point whose components are infinite with known ratios (the family's entry
    point knows ``lead`` and, where it matters, the bounded remainder ``rest``).

    ``lead``, ``rest``: stacked symmetric matrices (n, 3, 3); NaN entries of ``rest`` mean
    unknown (e.g. direction-dependent).  Returns (von_mises, (s1, s2, s3)): a principal stress is
    +-inf with the sign of the eigenvalue of ``lead``; where that eigenvalue is 0 it is the limit
    of the eigenvalue of ``rest`` projected on the null space of ``lead`` (first-order
    perturbation; NaN if ``rest`` is unknown).  Von Mises is +inf where ``lead`` has a deviatoric
    part, else the von Mises stress of ``rest``.  A row of ``lead`` with NaN gives NaN throughout."""
    lead = np.asarray(lead, dtype=float)
    rest = np.asarray(rest, dtype=float)
    n = lead.shape[0]
    known = np.all(np.isfinite(lead.reshape(n, 9)), axis=1)
    safe = np.where(known[:, None, None], lead, 0.0)
    vals, vecs = np.linalg.eigh(safe)
    size = np.max(np.abs(vals), axis=1, keepdims=True)
    # eigenvalues of the leading matrix that are zero up to its rounding (exact zeros, e.g. the
    # hoop stress of a flat punch edge at nu = 0, come out as ~1e-17 of the norm)
    zero = np.abs(vals) <= 64.0 * np.finfo(float).eps * size
    with np.errstate(invalid="ignore"):
        principal = np.where(zero, np.nan, np.sign(vals) * np.inf)
    for i in np.flatnonzero(np.any(zero, axis=1) & known):
        basis = vecs[i][:, zero[i]]
        principal[i, zero[i]] = np.linalg.eigvalsh(basis.T @ rest[i] @ basis)
    principal = np.sort(principal, axis=1)[:, ::-1]   # NaN sorts last: ``principal[~known]`` below
    principal[~known] = np.nan
    dev = safe - np.trace(safe, axis1=1, axis2=2)[:, None, None] / 3.0 * np.eye(3)
    hydrostatic = np.max(np.abs(dev).reshape(n, 9), axis=1) <= 64.0 * np.finfo(float).eps * size[:, 0]
    with np.errstate(invalid="ignore"):
        vm_rest = von_mises(rest[:, 0, 0], rest[:, 1, 1], rest[:, 2, 2], rest[:, 0, 1], rest[:, 0, 2],
                            rest[:, 1, 2])
    vm = np.where(hydrostatic, vm_rest, np.inf)
    vm[~known] = np.nan
    return vm, tuple(principal[:, k] for k in range(3))
