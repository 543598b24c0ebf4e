"""The 1-D integrals of the general (any profile) route, vectorised over field points.

Willert, Forsbach & Popov, eqs. (9), (11), (24)-(26), with the substitutions of formula sheet §0:

* ``u = r cosh t`` for integrals over u in [r, a] with the kernel 1/sqrt(u^2 - r^2): the endpoint
  singularity and the nearby branch point u = -r both disappear (u = -r maps to t = i pi), the
  integrand g'(r cosh t) is smooth; composite Gauss–Legendre on panels of fixed length because the
  interval [0, arccosh(a/r)] grows like ln(2a/r) as r -> 0.
* ``u = r sin t`` for integrals over u in [0, min(r, a)] with the kernel 1/sqrt(r^2 - u^2).
* Tabulated (spline) profiles: the Abel transform of a cubic spline has cusps at the knots (g'' ~
  sqrt(u - k) just right of a knot k, from the jumps of the spline's third derivative).  Their rules
  break at every knot and grade the nodes towards it (``segment_rule``), which restores fast
  convergence.
* Power-law profiles g' = B u^m (m = n - 1 possibly non-integer) behave like t^m at t = 0 after the
  sin substitution; there Gauss–Jacobi rules with that weight make the rest of the integrand smooth,
  and the pressure-gradient integral (11) is taken as the Hadamard finite part (valid for n < 1,
  where g'(0) is infinite and g'' not integrable).

All functions take 1-D arrays of equal length (points with r > 0) and return 1-D arrays.
"""
from __future__ import annotations

import math

import numpy as np

from ..quadrature import Orders, gauss_jacobi, group_by, panel_count, panel_rule, segment_rule
from .common import arccosh_ratio, log_sinc, sqrt_diff

__all__ = ["tau_integrals", "theta_moments", "pressure_gradient_D", "pressure_gradient_far",
           "log_integral"]


def _is_power_law(profile) -> bool:
    return profile.kind == "power_law"


def _knots(profile):
    """Interior spline knots (where g' and g'' have cusps), or None."""
    if profile.kind != "tabulated":
        return None
    kn = profile._knots[1:-1]
    return kn if kn.size else None


def _panel_length(profile, ords: Orders) -> float:
    """Panel length of the u = r cosh t rules.  g' ~ u^m grows like exp(m t); the tabulated
    lengths resolve m <= 4 (growth ``_GROWTH``), steeper power laws get proportionally shorter
    panels so that m * h stays fixed."""
    m = profile.tip_exponent if _is_power_law(profile) else 1.0
    return ords.h_tau * min(1.0, _GROWTH / max(m, 1e-300))


_GROWTH = 4.0


def _seg_order(n: int) -> int:
    """Nodes per knot-to-knot segment: segments are short, so fewer nodes than a full panel."""
    return n


def _with_breaks(lo, hi, breaks, n):
    """Graded segment rule on [lo, hi] split at ``breaks`` (shape (k, m), clipped into [lo, hi])."""
    inner = np.sort(np.clip(breaks, lo[:, None], hi[:, None]), axis=1)
    return segment_rule(np.concatenate([lo[:, None], inner, hi[:, None]], axis=1), n)


def _tau_rule(profile, r, lo, hi, panels, n):
    """Nodes/weights in t (u = r cosh t) on [lo, hi]: equal panels, plus breaks at the knots of a
    tabulated profile."""
    kn = _knots(profile)
    if kn is None:
        return panel_rule(lo, hi, panels, n)
    frac = np.arange(1, panels) / panels
    uniform = lo[:, None] + (hi - lo)[:, None] * frac[None, :]
    kk, rr = kn[None, :], r[:, None]
    tk = np.where(kk > rr, arccosh_ratio(np.maximum(kk, rr), rr), -np.inf)
    return _with_breaks(lo, hi, np.concatenate([uniform, tk], axis=1), _seg_order(n))


def _theta_rule(profile, r, lo, hi, n):
    """Nodes/weights in t (u = r sin t) on [lo, hi] within [0, pi/2]; breaks at the knots of a
    tabulated profile."""
    kn = _knots(profile)
    if kn is None:
        return panel_rule(lo, hi, 1, n)
    kk, rr = kn[None, :], r[:, None]
    tk = np.where(kk < rr, np.arctan2(kk, sqrt_diff(rr, np.minimum(kk, rr))), np.inf)
    return _with_breaks(lo, hi, tk, _seg_order(n))


def tau_integrals(profile, r, lo, hi, ords: Orders, kinds):
    """int_lo^hi F(u) dt with u = r cosh t, s = r sinh t, for F in ``kinds``:
    "G": g'(u)  (so int_u g'(u) du / sqrt(u^2 - r^2), eq. 9 and 24);
    "GE": g'(u) exp(-2t)  (for the load bracket of eq. 9, see ``normal``);
    "H": g''(u) / (u + s)  (so int_u g''(u) du / (sqrt(u^2 - r^2) (u + sqrt(u^2 - r^2))), eq. 26).
    Returns {kind: array}."""
    out = {k: np.zeros(r.size) for k in kinds}
    if r.size == 0:
        return out
    counts = panel_count(lo, hi, _panel_length(profile, ords))
    for panels, idx in group_by(counts):
        t, w = _tau_rule(profile, r[idx], lo[idx], hi[idx], int(panels), ords.n_tau)
        e = np.exp(t)
        ei = 1.0 / e
        rr = r[idx, None]
        u = rr * (0.5 * (e + ei))
        if "G" in kinds or "GE" in kinds:
            wg = w * profile.dg(u)
            if "G" in kinds:
                out["G"][idx] = wg.sum(axis=1)
            if "GE" in kinds:
                out["GE"][idx] = (wg * (ei * ei)).sum(axis=1)
        if "H" in kinds:
            # u + s = r e^t exactly
            out["H"][idx] = (w * profile.d2g(u) * ei).sum(axis=1) / r[idx]
    return out


def _sin_power_moments(p, theta, n):
    """int_0^theta sin^p(t) dt and int_0^theta sin^(p+2)(t) dt (p > -1, 0 <= theta <= pi/2) by one
    Gauss–Jacobi rule with weight t^p: theta^(p+1) int_0^1 w^p (sin(theta w)/(theta w))^p {1,
    sin^2(theta w)} dw.  (The power of sin t / t is formed directly: its relative error is p ulps.)"""
    w_nodes, w_weights = gauss_jacobi(n, p)
    th = theta[:, None] * w_nodes[None, :]
    st = np.sin(th)
    f = w_weights * (st / th) ** p
    scale = theta ** (p + 1.0)
    return scale * f.sum(axis=1), scale * (f * st * st).sum(axis=1)


def theta_moments(profile, r, th_lo, th_hi, ords: Orders):
    """P0 = int sin(t) g'(r sin t) dt and P2 = int sin^3(t) g'(r sin t) dt over [th_lo, th_hi]:
    the operator I of eq. (25) divided by r and r^3 (u = r sin t)."""
    if r.size == 0:
        return np.zeros(0), np.zeros(0)
    if _is_power_law(profile):
        m, B = profile.tip_exponent, profile.tip_coefficient
        scale = B * r ** m
        p0, p2 = _sin_power_moments(m + 1.0, th_hi, ords.n_jacobi)
        low = th_lo > 0.0
        if np.any(low):
            idx = np.flatnonzero(low)
            q0, q2 = _sin_power_moments(m + 1.0, th_lo[idx], ords.n_jacobi)
            p0[idx] -= q0
            p2[idx] -= q2
        return scale * p0, scale * p2
    t, w = _theta_rule(profile, r, th_lo, th_hi, ords.n_theta)
    st = np.sin(t)
    wg = w * st * profile.dg(r[:, None] * st)
    return wg.sum(axis=1), (wg * st * st).sum(axis=1)


def pressure_gradient_D(profile, r, th_h, ords: Orders):
    """D(r) = g'(0)/r + int_0^th_h g''(r sin t) dt, th_h = arcsin(min(r, a)/r): the bracket of
    eq. (11) / (33).  For a power law g' = B u^m: B m r^(m-1) int_0^th_h sin^(m-1) t dt for m > 0
    (Gauss–Jacobi, weight t^(m-1)); B/r for the cone m = 0; for -1 < m < 0 (g'(0) infinite) the
    Hadamard finite part B r^(m-1) [th_h^m + m int_0^th_h t^(m-1) ((sin t / t)^(m-1) - 1) dt].
    (The finite-part form is valid for every m > -1 but cancels badly for large m.)"""
    if r.size == 0:
        return np.zeros(0)
    if _is_power_law(profile):
        m, B = profile.tip_exponent, profile.tip_coefficient
        if m > 0.0:
            return B * m * r ** (m - 1.0) * _sin_power_moments(m - 1.0, th_h, ords.n_jacobi)[0]
        if m == 0.0:
            return B / r
        nodes, weights = gauss_jacobi(ords.n_jacobi, m + 1.0)
        th = th_h[:, None] * nodes[None, :]
        ls, ratio = log_sinc(th)
        z = (m - 1.0) * ls
        phi = (m - 1.0) * ratio * (np.expm1(z) / z)   # ((sin t/t)^(m-1) - 1) / t^2; z < 0 here
        return B * r ** (m - 1.0) * (th_h ** m + m * th_h ** (m + 2.0) * (weights * phi).sum(axis=1))
    t, w = _theta_rule(profile, r, np.zeros_like(th_h), th_h, ords.n_theta)
    integral = (w * profile.d2g(r[:, None] * np.sin(t))).sum(axis=1)
    g0 = float(profile.dg(0.0))
    return integral + (g0 / r if g0 != 0.0 else 0.0)


def pressure_gradient_far(profile, r, th_h, ords: Orders):
    """int_0^th_h sin(t) g'(r sin t) / cos^2(t) dt, th_h = arcsin(a/r): r times the outside
    integral of eq. (11), int_0^a u g'(u) du / (r^2 - u^2)^(3/2).  Used for r > 2a, where the
    by-parts form (11b') would cancel like (r/a)^2."""
    if r.size == 0:
        return np.zeros(0)
    if _is_power_law(profile):
        m, B = profile.tip_exponent, profile.tip_coefficient
        p = m + 1.0
        nodes, weights = gauss_jacobi(ords.n_jacobi, p)
        th = th_h[:, None] * nodes[None, :]
        c = np.cos(th)
        return B * r ** m * th_h ** (p + 1.0) * (weights * (np.sin(th) / th) ** p / (c * c)).sum(axis=1)
    t, w = _theta_rule(profile, r, np.zeros_like(th_h), th_h, ords.n_theta)
    st, ct = np.sin(t), np.cos(t)
    return (w * st * profile.dg(r[:, None] * st) / (ct * ct)).sum(axis=1)


def log_integral(profile, lo, hi, ords: Orders):
    """int_lo^hi g'(u) du / u (the r -> 0 limit of the t-integrals), 0 <= lo <= hi.  Infinite
    (with the sign of g'(0)) when lo = 0 and the tip is conical or sharper (g'(0) != 0)."""
    lo = np.asarray(lo, dtype=float)
    hi = np.asarray(hi, dtype=float)
    out = np.zeros(lo.shape)
    if lo.size == 0:
        return out
    m = profile.tip_exponent
    kn = _knots(profile)
    pos = lo > 0.0
    zero = ~pos
    if np.any(pos):
        # u = e^v: int g'(e^v) dv, panels of fixed length like the cosh rule
        vlo, vhi = np.log(lo[pos]), np.log(hi[pos])
        vals = np.zeros(vlo.size)
        counts = panel_count(vlo, vhi, _panel_length(profile, ords))
        for panels, idx in group_by(counts):
            if kn is None:
                v, w = panel_rule(vlo[idx], vhi[idx], int(panels), ords.n_tau)
            else:
                frac = np.arange(1, panels) / panels
                uniform = vlo[idx, None] + (vhi - vlo)[idx, None] * frac[None, :]
                logk = np.broadcast_to(np.log(kn)[None, :], (idx.size, kn.size))
                v, w = _with_breaks(vlo[idx], vhi[idx], np.concatenate([uniform, logk], axis=1),
                                    _seg_order(ords.n_tau))
            vals[idx] = (w * profile.dg(np.exp(v))).sum(axis=1)
        out[pos] = vals
    if np.any(zero):
        if m <= 0.0:
            out[zero] = math.copysign(math.inf, profile.tip_coefficient)
        elif _is_power_law(profile):
            out[zero] = profile.tip_coefficient * hi[zero] ** m / m
        else:
            # g'(u)/u is bounded at 0 for a smooth tip
            h = hi[zero]
            if kn is None:
                v, w = panel_rule(np.zeros_like(h), h, 4, ords.n_theta)
            else:
                v, w = _with_breaks(np.zeros_like(h), h, np.broadcast_to(kn[None, :], (h.size, kn.size)),
                                    _seg_order(ords.n_theta))
            with np.errstate(invalid="ignore", divide="ignore"):
                vals = np.where(w > 0.0, w * profile.dg(v) / np.where(v > 0.0, v, 1.0), 0.0)
            out[zero] = vals.sum(axis=1)
    return out
