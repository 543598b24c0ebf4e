"""Private quadrature forms of the MDR rules (10)-(15) of Hess & Popov 2016 for any 1D profile
(docs/theory/graded.md (G15)-(G20)).

These are the general route (tabulated profiles) and the independent check of the closed forms.
The 1D profile enters through a callable ``fn(x, **P)``: ``x`` carries one more trailing axis
than the evaluation points and every entry of ``P`` (always including ``k``) is the matching
per-point parameter with a trailing axis of length 1.

Each integral is split at the profile's break points (spline knots of a tabulated profile, where
the integrand is not smooth) and every piece is done by tanh-sinh.  On the piece that touches a
singular end point the kernel (distance)^alpha is removed by the power substitution
distance = L v^p, p = 1/(1+alpha) (docs/theory/graded.md (G42)); elsewhere p = 1 (plain mapping).  Distances to
the end points are formed without rounding (a - r is exact for r close to a; 1 - t comes from
the rule).
"""
from __future__ import annotations

import numpy as np

from .. import quadrature
from .material import cos_half_pi_k


def _prepare(arrays: dict, mask=None):
    """Broadcast, optionally select ``mask``, and add the trailing quadrature axis."""
    b = dict(zip(arrays, np.broadcast_arrays(*[np.asarray(v, float) for v in arrays.values()])))
    if mask is not None:
        b = {key: v[mask] for key, v in b.items()}
    return {key: v[..., None] for key, v in b.items()}


def _pieces(lo, hi, breaks):
    """Yield (x0, x1) per piece of [lo, hi] cut at ``breaks`` (empty pieces have x0 == x1)."""
    edges = [lo] + [np.clip(b, lo, hi) for b in np.asarray(breaks, float)] + [hi]
    for x0, x1 in zip(edges[:-1], edges[1:]):
        yield x0, x1


def _singular_piece(x0, x1, delta, alpha, p_sing, integrand_x, rtol, toward_left, level=3):
    """int over [x0, x1] of integrand_x(x) * dist(x)^alpha, where dist = delta + (x - x0)
    (toward_left) or delta + (x1 - x) (otherwise), delta >= 0 the distance of the piece to the
    singular point.  The substitution (x - x0) = L v^p uses p = p_sing where delta == 0."""
    L = x1 - x0
    live = L > 0
    # empty pieces: zero length, a harmless distance, nodes pinned inside the interval
    Ls = np.where(live, L, 0.0)
    delta = np.where(live, delta, 1.0)
    p = np.where(delta == 0.0, p_sing, 1.0)

    sing = delta == 0.0

    def integrand(v, vc):
        s = v ** p                                   # distance from the singular-side end / L
        s = np.where(s < 1e-250, 0.0, s)             # denormal positions carry no precision
        x = x0 + Ls * s if toward_left else x1 - Ls * s
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            # on the singular piece v^(p-1) (L v^p)^alpha = L^alpha exactly (p (1 + alpha) = 1);
            # forming it from the factors would give 0 * inf once v^p underflows (k -> 1)
            jac = np.where(sing, Ls ** alpha, v ** (p - 1.0) * (delta + Ls * s) ** alpha)
            fx = integrand_x(x)          # (np.where branches not taken may overflow harmlessly)
        return Ls * p * jac * fx

    return quadrature.integrate(integrand, rtol=rtol, level=level)


def foundation_integral(a, fn, params, rtol, breaks=()):
    """int_0^a x^k fn(x) dx (eq. 12 without the factor 2 c_N_star)."""
    P = _prepare({"a": a, **params})
    ae = P.pop("a")
    k = P["k"]
    total = 0.0
    for x0, x1 in _pieces(np.zeros_like(ae), ae, breaks):
        L = x1 - x0

        def integrand(t, tc, x0=x0, L=L):
            x = x0 + L * t
            return L * x ** k * fn(x, **P)

        total = total + quadrature.integrate(integrand, rtol=rtol)
    return total


def _scaled_breaks(breaks, lam):
    """Break points in the integration variable x = X/lam (X the physical radius)."""
    return [b / lam for b in np.asarray(breaks, float)]


def pressure_integral(r, a, dg, params, rtol, breaks=(), lam=1.0, level=3):
    """(1/pi) int_r^a dg(x) (x^2 - r^2)^(-(1-k)/2) dx: eq. (13) with u'_1D = -g' on (0, a).

    Zero for r >= a.  The singular factor (x - r)^(-(1-k)/2) is removed with p = 2/(1+k).
    ``r``, ``a`` may be given in units of ``lam`` (physical radii lam r, lam a; e.g. r/a and 1
    with lam = a, so that the edge distance 1 - r/a is exact): the integral is then
    lam^k (1/pi) int dg(lam x) (x^2 - r^2)^(-(1-k)/2) dx.  ``level``: the first tanh-sinh level
    away from the centre (the step then halves until two levels agree to rtol).
    """
    r, a = np.broadcast_arrays(np.asarray(r, float), np.asarray(a, float))
    shape = np.broadcast(r, lam, *params.values()).shape
    m = np.broadcast_to(r < a, shape)
    out = np.zeros(shape)
    if not m.any():
        return out
    P = _prepare({"r": r, "a": a, "lam": lam, **params}, m)
    breaks = _select(breaks, m)
    total = np.zeros(P["k"].shape[0])
    split = np.zeros(total.shape, bool)
    centre = (P["r"][:, 0] == 0.0) & (P["k"][:, 0] > 0.0)
    if centre.any():
        try:                    # g'(0): finite unless f'(r) -> inf at r = 0 (then no convergence)
            with np.errstate(all="ignore"):
                g0 = dg(np.zeros_like(P["r"]), **{key: v for key, v in P.items() if key not in ("r", "a", "lam")})
        except quadrature.QuadratureError:
            g0 = np.full(P["r"].shape, np.inf)
        split = centre & np.isfinite(g0[:, 0])
    for sel, fn in ((split, _centre_part), (~split, _general_part)):
        if sel.any():
            sub = {key: v[sel] for key, v in P.items()}
            total[sel] = fn(sub, dg, g0[sel] if fn is _centre_part else None, _select(breaks, sel), rtol, level)
    lam_k = np.broadcast_to(np.asarray(lam, float), shape)[m] ** np.broadcast_to(params["k"], shape)[m]
    out[m] = lam_k * total / np.pi
    return out


def _select(breaks, mask):
    """Breaks for the points of ``mask``: per-point breaks (shape (rows, points, 1), one row per
    rank) are selected along their point axis; a common list of breaks is kept as it is."""
    if np.ndim(breaks) != 3:
        return breaks
    return np.asarray(breaks)[:, np.ravel(mask)]


def _general_part(P, dg, _, breaks, rtol, level=3):
    """(x^2 - r^2)^(-(1-k)/2) removed at x = r by p = 2/(1+k); at the centre (only where g'(0) is
    unbounded) both kernel factors are singular at x = 0 and x^(-(1-k)) is removed by p = 1/k."""
    P = dict(P)
    ri, ai, lam, k = P.pop("r"), P.pop("a"), P.pop("lam"), P["k"]
    alpha = -0.5 * (1.0 - k)
    centre = (ri == 0.0) & (k > 0.0)
    alpha_s = np.where(centre, 2.0 * alpha, alpha)
    p_s = np.where(centre, 1.0 / np.where(centre, k, 1.0), 2.0 / (1.0 + k))
    total = 0.0
    for x0, x1 in _pieces(ri, ai, _scaled_breaks(breaks, lam)):
        total = total + _singular_piece(
            x0, x1, x0 - ri, alpha_s, p_s,
            lambda x: dg(lam * x, **P) * np.where(centre, 1.0, (x + ri) ** alpha), rtol, toward_left=True,
            level=level)
    return total


def _centre_part(P, dg, g0, breaks, rtol, _level=None):
    P = dict(P)
    P.pop("r")
    a, lam = P.pop("a"), P.pop("lam")
    return _centre_split(a, P["k"], lam, P, dg, g0, breaks, rtol)


def _centre_split(a, k, lam, P, dg, g0, breaks, rtol):
    """int_0^a dg(lam x) x^(k-1) dx (the centre r = 0) as g'(0) x1^k/k + int (g' - g'(0)) x^(k-1) dx
    on the first piece [0, x1] and plain tanh-sinh elsewhere, docs/theory/graded.md (G50).

    The remainder behaves like x^k (or x^(n+k-2), n > 1) at 0, which tanh-sinh takes as it is;
    removing x^(k-1) by x = L v^(1/k) instead crowds the nodes into v > 1 - 1e-6 at k = 1e-6
    (no convergence at rtol 1e-12, measured).  x1^k/k = exp(k ln x1)/k is exact for small k.
    """
    total = 0.0
    for i, (x0, x1) in enumerate(_pieces(np.zeros_like(a), a, _scaled_breaks(breaks, lam))):
        L = x1 - x0
        c = g0 if i == 0 else 0.0

        def integrand(t, tc, x0=x0, x1=x1, L=L, c=c):
            x = x0 + L * t
            live = x > 0.0
            xs = np.where(live, x, x1)            # a point inside the table (x = 0 adds nothing)
            with np.errstate(divide="ignore", invalid="ignore"):
                return np.where(live, L * (dg(lam * xs, **P) - c) * xs ** (k - 1.0), 0.0)

        if i == 0:
            head = (g0 * np.exp(k * np.log(np.where(x1 > 0.0, x1, 1.0))) / k)[:, 0]
            total = total + head + quadrature.integrate(integrand, rtol=rtol, atol=1e-3 * rtol * float(np.min(
                np.abs(head)) if np.any(head != 0) else 0.0))
        else:
            total = total + quadrature.integrate(integrand, rtol=rtol)
    return total


def displacement_integral(r, a, u1d, params, rtol, breaks=(), lam=1.0):
    """u_z(r) = (2/pi) cos(k pi/2) int_0^min(r,a) x^k u1d(x) (r^2 - x^2)^(-(1+k)/2) dx, eq. (15).

    Outside (r > a) the kernel is regular but nearly singular as r -> a+ (distance r - x formed
    from the exact r - a).  Inside (r <= a) this is the inverse transform (6) of u_1D, i.e.
    d - f(r); the kernel (r - x)^(-(1+k)/2) is removed with p = 2/(1-k), and the vanishing
    cos(k pi/2) times the growing p stays finite as k -> 1.  ``r``, ``a`` may be given in units of
    ``lam`` as in :func:`pressure_integral` (the kernel is homogeneous of degree 0: no factor).
    """
    r, a = np.broadcast_arrays(np.asarray(r, float), np.asarray(a, float))
    shape = np.broadcast(r, lam, *params.values()).shape
    out = np.empty(shape)
    outside = np.broadcast_to(r > a, shape)
    centre = np.broadcast_to(r == 0.0, shape)
    if centre.any():         # the kernel tends to a delta at x = 0: u_z(0) = u_1D(0) = d
        P = _prepare({"r": r, **params}, centre)
        P.pop("r")
        out[centre] = u1d(np.zeros_like(P["k"]), **P)[:, 0]
    for mask, upper in ((outside, "a"), (~outside & ~centre, "r")):
        if not mask.any():
            continue
        P = _prepare({"r": r, "a": a, "lam": lam, **params}, mask)
        ri, ai, lam_m, k = P.pop("r"), P.pop("a"), P.pop("lam"), P["k"]
        top = ai if upper == "a" else ri
        alpha = -0.5 * (1.0 + k)
        total = 0.0
        for x0, x1 in _pieces(np.zeros_like(top), top, _scaled_breaks(breaks, lam_m)):
            total = total + _singular_piece(
                x0, x1, ri - x1, alpha, 2.0 / (1.0 - k),
                lambda x, lam_m=lam_m: x ** k * u1d(lam_m * x, **P) * (ri + x) ** alpha, rtol, toward_left=False)
        out[mask] = (2.0 / np.pi) * cos_half_pi_k(k[:, 0]) * total
    return out
