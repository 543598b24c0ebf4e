"""The 1-D superposition of flat punches below the surface (docs/theory/interior.md (I15)-(I17))
against routes independent of it:

* the closed forms (Hertz for the paraboloid and for a spline of a paraboloid);
* on the axis, a ring superposition of the Boussinesq point load by adaptive scipy quadrature,
  with the contact pressure from its own formula (cone: closed form; power law: scipy quadrature
  of the Abel integral);
* equilibrium by central differences and the traction boundary condition at z -> 0;
* the Boussinesq point load in the far field;
* the accuracy of each rtol row against the finest rule.
"""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from stressfields.physics import axisymmetric as ax
from stressfields.physics.axisymmetric.interior import interior_stress

NU = 0.3
RNG = np.random.default_rng(11)
_R = np.concatenate([RNG.uniform(0.0, 3.0, 60), [0.0, 1e-12, 1e-6, 0.999, 1.0, 1.001]])
_T = RNG.uniform(0.0, 2 * math.pi, _R.size)
X, Y = _R * np.cos(_T), _R * np.sin(_T)
Z = 10 ** RNG.uniform(-10, 1.3, _R.size)


def _pm(profile, a=1.0):
    return float(profile.normal_force(a)) / (math.pi * a * a)


def _scaled_error(q, ref, pm):
    return max(np.max(np.abs(q[c] - ref[c]) / np.maximum(np.abs(ref[c]), pm)) for c in ax.COMPONENTS)


@pytest.mark.parametrize("rtol", [1e-6, 1e-10])
def test_paraboloid_quadrature_equals_hertz(rtol):
    P = ax.paraboloid(1.5)
    closed = interior_stress(X, Y, Z, 1.0, NU, P, method="closed")
    q = interior_stress(X, Y, Z, 1.0, NU, P, method="quadrature", rtol=rtol)
    assert _scaled_error(q, closed, _pm(P)) <= rtol


def test_spline_of_a_paraboloid_equals_hertz():
    """A not-a-knot spline reproduces r^2/(2R) exactly: its 1-D route (knot cusps, graded panels)
    must give the Hertz field."""
    r = np.linspace(0.0, 1.3, 9)
    closed = interior_stress(X, Y, Z, 1.0, NU, ax.paraboloid(1.0))
    q = interior_stress(X, Y, Z, 1.0, NU, ax.tabulated(r, r * r / 2), rtol=1e-10)
    assert _scaled_error(q, closed, _pm(ax.paraboloid(1.0))) <= 1e-10


def _ring_axis(p, z):
    """sigma_zz and sigma_xx on the axis at depth z from rings of Boussinesq point loads:
    sigma_zz = -int 3 z^3 s p / rho^5 ds, sigma_xx = int s p [(1-2nu) z/rho^3 - 3 z s^2/rho^5]/2 ds."""
    kw = dict(epsabs=0.0, epsrel=1e-12, limit=400, points=[z])
    zz = -quad(lambda s: 3 * z ** 3 * s * p(s) / (s * s + z * z) ** 2.5, 0, 1, **kw)[0]
    xx = quad(lambda s: 0.5 * s * p(s) * ((1 - 2 * NU) * z / (s * s + z * z) ** 1.5
                                          - 3 * z * s * s / (s * s + z * z) ** 2.5), 0, 1, **kw)[0]
    return zz, xx


def test_cone_axis_against_boussinesq_rings():
    tan_theta = 0.4
    p = lambda s: 0.5 * tan_theta * math.acosh(1 / s) if 0 < s < 1 else 0.0   # cone pressure / E*
    for z in (0.05, 0.2, 0.5, 1.0, 3.0):
        zz, xx = _ring_axis(p, z)
        s = interior_stress(0.0, 0.0, z, 1.0, NU, ax.cone(tan_theta), rtol=1e-12)
        assert abs(float(s["zz"]) - zz) <= 1e-11 * abs(zz)
        assert abs(float(s["xx"]) - xx) <= 1e-11 * abs(xx) and abs(float(s["yy"]) - xx) <= 1e-11 * abs(xx)


def test_power_law_axis_against_boussinesq_rings():
    """n = 0.5: g' ~ rho^(-1/2) at the tip; the pressure by scipy quadrature of the Abel integral."""
    P = ax.power_law(1.0, 0.5)

    def p(s):
        f = lambda u: float(P.dg(u)) / math.sqrt(u + s)
        return quad(f, s, 1.0, weight="alg", wvar=(-0.5, 0.0), epsabs=0.0, epsrel=1e-13, limit=200)[0] / math.pi
    zz, xx = _ring_axis(p, 0.3)
    s = interior_stress(0.0, 0.0, 0.3, 1.0, NU, P, rtol=1e-12)
    assert abs(float(s["zz"]) - zz) <= 1e-11 * abs(zz) and abs(float(s["xx"]) - xx) <= 1e-11 * abs(xx)


def test_cone_equilibrium_and_surface_traction():
    P = ax.cone(0.4)
    pts = np.column_stack([RNG.uniform(-1.4, 1.4, 6), RNG.uniform(-1.4, 1.4, 6), RNG.uniform(0.2, 1.2, 6)])
    f = lambda q: interior_stress(q[:, 0], q[:, 1], q[:, 2], 1.0, NU, P, rtol=1e-12)
    rows = [("xx", "xy", "xz"), ("xy", "yy", "yz"), ("xz", "yz", "zz")]
    res = []
    for h in (2e-3, 1e-3):
        div = np.zeros((6, 3))
        for j in range(3):
            e = np.eye(3)[j] * h
            up, down = f(pts + e), f(pts - e)
            div += np.column_stack([(up[row[j]] - down[row[j]]) / (2 * h) for row in rows])
        res.append(np.abs(div).max())
    assert res[1] < 1e-5 and 3.5 < res[0] / res[1] < 4.5
    r = np.array([0.1, 0.5, 0.9, 1.5])
    s = interior_stress(r, 0 * r, 1e-9, 1.0, NU, P)
    p = 0.2 * np.arccosh(np.maximum(1 / r, 1.0))
    assert np.allclose(s["zz"], -p, rtol=0, atol=1e-7) and np.all(np.abs(s["xz"]) < 1e-7)


def test_cone_far_field_is_boussinesq():
    P = ax.cone(0.4)
    load = float(P.normal_force(1.0))                 # F_N / E*
    x = np.array([1e3, 3e3, 0.0, 7e3])
    z = np.array([1e3, 5e3, 2e3, 1e4])
    rho = np.hypot(x, z)
    s = interior_stress(x, 0 * x, z, 1.0, NU, P)
    k = load / (2 * math.pi)
    assert np.allclose(s["zz"], -3 * k * z ** 3 / rho ** 5, rtol=20 / rho.min() ** 2, atol=0)
    assert np.allclose(s["xz"], -3 * k * x * z ** 2 / rho ** 5, rtol=20 / rho.min() ** 2, atol=0)


_KNOTS = np.linspace(0.0, 1.2, 13)


@pytest.mark.parametrize("profile", [ax.cone(0.3), ax.power_law(1.0, 0.5), ax.power_law(1.0, 3.0),
                                     ax.tabulated(_KNOTS, _KNOTS ** 2 / 2 + 0.3 * _KNOTS ** 4)])
@pytest.mark.parametrize("rtol", [1e-4, 1e-8])
def test_orders_meet_rtol(profile, rtol):
    ref = interior_stress(X, Y, Z, 1.0, NU, profile, rtol=1e-12)
    q = interior_stress(X, Y, Z, 1.0, NU, profile, rtol=rtol)
    assert _scaled_error(q, ref, _pm(profile)) <= rtol


def test_surface_continuity_and_flat_punch():
    P = ax.cone(0.4)
    r = np.array([0.0, 0.3, 0.8, 1.4])
    s0 = interior_stress(r, 0 * r, 0.0, 1.0, NU, P)
    s1 = interior_stress(r[1:], 0 * r[1:], 1e-11, 1.0, NU, P)
    assert np.all(s0["zz"][:1] == -np.inf)                       # the cone's apex
    for c in ax.COMPONENTS:
        assert np.allclose(s1[c], s0[c][1:], rtol=1e-8, atol=1e-10)
    fp = interior_stress(r, 0 * r, 1e-12, 1.0, NU, ax.flat_punch(1.0, 0.01))
    assert np.allclose(fp["zz"][r < 1], -0.01 / (math.pi * np.sqrt(1 - r[r < 1] ** 2)), rtol=1e-9, atol=0)


# -- d p_h/dz (docs/theory/interior.md (I24)-(I28)) -----------------------------------------------

_RD = np.concatenate([np.linspace(0.0, 1.2, 40), 1 - 10.0 ** -np.arange(1, 13), 1 + 10.0 ** -np.arange(1, 13, 2)])
_ZD = 10.0 ** np.linspace(-12, 0.5, _RD.size)[::-1]


def _trace_derivative(profile, x, y, z, h, rtol=1e-12):
    ph = [-sum(interior_stress(x, y, z + s * h, 1.0, NU, profile, rtol=rtol)[c] for c in ("xx", "yy", "zz")) / 3
          for s in (1, -1)]
    return (ph[0] - ph[1]) / (2 * h)


@pytest.mark.parametrize("profile", [ax.paraboloid(1.0), ax.flat_punch(1.0, 0.3)])
def test_closed_dpdz_is_the_derivative_of_the_trace(profile):
    """(I26), (I27) against central differences of the closed-form stresses: second order."""
    x, y, z = RNG.uniform(-2, 2, 20), RNG.uniform(-2, 2, 20), RNG.uniform(0.1, 2.0, 20)
    exact = ax.interior_dpdz(x, y, z, 1.0, NU, profile)
    err = [np.max(np.abs(_trace_derivative(profile, x, y, z, h) - exact)) for h in (2e-3, 1e-3)]
    assert err[1] < 1e-5 and 3.5 < err[0] / err[1] < 4.5


@pytest.mark.parametrize("rtol", [1e-4, 1e-6, 1e-8, 1e-10])
def test_dpdz_superposition_of_the_paraboloid_equals_hertz(rtol):
    """The 1-D route (with the integration by parts of (I28)) against (I26), from the axis to
    next to the edge ring and from z = 1e-12 a (y = 0: r is exact, no conditioning of x -> r)."""
    P = ax.paraboloid(1.0)
    closed = ax.interior_dpdz(_RD, 0 * _RD, _ZD, 1.0, NU, P)
    q = ax.interior_dpdz(_RD, 0 * _RD, _ZD, 1.0, NU, P, method="quadrature", rtol=rtol)
    assert np.max(np.abs(q - closed) / np.maximum(np.abs(closed), _pm(P))) <= rtol


@pytest.mark.parametrize("profile", [ax.cone(0.3), ax.power_law(1.0, 0.5), ax.power_law(1.0, 3.0),
                                     ax.tabulated(_KNOTS, _KNOTS ** 2 / 2 + 0.3 * _KNOTS ** 4)])
def test_dpdz_superposition_meets_rtol(profile):
    """Every profile: the finest row against a difference of the (independently tested) stresses in
    z, then each row against the finest one, near the surface included."""
    x, y, z = RNG.uniform(-1.5, 1.5, 12), RNG.uniform(-1.5, 1.5, 12), RNG.uniform(0.2, 1.5, 12)
    fine = ax.interior_dpdz(x, y, z, 1.0, NU, profile, rtol=1e-12)
    assert np.max(np.abs(_trace_derivative(profile, x, y, z, 1e-3) - fine)) < 1e-5 * _pm(profile)
    ref = ax.interior_dpdz(_RD, 0 * _RD, _ZD, 1.0, NU, profile, rtol=1e-12)
    for rtol in (1e-4, 1e-8):
        q = ax.interior_dpdz(_RD, 0 * _RD, _ZD, 1.0, NU, profile, rtol=rtol)
        assert np.max(np.abs(q - ref) / np.maximum(np.abs(ref), _pm(profile))) <= rtol


def test_dpdz_tends_to_the_surface_kernel():
    """z -> 0+ against the surface kernel (docs/theory/axisymmetric.md (A24)-(A26)), off the edge."""
    r = np.array([0.0, 0.3, 0.8, 1.4, 2.5])
    for profile in (ax.paraboloid(1.0), ax.cone(0.4), ax.flat_punch(1.0, 0.01)):
        surface = ax.surface_dpdz(r, 0 * r, 1.0, 1.0, NU, 0.0, profile, method="closed")
        near = ax.interior_dpdz(r[1:], 0 * r[1:], 1e-9, 1.0, NU, profile)
        assert np.allclose(near, surface[1:], rtol=1e-6, atol=1e-7)
        assert np.allclose(ax.interior_dpdz(r, 0 * r, 0.0, 1.0, NU, profile)[1:], surface[1:], rtol=1e-10, atol=0)
