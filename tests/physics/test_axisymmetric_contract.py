"""The accuracy contract of the axisymmetric family, sampled: invariants at singular points against
their exact limits, the cone's far field against 60-digit decimal arithmetic of the printed eq. (40),
tensile tabulated data refused, and seeded properties: closed forms against the quadrature route,
the MDR-free relation (A17) against scipy quadrature of the pressure, symmetry in y and rotational
invariance, physical = normalised times the scale.  Independent routes only; nothing is copied from
the code."""
import math
from decimal import Decimal, getcontext

import numpy as np
import pytest
from hypothesis import Phase, assume, given, settings
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.special import gammaln

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


# -- seeded properties of the contract --------------------------------------------------------------
#
# Units below: a = 1, stresses in p_m, dp/dz in p_m/a (the fields per unit E* divided by p_m/E*), so
# the normalisation S of the contract is 1 for every valued field.


_VALUED = ax.STRESS + ("dpdz",)
_EVEN = ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz", "dpdz")
_ODD = ("sigma_xy", "sigma_yz")
_RTOLS = st.sampled_from([1e-6, 1e-10])
_NU = st.sampled_from([0.0, 0.5]) | st.floats(0.0, 0.5)
_MU = st.sampled_from([0.0, 1.0]) | st.floats(0.0, 1.0)
_UX0 = st.sampled_from([0.0]) | st.floats(1e-3, 2.0)      # u_x0/delta; large values reach gross slip
_EPS = st.floats(1e-12, 1e-2)                             # distance to an edge, relative
_PHI = st.sampled_from([0.0, math.pi / 2, math.pi, -math.pi / 2]) | st.floats(-math.pi, math.pi)


def _closed_profile(kind, amp):
    """The profiles with closed forms (routes.py): cone, paraboloid, power law n = 1 and n = 2."""
    return {"cone": lambda: ax.cone(amp), "paraboloid": lambda: ax.paraboloid(amp),
            "pl1": lambda: ax.power_law(amp, 1.0), "pl2": lambda: ax.power_law(amp, 2.0)}[kind]()


@st.composite
def _radii(draw, where=("axis", "stick", "edge", "far", "any")):
    """r/a of a few points: the axis r = 0 (and r -> 0 down to 1e-150; below, where r^2 is subnormal
    or zero, see the reproducers after this test), both sides of the stick edge r = c
    (returned as ("stick", eps, side), resolved once c is known), both sides of the contact edge,
    the far field up to 1e6 a, anywhere in [0, 3]."""
    out = []
    for kind in draw(st.lists(st.sampled_from(where), min_size=4, max_size=8)):
        side = draw(st.sampled_from([-1.0, 1.0]))
        if kind == "axis":
            out.append(draw(st.sampled_from([0.0, 1e-150, 1e-12]) | st.floats(1e-9, 1e-3)))
        elif kind == "stick":
            out.append(("stick", draw(_EPS), side))
        elif kind == "edge":
            out.append(1.0 + side * draw(_EPS))
        elif kind == "far":
            out.append(10.0 ** draw(st.floats(0.3, 6.0)))
        else:
            out.append(draw(st.floats(0.0, 3.0)))
    return out


def _points(radii, phis, c):
    rho = np.array([c * (1.0 + r[2] * r[1]) if isinstance(r, tuple) else r for r in radii])
    phi = np.resize(np.asarray(phis, dtype=float), rho.size)
    # x = 0 and y = 0 exactly on the axes (cos(pi/2) is 6e-17, not 0)
    x = np.where(np.isin(phi, [math.pi / 2, -math.pi / 2]), 0.0, rho * np.cos(phi))
    y = np.where(np.isin(phi, [0.0, math.pi]), 0.0, rho * np.sin(phi))
    return x, y


def _normalised(profile, x, y, nu, mu, ux0, method="auto", rtol=1e-10, names=_VALUED + ("validity",)):
    pm = float(ax.mean_pressure(1.0, profile))
    vals, route = ax.fields(names, profile, x, y, a=1.0, nu=nu, mu=mu, ux0=ux0, method=method, rtol=rtol)
    # per unit E* -> units of p_m (and p_m/a for dp/dz, a = 1)
    return {n: v if n == "validity" else v / pm for n, v in vals.items()}, route


def _same_singular_points(u, v, name):
    """Both routes agree on where a value is +-inf (with the sign) or NaN."""
    np.testing.assert_array_equal(np.isnan(v), np.isnan(u), err_msg=name)
    np.testing.assert_array_equal(v[np.isinf(u)], u[np.isinf(u)], err_msg=name)
    np.testing.assert_array_equal(np.isinf(v), np.isinf(u), err_msg=name)


@settings(derandomize=True, max_examples=60, deadline=None)
@given(kind=st.sampled_from(["cone", "paraboloid", "pl1", "pl2"]), amp=st.floats(0.05, 5.0), nu=_NU, mu=_MU,
       ux0=_UX0, rtol=_RTOLS, radii=_radii(), phis=st.lists(_PHI, min_size=1, max_size=4))
def test_property_closed_vs_quadrature(kind, amp, nu, mu, ux0, rtol, radii, phis):
    """The quadrature route within rtol * max(|value|, S) of the closed forms, which are within
    1e-12 |value| of the exact value: |quad - closed| <= rtol max(|v|, S) + 1e-12 |v|, at the
    axis, both sides of both edges and the far field; the same singular points."""
    profile = _closed_profile(kind, amp)
    c = float(ax.stick_radius(1.0, nu, mu, ux0, profile))
    x, y = _points(radii, phis, c)
    closed, rc = _normalised(profile, x, y, nu, mu, ux0, method="closed")
    quadr, rq = _normalised(profile, x, y, nu, mu, ux0, method="quadrature", rtol=rtol)
    assert rc.kernel == "closed" and rq.kernel == "quadrature"
    for name in _VALUED:
        u, v = closed[name], quadr[name]
        _same_singular_points(u, v, name)
        fin = np.isfinite(u)
        bound = rtol * np.maximum(np.abs(u[fin]), 1.0) + 1e-12 * np.abs(u[fin])
        bad = np.abs(v[fin] - u[fin]) > bound
        assert not bad.any(), (name, x[fin][bad], y[fin][bad], u[fin][bad], v[fin][bad], c)
    np.testing.assert_array_equal(closed["validity"], quadr["validity"])


def test_cone_gross_slip_closed_near_axis_reproducer():
    """At r = 1e-200 a on y = 0 (nu = 0, mu = 1, gross slip c = 0) the exact sigma_xx / p_m is the
    normal part (A20), p0 [B/2 - L/2] with B = 1/2 + O(r^2), L = ln(2a/r) + O(r^2), plus the
    tangential part (A50) with C = 1, A = 0, X = 1: -2 mu p0.  Both routes; the closed one once
    formed C = sqrt_diff(r, c)/r, whose r*r underflowed, and gave the normal part alone (2 p_m off)."""
    r = 1e-200
    expect = 0.25 - 0.5 * math.log(2.0 / r) - 2.0
    for method in ("quadrature", "closed"):
        got, _ = _normalised(ax.cone(1.0), np.array([r]), np.array([0.0]), 0.0, 1.0, 1.0, method=method)
        assert float(got["sigma_xx"][0]) == pytest.approx(expect, rel=1e-12), method


def test_quadrature_normal_subnormal_radius_reproducer():
    """sigma_xy of the cone under normal load at r = 1e-160 a, direction (0.6, 0.8): exactly
    (sigma_rr - sigma_phiphi) X Y = p0 (1 - 2 nu) B X Y (A20), (A22), B = 1/2 + O(r^2): 0.24 p_m at
    nu = 0.  Both routes; the quadrature one once divided F(r) by a subnormal r^2 (1.1e-4 p_m off)."""
    r = 1e-160
    for method in ("closed", "quadrature"):
        got, _ = _normalised(ax.cone(1.0), np.array([0.6 * r]), np.array([0.8 * r]), 0.0, 0.0, 0.0, method=method)
        assert abs(float(got["sigma_xy"][0]) - 0.24) <= 1e-10, method


# -- the MDR-free relation (A17) against scipy quadrature of the pressure ---------------------------

def _kappa(n):
    """kappa_n = sqrt(pi) Gamma(n/2 + 1) / Gamma(n/2 + 1/2) of g = kappa_n A |x|^n (A7)."""
    return math.sqrt(math.pi) * math.exp(gammaln(0.5 * n + 1.0) - gammaln(0.5 * n + 0.5))


def _pressure(terms, s):
    """p(s) / E* = (1/pi) int_s^1 g'(u) du / sqrt(u^2 - s^2) (A14), a = 1, for f = sum A r^n
    (g' = sum kappa_n A n u^(n-1)), by adaptive quadrature in u = s cosh t (smooth integrand)."""
    if s >= 1.0:
        return 0.0
    top = math.log1p((1.0 - s + math.sqrt((1.0 - s) * (1.0 + s))) / s)     # arccosh(1/s)
    out = 0.0
    for amp, n in terms:
        b = _kappa(n) * amp * n
        out += b * quad(lambda t: (s * math.cosh(t)) ** (n - 1.0), 0.0, top, epsabs=0.0, epsrel=1e-13,
                        limit=200)[0]
    return out / math.pi


def _load_inside(terms, r):
    """int_0^min(r, 1) p(s) s ds, by adaptive quadrature of the quadrature above, in s = sin(th):
    p ~ sqrt(1 - s) at the edge becomes smooth (10x fewer evaluations than in s)."""
    top = math.asin(min(r, 1.0))
    return quad(lambda th: _pressure(terms, math.sin(th)) * math.sin(th) * math.cos(th), 0.0, top, epsabs=0.0,
                epsrel=1e-12, limit=200)[0]


def _power_terms(kind, amp, n, coef):
    """(profile, [(A, n), ...]) with f = sum A r^n; a tabulated table of a polynomial of degree <= 3
    with non-negative coefficients (monotone, convex: p >= 0) is the not-a-knot spline exactly."""
    if kind == "cone":
        return ax.cone(amp), [(amp, 1.0)]
    if kind == "paraboloid":
        return ax.paraboloid(amp), [(0.5 / amp, 2.0)]
    if kind == "power_law":
        return ax.power_law(amp, n), [(amp, n)]
    knots, terms = coef
    r = np.concatenate([[0.0], np.sort(knots), [1.25]])
    f = sum(A * r ** k for A, k in terms)
    return ax.tabulated(r, f), terms


_TAB = st.tuples(st.lists(st.floats(0.05, 1.2), min_size=3, max_size=6, unique=True),
                 st.sampled_from([[(1.0, 2.0)], [(0.3, 1.0), (1.0, 2.0)], [(1.0, 2.0), (0.7, 3.0)],
                                  [(0.2, 1.0), (0.5, 2.0), (1.5, 3.0)], [(1.0, 3.0)]]))


@settings(derandomize=True, max_examples=25, deadline=None)
@given(kind=st.sampled_from(["cone", "paraboloid", "power_law", "tabulated"]), amp=st.floats(0.2, 3.0),
       n=st.floats(0.3, 6.0), coef=_TAB, nu=_NU, mu=_MU,
       radii=_radii(where=("edge", "far", "any")))
def test_property_mdr_free_surface_relation(kind, amp, n, coef, nu, mu, radii):
    """Under normal load (u_x0 = 0, any mu) sigma_rr = -p + ((1 - 2nu)/r^2) int_0^r p s ds,
    sigma_phiphi = -2nu p - ((1 - 2nu)/r^2) int_0^r p s ds and sigma_zz = -p (A17), p by scipy
    quadrature of (A14) and p_m = 2 int_0^a p s ds / a^2 from it, on y = 0 (sigma_xx = sigma_rr,
    sigma_yy = sigma_phiphi).  Bound: rtol max(|v|, p_m) of the quadrature route (rtol 1e-8) or the
    closed forms, checked at 1e-10 max(|v|, p_m), the accuracy of the nested scipy quadrature."""
    profile, terms = _power_terms(kind, amp, n, coef)
    # r >= 1e-6: below, the reference's w / r^2 = p/2 + O(r) is not resolved by quadrature
    rho = np.array([r for r in radii if 1e-6 <= r <= 1e4])
    assume(rho.size > 0)
    got, route = _normalised(profile, rho, np.zeros_like(rho), nu, mu, 0.0, rtol=1e-8,
                             names=("sigma_xx", "sigma_yy", "sigma_zz"))
    tol = 1e-8 if route.kernel == "quadrature" else 1e-10
    pm = 2.0 * _load_inside(terms, 1.0)
    for i, r in enumerate(rho):
        p, w = _pressure(terms, r) / pm, (_load_inside(terms, r) if r < 1.0 else 0.5 * pm) / pm
        expect = {"sigma_xx": -p + (1 - 2 * nu) * w / r ** 2, "sigma_yy": -2 * nu * p - (1 - 2 * nu) * w / r ** 2,
                  "sigma_zz": -p}
        for name, e in expect.items():
            assert abs(got[name][i] - e) <= tol * max(abs(e), 1.0), (name, r, got[name][i], e)


def test_mdr_free_relation_flat_punch():
    """The flat punch: p = P / sqrt(a^2 - r^2), int_0^r p s ds = P (a - sqrt(a^2 - r^2)), p_m = 2P/a
    (a = 1): (A17) at points inside, next to the edge and outside."""
    rho = np.array([1e-12, 0.3, 0.9, 1 - 1e-6, 1 + 1e-9, 1.5, 1e3, 1e6])
    for nu in (0.0, 0.3, 0.5):
        got, _ = _normalised(ax.flat_punch(1.0), rho, np.zeros_like(rho), nu, 0.0, 0.0,
                             names=("sigma_xx", "sigma_yy", "sigma_zz"))
        s = np.sqrt(np.maximum((1 - rho) * (1 + rho), 0.0))
        p = np.where(rho < 1, 0.5 / np.where(rho < 1, s, 1.0), 0.0)
        w = 0.5 * np.where(rho < 1, rho * rho / (1 + s), 1.0)        # (a - s) = r^2/(a + s)
        np.testing.assert_allclose(got["sigma_zz"], -p, rtol=1e-12, atol=0)
        np.testing.assert_allclose(got["sigma_xx"], -p + (1 - 2 * nu) * w / rho ** 2, rtol=1e-12, atol=1e-300)
        np.testing.assert_allclose(got["sigma_yy"], -2 * nu * p - (1 - 2 * nu) * w / rho ** 2, rtol=1e-12,
                                   atol=1e-300)


# -- symmetry in y and rotational invariance --------------------------------------------------------

def _any_profile(kind, amp, n, coef):
    if kind == "flat_punch":
        return ax.flat_punch(1.0)
    return _power_terms(kind, amp, n, coef)[0]


def _bound(route, rtol, v):
    """The contract's error bound on one value (S = 1 in these units)."""
    return 1e-12 * np.abs(v) if route.kernel == "closed" else rtol * np.maximum(np.abs(v), 1.0)


@settings(derandomize=True, max_examples=40, deadline=None)
@given(kind=st.sampled_from(["cone", "paraboloid", "power_law", "tabulated", "flat_punch"]), amp=st.floats(0.2, 3.0),
       n=st.floats(0.3, 6.0), coef=_TAB, nu=_NU, mu=_MU, ux0=_UX0, radii=_radii(),
       phis=st.lists(_PHI, min_size=1, max_size=4), turn=st.floats(0.0, 2 * math.pi))
def test_property_symmetry_and_rotation(kind, amp, n, coef, nu, mu, ux0, radii, phis, turn):
    """Mirror y -> -y (the tangential load is along x): sigma_xy, sigma_yz odd, the rest even, the
    validity flag the same; each side within the contract of the exact value, so they differ by at
    most twice the bound.  Under normal load (u_x0 = 0) sigma_rr, sigma_phiphi, sigma_zz, dp/dz
    depend on r only: the tensor rotated to polar axes at angle phi + turn against phi = 0 (y = 0),
    within 3 bounds of the largest in-plane component (rotation weights X^2 + Y^2 + 2|XY| <= 2)."""
    profile = _any_profile(kind, amp, n, coef)
    rtol = 1e-10
    c = float(ax.stick_radius(1.0, nu, mu, ux0, profile))
    x, y = _points(radii, phis, c)
    up, route = _normalised(profile, x, y, nu, mu, ux0, rtol=rtol)
    down, _ = _normalised(profile, x, -y, nu, mu, ux0, rtol=rtol)
    np.testing.assert_array_equal(up["validity"], down["validity"])
    for name in _VALUED:
        u, v = up[name], (-1.0 if name in _ODD else 1.0) * down[name]
        _same_singular_points(u, v, name)
        fin = np.isfinite(u)
        assert np.all(np.abs(u[fin] - v[fin]) <= 2 * _bound(route, rtol, u[fin])), name
    # rotational invariance under normal load
    rho = np.hypot(x, y)
    rho = rho[(rho > 0) & np.isfinite(rho)]
    assume(rho.size > 0)
    phi = np.resize(np.asarray(phis), rho.size) + turn
    X, Y = np.cos(phi), np.sin(phi)
    turned, _ = _normalised(profile, rho * X, rho * Y, nu, mu, 0.0, rtol=rtol)
    # on y = 0 at the rotated point's own r = hypot(x, y): 1 ulp of r changes the value by 5e-5 of
    # it at 1e-12 from the edge, which is not what this property is about
    on_x, _ = _normalised(profile, np.hypot(rho * X, rho * Y), np.zeros_like(rho), nu, mu, 0.0, rtol=rtol)
    sxx, syy, sxy = (turned[k] for k in ("sigma_xx", "sigma_yy", "sigma_xy"))
    polar = {"sigma_xx": sxx * X * X + syy * Y * Y + 2 * sxy * X * Y,          # sigma_rr
             "sigma_yy": sxx * Y * Y + syy * X * X - 2 * sxy * X * Y}          # sigma_phiphi
    big = np.maximum(np.abs(on_x["sigma_xx"]), np.abs(on_x["sigma_yy"]))
    for name in ("sigma_xx", "sigma_yy"):
        fin = np.isfinite(on_x[name]) & np.isfinite(polar[name])
        assert np.all(np.abs(polar[name] - on_x[name])[fin] <= 3 * _bound(route, rtol, big[fin])), name
    for name in ("sigma_zz", "dpdz"):
        u, v = on_x[name], turned[name]
        _same_singular_points(u, v, name)
        fin = np.isfinite(u)
        assert np.all(np.abs(u[fin] - v[fin]) <= 2 * _bound(route, rtol, u[fin])), name
    assert np.all(turned["sigma_xz"] == 0) and np.all(turned["sigma_yz"] == 0)


# -- physical = normalised times the scale, through sf.generate --------------------------------------

def _geometry(kind, E, nu, delta, shape):
    """(recipe geometry, a, p_m) from the load relations (A3)-(A8), computed here."""
    e_star = E / (1 - nu * nu)
    if kind == "conical":
        a = 2 * delta / (math.pi * math.tan(shape))
        return {"theta": shape}, a, e_star * math.tan(shape) / 2
    if kind == "parabolic":
        a = math.sqrt(shape * delta)
        return {"R": shape}, a, 4 * e_star * a / (3 * math.pi * shape)
    if kind == "flat_punch":
        return {"profile": "flat_punch", "radius": shape}, shape, 2 * e_star * delta / (math.pi * shape)
    n, A = 2.5, shape
    a = (delta / (_kappa(n) * A)) ** (1 / n)
    return ({"profile": "power_law", "n": n, "A": A}, a,
            2 * e_star * _kappa(n) * A * n * a ** (n - 1) / ((n + 1) * math.pi))


@settings(derandomize=True, max_examples=12, deadline=None, phases=(Phase.explicit, Phase.generate))
@given(kind=st.sampled_from(["conical", "parabolic", "flat_punch", "power_law"]), E=st.floats(1e6, 1e12),
       nu=_NU, mu=st.floats(0.05, 1.0), ux0=st.floats(0.0, 0.3), delta=st.floats(1e-7, 1e-3),
       shape=st.floats(0.05, 1.4), xs=st.lists(st.floats(-3.0, 3.0), min_size=2, max_size=4, unique=True),
       y=st.floats(-2.0, 2.0))
def test_property_physical_equals_normalised(kind, E, nu, mu, ux0, delta, shape, xs, y):
    """The same recipe with E, delta and the geometry (theta, R, A, radius) in pascals and metres is
    the normalised one times p_m (stresses), p_m/a (dpdz), a (lengths), with a and p_m from (A3)-(A8)
    here.  Points 1e-3 a or more from both edges (1 ulp of x a / a is a relative change there of at
    most 1e-13); each mode within the contract, so they differ by at most twice its bound (the power
    law n = 2.5 takes the quadrature route at rtol = 1e-10)."""
    geo, a, pm = _geometry(kind, E, nu, delta, shape)
    c = 1 - (2 * (1 - nu) / (2 - nu)) * ux0 / mu          # (A32) for the cone; used to stay off r = c
    rad = {"conical": c, "parabolic": math.sqrt(max(c, 0)), "power_law": max(c, 0) ** (1 / 2.5)}.get(kind, 1.0)
    xs = sorted(v for v in xs if min(abs(math.hypot(v, y) - 1), abs(math.hypot(v, y) - rad)) > 1e-3)
    assume(xs)
    base = {"nu": nu, "mu": mu, "ux0": ux0, "y": y}
    if kind in ("flat_punch", "power_law"):
        base["profile"] = geo["profile"]
        if kind == "power_law":
            base["n"] = geo["n"]
    scenario = {"conical": "conical", "parabolic": "parabolic"}.get(kind, "axisymmetric")
    names = list(_VALUED) + ["von_mises", "sigma_1", "sigma_2", "sigma_3", "stick_radius", "region",
                             "mean_pressure"]
    norm = sf.generate({"scenario": scenario, "parameters": dict(base, x=xs),
                        "output": {"variables": names}}).compute(scheduler="synchronous")
    phys = sf.generate({"scenario": scenario, "parameters": dict(base, **geo, E=E, delta=delta, y=y * a,
                                                                 x=[v * a for v in xs]),
                        "output": {"variables": names + ["contact_radius", "normal_force"]}}
                       ).compute(scheduler="synchronous")
    assert phys.attrs["stressfields_units_mode"] == "physical"
    quadrature = kind == "power_law"
    for name in ax.STRESS + ("von_mises", "sigma_1", "sigma_2", "sigma_3", "dpdz"):
        u = norm[name].values.ravel()
        v = phys[name].values.ravel() / (pm / a if name == "dpdz" else pm)
        _same_singular_points(u, v, name)
        fin = np.isfinite(u)
        bound = 2e-10 * np.maximum(np.abs(u), 1.0) if quadrature else 2e-12 * np.abs(u)
        assert np.all(np.abs(v[fin] - u[fin]) <= bound[fin]), (name, u, v)
    np.testing.assert_array_equal(phys.region.values, norm.region.values)
    np.testing.assert_array_equal(phys.validity.values, norm.validity.values)
    assert float(phys.stick_radius) / a == pytest.approx(float(norm.stick_radius), rel=1e-12, abs=1e-300)
    assert float(phys.mean_pressure) == pytest.approx(pm, rel=1e-12)
    assert float(phys.contact_radius) == pytest.approx(a, rel=1e-12)
    assert float(phys.normal_force) == pytest.approx(math.pi * a * a * pm, rel=1e-12)
