"""Frictionless normal contact: surface (z = 0) stresses and d p_h/dz, divided by E*.

E. Willert, F. Forsbach, V. L. Popov, "Stress tensor and gradient of hydrostatic pressure in the
contact plane of axisymmetric bodies under normal and tangential loading".  Closed forms: eq. (1)
and (5) (paraboloid, Huber/Hertz), eq. (36)-(37) (cone), eq. (3) and the regular part of (6) (flat
punch, times its depth).  General profile: eq. (9) and (11) evaluated by the 1-D integrals of
``integrals``.  Signs and conventions as docs/theory/axisymmetric.md section 2 (tension positive, z
into the body); equations docs/theory/axisymmetric.md (A12)-(A30).

Functions here work on 1-D arrays of points with r > 0 (the public wrappers in ``surface`` handle
broadcasting, validation and r = 0).  Polar results are returned as (szz, srr, sff, dev) with
dev = (srr - sff)/2 computed without cancellation.
"""
from __future__ import annotations

import math

import numpy as np

from .common import arccosh_ratio, asin_defect, sqrt_diff
from .integrals import pressure_gradient_D, pressure_gradient_far

__all__ = ["polar_closed", "polar_from_integrals", "dpdz_closed", "dpdz_quadrature", "origin"]


def _err():
    return np.errstate(divide="ignore", invalid="ignore", over="ignore")


def polar_closed(closed, r, a, nu):
    """(szz, srr, sff, dev) of the closed forms (1), (3), (36) (docs/theory/axisymmetric.md (A12)-(A13),
    (A18)-(A21), in the stable forms (A80)-(A83)); r > 0.  r <= a counts as contact."""
    kind = closed[0]
    inside = r <= a
    s = sqrt_diff(a, r)                      # sqrt(a^2 - r^2) inside
    q = 1.0 - 2.0 * nu
    with _err():
        if kind == "cone":
            p0 = 0.5 * closed[1]
            L = np.where(inside, arccosh_ratio(a, np.minimum(r, a)), 0.0)
            B = a / (a + s)                  # (a^2/r^2)(1 - sqrt(1 - r^2/a^2)), stable form (A80)
            szz = np.where(inside, -p0 * L, 0.0)
            out_rr = 0.5 * q * p0 * (a / r) ** 2
            srr = np.where(inside, p0 * (0.5 * q * B - 0.5 * (1.0 + 2.0 * nu) * L), out_rr)
            dev = np.where(inside, 0.5 * q * p0 * B, out_rr)
        elif kind == "paraboloid":
            P = 2.0 / (math.pi * closed[1])   # p0 / a
            Q = q * (a * a + a * s + s * s) / (3.0 * (a + s))   # (1-2nu)(a^3 - s^3)/(3 r^2), stable
            szz = np.where(inside, -P * s, 0.0)
            out_rr = P * q * a ** 3 / (3.0 * r * r)
            srr = np.where(inside, P * (Q - s), out_rr)
            # (srr - sff)/2 = (1-2nu) P r^2 (2a + s) / (6 (a + s)^2) inside (no cancellation at r -> 0)
            dev = np.where(inside, q * P * r * r * (2.0 * a + s) / (6.0 * (a + s) ** 2), out_rr)
        elif kind == "flat_punch":
            P = closed[2] / math.pi           # depth / pi
            szz = np.where(inside, -P / s, 0.0)
            out_rr = P * q * a / (r * r)
            srr = np.where(inside, P * (q / (a + s) - 1.0 / s), out_rr)
            dev = np.where(inside, 0.5 * P * q * (2.0 / (a + s) - 1.0 / s), out_rr)
            dev = np.where(inside & (q == 0.0), 0.0, dev)
        else:  # pragma: no cover - guarded by the caller
            raise ValueError(f"no closed form for {kind!r}")
    sff = np.where(inside, srr - 2.0 * dev, -srr)
    if kind == "flat_punch":
        # at the edge srr - 2 dev is inf - inf; the limit is -(1-2nu)/(a+s) P - 2 nu P / s
        with _err():
            ff = P * (-q / (a + s) - np.where(nu > 0.0, 2.0 * nu / s, 0.0))
        sff = np.where(inside, ff, -srr)
    return szz, srr, sff, dev


#: r / a below which F(r)/r^2 is its tip term (see ``polar_from_integrals``)
_TIP = 1e-100


def polar_from_integrals(profile, r, a, nu, G, GE):
    """(szz, srr, sff, dev) of eq. (9) from the t-integrals over [0, arccosh(a/r)] (zero outside):
    G = int g'(u)/sqrt(u^2-r^2) du and GE = the same with weight exp(-2t).

    The load bracket of eq. (9), F_N - 2 int_r^a sqrt(u^2-r^2) g' du, is a difference of O(1)
    terms that is O(r^2): as written it loses (a/r)^2 relative digits as r -> 0.  It is rewritten as
    F(r) + 2 r^2 int_r^a g'(u) du / (u + sqrt(u^2 - r^2)), F(r) = 2 int_0^r u g' du (the force of
    the same profile at contact radius r), whose terms are both O(r^2) (docs/theory/axisymmetric.md
    (A84)).  With u = r cosh t,
    du / (u + s) = (1 - e^{-2t})/2 dt, so the integral is (G - GE)/2."""
    inside = r <= a
    h = np.minimum(r, a)
    with _err():
        force = 0.5 * profile.normal_force(h) / (r * r)
        # F(r)/r^2 -> 2 B r^m/(m + 2) at the tip.  Below r = 1.5e-154 the square r^2 is subnormal
        # (it kept 1e-4 p_m of error at r = 1e-160 a) or 0, and F(r) too; the tip term is exact for
        # a power law and off by a relative O(r/knot) for a table, so it is taken below 1e-100 a
        m, B = profile.tip_exponent, profile.tip_coefficient
        force = np.where(r > _TIP * a, force, B * r ** m / (m + 2.0))
    K = force + np.where(inside, 0.5 * (G - GE), 0.0)
    szz = np.where(inside, -G / math.pi, 0.0)
    q = 1.0 - 2.0 * nu
    srr = szz + q / math.pi * K
    # srr - sff = 2 srr - (1 + 2 nu) szz = (1 - 2nu)(szz + 2K/pi)
    dev = 0.5 * q * (szz + 2.0 * K / math.pi)
    sff = srr - 2.0 * dev
    return szz, srr, sff, dev


def _C(nu):
    return 2.0 * (1.0 + nu) / (3.0 * math.pi)


def dpdz_closed(closed, r, a, nu):
    """Normal-load d p_h/dz / E* at z = 0+: eq. (5) paraboloid, (37) cone, regular part of (6) flat
    punch; r > 0; r <= a counts as contact (value of the inside branch)."""
    kind = closed[0]
    inside = r <= a
    s = sqrt_diff(r, a)                      # sqrt(r^2 - a^2) outside
    C2 = 2.0 * (1.0 + nu) / 3.0
    with _err():
        if kind == "cone":
            p0 = 0.5 * closed[1]
            # 1/sqrt(r^2-a^2) - 1/r = a^2 / (r s (r + s)), docs/theory/axisymmetric.md (A91)
            return np.where(inside, -C2 * p0 / r, C2 * p0 * a * a / (r * s * (r + s)))
        if kind == "paraboloid":
            R = closed[1]
            return np.where(inside, -C2 / R,
                            2.0 * C2 / (math.pi * R) * asin_defect(a, np.maximum(r, a)))
        if kind == "flat_punch":
            depth = closed[2]
            return np.where(inside, 0.0, C2 * depth * a / (math.pi * s ** 3))
    raise ValueError(f"no closed form for {kind!r}")  # pragma: no cover


def dpdz_quadrature(profile, r, a, nu, ords):
    """Normal-load d p_h/dz / E*, eq. (11): -C D(r) inside; the by-parts form
    C [g'(a)/sqrt(r^2-a^2) - D(r)] for a < r <= 2a (docs/theory/axisymmetric.md (A26)); the direct
    outside integral for r > 2a (A86), where the by-parts form would cancel like (r/a)^2.
    C = 2(1+nu)/(3 pi)."""
    out = np.empty(r.size)
    inside = r <= a
    near = ~inside & (r <= 2.0 * a)
    far = r > 2.0 * a
    with _err():
        if np.any(inside):
            i = np.flatnonzero(inside)
            D = pressure_gradient_D(profile, r[i], np.full(i.size, 0.5 * math.pi), ords)
            out[i] = -_C(nu[i]) * D
        if np.any(near):
            i = np.flatnonzero(near)
            s = sqrt_diff(r[i], a[i])
            th = np.arctan2(a[i], s)
            D = pressure_gradient_D(profile, r[i], th, ords)
            out[i] = _C(nu[i]) * (profile.dg(a[i]) / s - D)
        if np.any(far):
            i = np.flatnonzero(far)
            th = np.arcsin(a[i] / r[i])
            out[i] = _C(nu[i]) / r[i] * pressure_gradient_far(profile, r[i], th, ords)
    return out


def origin(info, a, nu, log0, d2g0):
    """Limits at r = 0 (inside the contact).  ``info``: ("flat_punch", radius, depth) or
    ("tip", m0, B) with g'(u) ~ B u^m0.  log0 = int_0^a g'(u)/u du (finite iff m0 > 0),
    d2g0 = g''(0).  Returns (szz, sxx, sxy, dpdz): sxx = syy by symmetry; sxy is NaN for a
    conical or sharper tip (its limit depends on the direction) unless nu = 1/2."""
    C = _C(nu)
    if info[0] == "flat_punch":
        depth = info[2]
        szz = -depth / (math.pi * a)
        sxx = -(1.0 + 2.0 * nu) * depth / (2.0 * math.pi * a)
        return szz, sxx, np.zeros_like(a), np.zeros_like(a)
    m0 = info[1]
    if m0 <= 0.0:
        inf = np.full(a.shape, -math.inf)
        sxy = np.where(nu == 0.5, 0.0, np.nan)
        return inf, inf, sxy, inf
    szz = -log0 / math.pi
    sxx = 0.5 * (1.0 + 2.0 * nu) * szz
    if m0 < 1.0:
        dp = np.full(a.shape, -math.inf)
    else:
        dp = -C * 0.5 * math.pi * d2g0
    return szz, sxx, np.zeros_like(a), dp + 0.0 * a
