"""The Hertz sliding field and the Cattaneo–Mindlin partial-slip field below the surface
(docs/theory/interior.md (I18)-(I23)) against routes that share no code with them:

* oracle-free: equilibrium and Beltrami–Michell compatibility by central differences (the residual
  must fall like h^2; a field with nu perturbed must fail) and the traction conditions at z -> 0;
* the defining integral: the Cerruti point load (its textbook displacements, differentiated by
  complex step) integrated over the traction q0 sqrt(1 - r^2) by a 2-D product rule;
* on the axis, the same integral reduced to 1-D; next to it, the closed form in np.longdouble;
* the surface kernels of the family (docs/theory/axisymmetric.md (A34)-(A36)) at z = 0;
* the Cerruti point load in the far field.
"""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from stressfields.physics import axisymmetric as ax
from stressfields.physics.axisymmetric.hertz_geometry import geometry
from stressfields.physics.axisymmetric.interior_hertz import (_sliding_cartesian, sliding_punch_unit, sliding_scalars,
                                                             sliding_unit)
from stressfields.physics.axisymmetric.interior_tangential import interior_stress_tangential
from stressfields.physics.axisymmetric.surface import surface_stress

from interior_checks import NU, POINTS, residuals as _residuals


def test_equilibrium_and_compatibility_fall_like_h2():
    coarse, fine = _residuals(sliding_unit, 1e-3), _residuals(sliding_unit, 5e-4)
    for c, fi in zip(coarse, fine):
        assert fi < 1e-4 and 3.5 < c / fi < 4.5        # O(h^2): the field solves both PDEs


def test_residual_check_discriminates():
    def wrong(x, y, z, nu):
        s = sliding_unit(x, y, z, nu)
        s["xx"] = sliding_unit(x, y, z, nu * 1.01)["xx"]
        return s
    assert _residuals(wrong, 5e-4)[1] > 30 * _residuals(sliding_unit, 5e-4)[1]


def test_traction_boundary_conditions():
    """z -> 0: sigma_xz = -q = -sqrt(1 - r^2) inside, 0 outside; sigma_zz = sigma_yz = 0."""
    r = np.array([0.0, 0.3, 0.6, 0.9, 1.2, 2.0])
    for z in (0.0, 1e-12, 1e-10):
        s = sliding_unit(r * 0.8, r * 0.6, z, NU)
        assert np.allclose(s["xz"], -np.sqrt(np.clip(1 - r * r, 0, None)), rtol=0, atol=1e-9)
        assert np.all(np.abs(s["zz"]) < 1e-9) and np.all(np.abs(s["yz"]) < 1e-9)


# -- the defining integral: Cerruti point loads over the traction ---------------------------------

def _cerruti_u(x, y, z, nu):
    """Displacements (G = 1, unit force along +x at the origin) of the Cerruti point load (Johnson,
    Contact Mechanics 1985, sec. 3.2)."""
    rho = np.sqrt(x * x + y * y + z * z)
    k, b = 1 / (4 * math.pi), 1 - 2 * nu
    ux = k * (1 / rho + x * x / rho ** 3 + b * (1 / (rho + z) - x * x / (rho * (rho + z) ** 2)))
    uy = k * (x * y / rho ** 3 - b * x * y / (rho * (rho + z) ** 2))
    uz = k * (x * z / rho ** 3 + b * x / (rho * (rho + z)))
    return ux, uy, uz


def _cerruti_stress(x, y, z, nu):
    """Hooke's law on the complex-step gradient of ``_cerruti_u`` (exact to rounding)."""
    h = 1e-30
    grad = np.empty((3, 3) + np.shape(x))
    for j in range(3):
        p = [np.asarray(v, dtype=complex) for v in (x, y, z)]
        p[j] = p[j] + 1j * h
        for i, u in enumerate(_cerruti_u(*p, nu)):
            grad[i, j] = u.imag / h
    lam = 2 * nu / (1 - 2 * nu)
    div = grad[0, 0] + grad[1, 1] + grad[2, 2]
    s = grad + np.swapaxes(grad, 0, 1) + lam * div * np.eye(3).reshape(3, 3, *([1] * np.ndim(x)))
    return {c: s["xyz".index(c[0]), "xyz".index(c[1])] for c in ax.COMPONENTS}


def _defining_integral(x, y, z, n_theta=160, n_phi=160):
    """int over the disc of sqrt(1 - s^2) times the Cerruti field at (x - xi, y - eta, z): s = sin t
    removes the square-root edge, Gauss–Legendre in t, the periodic trapezoid rule in the angle."""
    t, w = np.polynomial.legendre.leggauss(n_theta)
    t, w = (t + 1) * math.pi / 4, w * math.pi / 4
    ang = 2 * math.pi * np.arange(n_phi) / n_phi
    s = np.sin(t)[:, None]
    weight = (w * np.cos(t) ** 2 * np.sin(t))[:, None] * (2 * math.pi / n_phi)
    st = _cerruti_stress(x - s * np.cos(ang), y - s * np.sin(ang), z + 0 * s * ang, NU)
    return {c: float(np.sum(weight * v)) for c, v in st.items()}


@pytest.mark.parametrize("p", [(0.3, 0.2, 0.5), (-0.8, 0.5, 0.7), (1.3, -0.4, 0.6), (0.0, 0.9, 1.5)])
def test_against_the_defining_integral(p):
    ref = _defining_integral(*p)
    s = sliding_unit(*p, NU)
    scale = max(abs(v) for v in ref.values())
    for c in ax.COMPONENTS:
        assert abs(float(s[c]) - ref[c]) <= 1e-12 * scale, (c, float(s[c]), ref[c])


# -- the axis -------------------------------------------------------------------------------------

def _axis_xz(z):
    """sigma_xz(0, 0, z) / q0: the Cerruti sigma_xz = -3 x^2 z / (2 pi rho^5) over rings of the
    traction, the angle done by hand (cos^2 averages to 1/2)."""
    f = lambda s: math.sqrt(1 - s * s) * s ** 3 * z / (s * s + z * z) ** 2.5
    return -1.5 * quad(f, 0, 1, epsabs=0, epsrel=1e-13, limit=200, points=[z])[0]


def _longdouble(x, y, z):
    x, y, z = (np.asarray(v, dtype=np.longdouble) for v in (x, y, z))
    g = geometry(x, y, z)
    return _sliding_cartesian(x, y, z, np.longdouble(NU), sliding_scalars(g), g["N"])


@pytest.mark.parametrize("r", [0.0, 1e-16, 1e-8])
def test_near_axis_without_cancellation(r):
    z = np.array([0.01, 0.2, 0.5, 1.0, 2.0, 5.0])
    for phi in (0.0, 0.7, 2.5):
        x, y = r * math.cos(phi), r * math.sin(phi)
        s, ref = sliding_unit(x, y, z, NU), _longdouble(x, y, z)
        for c in ax.COMPONENTS:
            err = np.abs(s[c] - ref[c].astype(float))
            assert np.all(err <= 1e-13 * np.maximum(np.abs(ref[c].astype(float)), 1e-300) + 1e-300), (c, r)
        assert np.allclose(s["xz"], [_axis_xz(v) for v in z], rtol=1e-12, atol=0)
    # the odd components are O(r): their slopes at r = 1e-16 and 1e-8 agree with r = 1e-4
    slope = lambda rr: {c: sliding_unit(rr, 0.0, z, NU)[c] / rr for c in ("xx", "yy", "zz")}
    if r > 0:
        near, ref = slope(r), slope(1e-4)
        for c in near:
            assert np.allclose(near[c], ref[c], rtol=1e-7, atol=0)


def test_far_field_is_cerruti():
    """r, z ~ 1e3 ... 1e4: the point load Q = 2 pi q0 a^2 / 3 to relative O((a/R)^2)."""
    x = np.array([1e3, 3e3, -2e3, 7e3, 1e4])
    z = np.array([1e3, 5e3, 2e3, 1e4, 2e3])
    y = np.array([5e2, -1e3, 4e3, 0.0, 3e3])
    rho = np.sqrt(x * x + y * y + z * z)
    ref = _cerruti_stress(x, y, z, NU)
    s = sliding_unit(x, y, z, NU)
    q = 2 * math.pi / 3
    for c in ax.COMPONENTS:
        scale = np.max([np.abs(ref[k]) for k in ax.COMPONENTS], axis=0) * q
        assert np.all(np.abs(s[c] - q * ref[c]) <= 20 / rho ** 2 * scale), c


# -- partial slip and the entry point ---------------------------------------------------------------

@pytest.mark.parametrize("c", [0.0, 0.3])
def test_partial_slip_surface_equals_surface_kernels(c):
    """Tangential part at z = 0 and z -> 0 against the surface kernels (paraboloid R = 2, a = 0.5,
    mu = 0.4): surface_stress(mu) - surface_stress(mu = 0); the edge rings r = a and r = c are
    approached like sqrt(z) and left out at z > 0."""
    R, a, mu = 2.0, 0.5, 0.4
    r = np.array([0.0, 1e-9, 0.1, 0.25, 0.3, 0.4, 0.499, 0.5, 0.501, 0.7, 3.0])
    x, y = r * math.cos(0.4), r * math.sin(0.4)
    par = ax.paraboloid(R)
    ref = {k: surface_stress(x, y, a, c, NU, mu, par)[k] - surface_stress(x, y, a, a, NU, 0.0, par)[k]
           for k in ax.COMPONENTS}
    scale = mu * 2 * a / (math.pi * R)
    for z, tol, keep in ((0.0, 1e-13, r >= 0), (1e-13, 1e-9, (r != a) & (r != c))):
        s = interior_stress_tangential(x, y, z, a, c, NU, mu, par)
        for k in ax.COMPONENTS:
            assert np.allclose(s[k][keep], ref[k][keep], rtol=0, atol=tol * scale), (k, z)


def test_partial_slip_is_the_difference_of_two_sliding_fields():
    """(I23) with its scaling: sigma_xz(z = 0) = -mu p0 [sqrt(1 - r^2/a^2) - (c/a) sqrt(1 - r^2/c^2)];
    c = a gives no tangential field; the stick-zone traction is the Cattaneo–Mindlin one."""
    R, a, c, mu = 1.5, 0.8, 0.5, 0.3
    p0 = 2 * a / (math.pi * R)
    r = np.array([0.0, 0.2, 0.49, 0.6, 0.79, 0.9])
    s = interior_stress_tangential(r, 0.0, 0.0, a, c, NU, mu, ax.paraboloid(R))
    q = mu * p0 * (np.sqrt(np.clip(1 - r * r / a / a, 0, None)) - c / a * np.sqrt(np.clip(1 - r * r / c / c, 0, None)))
    assert np.allclose(s["xz"], -q, rtol=1e-14, atol=1e-16)
    z = np.linspace(0, 2, 5)
    none = interior_stress_tangential(0.3, 0.1, z, a, a, NU, mu, ax.paraboloid(R))
    assert all(np.all(none[k] == 0.0) for k in ax.COMPONENTS)
    gross = interior_stress_tangential(0.3, 0.1, z, a, 0.0, NU, mu, ax.paraboloid(R))
    unit = sliding_unit(0.3 / a, 0.1 / a, z / a, NU)
    assert all(np.allclose(gross[k], mu * p0 * unit[k], rtol=1e-15, atol=0) for k in ax.COMPONENTS)


def test_edge_rings_are_finite_and_continuous():
    """The limit on the edge ring exists (I22); it is approached like sqrt(distance)."""
    s = sliding_unit(np.array([1.0, 0.6]), np.array([0.0, 0.8]), 0.0, NU)
    near = sliding_unit(np.array([1.0, 0.6]) * (1 + 1e-12), np.array([0.0, 0.8]) * (1 + 1e-12), 1e-14, NU)
    for k in ax.COMPONENTS:
        assert np.all(np.isfinite(s[k])) and np.allclose(s[k], near[k], rtol=0, atol=10 * 1e-6), k


def test_validation():
    par = ax.paraboloid(1.0)
    with pytest.raises(ValueError, match="closed"):
        interior_stress_tangential(0.0, 0.0, 1.0, 1.0, 0.0, NU, 0.3, ax.cone(0.2), method="closed")
    for bad in (dict(z=-1.0), dict(c=2.0), dict(nu=0.6), dict(mu=-0.1)):
        args = dict(z=1.0, c=0.5, nu=NU, mu=0.3) | bad
        with pytest.raises(ValueError):
            interior_stress_tangential(0.0, 0.0, args["z"], 1.0, args["c"], args["nu"], args["mu"], par)
    with pytest.raises(ValueError, match="method"):
        interior_stress_tangential(0.0, 0.0, 1.0, 1.0, 0.0, NU, 0.3, par, method="series")
    with pytest.raises(ValueError, match="punch radius"):
        interior_stress_tangential(0.0, 0.0, 1.0, 2.0, 0.0, NU, 0.3, ax.flat_punch(1.0))


# -- the sliding punch K_T and the superposition of sliding punches (I30)-(I33) ----------------------

CONE, CUBIC = ax.cone(0.3), ax.power_law(0.7, 3.0)


def test_sliding_punch_is_the_rho_derivative_of_the_sliding_field():
    """(I30): pi K_T = d/d rho [rho T(x/rho)] at rho = 1, by a Richardson-extrapolated central
    difference of the Hertz sliding field (error O(h^4) = 1e-12, rounding eps/h = 1e-13)."""
    x, y, z = POINTS.T
    bt = lambda b: {k: b * v for k, v in sliding_unit(x / b, y / b, z / b, NU).items()}
    d = lambda h: {k: (bt(1 + h)[k] - bt(1 - h)[k]) / (2 * h) for k in ax.COMPONENTS}
    d1, d2 = d(1e-3), d(5e-4)
    u = sliding_punch_unit(x, y, z, NU)
    for k in ax.COMPONENTS:
        ref = (4 * d2[k] - d1[k]) / (3 * math.pi)
        assert np.max(np.abs(u[k] - ref)) <= 1e-10 * np.max(np.abs(ref)), k


def test_sliding_punch_solves_the_pdes_and_traction():
    coarse, fine = _residuals(sliding_punch_unit, 1e-3), _residuals(sliding_punch_unit, 5e-4)
    for c, fi in zip(coarse, fine):
        assert fi < 1e-3 and 3.5 < c / fi < 4.5
    r = np.array([0.0, 0.3, 0.6, 0.9, 1.2, 2.0])
    s = sliding_punch_unit(r * 0.8, r * 0.6, 0.0, NU)
    q = np.where(r < 1, 1 / (math.pi * np.sqrt(np.abs(1 - r * r))), 0.0)
    assert np.allclose(s["xz"], -q, rtol=1e-14, atol=0)
    assert np.all(s["zz"] == 0.0) and np.all(s["yz"] == 0.0)
    # in-plane: 0 inside the punch, (A42)-(A44) outside (the surface kernels' flat punch)
    fp = ax.flat_punch(1.0)
    ref = {k: surface_stress(r * 0.8, r * 0.6, 1.0, 0.0, NU, 1.0, fp)[k]
           - surface_stress(r * 0.8, r * 0.6, 1.0, 1.0, NU, 0.0, fp)[k] for k in ("xx", "yy", "xy")}
    for k in ref:
        assert np.allclose(s[k], ref[k], rtol=1e-13, atol=1e-16), k


def test_sliding_punch_edge_ring():
    """(I32): on r = 1, z = 0 sigma_xz = -inf, sigma_xx = -inf sgn x, 0 where odd by symmetry, NaN
    where the sign depends on the direction (sigma_zz off x = 0)."""
    x, y = np.array([1.0, -1.0, 0.0, 0.6]), np.array([0.0, 0.0, 1.0, 0.8])
    s = sliding_punch_unit(x, y, 0.0, NU)
    assert np.all(s["xz"] == -math.inf)
    assert list(s["xx"]) == [-math.inf, math.inf, 0.0, -math.inf]
    assert list(s["xy"][:3]) == [0.0, 0.0, -math.inf] and s["yz"][0] == 0.0 and s["yz"][2] == 0.0
    assert np.isnan(s["zz"][0]) and s["zz"][2] == 0.0 and np.isnan(s["yz"][3])
    # the sign of -inf is the one of the field next to the ring, in every direction into the body
    om = np.linspace(0.01, math.pi - 0.01, 50)
    near = sliding_punch_unit(0.6 * (1 + 1e-9 * np.cos(om)), 0.8 * (1 + 1e-9 * np.cos(om)), 1e-9 * np.sin(om), NU)
    for k in ("xx", "xy", "xz"):
        assert np.all(near[k] < 0.0), k


def _tangential(profile, c, rtol=1e-12, mu=1.0):
    return lambda x, y, z, nu: interior_stress_tangential(x, y, z, 1.0, c, nu, mu, profile, rtol=rtol)


@pytest.mark.parametrize("profile", [CONE, CUBIC], ids=["cone", "power3"])
def test_one_d_route_solves_the_pdes(profile):
    coarse, fine = _residuals(_tangential(profile, 0.4), 1e-3), _residuals(_tangential(profile, 0.4), 5e-4)
    for c, fi in zip(coarse, fine):
        assert fi < 1e-4 and 3.5 < c / fi < 4.5


@pytest.mark.parametrize("c", [0.0, 0.4])
@pytest.mark.parametrize("profile", [CONE, CUBIC], ids=["cone", "power3"])
def test_one_d_route_traction_equals_surface_kernels(profile, c):
    """z -> 0+: the traction (sigma_xz, sigma_yz, sigma_zz) and the in-plane stresses tend to the
    surface kernels' tangential part (closed forms for the cone, quadrature for n = 3)."""
    r = np.array([0.05, 0.2, 0.35, 0.5, 0.8, 0.95, 1.1, 2.0])
    x, y = r * math.cos(0.7), r * math.sin(0.7)
    method = "closed" if profile is CONE else "quadrature"
    ref = {k: surface_stress(x, y, 1.0, c, NU, 0.5, profile, method=method)[k]
           - surface_stress(x, y, 1.0, 1.0, NU, 0.0, profile, method=method)[k] for k in ax.COMPONENTS}
    pm = float(profile.normal_force(1.0)) / math.pi
    s = interior_stress_tangential(x, y, 1e-10, 1.0, c, NU, 0.5, profile)
    for k in ax.COMPONENTS:
        assert np.allclose(s[k], ref[k], rtol=0, atol=1e-8 * pm), k


@pytest.mark.parametrize("c", [0.0, 0.5, 0.999])
def test_one_d_route_equals_the_paraboloid_closed_form(c):
    rng = np.random.default_rng(3)
    r = np.concatenate([rng.uniform(0, 3, 80), [0.0, 1e-12, 0.5, 0.999, 1.0, 1.001]])
    t = rng.uniform(0, 2 * math.pi, r.size)
    x, y, z = r * np.cos(t), r * np.sin(t), 10 ** rng.uniform(-10, 1.3, r.size)
    par, mu = ax.paraboloid(1.5), 0.4
    smu = mu * float(par.normal_force(1.0)) / math.pi
    closed = interior_stress_tangential(x, y, z, 1.0, c, NU, mu, par)
    for rtol in (1e-6, 1e-10):
        q = interior_stress_tangential(x, y, z, 1.0, c, NU, mu, par, method="quadrature", rtol=rtol)
        for k in ax.COMPONENTS:
            assert np.all(np.abs(q[k] - closed[k]) <= rtol * np.maximum(np.abs(closed[k]), smu)), (k, rtol)


def _cone_axis_xz(z, c, t=0.3, mu=1.0):
    """sigma_xz(0, 0, z) of the cone: Cerruti's sigma_xz = -3 x^2 z/(2 pi rho^5) over rings of the
    traction q = mu p0 [arccosh(1/s) - arccosh(c/s)] (p0 = tan(theta)/2 per E*, (A36)), a = 1."""
    q = lambda s: 0.5 * t * mu * (math.acosh(1 / s) - (math.acosh(c / s) if s < c else 0.0))
    f = lambda s: q(s) * s ** 3 * z / (s * s + z * z) ** 2.5
    pts = sorted({z, c} - {0.0})
    return -1.5 * quad(f, 0, 1, epsabs=0, epsrel=1e-13, limit=400, points=pts)[0]


@pytest.mark.parametrize("c", [0.0, 0.4])
def test_cone_axis_against_cerruti_rings(c):
    z = np.array([1e-3, 0.05, 0.4, 1.0, 3.0])
    for r in (0.0, 1e-9):
        s = interior_stress_tangential(r, 0.0, z, 1.0, c, NU, 1.0, CONE, rtol=1e-12)
        ref = np.array([_cone_axis_xz(v, c) for v in z])
        assert np.allclose(s["xz"], ref, rtol=1e-11, atol=0), r
        for k in ("xx", "yy", "zz", "xy", "yz"):         # O(r): zero on the axis
            assert np.all(np.abs(s[k]) <= 1e3 * r / z + 1e-14 * np.abs(ref)), k   # slope ~ 1/z (log tip)


def test_cone_far_field_is_cerruti():
    """R = 1e2 ... 1e3 a: the point load Q = mu (F(a) - F(c)) to relative O((a/R)^2)."""
    x = np.array([1e2, 3e2, -2e2, 7e2, 1e3])
    z = np.array([1e2, 5e2, 2e2, 1e3, 2e2])
    y = np.array([50.0, -1e2, 4e2, 0.0, 3e2])
    rho = np.sqrt(x * x + y * y + z * z)
    c, mu = 0.4, 0.5
    Q = mu * float(CONE.normal_force(1.0) - CONE.normal_force(c))
    ref = _cerruti_stress(x, y, z, NU)
    s = interior_stress_tangential(x, y, z, 1.0, c, NU, mu, CONE)
    scale = np.max([np.abs(ref[k]) for k in ax.COMPONENTS], axis=0) * Q
    for k in ax.COMPONENTS:
        assert np.all(np.abs(s[k] - Q * ref[k]) <= 20 / rho ** 2 * scale), k


def test_flat_punch_and_no_load():
    fp = ax.flat_punch(0.5, 0.02)
    x, y, z = POINTS.T * 0.5
    s = interior_stress_tangential(x, y, z, 0.5, 0.2, NU, 0.3, fp, method="quadrature")
    u = sliding_punch_unit(x / 0.5, y / 0.5, z / 0.5, NU)
    assert all(np.allclose(s[k], 0.3 * 0.02 / 0.5 * u[k], rtol=1e-15, atol=0) for k in ax.COMPONENTS)
    for prof, c, mu in ((fp, 0.5, 0.3), (CONE, 0.3, 0.0), (CONE, 0.5, 0.3)):
        a = 0.5
        none = interior_stress_tangential(x, y, z, a, c, NU, mu, prof)
        assert all(np.all(none[k] == 0.0) for k in ax.COMPONENTS)


# -- partial slip of tips g' ~ rho^(n-1), n < 1, at rtol = 1e-12: the direct integral over [c, a] (I45) --

TIPS = [ax.power_law(0.7, 0.5), ax.power_law(0.7, 0.8)]
SLIP_POINTS = [(0.0, 0.0, 7.6e-10), (0.0, 0.0, 1e-3), (1e-9, 0.0, 1e-6), (0.3, 0.1, 1e-8), (0.45, 0.0, 1e-4),
               (0.7, 0.2, 0.01), (1.5, 0.5, 0.3), (2.0, 1.0, 5.0)]


def _sliding_defining_integral(x, y, z, c, profile):
    """int_c^1 K_T(x; rho) g'(rho) d rho (I33) by adaptive quadrature (QUADPACK, break points at the
    layer rho = r, r +- z): a rule that shares no panels or nodes with the 1-D route."""
    r = math.hypot(x, y)
    pts = sorted({p for p in (r, r - z, r + z) if c < p < 1.0}) or None
    out = {}
    for k in ax.COMPONENTS:
        f = lambda rho: float(sliding_punch_unit(x / rho, y / rho, z / rho, NU, rm1=(r - rho) / rho)[k]
                              * profile.dg(rho)) / rho
        out[k] = quad(f, c, 1.0, epsabs=0, epsrel=2e-14, limit=1000, points=pts)[0]
    return out


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
@pytest.mark.parametrize("c", [0.4, 0.9])
@pytest.mark.parametrize("profile", TIPS, ids=["n0.5", "n0.8"])
def test_tip_partial_slip_at_rtol_1e12(profile, c):
    """Power laws n < 1 in partial slip at rtol = 1e-12 (the floor was 1e-11 while partial slip was
    Sigma_T(a) - Sigma_T(c); axis points at z = 7.6e-10 a lost 2e-11 mu p_m): |error| <=
    1e-12 max(|value|, mu p_m) against the defining integral; measured at most 3e-15."""
    pm = float(profile.normal_force(1.0)) / math.pi
    for x, y, z in SLIP_POINTS:
        s = interior_stress_tangential(x, y, z, 1.0, c, NU, 1.0, profile, rtol=1e-12)
        ref = _sliding_defining_integral(x, y, z, c, profile)
        for k in ax.COMPONENTS:
            assert abs(float(s[k]) - ref[k]) <= 1e-12 * max(abs(ref[k]), pm), (x, y, z, k, float(s[k]), ref[k])


def _tip_axis_xz(z, c, profile, mu=1.0):
    """sigma_xz(0, 0, z): Cerruti rings over the traction q(s) = (mu/pi) int_max(s,c)^1 g'(rho) d rho /
    sqrt(rho^2 - s^2) (rho = s cosh t removes the root), a = 1; no kernel of the package involved."""
    def q(s):
        t0 = math.acosh(max(s, c) / s)
        return mu / math.pi * quad(lambda t: float(profile.dg(s * math.cosh(t))), t0, math.acosh(1.0 / s),
                                   epsabs=0, epsrel=1e-13, limit=200)[0]
    f = lambda s: q(s) * s ** 3 * z / (s * s + z * z) ** 2.5
    pts = sorted({min(z, 0.5), c})
    return -1.5 * quad(f, 0, 1, epsabs=0, epsrel=1e-13, limit=400, points=pts)[0]


@pytest.mark.parametrize("profile", TIPS, ids=["n0.5", "n0.8"])
def test_tip_partial_slip_axis_against_cerruti_rings(profile):
    z = np.array([1e-3, 0.05, 0.4, 2.0])
    s = interior_stress_tangential(0.0, 0.0, z, 1.0, 0.4, NU, 1.0, profile, rtol=1e-12)
    ref = np.array([_tip_axis_xz(v, 0.4, profile) for v in z])
    assert np.allclose(s["xz"], ref, rtol=1e-11, atol=0)


_SPLINE_KNOTS = np.linspace(0.0, 1.2, 13)
SPLINE = ax.tabulated(_SPLINE_KNOTS, _SPLINE_KNOTS ** 2 / 2 + 0.3 * _SPLINE_KNOTS ** 4)


@pytest.mark.parametrize("profile", [CONE, CUBIC, SPLINE] + TIPS, ids=["cone", "power3", "spline", "n0.5", "n0.8"])
def test_direct_partial_slip_equals_the_difference_of_two_superpositions(profile):
    """The integral over [c, a] (I45) against Sigma_T(a) - Sigma_T(c) (I33), two integrals over
    [0, a] and [0, c] on their own panels; away from the axis tip, where that difference is sound."""
    rng = np.random.default_rng(11)
    r = rng.uniform(0.0, 3.0, 40)
    t = rng.uniform(0.0, 2 * math.pi, r.size)
    x, y, z = r * np.cos(t), r * np.sin(t), 10 ** rng.uniform(-3, 1, r.size)
    pm = float(profile.normal_force(1.0)) / math.pi
    s = interior_stress_tangential(x, y, z, 1.0, 0.4, NU, 1.0, profile, rtol=1e-12)
    scaled = (interior_stress_tangential(x / 0.4, y / 0.4, z / 0.4, 1.0, 0.0, NU, 1.0, profile, rtol=1e-12)
              if profile.kind == "cone" else None)
    full = interior_stress_tangential(x, y, z, 1.0, 0.0, NU, 1.0, profile, rtol=1e-12)
    inner = interior_stress_tangential(x, y, z, 0.4, 0.0, NU, 1.0, profile, rtol=1e-12)
    for k in ax.COMPONENTS:
        assert np.all(np.abs(s[k] - (full[k] - inner[k])) <= 1e-11 * np.maximum(np.abs(s[k]), pm)), k
    if scaled is not None:           # the cone's g' is constant: Sigma_T(x; b) = Sigma_T(x/b; 1)
        for k in ax.COMPONENTS:
            assert np.allclose(inner[k], scaled[k], rtol=1e-11, atol=1e-14 * pm), k
