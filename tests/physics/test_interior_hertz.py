"""The closed forms below the surface (docs/theory/interior.md (I5)-(I14)) against routes that
share no code with them:

* oracle-free: equilibrium d_j sigma_ij = 0 and Beltrami–Michell compatibility by central
  differences (the residual must fall like h^2; a field with nu perturbed must fail), and the
  traction boundary conditions at z -> 0;
* Johnson's axis formulas (Contact Mechanics 1985, sec. 3.4), evaluated in extended precision;
* the surface kernels of the family (docs/theory/axisymmetric.md (A18)-(A22)) at z = 0;
* the Boussinesq point load in the far field;
* the flat-punch kernel against a central difference in a of a S(x/a) (its definition (I10)).
"""
import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from stressfields.physics import axisymmetric as ax
from stressfields.physics.axisymmetric.interior import interior_stress
from stressfields.physics.axisymmetric.interior_hertz import hertz_unit, punch_unit

from interior_checks import NU, POINTS, residuals as _residuals


@pytest.mark.parametrize("f", [hertz_unit, punch_unit])
def test_equilibrium_and_compatibility_fall_like_h2(f):
    coarse, fine = _residuals(f, 1e-3), _residuals(f, 5e-4)
    for c, fi in zip(coarse, fine):
        assert fi < 2e-4 and 3.5 < c / fi < 4.5        # O(h^2): the field solves both PDEs


def test_residual_check_discriminates():
    """Control: sigma_xx taken at nu * 1.01 breaks compatibility by orders of magnitude."""
    def wrong(x, y, z, nu):
        s = hertz_unit(x, y, z, nu)
        s["xx"] = hertz_unit(x, y, z, nu * 1.01)["xx"]
        return s
    assert _residuals(wrong, 5e-4)[1] > 50 * _residuals(hertz_unit, 5e-4)[1]


@pytest.mark.parametrize("f, p", [(hertz_unit, lambda r: np.sqrt(np.clip(1 - r * r, 0, None))),
                                  (punch_unit, lambda r: 1 / (math.pi * np.sqrt(1 - r * r)))])
def test_traction_boundary_conditions(f, p):
    """z -> 0: sigma_zz = -p, sigma_xz = sigma_yz = 0 inside, all three 0 outside the contact."""
    r = np.array([0.0, 0.3, 0.6, 0.9, 1.2, 2.0])
    x, y = r * 0.8, r * 0.6
    s = f(x, y, 1e-10, NU)
    inside = r < 1
    assert np.allclose(s["zz"][inside], -p(r[inside]), rtol=1e-8, atol=0)
    assert np.all(np.abs(s["zz"][~inside]) < 1e-12)
    assert np.all(np.abs(s["xz"]) < 1e-8) and np.all(np.abs(s["yz"]) < 1e-8)


def _johnson_axis(z):
    """sigma_zz, sigma_rr on the axis / p0 (Johnson 1985, sec. 3.4), in extended precision."""
    z = np.longdouble(z)
    return -1 / (1 + z * z), -(1 + NU) * (1 - z * np.arctan(1 / z)) + 1 / (2 * (1 + z * z))


@pytest.mark.parametrize("r", [0.0, 1e-16, 1e-8])
def test_axis_values(r):
    z = np.array([0.01, 0.2, 0.5, 1.0, 2.0, 5.0])
    zz, rr = _johnson_axis(z)
    for phi in (0.0, 0.7):
        s = hertz_unit(r * math.cos(phi), r * math.sin(phi), z, NU)
        assert np.all(np.abs(s["zz"] / zz - 1) < 1e-12)
        assert np.all(np.abs(s["xx"] / rr - 1) < 1e-12) and np.all(np.abs(s["yy"] / rr - 1) < 1e-12)
        assert np.all(np.abs(s["xy"]) <= 1e-12 * np.abs(rr))
        assert np.all(np.abs(s["xz"]) <= 2 * r) and np.all(np.abs(s["yz"]) <= 2 * r)   # sigma_rz = O(r)


def test_tau_max_on_axis():
    """Peak of (sigma_zz - sigma_rr)/2 on the axis (nu = 0.3): 0.31 p0 at z = 0.48 a; found by a
    bounded scalar search on the kernel (xatol 1e-10), the same search on Johnson's formula agrees
    to 1e-13 in the value and, the peak being flat, to sqrt(eps) in z: 0.310020501954521 p0 at
    z = 0.4808645 a."""
    tau = lambda z: 0.5 * float(np.diff([hertz_unit(0.0, 0.0, z, NU)[c] for c in ("zz", "xx")])[0])
    ref = lambda z: 0.5 * float(np.diff(_johnson_axis(z))[0])
    found = [minimize_scalar(lambda z: -g(z), bounds=(0.1, 1.0), method="bounded", options=dict(xatol=1e-10))
             for g in (tau, ref)]
    assert abs(found[0].x - found[1].x) < 1e-7 and abs(found[0].fun - found[1].fun) < 1e-13
    assert round(-found[0].fun, 2) == 0.31 and round(found[0].x, 2) == 0.48


def test_surface_limit_matches_surface_kernels():
    """z = 0 and z -> 0 against the surface kernels (paraboloid R = 2, a = 0.5), edge ring included."""
    R, a = 2.0, 0.5
    r = np.array([0.0, 1e-9, 0.1, 0.25, 0.4, 0.499, 0.5, 0.501, 0.7, 3.0])
    x, y = r * math.cos(0.4), r * math.sin(0.4)
    names = ["sigma_" + c for c in ax.COMPONENTS]
    surf, _ = ax.fields(names, ax.paraboloid(R), x, y, a=a, nu=NU, mu=0.0, ux0=0.0)
    p0 = 2 * a / (math.pi * R)
    # z -> 0 is continuous: O(z) away from the edge ring, O(sqrt(z)) on it (r = a is left out at z > 0)
    for z, tol, keep in ((0.0, 1e-12, r >= 0), (1e-13, 1e-9, r != a)):
        s = interior_stress(x, y, z, a, NU, ax.paraboloid(R))
        for c in ax.COMPONENTS:
            assert np.allclose(s[c][keep], surf["sigma_" + c][keep], rtol=tol, atol=tol * p0), (c, z)
    edge = hertz_unit(1.0, 0.0, 0.0, NU)
    assert edge["xx"] == pytest.approx((1 - 2 * NU) / 3, rel=1e-14) and edge["yy"] == pytest.approx(-(1 - 2 * NU) / 3)
    assert edge["zz"] == 0.0 and edge["xz"] == 0.0


@pytest.mark.parametrize("f, load", [(hertz_unit, 2 * math.pi / 3), (punch_unit, 2.0)])
def test_far_field_is_boussinesq(f, load):
    """r, z ~ 1e3 ... 1e4: the point load P (Hertz: 2 pi p0 a^2 / 3; punch: 2 E* a delta) to
    relative O((a/R)^2)."""
    x = np.array([1e3, 3e3, 0.0, 7e3, 1e4])
    z = np.array([1e3, 5e3, 2e3, 1e4, 2e3])
    y = 0.5 * x
    r2 = x * x + y * y
    rho = np.sqrt(r2 + z * z)
    k = load / (2 * math.pi)
    srr_plus_stt = k * ((1 - 2 * NU) * z / rho ** 3 - 3 * z * r2 / rho ** 5)
    s = f(x, y, z, NU)
    assert np.allclose(s["zz"], -3 * k * z ** 3 / rho ** 5, rtol=20 / rho.min() ** 2, atol=0)
    assert np.allclose(s["xz"], -3 * k * x * z ** 2 / rho ** 5, rtol=20 / rho.min() ** 2, atol=0)
    assert np.allclose(s["xx"] + s["yy"], srr_plus_stt, rtol=20 / rho.min() ** 2, atol=0)


def test_punch_kernel_is_the_a_derivative_of_hertz():
    """(I10): punch = (1/pi) d/da [a S(x/a)] at a = 1, against central differences in a (steps
    1e-3 and 5e-4, Richardson-extrapolated: error O(h^4) + rounding ~ 1e-12)."""
    p = POINTS.T

    def fd(c, h):
        up = hertz_unit(p[0] / (1 + h), p[1] / (1 + h), p[2] / (1 + h), NU)[c] * (1 + h)
        down = hertz_unit(p[0] / (1 - h), p[1] / (1 - h), p[2] / (1 - h), NU)[c] * (1 - h)
        return (up - down) / (2 * h * math.pi)
    k = punch_unit(*p, NU)
    for c in ax.COMPONENTS:
        assert np.allclose(k[c], (4 * fd(c, 5e-4) - fd(c, 1e-3)) / 3, rtol=0, atol=1e-10), c


def test_punch_edge_ring_and_validation():
    k = punch_unit(np.array([1.0, 0.6]), np.array([0.0, 0.8]), 0.0, NU)
    assert np.all(k["zz"] == -np.inf) and np.all(k["xx"] == -np.inf)
    assert k["yz"][0] == 0.0 and np.isnan(k["xz"]).all() and np.isnan(k["xy"][1])
    with pytest.raises(ValueError, match="depth"):
        hertz_unit(0.0, 0.0, -1.0, NU)
    with pytest.raises(ValueError, match="closed"):
        interior_stress(0.0, 0.0, 1.0, 1.0, NU, ax.power_law(0.2, 1.5), method="closed")   # the cone has (I37)-(I42)
