"""A sweep split over files: sf.open_mfdataset combines them with every source recipe recorded, and
sf.write refuses a merge that kept the first file's recipe (xarray's default) instead of writing it."""
import numpy as np
import pytest
import xarray as xr

import stressfields as sf
from stressfields.errors import OutputError
from stressfields.output.formats import verify

BASE = {"scenario": "graded_adhesive", "parameters": {"profile": "parabolic", "R": 0.01, "E0": 1e6, "delta_gamma": 0.05,
                                                      "contact_radius": 1e-4},
        "output": {"variables": ["critical_radius", "critical_force"]}}


def _part(k):
    return {**BASE, "parameters": {**BASE["parameters"], "k": k}}


@pytest.fixture(scope="module")
def parts(tmp_path_factory):
    out = tmp_path_factory.mktemp("merge")
    paths = [sf.write(sf.generate(_part(k)), out / f"sweep_{i}.nc") for i, k in enumerate(([0.0, 0.3], [0.6, 0.9]))]
    whole = sf.generate(_part([0.0, 0.3, 0.6, 0.9])).compute()
    return out, paths, whole


def test_open_mfdataset_records_every_source_recipe(parts):
    out, paths, whole = parts
    recipes = []
    for path in paths:
        with xr.open_dataset(path) as one:
            recipes.append(one.attrs["stressfields_recipe_sha256"])
    with sf.open_mfdataset(str(out / "sweep_*.nc")) as ds:
        assert ds.attrs["stressfields_source_recipe_sha256"].split() == recipes and len(set(recipes)) == 2
        assert "stressfields_recipe" not in ds.attrs and "id" not in ds.attrs       # the first file's, dropped
        assert ds.attrs["history"].count("generate") == 2 and "open_mfdataset of 2 files" in ds.attrs["history"]
        assert list(ds.control.values) == ["fixed_load", "fixed_grips"]               # choices by name
        np.testing.assert_array_equal(ds.critical_force.values, whole.critical_force.values)
        merged = sf.write(ds, out / "merged.nc")
    assert verify(merged)
    with xr.open_dataset(merged) as back:
        assert back.attrs["stressfields_source_recipe_sha256"].split() == recipes
        assert back.attrs["title"] and back.attrs["summary"]
    pytest.importorskip("compliance_checker")
    from test_clients import cf_warnings

    assert cf_warnings(merged) == []


def test_write_refuses_a_merge_that_kept_the_first_recipe(parts, tmp_path):
    _, paths, _ = parts
    with xr.open_mfdataset(paths, preprocess=sf.reading.decode_choices) as ds:      # xarray's default attributes
        with pytest.raises(OutputError, match=r"k = 0\.6 is not a value of the recipe .* sf\.open_mfdataset"):
            sf.write(ds, tmp_path / "wrong.nc")
    assert list(tmp_path.iterdir()) == []


def test_a_selection_of_a_recipe_still_writes(tmp_path):
    ds = sf.generate(_part([0.0, 0.3, 0.6]))
    path = sf.write(ds.sel(k=[0.3]), tmp_path / "one.nc")
    with xr.open_dataset(path) as back:
        assert back.k.values.tolist() == [0.3]
