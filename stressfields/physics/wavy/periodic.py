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

import numpy as np
import scipy.fft
from scipy.special import eval_legendre

from . import series
from .profile import gap_slope

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
    phi = 0.5 * np.sin(2.0 * n[None, :, None] * np.arctan(alpha[:, None, None] * np.cos(theta)))
    A = scipy.fft.dct(phi, type=2, axis=-1) / M
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
    """p_inf/p* = (1/2) sum_{i<N} (Delta_i/Delta_1) n_i [P_{n_i-1}(cos a) - P_{n_i}(cos a)].

    Closed form of eq. (6), docs/theory/wavy.md (W11) (not in the paper, which integrates the
    series numerically).  n = 1 gives Westergaard's sin^2(a/2).
    """
    c = np.cos(a)
    out = np.zeros(np.broadcast(a, N).shape)
    for i in range(len(n)):
        term = 0.5 * delta_ratio[i] * n[i] * (eval_legendre(n[i] - 1, c) - eval_legendre(n[i], c))
        out += np.where(N > i, term, 0.0)
    return out


def approach(a, delta_ratio, n, N):
    """u_z(0)/Delta_1 (= approach delta) with the ln|2 sin| kernel and C = 0, docs/theory/wavy.md (W16).

    From Betti's reciprocal theorem with the periodic flat punch (derived for this package,
    verified against independent quadrature, tests/data/wavy_tsukanov.json):
    delta = W delta_0(a) + int p_0 g dx with delta_0 = -2 ln sin(a/2)/(pi E*) per unit load and
    int p_0 cos(n x) dx = [P_n + P_{n-1}](cos a)/2, hence

        u_z(0)/Delta_1 = sum_i (Delta_i/Delta_1) { -n_i ln sin(a/2) [P_{n-1} - P_n] + 1 - [P_n + P_{n-1}]/2 }.

    n = 1 gives Westergaard's Delta sin^2(a/2) (1 - 2 ln sin(a/2)), docs/theory/wavy.md (W27).
    """
    c = np.cos(a)
    lns = np.log(np.sin(0.5 * a))
    out = np.zeros(np.broadcast(a, N).shape)
    for i in range(len(n)):
        p1, p0 = eval_legendre(n[i] - 1, c), eval_legendre(n[i], c)
        term = delta_ratio[i] * (-n[i] * lns * (p1 - p0) + 1.0 - 0.5 * (p0 + p1))
        out += np.where(N > i, term, 0.0)
    return out


def _w_of_x(x, a):
    """w = r - sqrt(r^2 - 1) in (0, 1] for a <= x <= pi, cancellation-free:
    w = sin(a/2) cos(x/2) / (sin(x/2) cos(a/2) + sqrt(sin((x-a)/2) sin((x+a)/2)))."""
    s = np.sqrt(np.maximum(np.sin(0.5 * (x - a)) * np.sin(0.5 * (x + a)), 0.0))
    return np.sin(0.5 * a) * np.cos(0.5 * x) / (np.sin(0.5 * x) * np.cos(0.5 * a) + s)


class OutsideTable:
    """gap(x)/Delta_1 = int_a^x [g'(y) + u_z'(y)] dy / Delta_1 for a < x <= pi, every table row,
    docs/theory/wavy.md (W18).

    Outside the contact u_z'/Delta_1 = -sum_m D_m w^(2m+1) (the Cauchy transform of
    sqrt(1-s^2) U_{j-1}(s) is w^j off the cut; inside it is T_j, which gives back -g').
    The integral has no closed form in this kernel, so it is done numerically in
    tau = sqrt((x-a)/(pi-a)) (removes the (x-a)^(1/2) edge behaviour) on panels fine enough for
    the profile's shortest wave, for w(x) and for the edge; 16-point Gauss-Legendre per panel.
    Cumulative panel sums make later evaluations cost one panel each.
    """

    def __init__(self, table, delta_ratio, n, rows):
        self.table, self.dr, self.n = table, delta_ratio, n
        self.rows = np.asarray(rows)
        a = table.a[self.rows][:, None]
        n_max = int(np.max(n[: int(np.max(table.N[self.rows]))]))
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
        slope = gap_slope(x, self.dr, self.n, self.table.N[row]) - series.power_sum(self.table, row, _w_of_x(x, a))
        return slope * 2.0 * (np.pi - a) * tau

    def _integrate(self, row, lo, hi):
        half = 0.5 * (hi - lo)
        nodes = (0.5 * (hi + lo))[..., None] + half[..., None] * _GL_NODES
        f = self._integrand(np.broadcast_to(row[..., None], nodes.shape), nodes)
        return half * np.sum(f * _GL_WEIGHTS, axis=-1)

    def gap(self, row, tau):
        """gap/Delta_1 at tau in [0, 1] for table rows ``row`` (same shape)."""
        row, tau = np.broadcast_arrays(np.asarray(row), np.asarray(tau, dtype=float))
        k_row = self.local[row]
        P = self.B.shape[1]
        flat = (self.B + 2.0 * np.arange(len(self.rows))[:, None]).ravel()
        k = np.searchsorted(flat, tau + 2.0 * k_row, side="right") - 1 - k_row * P
        k = np.clip(k, 0, P - 2)
        lo = self.B[k_row, k]
        return self.cum[k_row, k] + self._integrate(row, lo, tau)
