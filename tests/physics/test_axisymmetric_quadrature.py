"""Quadrature rules and the order table of ``stressfields.physics.quadrature``.

The table (rtol -> orders) was chosen by measuring, per row, the deviation from the most accurate
row (1e-14) over power laws with n from 0.3 to 50, tabulated splines (25 and 101 knots, a
hyperboloid, a geometric grid) and the cone/paraboloid, at r/a from 1e-8 to 100 on five rays and
with c/a in {0, 0.3, 0.9}.  Measured maxima (stresses and dp/dz, in units of p_m and p_m/a):
rtol 1e-4 -> 2.4e-7, 1e-6 -> 3.5e-9, 1e-8 -> 7.8e-11, 1e-10 -> 5.4e-12, 1e-12 -> 1.8e-12 (pl50,
limited by rounding).  This test re-measures a subset and demands a margin of 10.  Accuracy against
routes independent of the implementation is in the other test files."""
import math

import numpy as np
import pytest

from stressfields.physics import axisymmetric as ax
from stressfields.physics import quadrature as q

KEYS = ("xx", "yy", "zz", "xy", "xz", "yz")


def test_gauss_rules_are_exact_for_polynomials():
    t, w = q.gauss_legendre(7)
    for k in range(14):
        assert np.sum(w * t ** k) == pytest.approx(1.0 / (k + 1), rel=1e-14)
    for beta in (-0.5, 0.3, 2.5, 49.0):
        t, w = q.gauss_jacobi(9, beta)
        for k in range(18):
            assert np.sum(w * t ** k) == pytest.approx(1.0 / (k + beta + 1), rel=1e-13)
    with pytest.raises(ValueError):
        q.gauss_jacobi(4, -1.0)
    # graded segments: exact for polynomials in sqrt(t - left) up to degree 2n-1
    pts = np.array([[0.0, 0.3, 1.0], [0.2, 0.2, 0.7]])
    t, w = q.segment_rule(pts, 6)
    np.testing.assert_allclose(np.sum(w * np.sqrt(np.abs(t - 0.3)) ** 3 * (t > 0.3), axis=1)[0],
                               0.7 ** 2.5 / 2.5, rtol=1e-13)
    np.testing.assert_allclose(np.sum(w, axis=1), [1.0, 0.5], rtol=1e-14)


def test_orders_table():
    prev = None
    for tol, _ in q._TABLE:
        o = q.orders(tol)
        if prev is not None:
            assert o.n_tau >= prev.n_tau and o.n_theta >= prev.n_theta and o.n_jacobi >= prev.n_jacobi
        prev = o
    assert q.orders(1.0) == q._TABLE[0][1]
    assert q.orders(5e-10) == q.orders(1e-10) and q.orders(3e-11) == q.orders(1e-12)
    for bad in (0.0, -1e-3, math.nan, math.inf, 1e-15):
        with pytest.raises(ValueError, match="rtol"):
            q.orders(bad)


def test_panel_rule_and_grouping():
    lo, hi = np.array([0.0, 1.0]), np.array([3.0, 1.5])
    t, w = q.panel_rule(lo, hi, 3, 5)
    np.testing.assert_allclose(np.sum(w * t ** 2, axis=1), (hi ** 3 - lo ** 3) / 3, rtol=1e-14)
    counts = q.panel_count(np.zeros(4), np.array([0.1, 1.6, 3.0, 0.0]), 1.5)
    assert list(counts) == [1, 2, 2, 1]
    seen = sorted((int(k), list(i)) for k, i in q.group_by(counts))
    assert seen == [(1, [0, 3]), (2, [1, 2])]


PROFILES = {
    "power_law_0.5": ax.power_law(1.0, 0.5),
    "power_law_1.5": ax.power_law(1.0, 1.5),
    "power_law_6": ax.power_law(1.0, 6.0),
    "power_law_20": ax.power_law(1.0, 20.0),
    "tabulated_quartic": ax.tabulated(np.linspace(0, 1.2, 25), np.linspace(0, 1.2, 25) ** 4),
    "tabulated_hyperboloid": ax.tabulated(np.linspace(0, 1.0, 8),
                                          np.sqrt(np.linspace(0, 1.0, 8) ** 2 + 0.09) - 0.3),
}


@pytest.mark.parametrize("name", list(PROFILES))
def test_order_table_reaches_its_tolerance(name):
    prof = PROFILES[name]
    rho = np.array([1e-8, 1e-3, 0.1, 0.45, 0.9, 0.999, 1 - 1e-9, 1 + 1e-9, 1.01, 1.6, 2.5, 100.0])
    phi = np.array([0.3, 2.0, 4.5])
    R, P = np.meshgrid(rho, phi)
    x, y = (R * np.cos(P)).ravel(), (R * np.sin(P)).ravel()
    pm = float(ax.mean_pressure(1.0, prof))
    for c in (0.0, 0.3):
        ref = ax.surface_stress(x, y, 1.0, c, 0.3, 0.4, prof, method="quadrature", rtol=q.MIN_RTOL)
        refd = ax.surface_dpdz(x, y, 1.0, c, 0.3, 0.4, prof, method="quadrature", rtol=q.MIN_RTOL)
        for tol in (1e-6, 1e-8, 1e-10):
            s = ax.surface_stress(x, y, 1.0, c, 0.3, 0.4, prof, method="quadrature", rtol=tol)
            d = ax.surface_dpdz(x, y, 1.0, c, 0.3, 0.4, prof, method="quadrature", rtol=tol)
            for u, v, sc in [(ref[k], s[k], pm) for k in KEYS] + [(refd, d, pm)]:
                fin = np.isfinite(u)
                np.testing.assert_array_equal(np.isfinite(v), fin)
                err = np.abs(u[fin] - v[fin]) / sc / np.maximum(1.0, np.abs(u[fin]) / sc)
                assert err.max() <= tol / 10, (name, c, tol, err.max())
