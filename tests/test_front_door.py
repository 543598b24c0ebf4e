"""The front door: a run is decided in one place (`api.plan`/`api.run`), and a dataset of
`sf.generate` carries its recipe's [output] options, so the API and the command line store the same."""
import tomllib

import netCDF4
import numpy as np
import pytest

import stressfields as sf
from stressfields import api, cli
from stressfields.output.formats import file_hash
from stressfields.output.options import FILL_VALUES, OPTIONS_ATTR

STORED = """scenario = "conical"
[parameters]
mu = [0.0, 0.3]
x = { start = -1.5, stop = 1.5, num = 41 }
y = 0.0
[output]
variables = ["sigma_xx", "von_mises", "validity"]
chunks = { mu = 1 }
dtype = "float32"
compression = 4
"""


@pytest.fixture
def recipe(tmp_path):
    path = tmp_path / "stored.toml"
    path.write_text(STORED)
    return path


def _filters(path, name):
    with netCDF4.Dataset(path) as nc:
        return nc[name].dtype, nc[name].filters()


def test_the_api_and_the_command_line_store_what_the_recipe_asks(recipe, tmp_path):
    by_api = sf.write(sf.generate(recipe), tmp_path / "api.nc")
    assert cli.main(["run", str(recipe), "-o", str(tmp_path / "cli.nc"), "-q"]) == 0
    by_run = sf.run(recipe, tmp_path / "run.nc")
    digest, stored = file_hash(by_api)
    assert digest == stored
    assert file_hash(tmp_path / "cli.nc") == (digest, digest) == file_hash(by_run)
    dtype, filters = _filters(by_api, "sigma_xx")
    assert dtype == np.float32 and filters["zlib"] and filters["complevel"] == 4
    with netCDF4.Dataset(by_api) as nc:
        assert nc.getncattr(OPTIONS_ATTR) == "dtype=float32; compression=4; nonfinite=keep"


def test_what_the_caller_gives_overrides_what_the_dataset_carries(recipe, tmp_path):
    ds = sf.generate(recipe)
    assert ds.encoding[OPTIONS_ATTR] == {"dtype": "float32", "compression": 4}
    plain = sf.write(ds, tmp_path / "plain.nc", dtype="float64", compression=0)
    dtype, filters = _filters(plain, "sigma_xx")
    assert dtype == np.float64 and not filters["zlib"]
    assert cli.main(["run", str(recipe), "-o", str(tmp_path / "cli.nc"), "-q", "--dtype", "float64",
                     "--compression", "0"]) == 0
    assert file_hash(tmp_path / "cli.nc")[0] == file_hash(plain)[0]
    # a dataset without carried options (not made by generate) is written with the defaults
    bare = ds.copy()
    bare.encoding = {}
    assert _filters(sf.write(bare, tmp_path / "bare.nc"), "sigma_xx")[0] == np.float64


def test_a_recipe_without_output_options_is_written_as_before(tmp_path):
    recipe = STORED.replace('dtype = "float32"\ncompression = 4\n', "")
    ds = sf.generate(tomllib.loads(recipe))
    assert ds.encoding[OPTIONS_ATTR] == {}
    dtype, filters = _filters(sf.write(ds, tmp_path / "d.nc"), "sigma_xx")
    assert dtype == np.float64 and not filters["zlib"]


def test_the_parts_policy_is_the_front_doors(recipe, tmp_path, monkeypatch):
    assert not api.plan(recipe, tmp_path / "a.nc").parts
    monkeypatch.setattr(api, "PARTS_ABOVE", 10)         # 82 points: above it
    assert api.plan(recipe, tmp_path / "a.nc").parts
    assert not api.plan(recipe, tmp_path / "a.zarr").parts      # Zarr is not written in parts
    written = api.run(recipe, tmp_path / "a.nc")
    assert file_hash(written)[0] == file_hash(sf.write(sf.generate(recipe), tmp_path / "b.nc"))[0]
    assert not (tmp_path / "a.nc.parts").exists()


def test_the_front_door_checks_everything_before_any_work(recipe, tmp_path):
    (tmp_path / "taken.nc").write_text("x")
    with pytest.raises(sf.OutputError, match="exists"):
        api.plan(recipe, tmp_path / "taken.nc")
    with pytest.raises(sf.RecipeError, match="'q' is not a swept dimension|q is not a swept dimension"):
        api.plan(recipe, tmp_path / "new.nc", chunks={"q": 2})
    with pytest.raises(sf.OutputError, match="dtype = 'float16'"):
        api.plan(recipe, tmp_path / "new.nc", dtype="float16")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["stored.toml", "taken.nc"]
    # a dry run checks no target
    assert api.plan(recipe, tmp_path / "taken.nc", check_target=False).target.name == "taken.nc"


def test_the_fill_values_are_netcdfs_defaults():
    assert FILL_VALUES == {4: netCDF4.default_fillvals["f4"], 8: netCDF4.default_fillvals["f8"]}
    assert np.float32(FILL_VALUES[4]) == np.float32(netCDF4.default_fillvals["f4"])
