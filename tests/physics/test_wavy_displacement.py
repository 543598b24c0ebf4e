"""Displacements below the single wavy indenter (docs/theory/wavy.md (W45)), proven by independent routes:
mpmath quadrature of the Flamant line-load displacement kernels over the pressure, the surface displacement
(W15) and Johnson's surface u_x at z = 0, plane-strain Hooke's law against the product's own stresses by
central differences (residual falling as h^2), and the Hertz line contact's primitive written directly."""
from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from stressfields.physics.wavy import contact

F1 = ([0.5], [1])
F2 = ([0.5, 0.01], [1, 11])
F11 = ([0.5] + [0.004] * 10, list(range(1, 12)))
NU = 0.3


def disp(x, z, w, profile=F2, nu=NU):
    ux, uz, info = contact.subsurface_displacement(np.asarray(x, float), np.asarray(z, float), w, *profile,
                                                   periodic=False, nu=nu)
    return ux, uz, info["error_estimate"]


def coefficients(w, profile):
    """The pressure p/p* = sum_m D_m sin((2m + 1) theta), x = a cos theta: the input of the quadrature
    (the surface series, proven by the surface tests), and the contact angle a (lambda_1 = 2 pi)."""
    c = contact._interior_ctx(w, *profile, False, None, contact.DEFAULT_RTOL, contact.DEFAULT_MAX_TERMS)
    K = int(c.table.K[c.row])
    return [mp.mpf(float(d)) for d in c.table.D[c.row, :K]], float(c.a_in)


def flamant(x, z, D, a, nu):
    """u_x/Delta_1, u_z/Delta_1 by quadrature of the Flamant line-load displacements (plane strain, kernel
    units, log datum ln rho): per unit load 2 mu u_x = ((1 - 2 nu)(phi - pi/2) + (x - s) z/rho^2)/pi,
    2 mu u_z = (-2 (1 - nu) ln rho + z^2/rho^2)/pi, phi = atan2(z, x - s), with 2 mu = E* (1 - nu) and
    p* = E* Delta_1/2."""
    x, z, nu = mp.mpf(x), mp.mpf(z), mp.mpf(nu)

    def p(th):
        return sum(d * mp.sin((2 * m + 1) * th) for m, d in enumerate(D))

    def kx(th):
        s = a * mp.cos(th)
        rho2 = (x - s) ** 2 + z ** 2
        return p(th) * a * mp.sin(th) * ((1 - 2 * nu) * (mp.atan2(z, x - s) - mp.pi / 2) + (x - s) * z / rho2)

    def kz(th):
        s = a * mp.cos(th)
        rho2 = (x - s) ** 2 + z ** 2
        return p(th) * a * mp.sin(th) * (-(1 - nu) * mp.log(rho2) + z ** 2 / rho2)

    cuts = [0, mp.pi]
    if abs(x) < a:
        cuts = [0, mp.acos(x / a), mp.pi]
    ux = mp.quad(kx, cuts) / (2 * mp.pi * (1 - nu))
    uz = mp.quad(kz, cuts) / (2 * mp.pi * (1 - nu))
    return float(ux), float(uz)


@pytest.mark.parametrize("w, profile", [(1e-3, F1), (0.3, F2), pytest.param(0.9, F2, marks=pytest.mark.slow),
                                        (0.5, F11)])
def test_against_flamant_quadrature(w, profile):
    """About 50 points over the four cases, depths 1e-9 a to 5 lambda_1, inside and outside the contact."""
    mp.mp.dps = 20
    D, a = coefficients(w, profile)
    rng = np.random.default_rng(7)
    t = np.concatenate([[0.0, 0.5, -0.97, 1.3, -2.0], rng.uniform(-3.0, 3.0, 6)])
    zt = np.concatenate([[1e-9, 0.2, 1.0, 0.05, 3.0], 10.0 ** rng.uniform(-6.0, math.log10(10 * math.pi / a), 6)])
    ux, uz, err = disp(t, zt, w, profile)
    for i in range(t.size):
        rx, rz = flamant(a * t[i], a * zt[i], D, a, NU)
        tol = err[i] + 2e-14 * (1.0 + abs(rz))
        assert abs(ux[i] - rx) <= tol, (t[i], zt[i], ux[i], rx)
        assert abs(uz[i] - rz) <= tol, (t[i], zt[i], uz[i], rz)
    assert np.all(err <= 1e-12)


@pytest.mark.parametrize("w, profile", [(1e-3, F1), (0.3, F2), (0.9, F2), (0.5, F11)])
def test_surface_uz_and_johnson_ux(w, profile):
    """z = 0: u_z is the surface displacement (W15) to its accuracy (inside and outside the contact), and u_x
    is Johnson's (1 - 2 nu)/(4 mu) [int_x^a p - int_-a^x p], here by mpmath quadrature of the pressure."""
    mp.mp.dps = 15
    t = np.array([-2.5, -1.0, -0.6, 0.0, 0.3, 0.999, 1.7])
    ux, uz, err = disp(t, 0.0, w, profile)
    ref = contact.displacement(t, w, *profile, periodic=False)[0]
    np.testing.assert_allclose(uz, ref, rtol=0, atol=1e-13)
    D, a = coefficients(w, profile)

    def p(th):
        return sum(d * mp.sin((2 * m + 1) * th) for m, d in enumerate(D)) * a * mp.sin(th)

    for ti, u in zip(t, ux):
        th = mp.acos(min(max(ti, -1.0), 1.0))          # x = a cos theta: int_x^a p = int_0^theta
        right, left = mp.quad(p, [0, th]), mp.quad(p, [th, mp.pi])
        johnson = float((1 - 2 * mp.mpf(NU)) / (4 * (1 - mp.mpf(NU))) * (right - left))
        assert abs(u - johnson) <= 1e-13, (ti, u, johnson)


def test_incompressible_surface_has_no_lateral_displacement():
    ux, _, _ = disp(np.linspace(-2, 2, 9), 0.0, 0.3, nu=0.5)
    np.testing.assert_array_equal(ux, 0.0)


@pytest.mark.parametrize("x, z", [(0.4, 0.3), (1.2, 0.7), (-0.9, 2.0)])
def test_hooke_against_the_stresses_falls_as_h_squared(x, z):
    """Plane-strain Hooke's law: 2 (1 - nu)/a du_x/dt = sxx - nu (sxx + szz), 2 (1 - nu)/a du_z/dzt =
    szz - nu (sxx + szz), (1 - nu)/a (du_x/dzt + du_z/dt) = sxz (p* units, t = x/a), with the product's stresses
    of ``subsurface``; central differences, so the residual falls as h^2 (by 16 at h/4) to rounding."""
    w, prof = 0.3, F2
    s, _ = contact.subsurface(("sigma_xx", "sigma_zz", "sigma_xz"), x, z, w, *prof, periodic=False)
    hooke_falls_as_h_squared(x, z, w, prof, s)


def hooke_falls_as_h_squared(x, z, w, prof, s, mu=0.0, fx=0.0):
    """The residual of plane-strain Hooke's law (normalised: see the test above) between central differences
    of u at steps h = 4e-2 and 1e-2 and the stresses s; it must be visible and fall by about 16."""
    a = float(contact._interior_ctx(w, *prof, False, None, contact.DEFAULT_RTOL, contact.DEFAULT_MAX_TERMS).a_in)
    sxx, szz, sxz = (float(s[k]) for k in ("sigma_xx", "sigma_zz", "sigma_xz"))
    tr = sxx + szz

    def residual(h):
        X = np.array([x + h, x - h, x, x])
        Z = np.array([z, z, z + h, z - h])
        ux, uz, _ = contact.subsurface_displacement(X, Z, w, *prof, periodic=False, nu=NU, mu=mu, fx=fx)
        exx = (ux[0] - ux[1]) / (2 * h) / a
        ezz = (uz[2] - uz[3]) / (2 * h) / a
        gxz = ((ux[2] - ux[3]) + (uz[0] - uz[1])) / (2 * h) / a
        return np.array([2 * (1 - NU) * exx - (sxx - NU * tr), 2 * (1 - NU) * ezz - (szz - NU * tr),
                         (1 - NU) * gxz - sxz])

    r1, r2 = np.max(np.abs(residual(4e-2))), np.max(np.abs(residual(1e-2)))
    assert r1 > 1e-9                                   # the difference error is visible at the larger step
    assert 12.0 < r1 / r2 < 20.0, (r1, r2)


def test_hertz_limit():
    """2a/lambda_1 = 1e-6, one harmonic: the Hertz pressure p0 sqrt(1 - t^2), whose primitive written directly,
    Psi = a p0 [Z^2/2 - Z r/2 + log(Z + r)/2 - 1/4 - log(2)/2 + log(a)/2] - i pi a p0/4, r = sqrt(Z^2 - 1),
    gives the displacements to O(a^2) relatively."""
    w = 1e-6
    a = math.pi * w
    p0 = math.sin(a / 2) * 2                    # Westergaard's p(0)/p* -> the Hertz peak (W27)
    t = np.array([0.0, 0.5, -0.8, 1.5, -3.0, 0.2])
    zt = np.array([0.3, 0.78, 1e-3, 2.0, 0.5, 10.0])
    ux, uz, err = disp(t, zt, w, F1)
    Z = t + 1j * zt
    r = np.sqrt(Z - 1) * np.sqrt(Z + 1)
    Psi = a * p0 * (Z ** 2 / 2 - Z * r / 2 + np.log(Z + r) / 2 - 0.25 - math.log(2) / 2 + math.log(a) / 2) \
        - 0.25j * math.pi * a * p0
    G = p0 * (Z - r)
    k = 0.5 / (1 - NU)
    zk = a * zt
    rx = k * ((1 - 2 * NU) * Psi.imag + zk * G.real)
    rz = -Psi.real - k * zk * G.imag
    scale = a * p0 * (1 + abs(math.log(a)))
    np.testing.assert_allclose(ux, rx, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(uz, rz, rtol=0, atol=1e-9 * scale)


def flamant_tangential(x, z, a, c, Da, Dc, mu, nu):
    """u_x/Delta_1, u_z/Delta_1 by quadrature of the tangential line-load displacements (plane strain, kernel
    units, log datum ln rho) over the traction q = mu [p(s; a) - p(s; c)]: per unit load along +x
    2 mu u_x = (-2 (1 - nu) ln rho - z^2/rho^2)/pi, 2 mu u_z = (-(1 - 2 nu)(phi - pi/2) + (x - s) z/rho^2)/pi."""
    x, z, nu, mu = mp.mpf(x), mp.mpf(z), mp.mpf(nu), mp.mpf(mu)

    def p(s, w, D):
        if abs(s) >= w:
            return mp.mpf(0)
        th = mp.acos(s / w)
        return sum(d * mp.sin((2 * m + 1) * th) for m, d in enumerate(D))

    def q(s):
        return mu * (p(s, a, Da) - p(s, c, Dc))

    def kx(s):
        rho2 = (x - s) ** 2 + z ** 2
        return q(s) * (-(1 - nu) * mp.log(rho2) - z ** 2 / rho2)

    def kz(s):
        rho2 = (x - s) ** 2 + z ** 2
        return q(s) * (-(1 - 2 * nu) * (mp.atan2(z, x - s) - mp.pi / 2) + (x - s) * z / rho2)

    cuts = sorted({-a, -c, c, a} | ({x} if abs(x) < a else set()))
    return (float(mp.quad(kx, cuts) / (2 * mp.pi * (1 - nu))), float(mp.quad(kz, cuts) / (2 * mp.pi * (1 - nu))))


def test_partial_slip_against_flamant_quadrature():
    """Normal plus tangential load (fx = 0.6, mu = 0.3): the product less its normal-load part against the
    quadrature of the tangential kernels over mu [p(s; a) - p(s; c)], c from the stick-width relation."""
    mp.mp.dps = 15
    w, prof, mu, fx = 0.3, F2, 0.3, 0.6
    ratio = float(contact.stick_half_width(w, *prof, fx, periodic=False)[0])
    Da, a = coefficients(w, prof)
    Dc, c = coefficients(w * ratio, prof)
    t = np.array([0.0, 0.7, -0.95, 1.4, -0.3])
    zt = np.array([1e-9, 0.3, 0.05, 1.0, 2.5])
    ux, uz, info = contact.subsurface_displacement(t, zt, w, *prof, periodic=False, nu=NU, mu=mu, fx=fx)
    nx, nz, _ = disp(t, zt, w, prof)
    for i in range(t.size):
        rx, rz = flamant_tangential(a * t[i], a * zt[i], a, c, Da, Dc, mu, NU)
        tol = info["error_estimate"][i] + 2e-14
        assert abs(ux[i] - nx[i] - rx) <= tol, (t[i], zt[i], ux[i] - nx[i], rx)
        assert abs(uz[i] - nz[i] - rz) <= tol, (t[i], zt[i], uz[i] - nz[i], rz)


@pytest.mark.parametrize("x, z", [(0.4, 0.3), (-0.9, 1.1)])
def test_partial_slip_hooke(x, z):
    """Hooke's law against the product's stresses under the combined load, residual falling as h^2."""
    w, prof, mu, fx = 0.3, F2, 0.4, 0.5
    s, _ = contact.subsurface(("sigma_xx", "sigma_zz", "sigma_xz"), x, z, w, *prof, periodic=False, mu=mu, fx=fx)
    hooke_falls_as_h_squared(x, z, w, prof, s, mu, fx)
