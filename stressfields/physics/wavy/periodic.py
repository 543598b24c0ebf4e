"""Periodic problem (period lambda_1 = 2 pi, Hilbert/cot kernel).

Tsukanov (2018), Adv. Tribology 8431467, eqs. (1), (5)-(12) and (A.1)-(A.10), as corrected in
docs/theory/wavy.md (W3), (W6), (W7): per-harmonic pressure

    p_i(x) = Delta_i n_i sum_j A_ij sin(j theta),   cos(theta) = r = tan(x/2)/tan(a/2),
    A_ij = (1/pi) int_0^pi sin(2 n_i arctan(tan(a/2) cos t)) cos(j t) dt   (eq. 11-12),

combined with the corrected factor E* = E/(1-nu^2), docs/theory/wavy.md (W5).  Displacements use
the periodic kernel ln|2 sin((x-xi)/2)| with C = 0 in eq. (5), docs/theory/wavy.md (W15): its
datum is zero mean displacement over one period.
"""

from __future__ import annotations

import functools

import numpy as np
import scipy.fft
from scipy.special import eval_jacobi, eval_legendre

from . import series

# Gauss-Legendre rule used on every panel of the outside-contact integrals
_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(16)


#: DCT coefficients end in a rounding plateau that must not count as a truncation tail
COEFFICIENT_NOISE = True


def window_terms(a, n_max, rtol):
    """Terms (odd Chebyshev indices) expected for rtol, docs/theory/wavy.md (W24):
    J ~ 1.2 [2 n tan(a/2) + ln(1/rtol) / ln cot(a/4)], i.e. about J/2 + 1 odd terms."""
    J = 1.2 * (2.0 * n_max * np.tan(0.5 * a) + np.log(1.0 / rtol) / np.log(1.0 / np.tan(0.25 * a)))
    return 0.5 * J + 1.0


def coefficients(a, n, L):
    """Odd Chebyshev coefficients A_{i,2m+1}, m < L, of eq. (11), shape (len(a), len(n), L).

    One DCT-II of M = 4L Gauss-Chebyshev nodes per (a, harmonic): indices up to 2L-1 are then
    aliased only by indices >= 6L, negligible where the series has converged.  phi_i is used
    in its exact form sin(2 n arctan(alpha s))/2 (eq. A.5), docs/theory/wavy.md (W7), not through U_{n-1}.
    """
    M = 4 * L
    theta = (2.0 * np.arange(M) + 1.0) * np.pi / (2.0 * M)
    alpha = np.tan(0.5 * np.asarray(a, dtype=float))
    phi = 0.5 * np.sin(2.0 * n[None, :, None] * np.arctan(alpha.reshape(-1)[:, None, None] * np.cos(theta)))
    # one DCT per angle: a batched DCT may round a row differently with the number of rows, and an
    # angle's coefficients must not depend on the other angles of the call
    A = np.stack([scipy.fft.dct(row, type=2, axis=-1) for row in phi]) / M if len(phi) else phi
    return A[..., 1:2 * L:2]


def _one_minus_plus_r(t, a):
    """1 - r and 1 + r, r = tan(x/2)/tan(a/2), x = a t, without cancellation at r -> +-1,
    docs/theory/wavy.md (W6)."""
    den = np.sin(0.5 * a) * np.cos(0.5 * a * t)
    return np.sin(0.5 * a * (1.0 - t)) / den, np.sin(0.5 * a * (1.0 + t)) / den


def theta_of_t(t, a):
    """theta in [0, pi/2] for t = |x|/a in [0, 1]."""
    om, op = _one_minus_plus_r(t, a)
    return 2.0 * np.arctan2(np.sqrt(om), np.sqrt(op))


def t_of_theta(theta, a):
    """Inverse of theta_of_t: x = 2 arctan(tan(a/2) cos theta), t = x/a."""
    return 2.0 * np.arctan(np.tan(0.5 * a) * np.cos(theta)) / a


def shape_ratio(t, a):
    """sin(theta)/sqrt(1-t^2) > 0; turns p/sin(theta) into phi = p/sqrt(1-(x/a)^2).

    Equals sqrt(a/sin a) at the edge; written with sinc so t = 1 is not 0/0."""
    den = np.sin(0.5 * a) * np.cos(0.5 * a * t)
    sinc = lambda u: np.sinc(u / np.pi)
    return np.sqrt((0.5 * a) ** 2 * sinc(0.5 * a * (1.0 - t)) * sinc(0.5 * a * (1.0 + t))) / den


def mean_pressure(a, delta_ratio, n, N):
    """p_inf/p* = (1/2) sum_{i<N} (Delta_i/Delta_1) n_i [P_{n_i-1}(cos a) - P_{n_i}(cos a)]
    = sum_i (Delta_i/Delta_1) n_i sin^2(a/2) P_{n_i-1}^(1,0)(cos a), the second form (W34) evaluated.

    Closed form of eq. (6), docs/theory/wavy.md (W11) (not in the paper, which integrates the
    series numerically).  n = 1 gives Westergaard's sin^2(a/2).
    """
    u = np.sin(0.5 * np.asarray(a, dtype=float)) ** 2
    out = np.zeros(np.broadcast(a, N).shape)
    for i in range(len(n)):
        term = delta_ratio[i] * n[i] * u * _jacobi10(int(n[i]) - 1, u)
        out += np.where(N > i, term, 0.0)
    return out


def _jacobi10(m, u):
    """P_m^(1,0)(1 - 2u), so that P_m - P_{m+1} = 2u P_m^(1,0) (W34) without the cancellation of the
    difference as a -> 0 (relative error 1 at 2a/lambda_1 = 1e-9 in the Legendre form).

    Where (m+1)^2 u <= 1/2: (m+1) 2F1(-m, m+2; 2; u), terms shrinking by at least 1/((k+1)(k+2)),
    so no cancellation; elsewhere scipy's eval_jacobi (the value is then >= O(1/m))."""
    u = np.asarray(u, dtype=float)
    small = (m + 1) ** 2 * u <= 0.5
    term = np.full(u.shape, float(m + 1))
    total = term.copy()
    for k in range(min(m, 40)):   # ratio <= 0.5/((k+1)(k+2)): 40 terms reach far below eps
        term = term * -(m - k) * (m + 2 + k) * u / ((k + 1) * (k + 2))
        total = total + term
    return np.where(small, total, eval_jacobi(m, 1, 0, 1.0 - 2.0 * u))


def approach(a, delta_ratio, n, N):
    """u_z(0)/Delta_1 (= approach delta) with the ln|2 sin| kernel and C = 0, docs/theory/wavy.md (W16).

    From Betti's reciprocal theorem with the periodic flat punch (derived for this package,
    verified against independent quadrature, tests/data/wavy_tsukanov.json):
    delta = W delta_0(a) + int p_0 g dx with delta_0 = -2 ln sin(a/2)/(pi E*) per unit load and
    int p_0 cos(n x) dx = [P_n + P_{n-1}](cos a)/2, hence

        u_z(0)/Delta_1 = sum_i (Delta_i/Delta_1) { -n_i ln sin(a/2) [P_{n-1} - P_n] + 1 - [P_n + P_{n-1}]/2 }.

    n = 1 gives Westergaard's Delta sin^2(a/2) (1 - 2 ln sin(a/2)), docs/theory/wavy.md (W27).
    """
    a = np.asarray(a, dtype=float)
    u = np.sin(0.5 * a) ** 2
    lns = np.log(np.sin(0.5 * a))
    out = np.zeros(np.broadcast(a, N).shape)
    for i in range(len(n)):
        k = int(n[i])
        # both differences without cancellation as a -> 0 (W34): P_{n-1} - P_n = 2u P^(1,0)_{n-1}
        diff = 2.0 * u * _jacobi10(k - 1, u)
        rest = 0.5 * (_one_minus_legendre(k, u) + _one_minus_legendre(k - 1, u))
        out += np.where(N > i, delta_ratio[i] * (-k * lns * diff + rest), 0.0)
    return out


def _one_minus_legendre(k, u):
    """1 - P_k(1 - 2u), docs/theory/wavy.md (W16), (W34).

    Where (k+1)^2 u <= 1/2: -sum_{m>=1} (-k)_m (k+1)_m/(m!)^2 u^m (the 2F1 form of P_k), first term
    k(k+1)u, alternating terms shrinking at least twofold, so relative accuracy is kept as a -> 0
    (the difference 1 - P_k loses every digit at 2a/lambda_1 = 1e-9); elsewhere 1 - P_k directly
    (then 1 - P_k >= O(1/k^2), no cancellation worth a digit)."""
    u = np.asarray(u, dtype=float)
    if k == 0:
        return np.zeros(u.shape)
    small = (k + 1) ** 2 * u <= 0.5
    term = np.full(u.shape, float(k * (k + 1))) * u
    total = term.copy()
    for m in range(1, min(k, 40)):   # ratio <= 1/2 and falling like 1/m^2: 40 terms reach far below eps
        term = term * -(k - m) * (k + 1 + m) * u / ((m + 1) * (m + 1))
        total = total + term
    return np.where(small, total, 1.0 - eval_legendre(k, 1.0 - 2.0 * u))


class OutsideTable:
    """gap(x)/Delta_1 = int_a^x [g'(y) + u_z'(y)] dy / Delta_1 for a < x <= pi, every table row,
    docs/theory/wavy.md (W18).

    Outside the contact g' + u_z' = S(x) Q(x), the closed form (W33) (the series form
    -sum_m D_m w^(2m+1) of (W18) converges slowly as 2a/lambda_1 -> 1).
    The integral is done numerically in
    tau = sqrt((x-a)/(pi-a)) (removes the (x-a)^(1/2) edge behaviour) on panels fine enough for
    the profile's shortest wave, for w(x) and for the edge; 16-point Gauss-Legendre per panel.
    Cumulative panel sums make later evaluations cost one panel each.  The panels of a row follow
    its own shortest wave (rows with equal n_max share a panel table), so a row's gap does not
    depend on the other rows tabulated with it.
    """

    def __init__(self, table, delta_ratio, n, rows):
        self.rows = np.asarray(rows)
        n_max = np.array([int(np.max(n[: int(N)])) for N in table.N[self.rows]], dtype=int)
        self.parts = {int(m): _Panels(table, self.rows[n_max == m], int(m)) for m in np.unique(n_max)}
        self.part = np.full(len(table.K), -1)
        self.part[self.rows] = n_max

    def gap(self, row, tau):
        """gap/Delta_1 at tau in [0, 1] for table rows ``row`` (same shape)."""
        row, tau = np.broadcast_arrays(np.asarray(row), np.asarray(tau, dtype=float))
        out = np.empty(row.shape)
        key = self.part[row]
        for m, part in self.parts.items():
            sel = key == m
            out[sel] = part.gap(row[sel], tau[sel])
        return out


class _Panels:
    """The panel table of OutsideTable for rows sharing the shortest wave 2 pi/n_max."""

    def __init__(self, table, rows, n_max):
        self.table = table
        self.rows = np.asarray(rows)
        a = table.a[self.rows][:, None]
        u = np.linspace(0.0, 1.0, 25)[None, :]
        tau_x = np.sqrt(np.linspace(0.0, 1.0, 2 * n_max + 9))[None, :] * np.ones_like(a)
        ww = np.linspace(0.0, 1.0, n_max + 9)[1:-1][None, :]
        xw = 2.0 * np.arctan(np.tan(0.5 * a) * 0.5 * (ww + 1.0 / ww))
        tau_w = np.sqrt(np.clip((xw - a) / (np.pi - a), 0.0, 1.0))
        self.B = np.sort(np.concatenate([u * np.ones_like(a), tau_x, tau_w], axis=1), axis=1)
        lo, hi = self.B[:, :-1], self.B[:, 1:]
        panel = self._integrate(np.repeat(self.rows[:, None], lo.shape[1], 1), lo, hi)
        self.cum = np.concatenate([np.zeros((len(self.rows), 1)), np.cumsum(panel, axis=1)], axis=1)
        self.local = np.full(len(table.K), -1)
        self.local[self.rows] = np.arange(len(self.rows))

    def _integrand(self, row, tau):
        a = self.table.a[row]
        x = a + (np.pi - a) * tau * tau
        slope = closed_gap_slope(self.table, row, x)
        return slope * 2.0 * (np.pi - a) * tau

    def _integrate(self, row, lo, hi):
        half = 0.5 * (hi - lo)
        nodes = (0.5 * (hi + lo))[..., None] + half[..., None] * _GL_NODES
        f = self._integrand(np.broadcast_to(row[..., None], nodes.shape), nodes)
        return half * series.row_dot(f, _GL_WEIGHTS)

    def gap(self, row, tau):
        """gap/Delta_1 at tau in [0, 1] for table rows ``row`` (same shape)."""
        row, tau = np.broadcast_arrays(np.asarray(row), np.asarray(tau, dtype=float))
        k_row = self.local[row]
        P = self.B.shape[1]
        # the panel of each point against its own row's breakpoints (a search in one flat array with
        # row offsets would round tau + offset, and so the panel, with the row's place in the table)
        k = np.empty(tau.shape, dtype=int)
        kf, rf, tf = k.reshape(-1), k_row.reshape(-1), tau.reshape(-1)
        step = max(1, (1 << 22) // P)
        for i0 in range(0, tf.size, step):
            sl = slice(i0, i0 + step)
            kf[sl] = np.count_nonzero(self.B[rf[sl]] <= tf[sl, None], axis=1) - 1
        k = np.clip(k, 0, P - 2)
        lo = self.B[k_row, k]
        return self.cum[k_row, k] + self._integrate(row, lo, tau)


# ------------------------------------------------------------- closed form, docs/theory/wavy.md (W30)

#: odd Chebyshev terms used only for the magnitude scale of a contact (W32); a lower bound of the
#: l2 norm, exact to rounding for 2a/lambda_1 <= 0.5 (where the substitution test applies)
_MAGNITUDE_TERMS = 64
#: unit roundoff u = eps/2; libm sin/cos are taken as good to 1 ulp (2u absolute for |cos| <= 1;
#: measured here 0.52 ulp on 10^6 arguments up to 1000 against 80-bit values)
_U = 0.5 * series.EPS


@functools.lru_cache(maxsize=4)
def _central(top):
    """g_m = binom(2m, m)/4^m, m < top, each correctly rounded (exact integers, one rounded division)."""
    g, c = [], 1
    for m in range(top):
        if m:
            c = c * (2 * m) * (2 * m - 1) // (m * m)
        g.append(c / (1 << (2 * m)))
    return np.array(g)


def legendre_by_cosines(a, top):
    """P_k(cos a) for k < top (columns) and a bound of each value's rounding error, rows of a.

    The positive-coefficient cosine sum (W35), P_k(cos a) = sum_m g_m g_{k-m} cos((k - 2m) a), whose
    weights sum to 1: its error is the cosines' own (argument j a rounded) plus the summation's, about
    (k/2 + k a) u, where the three-term recurrence of P_k(c) (scipy's eval_legendre) carries the
    rounding of c = cos a with the factor dP_k/dc = k(k + 1)/2 at c = 1 (measured 1.2 times the
    former bound of (W31) at n = 58).  Bound per value, u = eps/2:
    u [sum_j G_kj |sin(j a)| j a + k/2 + 9] (cosine argument and 1 ulp, weights 3u, k/2 + 1 sums).
    """
    return cosine_sums(a, _central(top), normalised=True)


def cosine_sums(a, g, *, normalised=False):
    """sum_m g_m g_{k-m} cos((k - 2m) a) for k < len(g) (columns), rows of a, and a bound of each
    value's rounding error: u [sum_j |G_kj| (|sin(j a)| j a + k/2 + 9)] with G_kj the weights of
    cos(j a), u = eps/2 (the bound of (W35), which has sum_j G_kj = 1).  The coefficients of
    (sum_m g_m e^{ima} w^m)(sum_m g_m e^{-ima} w^m): with g_m = binom(2m, m)/4^m the Legendre
    generating function (W35) (``normalised``: the weights of each k sum to 1, as (W35) counts them);
    with the coefficients of sqrt(1 - u) those of sqrt(1 - 2 w cos a + w^2), docs/theory/wavy.md (W40)."""
    a = np.asarray(a, dtype=float).reshape(-1)
    top = len(g)
    j = np.arange(top)
    ja = j[None, :] * a[:, None]
    cosj = np.cos(ja)
    arg = np.abs(np.sin(ja)) * ja
    P, A, W = np.zeros((a.size, top)), np.zeros((a.size, top)), np.zeros((1, top))
    # added in order of the cosine index j for every k (not a matrix product, whose grouping follows
    # the number of rows): a value does not depend on the other angles or on top
    for jj in range(top):
        k = np.arange(jj, top, 2)                   # k - 2m = jj
        m = (k - jj) // 2
        weight = g[m] * g[k - m] * (2.0 if jj > 0 else 1.0)
        P[:, k] += cosj[:, jj:jj + 1] * weight[None, :]
        A[:, k] += arg[:, jj:jj + 1] * np.abs(weight)[None, :]
        W[:, k] += np.abs(weight)[None, :]
    E = _U * (A + (1.0 if normalised else W) * (0.5 * j[None, :] + 9.0))
    return P, E


def closed_coefficients(a, delta_ratio, n, N, *, bound=False):
    """B_j (rows of a/N, j < max n_i): p/p* = R(x) sum_j B_j cos((j + 1/2) x),
    B_j = sum_{i<N, n_i>j} 2 (Delta_i/Delta_1) n_i P_{n_i-1-j}(cos a), docs/theory/wavy.md (W30), with
    P_k from (W35).  bound=True also returns a bound of each B_j's rounding error (W31)."""
    a, N = np.asarray(a, dtype=float), np.asarray(N, dtype=int)
    used = n[: int(np.max(N))]
    top = int(np.max(used))
    P, E = legendre_by_cosines(a, top)
    B, errB = np.zeros((a.size, top)), np.zeros((a.size, top))
    # sum over the harmonics: one product rounding each for w_i and w_i P, up to N additions (the
    # row's own N: a row's bound must not depend on the other rows' harmonic counts)
    acc = (N[:, None] + 2) * _U
    for i in range(len(used)):
        ni = int(n[i])
        k = ni - 1 - np.arange(ni)
        on = N[:, None] > i
        w = 2.0 * delta_ratio[i] * ni
        B[:, :ni] += np.where(on, w * P[:, k], 0.0)
        errB[:, :ni] += np.where(on, abs(w) * (E[:, k] + acc * (np.abs(P[:, k]) + E[:, k])), 0.0)
    return (B, errB) if bound else B


def rounding_bound(a, B, errB, K, reach):
    """Bound of |Q_computed - Q| for |x| <= reach, rows of B (W31): the coefficients' own errors, the
    argument of cos((j + 1/2) x) (x = a t and the product rounded: (2j + 1) x u, plus 1 ulp), one
    product and K sums per term."""
    j = np.arange(B.shape[1])
    absB = np.abs(B)
    # column-order sums (series.row_dot): a row's bound does not depend on the others or the width
    return series.row_sum(errB) + _U * (series.row_dot(absB, 2.0 * j + 1.0) * reach + series.row_sum(absB) * (K + 4.0))


def build_table(a_values, N_values, delta_ratio, n, *, rtol):
    """The periodic route as a SeriesTable: D holds B_j of (W30), K the number of terms, err the
    rounding bound (W31), scale the magnitude scale (W32); converged = err <= rtol (p* units)."""
    if not rtol > 0:
        raise ValueError("rtol must be positive")
    a = np.repeat(np.asarray(a_values, dtype=float), len(N_values))
    N = np.tile(np.asarray(N_values, dtype=int), len(a_values))
    B, errB = closed_coefficients(a, delta_ratio, n, N, bound=True)
    K = np.array([int(np.max(n[:k])) for k in N])
    errQ = rounding_bound(a, B, errB, K, a)
    absQ = series.row_sum(np.abs(B))
    # p = R Q with R <= sin(a/2) good to 9u sin(a/2) (W31), one more product; phi = (a/2) sqrt(sinc
    # s2/(1 + t)) Q with the factor <= a/2 good to 8u of itself (W31)
    err = np.sin(0.5 * a) * (errQ + 10.0 * _U * absQ)
    err_shape = 0.5 * a * (errQ + 9.0 * _U * absQ)
    C = coefficients(np.asarray(a_values, dtype=float), n, _MAGNITUDE_TERMS)
    w = 2.0 * delta_ratio * n
    norm = np.cumsum(np.abs(w)[None, :] * np.sqrt(np.sum(C * C, axis=-1)), axis=1)[:, np.asarray(N_values) - 1]
    return series.SeriesTable(periodic=True, a=a, N=N, D=B, K=K, err=err, err_shape=err_shape,
                              converged=err <= rtol, scale=norm.reshape(-1))


def q_sum(table, row, x):
    """Q(x) = sum_j B_j cos((j + 1/2) x) for table rows ``row`` (W30)."""
    row, x = np.broadcast_arrays(np.asarray(row), np.asarray(x, dtype=float))
    out = np.zeros(x.shape)
    for j in range(table.D.shape[1]):
        out += table.D[row, j] * np.cos((j + 0.5) * x)
    return out


def _half_angle_sines(a, t):
    """y1 = a(1 - t)/2 and s1 = sin y1, s2 = sin(a(1 + t)/2), each good to a few u relative: past
    pi/2, s2 = sin a cos y1 - cos a sin y1, a sum of two non-negative terms, because sin of the
    rounded argument near pi loses digits (relative error 1e-9 at 2a/lambda_1 = 1 - 1e-7), (W31)."""
    y1 = 0.5 * a * (1.0 - t)
    y2 = 0.5 * a * (1.0 + t)
    s2 = np.where(y2 <= 0.5 * np.pi, np.sin(y2), np.sin(a) * np.cos(y1) - np.cos(a) * np.sin(y1))
    return y1, np.sin(y1), s2


def closed_pressure(table, row, t):
    """p/p* = R Q at |x|/a = t in [0, 1]; R = sqrt(sin(a(1-t)/2) sin(a(1+t)/2)) without
    cancellation at the edge, docs/theory/wavy.md (W30)."""
    a = table.a[row]
    _, s1, s2 = _half_angle_sines(a, t)
    return np.sqrt(s1 * s2) * q_sum(table, row, a * t)


def closed_shape(table, row, t):
    """phi = p/sqrt(1 - t^2) / p* = sqrt((a/2) sinc(a(1-t)/2) sin(a(1+t)/2)/(1 + t)) Q(a t), finite at
    the edge, where it is the edge coefficient (1/2) sqrt(a sin a) Q(a), docs/theory/wavy.md (W30)."""
    a = table.a[row]
    y1, _, s2 = _half_angle_sines(a, t)
    return np.sqrt(0.5 * a * np.sinc(y1 / np.pi) * s2 / (1.0 + t)) * q_sum(table, row, a * t)


def closed_peak(table, rows):
    """p(0)/p* = sin(a/2) sum_j B_j, docs/theory/wavy.md (W30)."""
    return np.sin(0.5 * table.a[rows]) * series.row_sum(table.D[rows])


def closed_gap_slope(table, row, x):
    """gap'(x)/Delta_1 = S(x) Q(x) for a <= x <= pi, S = sqrt(sin((x-a)/2) sin((x+a)/2)): the
    analytic continuation of (W30) off the contact, docs/theory/wavy.md (W33)."""
    a = table.a[row]
    S = np.sqrt(np.maximum(np.sin(0.5 * (x - a)) * np.sin(0.5 * (x + a)), 0.0))
    return S * q_sum(table, row, x)
