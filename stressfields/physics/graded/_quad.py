"""Private tanh–sinh (double-exponential) quadrature on [0, 1] for the graded kernels.

Why tanh–sinh: the MDR integrals of the graded half-space have algebraic end-point
singularities whose exponents depend on k, and k is swept as an array.  Gauss–Jacobi would need
one rule per distinct k; tanh–sinh uses one set of nodes for every k and converges exponentially
for end-point singularities of any strength.  The rule returns each node together with its exact
distance to the right end point (``tc = 1 - t`` computed without cancellation), which the
callers use to evaluate kernels such as (x - r)^(-(1-k)/2) without rounding the distance
(docs/theory/graded.md (G42), the edge r -> a).  Strong singularities (exponent close to -1) are first
removed by a power substitution (see :func:`power_map`).

The shared ``stressfields/physics/quadrature.py`` is owned elsewhere; this module is private to
``graded`` on purpose.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np

#: Half-width of the truncated s-range. At s = 3.6 the nodes are 1e-24 from the end points;
#: after the power substitutions every integrand is bounded, so the neglected tails are below
#: double precision.
S_MAX = 3.6


class QuadratureError(ArithmeticError):
    """The quadrature did not reach the requested tolerance."""


@lru_cache(maxsize=None)
def _nodes(level: int, odd_only: bool):
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
    """Integral over [0, 1] of ``func(t, tc)`` (``tc = 1 - t``), nodes on the last axis.

    ``func`` receives two 1-D arrays of nodes and must return an array whose last axis runs over
    them (any leading shape, broadcasting).  The step is halved (re-using the previous nodes)
    until two successive results agree to ``rtol`` (relative) or ``atol`` (absolute) at every
    point; since tanh–sinh doubles the number of correct digits per halving, the returned value
    is then far more accurate than ``rtol``.  Raises :class:`QuadratureError` otherwise.
    """
    t, tc, w = _nodes(level, False)
    val = np.sum(func(t, tc) * w, axis=-1)
    for lev in range(level + 1, max_level + 1):
        t, tc, w = _nodes(lev, True)
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
