"""Numerically stable elementary pieces shared by the axisymmetric kernels: the forms of
docs/theory/axisymmetric.md (A78)-(A94)."""
from __future__ import annotations

import math

import numpy as np
from scipy.special import zeta

__all__ = ["sqrt_diff", "arccosh_ratio", "asin_defect", "hertz_f2", "hertz_f4", "log_sinc"]


def sqrt_diff(p, q):
    """sqrt(p^2 - q^2) as sqrt((p - q)(p + q)): no cancellation near p = q
    (docs/theory/axisymmetric.md (A78)); 0 if p < q."""
    return np.sqrt(np.maximum((p - q) * (p + q), 0.0))


def arccosh_ratio(a, r):
    """arccosh(a/r) for a >= r > 0 as log1p((a - r + sqrt((a-r)(a+r)))/r), docs/theory/axisymmetric.md
    (A79): accurate both for r -> 0 and r -> a."""
    return np.log1p((a - r + sqrt_diff(a, r)) / r)


def _series(z, coef):
    """Horner sum of coef[k] z^k."""
    out = np.zeros_like(z)
    for c in coef[::-1]:
        out = out * z + c
    return out


# q/sqrt(1-q^2) - arcsin(q) = sum_{k>=1} binom(2k,k)/4^k * 2k/(2k+1) q^(2k+1)
_ASIN_DEFECT = [math.comb(2 * k, k) / 4.0 ** k * 2 * k / (2 * k + 1) for k in range(1, 18)]


def asin_defect(a, r):
    """a / sqrt(r^2 - a^2) - arcsin(a/r) for 0 <= a < r.  The direct difference loses (r/a)^2
    relative digits far outside the contact (Hertz dp/dz); a series in q = a/r is used for q < 0.25
    (docs/theory/axisymmetric.md (A92)).  Near r = a the square root is formed as sqrt((r-a)(r+a))
    (docs/theory/axisymmetric.md (A78)), not from a/r."""
    a = np.asarray(a, dtype=float)
    r = np.asarray(r, dtype=float)
    q = a / r
    small = q < 0.25
    with np.errstate(divide="ignore", invalid="ignore"):
        s = sqrt_diff(r, a)
        direct = a / s - np.arctan2(a, s)
    q2 = q * q
    series = q * q2 * _series(q2, _ASIN_DEFECT)
    return np.where(small, series, direct)


# f2 = theta - sin(theta)cos(theta) = sum_{k>=1} (-1)^(k+1) (2 theta)^(2k+1) / (2 (2k+1)!)
_F2 = [(-1) ** (k + 1) * 2.0 ** (2 * k + 1) / (2.0 * math.factorial(2 * k + 1)) for k in range(1, 13)]
# f4 = (3 theta - 2 sin 2theta + sin(4 theta)/4) / 4 = sum_{k>=2} (-1)^k (16^k - 4^(k+1)) theta^(2k+1) / (4 (2k+1)!)
_F4 = [(-1) ** k * (16.0 ** k - 4.0 ** (k + 1)) / (4.0 * math.factorial(2 * k + 1)) for k in range(2, 16)]


def hertz_f2(theta):
    """F / r^2 of eqs. (16)-(17): 2 int_0^theta sin^2 = theta - sin(theta) cos(theta).  Series for
    theta < 0.5 (the closed form loses (r/a)^2 relative digits far outside,
    docs/theory/axisymmetric.md (A93))."""
    t = np.asarray(theta, dtype=float)
    t2 = t * t
    series = t * t2 * _series(t2, _F2)
    direct = t - np.sin(t) * np.cos(t)
    return np.where(t < 0.5, series, direct)


def hertz_f4(theta):
    """H / r^4 of eqs. (16)-(17): 2 int_0^theta sin^4 = (3 theta - 2 sin 2theta + sin(4 theta)/4)/4.
    Series for theta < 0.5 (the closed form loses (r/a)^4 relative digits far outside,
    docs/theory/axisymmetric.md (A94))."""
    t = np.asarray(theta, dtype=float)
    t2 = t * t
    series = t * t2 * t2 * _series(t2, _F4)
    direct = 0.25 * (3.0 * t - 2.0 * np.sin(2.0 * t) + 0.25 * np.sin(4.0 * t))
    return np.where(t < 0.5, series, direct)


# log(sin t / t) = -sum_{k>=1} zeta(2k) / k * (t/pi)^(2k)
_LOGSINC = [-float(zeta(2 * k)) / k / math.pi ** (2 * k) for k in range(1, 16)]


def log_sinc(t):
    """log(sin t / t) for 0 <= t <= pi/2 and its ratio to t^2: returns (log_sinc, log_sinc / t^2),
    both accurate to a few ulps (series for t < 0.6, where the direct form cancels)."""
    t = np.asarray(t, dtype=float)
    t2 = t * t
    ratio_series = t2 * 0.0 + _series(t2, _LOGSINC)  # log_sinc / t^2
    with np.errstate(divide="ignore", invalid="ignore"):
        direct = np.log(np.sin(t) / t)
        ratio_direct = direct / t2
    small = t < 0.6
    ratio = np.where(small, ratio_series, ratio_direct)
    return ratio * t2, ratio
