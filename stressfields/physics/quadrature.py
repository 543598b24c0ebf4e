"""Shared quadrature rules for the 1-D integrals of the physics kernels.

Everything here is vectorised over field points: a rule is a set of nodes per point (an array of
shape ``(points, nodes)``) and the integral is a weighted sum along the last axis.  Nodes and
weights are cached per order; the arrays are read-only.

Rules
-----
* Gauss–Legendre on [0, 1] (``gauss_legendre``).
* Gauss–Jacobi on [0, 1] with weight ``t**beta`` (``gauss_jacobi``): for integrands that behave
  like a non-integer power at the origin (power-law profiles), which Gauss–Legendre integrates only
  algebraically.
* Composite Gauss–Legendre on equal panels (``panel_rule``): for the substitution ``u = r cosh t``
  whose interval ``[0, arccosh(a/r)]`` grows like ``ln(2a/r)`` as ``r -> 0``; a fixed panel length
  keeps the per-panel error fixed, so only the number of panels grows (logarithmically).
* Adaptive tanh–sinh on [0, 1] (``integrate``, with ``power_map`` for strong end-point
  singularities): for the graded MDR integrals, whose end-point exponents depend on the grading
  exponent k swept as an array — one node set serves every k, where Gauss–Jacobi would need a
  rule per k.

``orders(rtol)`` returns the node counts that reach a requested relative tolerance; the table was
measured by doubling (see ``tests/physics/test_axisymmetric_quadrature.py``, which re-checks it).
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy.special import roots_jacobi, roots_legendre

__all__ = ["Orders", "orders", "tolerance_of", "table_row", "gauss_legendre", "gauss_jacobi", "panel_count",
           "panel_rule", "interval_rule", "segment_rule", "group_by"]


@functools.lru_cache(maxsize=None)
def gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre nodes and weights of order ``n`` on [0, 1] (exact for degree 2n-1)."""
    x, w = roots_legendre(int(n))
    t, wt = 0.5 * (x + 1.0), 0.5 * w
    t.setflags(write=False)
    wt.setflags(write=False)
    return t, wt


@functools.lru_cache(maxsize=None)
def gauss_jacobi(n: int, beta: float) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights on [0, 1] for ``int_0^1 t**beta F(t) dt`` (beta > -1), exact for
    polynomial F of degree 2n-1."""
    if not beta > -1.0:
        raise ValueError(f"Gauss-Jacobi weight exponent must be > -1, got {beta!r}")
    # scipy's weight is (1-x)^alpha (1+x)^beta on [-1, 1]; t = (1+x)/2 gives (2t)^beta, dx = 2 dt
    x, w = roots_jacobi(int(n), 0.0, float(beta))
    t, wt = 0.5 * (x + 1.0), w / 2.0 ** (beta + 1.0)
    t.setflags(write=False)
    wt.setflags(write=False)
    return t, wt


@dataclass(frozen=True)
class Orders:
    """Node counts for one tolerance.

    n_tau, h_tau: Gauss–Legendre order per panel and panel length for the ``u = r cosh t``
    integrals; n_theta: order of the single-panel rules of the ``u = r sin t`` integrals;
    n_jacobi: order of the Gauss–Jacobi rules (power-law profiles, integrals from the origin).
    """

    n_tau: int
    h_tau: float
    n_theta: int
    n_jacobi: int


# rtol -> orders.  Measured against the 1e-14 row for cone, paraboloid, power laws n = 0.3 ... 50 and
# tabulated splines over r/a in [1e-8, 100]; worst deviations per row: 2.4e-7, 3.5e-9, 7.8e-11,
# 5.4e-12, 1.8e-12 (test_axisymmetric_quadrature.py re-measures a subset with a margin of 10).  The
# panel length 1.5 keeps the exp(m t) growth of g'(r cosh t) ~ (r cosh t)^m resolvable at low order
# for m <= 4; steeper power laws get shorter panels (axisymmetric.integrals._panel_length).
_TABLE = (
    (1e-4, Orders(n_tau=6, h_tau=1.5, n_theta=8, n_jacobi=8)),
    (1e-6, Orders(n_tau=8, h_tau=1.5, n_theta=10, n_jacobi=10)),
    (1e-8, Orders(n_tau=10, h_tau=1.5, n_theta=12, n_jacobi=12)),
    (1e-10, Orders(n_tau=12, h_tau=1.5, n_theta=16, n_jacobi=16)),
    (1e-12, Orders(n_tau=14, h_tau=1.5, n_theta=20, n_jacobi=20)),
    (1e-14, Orders(n_tau=18, h_tau=1.25, n_theta=24, n_jacobi=24)),
)

MIN_RTOL = _TABLE[-1][0]


def orders(rtol: float) -> Orders:
    """The cheapest tabulated orders whose measured accuracy is at least ``rtol``."""
    rtol = float(rtol)
    if not (math.isfinite(rtol) and rtol > 0.0):
        raise ValueError(f"rtol must be a positive finite number, got {rtol!r}")
    if rtol < MIN_RTOL:
        raise ValueError(f"rtol = {rtol!r} is below the reachable {MIN_RTOL:g} in double precision")
    for tol, o in _TABLE:
        if rtol >= tol:
            return o
    return _TABLE[-1][1]  # pragma: no cover - guarded above


def tolerance_of(ords: Orders) -> float:
    """The tolerance of the row of ``orders`` whose orders are ``ords`` (the last, finest row's for
    orders not in the table): the accuracy a caller that builds further rules on them must reach."""
    return next((tol for tol, o in _TABLE if o == ords), _TABLE[-1][0])


def table_row(table, rtol: float, what: str = "the quadrature"):
    """The row of ``table`` ((tolerance, orders) pairs, tolerances falling) for ``rtol``: the first whose
    measured tolerance is at most rtol; ValueError for a non-positive rtol or one below the last row."""
    rtol = float(rtol)
    if not (math.isfinite(rtol) and rtol > 0.0):
        raise ValueError(f"rtol = {rtol!r} must be a positive finite number")
    if rtol < table[-1][0]:
        raise ValueError(f"rtol = {rtol!r} is below the reachable {table[-1][0]:g} of {what}")
    return next(o for tol, o in table if rtol >= tol)


def panel_count(lo: np.ndarray, hi: np.ndarray, h: float) -> np.ndarray:
    """Number of equal panels of length <= h covering [lo, hi] (at least one)."""
    with np.errstate(invalid="ignore"):
        n = np.ceil((hi - lo) / h)
    return np.maximum(np.nan_to_num(n, nan=1.0, posinf=1.0), 1.0).astype(np.int64)


def panel_rule(lo: np.ndarray, hi: np.ndarray, panels: int, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Composite Gauss–Legendre nodes/weights on [lo, hi] per point: ``panels`` equal panels of
    ``n`` nodes.  lo, hi: shape (k,); returns two arrays of shape (k, panels*n)."""
    t, w = gauss_legendre(n)
    if panels > 1:
        t = (np.arange(panels)[:, None] + t[None, :]).ravel() / panels
        w = np.tile(w, panels) / panels
    length = (hi - lo)[:, None]
    return lo[:, None] + length * t[None, :], length * w[None, :]


def interval_rule(lo: np.ndarray, hi: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Single-panel Gauss–Legendre nodes/weights on [lo, hi] per point, shape (k, n)."""
    return panel_rule(lo, hi, 1, n)


@functools.lru_cache(maxsize=None)
def _graded(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre in w with t = w^2 on [0, 1]: nodes t and weights 2 w W."""
    w, W = gauss_legendre(n)
    t, wt = w * w, 2.0 * w * W
    t.setflags(write=False)
    wt.setflags(write=False)
    return t, wt


def segment_rule(points: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Composite rule over the segments between consecutive columns of ``points`` (shape (k, m+1),
    non-decreasing along axis 1; zero-length segments contribute nothing).  Each segment uses
    Gauss–Legendre after t = left + length * w^2, which turns a (t - left)^(j + 1/2) singularity at
    the segment's left end (the cusp that a spline knot leaves in the Abel transform) into a
    polynomial.  Returns nodes and weights of shape (k, m*n)."""
    t, w = _graded(n)
    left = points[:, :-1, None]
    length = np.diff(points, axis=1)[:, :, None]
    k = points.shape[0]
    return (left + length * t).reshape(k, -1), (length * w).reshape(k, -1)


def group_by(keys: np.ndarray):
    """Yield ``(key, index_array)`` for each distinct key; used to evaluate points that need the
    same number of panels together (a loop over a handful of panel counts, not over points)."""
    keys = np.asarray(keys)
    if keys.size == 0:
        return
    uniq = np.unique(keys)
    if uniq.size == 1:
        yield uniq[0], np.arange(keys.size)
        return
    order = np.argsort(keys, kind="stable")
    sorted_keys = keys[order]
    bounds = np.searchsorted(sorted_keys, uniq, side="left").tolist() + [keys.size]
    for i, k in enumerate(uniq):
        yield k, order[bounds[i]:bounds[i + 1]]


# ---------------------------------------------------------------------------------------------
# Tanh–sinh (double-exponential) quadrature on [0, 1]: the graded family's MDR integrals
# ---------------------------------------------------------------------------------------------
#
# Why tanh–sinh: the MDR integrals of the graded half-space have algebraic end-point singularities
# whose exponents depend on k, and k is swept as an array.  Gauss–Jacobi would need one rule per
# distinct k; tanh–sinh uses one set of nodes for every k and converges exponentially for end-point
# singularities of any strength.  The rule returns each node together with its exact distance to
# the right end point (``tc = 1 - t`` computed without cancellation), which the callers use to
# evaluate kernels such as (x - r)^(-(1-k)/2) without rounding the distance
# (docs/theory/graded.md (G42), the edge r -> a).  Strong singularities (exponent close to -1) are
# first removed by a power substitution (see :func:`power_map`).

__all__ += ["QuadratureError", "integrate", "power_map"]

#: Half-width of the truncated s-range. At s = 3.6 the nodes are 1e-24 from the end points;
#: after the power substitutions every integrand is bounded, so the neglected tails are below
#: double precision.
S_MAX = 3.6


class QuadratureError(ArithmeticError):
    """The quadrature did not reach the requested tolerance."""


@functools.lru_cache(maxsize=None)
def _tanh_sinh_nodes(level: int, odd_only: bool):
    h = 2.0 ** -level
    m = int(np.ceil(S_MAX / h))
    j = np.arange(-m, m + 1)
    if odd_only:
        j = j[j % 2 != 0]
    s = h * j
    u = 0.5 * np.pi * np.sinh(s)
    t = 1.0 / (1.0 + np.exp(-2.0 * u))
    tc = 1.0 / (1.0 + np.exp(2.0 * u))           # exact 1 - t, no cancellation near t = 1
    w = h * 0.25 * np.pi * np.cosh(s) / np.cosh(u) ** 2   # dt/ds = sech^2(u) (pi/2) cosh(s) / 2
    for a in (t, tc, w):
        a.setflags(write=False)
    return t, tc, w


def integrate(func, *, rtol: float = 1e-10, atol: float = 0.0, level: int = 3, max_level: int = 8):
    """Integral over [0, 1] of ``func(t, tc)`` (``tc = 1 - t``) by tanh–sinh, nodes on the last axis.

    ``func`` receives two 1-D arrays of nodes and must return an array whose last axis runs over
    them (any leading shape, broadcasting).  The step is halved (re-using the previous nodes)
    until two successive results agree to ``rtol`` (relative) or ``atol`` (absolute) at every
    point; since tanh–sinh doubles the number of correct digits per halving, the returned value
    is then far more accurate than ``rtol``.  Raises :class:`QuadratureError` otherwise.
    """
    t, tc, w = _tanh_sinh_nodes(level, False)
    val = np.sum(func(t, tc) * w, axis=-1)
    for lev in range(level + 1, max_level + 1):
        t, tc, w = _tanh_sinh_nodes(lev, True)
        new = 0.5 * val + np.sum(func(t, tc) * w, axis=-1)
        err = np.abs(new - val)
        val = new
        # the 1e-280 floor keeps values that underflow towards denormals from blocking convergence
        if np.all((err <= rtol * np.abs(val)) | (err <= max(atol, 1e-280))):
            return val
    worst = np.max(err / np.maximum(np.abs(val), np.finfo(float).tiny))
    raise QuadratureError(f"tanh-sinh quadrature did not converge to rtol={rtol:g} "
                          f"(relative change {worst:.3g} at level {max_level})")


def power_map(v, vc, p):
    """Substitution 1 - t = v**p that removes an end-point factor (1 - t)**(1/p - 1).

    Returns ``(t, 1 - t)`` with both computed without cancellation; the Jacobian of
    ``int_0^1 (1-t)**(1/p-1) phi(t) dt = p int_0^1 phi(t(v)) dv`` is the constant ``p``.
    ``v``/``vc`` are tanh–sinh nodes and their complements; ``p`` broadcasts against them.
    """
    one_minus_t = v ** p                         # accurate where v is small (t -> 1)
    log_v = np.where(vc < 0.5, np.log1p(-np.minimum(vc, 0.5)), np.log(v))   # log v without rounding
    t = -np.expm1(p * log_v)                     # accurate where vc is small (t -> 0)
    return t, one_minus_t
