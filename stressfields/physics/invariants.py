"""Stress invariants of a symmetric 3x3 stress tensor given by its six components.

Von Mises equivalent stress, eq. (30) of E. Willert, F. Forsbach, V. L. Popov, "Stress tensor and
gradient of hydrostatic pressure in the contact plane of axisymmetric bodies under normal and
tangential loading": sqrt(3 J2) (the paper's prose says "square root of the second invariant"; its
formula, like the standard definition, is sqrt(3 J2)).  Principal stresses are the eigenvalues,
solved analytically (trigonometric root of the deviator's characteristic equation, then the 2 x 2
tensor orthogonal to its eigenvector).

Arrays broadcast against each other; any non-finite component gives NaN at that point (an
infinite component leaves the invariants undefined without the limit process), never an error.
``singular_limits`` gives that limit where the caller knows how the components grow.
"""
from __future__ import annotations

import numpy as np

__all__ = ["von_mises", "principal_stresses", "singular_limits"]

_CHUNK = 1 << 13


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
    """Principal stresses (s1, s2, s3), s1 >= s2 >= s3 exactly, each of the broadcast shape.

    Analytic eigenvalues of the symmetric tensor (docs/theory/axisymmetric.md (A60) gives J2):
    the best-separated eigenvalue by the trigonometric solution of the deviator's characteristic
    equation, the other two from the 2 x 2 tensor on the plane orthogonal to its eigenvector
    (``_eigenvalues``).  Every eigenvalue is within a few ulps of the tensor's Frobenius norm
    (measured worst case 2e-15 of it over 1e6 random and degenerate tensors; the tests hold it to
    1e-13); a tensor with a principal axis along x, y or z (two shears exactly 0) keeps its normal
    stress there exactly.  ~95 ns per point, against ~480 for LAPACK's eigvalsh on stacked 3 x 3
    matrices (1e6 points, median of 5).  NaN where any component is not finite."""
    comps = np.broadcast_arrays(*(np.asarray(s, dtype=float) for s in (sxx, syy, szz, sxy, sxz, syz)))
    shape = comps[0].shape
    flat = [c.ravel() for c in comps]
    n = flat[0].size
    out = np.empty((3, n))
    # chunks keep the ~40 temporaries of a chunk in cache (2^13 the fastest; the whole array at once
    # takes twice as long: docs/bench/tuning.md)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for s in range(0, n, _CHUNK):
            sl = slice(s, s + _CHUNK)
            out[:, sl] = _eigenvalues(*(c[sl] for c in flat))
    return tuple(out[k].reshape(shape) for k in range(3))


def _eigenvalues(a00, a11, a22, a01, a02, a12):
    """Descending eigenvalues of symmetric 3 x 3 tensors (1-D component arrays), stacked (3, n).

    1. Shift by the mean normal stress q and scale by the largest deviator entry (no overflow or
       underflow, whatever the dynamic range); with p = sqrt(tr(B^2)/6) of the scaled deviator B,
       det(B/p)/2 = cos(3 phi) and the eigenvalues of B/p are 2 cos(phi + 2 pi k/3).
    2. The root farthest from the other two (the largest if det >= 0, else the smallest) is
       well conditioned in cos(3 phi) (d/dr of 2 cos(acos(r)/3) stays <= 2/3 at r = +-1) and lies
       at least sqrt(3) p from both others, so its eigenvector, the largest cross product of two
       rows of B - lambda I, is accurate to a few ulps.
    3. The other two are the eigenvalues of the 2 x 2 tensor [U V]^T B [U V] on the plane normal
       to that eigenvector: mean +- hypot(half difference, off-diagonal), which keeps the gap between
       them to ulps however small it is (the quadratic from trace and determinant would lose half
       the digits of a small gap).
    Non-finite components give NaN rows."""
    q = (a00 + a11 + a22) / 3.0
    b00, b11, b22 = a00 - q, a11 - q, a22 - q
    size = np.maximum(np.maximum(np.maximum(abs(b00), abs(b11)), np.maximum(abs(b22), abs(a01))),
                      np.maximum(abs(a02), abs(a12)))
    bad = ~np.isfinite(size + q)
    size = np.where((size > 0.0) & ~bad, size, 1.0)   # a hydrostatic tensor: B = 0, all roots q
    inv = 1.0 / size
    b00, b11, b22, b01, b02, b12 = b00 * inv, b11 * inv, b22 * inv, a01 * inv, a02 * inv, a12 * inv
    p2 = (b00 * b00 + b11 * b11 + b22 * b22) / 6.0 + (b01 * b01 + b02 * b02 + b12 * b12) / 3.0
    p = np.sqrt(p2)
    det = (b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) + b02 * (b01 * b12 - b11 * b02))
    r = np.clip(0.5 * det / np.where(p > 0.0, p2 * p, 1.0), -1.0, 1.0)
    phi = np.arccos(np.abs(r)) / 3.0                    # in [0, pi/6]: the far root is 2 p cos(phi)
    far = np.copysign(2.0 * p * np.cos(phi), r)         # det < 0: the smallest, mirrored
    # eigenvector of ``far``: rows of M = B - far I, the largest of their three cross products
    m00, m11, m22 = b00 - far, b11 - far, b22 - far
    c0 = (b01 * b12 - b02 * m11, b02 * b01 - m00 * b12, m00 * m11 - b01 * b01)   # row0 x row1
    c1 = (b01 * m22 - b02 * b12, b02 * b02 - m00 * m22, m00 * b12 - b01 * b02)   # row0 x row2
    c2 = (m11 * m22 - b12 * b12, b12 * b02 - b01 * m22, b01 * b12 - m11 * b02)   # row1 x row2
    n0, n1, n2 = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2] for c in (c0, c1, c2))
    use1, use2 = (n1 > n0) & (n1 >= n2), (n2 > n0) & (n2 > n1)
    v = [np.where(use2, z, np.where(use1, y, x)) for x, y, z in zip(c0, c1, c2)]
    nv = np.where(use2, n2, np.where(use1, n1, n0))
    # B = 0 (or rows below underflow): any unit vector is an eigenvector
    degenerate = ~(nv > 0.0)
    inv_nv = 1.0 / np.sqrt(np.where(degenerate, 1.0, nv))
    v0 = np.where(degenerate, 1.0, v[0] * inv_nv)
    v1 = np.where(degenerate, 0.0, v[1] * inv_nv)
    v2 = np.where(degenerate, 0.0, v[2] * inv_nv)
    # U: unit vector normal to v from its two largest components; V = v x U
    big0 = np.abs(v0) > np.abs(v1)
    inv_u = 1.0 / np.sqrt(np.where(big0, v0 * v0 + v2 * v2, v1 * v1 + v2 * v2))
    u0 = np.where(big0, -v2 * inv_u, 0.0)
    u1 = np.where(big0, 0.0, v2 * inv_u)
    u2 = np.where(big0, v0 * inv_u, -v1 * inv_u)
    w0, w1, w2 = v1 * u2 - v2 * u1, v2 * u0 - v0 * u2, v0 * u1 - v1 * u0
    bu0 = b00 * u0 + b01 * u1 + b02 * u2
    bu1 = b01 * u0 + b11 * u1 + b12 * u2
    bu2 = b02 * u0 + b12 * u1 + b22 * u2
    j00 = u0 * bu0 + u1 * bu1 + u2 * bu2
    j01 = w0 * bu0 + w1 * bu1 + w2 * bu2
    j11 = (w0 * (b00 * w0 + b01 * w1 + b02 * w2) + w1 * (b01 * w0 + b11 * w1 + b12 * w2)
           + w2 * (b02 * w0 + b12 * w1 + b22 * w2))
    out = _ordered(far, j00, j11, j01) * size + q
    # a principal axis along x, y or z (both its shear components exactly 0, as at the surface
    # outside the contact): that normal stress and the 2 x 2 block, exact zeros kept exact
    for axis, (pair, normal) in enumerate((((a11, a22, a12), a00), ((a00, a22, a02), a11),
                                           ((a00, a11, a01), a22))):
        shears = ((a01, a02), (a01, a12), (a02, a12))[axis]
        split = (shears[0] == 0.0) & (shears[1] == 0.0)
        if np.any(split):
            out[:, split] = _ordered(normal[split], *(v[split] for v in pair))
    out[:, bad] = np.nan
    return out


def _ordered(single, b00, b11, b01):
    """(s1, s2, s3) of an eigenvalue ``single`` and the 2 x 2 block [[b00, b01], [b01, b11]]:
    mean +- hypot(half difference, b01), ordered exactly (rounding can put ``single`` a hair inside
    the pair when all three nearly agree)."""
    mid, rad = 0.5 * (b00 + b11), np.hypot(0.5 * (b00 - b11), b01)
    hi, lo = mid + rad, mid - rad
    return np.stack([np.maximum(single, hi), np.maximum(np.minimum(single, hi), lo), np.minimum(single, lo)])


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
