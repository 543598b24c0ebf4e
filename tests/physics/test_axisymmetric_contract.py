"""The accuracy contract of the axisymmetric family, sampled: invariants at singular points against
their exact limits, the cone's far field against 60-digit decimal arithmetic of the printed eq. (40),
and tensile tabulated data refused.  Independent routes only; nothing is copied from the code."""
import math
from decimal import Decimal, getcontext

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import stressfields as sf
from stressfields.physics import axisymmetric as ax
from stressfields.physics.invariants import singular_limits

getcontext().prec = 60


def _cone_inplane_decimal(x, y, c, nu, mu):
    """Printed eq. (40) (a = 1, p0 = 1/2), in 60-digit decimals: the cancellation of C - A and
    A^3 - C^3 costs 24 of them at r = 1e6 a."""
    x, y, c, nu, mu = (Decimal(repr(v)) for v in (x, y, c, nu, mu))
    r = (x * x + y * y).sqrt()
    X, Y = x / r, y / r
    A, C = (1 - 1 / (r * r)).sqrt(), (1 - c * c / (r * r)).sqrt()
    D1, D3, k = C - A, A ** 3 - C ** 3, mu / 2
    sxx = 2 * k * X * (D1 * (nu * X * X - (1 + nu)) + nu / 3 * (4 * X * X - 3) * D3)
    syy = -2 * nu * k * X * (D1 * X * X + (1 - 4 * Y * Y) / 3 * D3)
    sxy = k * Y * (D1 * (2 * nu * X * X - 1) + 2 * nu / 3 * (4 * X * X - 1) * D3)
    return float(sxx), float(syy), float(sxy)


@settings(derandomize=True, max_examples=60, deadline=None)
@given(nu=st.sampled_from([0.0, 0.5]) | st.floats(0.0, 0.5), rho=st.floats(10.0, 1e6),
       phi=st.floats(0.01, 1.5), c=st.floats(0.05, 0.95), mu=st.floats(0.05, 2.0))
def test_cone_far_field_relative_1e12(nu, rho, phi, c, mu):
    from stressfields.physics.axisymmetric import tangential
    x, y = rho * math.cos(phi), rho * math.sin(phi)
    one = np.array([1.0])
    got = tangential.inplane_closed(("cone", 1.0), x * one, y * one, np.hypot(x, y) * one, one, c * one, nu * one,
                                    mu * one)
    for g, e in zip(got, _cone_inplane_decimal(x, y, c, nu, mu)):
        assert float(g[0]) == pytest.approx(e, rel=1e-12, abs=1e-300)


def test_cone_sigma_yy_far_field_at_nu_half():
    """The reproducer: sigma_yy of the cone at nu = 1/2, x = 1e6 a (value ~1e-26 p_m)."""
    ds = sf.generate({"scenario": "conical", "parameters": {"x": [1e6], "y": 0.0, "nu": 0.5, "mu": 0.3,
                                                            "ux0": 0.1}}).compute()
    c = 1 - (2 * 0.5 / 1.5) * 0.1 / 0.3                  # cone stick radius c/a (A32)
    expect = _cone_inplane_decimal(1e6, 0.0, c, 0.5, 0.3)[1] / 0.5     # p0 = p_m = 1/2 per E*
    assert float(ds.sigma_yy.squeeze()) == pytest.approx(expect, rel=1e-12)


# -- invariants at singular points ------------------------------------------------------------------

def _gen(scenario, **p):
    return sf.generate({"scenario": scenario, "parameters": p}).compute()


def test_cone_tip_invariants_are_the_limits():
    """r = 0 of a cone: sigma ~ -p0 ln(2a/r) ((1+2nu)/2, (1+2nu)/2, 1) (A97): all principal
    stresses -inf, von Mises +inf for nu < 1/2; at nu = 1/2 the normal part is hydrostatic and von
    Mises is that of the stick-zone shear, sqrt(3) mu ln(a/c) p_m (c/a = 1 - k u_x0/mu, A32); 0 under
    normal load."""
    ds = _gen("conical", x=[0.0], y=0.0, nu=[0.3, 0.5], mu=0.4, ux0=[0.0, 0.25])
    vm = ds.von_mises.squeeze().values
    c = 1 - (2 * 0.5 / 1.5) * 0.25 / 0.4
    assert vm[0].tolist() == [math.inf, math.inf]
    assert vm[1, 0] == 0.0
    assert vm[1, 1] == pytest.approx(math.sqrt(3) * 0.4 * math.log(1 / c), rel=1e-12)
    assert vm[1, 1] == pytest.approx(0.3734, abs=1e-4)
    for k in ("sigma_1", "sigma_2", "sigma_3"):
        assert np.all(ds[k].values == -math.inf)
    # the limit along a ray, at r = 1e-200 a (finite there): the same signs, and at nu = 1/2 the value
    near = _gen("conical", x=[1e-200], y=[0.0, 1e-200], nu=0.5, mu=0.4, ux0=0.25)
    np.testing.assert_allclose(near.von_mises.values.ravel(), vm[1, 1], rtol=1e-12)


def test_flat_punch_edge_von_mises():
    """Flat punch edge r = a from inside: (rr, phiphi, zz) ~ -p (1, 2nu, 1): von Mises +inf for
    nu < 1/2, 0 at nu = 1/2 without tangential load; sigma_1 = -(1-2nu)... finite hoop limit at
    nu = 0: sigma_phiphi -> -P/a = -p_m/2."""
    ds = _gen("axisymmetric", profile="flat_punch", x=[1.0], y=0.0, nu=[0.0, 0.3, 0.5])
    assert ds.von_mises.values.ravel().tolist() == [math.inf, math.inf, 0.0]
    assert float(ds.sigma_1.values.ravel()[0]) == pytest.approx(-0.5, rel=1e-13)
    # the limit from inside along the ray: sigma_phiphi(r) = -(1-2nu)/(a+s) P - 2 nu P/s at nu = 0
    r = 1 - 1e-12
    near = _gen("axisymmetric", profile="flat_punch", x=[0.0], y=r, nu=0.0)
    assert float(near.sigma_xx.squeeze()) == pytest.approx(-0.5, rel=2e-6)


@settings(derandomize=True, max_examples=40, deadline=None)
@given(lead=st.lists(st.sampled_from([0.0, -1.0, 1.0]) | st.floats(0.1, 3.0) | st.floats(-3.0, -0.1), min_size=6,
                     max_size=6), lam=st.sampled_from([1e6, 1e8]))
def test_singular_limits_match_large_lambda(lead, lam):
    """The limit rules (A97) against the eigenvalues of lam * M + R for a large lam."""
    M = np.zeros((3, 3))
    M[np.triu_indices(3)] = lead
    M = M + np.triu(M, 1).T
    R = np.diag([0.3, -0.2, 0.1])
    vm, pr = singular_limits(M[None], R[None])
    big = np.linalg.eigvalsh(lam * M + R)[::-1]
    for got, b in zip(pr, big):
        if np.isinf(got[0]):
            assert np.sign(got[0]) == np.sign(b) and abs(b) > 1e-3 * lam
    assert vm[0] == math.inf or abs(vm[0]) < 10


# -- tabulated data with tensile pressure -------------------------------------------------------------

def test_tensile_tabulated_profile_is_refused():
    """The reproducer gave sigma_zz = +2.01 p_m (tension) at x = 0.6 a with validity 0.  The pressure
    at r = 0.6 a by adaptive quadrature of (A14) over the exact g' (independent of the kernels'
    rules) is tensile, and the recipe is refused, naming it."""
    from scipy.integrate import quad
    r, f = [0, 0.2, 0.4, 0.6, 0.8, 1.0], [0, 0, 0, 1, 1, 1]
    prof = ax.tabulated(r, f)
    r0 = 0.6
    p = quad(lambda t: float(prof._sums(r0 * math.cosh(t), 1)), 0, math.acosh(1 / r0),
             points=[math.acosh(0.8 / r0)], limit=200)[0] / math.pi / float(ax.mean_pressure(1.0, prof))
    assert p < -1.0
    with pytest.raises(sf.RecipeError, match="tensile"):
        sf.generate({"scenario": "axisymmetric", "parameters": {"profile": "tabulated", "profile_r": r,
                                                                 "profile_f": f, "x": [0.6], "y": 0.0}})
    # a convex table is accepted, with p >= 0 everywhere
    assert ax.min_pressure(ax.tabulated(r, np.square(r) / 2), 1.0)[0] >= 0.0


# -- Hertz–Mindlin as c -> a ------------------------------------------------------------------------

def _hm_moment(h, r, lo, hi):
    """int_lo^hi h(u) u g'(u) du / sqrt(r^2 - u^2) for g' = 2u (R = 1), hi <= r, by adaptive quad:
    u = lo + w (r - lo, hi - lo exact) off the root, u = r - v^2 onto it."""
    from scipy.integrate import quad

    def f(u):
        return h(u) * 2.0 * u * u

    opts = dict(epsabs=0.0, epsrel=2e-14, limit=200)
    if hi < r:
        d0 = r - lo
        return quad(lambda w: f(lo + w) / math.sqrt((d0 - w) * (r + lo + w)), 0.0, hi - lo, **opts)[0]
    return quad(lambda v: 2.0 * f(r - v * v) / math.sqrt(2.0 * r - v * v), 0.0, math.sqrt(r - lo), **opts)[0]


def _hm_reference(x, y, c, nu, mu):
    """(sxx, syy, sxy) of (A39)-(A41) by quadrature (polynomials regrouped with r^2 - u^2 >= 0, no
    term cancels) and sxz, dp/dz of (A35), (A56) in 60-digit decimals of the exact binary inputs;
    a = R = 1, r the kernels' hypot(x, y)."""
    r = math.hypot(x, y)
    lo, hi, r2 = min(r, c), min(r, 1.0), r * r

    def d(u):
        return (r - u) * (r + u)

    if r <= c:
        inplane = (0.0, 0.0, 0.0)
    else:
        ixx = _hm_moment(lambda u: r2 * r2 + nu * ((x * x - 3 * y * y) * d(u) + y * y * r2), r, lo, hi)
        iyy = _hm_moment(lambda u: u * u * x * x + 3 * y * y * d(u), r, lo, hi)
        ixy = _hm_moment(lambda u: (1 - 2 * nu) * r2 * r2 + 2 * nu * (u * u * y * y + 3 * x * x * d(u)), r, lo, hi)
        k = mu / (math.pi * r2 ** 3)
        inplane = (-2 * k * x * ixx, -2 * nu * k * x * iyy, -k * y * ixy)
    X, R, C, NU, MU, PI = (Decimal(float(v)) for v in (x, r, c, nu, mu, math.pi))
    sa, sc = (((b - R) * (b + R)).sqrt() if R < b else Decimal(0) for b in (Decimal(1), C))
    sxz = -MU * 2 / PI * (sa - sc)
    dp = Decimal(0) if R >= 1 else -4 * (1 + NU) * MU / (3 * PI) * X * (1 / sa - (1 / sc if R < C else 0))
    return inplane + (float(sxz), float(dp))


@pytest.mark.parametrize("eps", [1e-4, 1e-8, 1e-12])
def test_hertz_mindlin_as_c_tends_to_a(eps):
    """The stick-zone differences of (A35), (A49), (A56) lost 1/(1 - (c/a)^3) relative digits (1e-6
    relative at c/a = 1 - 1e-10); (A99)-(A101) keep 1e-12 of |value| in the stick zone, the thin
    slip annulus, next to the edge and far outside."""
    from stressfields.physics.axisymmetric import tangential
    P, one, c, nu, mu = ("paraboloid", 1.0), np.array([1.0]), 1.0 - eps, 0.3, 0.5
    for rho in (0.3, c * (1 - 0.5 * eps), c + 0.5 * eps, 1 - 0.25 * eps, 1 + 0.5 * eps, 1 + 1e-6, 1.5, 1e3):
        for phi in (0.0, 0.4, 1.2):
            x, y = rho * math.cos(phi), rho * math.sin(phi)
            r = math.hypot(x, y)
            a1 = (x * one, y * one, r * one, one, c * one, nu * one, mu * one)
            got = [float(v[0]) for v in tangential.inplane_closed(P, *a1)]
            got.append(float(tangential.shear_closed(P, r * one, one, c * one, mu * one)[0]))
            got.append(float(tangential.dpdz_closed(P, x * one, r * one, one, c * one, nu * one, mu * one)[0]))
            for name, g, e in zip(("xx", "yy", "xy", "xz", "dpdz"), got, _hm_reference(x, y, c, nu, mu)):
                assert g == pytest.approx(e, rel=1e-12, abs=1e-300), (name, rho, phi)
