"""Series lengths, error estimates, stability near full contact and at large a n, broadcasting."""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import eval_legendre, j0

from stressfields.physics import wavy
from stressfields.physics.wavy import profile, series

F1 = dict(amplitudes=[1.0], wavenumbers=[1])
F3 = dict(amplitudes=[0.5, 0.01, 0.00075], wavenumbers=[1, 11, 40])


def _single(n):
    """Harmonic n with weight w = 2 (Delta_n/Delta_1) n = 1 on the base row (required), whose own
    series is no longer than harmonic n's: the length is harmonic n's, and the values stay of the
    order of p*, where the tolerance rtol * max(|value|, p*) is reachable."""
    return dict(amplitudes=[1.0], wavenumbers=[1]) if n == 1 else dict(amplitudes=[1.0, 0.5 / n], wavenumbers=[1, n])


# docs/theory/wavy.md (W24): highest Chebyshev index J for 1e-10 (periodic), K terms (Bessel), measured
# against long sums in the sup norm over the contact
TABLE_J = {1: [7, 13, 27, 73, 145, 293, 1465], 2: [7, 13, 31, 85, 171, 343, 1719],
           11: [11, 25, 59, 169, 343, 689, 3425], 40: [21, 51, 131, 387, 791, 1589, 7929]}
TABLE_W = [0.05, 0.2, 0.5, 0.8, 0.9, 0.95, 0.99]
TABLE_Z = [0.1, 0.5, 1, 2, 5, 10, 20, 50, 100, 200, 400]
TABLE_K = [3, 4, 5, 7, 10, 14, 21, 40, 68, 123, 229]


def _dct_series(w, prof, rtol, max_terms=wavy.DEFAULT_MAX_TERMS):
    """The periodic Chebyshev series (W9) with DCT coefficients (W7): no longer the route (the closed
    form (W30) is), kept as an independent check of it; its length law is tested here."""
    dr, n = profile.harmonic_table(prof["amplitudes"], prof["wavenumbers"])
    return series.build_table(np.pi * np.atleast_1d(w), [len(n)], dr, n, is_periodic=True, rtol=rtol,
                              max_terms=max_terms)


@pytest.mark.parametrize("n", sorted(TABLE_J))
def test_periodic_lengths_follow_length_law(n):
    info = {"n_terms": (t := _dct_series(TABLE_W, _single(n), 1e-10)).K, "converged": t.converged}
    J = 2 * info["n_terms"] - 1
    # our criterion (l1 tail of the coefficients, (W22)) is slightly stricter than the table's sup norm
    assert np.all(J >= 0.95 * np.array(TABLE_J[n]) - 2)
    assert np.all(J <= 1.2 * np.array(TABLE_J[n]) + 2)
    assert info["converged"].all()


def test_bessel_lengths_follow_length_law():
    n = 100_000   # a = z/n <= 0.004: the base row adds <= 1 % to the scale rtol refers to
    _, info = wavy.peak_pressure(np.array(TABLE_Z) / (np.pi * n), **_single(n), periodic=False, rtol=1e-10)
    np.testing.assert_array_equal(info["n_terms"], TABLE_K)


def test_periodic_terms_grow_with_ratio_cot_a_over_4():
    """|A_j| ~ rho^-j, rho = cot(a/4): each factor 100 in rtol costs ln(100)/(2 ln rho) more odd terms."""
    for w in [0.5, 0.9]:
        a = np.pi * w
        K = [_dct_series(w, F1, r).K[0] for r in (1e-6, 1e-8, 1e-10)]
        step = np.log(100) / (2 * np.log(1 / np.tan(a / 4)))
        np.testing.assert_allclose(np.diff(K), step, atol=1.5)


@pytest.mark.parametrize("w", [0.99])
def test_stable_near_full_contact(w):
    """2a/lambda_1 = 0.99: the rough profile (n up to 40) either meets rtol or says it does not,
    and the estimate covers the true error of p(0) (Legendre closed form, docs/theory/wavy.md (W13))."""
    a = np.pi * w
    amp, wn = F3["amplitudes"], F3["wavenumbers"]
    ref = 0.0
    for d, n in zip(amp, wn):
        f = lambda t: (eval_legendre(n - 1, np.cos(t)) + eval_legendre(n, np.cos(t))) / np.cos(t / 2)
        ref += 2 * d / amp[0] * n * n / 4 * quad(f, 0, a, limit=1000, epsabs=1e-13, epsrel=1e-13)[0]
    assert _dct_series(w, F3, 1e-12).K[0] > 3000   # (W24): J ~ 7929 for n = 40 at 0.99 ...
    p0, info = wavy.peak_pressure(w, **F3, periodic=True)
    assert info["n_terms"] == 40               # ... the closed form (W30) needs max n_i terms
    assert abs(p0 - ref) <= info["error_estimate"] + 1e-12
    assert abs(p0 - ref) < 1e-11          # rounding-limited there, but still accurate
    p, info = wavy.pressure(np.linspace(0, 1, 101), w, **F3, periodic=True)
    assert np.all(np.isfinite(p)) and np.all(info["error_estimate"] < 1e-9)


def test_large_a_n_nonperiodic():
    """a n = 400: about a n / 2 + 2 (a n)^(1/3) + 8 = 229 Bessel terms; p(0) from eq. (21) by quadrature."""
    n, a = 400, 1.0
    prof = dict(amplitudes=[1.0, 0.01], wavenumbers=[1, n])
    w = a / np.pi
    p0, info = wavy.peak_pressure(w, **prof, periodic=False)
    ref = (2 * 0.5 * quad(j0, 0, a, epsabs=1e-15)[0]
           + 2 * 0.01 * 0.5 * n * quad(j0, 0, a * n, limit=500, epsabs=1e-14)[0])
    assert 225 <= info["n_terms"] <= 240
    assert abs(p0 - ref) <= info["error_estimate"] + 1e-12
    # p ~ 5 p*: the rounding part of (W23), eps sum (2m+1)|D_m| ~ 2.7e-12 p*, exceeds the default
    # rtol p* = 1e-12 p*, so the contract's converged flag (estimate <= rtol p*) is honestly 0 there
    assert bool(info["converged"]) is bool(info["error_estimate"] <= wavy.DEFAULT_RTOL)
    assert not info["converged"]
    p0, info = wavy.peak_pressure(w, **prof, periodic=False, rtol=1e-11)
    assert info["converged"] and abs(p0 - ref) <= info["error_estimate"] + 1e-12
    # the pressure field itself stays bounded and even; Bessel tail terms are not unstable
    p, _ = wavy.pressure(np.linspace(-1, 1, 401), w, **prof, periodic=False)
    assert np.all(np.isfinite(p)) and np.max(np.abs(p)) < 10
    np.testing.assert_allclose(p, p[::-1], atol=1e-13)


def test_unreachable_tolerance_is_flagged_not_hidden():
    t = np.linspace(0, 1, 301)
    w = 0.99
    a = np.pi * w
    exact = 2 * np.cos(t * a / 2) * np.sqrt(np.sin(a * (1 - t) / 2) * np.sin(a * (1 + t) / 2))
    # the Chebyshev series (W9) with its length capped far below the 1500-odd terms needed
    tab = _dct_series(w, F1, 1e-12, max_terms=256)
    info = {"converged": tab.converged, "n_terms": tab.K, "error_estimate": tab.err}
    p = series.sine_sum(tab, np.zeros(t.shape, dtype=int), wavy.periodic.theta_of_t(t, a))
    assert not info["converged"].any()
    assert info["n_terms"].max() == 256
    err = np.max(np.abs(p - exact))
    assert err > 1e-6                                   # really not converged ...
    assert np.all(info["error_estimate"] >= err)        # ... and the estimate says so honestly
    # a tolerance below double precision cannot be met either
    p, info = wavy.pressure(t, w, **F1, periodic=True, rtol=1e-17)
    assert not info["converged"].any()
    assert np.max(np.abs(p - exact)) <= info["error_estimate"].max()


def test_broadcasting_and_harmonic_count():
    x = np.linspace(-1.2, 1.2, 7)[:, None, None]
    w = np.array([0.1, 0.3, 0.7])[None, :, None]
    N = np.array([1, 2, 3])[None, None, :]
    for periodic in (True, False):
        p, info = wavy.pressure(x, w, **F3, periodic=periodic, n_harmonics=N)
        assert p.shape == info["n_terms"].shape == (7, 3, 3)
        for j, ww in enumerate(w.ravel()):
            for k, nn in enumerate(N.ravel()):
                amp, wn = F3["amplitudes"][:nn], F3["wavenumbers"][:nn]
                pj, _ = wavy.pressure(x.ravel(), ww, amp, wn, periodic=periodic)
                np.testing.assert_allclose(p[:, j, k], pj, atol=1e-13)
        assert np.all(p[np.abs(x.ravel()) > 1] == 0)
        assert np.all(info["n_terms"][:, :, 0] <= info["n_terms"][:, :, 2])
        pinf = wavy.mean_pressure(w, **F3, periodic=periodic, n_harmonics=N)
        assert pinf.shape == (1, 3, 3)
        v = wavy.contact_validity(w, **F3, periodic=periodic, n_harmonics=N)
        assert v["ok"].shape == (1, 3, 3) and v["ok"].dtype == bool
        u, _ = wavy.displacement(x, w, **F3, periodic=periodic, n_harmonics=N)
        assert u.shape == (7, 3, 3) and np.all(np.isfinite(u))


def test_input_validation():
    with pytest.raises(ValueError, match="two_a_over_lambda1"):
        wavy.pressure(0.0, 1.0, **F1, periodic=True)
    with pytest.raises(ValueError, match="two_a_over_lambda1"):
        wavy.mean_pressure(0.0, **F1, periodic=False)
    with pytest.raises(ValueError, match="integers"):
        wavy.pressure(0.0, 0.5, [1.0, 0.1], [1, 2.5], periodic=True)
    with pytest.raises(ValueError, match="base wave"):
        wavy.pressure(0.0, 0.5, [1.0, 0.1], [2, 3], periodic=True)
    with pytest.raises(ValueError, match="n_harmonics"):
        wavy.pressure(0.0, 0.5, **F3, periodic=True, n_harmonics=4)
    with pytest.raises(ValueError, match="rtol"):
        wavy.pressure(0.0, 0.5, **F3, periodic=True, rtol=0.0)
