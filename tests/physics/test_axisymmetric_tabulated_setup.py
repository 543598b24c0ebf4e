"""The set-up of tabulated profiles: cached per content, O(log knots) per table point, 1e4 samples.

* the set-up cache (physics/setup_cache.py): a cached call returns bit-identical values; profiles
  that differ in one sample (by one ulp), in their length or only in a graded slope never share an
  entry; one build per key however many threads ask at once; the bounds hold;
* the g', g'' table built from the O(log knots) far-field sums (``Tabulated._fast_sums``) against the
  table built from the exact sums over every piece (``_FAST_SUMS = False``, the route it replaced)
  and against those exact sums themselves (A103), on a uniform and a noisy measured-like table;
* 1e4 samples: accepted by the recipes of the axisymmetric and graded scenarios, and a sampled
  paraboloid's surface stresses against the Hertz closed form (A5), to the route's rtol;
* the graded tangential stick radius and normal force of a tabulated profile against a 40-digit
  mpmath root of the closed forms of a sampled r^2/(2R) + c3 r^3 (the spline reproduces it), and
  its work (g' evaluations, counted, not timed) falling as rtol loosens.
"""
import threading

import mpmath as mp
import numpy as np
import pytest

import stressfields as sf
from stressfields.physics import axisymmetric as ax
from stressfields.physics.axisymmetric import profiles as AP
from stressfields.physics.graded import profiles as GP
from stressfields.physics.graded import tangential as GT
from stressfields.physics.graded import normal as GN
from stressfields.physics.graded.indenter import Indenter
from stressfields.physics.setup_cache import SETUP, SetupCache, content_key
from stressfields.recipe import load

EPS = np.finfo(float).eps


def _hyperboloid(n, shift=0.0):
    r = np.linspace(0.0, 1.2, n)
    return r, np.sqrt(r ** 2 + 0.04) - 0.2 + shift * r


def _measured_like(n=200):
    rng = np.random.default_rng(11)
    h = 1.6 / (n - 1)
    r = np.linspace(0.0, 1.6, n) + np.concatenate([[0.0], rng.uniform(-0.25, 0.25, n - 2) * h, [0.0]])
    return r, 0.3 * r ** 2 + 0.05 * r + 1e-4 * np.cumsum(rng.random(n))


# -- the cache ----------------------------------------------------------------------------------------

def test_a_cached_call_returns_bit_identical_values():
    r, f = _hyperboloid(150, shift=0.0123)
    x = np.linspace(0.0, 1.2, 997)
    SETUP.clear()
    first = AP.Tabulated(tuple(r), tuple(f))
    built = SETUP.builds
    v1 = (first.dg(x), first.d2g(x))
    assert SETUP.builds > built                      # the table (and its far field) were built
    again = AP.Tabulated(tuple(r), tuple(f))          # a new object with the same samples
    builds = SETUP.builds
    v2 = (again.dg(x), again.d2g(x))
    assert SETUP.builds == builds                     # nothing rebuilt
    for a, b in zip(v1, v2):
        assert np.array_equal(a, b)
    rec = {"scenario": "axisymmetric", "parameters": {"profile": "tabulated", "profile_r": r.tolist(),
           "profile_f": f.tolist(), "nu": 0.3, "mu": 0.3, "ux0": 0.2, "y": 0.0, "x": [0.0, 0.3, 0.95, 1.5]},
           "output": {"variables": ["sigma_xx", "sigma_zz", "dpdz"]}}
    one, two = sf.generate(rec).compute(), sf.generate(rec).compute()
    for name in ("sigma_xx", "sigma_zz", "dpdz"):
        assert np.array_equal(one[name].values, two[name].values, equal_nan=True)


def test_profiles_that_differ_never_share_an_entry():
    r, f = _hyperboloid(60)
    g = f.copy()
    g[30] = np.nextafter(g[30], np.inf)               # one ulp in one sample
    a, b = AP.Tabulated(tuple(r), tuple(f)), AP.Tabulated(tuple(r), tuple(g))
    assert a._key != b._key
    a.dg(0.5), b.dg(0.5)
    assert a._table is not b._table
    # the spline changes, and so do the values (the table was not shared)
    x = np.linspace(0.5, 1.2, 50)
    assert not np.array_equal(a.d2g(x), b.d2g(x))
    # a table that is a prefix of another, and the graded profile objects of both
    assert content_key(r[:59], f[:59]) != content_key(r, f)
    assert Indenter.tabulated(r, f).table is Indenter.tabulated(r.copy(), f.copy()).table
    assert Indenter.tabulated(r, f).table is not Indenter.tabulated(r, g).table
    # the graded set-up lives on its own object: a clamped slope is another profile
    assert GP.Tabulated(r, f)._setup is not GP.Tabulated(r, f, slope_at_0=0.0)._setup


def test_one_build_per_key_across_threads():
    cache = SetupCache(max_entries=8, max_bytes=1 << 20)
    calls = []
    gate = threading.Barrier(8)

    def build():
        calls.append(1)
        return np.arange(10.0)

    results = []

    def ask(key):
        gate.wait()
        results.append(cache.get(key, build))

    threads = [threading.Thread(target=ask, args=(("k", i % 2),)) for i in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(calls) == 2 and len(results) == 8      # two keys, two builds, every caller answered
    # a failing build is not stored and raises for its caller; the next caller builds again
    with pytest.raises(RuntimeError):
        cache.get("bad", lambda: (_ for _ in ()).throw(RuntimeError("boom")))
    assert cache.get("bad", lambda: 1) == 1


def test_the_cache_is_bounded():
    cache = SetupCache(max_entries=3, max_bytes=1000)
    for i in range(5):
        cache.get(i, lambda: np.zeros(10))             # 80 bytes each
    assert len(cache) == 3
    cache.get("big", lambda: np.zeros(100))            # 800 bytes: the oldest go
    assert cache._bytes <= 1000 and len(cache) <= 3
    cache.get("huge", lambda: np.zeros(1000))          # larger than the bound: returned, not kept
    assert "huge" not in cache._items


# -- the table from the fast sums against the exact sums ----------------------------------------------

@pytest.mark.parametrize("shape", ["uniform", "measured_like"])
def test_fast_table_against_the_exact_sums(shape, monkeypatch):
    """Within 64 ulps of max |g'| (max |g''|) of the exact sums (A103) at points spread over the
    table and next to every knot; the table built from the exact sums is held to its own 8 ulps
    target (plus their rounding) by tests/physics/test_axisymmetric_tabulated_abel_sums.py.  Measured: 17-34 ulps."""
    r, f = _hyperboloid(200) if shape == "uniform" else _measured_like()
    knots = r[1:-1]
    x = np.sort(np.concatenate([np.linspace(1e-3, r[-1], 701), knots * (1 + 1e-9), knots * (1 - 1e-9)]))
    fast = AP.Tabulated(tuple(r), tuple(f))
    ref1, ref2 = fast._sums(x, 1), fast._sums(x, 2)
    s1, s2 = np.max(np.abs(ref1)), np.max(np.abs(ref2))
    raw = fast._fast_sums(x, False)
    assert np.max(np.abs(raw[0] - ref1)) <= 64 * EPS * s1
    assert np.max(np.abs(raw[1] - ref2)) <= 64 * EPS * s2
    assert np.max(np.abs(fast.dg(x) - ref1)) <= 64 * EPS * s1
    assert np.max(np.abs(fast.d2g(x) - ref2)) <= 64 * EPS * s2
    # the table of the exact sums (the former set-up) agrees with it to the same bound
    monkeypatch.setattr(AP, "_FAST_SUMS", False)
    exact = AP.Tabulated(tuple(r), tuple(f))           # its table: from the exact sums (another cache key)
    assert np.max(np.abs(exact.dg(x) - fast.dg(x))) <= 64 * EPS * s1


# -- 1e4 samples ---------------------------------------------------------------------------------------

@pytest.mark.slow          # ~2 s: CI runs it with the slow tests
def test_ten_thousand_samples_are_accepted_and_agree_with_the_closed_form():
    """A paraboloid f = r^2/(2R) sampled at 1e4 radii is its own spline up to rounding: the surface
    stresses of the tabulated route meet the Hertz closed form (A5) within rtol max(p_m, |value|)."""
    R, rtol = 0.7, 1e-10            # the recipe check's rtol: one block tree serves both
    r = np.linspace(0.0, 1.3, 10000)
    a = 1.0
    prof, ref = ax.tabulated(r, r ** 2 / (2 * R)), ax.paraboloid(R)
    x = np.array([0.0, 0.31, 0.77, 0.999, 1.001, 1.6])
    y = np.zeros_like(x)
    got = ax.surface_stress(x, y, a, a, 0.3, 0.0, prof, method="quadrature", rtol=rtol)
    want = ax.surface_stress(x, y, a, a, 0.3, 0.0, ref, method="closed")
    pm = float(ax.mean_pressure(a, ref))
    for k in want:
        err = np.abs(got[k] - want[k]) / np.maximum(pm, np.abs(want[k]))
        assert err.max() <= rtol, (k, err.max())
    # the recipes take 1e4 samples (and refuse one more, naming the limit)
    for scen, extra in (("axisymmetric", {"nu": 0.3, "y": 0.0, "x": [0.5]}),
                        ("graded_normal", {"E0": 1e9, "contact_radius": 1.0, "rho": [0.5]})):
        params = {"profile": "tabulated", "profile_r": r.tolist(), "profile_f": (r ** 2 / (2 * R)).tolist(), **extra}
        load({"scenario": scen, "parameters": params})                   # every check of the recipe
        long = np.linspace(0.0, 1.3, 10001)
        params.update(profile_r=long.tolist(), profile_f=(long ** 2 / (2 * R)).tolist())
        with pytest.raises(sf.RecipeError, match="at most 10,000"):
            load({"scenario": scen, "parameters": params})
    # a bad graded table is named by its first offending value, not echoed whole
    params.update(profile_f=np.concatenate([r[:5000] ** 2, r[5000:] ** 2 - 1.0]).tolist(), profile_r=r.tolist())
    with pytest.raises(sf.RecipeError) as bad:
        load({"scenario": "graded_normal", "parameters": params})
    assert "profile_f[5000] does not increase" in str(bad.value) and len(str(bad.value)) < 400


# -- graded: stick radius and normal force --------------------------------------------------------------

R_G, C3, K, A_G = 1.7, 0.9, 0.5, 0.6
TERMS = ((2, 1 / (2 * R_G)), (3, C3))


def _moment(c):
    """M(c) = int_0^c g'(x) x^(1+k) dx of g = sum kappa(n, k) A_n x^n (G13), in mpmath."""
    k = mp.mpf(K)
    return sum(n * (mp.mpf(n) / 2 * mp.beta(mp.mpf(n) / 2, (1 + k) / 2)) * mp.mpf(An) * c ** (n + k + 1) / (n + k + 1)
               for n, An in TERMS)


def _stick_reference(F):
    """c/a with M(c) = (1 - F) M(a), by 150 mpmath bisections at 40 digits."""
    with mp.workdps(40):
        total, lo, hi = _moment(mp.mpf(A_G)), mp.mpf(0), mp.mpf(1)
        for _ in range(150):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if _moment(A_G * mid) < (1 - mp.mpf(F)) * total else (lo, mid)
        s = (lo + hi) / 2
        return float(s), float(1 - s)


@pytest.fixture(scope="module")
def graded_cases():
    F = np.array([1e-9, 1e-3, 0.3, 0.5, 0.5 + 1e-7, 0.9, 1 - 1e-9])
    return F, np.array([_stick_reference(x) for x in F])


@pytest.mark.parametrize("samples", [41, pytest.param(10000, marks=pytest.mark.slow)])
def test_graded_stick_radius_against_the_closed_form(samples, graded_cases):
    F, ref = graded_cases
    rt = np.linspace(0.0, 1.0, samples)
    for rtol in ((1e-8,) if samples > 1000 else (1e-4, 1e-6, 1e-10, 1e-12)):
        prof = GP.Tabulated(rt, rt ** 2 / (2 * R_G) + C3 * rt ** 3)
        c = GT.stick_radius_quad(A_G, F, prof, k=K, nu=0.3, E0=1.0, c0=1.0, rtol=rtol) / A_G
        sc, D = GT.slip_width_quad(A_G, F, prof, k=K, rtol=rtol)
        assert np.max(np.abs(c / ref[:, 0] - 1)) <= rtol, rtol
        assert np.max(np.abs(sc / ref[:, 0] - 1)) <= rtol, rtol
        assert np.max(np.abs(D / ref[:, 1] - 1)) <= rtol, rtol
        # F_N = 2 c_N* M(a) / (1 + k) (G16)
        cN = float(GN.c_N_star(K, 0.3, 1.0, 1.0, np.inf, None))
        with mp.workdps(30):
            want = float(2 * cN * _moment(mp.mpf(A_G)) / (1 + K))
        got = GN.normal_force_quad(A_G, prof, k=K, nu=0.3, E0=1.0, c0=1.0, rtol=rtol)
        assert abs(got / want - 1) <= rtol, rtol


def test_graded_stick_radius_work_falls_as_rtol_loosens():
    rt = np.linspace(0.0, 1.0, 300)
    work = []
    for rtol in (1e-12, 1e-8, 1e-4):
        prof = GP.Tabulated(rt, rt ** 2 / (2 * R_G) + C3 * rt ** 3)
        GT.stick_radius_quad(A_G, 0.4, prof, k=K, nu=0.3, E0=1.0, c0=1.0, rtol=rtol)
        work.append(prof.exact_terms + prof.block_terms)
    assert work[0] > work[1] > work[2]
