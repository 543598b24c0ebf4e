"""sf.batches: procedural (inputs, targets) batches, the same bytes for the same (recipe, seed) whatever
the batch size, equal to the dataset route, and right against Hertz's surface pressure."""
import numpy as np
import pytest

import stressfields as sf
from stressfields.recipe import RecipeError

STRESS = ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "sigma_yz"]


def hertz(n=5000, method="sobol", z=(0.0, 3.0), **extra):
    return {"scenario": "parabolic", "parameters": {"nu": 0.3},
            "points": {"sample": {"n": n, "method": method, "seed": 99, "x": [-2.0, 2.0], "y": [-2.0, 2.0],
                                  "z": list(z), **extra}},
            "output": {"variables": STRESS}}


def joined(stream):
    parts = list(stream)
    return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts]), [len(p[0]) for p in parts]


@pytest.mark.parametrize("method", ["sobol", "uniform"])
def test_same_bytes_across_runs_and_batch_sizes(method):
    ref_in, ref_out, sizes = joined(sf.batches(hertz(method=method), 5000, seed=7))
    assert sizes == [5000] and ref_out.shape == (5000, 7)
    for size in (1000, 4096, 333):
        stream = sf.batches(hertz(method=method), size, seed=7)
        x, y, sizes = joined(stream)
        assert sizes == [size] * (5000 // size) + ([5000 % size] if 5000 % size else []) and len(stream) == len(sizes)
        assert x.tobytes() == ref_in.tobytes() and y.tobytes() == ref_out.tobytes()
    again = joined(sf.batches(hertz(method=method), 1000, seed=7))
    assert again[1].tobytes() == ref_out.tobytes()
    other = joined(sf.batches(hertz(method=method), 1000, seed=8))
    assert other[0].tobytes() != ref_in.tobytes()


def test_equal_to_the_dataset_of_the_same_sample():
    """The concatenated batches are the points `[points.sample]` draws with the same seed and the
    values `sf.generate` computes there, bit for bit."""
    stream = sf.batches(hertz(n=3000), 700, seed=5)
    assert stream.input_names == ("x", "y", "z") and stream.target_names == (*STRESS, "validity")
    x, y, _ = joined(stream)
    recipe = hertz(n=3000)
    recipe["points"]["sample"]["seed"] = 5
    ds = sf.generate(recipe).compute()
    for i, name in enumerate(stream.input_names):
        assert x[:, i].tobytes() == ds[name].values.tobytes()
    for j, name in enumerate(stream.target_names):
        assert y[:, j].tobytes() == ds[name].values.astype(float).tobytes(), name


def test_surface_batches_hold_hertz_pressure():
    """z = 0: sigma_zz = -p(r) = -(3/2) p_m sqrt(1 - r^2) inside the contact, 0 outside (closed form here)."""
    stream = sf.batches(hertz(n=2000, method="uniform", z=(0.0, 0.0)), 512, seed=1)
    x, y, _ = joined(stream)
    r = np.hypot(x[:, 0], x[:, 1])
    expect = -1.5 * np.sqrt(np.clip(1 - r ** 2, 0, None))
    np.testing.assert_allclose(y[:, STRESS.index("sigma_zz")], expect, rtol=1e-12, atol=1e-12)
    assert np.all(y[:, -1] == 0)                                   # validity: within the stated accuracy


@pytest.mark.parametrize("change, words", [
    (lambda r: r["points"]["sample"].update(method="lhs"), "Latin hypercube"),
    (lambda r: r.pop("points"), "[points.sample]"),
    (lambda r: r["points"]["sample"].update(n=0), "points.sample.n = 0"),
    (lambda r: r["points"]["sample"].update(z=[-1.0, 1.0]), "points.sample.z"),
])
def test_hostile_inputs_are_refused_naming_the_key(change, words):
    recipe = hertz()
    change(recipe)
    with pytest.raises(RecipeError) as err:
        sf.batches(recipe, 100, seed=0)
    assert len(err.value.problems) == 1 and words in err.value.problems[0]


def test_bad_batch_size_and_seed():
    for size, seed in ((0, 0), (1.5, 0), (10, -1)):
        with pytest.raises(RecipeError):
            sf.batches(hertz(), size, seed)
