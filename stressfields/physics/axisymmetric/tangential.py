"""Cattaneo–Mindlin tangential contact: surface (z = 0) stresses and d p_h/dz, divided by E*.

E. Willert, F. Forsbach, V. L. Popov, "Stress tensor and gradient of hydrostatic pressure in the
contact plane of axisymmetric bodies under normal and tangential loading".  Traction on the
half-space along +x (docs/theory/axisymmetric.md section 2): sigma_xz = -q = mu [sigma_zz(r; a) -
sigma_zz(r; c)], eq. (24), docs/theory/axisymmetric.md (A34);
stick radius c (c = 0: gross slip).  Closed forms: cone eq. (39)-(41); paraboloid eq. (14)-(17),
(21) with the stick-zone difference; sliding flat punch eq. (18), (19), regular part of (22) times
its depth.  General profile: eq. (24)-(26) from the 1-D integrals of ``integrals``.

Functions work on 1-D arrays of points with r > 0 where the tangential load is active
(mu > 0, c < a).  Points with r <= c count as stick zone, r <= a as contact.
"""
from __future__ import annotations

import math

import numpy as np

from ..quadrature import gauss_legendre
from .common import arccosh_ratio, sqrt_diff

__all__ = ["shear_closed", "inplane_closed", "dpdz_closed", "shear_from_integrals",
           "inplane_from_moments", "dpdz_from_integrals", "inplane_angles"]


def _err():
    return np.errstate(divide="ignore", invalid="ignore", over="ignore")


def _zero_where_x0(x, v):
    """x * (something infinite) on the edge circles: the radial limit along x = 0 is 0."""
    return np.where(x == 0.0, 0.0, v)


#: annulus widths w <= _THIN_WIDTH a take the forms of (A109); wider ones the plain differences of
#: the rounded radii, which lose at most 1e-16 a/w (1e-13) there, so that their values stay bit for bit
_THIN_WIDTH = 1e-3


def thin(a, w):
    """Where the slip annulus' width ``w`` (None: not known) is thin, w <= ``_THIN_WIDTH`` a."""
    return np.zeros(np.shape(a), dtype=bool) if w is None else (w <= _THIN_WIDTH * a)


def _width(a, c, w):
    """The slip annulus' width a - c: ``w`` (from the exact slip ratio, ``profiles.annulus_width``)
    where the annulus is thin, else the difference of the rounded radii."""
    return a - c if w is None else np.where(thin(a, w), w, a - c)


def _near(r, a, w):
    """Points where the offsets of (A109) apply: a thin annulus and r >= a/2 (a - r exact there,
    Sterbenz; nearer the centre a - r would carry 1e-16 a into c - r without need)."""
    return thin(a, w) & (r >= 0.5 * a)


def _stick_root(r, a, c, w):
    """sqrt(c^2 - r^2) (0 for r >= c), with c - r = (a - r) - w at ``_near`` points: next to a thin
    slip annulus the rounding of c (1e-16 a) is not magnified by 1/(c - r)
    (docs/theory/axisymmetric.md (A109))."""
    plain = sqrt_diff(c, r)
    if w is None:
        return plain
    return np.where(_near(r, a, w), np.sqrt(np.maximum(((a - r) - w) * (c + r), 0.0)), plain)


def _slip_difference(r, a, c, w):
    """r - c, as (r - a) + w at ``_near`` points (``_stick_root``)."""
    return r - c if w is None else np.where(_near(r, a, w), (r - a) + w, r - c)


def _slip_root(r, a, c, w):
    """sqrt(r^2 - c^2) (0 for r <= c), with ``_slip_difference``."""
    if w is None:
        return sqrt_diff(r, np.minimum(r, c))
    return np.sqrt(np.maximum(_slip_difference(r, a, c, w) * (r + c), 0.0))


def shear_closed(closed, r, a, c, mu, w=None):
    """sigma_xz / E*: cone eq. (39), paraboloid eq. (14) with the stick-zone difference, flat punch
    eq. (18) (sliding; its stick radius plays no role).  ``w``: the annulus width a - c where known
    more accurately than from the rounded c (``_width``)."""
    kind = closed[0]
    sa, sc = sqrt_diff(a, r), _stick_root(r, a, c, w)
    wd = _width(a, c, w)
    with _err():
        if kind == "cone":
            p0 = 0.5 * closed[1]
            stick = r <= c
            # ln((a + sqrt(a^2-r^2)) / (c + sqrt(c^2-r^2))): no difference of two arccosh (A36)
            v_stick = np.log((a + sa) / np.where(stick, c + sc, 1.0))
            # thin annulus: log1p((a - c + sa - sc)/(c + sc)), sa - sc = (a - c)(a + c)/(sa + sc) (A109)
            v_stick = np.where(thin(a, w), np.log1p((wd + wd * (a + c) / (sa + sc)) / np.where(stick, c + sc, 1.0)),
                               v_stick)
            v_slip = arccosh_ratio(a, np.minimum(r, a))
            return np.where(r <= a, -mu * p0 * np.where(stick, v_stick, v_slip), 0.0)
        if kind == "paraboloid":
            P = 2.0 / (math.pi * closed[1])
            # stick zone: sa - sc = (a - c)(a + c)/(sa + sc), no cancellation as c -> a (A99)
            v = np.where(r <= c, wd * (a + c) / (sa + sc), sa)
            return -mu * P * np.where(r <= a, v, 0.0)
        if kind == "flat_punch":
            return np.where(r <= a, -mu * closed[2] / (math.pi * sa), 0.0)
    raise ValueError(f"no closed form for {kind!r}")  # pragma: no cover


def _root_ratio(r, b):
    """sqrt(r^2 - b^2)/r as sqrt(((r - b)/r) ((r + b)/r)) (0 for r <= b): r - b is exact near the
    edge r = b (docs/theory/axisymmetric.md (A78)), the value is exactly 1 for b = 0, and no r^2 is
    formed (it underflows below r = 1.5e-154)."""
    return np.sqrt(np.maximum(((r - b) / r) * ((r + b) / r), 0.0))


def _cone_e3(A, Cc, a, c, r, outside):
    """E3 = 3 - A^2 - A C - C^2 with A = sqrt(1 - a^2/r^2) (0 inside), C = sqrt(1 - c^2/r^2):
    with alpha = a^2/r^2, gamma = c^2/r^2 and 1 - AC = (alpha + gamma - alpha gamma)/(1 + AC),
    E3 = alpha + gamma + (alpha + gamma - alpha gamma)/(1 + AC) outside (every term positive),
    3 - C^2 = 2 + gamma inside (docs/theory/axisymmetric.md (A96))."""
    alpha, gamma = (a / r) ** 2, (c / r) ** 2
    out = alpha + gamma + (alpha + gamma - alpha * gamma) / (1.0 + A * Cc)
    return np.where(outside, out, 2.0 + gamma)


# Gauss–Legendre rule for the Hertz moments: sin^2 t and sin^2 t cos^2 t are trigonometric
# polynomials of degree 4, so on an interval of length <= pi/2 a 12-point rule errs by less than
# (pi/2)^25 (12!)^4 4^24 / (25 (24!)^3) = 2e-19 of the integrand's scale (and, as the interval
# shrinks, by a further factor (length)^24): exact to rounding, with positive terms only.
_HK_NODES, _HK_WEIGHTS = (v.copy() for v in gauss_legendre(12))


def _hertz_angles(r, a, c, w=None):
    """(theta_c, theta_a - theta_c) with theta_b = arcsin(min(r, b)/r): the difference from
    sin(theta_a - theta_c) = (a - c)(a + c)/(a s_c + c s_a) and cos = (s_a s_c + a c)/r^2 (s_b =
    sqrt(r^2 - b^2), 0 inside), so that a - c, exact in floating point near c = a, carries it
    (docs/theory/axisymmetric.md (A100))."""
    sa, sc = sqrt_diff(r, np.minimum(r, a)), _slip_root(r, a, c, w)
    wd = _width(a, c, w)
    th_c = np.where(r <= c, 0.5 * math.pi, np.arctan2(c, sc))
    # r <= c: empty; c < r <= a: arccos(c/r); r > a: the difference of the two arcsines
    slip = np.arctan2(sc, c)
    with np.errstate(invalid="ignore", divide="ignore"):
        outer = np.arctan2(r * r * (wd * (a + c) / (a * sc + c * sa)), sa * sc + a * c)
    delta = np.where(r <= c, 0.0, np.where(r <= a, slip, outer))
    return th_c, delta


def _hertz_hk(r, a, c, w=None):
    """H / r^4 = 2 int sin^4 t dt and K / r^4 = 2 int sin^2 t cos^2 t dt over [theta_c, theta_a],
    with F / r^2 = H + K of eqs. (16)-(17) (A49) and the difference a - c
    (docs/theory/axisymmetric.md (A101)): one Gauss–Legendre rule on the interval itself, so that
    neither the far field nor c -> a cancels."""
    th_c, delta = _hertz_angles(r, a, c, w)
    t = th_c[..., None] + delta[..., None] * _HK_NODES
    s2 = np.sin(t) ** 2
    w = 2.0 * delta[..., None] * _HK_WEIGHTS
    H = (w * s2 * s2).sum(axis=-1)
    K = (w * s2 * np.cos(t) ** 2).sum(axis=-1)
    return H, K


def inplane_closed(closed, x, y, r, a, c, nu, mu, w=None):
    """(sxx, syy, sxy) / E* of the tangential load: cone eq. (40), paraboloid eqs. (15)-(17) (in the
    positive-term form (A101), its moments by a rule exact to rounding), flat punch eq. (19).  Zero
    in the stick zone r <= c.  ``w`` as ``shear_closed``."""
    kind = closed[0]
    X, Y = x / r, y / r
    X2, Y2 = X * X, Y * Y
    with _err():
        if kind == "cone":
            p0 = 0.5 * closed[1]
            outside = r > a
            # A = sqrt(1 - a^2/r^2), C = sqrt(1 - c^2/r^2) without r^2: r * r underflows to 0 below
            # r = 1.5e-154 a, and C = sqrt_diff(r, c)/r then dropped the gross-slip (c = 0, C = 1) part
            A = np.where(outside, _root_ratio(r, a), 0.0)
            Cc = _root_ratio(r, c)
            if w is not None:   # as _root_ratio, with r - c from the annulus width (A109)
                Cc = np.where(_near(r, a, w), np.sqrt(np.maximum((_slip_difference(r, a, c, w) / r) * ((r + c) / r),
                                                                 0.0)), Cc)
            wd = _width(a, c, w)
            # C - A without cancellation far outside: ((a^2 - c^2)/r^2) / (A + C), docs/theory/axisymmetric.md (A90)
            D1 = np.where(outside, (wd / r) * ((a + c) / r) / (A + Cc), Cc)
            # A^3 - C^3 = -D1 (3 - E3): the brackets of eq. (40) are written with E3 = 3 - A^2 - AC - C^2,
            # formed without cancellation (A96), so that their O(1) parts cancel exactly (by algebra, not
            # in rounding: sigma_yy at nu = 1/2, r = 1e6 a was 1.3e-5 relative off) and what remains is O(a^2/r^2)
            E3 = _cone_e3(A, Cc, a, c, r, outside)
            k = mu * p0
            sxx = 2.0 * k * X * D1 * (-(1.0 - 2.0 * nu) - 3.0 * nu * X2 + nu / 3.0 * (4.0 * X2 - 3.0) * E3)
            syy = -2.0 * nu * k * X * D1 * (3.0 * Y2 + (1.0 - 4.0 * Y2) / 3.0 * E3)
            sxy = k * Y * D1 * (-(1.0 - 2.0 * nu) - 6.0 * nu * X2 + 2.0 * nu / 3.0 * (4.0 * X2 - 1.0) * E3)
        elif kind == "paraboloid":
            H, K = _hertz_hk(r, a, c, w)
            k = mu / (math.pi * closed[1])
            # eqs. (15)-(17) with F = H + K: every bracket a sum of non-negative terms (A101)
            sxx = -2.0 * k * x * ((1.0 + nu * Y2) * H + ((1.0 + nu) - 3.0 * nu * Y2) * K)
            syy = -2.0 * nu * k * x * (X2 * H + 3.0 * Y2 * K)
            sxy = -k * y * ((1.0 - 2.0 * nu * X2) * H + ((1.0 - 2.0 * nu) + 6.0 * nu * X2) * K)
        elif kind == "flat_punch":
            depth = closed[2]
            outside = r > a
            s = np.where(outside, sqrt_diff(r, a), 1.0)
            b2 = (a / r) ** 2
            wy = b2 + Y2 * (3.0 - 4.0 * b2)                 # W_y / r^4
            wx = b2 + X2 * (3.0 - 4.0 * b2)
            k = mu * depth * a / (math.pi * r * r * s)
            sxx = np.where(outside, -2.0 * k * x * ((1.0 + nu) - nu * wy), 0.0)
            syy = np.where(outside, -2.0 * nu * k * x * wy, 0.0)
            sxy = np.where(outside, -k * y * ((1.0 - 2.0 * nu) + 2.0 * nu * wx), 0.0)
            return sxx, syy, sxy
        else:  # pragma: no cover
            raise ValueError(f"no closed form for {kind!r}")
    stick = r <= c
    return (np.where(stick, 0.0, sxx), np.where(stick, 0.0, syy), np.where(stick, 0.0, sxy))


def dpdz_closed(closed, x, r, a, c, nu, mu, w=None):
    """Tangential d p_h/dz / E*: cone eq. (41), paraboloid eq. (21) with the stick-zone difference,
    flat punch regular part of eq. (22).  +-inf on r = c (stick side) and r = a (contact side),
    with the sign of x; 0 there on x = 0 (radial limit).  ``w`` as ``shear_closed``."""
    kind = closed[0]
    sa, sc = sqrt_diff(a, r), _stick_root(r, a, c, w)
    wd = _width(a, c, w)
    C2 = 2.0 * (1.0 + nu) / 3.0
    inside, stick = r <= a, r <= c
    with _err():
        if kind == "cone":
            k = C2 * mu * 0.5 * closed[1]
            # (a/sqrt(a^2-r^2) - c/sqrt(c^2-r^2)) / r^2 = 1/(sa(a+sa)) - 1/(sc(c+sc)), docs/theory/axisymmetric.md (A89)
            v_stick = -k * x * (1.0 / (sa * (a + sa)) - 1.0 / (sc * (c + sc)))
            # thin annulus: = -(a^2 - c^2)/(sa sc (a sc + c sa)), the difference written out (A109)
            v_stick = np.where(thin(a, w), k * x * (wd * (a + c)) / (sa * sc * (a * sc + c * sa)), v_stick)
            v_slip = -k * (x / r) * (a / r) / sa   # not x a / (r^2 sa): r^2 underflows at r = 1e-300
            v = np.where(stick, v_stick, np.where(inside, v_slip, 0.0))
        elif kind == "paraboloid":
            k = 2.0 * C2 * mu / (math.pi * closed[1])
            # stick zone: 1/sa - 1/sc = -(a - c)(a + c)/(sa sc (sa + sc)), no cancellation as c -> a (A100)
            v_stick = np.where(c == a, 0.0, -wd * (a + c) / (sa * sc * (sa + sc)))
            v = -k * x * np.where(stick, v_stick, np.where(inside, 1.0 / sa, 0.0))
        elif kind == "flat_punch":
            v = np.where(inside, C2 * mu * closed[2] * x / (math.pi * sa ** 3), 0.0)
        else:  # pragma: no cover
            raise ValueError(f"no closed form for {kind!r}")
    return _zero_where_x0(x, v)


# -- general profile ----------------------------------------------------------------------------

def shear_from_integrals(r, a, mu, G_slip):
    """sigma_xz / E* = -(mu/pi) int_max(r,c)^a g'(u) du / sqrt(u^2 - r^2), eq. (24); G_slip is that
    integral (t over [arccosh(max(r,c)/r), arccosh(a/r)])."""
    return np.where(r <= a, -mu / math.pi * G_slip, 0.0)


def inplane_angles(r, a, c, w=None):
    """Integration limits of eq. (25) in t (u = r sin t): [arcsin(min(r,c)/r), arcsin(min(r,a)/r)];
    ``w`` as ``shear_closed`` (sqrt(r^2 - c^2) from the annulus width, (A109))."""
    th_hi = np.where(r <= a, 0.5 * math.pi, np.arctan2(a, sqrt_diff(r, a)))
    th_lo = np.where(r <= c, 0.5 * math.pi, np.arctan2(c, _slip_root(r, a, c, w)))
    return th_lo, th_hi


def inplane_from_moments(x, y, r, nu, mu, P0, P2):
    """(sxx, syy, sxy) / E* of eq. (25) from P0 = I[1]/r and P2 = I[u^2]/r^3: with X = x/r,
    Y = y/r the r^-6 prefactors cancel, so nothing is divided by a small r."""
    X, Y = x / r, y / r
    X2, Y2 = X * X, Y * Y
    k = mu / math.pi
    sxx = -2.0 * k * X * (((1.0 + nu) - 3.0 * nu * Y2) * P0 - nu * (1.0 - 4.0 * Y2) * P2)
    syy = -2.0 * nu * k * X * (3.0 * Y2 * P0 + (1.0 - 4.0 * Y2) * P2)
    sxy = -k * Y * (((1.0 - 2.0 * nu) + 6.0 * nu * X2) * P0 + 2.0 * nu * (1.0 - 4.0 * X2) * P2)
    return sxx, syy, sxy


def dpdz_from_integrals(profile, x, r, a, c, nu, mu, H_slip):
    """Tangential d p_h/dz / E*, eq. (26), in a form free of the r -> 0 cancellation of its bracket:
    with psi(v) = 1/(sqrt(v^2-r^2)(v + sqrt(v^2-r^2))) = (v/sqrt(v^2-r^2) - 1)/r^2,

      r <= c:      -C_T x [g'(a) psi(a) - g'(c) psi(c) - int_c^a g''(u) psi(u) du]
      c < r <= a:  -C_T x [g'(r)/r^2 + g'(a) psi(a) - int_r^a g''(u) psi(u) du]

    (the identity a g'(a)/sqrt(a^2-r^2) = g'(a)(1 + r^2 psi(a)) and int u g''/sqrt = int g''(1 +
    r^2 psi) turn eq. (26) into these; docs/theory/axisymmetric.md (A87)-(A88)).
    H_slip = int_max(r,c)^a g'' psi du.  C_T = 2(1+nu)mu/(3 pi)."""
    sa, sc = sqrt_diff(a, r), sqrt_diff(c, r)
    stick = r <= c
    with _err():
        psi_a = 1.0 / (sa * (a + sa))
        psi_c = 1.0 / (sc * (c + sc))
        # x times the first term, as (x/r)(g'(r)/r) in the slip zone: x g'(r)/r^2 overflows (r^2 -> 0)
        # at r = 1e-300 although the value, ~g'(0)/r, is finite
        first = np.where(stick, -x * profile.dg(c) * np.where(stick, psi_c, 0.0), (x / r) * (profile.dg(r) / r))
        v = -2.0 * (1.0 + nu) * mu / (3.0 * math.pi) * (first + x * (profile.dg(a) * psi_a - H_slip))
    return _zero_where_x0(x, np.where(r <= a, v, 0.0))
