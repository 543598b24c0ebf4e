"""[points] from a file (CSV, .npy, .npz, NetCDF), from a seeded sample, and from a DataFrame or Dataset.

Each source gives the dataset of the same columns written inline, bit for bit; a sample is checked
against the defining properties of its method (the box, Latin-hypercube strata, Sobol net balance),
and hostile files are refused in one message naming the file, before anything large is read.
"""
import hashlib
import json
import os
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import stressfields as sf
from stressfields import pointfiles
from stressfields.recipe import MAX_SWEEP, RecipeError, draw_sample, load

CONE = {"scenario": "conical", "parameters": {"nu": 0.3, "ux0": 0.25}}
RNG = np.random.default_rng(11)
#: full-precision values (repr round-trips): a CSV must give back the same doubles
COLS = {"x": RNG.uniform(-2, 2, 7), "y": RNG.uniform(-2, 2, 7), "mu": RNG.uniform(0, 1, 7)}
COLS["x"][3] = 0.0              # the cone's axis and a repeated point
COLS["y"][3] = 0.0
COLS["x"][5], COLS["y"][5], COLS["mu"][5] = COLS["x"][1], COLS["y"][1], COLS["mu"][1]


@pytest.fixture(autouse=True)
def _in_tmp_path(tmp_path, monkeypatch):
    """The files these tests write lie in the working directory: a dict recipe's folder (the read policy)."""
    monkeypatch.chdir(tmp_path)


def problems(data) -> str:
    with pytest.raises(RecipeError) as info:
        load(data)
    return " | ".join(info.value.problems)


def write_csv(path: Path, cols: dict, comment: bool = True) -> Path:
    names = list(cols)
    lines = (["# nodes of a test mesh", "# units: 1"] if comment else []) + [",".join(names)]
    lines += [",".join(repr(float(cols[n][i])) for n in names) for i in range(len(cols[names[0]]))]
    path.write_text("\n".join(lines) + "\n")
    return path


def write_npy(path: Path, cols: dict) -> Path:
    np.save(path, np.rec.fromarrays(list(cols.values()), names=list(cols)))
    return path


def write_npz(path: Path, cols: dict) -> Path:
    np.savez_compressed(path, **cols)
    return path


def write_nc(path: Path, cols: dict) -> Path:
    xr.Dataset({k: ("node", v) for k, v in cols.items()}).to_netcdf(path)
    return path


WRITERS = {"csv": write_csv, "npy": write_npy, "npz": write_npz, "nc": write_nc}


def same(a: xr.Dataset, b: xr.Dataset) -> None:
    """Bit-identical data and coordinates (the recipe attributes differ: the file is recorded)."""
    xr.testing.assert_identical(a.drop_attrs(), b.drop_attrs())
    for name in a.variables:
        np.testing.assert_array_equal(a[name].values, b[name].values, err_msg=name)


# -- files ---------------------------------------------------------------------------------------

@pytest.mark.parametrize("kind", list(WRITERS))
def test_every_file_type_gives_the_inline_dataset(tmp_path, kind):
    path = WRITERS[kind](tmp_path / f"nodes.{kind}", COLS)
    inline = sf.generate({**CONE, "points": COLS}).compute()
    from_file = sf.generate({**CONE, "points": {"file": str(path)}}).compute()
    same(from_file, inline)
    for name, values in COLS.items():
        assert from_file[name].dims == ("point",)
        np.testing.assert_array_equal(from_file[name].values, values)
    canon = json.loads(load({**CONE, "points": {"file": str(path)}}).canonical)["points"]
    assert canon["file"] == str(path)
    assert canon["file_sha256"] == hashlib.sha256(path.read_bytes()).hexdigest()
    assert canon["sha256"] == json.loads(load({**CONE, "points": COLS}).canonical)["points"]["sha256"]  # the columns


def test_relative_path_is_the_recipes_directory(tmp_path, monkeypatch):
    sub = tmp_path / "mesh"
    sub.mkdir()
    write_csv(sub / "nodes.csv", COLS)
    toml = sub / "r.toml"
    toml.write_text('scenario = "conical"\n[parameters]\nnu = 0.3\nux0 = 0.25\n[points]\nfile = "nodes.csv"\n')
    elsewhere = tmp_path / "work"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    r = load(toml)
    np.testing.assert_array_equal(r.values["x"], COLS["x"])
    assert json.loads(r.canonical)["points"]["file"] == "nodes.csv"
    # a dict recipe: relative to the working directory; an absolute path from anywhere
    assert "cannot read" in problems({**CONE, "points": {"file": "nodes.csv"}})
    monkeypatch.chdir(sub)
    assert load({**CONE, "points": {"file": "nodes.csv"}}).values["x"].tolist() == COLS["x"].tolist()
    # an absolute path inside the recipe's folder is read; one outside it only when allowed
    absolute = toml.with_name("abs.toml")
    absolute.write_text(toml.read_text().replace('"nodes.csv"', json.dumps(str(sub / "nodes.csv"))))
    monkeypatch.chdir(tmp_path)
    np.testing.assert_array_equal(load(absolute).values["y"], COLS["y"])
    outside = elsewhere / "r.toml"
    outside.write_text(absolute.read_text())
    assert "outside the recipe's folder" in " ".join(pytest.raises(RecipeError, load, outside).value.problems)
    np.testing.assert_array_equal(load(outside, allow_read=[sub]).values["y"], COLS["y"])


def test_recipe_hash_follows_the_file_content(tmp_path):
    path = write_csv(tmp_path / "nodes.csv", COLS)
    first = load({**CONE, "points": {"file": str(path)}})
    again = load({**CONE, "points": {"file": str(path)}})
    assert first.sha256 == again.sha256
    changed = {**COLS, "mu": COLS["mu"].copy()}
    changed["mu"][2] = np.nextafter(changed["mu"][2], 1.0)         # one ulp of one value
    write_csv(path, changed)
    assert load({**CONE, "points": {"file": str(path)}}).sha256 != first.sha256
    # a comment alone changes the file's SHA-256 (recorded) though not the columns
    write_csv(path, COLS, comment=False)
    other = load({**CONE, "points": {"file": str(path)}})
    assert other.sha256 != first.sha256
    assert json.loads(other.canonical)["points"]["sha256"] == json.loads(first.canonical)["points"]["sha256"]


def test_file_values_are_checked_like_inline_ones(tmp_path):
    bad = {**COLS, "mu": COLS["mu"].copy()}
    bad["mu"][4] = -0.25
    msg = problems({**CONE, "points": {"file": str(write_csv(tmp_path / "n.csv", bad))}})
    assert "n.csv" in msg and "points.mu[4] = -0.25" in msg and "[0, 10]" in msg
    msg = problems({**CONE, "points": {"file": str(write_npz(tmp_path / "n.npz", {"x": [0.1], "muu": [0.2]}))}})
    assert "n.npz" in msg and "unknown parameter 'muu'" in msg and "did you mean 'mu'?" in msg
    msg = problems({**CONE, "points": {"file": str(write_npz(tmp_path / "r.npz", {"x": [0.1, 0.2], "y": [0.0]}))}})
    assert "r.npz" in msg and "x has 2" in msg and "y has 1" in msg
    assert "missing parameter" not in msg
    msg = problems({**CONE, "parameters": {**CONE["parameters"], "mu": 0.1},
                    "points": {"file": str(tmp_path / "n.csv")}})
    assert "'mu' is also given in [parameters]" in msg


def test_one_source_per_table(tmp_path):
    path = str(write_csv(tmp_path / "n.csv", COLS))
    msg = problems({**CONE, "points": {"file": path, "z": [0.1] * 7}})
    assert "one source of points" in msg and "'z'" in msg
    msg = problems({**CONE, "points": {"sample": {"n": 4, "seed": 1, "mu": [0.0, 1.0]}, "x": [0.1] * 4}})
    assert "one source of points" in msg and "'x'" in msg
    assert "one source" in problems({**CONE, "points": {"file": path, "sample": {"n": 4, "seed": 1}}})


def _huge_csv(path: Path) -> Path:
    path.write_text("x," + "y" * 20_000 + "\n1,2\n")
    return path


def _sparse(path: Path) -> Path:
    with open(path, "wb") as handle:       # 1 GB + 1 byte without writing them: refused from its size
        handle.truncate(pointfiles.MAX_POINTS_FILE_BYTES + 1)
    return path


HOSTILE = {
    "missing": (lambda d: d / "none.csv", ["cannot read", "No such file"]),
    "directory": (lambda d: (d / "dir.csv").mkdir() or d / "dir.csv", ["is a directory"]),
    "empty": (lambda d: (d / "e.csv").write_text("") and d / "e.csv" or d / "e.csv", ["empty"]),
    "comments_only": (lambda d: (d / "c.csv").write_text("# x,y\n\n") and d / "c.csv", ["no header"]),
    "header_only": (lambda d: (d / "h.csv").write_text("x,y\n# none\n") and d / "h.csv", ["no rows"]),
    "not_numeric": (lambda d: (d / "t.csv").write_text("x,y\n1,2\n# c\n3,far\n") and d / "t.csv",
                    ["line 4, column 'y': not a number"]),
    "ragged": (lambda d: (d / "r.csv").write_text("x,y\n1,2\n3,4,5\n") and d / "r.csv",
               ["line 3 has 3 values", "names 2 columns"]),
    "no_header": (lambda d: (d / "n.csv").write_text("0.1,0.2\n0.3,0.4\n") and d / "n.csv", ["name the columns"]),
    "twice": (lambda d: (d / "w.csv").write_text("x,x\n1,2\n") and d / "w.csv", ["'x' appears twice"]),
    "huge_header": (lambda d: _huge_csv(d / "h.csv"), ["20,002 characters", "at most 10,000"]),
    "binary": (lambda d: (d / "b.csv").write_bytes(b"x\n\xff\xfe\n") and d / "b.csv", ["not UTF-8"]),
    "too_large": (lambda d: _sparse(d / "big.csv"), ["1,000,000,001 bytes", "at most 1,000,000,000"]),
    "suffix": (lambda d: (d / "n.xlsx").write_text("x\n1\n") and d / "n.xlsx", ["unknown file type", ".csv"]),
    "plain_npy": (lambda d: np.save(d / "p.npy", np.zeros((3, 2))) or d / "p.npy", ["structured array"]),
    "npy_2d": (lambda d: np.save(d / "q.npy", np.rec.fromarrays([np.zeros((2, 2))], names="x")) or d / "q.npy",
               ["shape (2, 2)", "1-D"]),
    "npy_objects": (lambda d: np.save(d / "o.npy", np.array([{"x": 1}], dtype=object), allow_pickle=True)
                    or d / "o.npy", ["Python objects"]),
    "npy_garbage": (lambda d: (d / "g.npy").write_bytes(b"not an array") and d / "g.npy", ["not a readable .npy"]),
    "npz_garbage": (lambda d: (d / "g.npz").write_bytes(b"PK not a zip") and d / "g.npz", ["not a readable .npz"]),
    "npz_2d": (lambda d: np.savez(d / "z.npz", x=np.zeros((2, 2))) or d / "z.npz", ["'x' has shape (2, 2)"]),
    "nc_garbage": (lambda d: (d / "g.nc").write_bytes(b"CDF garbage") and d / "g.nc", ["not a readable NetCDF"]),
    "nc_2d": (lambda d: xr.Dataset({"x": (("a", "b"), np.zeros((2, 2)))}).to_netcdf(d / "m.nc") or d / "m.nc",
              ["'x' has 2 dimensions"]),
    "nc_two_dims": (lambda d: xr.Dataset({"x": ("a", [0.1]), "y": ("b", [0.2, 0.3])}).to_netcdf(d / "t.nc")
                    or d / "t.nc", ["along 2 dimensions"]),
}


@pytest.mark.parametrize("case", list(HOSTILE))
def test_hostile_files_are_one_named_problem(tmp_path, case):
    make, words = HOSTILE[case]
    path = make(tmp_path)
    with pytest.raises(RecipeError) as info:
        load({**CONE, "points": {"file": str(path)}})
    found = info.value.problems
    assert len(found) == 1 and found[0].startswith(f"points.file = {str(path)!r}: "), found
    for w in words:
        assert w in found[0], (w, found[0])


def test_more_rows_than_allowed_are_refused(tmp_path, monkeypatch):
    monkeypatch.setattr(pointfiles, "MAX_SWEEP", 5)      # the readers' limit
    for kind in WRITERS:
        path = WRITERS[kind](tmp_path / f"n.{kind}", COLS)      # 7 rows
        msg = problems({**CONE, "points": {"file": str(path)}})
        # a CSV is read up to one row past the limit: "more than"
        assert ("7 rows" in msg or "more than 5 rows" in msg) and "at most 5" in msg and f"n.{kind}" in msg, (
            kind, msg)


def test_a_fifo_is_refused_without_waiting(tmp_path):
    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)
    assert "not a regular file" in problems({**CONE, "points": {"file": str(fifo)}})


def test_file_type_checks(tmp_path):
    assert "must be a file name" in problems({**CONE, "points": {"file": 3}})
    # NetCDF fill values are NaN, refused with their row like any non-finite value
    path = tmp_path / "f.nc"
    xr.Dataset({"x": ("n", [0.1, np.nan, 0.3])}).to_netcdf(path, encoding={"x": {"_FillValue": -9.0}})
    msg = problems({**CONE, "points": {"file": str(path)}})
    assert "points.x[1] = nan" in msg and "f.nc" in msg


def test_cli_validate_says_one_problem_and_exits_2(tmp_path):
    (tmp_path / "nodes.csv").write_text("x,y\n0.1,0.2\n0.3\n")
    toml = tmp_path / "r.toml"
    toml.write_text('scenario = "conical"\n[parameters]\nnu = 0.3\n[points]\nfile = "nodes.csv"\n')
    run = subprocess.run([sys.executable, "-m", "stressfields", "validate", str(toml)], capture_output=True,
                         text=True, timeout=120)
    assert run.returncode == 2 and "Traceback" not in run.stderr
    listed = [line for line in run.stderr.splitlines() if line.startswith("  - ")]
    assert listed == ["  - points.file = 'nodes.csv': line 3 has 1 values but the header names 2 columns (x, y)"]


@pytest.mark.parametrize("with_sweep", [False, True], ids=["only_points", "points_and_sweep"])
def test_cf_compliance_of_a_file_of_points(tmp_path, with_sweep):
    pytest.importorskip("compliance_checker")
    from test_cf_and_docs import cf_failures

    path = write_npz(tmp_path / "nodes.npz", {"x": COLS["x"], "y": COLS["y"]})
    params = {**CONE["parameters"], "mu": [0.0, 0.2] if with_sweep else 0.2}
    out = Path(sf.write(sf.generate({**CONE, "parameters": params, "points": {"file": str(path)}}),
                        tmp_path / "p.nc"))
    assert cf_failures(out) == []
    with xr.open_dataset(out, decode_coords=False) as ds:
        assert ds.attrs.get("featureType") == (None if with_sweep else "point")
        assert json.loads(ds.attrs["stressfields_recipe_canonical"])["points"]["file_sha256"] == hashlib.sha256(
            path.read_bytes()).hexdigest()


# -- samples -------------------------------------------------------------------------------------

def sample(**spec) -> dict:
    return {**CONE, "points": {"sample": spec}}


def test_sample_is_reproducible_from_its_seed():
    spec = {"n": 1000, "method": "sobol", "seed": 7, "mu": [0.0, 1.0], "x": [-2.0, 2.0], "y": [-1.0, 1.0]}
    a, b = load(sample(**spec)), load(sample(**dict(reversed(list(spec.items())))))   # key order: no matter
    for name in ("mu", "x", "y"):
        np.testing.assert_array_equal(a.values[name], b.values[name])
    assert a.sha256 == b.sha256
    other = load(sample(**{**spec, "seed": 8}))
    assert not np.array_equal(other.values["x"], a.values["x"]) and other.sha256 != a.sha256
    canon = json.loads(a.canonical)["points"]
    assert canon["sample"] == {"method": "sobol", "n": 1000, "seed": 7,
                               "ranges": {"mu": [0.0, 1.0], "x": [-2.0, 2.0], "y": [-1.0, 1.0]}}
    assert canon["sha256"] == json.loads(load({**CONE, "points": {k: a.values[k] for k in ("mu", "x", "y")}}
                                              ).canonical)["points"]["sha256"]     # the points drawn
    # another process draws the same bits
    code = ("import hashlib, stressfields.recipe as r; v = r.load(" + repr(sample(**spec)) + ").values; "
            "print(hashlib.sha256(b''.join(v[k].tobytes() for k in ('mu', 'x', 'y'))).hexdigest())")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True)
    here = hashlib.sha256(b"".join(a.values[k].tobytes() for k in ("mu", "x", "y"))).hexdigest()
    assert out.stdout.strip() == here


def test_sample_toml_forms_agree(tmp_path):
    head = 'scenario = "conical"\n[parameters]\nnu = 0.3\n'
    inline = tmp_path / "a.toml"
    inline.write_text(head + '[points]\nsample = { n = 50, method = "lhs", seed = 3, mu = [0.0, 1.0], '
                             'x = [0.0, 2.0] }\n')
    table = tmp_path / "b.toml"
    table.write_text(head + '[points.sample]\nn = 50\nmethod = "lhs"\nseed = 3\nx = [0.0, 2.0]\nmu = [0.0, 1.0]\n')
    a, b = load(inline), load(table)
    assert a.sha256 == b.sha256 and a.shape == {"point": 50}
    ds = sf.generate(table).compute()
    np.testing.assert_array_equal(ds.x.values, a.values["x"])


@pytest.mark.parametrize("method", ["sobol", "lhs", "uniform"])
def test_each_method_fills_the_box(method):
    box = {"mu": [0.25, 0.75], "x": [-3.0, 1e-3], "nu": [0.0, 0.5]}
    r = load({**CONE, "parameters": {"ux0": 0.25}, "points": {"sample": {"n": 777, "method": method, "seed": 0,
                                                                         **box}}})
    for name, (low, high) in box.items():
        v = r.values[name]
        assert v.shape == (777,) and v.dtype == np.float64
        assert low <= v.min() and v.max() <= high
        assert v.max() - v.min() > 0.9 * (high - low)              # spread over the box, not a corner


def test_lhs_has_one_point_per_stratum():
    n = 1000
    cols = draw_sample({"method": "lhs", "n": n, "seed": 5, "ranges": {"mu": [0.0, 1.0], "y": [0.0, 1.0]}})
    for v in cols.values():                    # on [0, 1] the value is the unit coordinate itself
        np.testing.assert_array_equal(np.sort(np.floor(v * n)), np.arange(n))


def test_sobol_is_a_balanced_net_and_needs_no_power_of_two():
    m = 10
    cols = draw_sample({"method": "sobol", "n": 2 ** m, "seed": 2, "ranges": {"mu": [0.0, 1.0], "y": [0.0, 1.0]}})
    u, v = cols["mu"], cols["y"]
    # a (0, m, 2)-net in base 2: every elementary box of area 2^-m holds exactly one point
    for a in range(m + 1):
        cells = np.floor(u * 2 ** a).astype(np.int64) * 2 ** (m - a) + np.floor(v * 2 ** (m - a)).astype(np.int64)
        np.testing.assert_array_equal(np.sort(cells), np.arange(2 ** m), err_msg=f"boxes 2^-{a} x 2^-{m - a}")
    # n not a power of two: the first n points of the same sequence, and no warning
    from scipy.stats import qmc

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        part = draw_sample({"method": "sobol", "n": 1000, "seed": 2, "ranges": {"mu": [0.0, 1.0], "y": [0.0, 1.0]}})
    np.testing.assert_array_equal(part["mu"], u[:1000])
    ref = qmc.Sobol(2, scramble=True, seed=np.random.default_rng(2)).random_base2(m)
    np.testing.assert_array_equal(np.column_stack([u, v]), ref)


def test_uniform_is_numpys_generator():
    cols = draw_sample({"method": "uniform", "n": 100, "seed": 9, "ranges": {"mu": [0.0, 1.0], "x": [0.0, 1.0]}})
    ref = np.random.default_rng(9).random((100, 2))
    np.testing.assert_array_equal(np.column_stack([cols["mu"], cols["x"]]), ref)


@pytest.mark.parametrize("spec, words", [
    ({"n": 10, "seed": 1, "mu": [-0.1, 1.0]}, ["points.sample.mu = [-0.1, 1.0]", "-0.1", "[0, 10]"]),
    ({"n": 10, "seed": 1, "y": [0.0, 2e6]}, ["points.sample.y = [0.0, 2000000.0]: 2000000.0 must be"]),
    ({"n": 10, "mu": [0.0, 1.0]}, ["seed is missing", "reproducible"]),
    ({"n": 10, "seed": -1, "mu": [0.0, 1.0]}, ["seed = -1", "integer >= 0"]),
    ({"n": 10, "seed": True, "mu": [0.0, 1.0]}, ["seed = True"]),
    ({"n": 0, "seed": 1, "mu": [0.0, 1.0]}, ["points.sample.n = 0", f"[1, {MAX_SWEEP:,}]"]),
    ({"n": MAX_SWEEP + 1, "seed": 1, "mu": [0.0, 1.0]}, [f"[1, {MAX_SWEEP:,}]"]),
    ({"seed": 1, "mu": [0.0, 1.0]}, ["points.sample.n = None"]),
    ({"n": 10, "seed": 1, "method": "halton", "mu": [0.0, 1.0]}, ["method = 'halton'", "'sobol', 'lhs', 'uniform'"]),
    ({"n": 10, "seed": 1, "mu": [1.0, 0.0]}, ["[low, high]", "low <= high"]),
    ({"n": 10, "seed": 1, "mu": 0.5}, ["[low, high]"]),
    ({"n": 10, "seed": 1, "muu": [0.0, 1.0]}, ["unknown parameter 'muu'", "did you mean 'mu'?"]),
    ({"n": 10, "seed": 1, "theta": [0.1, 0.2]}, ["'theta' cannot be sampled"]),
    ({"n": 10, "seed": 1}, ["names no parameter range"]),
])
def test_bad_samples_are_named(spec, words):
    msg = problems(sample(**spec))
    for w in words:
        assert w in msg, (w, msg)
    assert "missing parameter" not in msg


def test_sample_checks_against_parameters_and_size():
    msg = problems({**CONE, "parameters": {**CONE["parameters"], "mu": 0.1},
                    "points": {"sample": {"n": 4, "seed": 1, "mu": [0.0, 1.0]}}})
    assert "points.sample.mu: 'mu' is also given in [parameters]" in msg
    assert "must be a table" in problems({**CONE, "points": {"sample": 5}})
    # the product with the sweeps is bounded from n, before anything is drawn
    msg = problems({**CONE, "parameters": {"nu": {"start": 0.0, "stop": 0.5, "num": 10_000}},
                    "points": {"sample": {"n": MAX_SWEEP, "seed": 1, "x": [0.0, 1.0]}}})
    assert "at most" in msg and "point=10,000,000" in msg


def test_sampled_points_equal_the_same_inline_columns():
    r = load(sample(n=64, method="uniform", seed=4, x=[-2.0, 2.0], y=[-2.0, 2.0]))
    inline = {k: r.values[k] for k in ("x", "y")}
    same(sf.generate(sample(n=64, method="uniform", seed=4, x=[-2.0, 2.0], y=[-2.0, 2.0])).compute(),
         sf.generate({**CONE, "points": inline}).compute())


# -- Python objects ------------------------------------------------------------------------------

def test_dataframe_points():
    pd = pytest.importorskip("pandas")
    frame = pd.DataFrame(COLS, index=np.arange(100, 107))        # the index is not a column
    same(sf.generate({**CONE, "points": frame}).compute(), sf.generate({**CONE, "points": COLS}).compute())
    assert load({**CONE, "points": frame}).sha256 == load({**CONE, "points": COLS}).sha256
    assert "not a string" in problems({**CONE, "points": pd.DataFrame({0: [0.1]})})
    assert "points.mu[0] = -1.0" in problems({**CONE, "points": pd.DataFrame({"x": [0.1], "mu": [-1.0]})})


def test_dataset_points():
    ds = xr.Dataset({"x": ("node", COLS["x"]), "mu": ("node", COLS["mu"])},
                    coords={"y": ("node", COLS["y"]), "node": np.arange(7), "E": 1.0})
    # data variables and coordinates along the one dimension; the index numbering the nodes and the
    # scalar coordinate are not columns
    same(sf.generate({**CONE, "points": ds}).compute(), sf.generate({**CONE, "points": COLS}).compute())
    two = xr.Dataset({"x": (("a", "b"), np.zeros((2, 2)))})
    assert "one dimension" in problems({**CONE, "points": two})
    assert "unknown parameter 'node'" in problems(
        {**CONE, "points": xr.Dataset({"x": ("n", [0.1]), "node": ("n", [1.0])})})
