"""Non-periodic problem (single indenter, Cauchy kernel).

Tsukanov (2018), Adv. Tribology 8431467, eqs. (2), (13)-(16), (21), as corrected in
docs/theory/wavy.md (W4), (W8): per-harmonic pressure, s = x/a = cos(theta),

    p_i(x) = Delta_i n_i sum_j (-1)^j J_{2j+1}(a n_i) sin((2j+1) theta)            (eq. 14)

combined with E* = E/(1-nu^2), docs/theory/wavy.md (W5).  Bessel functions come from scipy's ``jv``
(forward recurrence is unstable for order > argument).  Displacement: kernel ln|x - xi| with
lengths in units where lambda_1 = 2 pi and C = 0 in eq. (5), docs/theory/wavy.md (W15).
"""

from __future__ import annotations

import numpy as np
from scipy.special import j0, j1, jv


#: scipy jv is accurate relative to each value: no absolute rounding plateau
COEFFICIENT_NOISE = False


def window_terms(a, n_max, rtol):
    """Terms expected for rtol, docs/theory/wavy.md (W24): K ~ z/2 + 2 z^(1/3) + 8 at 1e-10, z = a n
    (the super-exponential cut-off past order z); the additive part is scaled with ln(1/rtol)."""
    z = a * n_max
    return 0.5 * z + (2.0 * np.cbrt(z) + 8.0) * max(1.0, np.log(1.0 / rtol) / np.log(1e10))


def coefficients(a, n, L):
    """(-1)^m J_{2m+1}(a n_i), shape (len(a), len(n), L)."""
    m = np.arange(L)
    z = np.asarray(a, dtype=float)[:, None, None] * n[None, :, None]
    return np.where(m % 2 == 0, 1.0, -1.0) * jv(2.0 * m + 1.0, z)


def theta_of_t(t, a=None):
    """theta = arccos(t) in [0, pi/2] for t = |x|/a in [0, 1], accurate near t = 1."""
    return 2.0 * np.arctan2(np.sqrt(1.0 - t), np.sqrt(1.0 + t))


def t_of_theta(theta, a=None):
    return np.cos(theta)


def shape_ratio(t, a=None):
    """sin(theta)/sqrt(1-t^2) = 1 here."""
    return np.ones(np.broadcast(t, a).shape)


def mean_pressure(a, delta_ratio, n, N):
    """p_inf/p* = (1/2) sum_{i<N} (Delta_i/Delta_1) a n_i J_1(a n_i)  (eq. 16 times 2/Delta_1),
    docs/theory/wavy.md (W12)."""
    out = np.zeros(np.broadcast(a, N).shape)
    for i in range(len(n)):
        z = a * n[i]
        out += np.where(N > i, 0.5 * delta_ratio[i] * z * j1(z), 0.0)
    return out


def approach(a, delta_ratio, n, N):
    """u_z(0)/Delta_1 with kernel ln|x - xi| (lambda_1 = 2 pi units) and C = 0, docs/theory/wavy.md (W16).

    Betti's theorem with the flat punch (p_0 = 1/(pi sqrt(a^2-x^2)) per unit load, whose
    displacement is -2 ln(a/2)/(pi E*) and int p_0 cos(n x) dx = J_0(a n)) gives

        u_z(0)/Delta_1 = sum_i (Delta_i/Delta_1) [ -a n_i J_1(a n_i) ln(a/2) + 1 - J_0(a n_i) ],

    which equals eq. (15) at x = 0 (checked in the tests) without a series.
    """
    out = np.zeros(np.broadcast(a, N).shape)
    for i in range(len(n)):
        z = a * n[i]
        out += np.where(N > i, delta_ratio[i] * (-z * j1(z) * np.log(0.5 * a) + _one_minus_j0(z)), 0.0)
    return out


def _one_minus_j0(z):
    """1 - J_0(z), docs/theory/wavy.md (W16), without the cancellation of the difference as z -> 0
    (relative error 4e-7 at z = 3e-5, i.e. 3e-8 of the approach at 2a/lambda_1 = 1e-5, measured against
    the Hertz line contact): for z <= 2 the alternating series sum_{k>=1} (-1)^(k+1) (z^2/4)^k/(k!)^2,
    terms falling at least fourfold, first term at most 1.3 times the sum; beyond, |J_0| < 0.23 and the
    difference loses nothing."""
    z = np.asarray(z, dtype=float)
    q = 0.25 * z * z
    small = q <= 1.0
    term = np.where(small, q, 0.0)
    total = term.copy()
    for k in range(1, 24):          # 1/(24!)^2 ~ 1e-47: far below eps
        term = -term * q / ((k + 1) * (k + 1))
        total = total + term
    return np.where(small, total, 1.0 - j0(z))

