"""The geometry of the Hertz field below the surface, shared by every closed form of the family:
the coordinates M, N, S, Q of docs/theory/interior.md (I2)-(I4) (a = 1) and the stable forms of
the two functions whose direct evaluation loses digits in the far field, F(M) = 1 - M arctan(1/M)
(I4) and x - sin x.  The normal and sliding Hertz fields (``interior_hertz``), the cone
(``interior_cone``), the punch derivatives (``interior``, ``interior_tangential``) and the
displacements (``displacement``) are all written in these quantities.  Pure NumPy.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["geometry", "coords", "one_minus_m_atan", "x_minus_sin"]

# 1 - atan(t)/t = sum_k (-1)^(k+1) t^(2k) / (2k+1); 28 terms reach 0.25^28/57 < 1e-18 at t = 1/2
_ATAN_DEFECT = [(-1.0) ** (k + 1) / (2 * k + 1) for k in range(1, 29)]


def one_minus_m_atan(M):
    """F(M) = 1 - M arctan(1/M) for M >= 0 (F(0) = 1), docs/theory/interior.md (I4).  The direct
    form loses the digits of F ~ 1/(3 M^2) for large M (the far field); there the series in
    t = 1/M is used (t < 1/2), and (t - atan t)/t, which loses at most one digit, for 1/2 <= t < 1."""
    M = np.asarray(M)
    M = M.astype(np.result_type(M.dtype, np.float64))   # keeps np.longdouble (the tests' reference)
    out = np.empty_like(M)
    small = M <= 1.0
    out[small] = 1.0 - M[small] * (0.5 * math.pi - np.arctan(M[small]))
    t = 1.0 / M[~small]
    t2 = t * t
    series = np.zeros_like(t)
    for c in _ATAN_DEFECT[::-1]:
        series = series * t2 + c
    series *= t2
    mid = t >= 0.5
    series[mid] = (t[mid] - np.arctan(t[mid])) / t[mid]
    out[~small] = series
    return out


def geometry(x, y, z, rm1=None):
    """The quantities of docs/theory/interior.md (I2)-(I3), with a = 1: r^2, A = r^2 + z^2 - 1
    (as (r-1)(r+1) + z^2, exact next to the edge ring), S = sqrt(A^2 + 4 z^2), M, N with
    M^2 - N^2 = A and M N = z (the larger one from its square root, the other as z over it),
    W = r^2 + z^2 + 1 + S = 2 (1 + M^2), Q = 1 - N^2 = 2 r^2 / W, and R = N^2 / S (0 on the edge
    ring, where S = 0 and N = 0).  ``rm1``, if given, is r - 1 computed by the caller without the
    rounding of r = |x| / a (the superposition knows it from the node's offset)."""
    r2 = x * x + y * y
    if rm1 is None:
        rm1 = np.sqrt(r2) - 1.0
    A = rm1 * (rm1 + 2.0) + z * z
    S = np.hypot(A, 2.0 * z)
    big = A >= 0.0
    with np.errstate(invalid="ignore", divide="ignore"):
        root = np.sqrt(0.5 * (S + np.abs(A)))
        other = np.where(root > 0.0, z / np.where(root > 0.0, root, 1.0), 0.0)
    M = np.where(big, root, other)
    N = np.where(big, other, root)
    W = r2 + z * z + 1.0 + S
    Q = 2.0 * r2 / W
    with np.errstate(invalid="ignore", divide="ignore"):
        R = np.where(S > 0.0, N * N / np.where(S > 0.0, S, 1.0), 0.0)
    return dict(r2=r2, z=z, S=S, M=M, N=N, W=W, Q=Q, R=R)


def coords(x, y, z):
    x, y, z = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (x, y, z)))
    if np.any(z < 0.0):
        raise ValueError("z (depth below the surface) must be >= 0")
    return x, y, z


# x - sin x = sum_k (-1)^(k+1) x^(2k+1) / (2k+1)!; 12 terms reach 1/25! < 1e-25 at x = 1
_X_MINUS_SIN = [(-1.0) ** (k + 1) / math.factorial(2 * k + 1) for k in range(1, 13)]


def x_minus_sin(x, sin_x):
    """x - sin x for 0 <= x <= 2 pi: the series below x = 1 (where the difference loses the digits
    of x^3/6, e.g. 8 digits at x = 1e-4, the far field), the direct difference above (at most one
    digit lost: 1 - sin 1 = 0.16).  ``sin_x`` is sin x formed algebraically by the caller."""
    small = x < 1.0
    x2 = x * x
    series = np.zeros_like(x)
    for c in _X_MINUS_SIN[::-1]:
        series = series * x2 + c
    return np.where(small, series * x2 * x, x - sin_x)
