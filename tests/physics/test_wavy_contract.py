"""The accuracy contract of the wavy family, probed on seeded random cases.

Independent routes: Westergaard's closed form (one periodic harmonic, up to 2a/lambda_1 = 1 - 1e-7),
the Chebyshev series of (W7)/(W9) with DCT coefficients (periodic, several harmonics, where it
converges), the exact rational value of the hypergeometric polynomial for the mean pressure (W34),
and the recipe route with E given against the normalised one.
"""
from fractions import Fraction
from math import comb

import numpy as np
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
