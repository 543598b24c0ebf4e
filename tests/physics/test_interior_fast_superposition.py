"""The fast evaluation of the 1-D superpositions below the surface (docs/theory/interior.md
(I53)-(I55)) against routes independent of it:

* the punch's radial functions (I53) against the Cartesian punch ``punch_unit`` (I10)-(I14);
* the flat rule with a node count per panel (I54) against the panel rule of (I16)-(I17) with 32
  nodes per panel and the Cartesian punches at every node, at every rtol of ``interior_orders``,
  on the axis, at z = 1e-9 a, on r = a, next to it and in the far field; that rule in turn
  against adaptive QUADPACK quadrature (scipy.integrate.quad_vec) of the defining integrals
  (I15) and (I45);
* the cost: the number of nodes (not the time) falls as rtol grows, and stays below the panel
  rule's at every rtol.
"""
import functools
import math

import numpy as np
import pytest
from scipy.integrate import quad_vec

from stressfields.physics import axisymmetric as ax
from stressfields.physics.axisymmetric import interior as I
from stressfields.physics.axisymmetric.interior_hertz import COMPONENTS, punch_radial, punch_unit, sliding_punch_unit
from stressfields.physics.axisymmetric.interior_tangential import _integrate_sliding, interior_stress_tangential

NU = 0.3
RTOLS = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)
_KNOTS = np.linspace(0.0, 1.3, 13)
PROFILES = {
    "n3": ax.power_law(1.0, 3.0),
    "n05": ax.power_law(1.0, 0.5),
    "spline": ax.tabulated(_KNOTS, _KNOTS ** 3 + 0.2 * _KNOTS ** 2),
}

_RNG = np.random.default_rng(29)
# axis, next to it, z = 1e-9 a at r = a and inside/outside, far field, and random points
_R = np.concatenate([[0.0, 0.0, 1e-6, 0.4, 0.999, 1.0, 1.0, 1.001, 1.5, 1e4, 0.0, 0.7],
                     _RNG.uniform(0.0, 3.0, 18)])
_Z = np.concatenate([[1e-9, 0.3, 1e-9, 1e-9, 1e-9, 1e-9, 0.05, 1e-9, 1e-9, 1.0, 1e4, 3.8],
                     10 ** _RNG.uniform(-9.0, 1.0, 18)])
_T = _RNG.uniform(0.0, 2.0 * math.pi, _R.size)
X, Y = _R * np.cos(_T), _R * np.sin(_T)


def _pm(profile):
    return float(profile.normal_force(1.0)) / math.pi


def _fine_rule(profile, kernel, lower=None):
    """The reference: the panel rule of ``interior._superpose`` (I16)-(I17) with the Cartesian
    punches (I10)-(I14), (I30)-(I32) at every node and 32 nodes per panel, ratio 1.6 (the rule
    the table of ``interior_orders`` was measured against), itself held against QUADPACK below."""
    saved = I._ORDERS
    I._ORDERS = ((1e-12, (32, 1.6)),)
    try:
        return I._superpose(X, Y, _Z, np.ones(_R.size), np.full(_R.size, NU), profile, 1e-12, kernel, lower=lower)
    finally:
        I._ORDERS = saved


@functools.lru_cache(maxsize=None)
def _reference(name):
    return _fine_rule(PROFILES[name], I._STRESS_KERNEL)


@functools.lru_cache(maxsize=None)
def _reference_slip():
    return _fine_rule(PROFILES["n3"], (_integrate_sliding, COMPONENTS), lower=np.full(_R.size, 0.5))


def _quadpack(profile, unit, i, lower=0.0):
    """int_lower^1 g'(rho) unit(x / rho) / rho d rho at point i by quad_vec, in u with rho = u^2
    (g' ~ rho^(-1/2) at the tip of n = 0.5 becomes bounded), the layer rho = r and the knots as
    break points; (value, QUADPACK's error estimate)."""
    knots = list(np.asarray(profile.r)) if profile.kind == "tabulated" else []

    def f(u):
        rho = u * u
        k = unit(X[i] / rho, Y[i] / rho, _Z[i] / rho, NU, rm1=(_R[i] - rho) / rho)
        w = 2.0 * u * float(profile.dg(rho)) / rho
        return np.array([float(k[c]) * w for c in COMPONENTS])
    pts = sorted({math.sqrt(p) for p in [_R[i]] + knots if lower < p < 1.0})
    return quad_vec(f, math.sqrt(lower), 1.0, epsabs=1e-15, epsrel=1e-14, points=pts or None, limit=2000)


# axis at z = 0.3 a, r = a at z = 0.05 a, far field (r = 1e4 a; axis at 1e4 a), r = 0.7 a at z = 3.8 a,
# two random points at z ~ 1e-3 a (QUADPACK meets 1e-13 there without help)
_CHECKED = [1, 6, 9, 10, 11, 20, 21]


def _agree(ref, v, err, i, pm):
    """QUADPACK's (conservative) estimate at most 1e-12, the two routes within 2e-13 of
    max(|value|, p_m) (measured: at most 8.6e-14, the n = 0.5 tip's rounding floor; 1e-15 else)."""
    scale = max(pm, float(np.max(np.abs(v))))
    assert err <= 1e-12 * scale
    assert max(abs(ref[c][i] - v[j]) for j, c in enumerate(COMPONENTS)) <= 2e-13 * scale, i


@pytest.mark.slow   # QUADPACK references, ~15 s
@pytest.mark.parametrize("name", sorted(PROFILES))
def test_fine_rule_against_quadpack(name):
    P = PROFILES[name]
    ref = _reference(name)
    for i in _CHECKED:
        v, err = _quadpack(P, punch_unit, i)
        _agree(ref, v, err, i, _pm(P))


def test_fine_sliding_rule_against_quadpack():
    P = PROFILES["n3"]
    ref = _reference_slip()
    for i in _CHECKED:
        v, err = _quadpack(P, sliding_punch_unit, i, lower=0.5)
        _agree(ref, v, err, i, _pm(P))


def _scaled_error(q, ref, scale):
    return max(float(np.max(np.abs(q[c] - ref[c]) / np.maximum(np.abs(ref[c]), scale))) for c in COMPONENTS)


def test_punch_radial_equals_the_cartesian_punch():
    rng = np.random.default_rng(3)
    n = 20000
    r = np.concatenate([[0.0, 1e-300, 1e-16], 10 ** rng.uniform(-12, 4, n // 2),
                        1.0 + rng.choice([-1.0, 1.0], n // 2) * 10 ** rng.uniform(-12, 0, n // 2)])
    z = 10 ** rng.uniform(-12, 4, r.size)
    x, y = 0.6 * r, 0.8 * r
    ref = punch_unit(x, y, z, NU, rm1=r - 1.0)
    sigma, zz, e, t = punch_radial(r, z, r - 1.0, NU)
    ux, uy = I._direction(x, y, r)
    new = I._radial_cartesian(ux, uy, sigma, zz, e * r * r, t * r)
    largest = np.max([np.abs(ref[c]) for c in COMPONENTS], axis=0)
    for c in COMPONENTS:
        assert np.all(np.abs(new[c] - ref[c]) <= 1e-13 * largest), c


@pytest.mark.parametrize("name", sorted(PROFILES))
@pytest.mark.parametrize("rtol", RTOLS)
def test_flat_rule_against_quadpack(name, rtol):
    P = PROFILES[name]
    q = I.interior_stress(X, Y, _Z, 1.0, NU, P, method="quadrature", rtol=rtol)
    assert _scaled_error(q, _reference(name), _pm(P)) <= rtol


@pytest.mark.parametrize("rtol", RTOLS)
def test_partial_slip_flat_rule_against_quadpack(rtol):
    """(I45), c = a/2, mu = 1: the sliding punches over [c, a] (I55)."""
    P = PROFILES["n3"]
    q = interior_stress_tangential(X, Y, _Z, 1.0, 0.5, NU, 1.0, P, method="quadrature", rtol=rtol)
    assert _scaled_error(q, _reference_slip(), _pm(P)) <= rtol


def _node_counts(profile, rtol, lower):
    """(nodes of the flat rule (I54), nodes of the panel rule (I16)-(I17)) over the test points."""
    n, q = I.interior_orders(rtol)
    a, nu = np.ones(_R.size), np.full(_R.size, NU)
    flat = I._flat_nodes(X, Y, _Z, a, nu, profile, n, q, rtol, lower)
    rho_s, offsets = I._breakpoints(_R, _Z, a, profile, q, lower)
    panels = int(np.sum(np.diff(offsets, axis=1) > 0.0))
    return flat.row.size, panels * n + int(np.sum(~(lower > 0.0))) * (n + 4)


@pytest.mark.parametrize("name", sorted(PROFILES))
@pytest.mark.parametrize("lower", [0.0, 0.5])
def test_cost_falls_with_rtol(name, lower):
    counts = [_node_counts(PROFILES[name], rtol, np.full(_R.size, lower)) for rtol in RTOLS]
    flat = [c[0] for c in counts]
    assert all(a < b for a, b in zip(flat, flat[1:])), flat
    assert all(f <= panel for f, panel in counts), counts


def test_next_to_a_singular_tip_is_finite_and_continuous():
    """n = 0.5 (g' ~ rho^(-1/2)) at z = 1e-12 a: r = 1e-300 ... 1e-30 a is the axis value to
    O((r/z)^2) (the panel rule returned -inf at r = 1e-300 a); partial slip likewise.  The axis
    and the other points use different panels: each within rtol, so within 2 rtol of each other."""
    P = PROFILES["n05"]
    r = np.array([0.0, 1e-300, 1e-200, 1e-100, 1e-30])
    s = I.interior_stress(r, 0 * r, 1e-12, 1.0, NU, P, method="quadrature", rtol=1e-12)
    t = interior_stress_tangential(r, 0 * r, 1e-12, 1.0, 0.5, NU, 1.0, P, method="quadrature", rtol=1e-12)
    for out in (s, t):
        for c in COMPONENTS:
            assert np.all(np.isfinite(out[c])), c
            assert np.all(np.abs(out[c][1:] - out[c][0]) <= 2e-12 * max(abs(out[c][0]), _pm(P))), c
