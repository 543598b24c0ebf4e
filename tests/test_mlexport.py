"""ML layouts (`stressfields export FILE -o DIR --layout well|parquet`) and the recipe's [splits]:
stats.yaml against NumPy over the train split, disjoint splits, held-out regions exactly as declared,
the Croissant card, hostile split specifications."""
import json
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest
import yaml

import stressfields as sf
from stressfields.errors import OutputError
from stressfields.mlexport import export_layout
from stressfields.recipe import RecipeError, load

ROOT = Path(__file__).resolve().parents[1]
FIELDS = ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "sigma_yz", "u_x", "u_y", "u_z", "von_mises",
          "stick_radius"]


def recipe(splits, **parameters):
    return {"scenario": "parabolic",
            "parameters": {"nu": [0.2, 0.3, 0.45], "mu": 0.3, "fx": 0.5, "y": 0.0,
                           "z": {"start": 0.0, "stop": 1.0, "num": 6}, "x": {"start": -1.5, "stop": 1.5, "num": 31},
                           **parameters},
            "output": {"variables": FIELDS}, "splits": splits}


def written(tmp_path, spec, name="r.nc", **parameters):
    path = tmp_path / name
    sf.write(sf.generate(recipe(spec, **parameters)), path)
    return path


def read_split(folder, split, name="r"):
    with h5py.File(folder / "data" / split / f"{name}.hdf5") as f:
        inputs = {k: f["inputs"][k][()] for k in f["inputs"]}
        fields = {k: f[f"t{r}_fields"][k][()] for r in (0, 1, 2) for k in f[f"t{r}_fields"]}
    return inputs, fields


@pytest.fixture(scope="module")
def well(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("well")
    spec = {"seed": 3, "valid": {"fraction": 0.1}, "test": {"parameter": {"nu": [0.4, 0.5]}}}
    out = export_layout(written(tmp, spec), tmp / "W", "well")
    return out, tmp / "r.nc"


def test_stats_equal_numpy_over_train(well):
    folder = well[0]
    stats = yaml.safe_load((folder / "stats.yaml").read_text())
    _, fields = read_split(folder, "train")
    assert set(stats["mean"]) == {"sigma", "u", "von_mises", "stick_radius"}
    for name, values in fields.items():
        flat = values.reshape(values.shape[0], -1)
        mean = np.ravel(stats["mean"][name])
        std = np.ravel(stats["std"][name])
        for i in range(flat.shape[1]):
            x = flat[:, i][np.isfinite(flat[:, i])]
            np.testing.assert_allclose(mean[i], x.mean(), rtol=1e-15, atol=0)
            np.testing.assert_allclose(std[i], x.std(), rtol=1e-15, atol=0)


def test_tensor_orders_and_symmetric_stress(well):
    folder = well[0]
    meta = yaml.safe_load((folder / "r.yaml").read_text())
    assert meta["field_names"] == {0: ["von_mises", "stick_radius"], 1: ["u"], 2: ["sigma"]}
    assert "nu" in meta["constant_scalar_names"] and meta["constant_scalars"]["mu"] == 0.3
    _, fields = read_split(folder, "train")
    sigma = fields["sigma"]
    assert sigma.shape[1:] == (3, 3) and fields["u"].shape[1:] == (3,)
    assert np.array_equal(sigma, np.swapaxes(sigma, 1, 2))
    import xarray as xr

    inputs, _ = read_split(folder, "train")
    with xr.open_dataset(well[1]) as ds:        # each component sits where its name says
        at = {d: np.searchsorted(ds[d].values, inputs[d]) for d in ("nu", "z", "x")}
        for (i, j), name in np.ndenumerate(np.array(meta["field_components"]["sigma"])):
            assert np.array_equal(sigma[:, i, j], ds[name].values[at["nu"], at["z"], at["x"]]), name
        for i, name in enumerate(meta["field_components"]["u"]):
            assert np.array_equal(fields["u"][:, i], ds[name].values[at["nu"], at["z"], at["x"]]), name


def test_no_test_point_in_train_and_the_extrapolation_split_is_exactly_the_declared_range(well):
    folder = well[0]
    keys = {}
    for split in ("train", "valid", "test"):
        inputs, _ = read_split(folder, split)
        keys[split] = set(zip(*(inputs[k] for k in ("nu", "z", "x"))))
    assert not keys["test"] & keys["train"] and not keys["valid"] & keys["train"] and not keys["test"] & keys["valid"]
    nu = np.array([0.2, 0.3, 0.45])
    held = {(n, z, x) for n in nu[(nu >= 0.4) & (nu <= 0.5)] for z in np.linspace(0, 1, 6)
            for x in np.linspace(-1.5, 1.5, 31)}
    assert keys["test"] == held
    assert len(keys["valid"]) == round(0.1 * 3 * 6 * 31)
    assert sum(map(len, keys.values())) == 3 * 6 * 31


def test_region_hold_out_is_the_band_around_the_contact_and_stick_edges(tmp_path):
    spec = {"seed": 1, "valid": {"region": "stick_edge", "width": 0.1},
            "test": {"region": "contact_edge", "width": 0.15}}
    folder = export_layout(written(tmp_path, spec, nu=0.3), tmp_path / "W", "well")
    c = (1 - 0.5) ** (1 / 3)                      # Cattaneo-Mindlin: (c/a)^3 = 1 - F_x/(mu F_N)
    for split in ("train", "valid", "test"):
        inputs, fields = read_split(folder, split)
        r, z = np.abs(inputs["x"]), inputs["z"]
        to_edge, to_stick = np.hypot(r - 1, z), np.hypot(r - c, z)
        if split == "test":
            assert np.all(to_edge <= 0.15) and len(r) > 0
        elif split == "valid":
            assert np.all(to_stick <= 0.1) and np.all(to_edge > 0.15) and len(r) > 0
            np.testing.assert_allclose(fields["stick_radius"], c, rtol=1e-14)
        else:
            assert np.all(to_edge > 0.15) and np.all(to_stick > 0.1)


def test_cone_tip_hold_out(tmp_path):
    path = tmp_path / "cone.nc"
    sf.write(sf.generate({"scenario": "conical", "parameters": {"nu": 0.3, "y": 0.0,
                                                                "z": {"start": 0.0, "stop": 1.0, "num": 11},
                                                                "x": {"start": -1.0, "stop": 1.0, "num": 21}},
                          "output": {"variables": ["sigma_zz", "tau_max"]},
                          "splits": {"test": {"region": "tip", "width": 0.25}}}), path)
    folder = export_layout(path, tmp_path / "W", "well", overwrite=False)
    test_inputs, test_fields = read_split(folder, "test", "cone")
    train_inputs, train_fields = read_split(folder, "train", "cone")
    assert np.all(np.hypot(test_inputs["x"], test_inputs["z"]) <= 0.25)
    assert np.all(np.hypot(train_inputs["x"], train_inputs["z"]) > 0.25)
    assert not np.isfinite(test_fields["sigma_zz"]).all()        # the singular tip is held out
    assert np.isfinite(train_fields["sigma_zz"]).all()


def test_parquet_one_row_per_point_and_the_croissant_card(tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")
    spec = {"seed": 2, "valid": {"fraction": 0.2}, "test": {"fraction": 0.2}}
    source = written(tmp_path, spec, nu=0.3)
    folder = export_layout(source, tmp_path / "P", "parquet")
    rows = {s: pq.read_table(folder / f"{s}.parquet").to_pandas() for s in ("train", "valid", "test")}
    assert sum(map(len, rows.values())) == 6 * 31
    assert len(rows["valid"]) == len(rows["test"]) == round(0.2 * 6 * 31)
    assert {"x", "z", "sigma_xx", "sigma_xz", "u_z", "validity"} <= set(rows["train"].columns)
    card = json.loads((folder / "croissant.json").read_text())
    assert card["conformsTo"] == "http://mlcommons.org/croissant/1.0"
    assert "Closed forms" in card["description"] and "rtol" in card["description"]
    assert {r["name"] for r in card["recordSet"]} == {"train", "valid", "test"}
    import hashlib

    for item in card["distribution"]:
        assert hashlib.sha256((folder / item["contentUrl"]).read_bytes()).hexdigest() == item["sha256"]
    mlc = pytest.importorskip("mlcroissant")
    dataset = mlc.Dataset(jsonld=folder / "croissant.json")
    assert len(list(dataset.records("test"))) == len(rows["test"])


def test_splits_are_part_of_the_recipe_hash():
    a = load(recipe({"seed": 1, "test": {"fraction": 0.1}}))
    b = load(recipe({"seed": 2, "test": {"fraction": 0.1}}))
    plain = dict(recipe({}))
    del plain["splits"]
    assert a.sha256 != b.sha256 != load(plain).sha256
    assert "splits" not in load(plain).canonical


@pytest.mark.parametrize("spec, words", [
    ({"seed": 1, "valid": {"fraction": 0.6}, "test": {"fraction": 0.5}},
     ["add up to 1.1", "train split would be empty"]),
    ({"test": {"parameter": {"nu": [0.0, 0.5]}}}, ["splits.test.parameter.nu", "every value of nu", "empty"]),
    ({"valid": {"parameter": {"nu": [0.25, 0.35]}}, "test": {"parameter": {"nu": [0.3, 0.5]}}},
     ["overlap", "nu in [0.3, 0.35]"]),
    ({"test": {"parameter": {"youngs": [0.0, 1.0]}}}, ["unknown parameter 'youngs'", "one of: nu"]),
    ({"test": {"fraction": 0.1}}, ["splits.test.fraction needs splits.seed"]),
    ({"test": {"region": "rim", "width": 0.1}}, ["splits.test.region = 'rim'", "contact_edge"]),
    ({"train": {"fraction": 0.5}}, ["unknown key 'splits.train'"]),
])
def test_hostile_splits_are_refused_naming_the_key(spec, words):
    with pytest.raises(RecipeError) as err:
        load(recipe(spec))
    assert len(err.value.problems) == 1
    for w in words:
        assert w in err.value.problems[0], err.value.problems[0]


def test_hostile_splits_from_the_command_line_exit_2_writing_nothing(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('scenario = "parabolic"\n[parameters]\nnu = [0.2, 0.3]\nx = [0.0, 0.5]\n'
                   '[splits]\ntest = { parameter = { nu = [0.1, 0.4] } }\n')
    done = subprocess.run([sys.executable, "-m", "stressfields", "run", str(bad), "-o", str(tmp_path / "o.nc")],
                          capture_output=True, text=True, cwd=ROOT, timeout=60)
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert [line for line in done.stderr.splitlines() if line.startswith("  - ")] == [
        "  - splits.test.parameter.nu = [0.1, 0.4] holds out every value of nu (0.2, 0.3); the train split would "
        "be empty"]
    assert not (tmp_path / "o.nc").exists()


def test_export_refusals_are_one_line(tmp_path, well):
    no_splits = tmp_path / "plain.nc"
    sf.write(sf.generate({"scenario": "parabolic", "parameters": {"x": [0.0, 0.5]}}), no_splits)
    with pytest.raises(OutputError, match=r"no \[splits\] table"):
        export_layout(no_splits, tmp_path / "X", "well")
    # held-out sets that overlap only in the data (two parameters) are found when the points are assigned
    spec = {"valid": {"parameter": {"nu": [0.25, 0.5]}}, "test": {"parameter": {"z": [0.0, 0.5]}}}
    with pytest.raises(OutputError, match="overlap at"):
        export_layout(written(tmp_path, spec, name="o.nc"), tmp_path / "Y", "well")
    done = subprocess.run([sys.executable, "-m", "stressfields", "export", str(well[1]), "-o", str(well[0]),
                           "--layout", "well"], capture_output=True, text=True, cwd=ROOT, timeout=60)
    assert done.returncode == 2 and done.stderr.strip().count("\n") == 0 and "--overwrite" in done.stderr
    assert not (tmp_path / "X").exists() and not (tmp_path / "Y").exists()
