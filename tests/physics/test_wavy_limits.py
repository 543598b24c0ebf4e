"""Wavy contact kernels against classical limits and second routes (never against themselves).

Westergaard (periodic, one harmonic) and the Hertz line contact (non-periodic, a -> 0) are
derived here from first principles; closed forms are held against quadrature of the series.
"""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import eval_legendre, j0, j1, jv

from stressfields.physics import wavy

F1 = dict(amplitudes=[1.0], wavenumbers=[1])
F3 = dict(amplitudes=[0.5, 0.01, 0.00075], wavenumbers=[1, 11, 40])


def westergaard(t, a):
    """Periodic single wave g = Delta(1 - cos x), lambda = 2 pi (Johnson 1985, s. 13.2).

    In complete contact the pressure is the flattening pressure E* Delta cos x / 2 + const; the
    bounded partial-contact solution of the cot-kernel equation is
        p = E* Delta cos(x/2) sqrt(sin^2(a/2) - sin^2(x/2)),
    and with p* = pi E* Delta/lambda = E* Delta/2:  p/p* = 2 cos(x/2) sqrt(sin^2(a/2) - sin^2(x/2)).
    Check: p(0)/p* = 2 sin(a/2); mean (1/2pi) int p dx / p* = sin^2(a/2) (load W = pi E* Delta sin^2).
    """
    x = t * a
    return 2.0 * np.cos(x / 2) * np.sqrt(np.clip(np.sin(a / 2) ** 2 - np.sin(x / 2) ** 2, 0, None))


@pytest.mark.parametrize("w", [0.01, 0.2, 0.5, 0.8, 0.9, 0.95, 0.99])
def test_westergaard(w):
    a = np.pi * w
    t = np.linspace(-1.0, 1.0, 1001)
    p, info = wavy.pressure(t, w, **F1, periodic=True)
    err = np.max(np.abs(p - westergaard(t, a)))
    assert err <= max(1e-12, info["error_estimate"].max())
    assert err < 1e-12
    assert abs(wavy.mean_pressure(w, **F1, periodic=True) - np.sin(a / 2) ** 2) < 1e-15
    p0, _ = wavy.peak_pressure(w, **F1, periodic=True)
    assert abs(p0 - 2 * np.sin(a / 2)) < 1e-12
    # approach with the mean-zero datum: Delta sin^2(a/2) (1 - 2 ln sin(a/2)), docs/theory/wavy.md (W27)
    s = np.sin(a / 2)
    assert abs(wavy.approach(w, **F1, periodic=True) - s * s * (1 - 2 * np.log(s))) < 1e-14


@pytest.mark.parametrize("w", [0.05, 0.5, 0.9, 0.99])
def test_westergaard_gap_outside(w):
    """gap = 2 Delta [sin(x/2) R - sin^2(a/2) ln((sin(x/2) + R)/sin(a/2))], R = sqrt(sin^2(x/2) - sin^2(a/2))."""
    a = np.pi * w
    x = np.linspace(a, np.pi, 400)[1:]
    s, sa = np.sin(x / 2), np.sin(a / 2)
    R = np.sqrt(s * s - sa * sa)
    exact = 2 * (s * R - sa * sa * np.log((s + R) / sa))
    g, _ = wavy.separation(x / a, w, **F1, periodic=True)
    np.testing.assert_allclose(g, exact, rtol=0, atol=1e-13)
    # periodic in x: one period further gives the same
    g2, _ = wavy.separation((x + 2 * np.pi) / a, w, **F1, periodic=True)
    np.testing.assert_allclose(g2, g, atol=1e-13)


@pytest.mark.parametrize("w", [0.3, 0.8])
def test_periodic_displacement_has_zero_mean(w):
    """Datum of the ln|2 sin| kernel: int over one period of u_z = 0 (the kernel has zero mean)."""
    a = np.pi * w
    # Gauss-Legendre on [0, a] and [a, pi] in sqrt-graded variables (u_z has (x-a)^(3/2) kinks)
    z, wt = np.polynomial.legendre.leggauss(80)
    s = 0.5 * (z + 1)
    xin = a * (1 - s * s)                  # dense near x = a
    xout = a + (np.pi - a) * s * s
    uin, _ = wavy.displacement(xin / a, w, **F3, periodic=True)
    uout, _ = wavy.displacement(xout / a, w, **F3, periodic=True)
    mean = (np.sum(0.5 * wt * uin * 2 * a * s) + np.sum(0.5 * wt * uout * 2 * (np.pi - a) * s)) / np.pi
    assert abs(mean) < 1e-12


@pytest.mark.parametrize("periodic", [True, False])
@pytest.mark.parametrize("w", [0.1, 0.5, 0.85])
def test_mean_pressure_closed_form_vs_quadrature(w, periodic):
    """p_inf = (1/2pi) int p dx; Gauss-Chebyshev-type rule in theta (spectral, smooth periodic)."""
    a = np.pi * w
    m = 4096
    th = (np.arange(m) + 0.5) * np.pi / m
    if periodic:
        al = np.tan(a / 2)
        x = 2 * np.arctan(al * np.cos(th))
        dx = 2 * al * np.sin(th) / (1 + (al * np.cos(th)) ** 2)
    else:
        x, dx = a * np.cos(th), a * np.sin(th)
    p, _ = wavy.pressure(x / a, w, **F3, periodic=periodic)
    quad_mean = np.sum(p * dx) * (np.pi / m) / (2 * np.pi)
    assert abs(wavy.mean_pressure(w, **F3, periodic=periodic) - quad_mean) < 1e-13


@pytest.mark.parametrize("w", [0.3, 0.8, 0.95])
def test_periodic_peak_vs_legendre_integral(w):
    """p_i(0) = (Delta_i n_i^2/4) int_0^a [P_{n-1} + P_n](cos t)/cos(t/2) dt, docs/theory/wavy.md (W13),
    times 2/Delta_1."""
    a = np.pi * w
    amp, wn = F3["amplitudes"], F3["wavenumbers"]
    ref = 0.0
    for d, n in zip(amp, wn):
        f = lambda t: (eval_legendre(n - 1, np.cos(t)) + eval_legendre(n, np.cos(t))) / np.cos(t / 2)
        ref += 2 * d / amp[0] * n * n / 4 * quad(f, 0, a, limit=400, epsabs=1e-13, epsrel=1e-13)[0]
    p0, info = wavy.peak_pressure(w, **F3, periodic=True)
    assert abs(p0 - ref) < 1e-11


@pytest.mark.parametrize("w", [0.05, 0.5, 0.9])
def test_nonperiodic_peak_eq21(w):
    """Eq. (21): p_i(0) = 0.5 Delta_i n_i int_0^{a n_i} J_0(t) dt."""
    a = np.pi * w
    amp, wn = F3["amplitudes"], F3["wavenumbers"]
    ref = sum(2 * d / amp[0] * 0.5 * n * quad(j0, 0, a * n, limit=400, epsabs=1e-14)[0] for d, n in zip(amp, wn))
    p0, _ = wavy.peak_pressure(w, **F3, periodic=False)
    assert abs(p0 - ref) < 1e-12


def _uz_eq15(t, a, amp, wn, n_terms=200):
    """Paper's eq. (15) with the log term ln(2/a), docs/theory/wavy.md (W17), summed directly:
    u_z(x)/Delta_1 inside the contact."""
    T = lambda k: np.cos(k * np.arccos(t))
    out = 0.0
    for d, n in zip(amp, wn):
        z = a * n
        acc = j1(z) * (t * t - 0.5 - np.log(2.0 / a))
        for j in range(3, 2 * n_terms, 2):
            acc = acc + (-1.0) ** ((j - 1) // 2) * jv(j, z) * (T(j + 1) / (j + 1) - T(j - 1) / (j - 1))
        out = out - d / amp[0] * n * a * acc
    return out


@pytest.mark.parametrize("w", [0.05, 0.3, 0.7])
def test_nonperiodic_displacement_vs_eq15(w):
    a = np.pi * w
    t = np.array([0.0, 0.4, 0.8, 1.0])
    u, _ = wavy.displacement(t, w, **F3, periodic=False)
    np.testing.assert_allclose(u, _uz_eq15(t, a, F3["amplitudes"], F3["wavenumbers"]), atol=1e-13)


def test_hertz_limit_pressure_order():
    """Cylinder of radius R = 1/(Delta n^2): p = (E* a/(2R)) sqrt(1 - x^2/a^2) = p* a n^2 sqrt(1-t^2)
    (n = 1, Delta = Delta_1).  The cosine differs from the parabola at O(a^2): error ratio 4 per halving."""
    t = np.linspace(-1, 1, 201)
    errs = []
    ws = np.array([0.04, 0.02, 0.01, 0.005])
    for w in ws:
        a = np.pi * w
        p, _ = wavy.pressure(t, w, **F1, periodic=False)
        errs.append(np.max(np.abs(p - a * np.sqrt(1 - t * t))) / a)
    order = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    np.testing.assert_allclose(order, 2.0, atol=0.02)
    # relative size close to 0.115 a^2, the cosine-versus-parabola difference, docs/theory/wavy.md (W28)
    assert 0.08 < errs[-1] / (np.pi * ws[-1]) ** 2 < 0.13


def test_hertz_limit_gap_outside():
    """Line-contact separation outside: (a^2/(2R)) [t sqrt(t^2-1) - arccosh t], 1/R = Delta n^2."""
    w = 0.002
    a = np.pi * w
    t = np.array([1.001, 1.1, 1.5, 3.0, 10.0])
    g, _ = wavy.separation(t, w, **F1, periodic=False)
    hertz = 0.5 * a * a * (t * np.sqrt(t * t - 1) - np.arccosh(t))
    np.testing.assert_allclose(g, hertz, rtol=(a * t.max()) ** 2)


def test_periodic_tends_to_nonperiodic():
    """p_inf^per/p_inf^non - 1 = +0.1, 0.4, 1.7, 3.9, 12.3, 46 % at 2a/lambda_1 = 0.05 ... 0.8 (values of the
    independent reference solutions), the same for f1, f2, f3 (to 0.6 points); the difference vanishes
    like a^2, docs/theory/wavy.md (W26)."""
    ws = np.array([0.05, 0.1, 0.2, 0.3, 0.5, 0.8])
    expected = np.array([0.1, 0.4, 1.7, 3.9, 12.3, 46])
    for prof, tol in [(F1, 0.06), (F3, 0.6)]:
        r = 100 * (wavy.mean_pressure(ws, **prof, periodic=True) / wavy.mean_pressure(ws, **prof, periodic=False) - 1)
        np.testing.assert_allclose(r, expected, atol=max(tol, 0.0), rtol=0.02)
    # sup-norm difference of the pressure fields, rough profile, shrinking a
    t = np.linspace(0, 1, 401)
    ws = np.array([0.02, 0.01, 0.005])
    d = []
    for w in ws:
        pp, _ = wavy.pressure(t, w, **F1, periodic=True)
        pn, _ = wavy.pressure(t, w, **F1, periodic=False)
        d.append(np.max(np.abs(pp - pn)) / np.max(pn))
    np.testing.assert_allclose(np.log2(np.array(d[:-1]) / np.array(d[1:])), 2.0, atol=0.02)


def test_edge_coefficients():
    """Edge coefficient K = phi(|x| = a), docs/theory/wavy.md (W19): non-periodic
    E* sum Delta n (a n/2) J0(a n); periodic K = sqrt(a/(2 tan(a/2))) (1/pi) dW/da, W = lambda_1 p_inf:
    by finite differences."""
    amp, wn = np.array(F3["amplitudes"]), np.array(F3["wavenumbers"])
    for w in [0.1, 0.45, 0.8]:
        a = np.pi * w
        exact = np.sum(2 * amp / amp[0] * wn * (a * wn / 2) * j0(a * wn))
        for rtol in (1e-12, 1e-15):
            phi, info = wavy.pressure_shape(1.0, w, **F3, periodic=False, rtol=rtol)
            assert abs(phi - exact) <= info["error_estimate"]   # the estimate is honest ...
        assert abs(phi - exact) < 1e-13                           # ... and small when asked
        v = wavy.contact_validity(w, **F3, periodic=False)
        assert abs(v["edge_phi_over_pstar"] - exact) < 1e-11
        h = 1e-5
        dpinf = (wavy.mean_pressure(w + h, **F3, periodic=True)
                 - wavy.mean_pressure(w - h, **F3, periodic=True)) / (2 * h * np.pi)
        K_fd = np.sqrt(a / (2 * np.tan(a / 2))) * 2.0 * dpinf   # (1/pi) dW/da / p* = 2 d(p_inf/p*)/da
        phi, _ = wavy.pressure_shape(-1.0, w, **F3, periodic=True, rtol=1e-14)
        assert abs(phi - K_fd) < 1e-7 * max(1.0, abs(K_fd))


def test_paper_approximations_are_inaccurate():
    """Eq. (18) is exact only at x = 0; eq. (20) is off even at x = 0, docs/theory/wavy.md (W29)."""
    w, t = 0.5, np.linspace(0, 1, 101)
    p, _ = wavy.pressure(t, w, **F3, periodic=False)
    p18 = wavy.approximate_pressure_eq18(t, w, **F3)
    p20 = wavy.approximate_pressure_eq20(t, w, **F3)
    assert abs(p18[0] - p[0]) < 1e-12
    assert np.max(np.abs(p18 - p)) > 1e-3
    assert abs(p20[0] - p[0]) > 1e-3


def test_eq20_is_the_jacobi_anger_sum_of_eq19():
    """Eq. (20) as evaluated, docs/theory/wavy.md (W29), equals the series (19) summed term by term:
    J_1(a n) + sum_{j>=1} J_{2j}(a n + 1) cos(2 j x/a) = J_1(a n) + [cos((a n + 1) sin(x/a)) - J_0(a n + 1)]/2
    by Jacobi-Anger.  With the factor 1/2 on the cosine only (J_0 subtracted whole) the difference
    would be J_0(a n + 1)/2 * 2 Delta n sqrt(1 - t^2), far above the tolerance."""
    t = np.linspace(-1.0, 1.0, 41)
    amp, wn = F3["amplitudes"], F3["wavenumbers"]
    for w in (0.05, 0.3, 0.7):
        a = np.pi * w
        ref = 0.0
        for d, n in zip(amp, wn):
            z = a * n
            acc = j1(z) + sum(jv(2 * j, z + 1.0) * np.cos(2 * j * t) for j in range(1, 200))
            ref = ref + 2 * d / amp[0] * n * np.sqrt(1 - t * t) * acc
        np.testing.assert_allclose(wavy.approximate_pressure_eq20(t, w, **F3), ref, rtol=0, atol=1e-13)


def _uz_quadrature(x, w, amplitudes, wavenumbers, periodic):
    """u_z(x)/Delta_1 for |x| < a straight from the displacement integral, docs/theory/wavy.md (W15),
    C = 0: -(1/pi) int p/p* ln|x - xi| dxi (p* = E* Delta_1/2 turns -2/(pi E*) into -Delta_1/pi),
    plus ln(2 sin(y/2)/y) for the periodic kernel.  The log singularity at xi = x and the square-root
    ends are taken by QUADPACK's algebraic-log weights (p = phi sqrt(1 - (xi/a)^2), phi smooth)."""
    a = np.pi * w
    phi = lambda xi: wavy.pressure_shape(xi / a, w, amplitudes, wavenumbers, periodic=periodic, rtol=1e-14)[0]
    kw = dict(epsabs=1e-13, epsrel=1e-12, limit=400)
    right = quad(lambda xi: phi(xi) * np.sqrt(a + xi) / a, x, a, weight="alg-loga", wvar=(0.0, 0.5), **kw)[0]
    left = quad(lambda xi: phi(xi) * np.sqrt(a - xi) / a, -a, x, weight="alg-logb", wvar=(0.5, 0.0), **kw)[0]
    total = left + right
    if periodic:                     # smooth remainder of ln|2 sin(y/2)|: midpoint rule in xi = a cos s
        m = 2000
        s = (np.arange(m) + 0.5) * np.pi / m
        xi = a * np.cos(s)
        p, _ = wavy.pressure(np.cos(s), w, amplitudes, wavenumbers, periodic=True, rtol=1e-14)
        total += np.sum(p * np.log(np.sinc((x - xi) / (2 * np.pi))) * a * np.sin(s)) * np.pi / m
    return -total / np.pi


@pytest.mark.parametrize("periodic", [pytest.param(True, marks=pytest.mark.slow), False])
def test_pressure_solves_the_contact_integral_equation(periodic):
    """The pressure, combined with E* (docs/theory/wavy.md (W5)), reproduces the imposed surface
    displacement in the contact: u_z(x) - u_z(0) = -g(x) with u_z from quadrature of eq. (5), for the
    rough profile f3.  With the printed combining factor E/(2(1-nu^2)) the pressure, and so
    u_z(x) - u_z(0), would be half as large.  The absolute u_z(0) checks the datum of (W15) (and thus
    the ln(2/a) of eq. (15) and the periodic ln|2 sin| kernel)."""
    w = 0.3
    a = np.pi * w
    t = np.array([0.0, 0.3, 0.7, 0.95])
    u = np.array([_uz_quadrature(ti * a, w, **F3, periodic=periodic) for ti in t])
    g = wavy.initial_gap(t, w, **F3)
    assert g[-1] > 0.1
    np.testing.assert_allclose(u - u[0], -g, rtol=0, atol=1e-12)
    assert abs(u[0] - wavy.approach(w, **F3, periodic=periodic)) < 1e-12
    np.testing.assert_allclose(wavy.displacement(t, w, **F3, periodic=periodic)[0], u, rtol=0, atol=1e-12)
