"""The plane-strain field below the wavy contact (docs/theory/wavy.md (W36)-(W44)) against independent
routes: mpmath quadrature of the defining integrals (stored, tests/data/wavy_interior.json, and a few
live), the Flamant line load, McEwen's Hertz line contact, Westergaard's full-contact harmonics, the
surface values, and the field equations themselves (equilibrium, compatibility) by finite differences."""
from __future__ import annotations

import json
import math
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest

from stressfields.physics.wavy import contact, interior

DATA = Path(__file__).resolve().parents[1] / "data" / "wavy_interior.json"
STRESS = ("sigma_xx", "sigma_zz", "sigma_xz")
F2 = ([1.0, 0.02], [1, 11])


def field(x, z, w, profile=F2, periodic=True, names=STRESS, **kw):
    v, info = contact.subsurface(names, x, z, w, *profile, periodic=periodic, **kw)
    return v, info


# ------------------------------------------------------------------ stored mpmath reference

def _cases():
    return json.loads(DATA.read_text())["cases"]


def test_reference_covers_the_brief():
    cases = _cases()
    points = np.concatenate([np.array(c["points"]) for c in cases])
    assert len(points) >= 500
    assert {len(c["wavenumbers"]) for c in cases} == {1, 2, 11}
    assert {c["domain"] for c in cases} == {"periodic", "nonperiodic"}
    widths = sorted({c["two_a_over_lambda1"] for c in cases})
    assert widths[0] <= 1e-3 and widths[-1] >= 0.999
    depth_kernel = [np.array(c["points"])[:, 1] * math.pi * c["two_a_over_lambda1"] for c in cases]
    # depths from 1e-9 (lambda_1 = 2 pi units) to 5 lambda_1
    assert min(d.min() for d in depth_kernel) <= 1e-8 and max(d.max() for d in depth_kernel) >= 10 * math.pi * 0.999


@pytest.mark.parametrize("case", _cases(), ids=lambda c: f"{c['profile']}-{c['two_a_over_lambda1']}-{c['domain']}")
def test_against_mpmath_quadrature(case):
    P = np.array(case["points"])
    v, info = field(P[:, 0], P[:, 1], case["two_a_over_lambda1"], (case["amplitudes"], case["wavenumbers"]),
                    periodic=case["domain"] == "periodic", rtol=1e-12)
    got = np.stack([v[k] for k in STRESS], axis=1)
    err = np.abs(got - P[:, 2:5]).max(axis=1)
    assert info["converged"].all()
    assert (info["error_estimate"] <= 1e-12).all()
    # within the stated bound (the reference itself is good to ~1e-18)
    assert (err <= info["error_estimate"]).all(), err.max()
    assert err.max() <= 1e-12


def test_live_mpmath_cot_kernel():
    """A few points of the periodic potential by mpmath quadrature of G = (1/2pi) int p cot((zeta - s)/2) ds,
    with the pressure (W30) evaluated in mpmath (a check that does not depend on the stored file)."""
    mp.mp.dps = 18
    w = 0.45
    a = mp.pi * w
    amps, wns = F2
    B = [sum(2 * mp.mpf(d) * n * mp.legendre(n - 1 - j, mp.cos(a)) for d, n in zip(amps, wns) if n > j)
         for j in range(11)]

    def p(s):
        return mp.sqrt(mp.sin((a - s) / 2) * mp.sin((a + s) / 2)) * mp.fsum(B[j] * mp.cos((j + 0.5) * s)
                                                                             for j in range(11))
    for x, z in ((0.3, 0.01), (-2.5, 0.7), (4.0, 3.0)):
        zeta = mp.mpc(x, z)
        br = [-mp.pi / 2, mp.asin(x / a), mp.pi / 2] if abs(x) < a else [-mp.pi / 2, mp.pi / 2]
        G = mp.quad(lambda f: p(a * mp.sin(f)) * mp.cot((zeta - a * mp.sin(f)) / 2) * a * mp.cos(f), br) / (2 * mp.pi)
        Gp = -mp.quad(lambda f: p(a * mp.sin(f)) / mp.sin((zeta - a * mp.sin(f)) / 2) ** 2 * a * mp.cos(f),
                      br) / (4 * mp.pi)
        ref = (G.imag + z * Gp.real, G.imag - z * Gp.real, -z * Gp.imag)
        v, _ = field(x / float(a), z / float(a), w)
        for k, r in zip(STRESS, ref):
            assert abs(float(v[k]) - float(r)) <= 1e-12


# ----------------------------------------------------------------------------- limits

def test_flamant_kernels_of_the_potential_route():
    """A line load P at the origin: G = P/(pi zeta) gives Flamant's field (W36); a tangential line load
    Q: H = Q/(pi zeta) gives the tangential Flamant field (W41) (Johnson, Contact Mechanics, eq. 2.19)."""
    rng = np.random.default_rng(3)
    x, z = rng.uniform(-3, 3, 50), rng.uniform(0.01, 3, 50)
    zeta = x + 1j * z
    G, Gt = 1.0 / (math.pi * zeta), -1.0 / (math.pi * zeta ** 2)
    r4 = (x * x + z * z) ** 2
    sxx, szz, sxz = interior.normal_stresses(G, Gt, z)
    np.testing.assert_allclose(sxx, -2 / math.pi * x * x * z / r4, rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(szz, -2 / math.pi * z ** 3 / r4, rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(sxz, -2 / math.pi * x * z * z / r4, rtol=1e-13, atol=1e-15)
    txx, tzz, txz = interior.shear_stresses(G, Gt, z)
    np.testing.assert_allclose(txx, -2 / math.pi * x ** 3 / r4, rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(tzz, -2 / math.pi * x * z * z / r4, rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(txz, -2 / math.pi * x * x * z / r4, rtol=1e-13, atol=1e-15)


def mcewen(x, z, b=1.0, p0=1.0):
    """McEwen's closed form of the Hertz line contact p = p0 sqrt(1 - x^2/b^2) (Johnson, eq. 4.49)."""
    A = b * b - x * x + z * z
    root = np.sqrt(A * A + 4 * x * x * z * z)
    # m^2 n^2 = x^2 z^2: the smaller of the two from the larger, without the cancellation of root -+ A
    big = 0.5 * (root + np.abs(A))
    small = np.divide(x * x * z * z, big, out=np.zeros_like(big), where=big > 0)
    m = np.sqrt(np.where(A >= 0, big, small))
    n = np.sign(x) * np.sqrt(np.where(A >= 0, small, big))
    mn = m * m + n * n
    sxx = -p0 / b * (m * (1 + (z * z + n * n) / mn) - 2 * z)
    szz = -p0 / b * m * (1 - (z * z + n * n) / mn)
    sxz = -p0 / b * n * (m * m - z * z) / mn
    return sxx, szz, sxz


def test_hertz_limit_is_mcewen():
    """One small non-periodic harmonic: the pressure differs from Hertz by 0.115 a^2 relatively (W28), below
    1e-12 at 2a/lambda_1 = 1e-6; the whole field then equals McEwen's to 1e-12 p0."""
    w = 1e-6
    p0 = float(contact.peak_pressure(w, [1.0], [1], periodic=False)[0])
    rng = np.random.default_rng(5)
    x, z = rng.uniform(-3, 3, 200), np.exp(rng.uniform(math.log(1e-6), math.log(5), 200))
    v, _ = field(x, z, w, ([1.0], [1]), periodic=False)
    for k, ref in zip(STRESS, mcewen(x, z)):
        assert np.max(np.abs(v[k] / p0 - ref)) <= 1e-12


def test_hertz_limit_peak():
    """tau_max of the Hertz line contact: 0.300 p0 at z = 0.786 b on the axis (independently: the maximum
    of McEwen's (sigma_xx - sigma_zz)/2 on x = 0, by golden-section search)."""
    w = 1e-6
    p0 = float(contact.peak_pressure(w, [1.0], [1], periodic=False)[0])
    pk = contact.subsurface_peaks(w, [1.0], [1], periodic=False, nu=0.3)
    gr = (math.sqrt(5) - 1) / 2
    lo, hi = 0.5, 1.0
    f = lambda z: 0.5 * (mcewen(np.array(0.0), np.array(z))[0] - mcewen(np.array(0.0), np.array(z))[1])
    for _ in range(80):
        m1, m2 = hi - gr * (hi - lo), lo + gr * (hi - lo)
        lo, hi = (m1, hi) if f(m1) < f(m2) else (lo, m2)
    value, x0, z0 = (float(v) for v in pk["tau_max"])
    assert abs(value / p0 - float(f(lo))) <= 1e-12
    assert round(value / p0, 3) == 0.300 and round(z0, 2) == 0.79 and abs(x0) <= 1e-6
    assert abs(z0 - lo) <= 1e-5


def test_full_contact_is_westergaard():
    """2a/lambda_1 -> 1, one periodic harmonic: p -> 2 p* cos^2(x/2) = p* (1 + cos x) - the mean p* plus
    Westergaard's harmonic p_1 = p* cos x, whose field is sigma_xx = -p_1 (1 - z) e^{-z} cos x,
    sigma_zz = -p_1 (1 + z) e^{-z} cos x, sigma_xz = -p_1 z e^{-z} sin x (k = 1); the mean gives -p* in both."""
    w = 1.0 - 1e-12
    a = math.pi * w
    rng = np.random.default_rng(7)
    X, Z = rng.uniform(-4, 4, 100), rng.uniform(1e-6, 6, 100)
    v, _ = field(X / a, Z / a, w, ([1.0], [1]))
    e = np.exp(-Z)
    ref = (-1 - (1 - Z) * e * np.cos(X), -1 - (1 + Z) * e * np.cos(X), -Z * e * np.sin(X))
    for k, r in zip(STRESS, ref):
        assert np.max(np.abs(v[k] - r)) <= 1e-10   # the contact is 1e-12 short of full: p differs by ~1e-11


def test_surface_values_bit_for_bit_and_limit():
    """z = 0 gives the surface's own pressure to the bit; z = 1e-9 tends to it (sigma_zz -> -p, sigma_xz -> 0)."""
    for periodic in (True, False):
        x = np.linspace(-1.4, 1.4, 57)
        p = contact.pressure(x, 0.6, *F2, periodic=periodic)[0]
        v, _ = field(x, 0.0, 0.6, periodic=periodic)
        assert np.array_equal(v["sigma_zz"], 0.0 - p) and np.array_equal(v["sigma_xz"], np.zeros_like(x))
        assert np.array_equal(v["sigma_xx"], 0.0 - p)
        near, _ = field(x, 1e-9, 0.6, periodic=periodic)
        off = np.abs(np.abs(x) - 1.0) > 0.01      # at an edge p ~ sqrt(a - |x|): the limit is O(sqrt(z))
        assert np.max(np.abs(near["sigma_zz"] + p)[off]) <= 1e-8
        assert np.max(np.abs(near["sigma_xz"])[off]) <= 1e-8
        assert np.max(np.abs(near["sigma_zz"] + p)) <= 1e-3


def test_mean_pressure_mode_at_depth():
    """Periodic: sigma_xx = sigma_zz = -p_inf far below (the k = 0 mode), sigma_xz -> 0; single indenter: all -> 0."""
    pinf = float(contact.mean_pressure(0.6, *F2, periodic=True))
    v, _ = field(np.array([0.0, 1.0, 2.5]), 40.0, 0.6)
    np.testing.assert_allclose(v["sigma_xx"], -pinf, atol=1e-13)
    np.testing.assert_allclose(v["sigma_zz"], -pinf, atol=1e-13)
    np.testing.assert_allclose(v["sigma_xz"], 0.0, atol=1e-13)
    v, _ = field(np.array([0.0, 1.0]), 1e5, 0.6, periodic=False)
    assert np.max(np.abs(v["sigma_zz"])) < 1e-4


@pytest.mark.parametrize("periodic", [True, False])
def test_equilibrium_and_compatibility_fall_as_h_squared(periodic):
    """d sxx/dx + d sxz/dz = 0, d sxz/dx + d szz/dz = 0 and nabla^2 (sxx + szz) = 0 by central differences:
    the residuals fall like h^2 (ratio ~16 per halving of h twice) down to rounding, with no floor above it."""
    pts = [(0.4, 0.3), (1.3, 0.05), (-0.7, 1.2), (2.2, 0.6)]
    for x, z in pts:
        res = []
        for h in (4e-2, 1e-2):
            def s(dx, dz):
                v, _ = field(np.array(x + dx), np.array(z + dz), 0.6, periodic=periodic)
                return v["sigma_xx"], v["sigma_zz"], v["sigma_xz"]
            (xp, xm, zp, zm, c) = (s(h, 0), s(-h, 0), s(0, h), s(0, -h), s(0, 0))
            eq1 = (xp[0] - xm[0]) / (2 * h) + (zp[2] - zm[2]) / (2 * h)
            eq2 = (xp[2] - xm[2]) / (2 * h) + (zp[1] - zm[1]) / (2 * h)
            tr = lambda v: v[0] + v[1]
            lap = (tr(xp) + tr(xm) + tr(zp) + tr(zm) - 4 * tr(c)) / (h * h)
            res.append(np.abs([eq1, eq2, lap]))
        ratio = res[0] / np.maximum(res[1], 1e-300)
        scale = np.maximum(res[0], 1e-300)
        # each residual is O(h^2): a fourfold step reduces it ~16-fold, unless already at rounding (~1e-10)
        assert np.all((ratio > 10) | (res[1] < 1e-9)), (x, z, res)
        assert np.all(scale < 0.5)


# ----------------------------------------------------------------------------- partial slip

def cattaneo_2d(x, c):
    """2-D Cattaneo traction for p = sqrt(1 - x^2) (b = 1):
    q/(mu p0) = sqrt(1 - x^2) - c sqrt(1 - x^2/c^2) in |x| < c."""
    return np.sqrt(np.clip(1 - x * x, 0, None)) - c * np.sqrt(np.clip(1 - x * x / (c * c), 0, None))


def test_partial_slip_hertz_limit_is_cattaneo():
    """a << lambda: c/a = sqrt(1 - Q/(mu P)) and the traction of Cattaneo's line contact."""
    w, mu, fx = 1e-6, 0.4, 0.64
    ratio, ok = contact.stick_half_width(w, [1.0], [1], fx, periodic=False)
    assert ok and abs(float(ratio) - 0.6) <= 1e-9
    p0 = float(contact.peak_pressure(w, [1.0], [1], periodic=False)[0])
    x = np.linspace(-1.2, 1.2, 97)
    v, _ = field(x, 0.0, w, ([1.0], [1]), periodic=False, names=("shear_traction",), mu=mu, fx=fx)
    np.testing.assert_allclose(v["shear_traction"] / (mu * p0), cattaneo_2d(x, 0.6), atol=1e-9)


def test_partial_slip_interior_is_the_superposition_of_two_hertz_fields():
    """Below the surface (a << lambda): the tangential McEwen-type field of q = mu p0 [sqrt(1 - x^2) - c sqrt(1 -
    x^2/c^2)], from the potential H = mu p0 [(zeta - r(zeta)) - (zeta - r_c(zeta))] (the Hertz Cauchy potential in
    closed form, r = sqrt(zeta - 1) sqrt(zeta + 1)), through the tangential Flamant kernels (W41) - checked
    against a direct quadrature of those kernels at a few points."""
    w, mu, fx = 1e-6, 0.3, 0.64
    p0 = float(contact.peak_pressure(w, [1.0], [1], periodic=False)[0])
    xs = np.array([0.2, -0.5, 0.9, 1.4])
    zs = np.array([0.1, 0.4, 0.8, 0.3])
    v, _ = field(xs, zs, w, ([1.0], [1]), periodic=False, mu=mu, fx=fx)
    vn, _ = field(xs, zs, w, ([1.0], [1]), periodic=False)
    mp.mp.dps = 15
    for i, (x, z) in enumerate(zip(xs, zs)):
        def kern(which):
            def f(t):
                q = mp.sqrt(1 - t * t) - (0.6 * mp.sqrt(1 - (t / 0.6) ** 2) if abs(t) < 0.6 else 0)
                u = x - t
                r4 = (u * u + z * z) ** 2
                return q * {0: u ** 3, 1: u * z * z, 2: u * u * z}[which] / r4
            return -2 / mp.pi * mp.quad(f, [-1, -0.6, 0.6, 1])
        tan = [float(kern(k)) * mu for k in range(3)]
        for k, t in zip(STRESS, tan):
            assert abs((v[k][i] - vn[k][i]) / p0 - t) <= 1e-9


def test_tangential_surface_limit():
    """z -> 0: sigma_xz -> -q, sigma_zz -> -p under combined load (periodic, two harmonics)."""
    x = np.linspace(-0.95, 0.95, 21)
    surf, _ = field(x, 0.0, 0.5, mu=0.3, fx=0.5, names=STRESS + ("shear_traction",))
    near, _ = field(x, 1e-9, 0.5, mu=0.3, fx=0.5)
    assert np.array_equal(surf["sigma_xz"], -surf["shear_traction"])
    assert np.max(np.abs(near["sigma_xz"] - surf["sigma_xz"])) <= 1e-7
    assert np.max(np.abs(near["sigma_zz"] - surf["sigma_zz"])) <= 1e-7
    assert np.max(np.abs(near["sigma_xx"] - surf["sigma_xx"])) <= 1e-7


def test_stick_width_relation():
    """Q/(mu P) = 1 - P(c)/P(a) (Ciavarella, Jager) for both domains, against the closed load formulas."""
    for periodic in (True, False):
        for fx in (0.1, 0.5, 0.9):
            r, ok = contact.stick_half_width(0.4, *F2, fx, periodic=periodic)
            Pa = contact.mean_pressure(0.4, *F2, periodic=periodic)
            Pc = contact.mean_pressure(0.4 * float(r), *F2, periodic=periodic)
            assert ok and abs(1 - Pc / Pa - fx) <= 1e-12
    assert float(contact.stick_half_width(0.4, *F2, 0.0, periodic=True)[0]) == 1.0
    assert float(contact.stick_half_width(0.4, *F2, 1.0, periodic=True)[0]) == 0.0


@pytest.mark.parametrize("periodic", [True, False])
def test_values_do_not_depend_on_the_other_cases_of_the_call(periodic):
    """A case's stresses are the same bits alone and beside other contact widths and harmonic counts
    (the content hash of a file must not depend on its chunking)."""
    x, z = np.linspace(-2, 2, 11), np.array([0.0, 0.05, 0.7, 4.0])[:, None]
    alone, _ = field(x, z, 0.3, periodic=periodic, n_harmonics=2)
    both, _ = field(x, z[..., None], np.array([0.3, 0.9])[:, None], periodic=periodic,
                    n_harmonics=np.array([[2, 1]]).T)
    for k in STRESS:
        np.testing.assert_array_equal(alone[k], both[k][:, 0, :])
