"""Closed forms (eq. 1, 5, 14-17, 21, 36-41) against the general 1-D integral route (eq. 9, 11,
24-26) for the cone and the paraboloid, on a dense grid inside, outside and close to the edges
r = a and r = c, for several nu, mu, c."""
import math

import numpy as np
import pytest

from stressfields.physics import axisymmetric as ax

KEYS = ("xx", "yy", "zz", "xy", "xz", "yz")


def _grid(a, c):
    """Radii spanning the centre, the stick zone, both edges (within 1e-9) and the far field, on
    rays through all quadrants and the axes."""
    rho = np.concatenate([
        [1e-8, 1e-4, 0.01, 0.1, 0.35, 0.5, 0.75, 0.9, 0.999, 1.0 - 1e-9, 1.0, 1.0 + 1e-9, 1.001, 1.2, 1.999,
         2.0, 2.001, 3.0, 10.0, 100.0],
        c / a * np.array([1 - 1e-3, 1 - 1e-9, 1.0, 1 + 1e-9, 1 + 1e-3]) if c > 0 else [],
        np.linspace(0.02, 2.5, 37),
    ]) * a
    phi = np.array([0.0, 0.3, math.pi / 4, 1.1, math.pi / 2, 2.0, math.pi, 4.0, 1.5 * math.pi, 5.9])
    R, P = np.meshgrid(rho, phi)
    return (R * np.cos(P)).ravel(), (R * np.sin(P)).ravel()


def _compare(profile, a, c, nu, mu, rtol):
    x, y = _grid(a, c)
    pm = float(ax.mean_pressure(a, profile))
    sc = ax.surface_stress(x, y, a, c, nu, mu, profile, method="closed")
    sq = ax.surface_stress(x, y, a, c, nu, mu, profile, method="quadrature", rtol=rtol)
    dc = ax.surface_dpdz(x, y, a, c, nu, mu, profile, method="closed")
    dq = ax.surface_dpdz(x, y, a, c, nu, mu, profile, method="quadrature", rtol=rtol)
    worst = 0.0
    for name, u, v, scale in [(k, sc[k], sq[k], pm) for k in KEYS] + [("dpdz", dc, dq, pm / a)]:
        fin = np.isfinite(u)
        # the same points are singular, with the same sign
        np.testing.assert_array_equal(np.isfinite(v), fin, err_msg=name)
        np.testing.assert_array_equal(np.isnan(v), np.isnan(u), err_msg=name)
        np.testing.assert_array_equal(v[np.isinf(u)], u[np.isinf(u)], err_msg=name)
        err = np.abs(u[fin] - v[fin]) / scale / np.maximum(1.0, np.abs(u[fin]) / scale)
        worst = max(worst, float(err.max()))
        assert err.max() <= rtol, f"{name}: {err.max():.2e} > {rtol:.0e} at {np.argmax(err)}"
    return worst


@pytest.mark.parametrize("rtol", [1e-6, 1e-10])
@pytest.mark.parametrize("profile", [ax.cone(0.4), ax.paraboloid(3.0)], ids=["cone", "paraboloid"])
@pytest.mark.parametrize("nu,mu,c_over_a", [(0.3, 0.0, 0.0), (0.0, 0.2, 0.0), (0.3, 0.3, 16 / 51),
                                            (0.5, 0.4, 0.7), (0.25, 1.2, 0.05), (0.45, 0.3, 0.999)])
def test_closed_equals_quadrature(profile, nu, mu, c_over_a, rtol):
    a = 0.8
    _compare(profile, a, c_over_a * a, nu, mu, rtol)


def test_power_law_quadrature_equals_cone_and_paraboloid_closed():
    """power_law(n=1) is the cone tan(theta) = A, power_law(n=2) the paraboloid R = 1/(2A): the
    power-law quadrature route (Gauss–Jacobi rules) against the closed forms."""
    x, y = _grid(1.0, 0.4)
    for pl, closed in ((ax.power_law(0.6, 1.0), ax.cone(0.6)), (ax.power_law(0.25, 2.0), ax.paraboloid(2.0))):
        assert pl.has_closed_form
        pm = float(ax.mean_pressure(1.0, closed))
        assert float(ax.mean_pressure(1.0, pl)) == pytest.approx(pm, rel=1e-15)
        for rtol in (1e-6, 1e-10):
            sq = ax.surface_stress(x, y, 1.0, 0.4, 0.3, 0.3, pl, method="quadrature", rtol=rtol)
            sc = ax.surface_stress(x, y, 1.0, 0.4, 0.3, 0.3, closed)
            dq = ax.surface_dpdz(x, y, 1.0, 0.4, 0.3, 0.3, pl, method="quadrature", rtol=rtol)
            dc = ax.surface_dpdz(x, y, 1.0, 0.4, 0.3, 0.3, closed)
            for u, v in [(sc[k], sq[k]) for k in KEYS] + [(dc, dq)]:
                fin = np.isfinite(u)
                np.testing.assert_array_equal(np.isfinite(v), fin)
                err = np.abs(u[fin] - v[fin]) / pm / np.maximum(1.0, np.abs(u[fin]) / pm)
                assert err.max() <= rtol
            # and the closed route of the power law itself maps to the same forms
            s2 = ax.surface_stress(x, y, 1.0, 0.4, 0.3, 0.3, pl, method="closed")
            for k in KEYS:
                np.testing.assert_allclose(s2[k], sc[k], rtol=1e-14, atol=1e-15 * pm)
