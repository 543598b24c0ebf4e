"""Displacements of the axisymmetric contacts (docs/theory/interior.md (I36)-(I44)) against routes
that share no code with them:

* Hooke's law: the strains of the displacements (5-point central differences) against the
  family's stress kernels (``interior_stress``, ``interior_stress_tangential``), all six
  components, closed forms and 1-D routes, normal load and partial slip;
* the surface conditions: u_z = delta - f(r) in the contact, u_x = u_x0 (tangential part) and
  u_y = 0 in the stick zone;
* the defining integrals: the Boussinesq and Cerruti point-load displacements (Johnson 1985,
  sec. 2.2-2.3) integrated over the pressure and the traction (adaptive quadrature in the radius,
  periodic trapezoid in the angle);
* the surface integrals outside the contact (Mossakovskii: the cone's u_z in closed form; the
  radial displacement -(1 - 2 nu) F_N/(2 pi (1 - nu) r) per E*);
* the point loads in the far field; the axis r = 0, 1e-16 a, 1e-8 a;
* the 1-D route against the closed forms (paraboloid normal and partial slip).
"""
import math

import numpy as np
import pytest
from scipy.integrate import quad, quad_vec

from stressfields.physics import axisymmetric as ax
from stressfields.physics.axisymmetric.displacement import (displacements, hertz_displacement_unit,
                                                             hertz_sliding_displacement_unit,
                                                             punch_displacement_unit,
                                                             sliding_punch_displacement_unit)
from stressfields.physics.axisymmetric.loading import stick as _stick
from stressfields.physics.axisymmetric.interior import interior_stress
from stressfields.physics.axisymmetric.interior_hertz import (hertz_unit, punch_unit, sliding_punch_unit,
                                                             sliding_unit)
from stressfields.physics.axisymmetric.interior_tangential import interior_stress_tangential

NAMES = ("u_x", "u_y", "u_z")
PAIRS = {"xx": (0, 0), "yy": (1, 1), "zz": (2, 2), "xy": (0, 1), "xz": (0, 2), "yz": (1, 2)}
POINTS = [(0.3, 0.2, 0.5), (1.3, -0.4, 0.2), (0.1, 0.05, 2.0), (2.0, 1.0, 1.0), (0.0, 0.0, 0.7),
          (-0.6, 0.5, 0.05), (0.95, 0.1, 0.03)]


def _hooke(u, p, nu, h):
    """Hooke's law divided by 2G, eps + nu/(1 - 2 nu) tr(eps) I, with the strain of ``u`` (a
    function of a (3, k) array of points -> (3, k)) at the point p by 5-point differences."""
    p = np.asarray(p, float)
    steps = []
    for j in range(3):
        e = np.zeros(3)
        e[j] = h
        steps += [p + 2 * e, p + e, p - e, p - 2 * e]
    v = u(np.array(steps).T)
    grad = np.empty((3, 3))
    for j in range(3):
        up2, up, um, um2 = (v[:, 4 * j + k] for k in range(4))
        grad[:, j] = (8.0 * (up - um) - (up2 - um2)) / (12.0 * h)
    eps = 0.5 * (grad + grad.T)
    return eps + nu / (1.0 - 2.0 * nu) * np.trace(eps) * np.eye(3)


def _unit(fn, nu):
    return lambda P: np.array([fn(P[0], P[1], P[2], nu)[k] for k in "xyz"])


@pytest.mark.parametrize("disp, stress, scale", [
    (punch_displacement_unit, punch_unit, 1.0),
    (hertz_displacement_unit, hertz_unit, 2.0 / math.pi),          # p0 = 2/pi for a = R = delta = 1
    (sliding_punch_displacement_unit, sliding_punch_unit, 1.0),
    (hertz_sliding_displacement_unit, sliding_unit, 1.0),
])
@pytest.mark.parametrize("nu", [0.0, 0.3, 0.45])
def test_closed_forms_obey_hooke(disp, stress, scale, nu):
    # sigma / E* = 2 (G/E*) [eps + ...], G/E* = (1 - nu)/2 (E* = 1 in the unit kernels)
    for p in POINTS:
        ref = stress(*p, nu)
        big = max(abs(float(v)) for v in ref.values()) * scale
        s = (1.0 - nu) * _hooke(_unit(disp, nu), p, nu, 1e-3 * max(p[2], 0.02))
        for k, (i, j) in PAIRS.items():
            assert abs(s[i, j] - scale * float(ref[k])) <= 1e-8 * big, (p, k)


def _profiles():
    r = np.linspace(0.0, 1.2, 13)
    return [ax.cone(0.2), ax.power_law(0.8, 1.5), ax.power_law(0.5, 0.5), ax.tabulated(r, np.sqrt(r ** 2 + 0.09) - 0.3),
            ax.paraboloid(1.5)]


@pytest.mark.parametrize("profile", _profiles(), ids=lambda p: p.kind)
def test_one_d_route_obeys_hooke_normal_and_partial_slip(profile):
    a, nu, mu, ux0 = 0.8, 0.3, 0.4, 0.2
    _, c, muk = (float(v) for v in _stick(np.array(a), np.array(nu), np.array(mu), np.array(ux0), profile))
    assert 0.0 < c < a
    delta = float(profile.depth(a))
    for p in [(0.3, 0.2, 0.5), (1.1, -0.4, 0.2), (0.0, 0.0, 0.7), (-0.5, 0.4, 0.1)]:

        def u(P):
            d = displacements(NAMES, profile, P[0], P[1], P[2], a=a, nu=nu, mu=mu, ux0=ux0, c=c, mu_kernel=muk,
                              method="quadrature", rtol=1e-12)
            return np.array([d[n] for n in NAMES]) * delta
        s = (1.0 - nu) * _hooke(u, p, nu, 1e-3)
        ref = interior_stress(*p, a, nu, profile, method="quadrature", rtol=1e-12)
        tan = interior_stress_tangential(*p, a, c, nu, muk, profile, method="quadrature", rtol=1e-12)
        pm = float(profile.normal_force(a)) / (math.pi * a * a)
        for k, (i, j) in PAIRS.items():
            assert abs(s[i, j] - float(ref[k]) - float(tan[k])) <= 1e-7 * pm, (p, k)


def _f(profile, r):
    """The profile's height, from its own definition (not from the code's g)."""
    kind = profile.kind
    if kind == "cone":
        return profile.tan_theta * r
    if kind == "paraboloid":
        return r * r / (2.0 * profile.R)
    return profile.A * r ** profile.n


@pytest.mark.parametrize("profile", [ax.cone(0.2), ax.paraboloid(1.5), ax.power_law(0.8, 1.5), ax.power_law(0.5, 0.5),
                                     ax.power_law(1.0, 3.0)], ids=lambda p: p.kind)
@pytest.mark.parametrize("method", ["auto", "quadrature"])
def test_surface_conditions_in_the_contact(profile, method):
    a, nu, mu, ux0 = 0.8, 0.3, 0.4, 0.2
    _, c, muk = (float(v) for v in _stick(np.array(a), np.array(nu), np.array(mu), np.array(ux0), profile))
    r = np.array([0.0, 1e-16, 1e-8, 1e-3, 0.2, 0.5, 0.79, 0.8 * (1 - 1e-12)]) * a / 0.8
    delta = float(profile.depth(a))
    uz = displacements(("u_z",), profile, r, 0.0, 0.0, a=a, nu=nu, mu=0.0, ux0=0.0, c=a, mu_kernel=0.0,
                       method=method)["u_z"]
    assert np.all(np.abs(uz - (1.0 - _f(profile, r) / delta)) <= 1e-10)
    # the tangential part in the stick zone: u_x = u_x0, u_y = 0, at any angle
    th = np.linspace(0.0, 2.0 * math.pi, 7)
    rs = np.array([0.0, 1e-8, 0.3 * c, 0.9 * c, c * (1 - 1e-9)])[:, None]
    X, Y = rs * np.cos(th), rs * np.sin(th)
    kw = dict(a=a, nu=nu, mu=mu, ux0=ux0, method=method)
    full = displacements(NAMES, profile, X, Y, 0.0, c=c, mu_kernel=muk, **kw)
    normal = displacements(NAMES, profile, X, Y, 0.0, c=a, mu_kernel=0.0, **kw)
    assert np.all(np.abs(full["u_x"] - normal["u_x"] - ux0) <= 1e-10)
    assert np.all(np.abs(full["u_y"] - normal["u_y"]) <= 1e-10)


def test_flat_punch_surface_and_sticking():
    nu, a = 0.25, 1.3
    prof = ax.flat_punch(a, 0.1)
    r = np.array([0.0, 1e-16, 0.5, 1.29, a])
    d = displacements(NAMES, prof, r, 0.0, 0.0, a=a, nu=nu, mu=0.5, ux0=0.0, c=a, mu_kernel=0.0)
    assert np.all(np.abs(d["u_z"] - 1.0) <= 1e-15)
    r = r[:-1] / math.hypot(1.0, 0.2)                   # (r, 0.2 r) in the contact
    # sticking whole: c = a with ux0 > 0; the kernels take c = 0 and mu_kernel = (G*/E*) ux0
    ux0 = 0.03
    _, c, muk = (float(v) for v in _stick(np.array(a), np.array(nu), np.array(0.5), np.array(ux0), prof))
    kw = dict(a=a, nu=nu, mu=0.5, ux0=ux0)
    t = displacements(NAMES, prof, r, 0.2 * r, 0.0, c=c, mu_kernel=muk, **kw)
    n = displacements(NAMES, prof, r, 0.2 * r, 0.0, c=a, mu_kernel=0.0, **kw)
    assert np.all(np.abs(t["u_x"] - n["u_x"] - ux0) <= 1e-15 + 1e-14 * ux0)
    assert np.all(np.abs(t["u_y"] - n["u_y"]) <= 1e-16)


def test_hertz_surface_against_johnson():
    """The printed surface displacements (Johnson 1985, ch. 3) of the Hertz pressure and of the
    traction q = q0 sqrt(1 - r^2/a^2) along x: at z = 0, r <= a,
    u_r = -(1 - 2 nu)(1 + nu) p0 a^2 [1 - (1 - r^2/a^2)^(3/2)]/(3 E r), u_x = pi q0 [4(2 - nu) a^2
    - (4 - 3 nu) x^2 - (4 - nu) y^2]/(32 G a), u_y = pi q0 nu x y/(16 G a); E* = 1, a = 1."""
    nu = 0.3
    E, G = 1.0 - nu * nu, (1.0 - nu) / 2.0
    x, y = np.array([0.0, 0.3, -0.5, 0.1, 0.7]), np.array([0.0, 0.2, 0.4, -0.9, 0.0])
    r = np.hypot(x, y)
    h = hertz_displacement_unit(x, y, 0.0, nu)
    p0 = 2.0 / math.pi
    with np.errstate(invalid="ignore", divide="ignore"):
        ur = -(1 - 2 * nu) * (1 + nu) * p0 * (1 - (1 - r * r) ** 1.5) / (3 * E * r)
        ref_x = np.where(r > 0, ur * x / np.where(r > 0, r, 1), 0.0)
    assert np.allclose(h["x"], ref_x, rtol=1e-13, atol=1e-16)
    assert np.allclose(h["z"], 1.0 - r * r / 2.0, rtol=1e-14, atol=0)
    s = hertz_sliding_displacement_unit(x, y, 0.0, nu)
    assert np.allclose(s["x"], math.pi * (4 * (2 - nu) - (4 - 3 * nu) * x * x - (4 - nu) * y * y) / (32 * G),
                       rtol=1e-13, atol=0)
    assert np.allclose(s["y"], math.pi * nu * x * y / (16 * G), rtol=1e-13, atol=1e-17)


# -- the defining integrals: point loads over the surface tractions ----------------------------------

def _boussinesq(dx, dy, z, nu):
    """Displacements per unit normal force into the body, E* = 1 (4 pi G = 2 pi (1 - nu))."""
    rho = np.sqrt(dx * dx + dy * dy + z * z)
    k = 1.0 / (2.0 * math.pi * (1.0 - nu))
    radial = z / rho ** 3 - (1.0 - 2.0 * nu) / (rho * (rho + z))
    return k * np.array([dx * radial, dy * radial, 2.0 * (1.0 - nu) / rho + z * z / rho ** 3])


def _cerruti(dx, dy, z, nu):
    """Displacements per unit tangential force along +x (Johnson 1985, eq. 2.19), E* = 1."""
    rho = np.sqrt(dx * dx + dy * dy + z * z)
    k = 1.0 / (2.0 * math.pi * (1.0 - nu))
    rz = rho + z
    ux = 1 / rho + dx * dx / rho ** 3 + (1 - 2 * nu) * (1 / rz - dx * dx / (rho * rz * rz))
    uy = dx * dy / rho ** 3 - (1 - 2 * nu) * dx * dy / (rho * rz * rz)
    uz = dx * z / rho ** 3 + (1 - 2 * nu) * dx / (rho * rz)
    return k * np.array([ux, uy, uz])


def _integrate(kernel, load, b, p, nu, nth=256):
    """int_0^b int_0^2pi kernel(p - s e_theta) load(s) s dtheta ds: s = b sin t, so that the square
    roots at s = b are smooth; adaptive in t, trapezoid (periodic) in theta."""
    th = np.arange(nth) * (2.0 * math.pi / nth)

    def inner(t):
        s = b * math.sin(t)
        v = kernel(p[0] - s * np.cos(th), p[1] - s * np.sin(th), p[2], nu)
        return v.sum(axis=1) * (2.0 * math.pi / nth) * load(s) * s * b * math.cos(t)
    return quad_vec(inner, 0.0, 0.5 * math.pi, epsabs=1e-14, epsrel=1e-12)[0]


def _hertz_p(b, R):
    return lambda s: 2.0 * b / (math.pi * R) * math.sqrt(max(1.0 - (s / b) ** 2, 0.0))


def _cone_p(b, tan_t):
    return lambda s: 0.5 * tan_t * math.acosh(b / s) if 0.0 < s < b else 0.0


@pytest.mark.parametrize("case", ["paraboloid", "cone"])
def test_point_load_integrals(case):
    nu, a, mu, ux0 = 0.3, 1.0, 0.35, 0.15
    if case == "paraboloid":
        prof, press = ax.paraboloid(2.0), lambda b: _hertz_p(b, 2.0)
    else:
        prof, press = ax.cone(0.3), lambda b: _cone_p(b, 0.3)
    _, c, muk = (float(v) for v in _stick(np.array(a), np.array(nu), np.array(mu), np.array(ux0), prof))
    delta = float(prof.depth(a))
    for p in [(0.0, 0.0, 0.4), (0.4, 0.3, 0.3), (1.5, -0.5, 0.6), (0.9, 0.2, 1.0)]:
        normal = _integrate(_boussinesq, press(a), a, p, nu)
        tang = muk * (_integrate(_cerruti, press(a), a, p, nu) - _integrate(_cerruti, press(c), c, p, nu))
        ref = (normal + tang) / delta
        got = displacements(NAMES, prof, *p, a=a, nu=nu, mu=mu, ux0=ux0, c=c, mu_kernel=muk)
        for i, n in enumerate(NAMES):
            assert abs(float(got[n]) - ref[i]) <= 1e-10 * max(abs(ref).max(), 1.0), (p, n)


def test_surface_outside_the_contact():
    """z = 0, r > a: the cone's u_z = (2/pi) int_0^a arcsin(rho/r) g' d rho = tan(theta) [a arcsin(a/r)
    + sqrt(r^2 - a^2) - r] (Mossakovskii), and the radial displacement of every profile
    -(1 - 2 nu) F_N/(2 pi (1 - nu) r) per E* (the load inside r is F_N)."""
    nu, a = 0.3, 0.8
    r = a * np.array([1.0 + 1e-12, 1.0 + 1e-6, 1.01, 1.5, 3.0, 30.0])
    cone = ax.cone(0.2)
    delta = float(cone.depth(a))
    d = displacements(NAMES, cone, r, 0.0, 0.0, a=a, nu=nu, mu=0.0, ux0=0.0, c=a, mu_kernel=0.0)
    ref = 0.2 * (a * np.arcsin(a / r) + np.sqrt((r - a) * (r + a)) - r) / delta
    assert np.all(np.abs(d["u_z"] - ref) <= 1e-10 * np.maximum(np.abs(ref), 1.0))
    for prof in [cone, ax.paraboloid(1.0), ax.power_law(0.7, 0.5), ax.flat_punch(a)]:
        d = displacements(NAMES, prof, r / math.sqrt(2), r / math.sqrt(2), 0.0, a=a, nu=nu, mu=0.0, ux0=0.0, c=a,
                          mu_kernel=0.0)
        ur = -(1 - 2 * nu) * float(prof.normal_force(a)) / (2 * math.pi * (1 - nu) * r) / float(prof.depth(a))
        assert np.all(np.abs(d["u_x"] * math.sqrt(2) - ur) <= 1e-10), prof.kind


def test_radial_displacement_inside_the_contact():
    """u_r(r, 0) = -(1 - 2 nu) P(r)/(2 pi (1 - nu) r) per E*, P(r) the load inside r (Gauss's theorem
    for the logarithmic potential), the cone's pressure integrated by quad."""
    nu, a, tan_t = 0.2, 1.0, 0.3
    cone = ax.cone(tan_t)
    delta = float(cone.depth(a))
    for r in [1e-3, 0.2, 0.6, 0.999]:
        load = quad(lambda s: 2 * math.pi * s * 0.5 * tan_t * math.acosh(a / s), 0.0, r, epsabs=1e-15, limit=200)[0]
        ref = -(1 - 2 * nu) * load / (2 * math.pi * (1 - nu) * r) / delta
        got = displacements(("u_x",), cone, r, 0.0, 0.0, a=a, nu=nu, mu=0.0, ux0=0.0, c=a, mu_kernel=0.0)["u_x"]
        assert abs(float(got) - ref) <= 1e-10, r


@pytest.mark.parametrize("profile", [ax.paraboloid(1.0), ax.cone(0.25), ax.flat_punch(1.0), ax.power_law(1.0, 1.5)],
                         ids=lambda p: p.kind)
def test_far_field_point_loads(profile):
    nu, a, mu, ux0 = 0.3, 1.0, 0.3, 0.1
    _, c, muk = (float(v) for v in _stick(np.array(a), np.array(nu), np.array(mu), np.array(ux0), profile))
    delta = float(profile.depth(a))
    P = float(profile.normal_force(a))
    Q = muk * (P - float(profile.normal_force(c))) if profile.kind != "flat_punch" else muk * P
    for R in [1e3, 1e4]:
        for d in [(0.6, 0.0, 0.8), (0.48, 0.64, 0.6), (-0.3, 0.4, math.sqrt(0.75))]:
            p = R * np.array(d)
            ref = (P * _boussinesq(*p, nu) + Q * _cerruti(*p, nu)) / delta
            got = displacements(NAMES, profile, *p, a=a, nu=nu, mu=mu, ux0=ux0, c=c, mu_kernel=muk)
            for i, n in enumerate(NAMES):
                assert abs(float(got[n]) - ref[i]) <= 5.0 * (a / R) ** 2 * np.abs(ref).max(), (R, d, n)


@pytest.mark.parametrize("profile, method", [(ax.paraboloid(1.0), "auto"), (ax.flat_punch(1.0), "auto"),
                                             (ax.cone(0.2), "auto"), (ax.paraboloid(1.0), "quadrature")],
                         ids=["hertz", "punch", "cone", "hertz-1d"])
def test_axis_without_cancellation(profile, method):
    nu, a, mu, ux0 = 0.3, 1.0, 0.4, 0.2
    _, c, muk = (float(v) for v in _stick(np.array(a), np.array(nu), np.array(mu), np.array(ux0), profile))
    z = np.array([[0.0], [1e-6], [0.5], [3.0]])
    r = np.array([0.0, 1e-16, 1e-8])
    kw = dict(a=a, nu=nu, mu=mu, ux0=ux0, method=method)
    n = displacements(NAMES, profile, r, 0.0, z, c=a, mu_kernel=0.0, **kw)
    t = displacements(NAMES, profile, r, 0.0, z, c=c, mu_kernel=muk, **kw)
    # u_z and the tangential u_x are even in r: equal to the axis value to rounding (a conical tip
    # varies on the scale z: u(r) - u(0) ~ r^2/z and u_r ~ r ln(z/r) are the field's own, so its rows
    # z < 0.5 are left out)
    rows = slice(2, None) if profile.kind == "cone" else slice(None)
    assert np.all(np.abs(n["u_z"][rows, 1:] - n["u_z"][rows, :1]) <= 1e-14)
    tx = (t["u_x"] - n["u_x"])[rows]
    assert np.all(np.abs(tx[:, 1:] - tx[:, :1]) <= 1e-14)
    # the normal radial displacement is linear in r: u_x / x the same at 1e-16 and 1e-8
    slope = n["u_x"][rows, 1:] / r[1:]
    assert np.all(np.abs(slope[:, 0] - slope[:, 1]) <= 1e-12 * np.abs(slope[:, 1]) + 1e-14)
    assert np.all(n["u_x"][:, 0] == 0.0) and np.all(n["u_y"] == 0.0)
    # the axis value of u_z against the Boussinesq ring integral (quad)
    for i, zz in enumerate(z[:, 0]):
        if zz == 0.0 or profile.kind == "flat_punch":
            continue
        if profile.kind == "paraboloid":
            pr = _hertz_p(a, 1.0)
        else:
            pr = _cone_p(a, 0.2)
        k = 1.0 / (2.0 * math.pi * (1.0 - nu))

        def ring(s, zz=zz, pr=pr):
            h = math.hypot(s, zz)
            return 2 * math.pi * s * pr(s) * k * (2 * (1 - nu) / h + zz * zz / h ** 3)
        ref = quad(ring, 0.0, a, points=[zz * f for f in (0.1, 1.0, 10.0) if zz * f < a], epsabs=1e-15,
                   epsrel=1e-13, limit=400)[0] / float(profile.depth(a))
        assert abs(n["u_z"][i, 0] - ref) <= 1e-11, zz


def _grid():
    r = np.concatenate([np.linspace(0.0, 3.0, 13), [1e-12, 1e-3, 0.5 - 1e-9, 1.0 - 1e-12, 1.0 + 1e-12, 1.0 - 1e-6]])
    z = np.array([0.0, 1e-12, 1e-6, 1e-3, 0.1, 0.7, 3.0, 20.0])
    R, Z = np.meshgrid(r, z)
    th = 0.7
    return R.ravel() * math.cos(th), R.ravel() * math.sin(th), Z.ravel()


@pytest.mark.parametrize("rtol", [1e-6, 1e-10])
def test_one_d_route_against_closed_forms(rtol):
    """The paraboloid by the 1-D route against (I41), normal load and partial slip (c/a = 0.5 and
    gross slip), scaled to a = 1.3: |error| <= rtol * max(|value|, delta), with values / delta."""
    a, nu = 1.3, 0.3
    prof = ax.paraboloid(2.0)
    x, y, z = (v * a for v in _grid())
    for c, muk in [(a, 0.0), (0.5 * a, 0.4), (0.0, 0.4)]:
        kw = dict(a=a, nu=nu, mu=muk, ux0=0.0, c=c, mu_kernel=muk, rtol=rtol)
        cl = displacements(NAMES, prof, x, y, z, method="closed", **kw)
        qu = displacements(NAMES, prof, x, y, z, method="quadrature", **kw)
        for n in NAMES:
            err = np.abs(cl[n] - qu[n])
            assert np.all(err <= rtol * np.maximum(np.abs(cl[n]), 1.0)), (c, n, err.max())


def test_arguments_are_checked():
    prof = ax.cone(0.2)
    kw = dict(a=1.0, nu=0.3, mu=0.0, ux0=0.0, c=1.0, mu_kernel=0.0)
    with pytest.raises(ValueError, match="unknown displacement"):
        displacements(("u_r",), prof, 0.0, 0.0, 0.0, **kw)
    with pytest.raises(ValueError, match="z"):
        displacements(NAMES, prof, 0.0, 0.0, -1.0, **kw)
    with pytest.raises(ValueError, match="closed"):
        displacements(NAMES, prof, 0.0, 0.0, 1.0, method="closed", **kw)
    out = displacements(NAMES, prof, np.zeros((2, 1)), np.zeros(3), 0.5, **kw)
    assert all(v.shape == (2, 3) and np.all(np.isfinite(v)) for v in out.values())


@pytest.mark.parametrize("profile", _profiles() + [ax.flat_punch(0.8)], ids=lambda p: p.kind)
def test_surface_rule_meets_the_panels(profile):
    """z = 0 (the surface rule (I44) inside the range of integration) against z = 1e-12 a (the
    panels (I16)-(I17)): the field is Lipschitz in z away from the axis and the edge rings, so the
    two differ by O(1e-12) there; normal load and partial slip, slip zone and outside included."""
    a, nu, mu, ux0 = 0.8, 0.3, 0.4, 0.2
    _, c, muk = (float(v) for v in _stick(np.array(a), np.array(nu), np.array(mu), np.array(ux0), profile))
    r = np.concatenate([np.linspace(0.05, 2.0, 40) * a])
    r = r[(np.abs(r - a) > 0.01 * a) & (np.abs(r - c) > 0.01 * a)]
    kw = dict(a=a, nu=nu, mu=mu, ux0=ux0, c=c, mu_kernel=muk)
    top = displacements(NAMES, profile, 0.6 * r, 0.8 * r, 0.0, **kw)
    below = displacements(NAMES, profile, 0.6 * r, 0.8 * r, 1e-12 * a, **kw)
    for n in NAMES:
        assert np.all(np.abs(top[n] - below[n]) <= 1e-9), n
