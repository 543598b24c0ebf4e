"""Harmonic table, initial gap and argument handling for the wavy-contact kernels.

Tsukanov (2018), "Partial contact of a rigid multisinusoidal wavy surface with an elastic
half-plane", Adv. Tribology 2018, 8431467 (doi:10.1155/2018/8431467), eq. (3), with the
conventions of docs/theory/wavy.md (W1), (W2):

* lengths are scaled so that the longest wavelength is lambda_1 = 2*pi (n_1 = 1);
* initial gap g(x) = sum_i Delta_i (1 - cos n_i x), all harmonics in phase at x = 0;
* results are normalised by p* = pi E* Delta_1 / lambda_1 (pressures) and Delta_1 (lengths),
  so they depend on the ratios Delta_i/Delta_1 only.
"""

from __future__ import annotations

import numpy as np

#: weights below this are dropped from series tails (rounding floor of the coefficients)
EPS = np.finfo(float).eps


def harmonic_table(amplitudes, wavenumbers):
    """Validate a harmonic table and return ``(delta_ratio, n)`` as float arrays.

    ``delta_ratio = Delta_i / Delta_1``.  The first row must be the base wave (n_1 = 1,
    Delta_1 > 0): it fixes lambda_1 = 2 pi and the scales p* and Delta_1.
    """
    amp = np.atleast_1d(np.asarray(amplitudes, dtype=float))
    n = np.atleast_1d(np.asarray(wavenumbers, dtype=float))
    if amp.ndim != 1 or n.shape != amp.shape or amp.size == 0:
        raise ValueError("amplitudes and wavenumbers must be 1-D arrays of the same, non-zero length")
    if not (np.all(np.isfinite(amp)) and np.all(np.isfinite(n))):
        raise ValueError("amplitudes and wavenumbers must be finite")
    if np.any(n != np.round(n)) or np.any(n < 1):
        raise ValueError(f"wavenumbers must be integers >= 1 (lambda_i = lambda_1/n_i), got {n.tolist()}")
    if n[0] != 1 or not amp[0] > 0:
        raise ValueError("the first harmonic must be the base wave: wavenumbers[0] == 1 and amplitudes[0] > 0")
    return amp / amp[0], n


def contact_angle(two_a_over_lambda1):
    """a in the units of docs/theory/wavy.md (W2) (lambda_1 = 2 pi): a = pi * (2a/lambda_1); checks
    0 < 2a/lambda_1 < 1."""
    w = np.asarray(two_a_over_lambda1, dtype=float)
    if np.any(~np.isfinite(w)) or np.any(w <= 0.0) or np.any(w >= 1.0):
        raise ValueError("two_a_over_lambda1 must lie in the open interval (0, 1) "
                         f"(contact narrower than one wavelength), got min={np.min(w)}, max={np.max(w)}")
    return np.pi * w


def harmonic_counts(n_harmonics, n_rows):
    """Integer array of harmonic counts N (first N rows of the table); None means all rows."""
    if n_harmonics is None:
        return np.asarray(n_rows)
    N = np.asarray(n_harmonics)
    if N.dtype.kind not in "iu":
        Nf = np.asarray(N, dtype=float)
        if np.any(Nf != np.round(Nf)):
            raise ValueError("n_harmonics must be integers")
        N = Nf.astype(int)
    if np.any(N < 1) or np.any(N > n_rows):
        raise ValueError(f"n_harmonics must lie in [1, {n_rows}] (rows of the harmonic table)")
    return N


def gap(x, delta_ratio, n, N):
    """Initial gap g(x)/Delta_1 = sum_{i<N} (Delta_i/Delta_1)(1 - cos n_i x), eq. (3),
    docs/theory/wavy.md (W1).

    ``x`` (lambda_1 = 2 pi units) and ``N`` are arrays of one shape; harmonics are looped
    over (a table has few rows).  1 - cos is written as 2 sin^2 to keep small gaps exact.
    """
    out = np.zeros(np.broadcast(x, N).shape)
    for i in range(len(n)):
        s = np.sin(0.5 * n[i] * x)
        out += np.where(N > i, 2.0 * delta_ratio[i] * s * s, 0.0)
    return out
