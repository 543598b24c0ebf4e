"""Profiles (eq. 7, 10, 12), load relations (eq. 38, 42), the flat punch (eq. 2-3, 19, 22) and
the API's shape handling."""
import math

import numpy as np
import pytest

from stressfields.physics import axisymmetric as ax

KEYS = ("xx", "yy", "zz", "xy", "xz", "yz")


def test_power_law_n1_n2_are_cone_and_paraboloid():
    x = np.linspace(0.0, 2.0, 11)
    for pl, ref in ((ax.power_law(0.7, 1.0), ax.cone(0.7)), (ax.power_law(0.2, 2.0), ax.paraboloid(2.5))):
        for f in ("g", "dg", "d2g", "depth", "normal_force"):
            np.testing.assert_allclose(getattr(pl, f)(x), getattr(ref, f)(x), rtol=1e-15, atol=0)
        d = ref.depth(np.array([0.3, 1.7]))
        np.testing.assert_allclose(pl.contact_radius(d), [0.3, 1.7], rtol=1e-15)


def test_closed_form_relations():
    """Cone: delta = (pi/2) a tan(theta), p_m = tan(theta)/2; paraboloid: delta = a^2/R,
    F_N = 4 a^3/(3R) (docs/theory/axisymmetric.md (A3), (A5)-(A6))."""
    a = np.array([0.5, 2.0])
    cone, par = ax.cone(0.3), ax.paraboloid(4.0)
    np.testing.assert_allclose(cone.depth(a), 0.5 * math.pi * a * 0.3, rtol=1e-15)
    np.testing.assert_allclose(ax.mean_pressure(a, cone), 0.15, rtol=1e-15)
    np.testing.assert_allclose(par.depth(a), a ** 2 / 4.0, rtol=1e-15)
    np.testing.assert_allclose(par.normal_force(a), 4 * a ** 3 / 12.0, rtol=1e-15)
    np.testing.assert_allclose(ax.mean_pressure(a, par), 4 * a / (3 * math.pi * 4.0), rtol=1e-15)
    for prof in (cone, par, ax.power_law(1.3, 3.3), ax.power_law(2.0, 0.6)):
        np.testing.assert_allclose(prof.contact_radius(prof.depth(a)), a, rtol=1e-14)
    # eq. (10) for a power law against its definition 2 int_0^a u g'(u) du (Gauss-Legendre, n=3.3)
    pl = ax.power_law(1.3, 3.3)
    u, w = np.polynomial.legendre.leggauss(60)
    u, w = 0.5 * (u + 1) * 1.7, 0.5 * w * 1.7
    assert float(pl.normal_force(1.7)) == pytest.approx(2 * np.sum(w * u * pl.dg(u)), rel=1e-12)


@pytest.mark.parametrize("rt", [np.linspace(0.0, 1.5, 13), np.array([0.0, 0.07, 0.3, 0.31, 0.9, 1.2, 1.5]),
                                np.array([0.0, 0.5, 1.0, 1.5])], ids=["uniform13", "irregular7", "four"])
def test_tabulated_paraboloid_reproduces_paraboloid(rt):
    """A not-a-knot cubic spline reproduces f = r^2/(2R) exactly, so the tabulated route equals the
    paraboloid's closed forms up to rounding.  Measured: <= 3e-14 (in p_m, resp. p_m/a) for the
    stresses and dp/dz; asserted 1e-12."""
    R, a = 1.5, 1.2
    tab, par = ax.tabulated(rt, rt ** 2 / (2 * R) + 0.25), ax.paraboloid(R)   # f(0) != 0 is fine
    assert tab.tip_exponent == 1.0 and not tab.has_closed_form
    rho = np.array([0.0, 1e-6, 0.2, 0.5, 0.9, 1.0, 1.3, 2.0, 10.0]) * a
    x, y = rho * 0.6, rho * 0.8
    pm = float(ax.mean_pressure(a, par))
    assert float(ax.mean_pressure(a, tab)) == pytest.approx(pm, rel=1e-13)
    assert float(tab.contact_radius(par.depth(a))) == pytest.approx(a, rel=1e-13)
    for c, mu in ((0.0, 0.0), (0.5, 0.3), (0.0, 0.3)):
        st = ax.surface_stress(x, y, a, c, 0.3, mu, tab, method="quadrature", rtol=1e-10)
        sp = ax.surface_stress(x, y, a, c, 0.3, mu, par)
        dt = ax.surface_dpdz(x, y, a, c, 0.3, mu, tab, method="quadrature", rtol=1e-10)
        dp = ax.surface_dpdz(x, y, a, c, 0.3, mu, par)
        for u, v, sc in [(sp[k], st[k], pm) for k in KEYS] + [(dp, dt, pm / a)]:
            fin = np.isfinite(u)
            np.testing.assert_array_equal(np.isfinite(v), fin)
            assert np.max(np.abs(u[fin] - v[fin])) / sc < 1e-12


def test_tabulated_conical_tip_is_detected():
    rt = np.linspace(0.0, 1.0, 6)
    tab = ax.tabulated(rt, 0.4 * rt)
    assert tab.tip_exponent == 0.0
    assert float(tab.dg(0.0)) == pytest.approx(0.5 * math.pi * 0.4, rel=1e-15)
    s = ax.surface_stress(0.0, 0.0, 1.0, 0.0, 0.3, 0.0, tab, method="quadrature")
    assert s["zz"] == -np.inf


@pytest.mark.parametrize("r,f,match", [
    ([0, 1, 0.5, 2], [0, 1, 2, 3], "strictly increasing"),
    ([0, 1, 1, 2], [0, 1, 2, 3], "strictly increasing"),
    ([0, 1, 2], [0, 1, 2], "at least 4"),
    ([0, 1, 2, np.nan], [0, 1, 2, 3], "finite"),
    ([0, 1, 2, 3], [0, 1, np.inf, 3], "finite"),
    ([0, 1, 2, 3], [0, 2, 1, 3], "non-decreasing"),
    ([-1, 1, 2, 3], [0, 1, 2, 3], ">= 0"),
    ([0, 1, 2, 3], [0, 1, 2], "equal length"),
])
def test_tabulated_rejects_bad_tables(r, f, match):
    with pytest.raises(ValueError, match=match):
        ax.tabulated(np.asarray(r, dtype=float), np.asarray(f, dtype=float))


def test_tabulated_is_immutable_and_hashable():
    t1 = ax.tabulated([0, 0.5, 1, 1.5], [0, 0.1, 0.4, 0.9])
    t2 = ax.tabulated(np.array([0, 0.5, 1, 1.5]), np.array([0, 0.1, 0.4, 0.9]))
    assert t1 == t2 and hash(t1) == hash(t2)
    assert len({ax.cone(1.0), ax.cone(1.0), ax.paraboloid(1.0)}) == 2
    with pytest.raises(AttributeError):     # frozen
        t1.r = (0.0,)


def test_stick_radius_rules():
    """Eq. (38): G* u_x0 = mu E* [g(a) - g(c)], G*/E* = 2(1-nu)/(2-nu); eq. (42) gross slip."""
    nu, a = 0.3, 2.0
    gs = 2 * (1 - nu) / (2 - nu)
    for prof in (ax.cone(1.0), ax.paraboloid(3.0), ax.power_law(0.5, 2.6),
                 ax.tabulated(np.linspace(0, 2.5, 11), 0.1 * np.linspace(0, 2.5, 11) ** 3)):
        mu = np.array([0.05, 0.2, 0.5, 2.0])
        c = ax.stick_radius(a, nu, mu, 0.1, prof)
        delta = float(prof.depth(a))
        lhs = gs * 0.1 * delta                       # G* u_x0 / E*
        for ci, mi in zip(c, mu):
            if lhs >= mi * delta:
                assert ci == 0.0
            else:
                assert mi * (delta - float(prof.depth(ci))) == pytest.approx(lhs, rel=1e-10)
        assert float(ax.stick_radius(a, nu, 0.3, 0.0, prof)) == a        # no tangential load
        assert float(ax.stick_radius(a, nu, 0.0, 0.1, prof)) == 0.0      # mu = 0, u_x0 > 0
    # exactly at the onset of gross slip: G* u_x0 = mu E* delta -> c = 0
    assert float(ax.stick_radius(1.0, 0.0, 0.5, 0.5, ax.cone(1.0))) == 0.0
    # broadcasting
    assert ax.stick_radius(np.array([1.0, 2.0])[:, None], 0.3, np.array([0.2, 0.3, 0.4]), 0.25,
                           ax.cone(1.0)).shape == (2, 3)
    with pytest.raises(ValueError, match="ux0_over_delta"):
        ax.stick_radius(1.0, 0.3, 0.3, -0.1, ax.cone(1.0))


def _hertz_derivative(x, y, a, nu, mu, R, comps, h=1e-4):
    """Eq. (2): sigma^FP = (R/(2a)) d sigma^H/da (Richardson-extrapolated central differences of
    the paraboloid's closed forms)."""
    def s(aa):
        return ax.surface_stress(x, y, aa, 0.0, nu, mu, ax.paraboloid(R), components=comps)

    def d(hh):
        p, m = s(a + hh), s(a - hh)
        return {k: (p[k] - m[k]) / (2 * hh) for k in comps}
    d1, d2 = d(h), d(h / 2)
    return {k: R / (2 * a) * (4 * d2[k] - d1[k]) / 3 for k in comps}


def test_flat_punch_is_the_derivative_of_hertz():
    """Flat punch (eq. 3, 18, 19 per unit depth) against eq. (2) applied to the Hertz closed forms
    (1), (14)-(17); and d p/dz against the same derivative of (5), (21)."""
    R, a, nu, mu = 2.0, 1.0, 0.3, 0.25
    x = np.array([0.1, 0.5, -0.3, 1.2, -1.5, 2.0, 0.0])
    y = np.array([0.05, -0.4, 0.2, 0.3, 0.8, -1.0, 1.4])
    fp = ax.flat_punch(a)
    s = ax.surface_stress(x, y, a, 0.0, nu, mu, fp)
    ref = _hertz_derivative(x, y, a, nu, mu, R, KEYS)
    for k in KEYS:
        np.testing.assert_allclose(s[k], ref[k], rtol=1e-7, atol=1e-8, err_msg=k)
    dp = ax.surface_dpdz(x, y, a, 0.0, nu, mu, fp)
    h = 1e-4
    dh = lambda aa: ax.surface_dpdz(x, y, aa, 0.0, nu, mu, ax.paraboloid(R))  # noqa: E731
    d1 = (dh(a + h) - dh(a - h)) / (2 * h)
    d2 = (dh(a + h / 2) - dh(a - h / 2)) / h
    np.testing.assert_allclose(dp, R / (2 * a) * (4 * d2 - d1) / 3, rtol=1e-7, atol=1e-8)
    # depth scaling, both methods identical, mean pressure 2 delta/(pi a)
    fp3 = ax.flat_punch(a, 3.0)
    s3 = ax.surface_stress(x, y, a, 0.2, nu, mu, fp3, method="quadrature")
    for k in KEYS:
        np.testing.assert_allclose(s3[k], 3.0 * s[k], rtol=1e-15, atol=0)
    assert float(ax.mean_pressure(a, fp3)) == pytest.approx(6.0 / (math.pi * a), rel=1e-15)
    assert float(fp3.contact_radius(0.7)) == a


def test_components_subset_and_broadcasting():
    x = np.linspace(-2, 2, 7)[:, None]
    y = np.array([0.0, 0.3, 1.1])[None, :]
    prof = ax.paraboloid(1.0)
    for method in ("closed", "quadrature"):
        full = ax.surface_stress(x, y, 1.0, 0.4, 0.3, 0.2, prof, method=method)
        assert set(full) == set(KEYS) and all(v.shape == (7, 3) for v in full.values())
        part = ax.surface_stress(x, y, 1.0, 0.4, 0.3, 0.2, prof, components=("xz", "zz"), method=method)
        assert list(part) == ["xz", "zz"]
        for k in part:
            np.testing.assert_array_equal(part[k], full[k])
        only_xz = ax.surface_stress(x, y, 1.0, 0.4, 0.3, 0.2, prof, components=("xz",), method=method)
        np.testing.assert_array_equal(only_xz["xz"], full["xz"])
    # arrays for a, c, nu, mu broadcast too, equal to scalar calls
    mu = np.array([0.0, 0.2, 0.4])
    nu = np.array([[0.1], [0.45]])
    s = ax.surface_stress(0.3, 0.2, 1.0, 0.5, nu, mu, ax.cone(1.0))
    d = ax.surface_dpdz(0.3, 0.2, 1.0, 0.5, nu, mu, ax.cone(1.0), method="quadrature")
    assert s["xx"].shape == (2, 3) and d.shape == (2, 3)
    for i in range(2):
        for j in range(3):
            sij = ax.surface_stress(0.3, 0.2, 1.0, 0.5, float(nu[i, 0]), float(mu[j]), ax.cone(1.0))
            assert s["xx"][i, j] == sij["xx"]
    assert ax.surface_dpdz(0.3, 0.2, 1.0, 0.0, 0.3, 0.0, ax.cone(1.0)).shape == ()
