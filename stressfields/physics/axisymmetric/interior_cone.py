"""The cone below the surface under normal load in closed form (Sneddon 1948): the superposition
(I15) of flat punches with g' constant, integrated over the punch radius analytically,
docs/theory/interior.md (I46)-(I52).

Coordinates are divided by the contact radius a, stresses by E* tan(theta)/2 (the scale of the
cone's pressure p = (E* tan(theta)/2) arccosh(a/r)), d p_h/dz by E* tan(theta)/(2a).  Every
quantity is written as a sum of terms of one sign or with its small factor (r^2 near the axis,
(a/R)^2 in the far field, z at the surface) taken out analytically, so that the axis, the far
field (R = 1e4 a) and the tip (r = 0, z -> 0, where the stresses grow like log(1/z)) lose no digits.

Accuracy contract: closed forms, relative error at most 1e-12 of |value| everywhere the value is
finite, far field and next to edges included (where a component passes through zero, as the sum
Sigma = sigma_rr + sigma_tt and the Cartesian in-plane components do: of its largest term).  Pure NumPy.
"""
from __future__ import annotations

import math

import numpy as np
from ..flags import quiet

from .hertz_geometry import coords, geometry

__all__ = ["cone_unit", "cone_dpdz_unit"]

# sinh(t) - t = sum_k t^(2k+1)/(2k+1)!, k >= 1; 12 terms reach 1/25! < 1e-25 at t = 1
_SINH_MINUS = [1.0 / math.factorial(2 * k + 1) for k in range(1, 13)]


def _sinh_minus(t):
    """sinh t - t for t >= 0: the series below t = 1 (the direct difference loses the digits of
    t^3/6, all of them in the far field, where t ~ (a/R)^2), the difference above (no digit lost)."""
    t2 = t * t
    series = np.zeros_like(t)
    for c in _SINH_MINUS[::-1]:
        series = series * t2 + c
    with np.errstate(over="ignore"):
        return np.where(t < 1.0, series * t2 * t, np.sinh(np.maximum(t, 1.0)) - t)


def _ratio(num, den):
    """num / den with 0 where den = 0 (there num = 0 too: the limits named by the callers)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(den > 0.0, num / np.where(den > 0.0, den, 1.0), 0.0)


def _cone_scalars(x, y, z, nu):
    """L, J, Sigma, sigma_zz, E = (sigma_rr - sigma_tt)/r^2 and T = sigma_rz/r of the cone per
    E* tan(theta)/2 (a = 1), docs/theory/interior.md (I46)-(I50), with l2 = sqrt(1 + M^2) and
    R the distance from the tip (R^2 = 1 + M^2 - N^2)."""
    g = geometry(x, y, z)
    M, N, S = g["M"], g["N"], g["S"]
    opm = 1.0 + M * M
    l2 = np.sqrt(opm)
    r = np.hypot(x, y)                                      # not sqrt(x^2 + y^2): it underflows below 1e-154
    r2 = r * r
    R = np.hypot(r, z)                                      # > 0 for z > 0
    n_s, m_s = _ratio(N * N, S), _ratio(M * M, S)           # each <= 1; 0 on the edge ring (S = 0)
    # (I46): L = ln((l2 + N l2)/(R + z)) as log1p of a sum of positive terms (no far-field loss)
    L = np.log1p(N * (N / (l2 + R) + _ratio(N, N * l2 + z)) / (R + z))
    # (I47): J = L - c sinh L = L (1 - c) - c (sinh L - L), c = r^2/(l2 R) = sech t_a sech t_0
    with np.errstate(invalid="ignore", divide="ignore"):
        rr, zr = r / R, z / R                   # each <= 1: no R^2 (it underflows next to the tip)
        c = r * rr / l2
        omc = (N * N * opm + r2 * zr * zr) / (l2 * (l2 + r * rr))    # 1 - c, a sum of positive terms
    J = L * omc - c * _sinh_minus(L)
    zz = -N * n_s - J
    trace = -2.0 * (1.0 + nu) * L
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):      # E ~ 1/z^2 at the tip
        e0 = -N * M * (1.0 + M * R + M * M) / (opm * opm * (R + M) ** 2 * R) - N * m_s / (opm * opm)   # (I49)
        ev = (1.0 - 2.0 * nu) * (1.0 / (R + z) + M / opm) / (opm * (1.0 + N) * (M + R))
        T = -M * n_s / opm - N * _ratio(N * z, N * R + z) / (opm * R)                                  # (I50)
        E = e0 + ev
    # E r^2 from factors <= 1 (M/(R + M), r/(R + M), r/R, ...): E ~ 1/z^2 overflows next to the tip,
    # E r^2 is O(1) there (the in-plane stresses grow only like log)
    mr, rm = _ratio(M, R + M), _ratio(r, R + M)
    e0r2 = -N * (1.0 + M * R + M * M) / (opm * opm) * mr * rm * rr - N * m_s * r2 / (opm * opm)
    evr2 = (1.0 - 2.0 * nu) * (r / (R + z) + M * r / opm) * _ratio(r, M + R) / (opm * (1.0 + N))
    return dict(L=L, J=J, Sigma=trace - zz, zz=zz, E=E, Er2=e0r2 + evr2, T=T, r=r)


@quiet
def cone_unit(x, y, z, nu) -> dict[str, np.ndarray]:
    """Stress tensor below the surface of a rigid cone pressed to the contact radius 1, divided by
    E* tan(theta)/2, at coordinates divided by the contact radius; docs/theory/interior.md
    (I46)-(I51) (Sneddon 1948; the punch superposition (I15) integrated in closed form).  Finite
    for z > 0 (like log(1/R) next to the tip, R the distance from it), continuous on the edge ring
    r = 1, z = 0; at z = 0 the surface values ((A12)-(A13) of docs/theory/axisymmetric.md) off the
    tip.  Closed form: relative error at most 1e-12 of |value| everywhere the value is finite
    (where a component passes through zero: of its largest term)."""
    x, y, z = coords(x, y, z)
    nu = np.asarray(nu, dtype=float)
    s = _cone_scalars(x, y, z, nu)
    r = s["r"]
    # (I8) with E r^2 and the direction (x/r, y/r): no E (it overflows next to the tip), no r^2
    # (it underflows for r < 1e-154 a)
    ux, uy = _ratio(x, r), _ratio(y, r)
    d = 0.5 * s["Er2"] * (ux * ux - uy * uy)
    half = 0.5 * s["Sigma"]
    return {"xx": half + d, "yy": half - d, "zz": s["zz"], "xy": s["Er2"] * ux * uy, "xz": x * s["T"],
            "yz": y * s["T"]}


@quiet
def cone_dpdz_unit(x, y, z, nu) -> np.ndarray:
    """d p_h/dz of the cone, divided by E* tan(theta)/(2a), at coordinates divided by the contact
    radius: p_h = (2/3)(1 + nu) L (I46), d L/dz = M/S - 1/R written as
    (M^2 - 3 M^2 N^2 - N^4)/(S R (M R + S)) (I52), free of the far-field cancellation of the two
    terms.  Finite for z > 0.  Closed form: relative error at most 1e-12 of |value| where the value
    is finite (where it passes through zero: of the largest term of the numerator)."""
    x, y, z = coords(x, y, z)
    g = geometry(x, y, z)
    M, N, S = g["M"], g["N"], g["S"]
    R = np.hypot(np.hypot(x, y), z)               # x^2 + y^2 underflows below 1e-154 a
    m2, n2 = M * M, N * N
    with np.errstate(invalid="ignore", divide="ignore"):
        dl = (m2 - 3.0 * m2 * n2 - n2 * n2) / (S * R * (M * R + S))
    return (2.0 / 3.0) * (1.0 + np.asarray(nu, dtype=float)) * dl
