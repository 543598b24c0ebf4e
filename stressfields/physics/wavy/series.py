"""Truncated sine series shared by the periodic and non-periodic solutions.

Both of Tsukanov's (2018) solutions have the same form once harmonics are combined,
docs/theory/wavy.md (W9):

    p(x)/p* = sum_{m>=0} D_m sin((2m+1) theta),     D_m = 2 sum_i (Delta_i/Delta_1) n_i C_im,

* periodic, eqs. (10)-(12): C_im = A_{i,2m+1}, the odd Chebyshev coefficients of
  phi_i(s) = sin(2 n_i arctan(s tan(a/2)))/2, and cos(theta) = tan(x/2)/tan(a/2);
* non-periodic, eq. (14): C_im = (-1)^m J_{2m+1}(a n_i), and cos(theta) = x/a.

(The factor 2 is E*/p* with p* = E* Delta_1/2: the corrected combining factor E*, docs/theory/wavy.md (W5).)
Only the coefficients and the map x -> theta differ, so truncation, error estimates and
evaluation live here once.

Truncation.  For each contact angle the coefficients are computed on a window of L terms
(L from the laws of docs/theory/wavy.md (W24)), and the number of terms K kept is the smallest with

    tail(K) = sum_{m>=K} sum_i |w_i C_im|  (+ geometric extrapolation beyond the window)
            <= rtol * min(1, sum_i |w_i| ||C_i||_2)  (p* = 1, or the contact's smaller magnitude, (W22)).

tail(K) bounds |p - p_K|/p* pointwise (|sin| <= 1); plus rounding terms (coefficient noise,
summation) it is returned as the error estimate, an upper bound of |error|, and ``converged``
means the estimate is <= rtol * p*: the contract |error| <= rtol * max(|value|, p*),
docs/theory/wavy.md (W22), (W23).
When the tail is not small inside the window, the window is doubled, up to ``max_terms``;
past that the row is returned with ``converged = False`` and the (large) honest estimate.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .profile import EPS

#: terms and points evaluated at once (memory ~ 8 bytes * _BLOCK_TERMS * _CHUNK_ROWS = 4 MB); fixed,
#: so that neither depends on the other points of the array (see ``_series_sum``)
_BLOCK_TERMS = 64
_CHUNK_ROWS = 8192


@dataclass
class SeriesTable:
    """Combined coefficients for rows (a, N): row = ia * len(N_values) + iN."""

    periodic: bool
    a: np.ndarray          # (R,) contact angle of each row (lambda_1 = 2 pi)
    N: np.ndarray          # (R,) harmonic count of each row
    D: np.ndarray          # (R, Kmax) combined coefficients, zero beyond K
    K: np.ndarray          # (R,) terms kept
    err: np.ndarray        # (R,) bound of |p - p_K| / p*
    err_shape: np.ndarray  # (R,) bound of the error of p/sin(theta) (weights 2m+1)
    converged: np.ndarray  # (R,) error estimate <= rtol (p* units) reached
    scale: np.ndarray      # (R,) sum_i |w_i| ||C_i||_2; truncation aims at rtol * min(1, scale) (W22)


def _module(is_periodic):
    # imported here: periodic.py uses this module's evaluators (no import cycle at load time)
    from . import nonperiodic, periodic
    return periodic if is_periodic else nonperiodic


def _pow2(v, lo=16):
    return np.maximum(lo, 2 ** np.ceil(np.log2(np.maximum(v, 1.0)))).astype(int)


def _truncate(wC, N_values, rtol, window_full, noise, weighted):
    """Choose K for every (a, N) of one window; see the module docstring."""
    L = wC.shape[-1]
    cum_abs = np.cumsum(np.abs(wC), axis=1)[:, N_values - 1, :]          # (na, UN, L)
    D = np.cumsum(wC, axis=1)[:, N_values - 1, :]
    scale = np.cumsum(np.sqrt(np.sum(wC * wC, axis=-1)), axis=1)[:, N_values - 1]
    # DCT coefficients level off at an absolute rounding plateau (~eps/10 max|phi|), which is
    # not a truncation tail; it is measured on the last quarter of the window (if the series
    # has not reached it there, the tail test below fails and the window grows).  Bessel
    # values are accurate relative to themselves: no plateau.
    plateau = np.median(cum_abs[..., 3 * L // 4:], axis=-1) if noise else np.zeros(scale.shape)
    plateau = np.where(plateau <= 16 * EPS * scale, plateau, 0.0)  # still decaying: no plateau yet
    T = np.where(cum_abs > 8.0 * plateau[..., None], cum_abs, 0.0)
    last, prev = T[..., -1], T[..., -9]
    with np.errstate(divide="ignore", invalid="ignore"):
        q = np.where(prev > 0, (last / prev) ** 0.125, 0.0)
    q = np.clip(np.nan_to_num(q), 0.0, 0.999)
    beyond = last * q / (1.0 - q)
    tail = np.cumsum(T[..., ::-1], axis=-1)[..., ::-1] + beyond[..., None]  # tail[K] = sum_{m>=K}
    tail = np.concatenate([tail, beyond[..., None]], axis=-1)              # tail[L]
    k = 2.0 * np.arange(L) + 1.0                                           # 2m+1
    Tw = T * k[None, None, :]
    tail_w = np.cumsum(Tw[..., ::-1], axis=-1)[..., ::-1]
    tail_w = np.concatenate([tail_w, np.zeros_like(beyond)[..., None]], axis=-1)
    tail_w += (beyond * (2 * L + 1))[..., None]  # crude but honest: beyond-window terms weighted by 2L+1

    # rounding, without which the estimate could claim 0: the plateau noise in each of K kept
    # coefficients (weight 1, or 2m+1 for p/sin(theta), added as a random walk), plus
    # summation rounding of K terms, eps sqrt(K) sum_{m<K} |D_m| (random-walk size)
    zero = np.zeros_like(beyond)[..., None]
    head = np.concatenate([zero, np.cumsum(cum_abs, axis=-1)], axis=-1)
    head_w = np.concatenate([zero, np.cumsum(cum_abs * k, axis=-1)], axis=-1)
    n = np.arange(L + 1)
    # (p also feels theta's own rounding through sin((2m+1) theta): eps sum (2m+1)|D_m|)
    floor = plateau[..., None] * n + EPS * (np.sqrt(n + 1) * head + head_w) + 4 * EPS * scale[..., None]
    floor_w = 2 * plateau[..., None] * n ** 1.5 + EPS * np.sqrt(n + 1) * head_w + 4 * EPS * scale[..., None]
    total, total_w = tail + floor, tail_w + floor_w                        # estimates for each K
    crit_tail, crit = (tail_w, total_w) if weighted else (tail, total)

    # the contract: |error| <= rtol * max(|value|, p*), p* = 1 here; converged <=> estimate <= rtol.
    # Truncation aims at rtol * min(p*, scale): narrow contacts (scale ~ a n < 1) keep rtol relative
    # to their own size for a few more Bessel terms; a contact far larger than p* is cut at rtol p*,
    # or flagged where the rounding floor (~ eps * scale) exceeds it.
    tol = (rtol * np.minimum(scale, 1.0))[..., None]
    window = slice(1, L - max(2, L // 8) + 1)  # keep part of the window beyond K as evidence
    found = (crit_tail[..., window] <= tol).any(axis=-1)  # truncation reached: a longer window won't help
    ok = crit[..., window] <= tol
    K = np.where(ok.any(axis=-1), 1 + np.argmax(ok, axis=-1),
                 np.where(found, 1 + np.argmin(crit[..., window], axis=-1), L))
    take = lambda arr: np.take_along_axis(arr, K[..., None], axis=-1)[..., 0]
    return dict(D=D, K=K, err=take(total), err_shape=take(total_w), converged=take(crit) <= rtol,
                scale=scale, done=found.all(axis=1) | window_full)


def build_table(a_values, N_values, delta_ratio, n, *, is_periodic, rtol, max_terms, weighted=False):
    """Coefficient table for every pair (a_values[ia], N_values[iN]).

    weighted=True truncates on the error of p/sin(theta) (terms weighted by 2m+1, the edge
    coefficient's sensitivity) instead of p: used by the validity test.
    Loops only over window sizes (powers of two), never over points.
    """
    if not rtol > 0:
        raise ValueError("rtol must be positive")
    if max_terms < 16:
        raise ValueError("max_terms must be >= 16")
    mod = _module(is_periodic)
    a_values = np.asarray(a_values, dtype=float)
    N_values = np.asarray(N_values, dtype=int)
    # each harmonic count alone: its window (from its own shortest wave) and its stopping rule
    # must not depend on which other counts are tabulated with it
    parts = [_build_one(a_values, int(N), delta_ratio, n, mod, rtol, max_terms, weighted) for N in N_values]
    UN = N_values.size
    K = np.stack([part["K"] for part in parts], axis=1).reshape(-1)       # row = ia * UN + iN
    D = np.zeros((a_values.size * UN, int(K.max())))
    for iN, part in enumerate(parts):
        for ia in range(a_values.size):
            k = part["K"][ia]
            D[ia * UN + iN, :k] = part["D"][ia][:k]
    cat = lambda key: np.stack([part[key] for part in parts], axis=1).reshape(-1)
    return SeriesTable(periodic=is_periodic, a=np.repeat(a_values, UN), N=np.tile(N_values, a_values.size),
                       D=D, K=K, err=cat("err"), err_shape=cat("err_shape"),
                       converged=cat("converged"), scale=cat("scale"))


def _build_one(a_values, N, delta_ratio, n, mod, rtol, max_terms, weighted):
    """Truncation of every contact angle for one harmonic count N (first N harmonics only).
    Loops only over window sizes (powers of two), never over points; each angle's window and
    result depend on that angle alone."""
    n_used = n[:N]
    w = 2.0 * delta_ratio[:N] * n_used
    L = np.minimum(_pow2(1.25 * mod.window_terms(a_values, np.max(n_used), rtol) + 8), _pow2(max_terms))
    results = [None] * a_values.size
    pending = np.arange(a_values.size)
    last_N = np.array([N])
    while pending.size:
        still = []
        for Lw in np.unique(L[pending]):
            idx = pending[L[pending] == Lw]
            C = mod.coefficients(a_values[idx], n_used, int(Lw))          # (k, N, Lw)
            r = _truncate(w[None, :, None] * C, last_N, rtol, Lw >= max_terms, mod.COEFFICIENT_NOISE, weighted)
            for j, ia in enumerate(idx):
                if r["done"][j]:
                    results[ia] = {key: val[j][0] for key, val in r.items() if key != "done"}
                else:
                    still.append(ia)
        pending = np.asarray(still, dtype=int)
        L[pending] = np.minimum(2 * L[pending], _pow2(max_terms))
    return {key: [res[key] for res in results] if key == "D" else np.array([res[key] for res in results])
            for key in ("D", "K", "err", "err_shape", "converged", "scale")}


def row_dot(M, v):
    """sum_j M[:, j] v[j], added column by column in order j = 0, 1, ...

    A matrix product or numpy's pairwise ``sum`` groups the terms by the shape of the whole array
    (BLAS kernels by the number of rows, pairwise sums by the row length), so a row's value would
    change in the last bits with its neighbours and a table's width; in column order each row is
    summed alone, and trailing zero columns leave it unchanged.
    """
    M = np.asarray(M, dtype=float)
    out = np.zeros(M.shape[:-1])
    for j in range(M.shape[-1]):
        out += M[..., j] * v[j]
    return out


def row_sum(M):
    """sum_j M[..., j] in column order (see ``row_dot``)."""
    M = np.asarray(M, dtype=float)
    out = np.zeros(M.shape[:-1])
    for j in range(M.shape[-1]):
        out += M[..., j]
    return out


def _series_sum(table, row, arg, K_el, terms):
    """sum_{m < K_el} D[row, m] terms(arg, k = 2m+1) per element, each element's terms added in order
    m = 0, 1, ... (``row_dot``): a point's value does not depend on which other points share the
    array.  Points are taken in chunks of ``_CHUNK_ROWS`` (sorted by decreasing K, so a chunk stops
    at its own longest series) and terms in blocks of ``_BLOCK_TERMS`` to bound memory."""
    shape = np.broadcast(row, arg).shape
    row, arg = (np.ravel(v) for v in np.broadcast_arrays(row, arg))
    K_el = np.broadcast_to(np.asarray(K_el), shape).ravel()
    order = np.argsort(-K_el, kind="stable")
    row_s, arg_s, K_s = row[order], np.asarray(arg, dtype=float)[order], K_el[order]
    width = table.D.shape[1]
    out = np.zeros(row_s.size)
    for i0 in range(0, row_s.size, _CHUNK_ROWS):
        r, x, Ks = row_s[i0:i0 + _CHUNK_ROWS], arg_s[i0:i0 + _CHUNK_ROWS], K_s[i0:i0 + _CHUNK_ROWS]
        acc = out[i0:i0 + _CHUNK_ROWS]
        for m0 in range(0, min(int(Ks[0]) if Ks.size else 0, width), _BLOCK_TERMS):
            n_act = int(np.searchsorted(-Ks, -m0, side="left"))   # elements with K > m0
            m = np.arange(m0, min(m0 + _BLOCK_TERMS, width))
            k = 2.0 * m + 1.0
            # terms m >= an element's own K are not added (power_sum cuts K per element; the table
            # holds zeros there otherwise): which terms count is the element's own affair
            # terms along the rows of T (one contiguous row per m: the additions below stream)
            T = terms(x[None, :n_act], k[:, None]) * table.D[r[None, :n_act], m[:, None]]
            T = np.where(m[:, None] < Ks[None, :n_act], T, 0.0)
            for j in range(m.size):
                acc[:n_act] += T[j]
    res = np.empty_like(out)
    res[order] = out
    return res.reshape(shape)


def sine_sum(table, row, theta, *, over_sin=False):
    """sum_m D[row, m] sin((2m+1) theta), or with each term divided by sin(theta)
    (= U_2m(cos theta), equal to 2m+1 at theta = 0).  theta in [0, pi/2]."""
    def terms(th, k):
        s = np.sin(th * k)
        if not over_sin:
            return s
        st = np.sin(th)
        return np.where(st > 0, s / np.where(st > 0, st, 1.0), k)

    return _series_sum(table, row, theta, table.K[np.asarray(row)], terms)


def power_sum(table, row, w):
    """sum_m D[row, m] w^(2m+1) for 0 <= w <= 1 (outside-contact slope, periodic)."""
    row, w = np.broadcast_arrays(np.asarray(row), np.asarray(w, dtype=float))
    # terms with w^(2m+1) < 1e-18 cannot matter (|D_m| <= sum_i |w_i|): skip them per element
    with np.errstate(divide="ignore"):
        m_need = np.where(w < 1.0, np.ceil(0.5 * (np.log(1e-18) / np.log(np.clip(w, 1e-300, 1.0 - 1e-16)) - 1.0)) + 1,
                          np.inf)
    K_el = np.minimum(table.K[row], np.maximum(m_need, 1)).astype(int)
    return _series_sum(table, row, w, K_el, lambda x, k: x ** k)


def _log_terms(e, k):
    km1 = np.where(k > 1, k - 1, 1.0)
    # expm1 keeps the O(eta^2) result accurate next to the edge (eta -> 0)
    G = 0.5 * (-np.expm1(-km1 * e) / km1 + np.expm1(-(k + 1) * e) / (k + 1))
    return np.where(k > 1, G, 0.5 * (e + 0.5 * np.expm1(-2.0 * e)))


def log_integral_sum(table, row, eta):
    """sum_m D[row, m] G_{2m+1}, G_k = int_1^t w^k dt = (1/2)[(1-w^(k-1))/(k-1) - (1-w^(k+1))/(k+1)],
    w = exp(-eta), t = cosh(eta) (non-periodic, outside the contact); G_1 = (eta - (1-w^2)/2)/2."""
    return _series_sum(table, row, eta, table.K[np.asarray(row)], _log_terms)
