"""Extrema over the contact and over the gap outside it: global p_max, the exact
continuous-contact test, and the Johnson parameter.

docs/theory/wavy.md (W20), (W21) (Tsukanov 2018 uses chi < 1, which is neither necessary nor
sufficient: see the errata there).  The continuous-contact (bounded, fixed-a) solution is the
physical one iff
  (P) phi(t) = p(a t)/sqrt(1 - t^2) >= 0 on [-1, 1] (edge coefficient included), and
  (G) gap(x) = g(x) + u_z(x) - u_z(0) >= 0 for a < |x| <= lambda_1/2 (for the non-periodic
      indenter: the single bump |x| <= pi).
Both are found by a dense grid fitted to the series length and the shortest wave, followed by a
vectorised golden-section refinement of the best few local minima of every row.
"""

from __future__ import annotations

import numpy as np

from . import series
from .profile import gap as initial_gap

_GOLD = 0.5 * (np.sqrt(5.0) - 1.0)


def minimize_rows(f, lo, hi, G, *, V=None, n_iter=48, n_cand=3):
    """Global minimum of f(k, s) over s in [lo[k], hi[k]] for every row k at once.

    f takes arrays (row index, s) of one shape.  The grid is G equispaced points per row
    (values V may be given precomputed).  Returns (s_min, f_min) per row; never worse
    than the best grid point.
    """
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    R = lo.size
    s = lo[:, None] + (hi - lo)[:, None] * np.linspace(0.0, 1.0, G)[None, :]
    if V is None:
        V = f(np.broadcast_to(np.arange(R)[:, None], s.shape), s)
    pad = np.full((R, 1), np.inf)
    Vl, Vr = np.concatenate([pad, V[:, :-1]], 1), np.concatenate([V[:, 1:], pad], 1)
    cand = np.argsort(np.where((V <= Vl) & (V <= Vr), V, np.inf), axis=1)[:, : min(n_cand, G)]
    rr = np.arange(R)[:, None]
    a, b = s[rr, np.maximum(cand - 1, 0)], s[rr, np.minimum(cand + 1, G - 1)]
    kc = np.broadcast_to(rr, a.shape)
    c, d = b - _GOLD * (b - a), a + _GOLD * (b - a)
    fc, fd = f(kc, c), f(kc, d)
    for _ in range(n_iter):
        left = fc < fd                     # minimum in [a, d]
        a, b = np.where(left, a, c), np.where(left, d, b)
        new = np.where(left, b - _GOLD * (b - a), a + _GOLD * (b - a))
        fn = f(kc, new)
        c, d, fc, fd = (np.where(left, new, d), np.where(left, c, new),
                        np.where(left, fn, fd), np.where(left, fc, fn))
    s_ref = np.where(fc < fd, c, d)
    f_ref = np.minimum(fc, fd)
    s_all = np.concatenate([s_ref, s[rr, cand]], 1)
    f_all = np.concatenate([f_ref, V[rr, cand]], 1)
    j = np.argmin(f_all, axis=1)
    return s_all[np.arange(R), j], f_all[np.arange(R), j]


def _by_K(table, rows):
    """Rows grouped by series length (powers of two), so each group gets a grid of its own."""
    K = table.K[rows]
    key = np.ceil(np.log2(np.maximum(K, 1))).astype(int)
    for b in np.unique(key):
        sel = np.nonzero(key == b)[0]
        yield sel, int(2 ** b)


def _grid_values(table, rows, M, Kb, *, shape):
    """Series on theta_k = pi k/M, k = 0..M/2, by FFT (O(M log M) per row instead of O(M K)).

    Only used to pick candidate extrema; the refinement sums the series directly.
    """
    K = min(Kb, table.D.shape[1])  # rows here keep at most Kb terms
    G = M // 2 + 1
    out = np.empty((rows.size, G))
    theta = np.linspace(0.0, 0.5 * np.pi, G)
    # one row at a time: a batched FFT (and a matrix product) may round a row differently with the
    # number of rows, and the grid values are candidates of the result
    for i, r in enumerate(rows):
        c = np.zeros(2 * M, dtype=complex)
        c[1:2 * K:2] = table.D[r, :K]
        S = np.fft.ifft(c)[:G].imag * (2 * M)
        if shape:
            S[1:] /= np.sin(theta[1:])
            S[0] = series.row_dot(table.D[r, :K], 2.0 * np.arange(K) + 1.0)
        out[i] = S
    return theta, out


def _extreme_closed(table, rows, shape):
    """extreme_over_contact for the periodic closed form (W30), in theta with t = cos(theta) (which
    resolves the square-root edge): >= 16 grid points per harmonic of Q, then golden section."""
    from . import periodic

    def f(k, theta):
        t = np.cos(theta)
        return (periodic.closed_shape(table, rows[k], t) if shape
                else -periodic.closed_pressure(table, rows[k], t))

    th, v = np.empty(rows.size), np.empty(rows.size)
    for K in np.unique(table.K[rows]):     # the grid of a row follows its own K, not its neighbours'
        sel = np.flatnonzero(table.K[rows] == K)
        g = lambda k, theta, sel=sel: f(sel[k], theta)
        th[sel], v[sel] = minimize_rows(g, np.zeros(sel.size), np.full(sel.size, 0.5 * np.pi), 16 * int(K) + 65)
    return np.clip(np.cos(th), 0.0, 1.0), (v if shape else -v)


def extreme_over_contact(table, mod, rows, *, shape):
    """Per row: (t, value) of min phi (shape=True) or of max p (shape=False), t = |x|/a in [0, 1]."""
    rows = np.asarray(rows)
    if table.periodic:
        return _extreme_closed(table, rows, shape)
    t_out, v_out = np.empty(rows.size), np.empty(rows.size)
    for sel, Kb in _by_K(table, rows):
        r = rows[sel]
        a = table.a[r]

        def f(k, theta):
            if shape:
                t = mod.t_of_theta(theta, a[k])
                return series.sine_sum(table, r[k], theta, over_sin=True) * mod.shape_ratio(t, a[k])
            return -series.sine_sum(table, r[k], theta)

        # >= 8 samples per period of the highest kept term sin((2K-1) theta)
        M = max(64, 8 * Kb)
        theta, V = _grid_values(table, r, M, Kb, shape=shape)
        V = V * mod.shape_ratio(mod.t_of_theta(theta[None, :], a[:, None]), a[:, None]) if shape else -V
        th, v = minimize_rows(f, np.zeros(r.size), np.full(r.size, 0.5 * np.pi), theta.size, V=V)
        t_out[sel] = np.clip(mod.t_of_theta(th, a), 0.0, 1.0)
        v_out[sel] = v if shape else -v
    return t_out, v_out


def gap_outside(table, outside, rows, tau, delta_ratio, n):
    """gap(x)/Delta_1 = (g + u_z - u_z(0))/Delta_1 at x = a + (pi - a) tau^2 > a, table rows ``rows``,
    docs/theory/wavy.md (W18).

    Periodic: ``outside`` (periodic.OutsideTable).  Non-periodic: closed form; outside the cut
    the Cauchy transform of sqrt(1-s^2) U_{2m}(s) is w^(2m+1), w = t - sqrt(t^2-1), whose
    integral from 1 to t = x/a is G_{2m+1} (series.log_integral_sum), so
    u_z(x) - u_z(a) = -a sum_m D_m G_{2m+1}(t) in Delta_1 units."""
    a = table.a[rows]
    if table.periodic:
        return outside.gap(rows, tau)
    x = a + (np.pi - a) * tau * tau
    N = table.N[rows]
    eta = np.arccosh(np.maximum(x / a, 1.0))
    dg = initial_gap(x, delta_ratio, n, N) - initial_gap(a, delta_ratio, n, N)
    return dg - a * series.log_integral_sum(table, rows, eta)


def min_gap_outside(table, outside, rows, delta_ratio, n, *, tau0=1e-3):
    """Per row: (x/a, min gap/Delta_1) over a + 1e-6 (pi - a) <= x <= pi (tau >= tau0; at the
    edge itself the gap is 0 by construction).  Grid: >= 4 points per shortest wave."""
    rows = np.asarray(rows)
    # the grid of a row follows its own shortest wave, not its neighbours'
    n_max = np.array([int(np.max(n[: int(N)])) for N in table.N[rows]], dtype=int)
    tau, v = np.empty(rows.size), np.empty(rows.size)
    for m in np.unique(n_max):
        sel = np.flatnonzero(n_max == m)
        r = rows[sel]
        f = lambda k, t, r=r: gap_outside(table, outside, r[k], t, delta_ratio, n)
        tau[sel], v[sel] = minimize_rows(f, np.full(sel.size, tau0), np.ones(sel.size), 4 * int(m) + 129)
    a = table.a[rows]
    return (a + (np.pi - a) * tau * tau) / a, v
