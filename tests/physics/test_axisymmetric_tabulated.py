"""The tabulated (cubic spline) profile on the integral route, near its knots.

The Abel transform of a spline has cusps at the knots (g'' ~ sqrt(u - k) just right of a knot k),
so the pressure gradient dp/dz, which integrates g'', is where a quadrature rule that misses a
nearby cusp shows first: a knot just below r or c (or, for u = r cosh t, just above r) used to cost
the rules their order (errors ~1e-10 at rtol 1e-12).  Here the contract
|error| <= rtol * max(p_m / a, |value|) is checked for rtol 1e-4 ... 1e-12 at points on and next to
knots, in the stick zone, the slip annulus, near the contact edge and outside, against routes that
share nothing with the implementation's rules:

* the normal part inside the contact from the local identity dp/dz = ((1+nu)/3) Laplacian(u_z)
  (docs/theory/axisymmetric.md (A31)) with u_z = delta - f: -((1+nu)/3) (f'' + f'/r) of the spline itself, no MDR;
* eq. (11) outside (by-parts form, both branches) and eq. (26) for the tangential part, as written
  in docs/theory/axisymmetric.md (A53)-(A54) (u g''(u) / sqrt(u^2 - r^2), not the implementation's psi
  form (A87)-(A88)), by adaptive scipy
  quad after u = r -+ v^2 (which removes the end-point root), split at every knot;
* g' and g'' themselves from scipy quad of the spline, g'(x) = int_0^(pi/2) [f'(x s) + x s f''(x s)]
  dphi, s = sin(phi), split where x s crosses a knot (eq. 12 differentiated under the integral).
"""
import functools
import math
import warnings

import numpy as np
import pytest
from scipy.integrate import IntegrationWarning, quad
from scipy.interpolate import CubicSpline

from stressfields.physics import axisymmetric as ax

RTOLS = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)
QUAD = dict(limit=200, epsabs=0.0, epsrel=1e-13)
NU, MU, PHI = 0.3, 0.4, 0.4

# the benchmark's profile: 25 samples of a blunted cone (knots every 0.05)
RS = np.linspace(0.0, 1.2, 25)
FS = np.sqrt(RS ** 2 + 0.04) - 0.2
# a geometric grid (knot spacing from 0.01 to 0.3) and a table that does not start at r = 0
RG = np.concatenate([[0.0], np.geomspace(1e-2, 1.5, 20)])
FG = np.sqrt(RG ** 2 + 0.01) - 0.1
R0 = np.linspace(0.3, 2.0, 12)
F0 = R0 ** 2.5


def _spline(r, f):
    return CubicSpline(r, f - f[0])


def _g(prof, u, which):
    """g' (which=1) or g'' (2) of the profile by its exact Abel sums (the reference integrands)."""
    return float(prof._sums(u, which))


def _pieces(f, lo, hi, breaks):
    edges = [lo] + sorted(b for b in set(breaks) if lo < b < hi) + [hi]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)   # round-off notes at 1e-13
        return sum(quad(f, p, q, **QUAD)[0] for p, q in zip(edges[:-1], edges[1:]))


def _normal(prof, r, a, nu):
    """Eq. (11), both branches: C [H(r-a) g'(a)/sqrt(r^2-a^2) - g'(0)/r - int_0^min(r,a) g''(u) du /
    sqrt(r^2-u^2)], u = r - v^2."""
    h = min(r, a)

    def f(v):
        u = r - v * v
        return 2.0 * _g(prof, u, 2) / math.sqrt(r + u)

    integral = _pieces(f, math.sqrt(r - h), math.sqrt(r), [math.sqrt(r - k) for k in prof.r if 0.0 < k < h])
    out = -_g(prof, 0.0, 1) / r - integral
    if r > a:
        out += _g(prof, a, 1) / math.sqrt((r - a) * (r + a))
    return 2.0 * (1.0 + nu) / (3.0 * math.pi) * out


def _tangential(prof, x, r, a, c, nu, mu):
    """Eq. (26): -C_T x/r^2 [a g'(a)/sqrt(a^2-r^2) - (r < c) c g'(c)/sqrt(c^2-r^2)
    - int_max(r,c)^a u g''(u) du / sqrt(u^2-r^2)], u = r + v^2; 0 outside."""
    if r >= a:
        return 0.0
    lo = max(r, c)

    def f(v):
        u = r + v * v
        return 2.0 * u * _g(prof, u, 2) / math.sqrt(u + r)

    integral = _pieces(f, math.sqrt(lo - r), math.sqrt(a - r), [math.sqrt(k - r) for k in prof.r if lo < k < a])
    bracket = a * _g(prof, a, 1) / math.sqrt((a - r) * (a + r)) - integral
    if r < c:
        bracket -= c * _g(prof, c, 1) / math.sqrt((c - r) * (c + r))
    return -2.0 * (1.0 + nu) * mu / (3.0 * math.pi) * x / r ** 2 * bracket


def _local_normal(spline, r, nu):
    """Normal dp/dz inside the contact: ((1+nu)/3) Laplacian(delta - f) = -((1+nu)/3)(f'' + f'/r)."""
    return -(1.0 + nu) / 3.0 * (float(spline(r, 2)) + float(spline(r, 1)) / r)


# (name, table, a, c or None for the stick radius of u_x0/delta = 0.25, radii)
CASES = {
    # partial slip as in the benchmark (c/a = 0.546): on, just below and just above knots in the stick
    # zone and the slip annulus, next to c, next to the edge, outside
    "bench": ((RS, FS), 1.0, None,
              [0.3 + 1e-6, 0.45 - 1e-8, 0.5, 0.55 + 1e-5, 0.6 - 1e-7, 0.6, 0.6001, 0.65 + 1e-9, 0.8 + 1e-5,
               0.999, 1.0 - 1e-6, 1.0 + 1e-6, 1.05 + 1e-7, 1.3, 2.5]),
    # the stick radius just above a knot and the contact edge on one
    "c_near_knot": ((RS, FS), 0.95, 0.55 + 1e-7,
                    [0.3, 0.5 + 1e-6, 0.55 - 1e-6, 0.55 + 2e-7, 0.6 + 1e-6, 0.9 + 1e-5, 0.95 * (1 - 1e-6), 1.2]),
    # gross slip on a geometric grid
    "geometric_gross_slip": ((RG, FG), 1.0, 0.0,
                             [RG[9] + 1e-7, RG[12] + 1e-5, RG[14], RG[15] - 1e-7, RG[16] + 1e-5, 0.999, 1.001, 1.4]),
    # a table starting at r = 0.3 (its first piece continued to the axis), partial slip
    "offset_table": ((R0, F0), 1.0, None, [R0[1] + 1e-5, R0[2] - 1e-7, R0[3] + 1e-9, R0[4], 1.3]),
}


@functools.lru_cache(maxsize=None)
def _case(name):
    (rt, ft), a, c, radii = CASES[name]
    prof = ax.tabulated(rt, ft)
    if c is None:
        c = float(ax.stick_radius(a, NU, MU, 0.25, prof))
    r = np.array(radii)
    x, y = r * math.cos(PHI), r * math.sin(PHI)
    r = np.hypot(x, y)          # the implementation's r: near the edges the value is ill-conditioned in r
    ref = np.array([_normal(prof, ri, a, NU) + _tangential(prof, xi, ri, a, c, NU, MU) for ri, xi in zip(r, x)])
    return prof, a, c, x, y, ref


@pytest.mark.slow   # dense references near every knot, ~25 s
@pytest.mark.parametrize("name", list(CASES))
def test_dpdz_meets_rtol_near_knots(name):
    prof, a, c, x, y, ref = _case(name)
    scale = float(ax.mean_pressure(a, prof)) / a
    for rtol in RTOLS:
        got = ax.surface_dpdz(x, y, a, c, NU, MU, prof, method="quadrature", rtol=rtol)
        err = np.abs(got - ref) / np.maximum(scale, np.abs(ref))
        assert err.max() <= rtol, (name, rtol, float(np.hypot(x, y)[np.argmax(err)]), err.max())


def test_normal_dpdz_inside_is_the_local_laplacian():
    """No MDR at all: inside the contact the normal dp/dz is -((1+nu)/3)(f'' + f'/r) of the spline,
    on, beside and between knots."""
    prof, spline = ax.tabulated(RS, FS), _spline(RS, FS)
    a = 1.0
    scale = float(ax.mean_pressure(a, prof)) / a
    r = np.concatenate([RS[1:20] + d for d in (-1e-7, 0.0, 1e-9, 1e-5, 0.02)] + [[0.01, 0.999999]])
    ref = np.array([_local_normal(spline, ri, NU) for ri in r])
    for rtol in RTOLS:
        got = ax.surface_dpdz(r, 0.0, a, a, NU, 0.0, prof, method="quadrature", rtol=rtol)
        err = np.abs(got - ref) / np.maximum(scale, np.abs(ref))
        assert err.max() <= rtol, (rtol, r[np.argmax(err)], err.max())


@pytest.mark.parametrize("table", [(RS, FS), (RG, FG), (R0, F0)], ids=["uniform", "geometric", "offset"])
def test_abel_derivatives_against_quadrature_of_the_spline(table):
    """g' and g'' (the piecewise-polynomial table the quadrature evaluates, and the exact Abel sums it
    is built from) against scipy quad of the differentiated eq. (12), on, beside and between knots."""
    rt, ft = table
    prof, sp = ax.tabulated(rt, ft), _spline(rt, ft)
    knots = prof._knots[1:-1]
    x = np.concatenate([np.linspace(1e-3, rt[-1], 37), knots, knots + 1e-9, knots - 1e-9, knots + 1e-4])
    integrands = {1: lambda t, xv: sp(xv * math.sin(t), 1) + xv * math.sin(t) * sp(xv * math.sin(t), 2),
                  2: lambda t, xv: (2.0 * math.sin(t) * sp(xv * math.sin(t), 2)
                                    + xv * math.sin(t) ** 2 * sp(xv * math.sin(t), 3))}
    ref = {q: np.array([_pieces(lambda t: float(f(t, xv)), 0.0, 0.5 * math.pi,
                                [math.asin(k / xv) for k in rt if 0.0 < k < xv]) for xv in x])
           for q, f in integrands.items()}
    s1 = np.max(np.abs(ref[1]))
    scale = {1: s1, 2: max(np.max(np.abs(ref[2])), s1 / rt[-1])}
    eps = np.finfo(float).eps
    for q, fast in ((1, prof.dg), (2, prof.d2g)):
        exact = prof._sums(x, q)
        table_err = np.abs(fast(x) - exact) / scale[q]
        assert table_err.max() <= 16 * eps, (q, x[np.argmax(table_err)], table_err.max())
        quad_err = np.abs(fast(x) - ref[q]) / scale[q]
        assert quad_err.max() <= 1e-13, (q, x[np.argmax(quad_err)], quad_err.max())
    # the axis: the first piece is kept exact, g'(0) = (pi/2) f'(0) and g''(0) = 2 f''(0)
    assert float(prof.dg(0.0)) == float(prof._sums(0.0, 1))
    assert float(prof.d2g(0.0)) == float(prof._sums(0.0, 2))


@pytest.mark.slow   # dense references near every knot, ~25 s
@pytest.mark.parametrize("ux0", [0.0, 0.25], ids=["normal", "partial_slip"])
def test_dpdz_within_relative_1e12_of_knots(ux0):
    """|error| <= rtol max(|value|, p_m/a) at rtol 1e-8 ... 1e-12 for points 1e-6 and 1e-12 (relative)
    on either side of knots in the stick zone, the slip annulus and outside.  (A reference that
    integrates eq. (11) in u itself, with the knot and the root u = r as break points 1e-7 apart,
    is off by 2.6e-4 of p_m/a at r = 0.3 (1 + 1e-6): QUADPACK's extrapolation fails next to the root; the u = r -+ v^2
    references above agree with the kernels to 3e-16.)"""
    prof = ax.tabulated(RS, FS)
    a = 1.0
    c = a if ux0 == 0.0 else float(ax.stick_radius(a, NU, MU, ux0, prof))
    mu = MU if ux0 else 0.0
    r = np.array([k * (1.0 + s * d) for k in (0.3, 0.8, 1.05) for d in (1e-6, 1e-12) for s in (-1.0, 1.0)])
    x, y = r * math.cos(PHI), r * math.sin(PHI)
    r = np.hypot(x, y)
    ref = np.array([_normal(prof, ri, a, NU) + (_tangential(prof, xi, ri, a, c, NU, mu) if ux0 else 0.0)
                    for ri, xi in zip(r, x)])
    scale = float(ax.mean_pressure(a, prof)) / a
    for rtol in (1e-8, 1e-10, 1e-12):
        got = ax.surface_dpdz(x, y, a, c, NU, mu, prof, method="quadrature", rtol=rtol)
        err = np.abs(got - ref) / np.maximum(scale, np.abs(ref))
        assert err.max() <= rtol, (rtol, float(r[np.argmax(err)]), err.max())
