"""Material mapping of the power-law graded half-space (Hess & Popov 2016, eqs. 1-4, 53-56).

Expected values come from the reference points (tests/data/graded_power_law.json: 30-digit closed
forms and an independent 3D Green's-function ODE), from the k = 0 limits of eq. (4) and from the
Holl-ratio forms of docs/theory/graded.md (G8), never from the code under test.
"""

import numpy as np
import pytest

from stressfields.physics.graded import material as M
from stressfields.physics.graded import profiles as P
from graded_reference import REF, nu_of

CF = 1e-12


@pytest.mark.parametrize("case", REF["coefficients"], ids=lambda c: f"k{c['k']}-nu{c['nu']}")
def test_coefficients_against_reference(case):
    k, nu = case["k"], nu_of(case)
    assert M.beta(k, nu) == pytest.approx(float(case["beta"]), rel=CF)
    assert M.C_gs(k, nu) == pytest.approx(float(case["C_GS"]), rel=CF)
    assert M.h_N(k, nu) == pytest.approx(float(case["h_N"]), rel=CF)
    assert M.h_T(k, nu) == pytest.approx(float(case["h_T"]), rel=CF)
    # independent 3D route (ODE Green's function), accurate to ~1e-12
    assert M.h_N(k, nu) == pytest.approx(case["h_N_from_3D_ODE"], rel=2e-12)
    assert M.h_T(k, nu) == pytest.approx(case["h_T_from_3D_ODE"], rel=2e-12)
    # point-load constant C_G = (1 - nu^2) cos(k pi/2) / (pi h_N), docs/theory/graded.md (G9)
    CG = (1 - nu ** 2) * np.cos(k * np.pi / 2) / (np.pi * M.h_N(k, nu))
    assert CG == pytest.approx(float(case["green_normal_CG"]), rel=CF)
    for n, val in case["kappa"].items():
        assert P.kappa(float(n), k) == pytest.approx(float(val), rel=CF)


def test_vectorised_over_k_and_nu():
    k = np.array([0.0, 0.2, 0.5, 0.8, 0.95])[:, None]
    nu = np.array([0.25, 0.3])
    hN = M.h_N(k, nu)
    assert hN.shape == (5, 2)
    table = {(c["k"], c["nu"]): float(c["h_N"]) for c in REF["coefficients"]}
    for i, kk in enumerate(k[:, 0]):
        for j, nn in enumerate(nu):
            if (kk, str(nn)) in table:
                assert hN[i, j] == pytest.approx(table[(kk, str(nn))], rel=CF)
            assert hN[i, j] == M.h_N(kk, nn)


@pytest.mark.parametrize("nu", [-0.5, 0.0, 0.25, 0.3, 0.5])
def test_homogeneous_limit_eq4(nu):
    assert M.h_N(0.0, nu) == pytest.approx(1.0, rel=1e-14)
    assert M.h_T(0.0, nu) == pytest.approx(2 / ((1 + nu) * (2 - nu)), rel=1e-14)
    # continuity at k -> 0 (first order in k)
    assert M.h_N(1e-6, nu) == pytest.approx(1.0, rel=1e-5)
    assert M.h_T(1e-6, nu) == pytest.approx(2 / ((1 + nu) * (2 - nu)), rel=1e-5)


@pytest.mark.parametrize("k", [0.0, 1e-6, 1e-3, 0.3, 0.9, 0.999])
def test_holl_ratio_simple_forms(k):
    nu = M.holl_ratio(k)
    cos = np.cos(k * np.pi / 2)
    assert M.beta(k, nu) == pytest.approx(1.0, rel=1e-15)
    assert M.h_N(k, nu) == pytest.approx(2 * (1 + k) ** 2 * cos / (2 + k), rel=CF)
    assert M.h_T(k, nu) == pytest.approx(4 * (2 + k) * cos / (3 + k) ** 2, rel=CF)


def test_eq54_misprint_fails_k0_limit():
    """The paper's (54) with (1 - nu) instead of (1 - nu^2) gives h_T(0) = 1, not 2/((1+nu)(2-nu))."""
    k, nu = 0.0, 0.3
    b, C = 1.0, 2 / np.pi
    g1 = 1.0
    misprint = 4 * b * g1 / ((1 - nu) * (1 + k) * np.sqrt(np.pi) * C * 1.0 * np.sqrt(np.pi) + 2 * b * (1 + nu) * g1)
    assert abs(misprint - 2 / ((1 + nu) * (2 - nu))) > 0.05
    assert M.h_T(k, nu) == pytest.approx(2 / ((1 + nu) * (2 - nu)), rel=1e-14)


def test_k_to_one_is_finite_and_vanishing():
    k = np.array([0.99, 0.999, 0.9999])
    hN, hT = M.h_N(k, 0.3), M.h_T(k, 0.3)
    assert np.all(np.isfinite(hN)) and np.all(hN > 0) and np.all(np.diff(hN) < 0)
    assert np.all(np.isfinite(hT)) and np.all(hT > 0)
    # h_N ~ cos(k pi/2) as k -> 1: the ratio h_N/cos(k pi/2) converges
    ratio = hN / np.sin((1 - k) * np.pi / 2)
    assert ratio[2] == pytest.approx(ratio[1], rel=1e-3)


def test_foundation_stiffness():
    k, nu, E0, c0 = 0.5, 0.3, 2.5, 0.8
    rigid = M.c_N_star(k, nu, E0, c0)
    assert rigid == pytest.approx(M.h_N(k, nu) * E0 / ((1 - nu ** 2) * c0 ** k), rel=1e-15)
    same = M.c_N_star(k, nu, E0, c0, E0_2=E0, nu_2=nu)
    assert same == pytest.approx(rigid / 2, rel=1e-15)
    assert M.c_T_star(k, nu, E0, c0, E0_2=E0) == pytest.approx(M.h_T(k, nu) * E0 / (2 * c0 ** k), rel=1e-15)
    for case in REF["normal"]:
        cN = M.c_N_star(case["k"], nu_of(case), 2.5, 0.8) * 0.8 ** case["k"]
        assert cN == pytest.approx(float(case["c_N_at_c0"]), rel=CF)


@pytest.mark.parametrize("k", [-0.1, 1.0, 1.5, np.nan])
def test_k_domain(k):
    with pytest.raises(ValueError, match=r"k = .*0 <= k < 1"):
        M.h_N(k, 0.3)
    with pytest.raises(ValueError, match=r"k = "):
        M.h_N(np.array([0.2, k]), 0.3)


@pytest.mark.parametrize("k, nu", [(0.5, 0.7), (0.2, 0.9), (0.5, 0.6), (0.0, 0.55), (0.3, -1.0), (0.3, np.nan)])
def test_nu_domain(k, nu):
    # nu > 1/(1+k): beta of eq. 56 not real; 0.5 < nu <= 1/(1+k): thermodynamically inadmissible
    with pytest.raises(ValueError, match=r"nu = .*-1 < nu <= 0.5"):
        M.h_T(k, nu)
    with pytest.raises(ValueError, match=r"nu = "):
        M.beta(np.array([k, k]), np.array([0.3, nu]))


def test_tangential_decoupled_predicate():
    k = np.array([0.0, 0.5, 0.8])[:, None]
    nu = np.array([0.25, 0.4, 1 / 2.8])
    # identical bodies: always decoupled
    assert M.tangential_decoupled(k, nu).all()
    # rigid counter-body: only at the Holl ratio
    rigid = M.tangential_decoupled(k, nu, E0_2=np.inf)
    expected = np.isclose(nu, 1 / (2 + k), rtol=1e-12)
    assert rigid.shape == (3, 3) and np.array_equal(rigid, expected)
    assert rigid.sum() == 2            # k=0.5 with 0.4 and k=0.8 with 1/2.8
    # two elastic bodies: identical, or both at the Holl ratio
    assert M.tangential_decoupled(0.5, 0.4, E0=1.0, E0_2=3.0, nu_2=0.4)
    assert not M.tangential_decoupled(0.5, 0.3, E0=1.0, E0_2=3.0, nu_2=0.3)
    assert M.tangential_decoupled(0.5, 0.3, E0=3.0, E0_2=3.0, nu_2=0.3)
    assert not M.tangential_decoupled(0.5, 0.4, E0=1.0, E0_2=3.0, nu_2=0.3)
