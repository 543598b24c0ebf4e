"""A point's values do not depend on which other points share the array.

The content hash of a file is the same however the sweep is chunked only if every value is: each
wavy quantity evaluated on a random subset (and permutation) of the contact widths, harmonic counts
and points, single ones included, must be bit-identical to the same entries of the full evaluation;
and through the scenario, one chunk, chunks along a and chunks along x give identical datasets,
also where method auto substitutes the non-periodic series (decided from the whole sweep).
"""
import importlib

import numpy as np
import pytest
import xarray as xr

import stressfields as sf
from stressfields.physics import wavy
from stressfields.physics.flags import Validity
from stressfields.physics.wavy import contact

F3 = {"amplitudes": [0.5, 0.01, 0.00075], "wavenumbers": [1, 11, 40]}
# narrow to nearly closed contacts, both sides of where the periodic correction matters
A = np.array([1e-5, 1e-4, 3e-3, 0.05, 0.2, 0.5, 0.8, 0.95])
N = np.array([1, 2, 3])
X = np.concatenate([np.linspace(-1.3, 1.3, 41), [-1.0, 1.0, 0.999999, 7.0, -250.0]])
SHAPE = (A.size, N.size, X.size)
_FIELDS = importlib.import_module("stressfields.physics.wavy.fields")     # the module, not its function
SURFACE = _FIELDS.POINTWISE + _FIELDS.PER_CASE


def _fields(ia, iN, ix, periodic, rtol):
    # the surface fields (the field below the surface has its own chunk test in test_wavy_interior.py)
    out = wavy.fields(SURFACE, X[ix][None, None, :], A[ia][:, None, None], **F3, periodic=periodic,
                      n_harmonics=N[iN][None, :, None], rtol=rtol)
    return {k: np.broadcast_to(v, (len(ia), len(iN), len(ix))) for k, v in out.items()}


@pytest.fixture(scope="module", params=[(True, 1e-12), (False, 1e-12), (False, 1e-6)],
                ids=["periodic", "nonperiodic", "nonperiodic-1e-6"])
def full(request):
    periodic, rtol = request.param
    every = [np.arange(n) for n in SHAPE]
    return periodic, rtol, _fields(*every, periodic, rtol)


def _assert_same(full, part, ia, iN, ix):
    for name, value in part.items():
        expected = full[name][np.ix_(ia, iN, ix)]
        assert np.array_equal(value, expected, equal_nan=True), name
        # bit for bit (+0 and -0 alike would compare equal above)
        assert np.array_equal(np.signbit(value), np.signbit(expected)), name


@pytest.mark.parametrize("seed", range(6))
def test_random_subsets_and_permutations_are_bit_identical(full, seed):
    periodic, rtol, values = full
    rng = np.random.default_rng(seed)
    ia, iN, ix = (rng.permutation(n)[: rng.integers(1, n + 1)] for n in SHAPE)
    _assert_same(values, _fields(ia, iN, ix, periodic, rtol), ia, iN, ix)


def test_single_entries_are_bit_identical(full):
    periodic, rtol, values = full
    for ia in range(A.size):
        for ix in (0, 20, 41, 43, 45):
            _assert_same(values, _fields([ia], [2], [ix], periodic, rtol), [ia], [2], [ix])


def test_kernels_with_their_own_tables_are_bit_identical():
    """The per-contact kernels outside ``fields``: validity details, the shape of p, the gap."""
    kw = dict(**F3, n_harmonics=3, rtol=1e-12)
    for periodic in (True, False):
        whole = contact.contact_validity(A, periodic=periodic, **kw)
        shape_whole = contact.pressure_shape(np.array([0.0, 0.5, 1.0])[:, None], A[None, :], periodic=periodic, **kw)
        gap_whole = contact.separation(np.array([1.5, 3.0])[:, None], A[None, :], periodic=periodic, **kw)[0]
        for j in (0, 3, 7):
            one = contact.contact_validity(A[j], periodic=periodic, **kw)
            for key, value in one.items():
                assert np.array_equal(value, whole[key][j], equal_nan=True), key
            phi = contact.pressure_shape(np.array([0.0, 0.5, 1.0]), A[j], periodic=periodic, **kw)
            assert np.array_equal(phi[0], shape_whole[0][:, j])
            assert np.array_equal(phi[1]["error_estimate"], shape_whole[1]["error_estimate"][:, j])
            gap = contact.separation(np.array([1.5, 3.0]), A[j], periodic=periodic, **kw)[0]
            assert np.array_equal(gap, gap_whole[:, j])
    bound = contact.periodic_correction(A[:6], **kw)[0]
    assert np.array_equal([contact.periodic_correction(a, **kw)[0] for a in A[:6]], bound)


def test_contact_points_decide_the_substitution_not_the_call():
    """Given the count over the whole evaluation, a call with few points substitutes like a call
    with all of them (the default, counting the call's own points, would not)."""
    x = np.linspace(-1.0, 1.0, 7)
    p, info = wavy.pressure(x, 1e-4, **F3, periodic=True, rtol=1e-6, substitute=True,
                            contact_points=contact.SUBSTITUTE_MIN_POINTS)
    assert info["substituted"].all()
    np.testing.assert_array_equal(p, wavy.pressure(x, 1e-4, **F3, periodic=False, rtol=1e-6)[0])
    assert not wavy.pressure(x, 1e-4, **F3, periodic=True, rtol=1e-6, substitute=True)[1]["substituted"].any()


def _recipe(method, num):
    params = {"domain": ["periodic", "nonperiodic"], **F3, "n_harmonics": [1, 3],
              "a": [1e-4, 1e-3, 0.05, 0.5, 0.9], "x": {"start": -1.2, "stop": 1.2, "num": num}}
    return {"scenario": "wavy", "parameters": params, "method": {"method": method, "rtol": 1e-6}}


@pytest.mark.slow          # ~2 s a method: CI runs it with the slow tests
@pytest.mark.parametrize("method", ["auto", "series"])
def test_scenario_values_do_not_depend_on_the_chunking(method):
    recipe = _recipe(method, 61)
    whole = _computed(recipe, {"a": -1, "x": -1, "n_harmonics": -1, "domain": -1})
    for chunks in ({"a": 2}, {"x": 7}, {"a": 1, "x": 5, "n_harmonics": 1}):
        xr.testing.assert_identical(_computed(recipe, chunks), whole)


@pytest.mark.slow   # ~4.5 s; the normalised chunk tests stay
def test_physical_and_scattered_points_do_not_depend_on_the_chunking():
    """Physical units (x in metres: the contact is |x| <= a lambda_1/2) and a [points] table."""
    physical = {"scenario": "wavy", "method": {"rtol": 1e-8},
                "parameters": {"domain": "periodic", **F3, "E": 2e11, "nu": 0.3, "lambda_1": 1e-3,
                               "a": [1e-4, 0.05, 0.5], "x": {"start": -3e-4, "stop": 3e-4, "num": 41}}}
    whole = _computed(physical, {"a": -1, "x": -1})
    for chunks in ({"a": 1}, {"x": 6}):
        xr.testing.assert_identical(_computed(physical, chunks), whole)
    rng = np.random.default_rng(5)
    scattered = {"scenario": "wavy", "method": {"rtol": 1e-8},
                 "parameters": {"domain": ["periodic", "nonperiodic"], **F3},
                 "points": {"a": rng.uniform(1e-3, 0.9, 40).tolist(), "x": rng.uniform(-1.5, 1.5, 40).tolist()}}
    whole = _computed(scattered, {"point": -1})
    for chunks in ({"point": 7}, {"point": 1, "domain": 1}):
        xr.testing.assert_identical(_computed(scattered, chunks), whole)


def _computed(recipe, chunks):
    ds = sf.generate(recipe, chunks=chunks).compute()
    for when in ("history", "date_created"):      # when it was made
        del ds.attrs[when]
    return ds


def test_a_substituting_recipe_hashes_alike_however_chunked():
    """The case of test_scenario_wavy: 1e5 points per contact, where auto substitutes."""
    from stressfields.output import hashing

    recipe = _recipe("auto", contact.SUBSTITUTE_MIN_POINTS + 1)
    recipe["parameters"].update(a=[1e-4, 0.3], n_harmonics=3,
                                x={"start": -1.0, "stop": 1.0, "num": contact.SUBSTITUTE_MIN_POINTS + 1})
    recipe["output"] = {"variables": ["pressure"]}
    hashes = set()
    for chunks in ({"x": -1, "a": -1}, {"x": 30_000}, {"a": 1, "x": 77_777}):
        ds = sf.generate(recipe, chunks=chunks).compute()
        assert (ds.validity.sel(domain="periodic", a=1e-4) == Validity.nonperiodic_series_within_rtol).all()
        assert not (ds.validity.sel(domain="periodic", a=0.3) == Validity.nonperiodic_series_within_rtol).any()
        hashes.add(hashing.content_hash(ds))
    assert len(hashes) == 1
