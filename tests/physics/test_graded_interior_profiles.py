"""Below the graded surface at k > 0 (nu = 1/(2+k)) for the power laws other than the paraboloid: the cone
and f = A r^n (docs/theory/graded.md (G70)).  Their pressure shape Phi (G18) enters the 2-D rule of the
point-load field as the interpolant ``holl.PressureShape`` with extra panels towards the centre, where Phi
goes like rho^(n+k-1).  Held against: the family's pressure (interpolant; traction limit z -> 0), the
paraboloid's own rule (n = 2 through the general route), the normal force (force balance through planes),
the field equations (equilibrium, compatibility of the strains of Hooke's law with E(z)), the homogeneous
cone as k -> 0, and an mpmath double integral with the hypergeometric pressure (60 points)."""
from __future__ import annotations

import numpy as np
import pytest

from stressfields.physics import graded as gp
from stressfields.physics.axisymmetric import cone, interior_stress
from stressfields.physics.graded import holl
from stressfields.physics.graded.interior import INTERIOR, _shape, interior_fields
from stressfields.physics.graded.material import c_N_star
from stressfields.physics.graded.normal import pressure_shape

from conftest import load_reference
from test_graded_interior import _compatibility, _fd, check_force_balance

A0, E0, C0 = 1e-3, 2e9, 1e-2
CONE = gp.Indenter.conical(0.1)


def _unit(n, k, rtol=1e-12):
    """sigma / (c_N* n kappa A_n a^(n+k-1) / pi): the stress of the shape Phi on the unit disc."""
    return lambda r, z: holl.disc_stress(r, z, k, 0.5 * (1 + k), rtol, shape=_shape(n, k))


def test_the_interpolated_shape_is_the_familys_pressure():
    rng = np.random.default_rng(7)
    rho = np.concatenate([10 ** rng.uniform(-15, 0, 400), 1 - 10 ** rng.uniform(-13, -0.5, 200)])
    for n, k in ((1.0, 0.3), (0.6, 0.2), (1.5, 0.5), (7.0, 0.9), (50.0, 0.5)):
        got = _shape(n, k)(rho) * ((1 - rho) * (1 + rho)) ** (0.5 * (1 + k))
        np.testing.assert_allclose(got, pressure_shape(rho, k=k, n=n), rtol=1e-13)


def test_the_general_route_at_n_2_is_the_paraboloids_rule():
    """n = 2 through the interpolated shape and the centre panels (centre exponent forced to 1 + k) against
    (1 - rho^2)^e / (1 + k) by the paraboloid's own call: the plumbing of the shape, not the kernel."""
    k = 0.4
    shape = holl.PressureShape(lambda r: pressure_shape(r, k=k, n=2.0), 0.5 * (1 + k), 1 + k)
    rho, z = np.array([0.0, 0.3, 0.99, 1.0, 1.7]), np.array([0.05, 0.4, 0.01, 0.2, 1.0])
    got = holl.disc_stress(rho, z, k, 0.5 * (1 + k), 1e-10, shape=shape)
    want = holl.disc_stress(rho, z, k, 0.5 * (1 + k), 1e-12)
    for c in holl.COMPONENTS:
        np.testing.assert_allclose(got[c], want[c] / (1 + k), rtol=0, atol=1e-10)


@pytest.mark.parametrize("n,k", [(1.0, 0.3), (0.6, 0.2)])
def test_traction_tends_to_the_pressure_inside_and_zero_outside(n, k):
    """z = 1e-7 a: sigma_zz -> -Phi, sigma_rr -> -Phi/(1+k) (G66), sigma_rz -> 0; n = 0.6, k = 0.2: Phi
    unbounded at the centre."""
    rho = np.array([0.01, 0.3, 0.7, 0.9, 1.2, 2.0])
    s = holl.disc_stress(rho, 1e-7, k, 0.5 * (1 + k), 1e-10, shape=_shape(n, k))
    p = pressure_shape(rho, k=k, n=n)
    np.testing.assert_allclose(s["zz"], -p, atol=1e-5 * p[1])
    np.testing.assert_allclose(s["rr"], -p / (1 + k), atol=1e-5 * p[1])
    # the shear vanishes like z (the surface is free of shear): ten times less at a tenth of the depth
    deeper = holl.disc_stress(rho, 1e-8, k, 0.5 * (1 + k), 1e-10, shape=_shape(n, k))["rz"]
    np.testing.assert_allclose(s["rz"][:4], 10 * deeper[:4], rtol=1e-3)
    np.testing.assert_allclose(s["rz"][4:], 0.0, atol=1e-12)


@pytest.mark.parametrize("profile,k,dg", [(CONE, 0.5, None), (gp.Indenter.power_law(A=40.0, n=1.5), 0.3, None),
                                          (CONE, 0.3, 0.4), (gp.Indenter.power_law(A=1.0, n=50.0), 0.5, None)])
def test_vertical_force_through_any_plane_is_the_normal_force(profile, k, dg):
    check_force_balance(profile, k, dg)


@pytest.mark.parametrize("n,k,point", [(1.0, 0.5, (0.6, 0.4)), (0.6, 0.3, (0.2, 0.3))])
def test_equilibrium_residuals_fall_as_h_squared(n, k, point):
    res = []
    for h in (2e-2, 1e-2):
        s, dr, dz, *_ = _fd(_unit(n, k), *point, h)
        r = point[0]
        e1 = dr["rr"] + dz["rz"] + (s["rr"] - s["tt"]) / r
        e2 = dr["rz"] + dz["zz"] + s["rz"] / r
        res.append(max(abs(e1), abs(e2)))
    # the truncation error of the differences against the stress there (h = 0.02 next to a steep pressure)
    assert res[0] < 5e-3 * abs(s["zz"]) and 3.2 < res[0] / res[1] < 4.8


def test_strains_of_hookes_law_with_the_graded_modulus_are_compatible():
    k, point = 0.4, (0.5, 0.5)
    res = [_compatibility(_unit(1.0, k), *point, h, k, 1 / (2 + k)) for h in (2e-2, 1e-2)]
    assert res[0] < 1e-3 and 3.2 < res[0] / res[1] < 4.8
    wrong = [_compatibility(_unit(1.0, k), *point, h, k, 0.3) for h in (2e-2, 1e-2)]
    assert wrong[1] > 100 * res[1] and wrong[0] / wrong[1] < 1.5


def test_cone_as_k_to_zero_tends_to_the_homogeneous_cone_at_nu_one_half():
    """The graded cone at k -> 0 (nu = 1/(2+k) -> 1/2) against the axisymmetric family's closed-form cone
    interior at nu = 1/2: the gap falls like k."""
    rho, z = np.array([0.0, 0.5, 0.95, 1.3]), np.array([0.3, 0.1, 0.2, 0.5])
    ref = interior_stress(rho * A0, 0.0, z * A0, A0, 0.5, cone(0.1))
    gaps = []
    for k in (1e-2, 1e-3):
        got = interior_fields(["sigma_rr", "sigma_tt", "sigma_zz", "sigma_rz"], CONE, a=A0, rho=rho, z=z, k=k,
                              nu=1 / (2 + k), E0=E0, c0=C0, rtol=1e-12)
        scale = float(c_N_star(k, 1 / (2 + k), E0, C0)) * A0 ** k       # the pressure's modulus at k (G18)
        gaps.append(max(np.max(np.abs(got[f"sigma_{c}"] / scale - ref[x])) for c, x in
                        (("rr", "xx"), ("tt", "yy"), ("zz", "zz"), ("rz", "xz"))))
    # measured: a relative gap of about 2.2 k
    assert gaps[1] < 5e-3 * float(np.max(np.abs(ref["zz"]))) and gaps[0] / gaps[1] == pytest.approx(10.0, rel=0.15)


@pytest.mark.parametrize("rtol", [1e-6, 1e-10])
def test_against_the_mpmath_double_integral_with_the_hypergeometric_pressure(rtol):
    """|error| <= rtol max(|value|, p_m) at every stored point and component (tests/data/README.md): |value| the
    largest component at the point, p_m = 2/((1+k)(n+k+1)) the mean of Phi over the disc (G67), (G70)."""
    ref = load_reference("graded_interior_profiles")["points"]
    assert len(ref) >= 64 and max(p["err"] for p in ref) < 1e-12
    rho, z, k, n = (np.array([p[key] for p in ref]) for key in ("rho", "z", "k", "n"))
    want = {c: np.array([p[f"sigma_{c}"] for p in ref]) for c in holl.COMPONENTS}
    size = np.max([np.abs(v) for v in want.values()], axis=0)
    for nk in set(zip(n, k)):
        sel = (n == nk[0]) & (k == nk[1])
        got = holl.disc_stress(rho[sel], z[sel], k[sel], 0.5 * (1 + k[sel]), rtol, shape=_shape(*nk))
        bound = rtol * np.maximum(size[sel], 2.0 / ((1.0 + nk[1]) * (nk[0] + nk[1] + 1.0)))
        for c in holl.COMPONENTS:
            worst = np.max(np.abs(got[c] - want[c][sel]) / bound)
            assert worst < 1.0, (nk, c, worst)


def test_the_tip_of_a_sharp_power_law_is_unbounded_only_on_the_surface():
    """f = A r^0.6 at k = 0.2: n + k < 1, p(0) = +inf; on the surface -inf (G66) and tau_max +inf, below it
    finite."""
    prof = gp.Indenter.power_law(A=2.0, n=0.6)
    out = interior_fields(INTERIOR, prof, a=A0, rho=0.0, z=np.array([0.0, 1e-6, 0.1]), k=0.2, nu=1 / 2.2, E0=E0,
                          c0=C0)
    assert np.isneginf(out["sigma_zz"][0]) and np.isneginf(out["sigma_rr"][0])
    assert np.isposinf(out["tau_max"][0]) and np.isposinf(out["von_mises"][0])
    assert all(np.isfinite(out[c][1:]).all() for c in INTERIOR)
    assert out["sigma_zz"][1] < out["sigma_zz"][2] < 0.0


def test_peaks_of_the_cone_and_of_a_sharp_power_law():
    """The cone at k = 0.5: the search's peak is the largest tau_max of a 21 x 21 map and the maximum of a bounded
    1-D search on the axis, where it sits; f = A r^0.4 (n + k < 1): +inf at the surface centre, flag 1."""
    from scipy.optimize import minimize_scalar

    from stressfields.physics.graded.interior import peaks

    kw = dict(a=A0, k=0.5, nu=0.4, E0=E0, c0=C0, rtol=1e-8)        # the same field for both searches
    got = peaks(CONE, **kw)

    def tau(rho, z):
        return interior_fields(["tau_max"], CONE, rho=rho, z=z, **kw)["tau_max"]
    grid = tau(np.linspace(0.0, 2.0, 21)[None, :], np.linspace(0.0, 2.0, 21)[:, None])
    axis = minimize_scalar(lambda z: -float(tau(0.0, z)), bounds=(0.05, 1.0), method="bounded",
                           options={"xatol": 1e-9})
    assert float(got["tau_max_peak"]) >= np.max(grid)
    assert float(got["tau_max_peak"]) == pytest.approx(-axis.fun, rel=1e-9)
    assert float(got["tau_max_peak_depth"]) == pytest.approx(axis.x, abs=1e-5)
    assert float(got["tau_max_peak_rho"]) == 0.0 and int(got["peak_validity"]) == 0
    sharp = peaks(gp.Indenter.power_law(A=2.0, n=0.4), **kw)
    assert np.isposinf(sharp["tau_max_peak"]) and int(sharp["peak_validity"]) == 1
