"""Partial-slip tangential contact of graded bodies (Hess & Popov 2016, eqs. 39-52)."""

import numpy as np
import pytest
from scipy.integrate import quad

from stressfields.physics.graded import material as M
from stressfields.physics.graded import normal as N
from stressfields.physics.graded import profiles as P
from stressfields.physics.graded import tangential as T
from graded_reference import REF, nu_of

CF = 1e-12
RTOL = 1e-10
E0, C0, MU, A = 2.5, 0.8, 0.4, 0.6
A_N = {"parabolic": 1 / (2 * 1.7), "conical": 0.3, "power_n1.5": 0.9, "power_n3": 0.9}


def rel(x, ref):
    return np.max(np.abs(np.asarray(x, float) / np.asarray(ref, float) - 1))


@pytest.mark.parametrize("case", REF["tangential"], ids=lambda c: f"{c['profile']}-k{c['k']}-nu{c['nu']}")
def test_reference_points(case):
    k, nu, n = case["k"], nu_of(case), case["n"]
    An = A_N[case["profile"]]
    assert float(case["a"]) == A and float(case["mu"]) == MU
    m = dict(k=k, nu=nu, mu=MU, n=n, A_n=An)
    assert rel(T.normal_force(A, k=k, nu=nu, E0=E0, c0=C0, n=n, A_n=An), float(case["F_N"])) < CF
    assert rel(T.stiffness_ratio(k=k, nu=nu), float(case["ratio_cN_over_cT"])) < CF
    assert rel(T.max_tangential_displacement(A, **m), float(case["delta_x_max"]["value_str"])) < CF
    F = np.array([row["Fx_over_muFN"] for row in case["table"]])
    c_ref = np.array([float(row["c_over_a"]["value_str"]) for row in case["table"]])
    d_ref = np.array([float(row["delta_x"]["value_str"]) for row in case["table"]])
    D_ref = np.array([float(row["delta_over_delta_max"]) for row in case["table"]])
    assert rel(T.stick_radius(A, F, k=k, n=n) / A, c_ref) < CF
    assert rel(T.tangential_displacement(A, F, **m), d_ref) < CF
    assert rel(T.force_ratio_from_displacement(D_ref, k=k, n=n), F) < CF
    # quadrature route: bisection on eqs. (41)-(43)
    prof = P.PowerLaw(A=An, n=n)
    assert rel(T.stick_radius_quad(A, F, prof, k=k, nu=nu, E0=E0, c0=C0, rtol=RTOL) / A, c_ref) < 10 * RTOL
    assert rel(T.tangential_displacement_quad(A, F, prof, k=k, nu=nu, mu=MU, E0=E0, c0=C0,
                                              rtol=RTOL), d_ref) < 10 * RTOL


@pytest.mark.parametrize("k, tol", [(0.0, 1e-13), (1e-6, 1e-5)])
def test_cattaneo_mindlin_limit(k, tol):
    R, nu = 1.7, 0.3
    n, An = P.parabolic(R)
    G = E0 / (2 * (1 + nu))
    F = np.array([0.0, 0.2, 0.7, 1.0])
    FN = 4 * (E0 / (2 * (1 - nu ** 2))) * A ** 3 / (3 * R)          # two identical bodies
    assert T.normal_force(A, k=k, nu=nu, E0=E0, c0=C0, n=n, A_n=An) == pytest.approx(FN, rel=tol)
    dmax = 3 * MU * FN * (2 - nu) / (8 * G * A)
    m = dict(k=k, nu=nu, mu=MU, n=n, A_n=An)
    assert T.max_tangential_displacement(A, **m) == pytest.approx(dmax, rel=tol)
    assert np.allclose(T.stick_radius(A, F, k=k, n=n), A * (1 - F) ** (1 / 3), rtol=tol, atol=0)
    assert np.allclose(T.tangential_displacement(A, F, **m), dmax * (1 - (1 - F) ** (2 / 3)), rtol=tol, atol=0)


@pytest.mark.parametrize("k", [0.0, 0.3, 0.9, 0.999])
def test_holl_ratio_eq52(k):
    R = 1.7
    nu = 1 / (2 + k)
    dmax = T.max_tangential_displacement(A, k=k, nu=nu, mu=MU, n=2.0, A_n=1 / (2 * R))
    assert dmax == pytest.approx((3 + k) / 2 * MU * A ** 2 / R, rel=CF)
    # rigid body against a Holl-ratio body: same delta_x (ratio unchanged), twice the normal force
    rigid = T.max_tangential_displacement(A, k=k, nu=nu, mu=MU, n=2.0, A_n=1 / (2 * R), E0=E0, E0_2=np.inf)
    assert rigid == pytest.approx(dmax, rel=CF)
    FN_rigid = T.normal_force(A, k=k, nu=nu, E0=E0, c0=C0, n=2.0, A_n=1 / (2 * R), E0_2=np.inf)
    assert FN_rigid == pytest.approx(2 * T.normal_force(A, k=k, nu=nu, E0=E0, c0=C0, n=2.0, A_n=1 / (2 * R)), rel=CF)


def test_thirty_percent_claim():
    """Paper: 'about 30 % larger' delta_x,max at k = 0.9 (same a, R, mu; Holl ratio)."""
    d09 = T.max_tangential_displacement(A, k=0.9, nu=1 / 2.9, mu=MU, n=2.0, A_n=0.3)
    d0 = T.max_tangential_displacement(A, k=0.0, nu=0.5, mu=MU, n=2.0, A_n=0.3)
    assert d09 / d0 == pytest.approx(1.30, rel=1e-12)


@pytest.mark.parametrize("k", [1e-6, 0.5, 0.999])
@pytest.mark.parametrize("n, An", [(1.0, 0.3), (2.0, 0.3), (3.0, 0.9)])
def test_shear_traction_balances_tangential_force(k, n, An):
    nu, Fr = 0.3, 0.6
    m = dict(k=k, nu=nu, mu=MU, E0=E0, c0=C0, n=n, A_n=An)
    c = float(T.stick_radius(A, Fr, k=k, n=n))
    tau = lambda r: 2 * np.pi * r * float(T.shear_traction(r, A, Fr, **m))  # noqa: E731
    # split at the stick radius (cusp of p(r; c)); edge weight (a - r)^((1+k)/2) on the slip annulus
    b = 0.5 * (1 + k)
    inner = quad(tau, 0, c, epsrel=1e-11, limit=400)[0]
    outer = quad(lambda r: tau(min(r, A * (1 - 1e-13))) / (A - min(r, A * (1 - 1e-13))) ** b, c, A,
                 weight="alg", wvar=(0, b), epsrel=1e-11, limit=200)[0]
    FN = T.normal_force(A, k=k, nu=nu, E0=E0, c0=C0, n=n, A_n=An)
    assert inner + outer == pytest.approx(Fr * MU * FN, rel=1e-8)
    # slip zone: tau = mu p; stick zone: tau < mu p
    r = np.array([0.5 * c, 0.5 * (c + A)])
    p = N.pressure(r, A, k=k, nu=nu, E0=E0, c0=C0, n=n, A_n=An, E0_2=E0, nu_2=nu)
    t = T.shear_traction(r, A, Fr, **m)
    assert t[1] == pytest.approx(MU * p[1], rel=1e-14) and 0 < t[0] < MU * p[0]


def test_decoupling_errors_and_override():
    kw = dict(mu=MU, n=2.0, A_n=0.3)
    # rigid counter-body with nu != 1/(2+k): coupled -> error naming nu and the allowed value
    with pytest.raises(ValueError, match=r"nu = 0.3 .*k = 0.5.*1/\(2\+k\) = 0.4"):
        T.tangential_displacement(A, 0.5, k=0.5, nu=0.3, E0=E0, E0_2=np.inf, **kw)
    with pytest.raises(ValueError, match=r"nu = 0.3 .*identical or both"):
        T.max_tangential_displacement(A, k=0.5, nu=0.3, E0=E0, E0_2=3 * E0, nu_2=0.3, **kw)
    with pytest.raises(ValueError, match="nu = "):
        T.shear_traction(0.1, A, 0.5, k=np.array([0.5, 0.2]), nu=0.4, E0=E0, c0=C0, E0_2=np.inf, **kw)
    # allowed: rigid + Holl, identical, both Holl
    T.tangential_displacement(A, 0.5, k=0.5, nu=0.4, E0=E0, E0_2=np.inf, **kw)
    T.tangential_displacement(A, 0.5, k=0.5, nu=0.3, **kw)
    T.tangential_displacement(A, 0.5, k=0.5, nu=0.4, E0=E0, E0_2=7.0, nu_2=0.4, **kw)
    # override: the uncoupled approximation, flagged by the predicate instead
    k = np.array([0.2, 0.5])
    d = T.tangential_displacement(A, 0.5, k=k, nu=0.4, E0=E0, E0_2=np.inf, require_decoupled=False, **kw)
    assert np.all(np.isfinite(d))
    assert list(M.tangential_decoupled(k, 0.4, E0_2=np.inf)) == [False, True]


def test_domain_and_broadcasting():
    with pytest.raises(ValueError, match=r"Fx_over_muFN = 1.2 .*0.0 <= Fx_over_muFN <= 1.0"):
        T.stick_radius(A, 1.2, k=0.5)
    with pytest.raises(ValueError, match="mu = -0.1"):
        T.max_tangential_displacement(A, k=0.5, nu=0.3, mu=-0.1, n=2.0, A_n=0.3)
    with pytest.raises(ValueError, match="k = 1.0"):
        T.stick_radius(A, 0.5, k=1.0)
    k = np.array([0.0, 0.5, 0.9])[:, None, None]
    nu = np.array([0.25, 0.35])[None, :, None]
    F = np.linspace(0, 1, 5)
    d = T.tangential_displacement(A, F, k=k, nu=nu, mu=MU, n=2.0, A_n=0.3)
    assert d.shape == (3, 2, 5) and np.all(np.diff(d, axis=-1) > 0) and np.all(d[..., 0] == 0)
    np.testing.assert_allclose(d[..., -1], T.max_tangential_displacement(A, k=k, nu=nu, mu=MU, n=2.0, A_n=0.3)[..., 0],
                               rtol=1e-15)
