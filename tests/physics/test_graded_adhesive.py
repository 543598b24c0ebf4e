"""Adhesive normal contact on the power-law graded half-space (Hess & Popov 2016, eqs. 27-38, Table 3)."""

import numpy as np
import pytest

from stressfields.physics.graded import adhesive as AD
from stressfields.physics.graded import material as M
from stressfields.physics.graded import normal as N
from stressfields.physics.graded import profiles as P
from graded_reference import REF, nu_of

CF = 1e-12
RTOL = 1e-10
E0, C0, DG = 2.5, 0.8, 0.05


def close(x, ref, tol, scale=None):
    """|x - ref| <= tol * max(|ref|, scale): 'scale' covers values that are differences of larger
    terms (d = g - Delta l; d_c = 0 exactly when n C = 1, docs/theory/graded.md (G28))."""
    ref = np.asarray(ref, float)
    bound = tol * np.maximum(np.abs(ref), 0.0 if scale is None else scale)
    return np.all(np.abs(np.asarray(x) - ref) <= bound)


@pytest.mark.parametrize("case", REF["adhesive"], ids=lambda c: f"{c['profile']}-k{c['k']}-nu{c['nu']}")
def test_reference_points(case):
    k, nu, n, An = case["k"], nu_of(case), case["n"], float(case["A_n"])
    assert float(case["delta_gamma"]) == DG
    m = dict(k=k, nu=nu, E0=E0, c0=C0, delta_gamma=DG)
    prof = P.PowerLaw(A=An, n=n)
    at = case["at_a"]
    a = float(at["a"])
    dl = float(at["delta_l_max"])
    assert close(AD.delta_l_max(a, **m), dl, CF)
    for name, cf, q in (("d", AD.depth(a, n=n, A_n=An, **m), AD.depth_quad(a, prof, rtol=RTOL, **m)),
                        ("F_N", AD.normal_force(a, n=n, A_n=An, **m), AD.normal_force_quad(a, prof, rtol=RTOL, **m))):
        ref = float(at[name]["value_str"])
        assert close(cf, ref, CF), name
        assert close(q, ref, RTOL), name
    if "p_eq37" in at:
        r = np.array([p["r_over_a"] for p in at["p_eq37"]]) * a
        ref = np.array([float(p["value_str"]) for p in at["p_eq37"]])
        assert close(AD.pressure(r, a, n=n, A_n=An, **m), ref, CF)
        assert close(AD.pressure_quad(r, a, prof, rtol=RTOL, **m), ref, RTOL)
    for mode in ("fixed_load", "fixed_grips"):
        cm = case[mode]
        assert AD.adhesion_constant(k, mode) == pytest.approx(float(cm["C_k"]), rel=1e-15)
        ac, dc, Fc = AD.critical_state(n=n, A_n=An, mode=mode, **m)
        acq, dcq, Fcq = AD.critical_state_quad(prof, mode=mode, a_bracket=(1e-4, 1e2), rtol=RTOL, **m)
        ref = [float(cm[q]["value_str"]) for q in ("a_c", "d_c", "F_c")]
        scale_d = P.kappa(n, k) * An * ref[0] ** n        # size of the two terms whose difference is d_c
        assert close(ac, ref[0], CF) and close(acq, ref[0], 1e-9)
        assert close(dc, ref[1], CF, scale_d) and close(dcq, ref[1], 1e-9, scale_d)
        assert close(Fc, ref[2], CF) and close(Fcq, ref[2], 1e-9)
        if "F_c_over_pi_dgam_R" in cm:
            R = 0.5 / An
            assert Fc / (np.pi * DG * R) == pytest.approx(float(cm["F_c_over_pi_dgam_R"]), rel=CF)


@pytest.mark.parametrize("k", [0.0, 0.3, 0.9])
@pytest.mark.parametrize("mode", ["fixed_load", "fixed_grips"])
@pytest.mark.parametrize("n, An", [(1.0, 0.3), (1.5, 0.9), (2.0, 0.2), (3.0, 0.9)])
def test_table3_literal_forms(k, mode, n, An):
    """Table 3 written out literally (docs/theory/graded.md (G27)-(G29), second forms), independently of
    the simplified implementation."""
    nu = 0.3
    C = 2 / (3 + k) if mode == "fixed_load" else 2 / (1 - k)
    kap = n / 2 * __import__("scipy.special").special.beta(n / 2, (1 + k) / 2)
    hE = M.h_N(k, nu) * E0 / (1 - nu ** 2)
    X = 2 * np.pi * DG * C0 ** k / hE
    a_c = (X / (C ** 2 * n ** 2 * kap ** 2 * An ** 2)) ** (1 / (2 * n + k - 1))
    d_c = (1 - n * C) / (n * C) * (X ** n / (n * C * kap * An) ** (1 - k)) ** (1 / (2 * n + k - 1))
    F_c = (4 * np.pi * DG * (1 - C * (n + k + 1)) / ((1 + k) * (n + k + 1) * C)
           * (X ** (2 - n) / (n * C * kap * An) ** (3 + k)) ** (1 / (2 * n + k - 1)))
    ac, dc, Fc = AD.critical_state(k=k, nu=nu, E0=E0, c0=C0, n=n, A_n=An, delta_gamma=DG, mode=mode)
    assert ac == pytest.approx(a_c, rel=CF)
    assert dc == pytest.approx(d_c, rel=CF, abs=CF * kap * An * a_c ** n)
    assert Fc == pytest.approx(F_c, rel=CF)


@pytest.mark.parametrize("k, tol", [(0.0, 1e-13), (1e-6, 1e-5)])
def test_jkr_limit(k, tol):
    R, nu = 1.7, 0.25
    Es = E0 / (1 - nu ** 2)
    n, An = P.parabolic(R)
    m = dict(k=k, nu=nu, E0=E0, c0=C0, n=n, A_n=An, delta_gamma=DG)
    a = np.array([0.05, 0.6, 2.0])
    assert np.allclose(AD.depth(a, **m), a ** 2 / R - np.sqrt(2 * np.pi * DG * a / Es), rtol=tol, atol=0)
    assert np.allclose(AD.normal_force(a, **m), 4 * Es * a ** 3 / (3 * R) - np.sqrt(8 * np.pi * DG * Es * a ** 3),
                       rtol=tol, atol=0)
    rho = np.array([0.0, 0.5, 0.9])
    p_jkr = (2 * Es * 0.6 / (np.pi * R) * np.sqrt(1 - rho ** 2)
             - np.sqrt(2 * Es * DG / (np.pi * 0.6)) / np.sqrt(1 - rho ** 2))
    assert np.allclose(AD.pressure(rho * 0.6, 0.6, **m), p_jkr, rtol=tol, atol=0)
    # fixed load: a_c^3 = 9 pi dgam R^2/(8 E*), F_c = -3/2 pi dgam R
    ac, dc, Fc = AD.critical_state(mode="fixed_load", **m)
    assert ac == pytest.approx((9 * np.pi * DG * R ** 2 / (8 * Es)) ** (1 / 3), rel=tol)
    assert dc == pytest.approx(ac ** 2 / R - np.sqrt(2 * np.pi * DG * ac / Es), rel=tol)
    assert Fc == pytest.approx(-1.5 * np.pi * DG * R, rel=tol)
    # fixed grips: a_c^3 = pi dgam R^2/(8 E*), F_c = -5/6 pi dgam R
    ac, dc, Fc = AD.critical_state(mode="fixed_grips", **m)
    assert ac == pytest.approx((np.pi * DG * R ** 2 / (8 * Es)) ** (1 / 3), rel=tol)
    assert dc == pytest.approx(ac ** 2 / R - np.sqrt(2 * np.pi * DG * ac / Es), rel=tol)
    assert Fc == pytest.approx(-5 / 6 * np.pi * DG * R, rel=tol)


@pytest.mark.parametrize("k", [0.1, 0.5, 0.9, 0.999])
def test_pull_off_material_independent_for_paraboloid(k):
    R = 1.7
    n, An = P.parabolic(R)
    F = [AD.critical_force(k=k, nu=nu, E0=E, c0=c0, n=n, A_n=An, delta_gamma=DG, mode=mode)
         for nu, E, c0 in [(0.3, 2.5, 0.8), (0.1, 70.0, 3.0)] for mode in ("fixed_load", "fixed_grips")]
    assert F[0] == pytest.approx(-(3 + k) / 2 * np.pi * DG * R, rel=CF) and F[2] == pytest.approx(F[0], rel=CF)
    assert F[1] == pytest.approx(-(1 - k) * (5 + 3 * k) / (2 * (3 + k)) * np.pi * DG * R, rel=CF)
    assert F[3] == pytest.approx(F[1], rel=CF)


@pytest.mark.parametrize("k", [1e-6, 1e-3, 0.5, 0.999])
def test_probes_closed_form_vs_quadrature(k):
    m = dict(k=k, nu=0.3, E0=E0, c0=C0, delta_gamma=DG)
    a = 0.6
    r = np.array([0.0, 1e-4, 0.5, 0.9999]) * a
    for n, An in [(1.0, 0.3), (2.0, 0.3), (3.0, 0.9)]:
        if n == 1.0 and k < 1e-6:
            r_ = r[1:]          # cone centre: logarithmically large at k -> 0, p(0) = inf at k = 0
        else:
            r_ = r
        p = AD.pressure(r_, a, n=n, A_n=An, **m)
        pq = AD.pressure_quad(r_, a, P.PowerLaw(A=An, n=n), rtol=RTOL, **m)
        assert np.allclose(p, pq, rtol=10 * RTOL, atol=0)
        assert AD.depth(a, n=n, A_n=An, **m) == pytest.approx(AD.depth_quad(a, P.PowerLaw(A=An, n=n), rtol=RTOL, **m),
                                                              rel=10 * RTOL)


def test_edge_singularity_and_outside():
    m = dict(k=0.4, nu=0.3, E0=E0, c0=C0, n=2.0, A_n=0.3, delta_gamma=DG)
    p = AD.pressure(np.array([0.6, 0.7]), 0.6, **m)
    assert p[0] == -np.inf and p[1] == 0.0
    # the edge singularity -K (1 - r^2/a^2)^(-(1-k)/2)
    eps = np.array([1e-6, 1e-8])
    pe = AD.pressure(0.6 * (1 - eps), 0.6, **m)
    s = pe * (1 - (1 - eps) ** 2) ** 0.3
    assert s[0] == pytest.approx(s[1], rel=1e-4) and s[0] < 0
    # u_z continuous at r = a, approached as (r - a)^((1-k)/2) (flat-punch part, docs/theory/graded.md (G25))
    eps = np.array([1e-6, 1e-8])
    u0 = AD.surface_displacement(0.6, 0.6, **m)
    du = AD.surface_displacement(0.6 * (1 + eps), 0.6, **m) - u0
    assert du[1] / du[0] == pytest.approx(1e-2 ** 0.3, rel=2e-2)


def test_broadcasting_and_domain():
    k = np.array([0.0, 0.5, 0.9])[:, None]
    dg = np.array([0.0, 0.01, 0.05])
    ac = AD.critical_radius(k=k, nu=0.3, E0=E0, c0=C0, n=2.0, A_n=0.3, delta_gamma=dg)
    assert ac.shape == (3, 3) and np.all(ac[:, 0] == 0) and np.all(np.diff(ac, axis=1) > 0)
    kw = dict(k=0.5, nu=0.3, E0=E0, c0=C0, n=2.0, A_n=0.3, delta_gamma=DG)
    with pytest.raises(ValueError, match="delta_gamma = -0.1"):
        AD.depth(0.6, **(kw | dict(delta_gamma=-0.1)))
    with pytest.raises(ValueError, match="mode = 'sideways'"):
        AD.critical_state(mode="sideways", **kw)
    with pytest.raises(ValueError, match=r"n = 0.2 .* n > \(1-k\)/2"):
        AD.critical_state(**(kw | dict(n=0.2)))
    with pytest.raises(ValueError, match="k = "):
        AD.pressure(0.1, 0.6, **(kw | dict(k=-0.5)))
    with pytest.raises(ValueError, match="a_bracket"):
        AD.critical_state_quad(P.PowerLaw(A=0.3, n=2.0), k=0.5, nu=0.3, E0=E0, c0=C0, delta_gamma=DG,
                               a_bracket=(1e-3, 2e-3))


def test_zero_adhesion_recovers_normal_contact():
    m = dict(k=0.5, nu=0.3, E0=E0, c0=C0, n=1.5, A_n=0.9)
    r = np.array([0.0, 0.3, 0.59])
    assert np.array_equal(AD.pressure(r, 0.6, delta_gamma=0.0, **m), N.pressure(r, 0.6, **m))
    assert AD.normal_force(0.6, delta_gamma=0.0, **m) == N.normal_force(0.6, **m)
