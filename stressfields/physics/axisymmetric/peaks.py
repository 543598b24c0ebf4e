"""Where the maxima sit: the peak of tau_max and of von Mises over the half-space z >= 0, and its
position (r along the load axis y = 0, depth z), for one case or, by a loop, for many.

The fields are those of ``fields.fields`` (docs/theory/interior.md (I5)-(I35) below the surface,
docs/theory/axisymmetric.md (A14)-(A59) on it; von Mises (A60), tau_max = (sigma_1 - sigma_3)/2 from
the principal stresses (A61)).  Pure NumPy/SciPy.

The search (one rule for every profile):

1. Surface singular points.  The points where a field of the family may be unbounded lie on the
   surface z = 0: the axis r = 0 (cone tip, power laws n <= 1, a tabulated spline whose slope at
   r = 0 is not 0: a conical tip), the contact edge r = a (flat punch) and, under tangential load,
   the stick edge r = c.  They are probed first; where tau_max (or von
   Mises) is +inf at one of them the supremum is +inf: the peak is +inf at that point (depth 0) and
   the flag says ``UNBOUNDED`` (a NaN there, a limit that depends on the direction, gives NaN and
   ``UNDEFINED``).  The search never goes near a singular point: it only runs when there is none.
2. A coarse grid brackets the maximum: y = 0, x in [0, 2a] under normal load (the field is
   axisymmetric: r = x >= 0), x in [-2a, 2a] under tangential load (the field is even in y, not in
   x), depth z = 0 and 40 depths geometric from 1e-3 a to 3a (the peaks of the family sit between
   the surface and ~0.8 a; the geometric spacing resolves shallow peaks next to the edges).
3. Each of the three best grid local maxima is refined by a bounded Nelder-Mead search in (x, z)
   to xatol = 1e-9 a (and a function tolerance of 1e-14 of the peak); the best wins.  The surface
   z >= 0 is part of the search domain, because without a singular point the fields are bounded and
   continuous up to z = 0 (the surface kernels are the limit z -> 0+).
4. The surface points x = 0, +-c, +-a, where a surface field can have a kink (Hertz-Mindlin: a
   square-root edge) that a simplex locates only to ~sqrt(xatol), are candidates themselves.
5. A refined maximum on the outer boundary of the search box (|x| = 2a or z = 3a), or a Nelder-Mead
   search that did not converge, gives ``NOT_CONVERGED``: the value is then the best found, not the
   peak.

Accuracy: the peak value is the field at the refined point, so its error is that of the field
(closed forms: relative error at most 1e-12 of |value|; quadrature: |error| <= rtol * max(|value|,
p_m)) plus the search error, which at a smooth maximum is second order in the position error: the
refinement stops when its simplex spans less than 1e-9 a and its values differ by less than 1e-14
of the peak.  The positions are accurate to about 1e-7 a (a smooth maximum fixes its position only
to the square root of the function tolerance).  Measured on Hertz, nu = 0.3, against a bounded 1-D
search on Johnson's axis formulas: tau_max peak 0.31002050195452147 p0 equal to the last digit,
depth 0.480864485 a to 7e-9 a; one search takes 0.1-0.4 s (closed forms) and up to ~1.4 s (1-D
quadrature under tangential load) on one core.
"""
from __future__ import annotations

import numpy as np

from ..flags import Validity
from .fields import fields
from .profiles import Profile
from .surface import stick_radius

__all__ = ["PEAKS", "FINITE", "UNBOUNDED", "UNDEFINED", "NOT_CONVERGED", "peaks"]

#: the keys of ``peaks``
PEAKS = ("tau_max_peak", "tau_max_peak_r", "tau_max_peak_depth",
         "von_mises_peak", "von_mises_peak_r", "von_mises_peak_depth", "peak_validity")
#: peak_validity codes, from the product's table (physics.flags)
FINITE, UNBOUNDED, UNDEFINED, NOT_CONVERGED = (Validity.within_stated_accuracy, Validity.unbounded_at_singular_point,
                                               Validity.undefined_direction_dependent_limit,
                                               Validity.search_not_converged)
_INVARIANTS = ("tau_max", "von_mises")
#: the search box in units of a: every peak of the family lies well inside it
_X_MAX, _Z_MAX = 2.0, 3.0
_XATOL, _FATOL = 1e-9, 1e-14
_CANDIDATES = 3


def peaks(profile: Profile, *, a, nu, mu, ux0, method: str = "auto", rtol: float = 1e-10) -> dict:
    """The peaks of tau_max and von Mises (per E*, like ``fields``) and their positions (x on the
    load axis y = 0, depth z; lengths in the profile's unit), for every case of the broadcast
    ``a, nu, mu, ux0`` (a loop over the cases), and ``peak_validity`` (int8: ``FINITE``,
    ``UNBOUNDED``, ``UNDEFINED``, ``NOT_CONVERGED``); the search rule is the module docstring's."""
    arrays = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (a, nu, mu, ux0)))
    shape = arrays[0].shape
    out = {k: np.empty(shape, dtype=np.int8 if k == "peak_validity" else float) for k in PEAKS}
    for idx in np.ndindex(shape):
        one = _one(profile, *(float(v[idx]) for v in arrays), method, rtol)
        for k in PEAKS:
            out[k][idx] = one[k]
    return out


def _one(profile, a, nu, mu, ux0, method, rtol) -> dict:
    """The peaks of one case (scalars)."""
    tangential = mu > 0.0 and ux0 > 0.0
    c = float(stick_radius(a, nu, mu, ux0, profile)) if tangential else a

    def field(name, x, z):
        values, _ = fields([name], profile, x, 0.0, z, a=a, nu=nu, mu=mu, ux0=ux0, method=method, rtol=rtol)
        return values[name]

    edges = sorted({0.0, a, c} | ({-a, -c} if tangential else set()))
    edges = [e for e in edges if e == 0.0 or 0.0 < abs(e) <= a]
    out, flag = {}, FINITE
    for name in _INVARIANTS:
        value, x, z, code = _peak(lambda u, w: field(name, u * a, w * a), np.array(edges) / a, tangential)
        out.update({f"{name}_peak": value, f"{name}_peak_r": x * a, f"{name}_peak_depth": z * a})
        flag = max(flag, code)
    out["peak_validity"] = flag
    return out


def _peak(f, edges, tangential):
    """(value, x/a, z/a, code) of the maximum of f(x/a, z/a) over the search box."""
    at_edges = f(edges, 0.0)
    if np.any(np.isposinf(at_edges)):
        return np.inf, edges[np.argmax(np.isposinf(at_edges))], 0.0, UNBOUNDED
    if np.any(np.isnan(at_edges)):
        return np.nan, edges[np.argmax(np.isnan(at_edges))], 0.0, UNDEFINED
    lo = -_X_MAX if tangential else 0.0
    xs = np.linspace(lo, _X_MAX, 81 if tangential else 41)
    zs = np.concatenate([[0.0], np.geomspace(1e-3, _Z_MAX, 40)])
    grid = f(xs[None, :], zs[:, None])
    best = (float(np.max(at_edges)), float(edges[np.argmax(at_edges)]), 0.0, FINITE)
    scale = max(float(np.max(grid)), best[0])
    for i, j in _local_maxima(grid)[:_CANDIDATES]:
        found = _refine(f, xs, zs, i, j, lo, scale)
        if found[0] > best[0]:
            best = found
    return best


def _local_maxima(grid) -> list[tuple[int, int]]:
    """Indices of the grid's local maxima (>= every neighbour), largest first."""
    padded = np.pad(grid, 1, constant_values=-np.inf)
    rows, cols = grid.shape
    neighbours = [padded[1 + di:1 + di + rows, 1 + dj:1 + dj + cols]
                  for di in (-1, 0, 1) for dj in (-1, 0, 1) if di or dj]
    peak = np.all([grid >= n for n in neighbours], axis=0)
    idx = np.argwhere(peak)
    return [tuple(k) for k in idx[np.argsort(-grid[peak], kind="stable")]]


def _refine(f, xs, zs, i, j, lo, scale):
    """Bounded Nelder-Mead from grid point (zs[i], xs[j]), starting simplex one grid step wide."""
    x0, z0 = xs[j], zs[i]
    dx = xs[1] - xs[0]
    dz = max(zs[min(i + 1, len(zs) - 1)] - z0, 1e-3)
    simplex = np.array([[x0, z0], [min(x0 + dx, _X_MAX), z0], [x0, min(z0 + dz, _Z_MAX)]])
    if x0 + dx > _X_MAX:
        simplex[1, 0] = x0 - dx
    from scipy.optimize import minimize     # here: its import (0.1 s) only when peaks are asked for

    res = minimize(lambda v: -float(f(v[0], v[1])) / scale, simplex[0], method="Nelder-Mead",
                   bounds=[(lo, _X_MAX), (0.0, _Z_MAX)],
                   options=dict(initial_simplex=simplex, xatol=_XATOL, fatol=_FATOL, maxiter=4000, maxfev=8000))
    x, z = (float(v) for v in res.x)
    on_box = abs(x) >= _X_MAX * (1 - 1e-9) or z >= _Z_MAX * (1 - 1e-9)
    code = NOT_CONVERGED if (not res.success or on_box) else FINITE
    return float(f(x, z)), x, z, code
