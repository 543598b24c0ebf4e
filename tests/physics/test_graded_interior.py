"""The stress below the graded surface (docs/theory/graded.md section 10) against independent routes:
the axisymmetric family's interior at k = 0, Hertz minus the flat punch and its K_I, the incompressible
Hertz field as k -> 0, the field equations (equilibrium; compatibility of the strains of Hooke's law
with E(z) = E0 (z/c0)^k) by finite differences, the traction and force balances, and an mpmath double
integral of the point-load kernel (test_graded_interior_reference.py)."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from stressfields.physics import axisymmetric as ax
from stressfields.physics import graded as gp
from stressfields.physics.axisymmetric.interior_hertz import hertz_unit, punch_unit
from stressfields.physics.graded import holl
from stressfields.physics.graded.interior import INTERIOR, interior_fields

DATA = Path(__file__).resolve().parents[1] / "data"
R, A0, E0, C0 = 0.02, 1e-3, 2e9, 1e-2
PARA = gp.Indenter.parabolic(R)


def _stress(rho, z, *, k, nu, dg=None, rtol=1e-10, profile=PARA, a=A0):
    return interior_fields(("sigma_rr", "sigma_tt", "sigma_zz", "sigma_rz"), profile, a=a, rho=rho, z=z, k=k,
                           nu=nu, E0=E0, c0=C0, delta_gamma=dg, rtol=rtol)


# -- k = 0: the homogeneous half-space ------------------------------------------------------------

@pytest.mark.parametrize("nu", [0.0, 0.3, 0.5])
def test_k0_paraboloid_is_hertz_times_the_effective_modulus(nu):
    rho, z = np.meshgrid(np.linspace(0.0, 2.5, 11), np.array([1e-6, 0.1, 0.48, 1.0, 3.0]))
    got = _stress(rho, z, k=0.0, nu=nu)
    e_star = E0 / (1.0 - nu * nu)
    p0 = 2.0 * A0 * e_star / (math.pi * R)      # Hertz: p0 = 2 a E*/(pi R)
    ref = hertz_unit(rho, 0.0 * rho, z, nu)
    for c, src in (("rr", "xx"), ("tt", "yy"), ("zz", "zz"), ("rz", "xz")):
        np.testing.assert_allclose(got[f"sigma_{c}"], p0 * ref[src], rtol=1e-12, atol=1e-12 * p0)


def test_k0_power_law_equals_the_axisymmetric_interior_within_rtol():
    prof = gp.Indenter.power_law(A=3.0, n=1.5)
    rho, z = np.array([0.0, 0.4, 0.9, 1.3]), np.array([0.2, 0.05, 0.3, 0.7])
    got = _stress(rho, z, k=0.0, nu=0.25, profile=prof, rtol=1e-10)
    e_star = E0 / (1.0 - 0.25 ** 2)
    ref = ax.interior_stress(rho * A0, 0.0, z * A0, A0, 0.25, ax.power_law(3.0, 1.5), method="quadrature",
                             rtol=1e-12)
    pm = float(gp.normal_fields(["normal_force"], prof, a=A0, k=0.0, nu=0.25, E0=E0, c0=C0)["normal_force"]) / (
        math.pi * A0 ** 2)
    for c, src in (("rr", "xx"), ("tt", "yy"), ("zz", "zz"), ("rz", "xz")):
        np.testing.assert_allclose(got[f"sigma_{c}"], e_star * ref[src], rtol=0, atol=1e-9 * pm)


def test_k0_adhesive_is_hertz_minus_the_flat_punch_of_the_adhesive_depth():
    nu, dg = 0.3, 0.8
    rho, z = np.meshgrid(np.linspace(0.0, 2.0, 9), np.array([1e-4, 0.2, 1.0]))
    got = _stress(rho, z, k=0.0, nu=nu, dg=dg)
    e_star = E0 / (1.0 - nu * nu)
    dl = math.sqrt(2.0 * math.pi * dg * A0 / e_star)        # Delta l_max at k = 0 (c_N = E*)
    hz, pu = hertz_unit(rho, 0 * rho, z, nu), punch_unit(rho, 0 * rho, z, nu)
    p0 = 2.0 * A0 * e_star / (math.pi * R)
    for c, src in (("rr", "xx"), ("tt", "yy"), ("zz", "zz"), ("rz", "xz")):
        np.testing.assert_allclose(got[f"sigma_{c}"], p0 * hz[src] - e_star * dl / A0 * pu[src], rtol=1e-12,
                                   atol=1e-12 * p0)


def test_k0_adhesive_edge_stress_intensity_is_the_theory_pages_K_I():
    """Below the edge ring (theta = 90 deg from the contact) sigma_zz = K_I cos(45)(1 + sin45 sin135)
    / sqrt(2 pi eps) + O(1): Richardson on eps and 4 eps removes the O(sqrt eps) term of the
    normalised intensity.  K_I = c_N* Delta l_max / sqrt(pi a) = sqrt(2 E* Delta gamma) (G59)."""
    nu, dg = 0.3, 0.8
    e_star = E0 / (1.0 - nu * nu)
    eps = np.array([1e-12, 4e-12])
    szz = _stress(1.0, eps, k=0.0, nu=nu, dg=dg)["sigma_zz"]
    f90 = math.cos(math.pi / 4) * (1.0 + math.sin(math.pi / 4) * math.sin(3 * math.pi / 4))
    K = np.sqrt(2.0 * math.pi * eps * A0) * szz / f90
    assert 2.0 * K[0] - K[1] == pytest.approx(math.sqrt(2.0 * e_star * dg), rel=1e-8)


def test_surface_values_are_the_pressure_bit_for_bit():
    rho = np.linspace(0.0, 1.5, 16)
    for k, nu, dg in ((0.0, 0.3, None), (0.0, 0.3, 0.5), (0.5, 0.4, None), (0.5, 0.4, 0.5)):
        got = _stress(rho, 0.0, k=k, nu=nu, dg=dg)["sigma_zz"]
        if dg is None:
            p = gp.normal_fields(["pressure"], PARA, a=A0, rho=rho, k=k, nu=nu, E0=E0, c0=C0)["pressure"]
        else:
            p = gp.adhesive_fields(["pressure"], PARA, a=A0, rho=rho, k=k, nu=nu, E0=E0, c0=C0,
                                   delta_gamma=dg)["pressure"]
        assert np.array_equal(got, -p)


# -- k > 0, nu = 1/(2+k) ------------------------------------------------------------------------------

def test_the_point_load_kernel_balances_the_load():
    """chi int_0^(pi/2) cos^(chi-1) sin d theta = 1: the radial field carries P (G61)."""
    from scipy.integrate import quad

    for k in (0.0, 0.3, 0.9):
        chi = 3.0 + k
        assert quad(lambda t: chi * math.cos(t) ** (chi - 1) * math.sin(t), 0, math.pi / 2)[0] == pytest.approx(1.0)


def test_k_to_zero_tends_to_the_incompressible_hertz_field():
    rho, z = np.array([0.0, 0.5, 0.95, 1.2, 2.0]), np.array([0.3, 0.05, 0.2, 0.1, 1.0])
    ref = hertz_unit(rho, 0 * rho, z, 0.5)
    gaps = []
    for k in (1e-2, 1e-3, 1e-4):
        s = holl.disc_stress(rho, z, k, 0.5 * (1 + k), 1e-12)
        gaps.append(max(np.max(np.abs(s[c] - ref[x])) for c, x in (("rr", "xx"), ("tt", "yy"), ("zz", "zz"),
                                                                    ("rz", "xz"))))
    assert gaps[2] < 3e-4 and gaps[1] / gaps[2] == pytest.approx(10.0, rel=0.1)
    assert gaps[0] / gaps[1] == pytest.approx(10.0, rel=0.1)


def _fd(f, rho, z, h):
    """Central differences of the stress function f(rho, z) -> dict at (rho, z), step h (units of a)."""
    pts_r = np.array([rho, rho + h, rho - h, rho, rho])
    pts_z = np.array([z, z, z, z + h, z - h])
    s = f(pts_r, pts_z)
    d_r = {c: (s[c][1] - s[c][2]) / (2 * h) for c in s}
    d_z = {c: (s[c][3] - s[c][4]) / (2 * h) for c in s}
    d_rr = {c: (s[c][1] - 2 * s[c][0] + s[c][2]) / h ** 2 for c in s}
    d_zz = {c: (s[c][3] - 2 * s[c][0] + s[c][4]) / h ** 2 for c in s}
    mixed = f(np.array([rho + h, rho + h, rho - h, rho - h]), np.array([z + h, z - h, z + h, z - h]))
    d_rz = {c: (mixed[c][0] - mixed[c][1] - mixed[c][2] + mixed[c][3]) / (4 * h * h) for c in s}
    return {c: v[0] for c, v in s.items()}, d_r, d_z, d_rr, d_zz, d_rz


def _unit(k):
    return lambda r, z: holl.disc_stress(r, z, k, 0.5 * (1 + k), 1e-12)


@pytest.mark.parametrize("k,point", [(0.5, (0.6, 0.4)), (0.25, (1.4, 0.3))])
def test_equilibrium_residuals_fall_as_h_squared(k, point):
    res = []
    for h in (2e-2, 1e-2):
        s, dr, dz, *_ = _fd(_unit(k), *point, h)
        r = point[0]
        e1 = dr["rr"] + dz["rz"] + (s["rr"] - s["tt"]) / r
        e2 = dr["rz"] + dz["zz"] + s["rz"] / r
        res.append(max(abs(e1), abs(e2)))
    assert res[0] < 1e-3 and 3.2 < res[0] / res[1] < 4.8


def _compatibility(f, r, z, h, k, nu):
    """Residuals of the axisymmetric compatibility equations of the strains of Hooke's law with
    E = (z)^k (E0, c0 scale out): eps_rr = d(r eps_tt)/dr; d2 eps_rr/dz2 + d2 eps_zz/dr2 = 2 d2 eps_rz/drdz;
    2 d eps_rz/dz - r d2 eps_tt/dz2 = d eps_zz/dr."""
    def strain(rr, zz):
        s = f(rr, zz)
        E = zz ** k
        return {"rr": (s["rr"] - nu * (s["tt"] + s["zz"])) / E, "tt": (s["tt"] - nu * (s["rr"] + s["zz"])) / E,
                "zz": (s["zz"] - nu * (s["rr"] + s["tt"])) / E, "rz": (1 + nu) * s["rz"] / E}
    e, dr, dz, drr, dzz, drz = _fd(strain, r, z, h)
    c1 = e["rr"] - e["tt"] - r * dr["tt"]
    c2 = dzz["rr"] + drr["zz"] - 2 * drz["rz"]
    c3 = 2 * dz["rz"] - r * dzz["tt"] - dr["zz"]
    return max(abs(c1), abs(c2), abs(c3))


@pytest.mark.parametrize("k", [0.3, 0.7])
def test_strains_of_hookes_law_with_the_graded_modulus_are_compatible(k):
    point, nu = (0.7, 0.5), 1 / (2 + k)
    res = [_compatibility(_unit(k), *point, h, k, nu) for h in (2e-2, 1e-2)]
    assert res[0] < 1e-3 and 3.2 < res[0] / res[1] < 4.8
    # the test can fail: with another Poisson ratio the residual does not fall with h
    wrong = [_compatibility(_unit(k), *point, h, k, 0.3) for h in (2e-2, 1e-2)]
    assert wrong[1] > 100 * res[1] and wrong[0] / wrong[1] < 1.5


@pytest.mark.parametrize("k", [0.2, 0.6])
def test_traction_tends_to_the_pressure_inside_and_zero_outside(k):
    rho = np.array([0.0, 0.3, 0.7, 0.9, 1.2, 2.0])
    s = holl.disc_stress(rho, 1e-7, k, 0.5 * (1 + k), 1e-10)
    p = np.clip(1 - rho ** 2, 0.0, None) ** (0.5 * (1 + k))
    np.testing.assert_allclose(s["zz"], -p, atol=1e-6)
    np.testing.assert_allclose(s["rr"], -p / (1 + k), atol=1e-5)     # (G66)
    np.testing.assert_allclose(s["rz"], 0.0, atol=1e-5)


def check_force_balance(profile, k, dg):
    """The vertical force through the planes z = 0.2 a and a equals the normal force F_N to 1e-7 (rtol 1e-10)."""
    nu = 1 / (2 + k)
    kw = dict(k=k, nu=nu, E0=E0, c0=C0)
    if dg is None:
        F = float(gp.normal_fields(["normal_force"], profile, a=A0, **kw)["normal_force"])
    else:
        F = float(gp.adhesive_fields(["normal_force"], profile, a=A0, **kw, delta_gamma=dg)["normal_force"])
    chi = 3 + k
    # r in [0, 60a]: Gauss panels; beyond, the point-load tail F z^chi (R0^2 + z^2)^(-chi/2)
    edges = np.concatenate([[0.0], np.geomspace(0.05, 60.0, 30)])
    t, w = np.polynomial.legendre.leggauss(12)
    lo, hi = edges[:-1, None], edges[1:, None]
    r = (lo + (hi - lo) * (t + 1) / 2).ravel()
    wr = ((hi - lo) * w / 2).ravel()
    for z in (0.2, 1.0):
        szz = _stress(r, np.full(r.size, z), k=k, nu=nu, dg=dg, rtol=1e-10, profile=profile)["sigma_zz"]
        inner = -2 * math.pi * np.sum(wr * r * szz) * A0 ** 2
        tail = F * z ** chi * (60.0 ** 2 + z ** 2) ** (-chi / 2)
        assert inner + tail == pytest.approx(F, rel=1e-7)


@pytest.mark.parametrize("k,dg", [(0.5, None), (0.3, 0.4)])
def test_vertical_force_through_any_plane_is_the_normal_force(k, dg):
    check_force_balance(PARA, k, dg)


def test_live_check_against_a_direct_double_integral():
    """A few points by scipy's adaptive double integral in the disc's own coordinates (independent rule)."""
    from scipy.integrate import dblquad

    k, e = 0.5, 0.75
    chi = 3 + k
    for r, z in ((0.4, 0.3), (1.3, 0.5)):
        def f(psi, rho):
            dx = r - rho * math.cos(psi)
            R2 = dx * dx + (rho * math.sin(psi)) ** 2 + z * z
            return (1 - rho * rho) ** e * rho * z * z * R2 ** (-(chi + 2) / 2)
        val = -(chi / math.pi) * z ** (chi - 2) * dblquad(f, 0, 1, 0, math.pi, epsabs=1e-13, epsrel=1e-12)[0]
        assert holl.disc_stress(r, z, k, e, 1e-10)["zz"][0] == pytest.approx(val, rel=1e-9, abs=1e-11)


def test_unsupported_cases_and_negative_depth_are_refused_in_one_line():
    with pytest.raises(ValueError, match=r"nu = 0\.3 with k = 0\.5 is not solved below the surface.*holl_ratio"):
        _stress(0.5, 0.5, k=0.5, nu=0.3)
    r = np.linspace(0.0, 2e-3, 8)
    for k, nu in ((0.5, 0.4), (0.5, 0.3)):
        with pytest.raises(ValueError, match=r"profile = 'tabulated' is solved below the surface at k = 0 only: "
                                             r".*pressure at every radial node.*here k = 0\.5$"):
            _stress(0.5, 0.5, k=k, nu=nu, profile=gp.Indenter.tabulated(r, r ** 2 / (2 * R)))
    clamped = gp.Indenter("tabulated", (), gp.Tabulated(r, r ** 2 / (2 * R), slope_at_0=0.0))
    with pytest.raises(ValueError, match=r"slope_at_0 set is not solved below the surface.*\(slope_at_0 = 0\.0\)$"):
        _stress(0.5, 0.5, k=0.0, nu=0.3, profile=clamped)
    with pytest.raises(ValueError, match=r"z = -0\.1 is outside the allowed range z >= 0"):
        _stress(0.5, -0.1, k=0.0, nu=0.3)


def test_singular_points_are_flagged_infinite_not_finite():
    out = interior_fields(INTERIOR, PARA, a=A0, rho=1.0, z=0.0, k=0.5, nu=0.4, E0=E0, c0=C0, delta_gamma=0.5)
    assert np.isposinf(out["sigma_zz"]) and np.isposinf(out["tau_max"]) and np.isposinf(out["von_mises"])
    cone = interior_fields(("sigma_zz", "tau_max"), gp.Indenter.conical(0.2), a=A0, rho=0.0, z=0.0, k=0.0, nu=0.3,
                           E0=E0, c0=C0)
    assert np.isneginf(cone["sigma_zz"]) and np.isposinf(cone["tau_max"])
    below = interior_fields(("sigma_zz",), gp.Indenter.conical(0.2), a=A0, rho=0.0, z=1e-3, k=0.0, nu=0.3,
                            E0=E0, c0=C0)
    assert np.isfinite(below["sigma_zz"])


# -- tangential load (partial slip) at k = 0 ------------------------------------------------------------

@pytest.mark.parametrize("body2", [None, np.inf])
@pytest.mark.parametrize("fx", [0.4, 1.0])
def test_k0_tangential_traction_is_the_familys_shear_traction(body2, fx):
    """sigma_xz -> -tau(r), sigma_zz -> -p(r) as z -> 0 on both sides of the axis: the graded shear
    traction (G45)-(G48) and pressure (G18) with c_N* of the pair, independent formulas (identical bodies:
    half the rigid c_N*)."""
    from stressfields.physics.graded import normal, tangential
    from stressfields.physics.graded.interior import tangential_interior_fields

    x = np.array([-1.4, -0.95, -0.6, -0.2, 0.0, 0.3, 0.7, 0.99, 1.3])
    nu, mu = 0.3, 0.4
    tau = tangential.shear_traction(np.abs(x) * A0, A0, fx, k=0.0, nu=nu, mu=mu, E0=E0, c0=C0, n=2.0, A_n=0.5 / R,
                                    E0_2=body2, require_decoupled=False)
    p = normal.pressure(np.abs(x) * A0, A0, k=0.0, nu=nu, E0=E0, c0=C0, n=2.0, A_n=0.5 / R,
                        E0_2=E0 if body2 is None else body2)
    scale = float(np.max(p))
    for z, tol in ((0.0, 1e-12), (1e-10, 1e-8)):
        got = tangential_interior_fields(["sigma_xz", "sigma_zz"], PARA, a=A0, x=x, z=z, fx=fx, mu=mu, k=0.0, nu=nu,
                                         E0=E0, c0=C0, E0_2=body2)
        np.testing.assert_allclose(got["sigma_xz"], -tau, rtol=0, atol=tol * scale)
        np.testing.assert_allclose(got["sigma_zz"], -p, rtol=0, atol=tol * scale)


def test_k0_tangential_below_the_surface_is_the_axisymmetric_field_times_the_pair_modulus():
    from stressfields.physics.axisymmetric import interior_stress, interior_stress_tangential
    from stressfields.physics.graded.interior import tangential_interior_fields

    x, z, nu, mu, fx = np.array([-0.8, 0.0, 0.5, 1.2]), np.array([0.1, 0.4, 0.3, 0.6]), 0.25, 0.3, 0.6
    got = tangential_interior_fields(["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz"], PARA, a=A0, x=x, z=z, fx=fx,
                                     mu=mu, k=0.0, nu=nu, E0=E0, c0=C0)
    half = E0 / (1 - nu * nu) / 2.0                  # identical bodies: c_N* = E*/2 (eq. 46)
    c = A0 * (1 - fx) ** (1 / 3)                     # (G33) at n = 2, k = 0
    prof = ax.paraboloid(R)
    n = interior_stress(x * A0, 0.0, z * A0, A0, nu, prof)
    t = interior_stress_tangential(x * A0, 0.0, z * A0, A0, c, nu, mu, prof)
    for comp in ("xx", "yy", "zz", "xz"):
        np.testing.assert_allclose(got[f"sigma_{comp}"], half * (n[comp] + t[comp]), rtol=1e-12,
                                   atol=1e-12 * half * 0.1)


def test_tangential_k_above_zero_is_refused():
    from stressfields.physics.graded.interior import tangential_interior_fields

    with pytest.raises(ValueError, match=r"k = 0\.5 is not solved below the surface under tangential load"):
        tangential_interior_fields(["sigma_xz"], PARA, a=A0, x=0.0, z=0.3, fx=0.5, mu=0.3, k=0.5, nu=0.4, E0=E0, c0=C0)


def test_thin_layers_are_resolved_or_nan_never_infinite():
    """z/a down to 1e-99 next to the axis, inside, at and outside the edge tends to the surface limit (G66);
    below the resolved layer (1e-100) NaN, which the entry point flags 3 (not resolved)."""
    k, e = 0.5, 0.75
    rho = np.array([0.0, 0.5, 0.999999, 1.0, 1.5])
    s = holl.disc_stress(rho, 1e-99, k, e, 1e-8)
    p = np.clip(1 - rho ** 2, 0.0, None) ** e
    np.testing.assert_allclose(s["zz"], -p, rtol=0, atol=1e-8)          # the contract: rtol times P = 1
    np.testing.assert_allclose(s["rr"], -p / (1 + k), rtol=0, atol=1e-8)
    deep = holl.disc_stress([0.5, 0.3], [1e-200, 5e-324], k, e, 1e-8)
    assert all(np.isnan(v).all() for v in deep.values())
    from stressfields.physics.graded.interior import interior_fields as f
    out = f(["sigma_zz"], PARA, a=A0, rho=0.5, z=1e-200, k=k, nu=1 / (2 + k), E0=E0, c0=C0)
    assert np.isnan(out["sigma_zz"])
