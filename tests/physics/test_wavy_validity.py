"""Continuous-contact validity: the exact test (P) + (G) decides, not the Johnson parameter.

Failure intervals come from an independent scan of 2a/lambda_1 (step 0.0025, interval ends bisected
to 1e-4) made with a Nystroem solution of the integral equations, not with this package; the gap
outside the contact is also checked by brute-force quadrature of the displacement integral (eq. 5)
with the kernels of docs/theory/wavy.md (W15).  The test itself is docs/theory/wavy.md (W20).
"""

import numpy as np
import pytest
from scipy.integrate import quad

from stressfields.physics import wavy

PROFILES = {"f1": ([0.5], [1]), "f2": ([0.5, 0.01], [1, 11]), "f3": ([0.5, 0.01, 0.00075], [1, 11, 40])}

# intervals of 2a/lambda_1 where (P) tensile pressure / (G) interpenetration occur (the scan above)
SCAN_P = {
    ("f1", True): [], ("f1", False): [(0.7655, 0.995)],
    ("f2", True): [(0.6446, 0.7079), (0.8084, 0.9482)],
    ("f2", False): [(0.1085, 0.1185), (0.6312, 0.7708), (0.7922, 0.995)],
    ("f3", True): [(0.0796, 0.0985), (0.1194, 0.1508), (0.2800, 0.2907), (0.4732, 0.5017), (0.6277, 0.7118),
                   (0.8153, 0.9593), (0.9771, 0.995)],
    ("f3", False): [(0.0795, 0.0989), (0.1193, 0.1511), (0.2785, 0.2952), (0.4707, 0.5125), (0.6232, 0.995)],
}
SCAN_G = {
    ("f1", True): [], ("f1", False): [(0.6079, 0.995)],
    ("f2", True): [(0.6293, 0.6807), (0.7717, 0.8836)],
    ("f2", False): [(0.1061, 0.1143), (0.5902, 0.995)],
    # the scan lists (0.6205, 0.6903) as one interval; see test_gap_interval_f3_periodic_has_a_hole
    ("f3", True): [(0.0754, 0.0898), (0.1101, 0.1372), (0.2775, 0.2861), (0.4662, 0.4888), (0.6205, 0.6423),
                   (0.6465, 0.6903), (0.7677, 0.8905), (0.9689, 0.995)],
    ("f3", False): [(0.0753, 0.0899), (0.1099, 0.1373), (0.2746, 0.2878), (0.4606, 0.4914), (0.5928, 0.995)],
}


def _inside(w, intervals, margin=1.5e-3):
    return any(lo + margin < w < hi - margin for lo, hi in intervals)


def _outside(w, intervals, margin=1.5e-3):
    return all(w < lo - margin or w > hi + margin for lo, hi in intervals)


@pytest.mark.parametrize("periodic", [True, False])
@pytest.mark.parametrize("name", sorted(PROFILES))
def test_failure_intervals_match_scan(name, periodic):
    amp, wn = PROFILES[name]
    w = np.arange(0.0025, 0.995, 0.0025)
    v = wavy.contact_validity(w, amp, wn, periodic=periodic)
    P, G = SCAN_P[(name, periodic)], SCAN_G[(name, periodic)]
    checked = 0
    for i, wi in enumerate(w):
        if _inside(wi, P):
            assert not v["pressure_ok"][i], wi
        if _outside(wi, P):
            assert v["pressure_ok"][i], wi
        if _inside(wi, G):
            assert not v["gap_ok"][i], wi
        if _outside(wi, G):
            assert v["gap_ok"][i], wi
            checked += 1
    assert checked > 100
    # figure values 0.05, 0.2, 0.3 are admissible for all profiles in both problems
    assert wavy.continuous_contact([0.05, 0.2, 0.3], amp, wn, periodic=periodic).all()


@pytest.mark.parametrize("name,w,periodic", [("f3", 0.5, True), ("f3", 0.5, False), ("f1", 0.8, False),
                                             ("f2", 0.7, True)])
def test_johnson_says_valid_but_exact_test_fails(name, w, periodic):
    amp, wn = PROFILES[name]
    chi = wavy.johnson_parameter(w, amp, wn, periodic=periodic)
    assert chi < 1.0
    v = wavy.contact_validity(w, amp, wn, periodic=periodic)
    assert not v["ok"]
    # tensile pocket near the edge, never at the centre, docs/theory/wavy.md (W20)
    if not v["pressure_ok"]:
        assert v["min_phi_over_pstar"] < 0 and v["x_of_min_phi_over_a"] > 0.75


@pytest.mark.parametrize("periodic", [True, False])
def test_johnson_says_invalid_but_contact_is_continuous(periodic):
    """2a/lambda_1 <~ 0.02: chi > 1, yet the contact sits on one ripple crest with p >= 0."""
    amp, wn = PROFILES["f3"]
    w = np.array([0.005, 0.01])
    assert np.all(wavy.johnson_parameter(w, amp, wn, periodic=periodic) > 1.0)
    assert wavy.continuous_contact(w, amp, wn, periodic=periodic).all()


def test_johnson_parameter_ranges():
    """docs/theory/wavy.md (W21): for 2a/lambda_1 >= 0.05, chi_2 in [0.14, 0.80] and chi_3 in [0.04, 0.22]
    (the printed definition would give n_i/2 times these: 5.5x and 20x)."""
    w = np.arange(0.05, 0.9951, 0.0025)
    for periodic in (True, False):
        chi = wavy.johnson_parameter(w, *PROFILES["f3"], periodic=periodic, per_harmonic=True)
        assert 0.13 < chi[:, 1].min() and chi[:, 1].max() < 0.81
        assert 0.035 < chi[:, 2].min() and chi[:, 2].max() < 0.225
    assert np.all(wavy.johnson_parameter(w, *PROFILES["f1"], periodic=True) == 0.0)


@pytest.mark.parametrize("periodic", [True, False])
def test_edge_tensile_exactly_where_mean_pressure_falls(periodic):
    """K = c(a) dW/da with c > 0, docs/theory/wavy.md (W19): the sign of the edge coefficient from the series
    equals the sign of d p_inf/da from the closed forms."""
    amp, wn = PROFILES["f3"]
    w = np.arange(0.02, 0.99, 0.01)
    h = 1e-6
    dp = wavy.mean_pressure(w + h, amp, wn, periodic=periodic) - wavy.mean_pressure(w - h, amp, wn, periodic=periodic)
    K = wavy.contact_validity(w, amp, wn, periodic=periodic)["edge_phi_over_pstar"]
    clear = np.abs(dp) > 1e-9
    assert clear.sum() > 80
    np.testing.assert_array_equal(np.sign(K[clear]), np.sign(dp[clear]))


# ------------------------------------------------------------------ brute-force displacement

def _uz_bruteforce(x, w, amp, wn, periodic, m=4000):
    """u_z(x)/Delta_1 = -(1/pi) int p/p* kernel(x - xi) dxi (eq. 5, C = 0) for |x| > a, by the
    midpoint rule in xi = a cos s (smooth, periodic integrand: spectrally accurate)."""
    a = np.pi * w
    s = (np.arange(m) + 0.5) * np.pi / m
    xi = a * np.cos(s)
    p, _ = wavy.pressure(np.cos(s), w, amp, wn, periodic=periodic, rtol=1e-14)
    y = np.asarray(x, dtype=float)[..., None] - xi
    ker = np.log(np.abs(2 * np.sin(y / 2))) if periodic else np.log(np.abs(y))
    return -np.sum(p * ker * a * np.sin(s), axis=-1) * (np.pi / m) / np.pi


def _uz0_bruteforce(w, amp, wn, periodic):
    """u_z(0)/Delta_1: the ln|xi| part with QUADPACK's algebraic-log weight, the rest smooth."""
    a = np.pi * w
    # p = phi sqrt(1 - t^2): p/sqrt(a - xi) = phi sqrt(1 + t)/sqrt(a) is smooth on [0, a]
    f = lambda xi: (wavy.pressure_shape(xi / a, w, amp, wn, periodic=periodic, rtol=1e-14)[0]
                    * np.sqrt((1 + xi / a) / a))
    I_log = quad(f, 0, a, weight="alg-loga", wvar=(0.0, 0.5), epsabs=1e-14, epsrel=1e-13, limit=400)[0]
    I_rest = 0.0
    if periodic:
        m = 4000
        s = (np.arange(m) + 0.5) * (np.pi / 2) / m
        xi = a * np.cos(s)
        p, _ = wavy.pressure(np.cos(s), w, amp, wn, periodic=True, rtol=1e-14)
        I_rest = np.sum(p * np.log(2 * np.sin(xi / 2) / xi) * a * np.sin(s)) * (np.pi / 2) / m
    return -(2 / np.pi) * (I_log + I_rest)


def _gap_bruteforce(t, w, amp, wn, periodic):
    a = np.pi * w
    x = np.asarray(t) * a
    g = sum(d / amp[0] * (1 - np.cos(n * x)) for d, n in zip(amp, wn))
    return g + _uz_bruteforce(x, w, amp, wn, periodic) - _uz0_bruteforce(w, amp, wn, periodic)


@pytest.mark.parametrize("name,w,periodic", [("f3", 0.6475, True), ("f3", 0.03, True), ("f2", 0.8, False),
                                             ("f2", 0.3, True)])
def test_gap_outside_against_bruteforce(name, w, periodic):
    amp, wn = PROFILES[name]
    a = np.pi * w
    t = np.array([1.02, 1.07, 1.2, np.pi / a])
    g, _ = wavy.separation(t, w, amp, wn, periodic=periodic)
    np.testing.assert_allclose(g, _gap_bruteforce(t, w, amp, wn, periodic), atol=1e-11)
    v = wavy.contact_validity(w, amp, wn, periodic=periodic)
    gm = _gap_bruteforce(v["x_of_min_gap_over_a"], w, amp, wn, periodic)
    assert abs(v["min_gap_over_Delta1"] - gm) < 1e-11


def test_gap_interval_f3_periodic_has_a_hole():
    """The scan lists (G) failing on [0.6205, 0.6903] for f3-periodic.  Our exact test finds a
    hole: the tensile edge closes at 2a/lambda_1 ~ 0.6434 (edge coefficient K turns positive) and the
    first outside ripple crest (x/a ~ 1.077) touches only from ~ 0.6454.  At 0.645 -- one of the scan's
    scan points -- the brute-force gap (eq. 5, ln|2 sin| kernel) is positive everywhere outside.
    (P) fails there anyway, so the overall validity flag agrees with the scan; docs/theory/wavy.md (W20)."""
    amp, wn = PROFILES["f3"]
    w = 0.645
    v = wavy.contact_validity(w, amp, wn, periodic=True)
    assert v["gap_ok"] and not v["pressure_ok"] and not v["ok"]
    assert v["edge_phi_over_pstar"] > 0
    a = np.pi * w
    t = np.linspace(1.0005, np.pi / a, 600)
    gb = _gap_bruteforce(t, w, amp, wn, True)
    assert gb.min() > 0
    crest = (t > 1.05) & (t < 1.12)
    assert 1e-5 < gb[crest].min() < 1e-4          # the crest clears by ~5e-5 Delta_1
    g, _ = wavy.separation(t, w, amp, wn, periodic=True)
    np.testing.assert_allclose(g, gb, atol=1e-11)
    # neighbouring scan points do fail (G), as in the scan
    v2 = wavy.contact_validity([0.6425, 0.6475], amp, wn, periodic=True)
    assert not v2["gap_ok"].any()


def test_johnson_parameter_is_ripple_amplitude_over_hertz_peak():
    """docs/theory/wavy.md (W21) from its two ingredients, each obtained by another route:
    the pressure ripple of a flattened harmonic, p*_i = (Delta_i/Delta_1) n_i p*, is the amplitude
    p(0) - p_inf of the periodic base wave near full contact (Westergaard: 2 sin(a/2) - sin^2(a/2) -> 1);
    the carrier pressure p_h = 2 W/(pi a), W = lambda_1 p_inf, is the Hertz peak, i.e. p(0) of a narrow
    single bump.  The printed chi = pi E Delta_i/(2 p_h lambda_i) with p_h = 2 p_inf lambda_i/(pi a) is
    n_i/2 times this (5.5x for n = 11)."""
    one = dict(amplitudes=[1.0], wavenumbers=[1])
    p0, _ = wavy.peak_pressure(0.99, **one, periodic=True, rtol=1e-13)
    ripple = p0 - wavy.mean_pressure(0.99, **one, periodic=True)       # p*_1/p*, -> 1
    assert abs(ripple - 1.0) < 1e-7
    w_small = 0.002                                                   # Hertz: p(0) = 2 W/(pi a)
    a_small = np.pi * w_small
    p0_small, _ = wavy.peak_pressure(w_small, **one, periodic=False)
    hertz = 2 * (2 * np.pi * wavy.mean_pressure(w_small, **one, periodic=False)) / (np.pi * a_small)
    assert abs(p0_small / hertz - 1) < 1e-5
    amp, wn = PROFILES["f3"]
    w = np.array([0.05, 0.3, 0.6])
    a = np.pi * w
    ratio, n = np.array(amp) / amp[0], np.array(wn)
    for periodic in (True, False):
        p_h = 2 * (2 * np.pi * wavy.mean_pressure(w, amp, wn, periodic=periodic)) / (np.pi * a)
        expected = ratio[None, :] * n[None, :] * ripple / p_h[:, None]
        chi = wavy.johnson_parameter(w, amp, wn, periodic=periodic, per_harmonic=True)
        np.testing.assert_allclose(chi, expected, rtol=1e-7)
        np.testing.assert_array_equal(wavy.johnson_parameter(w, amp, wn, periodic=periodic), chi[:, 1:].max(axis=1))
