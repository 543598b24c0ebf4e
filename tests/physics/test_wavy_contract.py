"""The accuracy contract of the wavy family, probed on seeded random cases.

Independent routes: Westergaard's closed form (one periodic harmonic, up to 2a/lambda_1 = 1 - 1e-7),
the Chebyshev series of (W7)/(W9) with DCT coefficients (periodic, several harmonics, where it
converges), the exact rational value of the hypergeometric polynomial for the mean pressure (W34),
and the recipe route with E given against the normalised one.
"""
from fractions import Fraction
from math import comb

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import stressfields as sf
from stressfields.physics import wavy
from stressfields.physics.wavy import profile, series

SETTINGS = settings(derandomize=True, max_examples=25, deadline=None)
widths = st.one_of(st.floats(1e-6, 0.9), st.floats(0.9, 1.0 - 1e-7))
harmonics = st.lists(st.tuples(st.floats(-0.5, 0.5), st.integers(2, 40)), min_size=0, max_size=3)


def _profile(rest):
    return [1.0] + [d for d, _ in rest], [1] + [n for _, n in rest]


def _x(w):
    """edges, centre, inside, and beyond one period (lambda_1 = 2a/w in units of a)."""
    t = np.array([0.0, 0.3, 0.999999, 1.0, 1.0 - 1e-12])
    period = 2.0 / w
    return np.concatenate([t, -t, t + period, -t - 3 * period])


@SETTINGS
@given(w=widths)
def test_one_periodic_harmonic_is_westergaard(w):
    x = _x(w)[:10]                       # within one period (periodicity: test_periodic_and_even)
    p, info = wavy.pressure(x, w, [1.0], [1], periodic=True, rtol=1e-12)
    h = 0.5 * np.pi * w
    t = np.abs(x)
    exact = 2 * np.cos(h * t) * np.sqrt(np.clip(np.sin(h * (1 - t)) * np.sin(h * (1 + t)), 0, None))
    exact = np.where(t <= 1, exact, 0.0)
    err = np.abs(p - exact)
    assert np.all(err <= 1e-12 * np.maximum(np.abs(exact), 1.0))
    assert np.all(err <= info["error_estimate"] + 4e-16 * np.abs(exact))
    p0, info = wavy.peak_pressure(w, [1.0], [1], periodic=True)
    assert abs(p0 - 2 * np.sin(h)) <= 1e-12 * 2 * np.sin(h) and info["converged"]


@SETTINGS
@given(w=st.floats(1e-3, 0.6), rest=harmonics)
def test_periodic_closed_form_against_the_chebyshev_series(w, rest):
    amps, wns = _profile(rest)
    t = np.linspace(0.0, 1.0, 41)
    p, info = wavy.pressure(t, w, amps, wns, periodic=True, rtol=1e-10)
    dr, n = profile.harmonic_table(amps, wns)
    tab = series.build_table([np.pi * w], [len(n)], dr, n, is_periodic=True, rtol=1e-14, max_terms=1 << 14)
    ref = series.sine_sum(tab, np.zeros(t.shape, dtype=int), wavy.periodic.theta_of_t(t, np.pi * w))
    assert np.all(np.abs(p - ref) <= 1e-12 * np.maximum(np.abs(ref), 1.0) + tab.err[0])
    assert info["converged"].all()


@SETTINGS
@given(w=widths, rest=harmonics, periodic=st.booleans())
def test_periodic_and_even(w, rest, periodic):
    amps, wns = _profile(rest)
    x = _x(w)
    p, _ = wavy.pressure(x, w, amps, wns, periodic=periodic, rtol=1e-10)
    np.testing.assert_array_equal(p[:5], p[5:10])                       # p(-x) = p(x)
    if periodic:   # periods on: the same (away from the edge, where x + k lambda_1 rounds t by eps k/w)
        np.testing.assert_allclose(p[10:12], p[:2], rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(p[15:17], p[:2], rtol=1e-9, atol=1e-12)
    else:
        assert np.all(p[10:] == 0)


def _mean_exact(w, n):
    u = Fraction(float(np.sin(0.5 * np.pi * w) ** 2))
    return 0.5 * n * float(sum((-1) ** k * (comb(n - 1, k) * comb(n - 1 + k, k) - comb(n, k) * comb(n + k, k))
                               * u ** k for k in range(n + 1)))


@SETTINGS
@given(w=st.one_of(st.floats(1e-12, 1e-3), widths), n=st.integers(2, 40))
def test_periodic_mean_pressure_is_relative_accurate(w, n):
    v = wavy.mean_pressure(w, [1.0, 1.0], [1, n], periodic=True)
    ref = _mean_exact(w, 1) + _mean_exact(w, n)
    if _mean_exact(w, n) > 0:            # both terms positive: no cancellation between harmonics
        assert abs(v - ref) <= 1e-12 * abs(ref)


@settings(derandomize=True, max_examples=6, deadline=None)
@given(w=widths, periodic=st.booleans())
def test_physical_units_scale_the_normalised_values(w, periodic):
    E, nu, lam, delta = 70e9, 0.25, 2e-3, 1e-6
    a = w * lam / 2
    x = [0.0, 0.5, 1.0, 2.5]
    params = {"domain": "periodic" if periodic else "nonperiodic", "amplitudes": [1.0, 0.1], "wavenumbers": [1, 7],
              "a": w, "x": x}
    norm = sf.generate({"scenario": "wavy", "parameters": params}).compute()
    phys = sf.generate({"scenario": "wavy", "parameters": {**params, "amplitudes": [delta, 0.1 * delta], "E": E,
                                                            "nu": nu, "lambda_1": lam,
                                                            "x": [v * a for v in x]}}).compute()
    pstar = np.pi * E / (1 - nu ** 2) * delta / lam
    np.testing.assert_allclose(phys.pressure.values, norm.pressure.values * pstar, rtol=1e-9,
                               atol=1e-12 * pstar)
    np.testing.assert_allclose(phys.mean_pressure.values, norm.mean_pressure.values * pstar, rtol=1e-12)


def test_reproducer_full_contact():
    """2a/lambda_1 = 0.999999: p(0) = 2 sin(pi w/2) (Westergaard), converged, contact continuous."""
    params = {"domain": "periodic", "amplitudes": [1.0], "wavenumbers": [1], "a": 0.999999, "x": [0.0]}
    ds = sf.generate({"scenario": "wavy", "parameters": params, "method": {"rtol": 1e-8}}).compute()
    exact = 2 * np.sin(0.5 * np.pi * 0.999999)
    assert abs(float(ds.peak_pressure) - exact) <= 1e-12 * exact
    assert int(ds.converged) == 1 and int(ds.continuous_contact) == 1 and int(ds.validity.squeeze()) == 0


def _legendre_exact(k, u):
    """P_k(1 - 2u) in exact rational arithmetic (u a Fraction)."""
    return sum((-1) ** m * comb(k, m) * comb(k + m, m) * u ** m for m in range(k + 1))


@SETTINGS
@given(w=st.one_of(st.floats(1e-9, 1e-3), widths), n=st.integers(2, 40))
def test_periodic_approach_is_relative_accurate(w, n):
    """(W16) against its Legendre polynomials evaluated exactly in rationals at u = sin^2(a/2) (the
    terms 1 - (P_n + P_{n-1})/2 and P_{n-1} - P_n cancel in floating point as a -> 0)."""
    s = float(np.sin(0.5 * np.pi * w))
    u = Fraction(s * s)
    ref = 0.0
    for k in (1, n):
        pk, pk1 = _legendre_exact(k, u), _legendre_exact(k - 1, u)
        ref += -k * np.log(s) * float(pk1 - pk) + float(1 - (pk + pk1) / 2)
    v = wavy.approach(w, [1.0, 1.0], [1, n], periodic=True)
    assert abs(v - ref) <= 1e-12 * abs(ref)


@SETTINGS
@given(w=st.one_of(st.floats(1e-9, 1e-3), widths))
def test_one_periodic_harmonic_approach_is_westergaard(w):
    """(W27): delta/Delta = sin^2(a/2) [1 - 2 ln sin(a/2)], down to 2a/lambda_1 = 1e-9."""
    s = np.sin(0.5 * np.pi * w)
    exact = s * s * (1.0 - 2.0 * np.log(s))
    assert abs(wavy.approach(w, [1.0], [1], periodic=True) - exact) <= 1e-12 * exact


def _bessel_miller(z):
    """J_k(z), k = 0..top, by Miller's backward recurrence in extended precision, normalised by
    J_0 + 2 sum J_2k = 1 (independent of scipy's jv, which it matches to ~4e-17 absolute)."""
    ld = np.longdouble
    top = int(z + 12 * np.cbrt(z) + 60)
    top += top % 2
    j = np.zeros(top + 2, dtype=ld)
    j[top] = ld(1e-300)
    for k in range(top, 0, -1):
        j[k - 1] = (2 * k / ld(z)) * j[k] - j[k + 1]
        if abs(j[k - 1]) > ld(1e300):
            j[k - 1:] /= ld(1e300)
    return j[:top + 1] / (j[0] + 2 * np.sum(j[2:top + 1:2]))


def _nonperiodic_reference(t, w, amps, wns):
    """(W8)/(W9) summed to the end of the Miller table in extended precision."""
    ld = np.longdouble
    a = np.pi * w
    th = 2 * np.arctan2(np.sqrt(1 - np.asarray(t, dtype=ld)), np.sqrt(1 + np.asarray(t, dtype=ld)))
    out = np.zeros(th.shape, dtype=ld)
    for d, n in zip(np.asarray(amps) / amps[0], wns):
        J = _bessel_miller(a * n)
        for m in range((len(J) - 1) // 2):
            out += ld(2 * d * n) * (-1) ** m * J[2 * m + 1] * np.sin((2 * m + 1) * th)
    return out.astype(float)


@settings(derandomize=True, max_examples=30, deadline=None)
@given(w=st.floats(1e-6, 0.99), rest=st.lists(st.tuples(st.floats(-0.5, 0.5), st.integers(2, 400)), max_size=2),
       rtol=st.sampled_from([1e-8, 1e-12, 1e-15]))
def test_nonperiodic_error_estimate_is_an_upper_bound(w, rest, rtol):
    """(W22), (W23): |error| <= error_estimate against the extended-precision reference, and the flag
    is the contract's: converged = 1 exactly when error_estimate <= rtol p*."""
    amps, wns = _profile(rest)
    t = np.concatenate([np.linspace(0.0, 1.0, 33), 1 - np.logspace(-15, -1, 8)])
    p, info = wavy.pressure(t, w, amps, wns, periodic=False, rtol=rtol)
    err = np.abs(p - _nonperiodic_reference(t, w, amps, wns))
    assert np.all(err <= info["error_estimate"])
    assert np.array_equal(info["converged"], info["error_estimate"] <= rtol)
    assert np.all(err[info["converged"]] <= rtol * np.maximum(np.abs(p), 1.0)[info["converged"]])


def _periodic_reference(t, w, dr, n):
    """p/p* of (W30) in extended precision, with P_k(1 - 2u), u = sin^2(a/2), by the recurrence of the
    differences D_k = P_k - P_{k-1}, (k + 1) D_{k+1} = k D_k - 2u (2k + 1) P_k (no loss as c = cos a -> 1;
    a route independent of the cosine sum (W35) the code evaluates)."""
    ld = np.longdouble
    a = ld(np.pi * w)                    # the code's contact angle, exactly
    u = np.sin(a / 2) ** 2
    P, D = [ld(1)], ld(0)
    for k in range(int(max(n))):
        D = (k * D - 2 * u * (2 * k + 1) * P[k]) / (k + 1)
        P.append(P[k] + D)
    B = [ld(0)] * int(max(n))
    for d, ni in zip(dr, n):
        for j in range(int(ni)):
            B[j] += 2 * ld(d) * int(ni) * P[int(ni) - 1 - j]
    t = np.asarray(t, dtype=ld)
    R = np.sqrt(np.sin(a * (1 - t) / 2) * np.sin(a * (1 + t) / 2))
    return R * sum(b * np.cos((j + ld(0.5)) * a * t) for j, b in enumerate(B))


def test_periodic_rounding_bound_holds():
    """(W31) is an upper bound of |error| of p and phi (W30) with P_k by (W35): seeded profiles of up to 4
    harmonics, n <= 100, 2a/lambda_1 from 1e-6 to 1 - 1e-7, edges included (measured ratio <= 0.12;
    the bound with scipy's eval_legendre was exceeded 2.2-fold)."""
    rng = np.random.default_rng(20180831)
    worst = 0.0
    for _ in range(60):
        nh = rng.integers(0, 4)
        dr = np.array([1.0, *(rng.uniform(-1, 1, nh) * 10.0 ** rng.uniform(-3, 0, nh))])
        n = np.array([1, *rng.integers(2, 101, nh)], dtype=float)
        w = rng.choice([10 ** rng.uniform(-6, 0), 1 - 10 ** rng.uniform(-7, -1)])
        t = np.concatenate([rng.uniform(0, 1, 60), 1 - 10.0 ** -rng.uniform(1, 15, 12), [0.0, 1.0]])
        p, info = wavy.pressure(t, w, dr, n, periodic=True, rtol=1e-12)
        ref = _periodic_reference(t, w, dr, n)
        err = np.abs(p - ref.astype(float))
        worst = max(worst, float(err.max() / info["error_estimate"][0]))
        inner = t < 1.0                  # phi = p/sqrt(1 - t^2) and its bound err_shape
        phi, info_phi = wavy.pressure_shape(t[inner], w, dr, n, periodic=True, rtol=1e-12)
        ref_phi = ref[inner] / np.sqrt((1 - t[inner].astype(np.longdouble)) * (1 + t[inner]))
        worst = max(worst, float(np.max(np.abs(phi - ref_phi.astype(float)) / info_phi["error_estimate"])))
        assert np.array_equal(info["converged"], info["error_estimate"] <= 1e-12)
    assert worst <= 1.0


@pytest.mark.parametrize("amps, wns", [([1.0], [1]), ([1.0, 0.02], [1, 11]), ([1.0, 0.02, 0.00075], [1, 11, 40]),
                                       ([1.0, 0.1, -0.05], [1, 7, 23])])
def test_periodic_bound_is_not_too_loose(amps, wns):
    """The paper's profiles and moderate ripples (2 |Delta_i| n_i/Delta_1 <= 2.3) converge at rtol = 1e-12 over
    the whole range of 2a/lambda_1, although (W31) is a worst-case bound."""
    w = np.concatenate([np.logspace(-6, -1, 12), np.linspace(0.1, 0.99, 24), 1 - np.logspace(-7, -2, 8)])
    _, info = wavy.peak_pressure(w, amps, wns, periodic=True, rtol=1e-12)
    assert info["converged"].all()


@pytest.mark.parametrize("w", [1e-5, 1e-4, 1e-3, 1e-2])
def test_narrow_nonperiodic_contact_is_hertz(w):
    """One harmonic g = Delta (1 - cos(2 pi x/lambda)) is, near its crest, the parabola x^2/(2R) with
    R = lambda^2/(4 pi^2 Delta) (1 - cos y = y^2/2 - ...). Hertz line contact of half-width a (W28):
    p = (E* a/(2R)) sqrt(1 - x^2/a^2), load per length W = pi a^2 E*/(4R), and, with the datum of (W15)
    (kernel ln|2 pi (x - xi)/lambda|), approach delta = -(2/(pi E*)) int p(xi) ln|2 pi xi/lambda| dxi
    = (a^2/(2R)) [ln(lambda/(pi a)) + 1/2] (int_{-1}^{1} sqrt(1 - s^2) ln|s| ds = -(pi/2)(ln 2 + 1/2)).
    The cosine differs from the parabola by O(a^2): p by <= 0.118 (2 pi a/lambda)^2 of its peak (the
    J_3 term of (W8)), delta and W by (2 pi a/lambda)^2/8 relatively."""
    E_star, lam, delta = 2e11, 1e-3, 1e-6                # physical units, SI
    R = lam ** 2 / (4 * np.pi ** 2 * delta)
    a = w * lam / 2
    A = 2 * np.pi * a / lam                              # a in lambda = 2 pi units
    pstar = np.pi * E_star * delta / lam
    t = np.linspace(-1.0, 1.0, 41)
    p = wavy.pressure(t, w, [1.0], [1], periodic=False, rtol=1e-13)[0] * pstar
    peak = E_star * a / (2 * R)
    hertz = peak * np.sqrt(1 - t * t)
    assert np.max(np.abs(p - hertz)) <= 0.12 * A * A * peak + 1e-12 * peak
    W = wavy.mean_pressure(w, [1.0], [1], periodic=False) * pstar * lam
    W_h = np.pi * a * a * E_star / (4 * R)
    assert abs(W / W_h - 1) <= A * A / 8 * 1.01
    d = wavy.approach(w, [1.0], [1], periodic=False) * delta
    d_h = a * a / (2 * R) * (np.log(lam / (np.pi * a)) + 0.5)
    assert abs(d / d_h - 1) <= A * A / 8 * 1.01
    assert abs(d / d_h - 1) >= A * A / 8 * 0.5          # the O(a^2) difference is the cosine's, resolved
