"""The accuracy contract of the graded family, by seeded property tests.

Closed forms: relative error at most 1e-12 of |value| everywhere the value is finite (edges, far
field, k -> 0 and k -> 1 included); quadrature: relative error at most rtol.  Every check is against
an independent route: an analytic closed form written here (paraboloid, Hertz at k = 0), quadpack
quadrature of the defining integral (graded_reference), the scaling law in a, or the physical
identities between normal, adhesive and tangential contact (docs/theory/graded.md (G18), (G21),
(G24), (G32), (G43), (G44)).  The point is given as rho = r/a, as the scenarios do.
"""
import math

import numpy as np
from hypothesis import given, settings, strategies as st

import stressfields as sf
from stressfields.physics import graded as gp
from stressfields.physics.graded import material as M
from stressfields.physics.graded import normal as N
from graded_reference import kappa_minus_one_ref, uz_outside_ref

CF = 1e-12
RTOL = 1e-10
SETTINGS = dict(derandomize=True, deadline=None)

ks = st.one_of(st.floats(0.0, 0.999), st.floats(1.0, 12.0).map(lambda e: 1.0 - 10.0 ** -e),
               st.floats(1.0, 12.0).map(lambda e: 10.0 ** -e))
nus = st.floats(-0.9, 0.5)
radii = st.floats(-6.0, 3.0).map(lambda e: 10.0 ** e)            # a over decades (m)
ns = st.floats(0.3, 6.0)
edge = st.floats(1.0, 12.0).map(lambda e: 10.0 ** -e)            # distance of r/a to 1


def rel(x, ref):
    return float(np.max(np.abs(np.asarray(x, float) / np.asarray(ref, float) - 1.0)))


def pressure(kind, geometry, rho, a, k, nu, method="auto", E0=2e9):
    ind = getattr(gp.Indenter, kind)(*geometry)
    return gp.normal_fields(["pressure"], ind, a=a, rho=np.asarray(rho, float), k=k, nu=nu, E0=E0, c0=1.0,
                            method=method, rtol=RTOL)["pressure"]


@settings(max_examples=40, **SETTINGS)
@given(k=ks, nu=nus, a=radii, e=edge, R=st.floats(-2.0, 2.0).map(lambda x: 10.0 ** x))
def test_paraboloid_pressure_on_the_edge(k, nu, a, e, R):
    """n = 2: p = 2 c_N* a^(1+k) (1 - rho^2)^((1+k)/2) / (pi (1+k)^2 R) (eq. 22), 1 - rho^2 = (1-rho)(1+rho)."""
    rho = np.array([1.0 - e, 0.5, 0.0])
    cN = M.c_N_star(k, nu, 2e9, 1.0)
    exact = 2 * cN * a ** (1 + k) * ((1 - rho) * (1 + rho)) ** (0.5 * (1 + k)) / (math.pi * (1 + k) ** 2 * R)
    assert rel(pressure("parabolic", (R,), rho, a, k, nu), exact) <= CF


@settings(max_examples=8, **SETTINGS)
@given(k=st.floats(0.0, 0.99), a=radii, e=edge)
def test_quadrature_pressure_on_the_edge(k, a, e):
    rho = np.array([1.0 - e, 0.3])
    cN = M.c_N_star(k, 0.3, 2e9, 1.0)
    exact = 2 * cN * a ** (1 + k) * ((1 - rho) * (1 + rho)) ** (0.5 * (1 + k)) / (math.pi * (1 + k) ** 2)
    assert rel(pressure("parabolic", (1.0,), rho, a, k, 0.3, method="quadrature"), exact) <= RTOL


@settings(max_examples=30, **SETTINGS)
@given(k=ks, n=ns, a=radii, e=edge)
def test_pressure_scales_as_a_to_the_n_plus_k_minus_1(k, n, a, e):
    """p(rho a; a) = (c_N* n kappa A / pi) a^(n+k-1) Phi(rho) (G18): at fixed rho the ratio to a = 1 is exact."""
    rho = np.array([1.0 - e, 1.0 - 1e-3, 0.7])
    p_a = pressure("power_law", (0.4, n), rho, a, k, 0.25)
    p_1 = pressure("power_law", (0.4, n), rho, 1.0, k, 0.25)
    assert rel(p_a, p_1 * a ** (n + k - 1.0)) <= CF


@settings(max_examples=25, **SETTINGS)
@given(k=ks, n=st.floats(0.01, 50.0))
def test_kappa_minus_one_against_its_integral(k, n):
    assert rel(N.kappa_minus_one(n, k), kappa_minus_one_ref(n, k)) <= CF
    assert rel(N.kappa_minus_one(2.0, k), (1.0 - k) / (1.0 + k)) <= CF        # kappa(2, k) = 2/(1+k)


@settings(max_examples=30, **SETTINGS)
@given(k=ks, n=ns, a=radii, e=edge, side=st.sampled_from(["in", "edge", "out", "far"]))
def test_uz_against_quadrature_of_eq15(k, n, a, e, side):
    """Outside: quadpack of (G20); at and inside the edge: A a^n [(kappa-1) + (1 - rho^n)], both
    terms from independent routes (kappa - 1 by quadpack, 1 - rho^n from the exact 1 - rho)."""
    A = 0.7
    ind = gp.Indenter.power_law(A, n)
    rho = {"in": 1.0 - e, "edge": 1.0, "out": 1.0 + e, "far": 1.0 / e}[side]
    uz = gp.normal_fields(["uz"], ind, a=a, rho=np.array(rho), k=k)["uz"]
    if rho <= 1.0:
        ref = A * a ** n * (kappa_minus_one_ref(n, k) - math.expm1(n * math.log1p(-(1.0 - rho))))
    else:
        ref = A * a ** n * (1.0 + kappa_minus_one_ref(n, k)) * uz_outside_ref(rho, k, n)
    assert rel(uz, ref) <= CF


@settings(max_examples=20, **SETTINGS)
@given(nu=nus, a=radii, e=edge)
def test_hertz_limit_on_the_edge(nu, a, e):
    """k = 0: Hertz, p = (2 E*/(pi R)) sqrt(a^2 - r^2), E* = E0/(1 - nu^2)."""
    R, rho = 0.8, np.array([1.0 - e, 0.0])
    exact = 2 * 2e9 / (1 - nu ** 2) / (math.pi * R) * a * np.sqrt((1 - rho) * (1 + rho))
    assert rel(pressure("parabolic", (R,), rho, a, 0.0, nu), exact) <= CF


@settings(max_examples=20, **SETTINGS)
@given(k=ks, n=ns, a=radii, e=edge, method=st.sampled_from(["auto", "quadrature"]))
def test_adhesive_without_adhesion_is_normal_contact(k, n, a, e, method):
    """delta_gamma = 0: the adhesive pressure is the non-adhesive one, with the exact 0 at r = a (G44)."""
    if method == "quadrature":
        n = max(n, 1.0)                          # the quadrature route needs a tip of finite slope
    ind = gp.Indenter.power_law(0.5, n)
    rho = np.array([0.5, 1.0 - e, 1.0, 1.0 + e])
    mat = dict(k=k, nu=0.3, E0=1e9, c0=1.0)
    p = gp.adhesive_fields(["pressure"], ind, a=a, rho=rho, delta_gamma=0.0, method=method, rtol=RTOL,
                           **mat)["pressure"]
    p0 = gp.normal_fields(["pressure"], ind, a=a, rho=rho, method=method, rtol=RTOL, **mat)["pressure"]
    assert np.all(np.isfinite(p)) and p[2] == 0.0 and p[3] == 0.0
    assert rel(p[:2], p0[:2]) <= CF


@settings(max_examples=25, **SETTINGS)
@given(k=ks, n=ns, a=radii, e=edge, fx=st.floats(0.05, 1.0), mu=st.floats(0.1, 1.0))
def test_slip_annulus_traction_is_mu_times_pressure(k, n, a, e, fx, mu):
    """In the slip annulus c < r < a, tau = mu p(r; a) of the body pair (eqs. 39-40, (G32)); the
    pair of identical bodies has half the rigid-indenter c_N* (eq. 46)."""
    ind = gp.Indenter.power_law(0.5, n)
    c = (1.0 - fx) ** (1.0 / (n + k + 1.0))
    rho = np.array([1.0 - e * (1.0 - c), 0.5 * (1.0 + c)])                # both in the annulus
    tau = gp.tangential_fields(["shear_traction"], ind, a=a, rho=rho, fx=fx, mu=mu, k=k, nu=0.3, E0=1e9,
                               c0=1.0)["shear_traction"]
    p_rigid = gp.normal_fields(["pressure"], ind, a=a, rho=rho, k=k, nu=0.3, E0=1e9, c0=1.0)["pressure"]
    assert rel(tau, mu * 0.5 * p_rigid) <= CF


def test_reproducer_scenario_edge_with_small_radius():
    """The edge point r/a = 1 - 1e-12 with a = 0.00248 (before: 3.2e-5 relative error)."""
    rho = 0.999999999999
    ds = sf.generate({"scenario": "graded_normal", "parameters": {
        "profile": "parabolic", "R": 1.0, "E0": 1e9, "nu": 0.3, "k": 0.0, "contact_radius": 0.00248,
        "rho": [0.0, rho]}})
    p = ds.pressure.values.ravel()
    assert rel(p[1], p[0] * math.sqrt((1 - rho) * (1 + rho))) <= CF
    assert (ds.validity.values == 0).all()


def test_reproducer_scenario_adhesive_without_adhesion_at_the_edge():
    for method in ("auto", "quadrature"):
        ds = sf.generate({"scenario": "graded_adhesive", "method": {"method": method}, "parameters": {
            "profile": "parabolic", "R": 1.0, "E0": 1e9, "nu": 0.3, "k": 0.5, "contact_radius": 0.01,
            "delta_gamma": 0.0, "rho": [0.5, 1.0]}})
        assert ds.pressure.values.ravel()[1] == 0.0 and (ds.validity.values == 0).all()


# ---------------------------------------------------------------- stick zone (G45)-(G48)

def _stick_case(n, k, fx, method, rho):
    """tau in the stick zone and its reference: mu (c_N* n kappa A / pi) a^(n+k-1) J, J by quadpack of
    the defining integral (graded_reference.stick_zone_ref), kappa by scipy's beta (G13), c_N* of the
    pair of identical bodies (G2)."""
    from scipy.special import beta
    from graded_reference import stick_zone_ref
    a, mu, nu, E0, A = 0.003, 0.4, 0.3, 2e9, 0.7
    tau = gp.tangential_fields(["shear_traction"], gp.Indenter.power_law(A, n), a=a, rho=np.asarray(rho, float),
                               fx=fx, mu=mu, k=k, nu=nu, E0=E0, c0=1.0, method=method, rtol=RTOL)["shear_traction"]
    pref = mu * M.c_N_star(k, nu, E0, 1.0, E0, nu) * n * 0.5 * n * beta(0.5 * n, 0.5 * (1 + k)) * A / math.pi
    return tau, pref * a ** (n + k - 1.0) * np.array([stick_zone_ref(float(r), fx, k, n) for r in np.ravel(rho)])


@settings(max_examples=25, **SETTINGS)
@given(k=ks, n=ns, fx=st.floats(1.0, 12.0).map(lambda e: 10.0 ** -e) | st.floats(0.01, 0.99),
       u=st.floats(0.0, 1.0 - 1e-9))
def test_stick_zone_traction_against_its_integral(k, n, fx, u):
    """r < c: tau = mu (c_N*/pi) int_c^a g'(x)(x^2 - r^2)^(-(1-k)/2) dx as one integral (G45); before, the
    difference p(r; a) - p(r; c) lost digits like eps/fx (6e-4 relative at fx = 1e-12)."""
    c = (1.0 - fx) ** (1.0 / (n + k + 1.0))
    tau, ref = _stick_case(n, k, fx, "auto", [0.0, u * c, 0.5 * c])
    assert rel(tau, ref) <= CF


@settings(max_examples=6, **SETTINGS)
@given(k=st.floats(0.0, 0.95), n=st.floats(0.4, 3.0), fx=st.sampled_from([1e-12, 1e-6, 0.3, 0.9]))
def test_stick_zone_traction_quadrature_route(k, n, fx):
    c = (1.0 - fx) ** (1.0 / (n + k + 1.0))
    tau, ref = _stick_case(n, k, fx, "quadrature", [0.0, 0.4 * c, 0.999 * c])
    assert rel(tau, ref) <= RTOL


@settings(max_examples=20, **SETTINGS)
@given(nk=st.floats(0.3, 1.0) | st.just(1.0), k=st.floats(0.0, 0.9), fx=st.floats(1e-12, 0.999))
def test_centre_traction_under_partial_slip_is_finite(nk, k, fx):
    """r = 0, n + k <= 1, 0 < fx < 1: tau = mu (c_N* n kappa A/pi) a^(n+k-1) (1 - (c/a)^(n+k-1))/(n+k-1)
    (ln(a/c) at n + k = 1), (G47): the limit of int_c^a x^(n+k-2) dx, written here with c/a of (G33)."""
    n = nk - k
    if n <= 0.05:
        return
    tau, ref = _stick_case(n, k, fx, "auto", [0.0])
    m, L = n + k - 1.0, math.log1p(-fx) / (n + k + 1.0)
    closed = -L if m == 0.0 else -math.expm1(m * L) / m
    assert np.isfinite(tau).all() and rel(tau, ref) <= CF
    from graded_reference import stick_zone_ref
    assert rel(stick_zone_ref(0.0, fx, k, n), closed) <= CF          # (G47) against quadpack


def test_reproducer_centre_flags_under_partial_and_gross_slip():
    """The cone at k = 0 (n + k = 1): finite tau(0) with validity 0 under partial slip (before: NaN, flag 2),
    +inf with flag 1 in gross slip (fx = 1), on both routes."""
    for method in ("auto", "quadrature"):
        ds = sf.generate({"scenario": "graded_tangential", "method": {"method": method}, "parameters": {
            "profile": "conical", "tan_theta": 0.1, "E0": 1e9, "nu": 0.3, "k": 0.0, "contact_radius": 0.002,
            "mu": 0.3, "fx": [1e-12, 0.5, 1.0], "rho": [0.0, 0.5]}, "output": {"variables": ["shear_traction"]}})
        tau, flag = ds.shear_traction.values.reshape(3, 2), ds.validity.values.reshape(3, 2)
        assert np.isfinite(tau[:2]).all() and (flag[:2] == 0).all()
        assert np.isposinf(tau[2, 0]) and flag[2, 0] == 1 and flag[2, 1] == 0
        # r = 0, n + k = 1: tau = mu (c_N* kappa tan(theta)/pi) ln(a/c), ln(a/c) = -log1p(-fx)/2 (G47)
        kappa = 0.5 * math.pi                                     # (G13) at n = 1, k = 0: B(1/2, 1/2)/2
        cN = 0.5 * 1e9 / (1 - 0.3 ** 2) * M.h_N(0.0, 0.3)         # identical bodies: half of (G2)
        for i, fx in enumerate((1e-12, 0.5)):
            assert rel(tau[i, 0], 0.3 * cN * kappa * 0.1 / math.pi * -math.log1p(-fx) / 2.0) <= CF
