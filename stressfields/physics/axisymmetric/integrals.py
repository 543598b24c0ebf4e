"""The 1-D integrals of the general (any profile) route, vectorised over field points.

Willert, Forsbach & Popov, eqs. (9), (11), (24)-(26) (docs/theory/axisymmetric.md (A14)-(A15),
(A24)-(A26), (A34), (A38), (A53)-(A54)), with the substitutions of docs/theory/axisymmetric.md section 9:

* ``u = r cosh t`` for integrals over u in [r, a] with the kernel 1/sqrt(u^2 - r^2): the endpoint
  singularity and the nearby branch point u = -r both disappear (u = -r maps to t = i pi), the
  integrand g'(r cosh t) is smooth; composite Gauss–Legendre on panels of fixed length because the
  interval [0, arccosh(a/r)] grows like ln(2a/r) as r -> 0.
* ``u = r sin t`` for integrals over u in [0, min(r, a)] with the kernel 1/sqrt(r^2 - u^2).
* Tabulated (spline) profiles: the Abel transform of a cubic spline has cusps at the knots (g'' ~
  sqrt(u - k) just right of a knot k, from the jumps of the spline's third derivative).  Their rules
  break at every knot and grade the nodes towards it (``segment_rule``), and split a segment
  geometrically where a cusp lies just outside it (a knot just below r or c: see ``_knot_groups``),
  which restores fast convergence.  That costs O(knots) per point; with knots, the integrals take
  the block route instead (docs/theory/axisymmetric.md (A104)-(A106), end of this module): moments
  of g', g'' on a dyadic tree precomputed per profile, Chebyshev interpolation of the kernel on
  blocks away from u = r, the graded rules only on two short ends: O(log knots) per point.
* Power-law profiles g' = B u^m (m = n - 1 possibly non-integer) behave like t^m at t = 0 after the
  sin substitution; there Gauss–Jacobi rules with that weight make the rest of the integrand smooth,
  and the pressure-gradient integral (11) is taken as the Hadamard finite part (valid for n < 1,
  where g'(0) is infinite and g'' not integrable).

All functions take 1-D arrays of equal length (points with r > 0) and return 1-D arrays.
"""
from __future__ import annotations

import math

import numpy as np

from ..setup_cache import SETUP
from ..quadrature import Orders, gauss_jacobi, group_by, panel_count, panel_rule, segment_rule, tolerance_of
from .common import arccosh_ratio, log_sinc, sqrt_diff

__all__ = ["tau_integrals", "theta_moments", "pressure_gradient_D", "pressure_gradient_far",
           "log_integral", "normal_force", "blocks_apply"]


def _is_power_law(profile) -> bool:
    return profile.kind == "power_law"


def _knots(profile):
    """All spline knots 0 = k_0 < k_1 < ... of a tabulated profile (g' and g'' have cusps at the
    interior ones), or None."""
    if profile.kind != "tabulated":
        return None
    return profile._knots if profile._knots.size > 2 else None


def _panel_length(profile, ords: Orders) -> float:
    """Panel length of the u = r cosh t rules.  g' ~ u^m grows like exp(m t); the tabulated
    lengths resolve m <= 4 (growth ``_GROWTH``), steeper power laws get proportionally shorter
    panels so that m * h stays fixed."""
    m = profile.tip_exponent if _is_power_law(profile) else 1.0
    return ords.h_tau * min(1.0, _GROWTH / max(m, 1e-300))


_GROWTH = 4.0


# -- rules for tabulated (spline) profiles -------------------------------------------------------
#
# On the spline piece [k_j, k_j+1], g' and g'' are analytic functions with branch points at every
# knot k_i <= k_j (the sqrt(u - k_i) cusps) and nowhere to the right.  A segment rule graded at
# its left end (``segment_rule``) handles the cusp sitting on that end; a branch point a distance d
# *outside* the segment's left end (a knot just below r, c or a panel break; for u = r cosh t also
# the mirror image -t_k of a knot just above r, cosh t being even, and a knot k < r at
# t = +-i arccos(k/r)) is invisible to the rule and costs it its order: the pressure gradient, whose
# g'' has the stronger cusp, lost up to 2e-10 at rtol 1e-12 with a knot 1e-4 below r.  Such a
# segment is split geometrically at start + _RATIO d 2^j, so that no piece is longer than about
# twice its distance to the branch point: log2(length / d) extra pieces, only where a cusp is near.

_OWN = 1e-12        # a cusp nearer than this (relative to the segment) to its start is the start's own
_RATIO = 2.0        # split a segment longer than _RATIO times its distance to a cusp
_MAX_SPLITS = 48    # geometric splits per segment at most


def _u_of(mode, r, s):
    """u at the rule variable s: u = r cosh s, r sin s, e^s or s."""
    if mode == "cosh":
        return r * np.cosh(s)
    if mode == "sin":
        return r * np.sin(s)
    if mode == "exp":
        return np.exp(s)
    return s


def _s_of(mode, r, k):
    """Rule variable of the knots k (inside the range of the rule)."""
    if mode == "cosh":
        return arccosh_ratio(np.maximum(k, r), r)
    if mode == "sin":
        return np.arctan2(k, sqrt_diff(r, np.minimum(k, r)))
    if mode == "exp":
        with np.errstate(divide="ignore"):
            return np.log(k)
    return k


def _cusp_distance(mode, r, s, k):
    """Distance in the rule variable from s to the branch point of the knot k <= u(s).  For
    u = r cosh t a knot k < r lies at t = +-i arccos(k/r)."""
    if mode == "cosh":
        theta = np.arctan2(sqrt_diff(r, np.minimum(k, r)), k)
        return np.where(k < r, np.hypot(s, theta), np.abs(s - _s_of(mode, r, k)))
    return np.abs(s - _s_of(mode, r, k))


def _knot_groups(mode, kn, r, lo, hi, panels, n):
    """Graded composite rules on [lo, hi] (rule variable s, u = u(s)) for a spline with knots
    ``kn``: breaks at the knots inside, at ``panels`` equal panels, and geometric splits towards
    near branch points (see above).  Yields (index array, nodes, weights) per group of points that
    need the same number of segments."""
    P = r.size
    K = kn.size - 1                              # pieces
    rr = r[:, None]
    u_lo, u_hi = _u_of(mode, r, lo), _u_of(mode, r, hi)
    i0 = np.searchsorted(kn, u_lo, side="right")
    i1 = np.searchsorted(kn, u_hi, side="left")
    m = int(np.max(i1 - i0, initial=0))
    parts = [lo[:, None], hi[:, None]]
    if m > 0:
        cols = i0[:, None] + np.arange(m)[None, :]
        kk = kn[np.minimum(cols, K)]
        parts.append(np.where(cols < i1[:, None],
                              np.clip(_s_of(mode, rr, kk), lo[:, None], hi[:, None]), np.inf))
    if panels > 1:
        frac = np.arange(1, panels) / panels
        parts.append(lo[:, None] + (hi - lo)[:, None] * frac[None, :])
    B = _dedup(np.sort(np.concatenate(parts, axis=1), axis=1))
    S, E = B[:, :-1], B[:, 1:]
    seg = np.isfinite(E)
    with np.errstate(invalid="ignore"):
        length = np.where(seg, E - S, 0.0)
        mid = np.where(seg, 0.5 * (S + E), lo[:, None])
    j = np.clip(np.searchsorted(kn, _u_of(mode, rr, mid), side="right") - 1, 0, K - 1)
    d = np.full(S.shape, np.inf)
    own = _OWN * length
    with np.errstate(invalid="ignore", divide="ignore"):
        for c in (j, j - 1):                    # the piece's lower knot and the one before
            dist = _cusp_distance(mode, rr, S, kn[np.maximum(c, 0)])
            d = np.where((c >= 1) & (dist > own), np.minimum(d, dist), d)
        if mode == "cosh":                      # the fold of u = r cosh t at t = 0
            d = np.where((kn[j] >= rr) & (j >= 1) & (S > own), np.minimum(d, S), d)
        elif mode in ("sin", "lin"):            # the 1/u terms of g' beyond the first piece
            d = np.where((j >= 1) & (S > own), np.minimum(d, S), d)
        d = d * _RATIO
        near = seg & (d < length)
        J = np.where(near, np.minimum(np.ceil(np.log2(np.where(near, length / d, 1.0))), _MAX_SPLITS),
                     0).astype(np.int64)
    if np.any(J):
        pi, si = np.nonzero(J)
        Jp = J[pi, si]
        tot = int(Jp.sum())
        rows = np.repeat(pi, Jp)
        jj = np.arange(tot) - np.repeat(np.cumsum(Jp) - Jp, Jp)
        vals = np.repeat(S[pi, si], Jp) + np.repeat(d[pi, si], Jp) * 2.0 ** jj
        col = np.arange(tot) - np.searchsorted(rows, rows, side="left")
        X = np.full((P, int(col.max()) + 1), np.inf)
        X[rows, col] = vals
        B = _dedup(np.sort(np.concatenate([B, X], axis=1), axis=1))
    count = np.isfinite(B).sum(axis=1)
    for cnt, idx in group_by(count):
        t, w = segment_rule(B[idx, :int(cnt)], n)
        yield idx, t, w


def _dedup(B):
    """Sorted break rows with repeated values replaced by +inf and moved to the end."""
    rep = np.zeros(B.shape, dtype=bool)
    rep[:, 1:] = B[:, 1:] == B[:, :-1]
    if not np.any(rep):
        return B
    return np.sort(np.where(rep, np.inf, B), axis=1)


def _tau_groups(profile, r, lo, hi, panels, n):
    """(index, nodes, weights) in t (u = r cosh t) on [lo, hi]: equal panels, plus for a tabulated
    profile breaks at its knots and splits towards near cusps."""
    kn = _knots(profile)
    if kn is None:
        yield (np.arange(r.size),) + panel_rule(lo, hi, panels, n)
    else:
        yield from _knot_groups("cosh", kn, r, lo, hi, panels, n)


def _theta_groups(profile, r, lo, hi, n):
    """(index, nodes, weights) in t (u = r sin t) on [lo, hi] within [0, pi/2]; for a tabulated
    profile breaks at its knots and splits towards near cusps."""
    kn = _knots(profile)
    if kn is None:
        yield (np.arange(r.size),) + panel_rule(lo, hi, 1, n)
    else:
        yield from _knot_groups("sin", kn, r, lo, hi, 1, n)


def tau_integrals(profile, r, lo, hi, ords: Orders, kinds):
    """int_lo^hi F(u) dt with u = r cosh t for F in ``kinds`` (see ``_tau_exact``); a tabulated profile
    with knots takes the block route (``_blocks_tau``), the others the panel rules."""
    if _use_blocks(profile, r):
        return _blocks_tau(profile, r, lo, hi, ords, kinds)
    return _tau_exact(profile, r, lo, hi, ords, kinds)


def _tau_exact(profile, r, lo, hi, ords: Orders, kinds):
    """int_lo^hi F(u) dt with u = r cosh t, s = r sinh t, for F in ``kinds``:
    "G": g'(u)  (so int_u g'(u) du / sqrt(u^2 - r^2), eq. 9 and 24);
    "GE": g'(u) exp(-2t)  (for the load bracket of eq. 9, see ``normal``);
    "H": g''(u) / (u + s)  (so int_u g''(u) du / (sqrt(u^2 - r^2) (u + sqrt(u^2 - r^2))), eq. 26).
    Returns {kind: array}."""
    out = {k: np.zeros(r.size) for k in kinds}
    if r.size == 0:
        return out
    counts = panel_count(lo, hi, _panel_length(profile, ords))
    for panels, group in group_by(counts):
        for sub, t, w in _tau_groups(profile, r[group], lo[group], hi[group], int(panels), ords.n_tau):
            idx = group[sub]
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
    if _use_blocks(profile, r):
        v = _blocks_sin(profile, r, th_lo, th_hi, ords, ("P0", "P2"))
        return v["P0"], v["P2"]
    return _theta_exact(profile, r, th_lo, th_hi, ords)


def _theta_exact(profile, r, th_lo, th_hi, ords: Orders):
    """P0, P2 of ``theta_moments`` by the knot-resolving rules."""
    p0, p2 = np.zeros(r.size), np.zeros(r.size)
    for idx, t, w in _theta_groups(profile, r, th_lo, th_hi, ords.n_theta):
        st = np.sin(t)
        wg = w * st * profile.dg(r[idx, None] * st)
        p0[idx], p2[idx] = wg.sum(axis=1), (wg * st * st).sum(axis=1)
    return p0, p2


def pressure_gradient_D(profile, r, th_h, ords: Orders):
    """D(r) = g'(0)/r + int_0^th_h g''(r sin t) dt, th_h = arcsin(min(r, a)/r): the bracket of
    eq. (11) / (33).  For a power law g' = B u^m: B m r^(m-1) int_0^th_h sin^(m-1) t dt for m > 0
    (Gauss–Jacobi, weight t^(m-1)); B/r for the cone m = 0; for -1 < m < 0 (g'(0) infinite) the
    Hadamard finite part B r^(m-1) [th_h^m + m int_0^th_h t^(m-1) ((sin t / t)^(m-1) - 1) dt]
    (docs/theory/axisymmetric.md (A85)).  (The finite-part form is valid for every m > -1 but cancels
    badly for large m.)"""
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
    if _use_blocks(profile, r):
        integral = _blocks_sin(profile, r, np.zeros_like(th_h), th_h, ords, ("D",))["D"]
    else:
        integral = _D_exact(profile, r, np.zeros_like(th_h), th_h, ords)
    g0 = float(profile.dg(0.0))
    return integral + (g0 / r if g0 != 0.0 else 0.0)


def pressure_gradient_far(profile, r, th_h, ords: Orders):
    """int_0^th_h sin(t) g'(r sin t) / cos^2(t) dt, th_h = arcsin(a/r): r times the outside
    integral of eq. (11), int_0^a u g'(u) du / (r^2 - u^2)^(3/2) (docs/theory/axisymmetric.md (A86)).
    Used for r > 2a, where the by-parts form (A26) would cancel like (r/a)^2."""
    if r.size == 0:
        return np.zeros(0)
    if _is_power_law(profile):
        m, B = profile.tip_exponent, profile.tip_coefficient
        p = m + 1.0
        nodes, weights = gauss_jacobi(ords.n_jacobi, p)
        th = th_h[:, None] * nodes[None, :]
        c = np.cos(th)
        return B * r ** m * th_h ** (p + 1.0) * (weights * (np.sin(th) / th) ** p / (c * c)).sum(axis=1)
    if _use_blocks(profile, r):
        return _blocks_sin(profile, r, np.zeros_like(th_h), th_h, ords, ("F",))["F"]
    return _far_exact(profile, r, np.zeros_like(th_h), th_h, ords)


def _D_exact(profile, r, lo, hi, ords: Orders):
    """int_lo^hi g''(r sin t) dt by the knot-resolving rules."""
    out = np.zeros(r.size)
    for idx, t, w in _theta_groups(profile, r, lo, hi, ords.n_theta):
        out[idx] = (w * profile.d2g(r[idx, None] * np.sin(t))).sum(axis=1)
    return out


def _far_exact(profile, r, lo, hi, ords: Orders):
    """int_lo^hi sin(t) g'(r sin t) / cos^2(t) dt by the knot-resolving rules."""
    out = np.zeros(r.size)
    for idx, t, w in _theta_groups(profile, r, lo, hi, ords.n_theta):
        st, ct = np.sin(t), np.cos(t)
        out[idx] = (w * st * profile.dg(r[idx, None] * st) / (ct * ct)).sum(axis=1)
    return out


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
        for panels, group in group_by(counts):
            if kn is None:
                v, w = panel_rule(vlo[group], vhi[group], int(panels), ords.n_tau)
                vals[group] = (w * profile.dg(np.exp(v))).sum(axis=1)
                continue
            ones = np.ones(group.size)
            for sub, v, w in _knot_groups("exp", kn, ones, vlo[group], vhi[group], int(panels), ords.n_tau):
                vals[group[sub]] = (w * profile.dg(np.exp(v))).sum(axis=1)
        out[pos] = vals
    if np.any(zero):
        if m <= 0.0:
            out[zero] = math.copysign(math.inf, profile.tip_coefficient)
        elif _is_power_law(profile):
            out[zero] = profile.tip_coefficient * hi[zero] ** m / m
        else:
            # g'(u)/u is bounded at 0 for a smooth tip
            h = hi[zero]
            z = np.zeros_like(h)
            groups = ([(np.arange(h.size),) + panel_rule(z, h, 4, ords.n_theta)] if kn is None else
                      _knot_groups("lin", kn, np.ones(h.size), z, h, 1, ords.n_theta))
            vals = np.zeros(h.size)
            for idx, v, w in groups:
                with np.errstate(invalid="ignore", divide="ignore"):
                    vals[idx] = np.where(w > 0.0, w * profile.dg(v) / np.where(v > 0.0, v, 1.0), 0.0).sum(axis=1)
            out[zero] = vals
    return out


# -- the block route of tabulated profiles -----------------------------------------------------
#
# The knot-resolving rules cost O(knots) per point: g' and g'' have a sqrt cusp at every knot whose
# size does not shrink with the spacing fast enough to be merged into longer panels (ignoring the
# knots of a 1000-sample hyperboloid costs 1e-8 p_m in the stresses and 1e-4 p_m/a in dp/dz at any
# rtol).  Every integral here is int phi(u) k(u, r) du with phi = g' or g'' and a kernel k that is
# analytic except at u = +-r (docs/theory/axisymmetric.md (A104)).  On a dyadic tree of blocks over
# [0, r_max] the moments of phi against the Lagrange polynomials of p Chebyshev points are computed
# once per profile (knots resolved there, once); a block at least _SEP block widths away from
# u = r then contributes sum_i W_i k(u_i, r), with the kernel's interpolation error as its only
# error (A105).  Per point the range splits into such blocks (about two per tree level) and two
# short ends next to r and to the range's other limit, which the knot-resolving rules take as
# before: the cost per point is O(log knots) (1000 samples, rtol 1e-10, stresses and dp/dz: 139
# lookups and 632 block nodes per point against 18516 lookups of the knot-resolving rules).

_BLOCKS = True          # False: the knot-resolving rules alone (the reference of the tests)
# _SEP and _LEAF_FRACTION: of (1, 1.5, 2) x (0.25, 0.5), timed with the sums in cache-sized passes
# (surface stresses and dp/dz at rtol 1e-10, 2000 points, 25/200/1000 samples), (1, 0.5) was the
# fastest or within 4 % of it on every table (1.37e5/1.38e5/1.10e5 stress points per CPU second;
# (1.5, 0.5): 0.98e5/1.38e5/1.07e5): a smaller _SEP means more blocks of fewer nodes, a larger
# leaf fewer levels but more knots in the ends
_SEP = 1.0              # distance of a block from the singular point u = r, in block widths
_LEAF_FRACTION = 0.5    # leaf width / median knot spacing: the ends then hold one knot or none
_MAX_LEVEL = 15         # at most 2^15 leaves (r_max / 2^15 on tables with uneven spacing)
_LEAF_ORDER = 24        # graded Gauss nodes per knot segment of a leaf moment (exact to rounding)
# leaves per pass of the leaf moments: their (leaf, node, p) arrays stay below ~30 MB (1e4 samples,
# rtol 1e-10, the tree's CPU time: 0.40, 0.35, 0.26, 0.25 s for 256, 1024, 4096, all 32768 leaves)
_LEAVES = 4096


def _use_blocks(profile, r) -> bool:
    return _BLOCKS and r.size > 0 and _knots(profile) is not None


def blocks_apply(profile) -> bool:
    """True when the integrals of ``profile`` take the block route (then ``normal_force`` is the
    O(log knots) load of the same route)."""
    return _BLOCKS and _knots(profile) is not None


def _block_order(ords: Orders) -> int:
    """Chebyshev points per block for the tolerance row of ``ords``: the kernel interpolation
    error on a block _SEP widths from u = r is at most K rho^-p of the kernel's largest value on
    the block (A105); p makes it rtol/20."""
    rtol = tolerance_of(ords)
    delta = 1.0 + 2.0 * _SEP                         # singular point / half width, from the centre
    rho = _ELLIPSE * (delta + math.sqrt(delta * delta - 1.0))
    # the ellipse's nearest point to the singularity, in half widths; the strongest kernel of (A104)
    # is d^(-3/2) ("F"), and the bound of (A105) is 4 M rho^-p / (rho - 1)
    gap = delta - 0.5 * (rho + 1.0 / rho)
    K = 4.0 * ((delta - 1.0) / gap) ** 1.5 / (rho - 1.0)
    return int(math.ceil(math.log(20.0 * K / rtol) / math.log(rho)))


_ELLIPSE = 0.8      # the Bernstein ellipse used in the bound: 0.8 of the largest one that fits


class _Tree:
    """Moments W[phi][flat block, i] = int_block phi(u) l_i(u) du of phi = g' (1) and g'' (2),
    l_i the Lagrange polynomials of the block's p Chebyshev points; block b of level l (width
    r_max 2^-l) has flat index 2^l - 1 + b."""

    def __init__(self, profile, p: int):
        kn = profile._knots
        R = float(kn[-1])
        spacing = float(np.median(np.diff(kn)))
        self.L = int(np.clip(math.ceil(math.log2(R / (_LEAF_FRACTION * spacing))), 1, _MAX_LEVEL))
        self.w = R / 2.0 ** self.L
        from ..graded.fastsum import chebyshev_rule

        self.xi, self.lam = chebyshev_rule(p)                      # Chebyshev points, first kind
        leaves = self._leaf_moments(profile, kn, R, p)
        self.W = {q: self._upward(leaves[q]) for q in (1, 2)}
        # int_0^(j w) u g'(u) du at the leaf edges: u is a polynomial, so the leaf sums are exact
        centres = (np.arange(2 ** self.L) + 0.5) * self.w
        nodes = centres[:, None] + 0.5 * self.w * self.xi[None, :]
        self.cum_ug = np.concatenate([[0.0], np.cumsum((leaves[1] * nodes).sum(axis=1))])

    def _basis(self, x):
        """l_i(x) for x in [-1, 1], shape x.shape + (p,), by the barycentric formula (O(p) per point:
        the Chebyshev sum it replaced cost O(p^2), 5 s of the set-up of a 1e4-sample table)."""
        from ..graded.fastsum import lagrange

        return lagrange(x, self.xi, self.lam)

    def _leaf_moments(self, profile, kn, R, p):
        n = 2 ** self.L
        lo = np.arange(n) * self.w
        hi = np.minimum(lo + self.w, R)
        out = {1: np.zeros((n, p)), 2: np.zeros((n, p))}
        for start in range(0, n, _LEAVES):          # cache-sized (leaf, node, p) work arrays
            part = slice(start, start + _LEAVES)
            for idx, s, w in _knot_groups("lin", kn, np.ones(lo[part].size), lo[part], hi[part], 1, _LEAF_ORDER):
                x = (s - lo[part][idx, None]) * (2.0 / self.w) - 1.0
                ell = self._basis(x)
                for q, phi in ((1, profile.dg), (2, profile.d2g)):
                    out[q][start + idx] = np.einsum("mn,mnp->mp", w * phi(s), ell)
        return out

    def _upward(self, leaf):
        """All levels from the leaves: a parent's Lagrange polynomial is a polynomial of degree
        p - 1 on each child, so its moment is the child's moments at its values there (exact)."""
        left = self._basis(0.5 * (self.xi - 1.0))      # [j, i] = l_i(child node j), parent coordinate
        right = self._basis(0.5 * (self.xi + 1.0))
        levels = [leaf]
        for _ in range(self.L):
            W = levels[-1]
            levels.append(W[0::2] @ left + W[1::2] @ right)
        return np.concatenate(levels[::-1], axis=0)

    def decompose(self, r, lo, hi, side):
        """Blocks covering [ua, ub] within [lo, hi] (u units) that keep _SEP widths from r, the
        singular point below lo (side +1, u = r cosh t) or above hi (side -1, u = r sin t).
        Returns (point, flat index, level) per block and ua, ub, has (points with blocks); the
        ends [lo, ua] and [ub, hi] are left to the knot-resolving rules."""
        w, n = self.w, 2 ** self.L
        rho = r / w
        with np.errstate(invalid="ignore"):
            if side > 0:
                j0 = np.ceil(np.maximum(lo / w, rho + _SEP))
                j1 = np.floor(np.minimum(hi / w, n))
            else:
                j0 = np.ceil(lo / w)
                j1 = np.floor(np.minimum(np.minimum(hi / w, rho - _SEP), n))
        has = j1 > j0
        pts = np.flatnonzero(has)
        pos, end, rr = j0[pts].astype(np.int64), j1[pts].astype(np.int64), rho[pts]
        ua, ub = np.where(has, j0 * w, hi), np.where(has, j1 * w, hi)
        found = []
        while pts.size:
            low = pos & -pos
            m = np.where(pos == 0, self.L, np.log2(np.maximum(low, 1))).astype(np.int64)
            m = np.minimum(m, np.floor(np.log2(end - pos)).astype(np.int64))
            room = (pos - rr) / _SEP if side > 0 else (rr - pos) / (_SEP + 1.0)
            m = np.maximum(np.minimum(m, np.floor(np.log2(room)).astype(np.int64)), 0)
            level = self.L - m
            found.append((pts, (np.int64(1) << level) - 1 + (pos >> m), level))
            pos = pos + (np.int64(1) << m)
            keep = pos < end
            pts, pos, end, rr = pts[keep], pos[keep], end[keep], rr[keep]
        if found:
            pt, flat, level = (np.concatenate(v) for v in zip(*found))
        else:
            pt = flat = level = np.zeros(0, dtype=np.int64)
        return pt, flat, level, ua, ub, has

    def sums(self, pt, flat, level, r, P, terms):
        """{kind: sum over a point's blocks of sum_i W[phi][block, i] k(u_i, r)} for the
        (kind, phi, kernel) ``terms``, _PAIRS (point, block) pairs at a time."""
        vals = {kind: np.empty(pt.size) for kind, _, _ in terms}
        width = self.w * np.exp2(self.L - level)
        centre = (flat - ((np.int64(1) << level) - 1) + 0.5) * width
        for s in range(0, pt.size, _PAIRS):
            sl = slice(s, s + _PAIRS)
            u = centre[sl, None] + (0.5 * width[sl])[:, None] * self.xi[None, :]
            rr = r[pt[sl]][:, None]
            cache, moments = {}, {}
            for kind, q, kernel in terms:
                if q not in moments:
                    moments[q] = self.W[q][flat[sl]]
                vals[kind][sl] = np.einsum("ij,ij->i", moments[q], kernel(u, rr, cache))
        return {kind: np.bincount(pt, weights=v, minlength=P) for kind, v in vals.items()}


# (point, block) pairs per pass of ``_Tree.sums``: with p = 10-25 nodes (rtol 1e-4 to 1e-14) its work
# arrays are 0.3-0.8 MB and stay in cache; all pairs of 2000 points at once (1.3e6 nodes, 10 MB arrays) made the sums
# twice as slow (1000 samples, rtol 1e-10, surface stresses: 11 ms against 5 ms a call; 1024 to
# 16384 pairs per pass alike)
_PAIRS = 4096


def normal_force(profile, h, ords: Orders):
    """F_N/E* = 2 int_0^h u g'(u) du (A4), (A106) of a tabulated profile at contact radii h (1-D array) in
    O(log knots) per value: the exact leaf sums of the block tree up to the last leaf edge below h
    and the knot-resolving rule on the rest (shorter than a leaf).  (``Tabulated.normal_force`` sums
    all pieces below h: O(knots).)"""
    tree = _tree(profile, _block_order(ords))
    j = np.clip(np.floor(h / tree.w), 0, 2 ** tree.L).astype(np.int64)
    lo = np.minimum(j * tree.w, h)
    out = tree.cum_ug[j].copy()
    for idx, u, w in _knot_groups("lin", profile._knots, np.ones(h.size), lo, h, 1, ords.n_theta):
        out[idx] += (w * u * profile.dg(u)).sum(axis=1)
    return 2.0 * out


def _tree(profile, p: int) -> _Tree:
    """The block tree of ``profile`` with p points per block, built once per content (the shared
    set-up cache: every profile object with the same samples, every call and dask chunk)."""
    key = ("block tree", p, _SEP, _LEAF_FRACTION, _MAX_LEVEL, _LEAF_ORDER) + profile._key
    return SETUP.get(key, lambda: _Tree(profile, p))


def _cached(cache, key, make):
    if key not in cache:
        cache[key] = make()
    return cache[key]


def _root_inverse(p, q):
    """1/sqrt((p - q)(p + q)) (A78), in place: these arrays are the largest of the block route."""
    d = p - q
    d *= p + q
    np.sqrt(d, out=d)
    return np.reciprocal(d, out=d)


def _inv_s(u, r, cache):
    """1/s, s = sqrt(u^2 - r^2)."""
    return _cached(cache, "1/s", lambda: _root_inverse(u, r))


def _r_ups(u, r, cache):
    """r/(u + s) = e^-t."""
    def make():
        d = np.reciprocal(_inv_s(u, r, cache))
        d += u
        return np.divide(r, d, out=d)
    return _cached(cache, "r/(u+s)", make)


def _inv_c(u, r, cache):
    """1/c, c = sqrt(r^2 - u^2)."""
    return _cached(cache, "1/c", lambda: _root_inverse(r, u))


def _sin_t(u, r, cache):
    """u/r = sin t."""
    return _cached(cache, "u/r", lambda: u / r)


# kernels k(u, r) of (A104): the integrand of each kind per du, with the function it multiplies
# (1: g', 2: g'')
_KERNELS = {
    "G": (1, lambda u, r, c: _inv_s(u, r, c)),
    "GE": (1, lambda u, r, c: _inv_s(u, r, c) * _r_ups(u, r, c) ** 2),
    "H": (2, lambda u, r, c: _inv_s(u, r, c) * _r_ups(u, r, c) / r),
    "P0": (1, lambda u, r, c: _sin_t(u, r, c) * _inv_c(u, r, c)),
    "P2": (1, lambda u, r, c: _sin_t(u, r, c) ** 3 * _inv_c(u, r, c)),
    "D": (2, lambda u, r, c: _inv_c(u, r, c)),
    "F": (1, lambda u, r, c: u * r * _inv_c(u, r, c) ** 3),
}


def _blocks_tau(profile, r, lo, hi, ords: Orders, kinds):
    """``tau_integrals`` by the block route: blocks of [r cosh lo, r cosh hi] away from u = r, the
    two ends by ``_tau_exact``."""
    return _by_blocks(profile, r, lo, hi, ords, kinds, +1, lambda t: r * np.cosh(t),
                      lambda u: arccosh_ratio(np.maximum(u, r), r), _tau_exact)


def _by_blocks(profile, r, lo, hi, ords: Orders, kinds, side, radius, parameter, exact):
    """An integral over the parameter t in [lo, hi] whose radius u = ``radius(t)`` lies on one
    ``side`` of r: the tree's blocks away from u = r by their moments, the parameter ranges before
    the first and after the last block (``parameter`` maps a radius back) by the knot-resolving
    rule ``exact``."""
    tree = _tree(profile, _block_order(ords))
    pt, flat, level, ua, ub, has = tree.decompose(r, radius(lo), radius(hi), side)
    ta = np.where(has, np.clip(parameter(ua), lo, hi), hi)
    tb = np.where(has, np.clip(parameter(ub), ta, hi), hi)
    out = exact(profile, r, lo, ta, ords, kinds)
    ih = np.flatnonzero(has & (tb < hi))
    if ih.size:
        end = exact(profile, r[ih], tb[ih], hi[ih], ords, kinds)
        for k in out:
            out[k][ih] += end[k]
    blocks = tree.sums(pt, flat, level, r, r.size, [(k,) + _KERNELS[k] for k in kinds])
    for k in kinds:
        out[k] += blocks[k]
    return out


def _sin_exact(profile, r, lo, hi, ords: Orders, kinds):
    out = {}
    if "P0" in kinds or "P2" in kinds:
        out["P0"], out["P2"] = _theta_exact(profile, r, lo, hi, ords)
    if "D" in kinds:
        out["D"] = _D_exact(profile, r, lo, hi, ords)
    if "F" in kinds:
        out["F"] = _far_exact(profile, r, lo, hi, ords)
    return out


def _blocks_sin(profile, r, th_lo, th_hi, ords: Orders, kinds):
    """The u = r sin t integrals (P0, P2 of ``theta_moments``, D of ``pressure_gradient_D``, F of
    ``pressure_gradient_far``) by the block route: blocks of [r sin th_lo, r sin th_hi] away from
    u = r, the two ends by the knot-resolving rules."""
    def angle(u):
        return np.arctan2(u, sqrt_diff(r, np.minimum(u, r)))

    return _by_blocks(profile, r, th_lo, th_hi, ords, kinds, -1, lambda t: r * np.sin(t), angle, _sin_exact)
