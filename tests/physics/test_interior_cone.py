"""The cone's closed form below the surface (docs/theory/interior.md (I46)-(I52)) against routes
that share no code with it:

* the 1-D superposition of flat punches (I15) at rtol = 1e-12 on a grid (r/a 0 ... 3 with the axis
  and the edge, z/a 1e-9 ... 30), stresses and d p_h/dz;
* the printed (unstable) forms of the same functions in 300-digit decimal arithmetic, next to the
  axis (r = 0, 1e-16 a, 1e-8 a), the tip (z = 1e-12 a), the edge ring and the far field (R = 1e4 a);
* oracle-free: equilibrium and Beltrami–Michell compatibility by central differences;
* the axis: sigma_zz integrated over the flat punches' axis values, themselves integrated from
  Boussinesq's point load (no kernel of the package involved);
* the surface kernels (docs/theory/axisymmetric.md (A12)-(A13)) at z -> 0, Boussinesq's point load
  in the far field, and the routes (``auto`` takes the closed form, ``closed`` is allowed).
"""
import decimal
import math

import numpy as np
import pytest
from scipy.integrate import quad

from stressfields.physics import axisymmetric as ax
from stressfields.physics.axisymmetric.interior import interior_dpdz, interior_stress
from stressfields.physics.axisymmetric.interior_cone import _cone_scalars, cone_dpdz_unit, cone_unit
from stressfields.physics.axisymmetric.surface import surface_stress

from interior_checks import NU, residuals as _residuals

CONE = ax.cone(0.3)
K = 0.15                                   # E* tan(theta)/2 per E*: the scale of cone_unit
PM = float(CONE.normal_force(1.0)) / math.pi


def _grid():
    rng = np.random.default_rng(5)
    r = np.concatenate([rng.uniform(0.0, 3.0, 150), np.repeat([0.0, 1e-12, 1e-6, 0.999, 1.0, 1.001, 3.0], 4)])
    z = np.concatenate([10 ** rng.uniform(-9, math.log10(30.0), 150), np.tile([1e-9, 1e-3, 1.0, 30.0], 7)])
    t = rng.uniform(0.0, 2 * math.pi, r.size)
    t[150:] = 0.0           # y = 0: r exact next to the edge ring, whose sensitivity is eps a/|r - a|
    return r * np.cos(t), r * np.sin(t), z


def test_closed_form_equals_the_one_d_route():
    """|closed - quadrature(rtol 1e-12)| <= 1e-12 max(|value|, p_m) (p_m/a for d p_h/dz); measured
    2.6e-15 (stresses) and 6e-14 (d p_h/dz, the quadrature's own error)."""
    x, y, z = _grid()
    closed = interior_stress(x, y, z, 1.0, NU, CONE)
    quadr = interior_stress(x, y, z, 1.0, NU, CONE, method="quadrature", rtol=1e-12)
    for k in ax.COMPONENTS:
        assert np.all(np.abs(closed[k] - quadr[k]) <= 1e-12 * np.maximum(np.abs(quadr[k]), PM)), k
    d_closed = interior_dpdz(x, y, z, 1.0, NU, CONE)
    d_quad = interior_dpdz(x, y, z, 1.0, NU, CONE, method="quadrature", rtol=1e-12)
    assert np.all(np.abs(d_closed - d_quad) <= 1e-12 * np.maximum(np.abs(d_quad), PM))


def test_power_law_n1_and_contact_radius_scaling():
    """The power law n = 1 is the cone; a contact radius a scales lengths only (stresses depend
    on x/a), d p_h/dz scales like 1/a."""
    x, y, z = _grid()
    s = interior_stress(2.0 * x, 2.0 * y, 2.0 * z, 2.0, NU, ax.power_law(0.3, 1.0))
    d = interior_dpdz(2.0 * x, 2.0 * y, 2.0 * z, 2.0, NU, ax.power_law(0.3, 1.0))
    u = cone_unit(x, y, z, NU)
    for k in ax.COMPONENTS:
        np.testing.assert_allclose(s[k], K * u[k], rtol=1e-14, atol=0)
    np.testing.assert_allclose(d, K / 2.0 * cone_dpdz_unit(x, y, z, NU), rtol=1e-14, atol=0)


def _printed(r, z, nu):
    """The functions of (I46)-(I52) as first derived ((I46), (I48) and the potentials of section
    'The cone'), in 300-digit decimal arithmetic: L, J, sigma_zz, E = (sigma_rr - sigma_tt)/r^2 split
    into its nu-free part and the (1 - 2 nu) part, T = sigma_rz/r, Sigma, d p_h/dz (a = 1, per
    E* tan/2)."""
    with decimal.localcontext() as ctx:
        ctx.prec = 300
        D = decimal.Decimal
        r, z, nu = D(r), D(z), D(nu)
        l2 = (((r + 1) ** 2 + z * z).sqrt() + ((r - 1) ** 2 + z * z).sqrt()) / 2
        l1 = r / l2
        q, R = (l2 * l2 - r * r).sqrt(), (r * r + z * z).sqrt()
        N, S, M = q / l2, l2 * l2 - l1 * l1, (l2 * l2 - 1).sqrt()
        L = ((l2 + q) / (R + z)).ln()
        J = L - N + z / R
        zz = -N ** 3 / S - J
        tt1 = -2 * nu * L + z * (l2 * l2 - R * R) / (q * (R * q + z * l2))
        B = (1 + l2 * q - z * R - 2 * q / l2) / (r * r)
        tt = tt1 - (1 - 2 * nu) * (B + L) / 2
        sig = -2 * (1 + nu) * L - zz
        ev = (1 - 2 * nu) * B / (r * r)
        e0 = (sig - 2 * tt) / (r * r) - ev
        dl2 = r * (l2 * l2 - 1) / (l2 * S)
        T = z * (dl2 / q - r / (q * (l2 + q)) - (r / R) / (R + z)) / r
        dpdz = 2 * (1 + nu) / 3 * (M / S - 1 / R)
        dterm = 2 * (1 + nu) / 3 * (M / S + 1 / R)
        return {k: float(v) for k, v in dict(L=L, J=J, zz=zz, e0=e0, ev=ev, T=T, Sigma=sig, dpdz=dpdz,
                                             dterm=dterm).items()}


# (r, z): axis (r = 0 evaluated at r = 1e-30 in 300 digits, where it differs by O(r^2)), next to it,
# the tip, the surface inside and outside, the edge ring, the far field
EXTREME = [(0.0, 1e-12), (0.0, 0.3), (0.0, 1e4), (1e-16, 1e-12), (1e-16, 0.5), (1e-8, 1e-9), (1e-8, 2.0),
           (1e-12, 1e-12), (0.3, 1e-14), (0.7, 1e-10), (1.0 - 2 ** -40, 1e-12), (1.0, 1e-12), (1.0 + 2 ** -40, 1e-12),
           (1.5, 1e-14), (2.0, 0.5), (1e2, 1e-6), (1e3, 1e3), (1e4, 1e-2), (1e4, 1e4), (3e3, 1e4), (0.0, 1e6)]


@pytest.mark.parametrize("r, z", EXTREME)
def test_against_extended_precision(r, z):
    """Relative error <= 1e-12 of |value| for the terms of one sign (L, J, sigma_zz, T, and the two
    parts of E), of the largest term for the sums (Sigma, d p_h/dz); y = 0 so that r - 1 is exact."""
    s = _cone_scalars(np.array([r]), np.zeros(1), np.array([z]), NU)
    ref = _printed(max(r, 1e-30), z, NU)
    for k in ("L", "J", "zz", "T"):
        assert abs(float(s[k][0]) - ref[k]) <= 1e-12 * abs(ref[k]), (k, float(s[k][0]), ref[k])
    assert abs(float(s["E"][0]) - ref["e0"] - ref["ev"]) <= 1e-12 * (abs(ref["e0"]) + abs(ref["ev"]))
    big = 2 * (1 + NU) * ref["L"] + abs(ref["zz"])
    assert abs(float(s["Sigma"][0]) - ref["Sigma"]) <= 1e-12 * big
    d = float(cone_dpdz_unit(r, 0.0, z, NU))
    assert abs(d - ref["dpdz"]) <= 1e-12 * ref["dterm"], (d, ref["dpdz"])


def test_equilibrium_and_compatibility_fall_like_h2():
    coarse, fine = _residuals(cone_unit, 1e-3), _residuals(cone_unit, 5e-4)
    for c, fi in zip(coarse, fine):
        assert fi < 2e-4 and 3.5 < c / fi < 4.5        # O(h^2): the field solves both PDEs


def _punch_axis_zz(z, rho):
    """sigma_zz(0, 0, z) of a flat punch of radius rho pressed to depth 1 (E* = 1): Boussinesq's
    -3 P z^3/(2 pi R^5) over its pressure 1/(pi sqrt(rho^2 - s^2)) (s = rho sin(t) removes the root)."""
    f = lambda t: (rho * math.sin(t)) * 3 * z ** 3 / (rho * rho * math.sin(t) ** 2 + z * z) ** 2.5
    return -quad(f, 0.0, 0.5 * math.pi, epsabs=0, epsrel=1e-13, limit=200)[0] / math.pi


@pytest.mark.parametrize("z", [1e-3, 0.05, 0.4, 1.0, 5.0])
def test_axis_is_the_sum_of_punches(z):
    """sigma_zz on the axis: int_0^a g' sigma_zz^punch(z; rho) d rho (I15) with the punches' axis
    values from Boussinesq (two nested quadratures), against the closed form at r = 0 and 1e-12."""
    dg = float(CONE.dg(1.0))
    ref = quad(lambda rho: dg * _punch_axis_zz(z, rho), 0.0, 1.0, epsabs=0, epsrel=1e-12, limit=200,
               points=[min(z, 0.5)])[0]
    for r in (0.0, 1e-12):
        s = interior_stress(r, 0.0, z, 1.0, NU, CONE)
        assert abs(float(s["zz"]) - ref) <= 2e-12 * abs(ref), (r, float(s["zz"]), ref)
        # the printed axis value (I51): -(1/(1 + z^2) + ln(1 + 1/z^2)/2) per E* tan/2
        assert float(s["zz"]) == pytest.approx(-K * (1 / (1 + z * z) + 0.5 * math.log1p(1 / (z * z))), rel=1e-13)


def test_tip_is_logarithmic():
    """r = 0, z -> 0: sigma_zz = -(1 + ln(1/z)) + O(z^2) per E* tan/2, finite down to z = 1e-300 a;
    off the axis the field next to the tip is log(1/R) times a constant plus a function of the
    direction (d p_h/dz is homogeneous of degree -1)."""
    z = np.array([1e-12, 1e-50, 1e-150, 1e-300])
    s = cone_unit(0.0 * z, 0.0 * z, z, NU)
    np.testing.assert_allclose(s["zz"], -(1.0 - np.log(z)), rtol=1e-14)
    assert all(np.all(np.isfinite(s[k])) for k in ax.COMPONENTS)
    # off the axis next to the tip the field is a function of the direction plus log(1/R): the
    # shears and the differences of normal stresses repeat at every scale, down to R = 1e-300 a
    p = np.array([0.6, 0.3, 0.5])
    scales = np.array([1e-8, 1e-100, 1e-150, 1e-200, 1e-290])
    t = cone_unit(p[0] * scales, p[1] * scales, p[2] * scales, NU)
    for k in ("xy", "xz", "yz"):
        np.testing.assert_allclose(t[k], t[k][0], rtol=1e-12, atol=0, err_msg=k)
    np.testing.assert_allclose(t["xx"] - t["yy"], (t["xx"] - t["yy"])[0], rtol=1e-10, atol=0)
    np.testing.assert_allclose(t["zz"] - t["zz"][0], -np.log(scales / scales[0]) * (t["zz"][1] - t["zz"][0])
                               / -np.log(scales[1] / scales[0]), rtol=1e-12)
    d = cone_dpdz_unit(p[0] * scales, p[1] * scales, p[2] * scales, NU)
    np.testing.assert_allclose(d * scales, d[0] * scales[0], rtol=1e-12)     # homogeneous of degree -1


def test_surface_limit_matches_surface_kernels():
    """z = 0 (the closed form itself, off the tip) and z = 1e-13 a against the surface kernels'
    closed forms (docs/theory/axisymmetric.md (A12)-(A13)), the edge ring r = a included."""
    r = np.array([1e-9, 0.1, 0.5, 0.9, 0.999, 1.0, 1.001, 1.5, 3.0])
    x, y = r * math.cos(0.4), r * math.sin(0.4)
    ref = surface_stress(x, y, 1.0, 1.0, NU, 0.0, CONE, method="closed")
    at0 = cone_unit(x, y, 0.0, NU)
    near = interior_stress(x, y, 1e-13, 1.0, NU, CONE)
    # z -> 0 is O(z/r) next to the tip and O(sqrt(z)) at the edge ring: both are left out at z > 0
    keep = (r > 1e-3) & (r != 1.0)
    for k in ax.COMPONENTS:
        np.testing.assert_allclose(K * at0[k], ref[k], rtol=1e-12, atol=1e-15 * PM, err_msg=k)
        np.testing.assert_allclose(near[k][keep], ref[k][keep], rtol=0, atol=1e-9 * PM, err_msg=k)
    top = interior_stress(x, y, 0.0, 1.0, NU, CONE)
    assert all(np.array_equal(top[k], ref[k]) for k in ax.COMPONENTS)


def test_far_field_is_boussinesq():
    """R = 1e2 ... 1e4 a: the point load F_N to relative O((a/R)^2), every component (y != 0)."""
    x = np.array([1e2, 3e3, 0.0, 7e3, 1e4])
    z = np.array([1e2, 5e3, 2e3, 1e4, 2e3])
    y = 0.5 * x
    r2 = x * x + y * y
    rho = np.sqrt(r2 + z * z)
    k = float(CONE.normal_force(1.0)) / (2 * math.pi)
    s = interior_stress(x, y, z, 1.0, NU, CONE)
    tol = 20 / rho.min() ** 2
    np.testing.assert_allclose(s["zz"], -3 * k * z ** 3 / rho ** 5, rtol=tol, atol=0)
    np.testing.assert_allclose(s["xz"], -3 * k * x * z ** 2 / rho ** 5, rtol=tol, atol=0)
    np.testing.assert_allclose(s["yz"], -3 * k * y * z ** 2 / rho ** 5, rtol=tol, atol=0)
    np.testing.assert_allclose(s["xx"] + s["yy"], k * ((1 - 2 * NU) * z / rho ** 3 - 3 * z * r2 / rho ** 5),
                               rtol=tol, atol=0)
    d = interior_dpdz(x, y, z, 1.0, NU, CONE)        # p_h = (2/3)(1 + nu) k z / R^3
    np.testing.assert_allclose(d, 2 * (1 + NU) / 3 * k * (1 / rho ** 3 - 3 * z * z / rho ** 5), rtol=tol, atol=0)


def test_routes():
    rc = ax.resolve_interior("cone", "auto", 1e-10)
    assert rc.kernel == "closed" and "1e-12 of |value|" in rc.accuracy
    assert ax.resolve_interior("power_law", "closed", 1e-10, n=1.0).kernel == "closed"
    assert ax.has_interior_closed_form("cone") and ax.has_interior_closed_form("power_law", 1.0)
    assert not ax.has_interior_closed_form("power_law", 1.5)
    mixed = ax.resolve_interior("cone", "auto", 1e-10, tangential=True)
    assert mixed.kernel == "auto" and "normal part" in mixed.route and "(I33)" in mixed.route
    with pytest.raises(ValueError, match="tangential"):
        ax.resolve_interior("cone", "closed", 1e-10, tangential=True)
    assert ax.resolve_interior("cone", "quadrature", 1e-10).kernel == "quadrature"
    s = interior_stress(0.3, 0.2, 0.5, 1.0, NU, CONE, method="closed")
    assert float(s["zz"]) == pytest.approx(K * float(cone_unit(0.3, 0.2, 0.5, NU)["zz"]), rel=1e-15)


def test_closed_form_flag_under_tangential_load():
    """The scenarios' check: the cone has a closed form below the surface under normal load only."""
    assert ax.has_interior_closed_form("cone") and not ax.has_interior_closed_form("cone", tangential=True)
    assert not ax.has_interior_closed_form("power_law", 1.0, tangential=True)
    assert ax.has_interior_closed_form("paraboloid", tangential=True)
    assert ax.has_interior_closed_form("power_law", 2.0, tangential=True)
    assert ax.has_interior_closed_form("flat_punch", tangential=True)
    assert not ax.has_interior_closed_form("tabulated")
