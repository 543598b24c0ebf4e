"""What a recipe and `compare` read, and what they refuse before any work: the read policy of points
files (the recipe's folder, links resolved), messages that quote no file content, the units of
every points-file format, decoded-size bounds from the headers, the free-space check, the
pre-scanner's linear time, hostile names and titles. (`compare`'s report folder killed and on a
full disk: tests/test_faults.py and tests/test_disk_errors.py.)"""
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import xarray as xr

import stressfields as sf
from stressfields import cli, comparison, pointfiles, units
from stressfields.comparison import CompareError
from stressfields.recipe import RecipeError, load

CONE = {"scenario": "conical", "parameters": {"nu": 0.3, "ux0": 0.25}}
TOML = 'scenario = "conical"\n[parameters]\nnu = 0.3\nux0 = 0.25\n[points]\nfile = {name}\n'
#: the content of a file that is not a table of points and must never be echoed
SECRET = "root:x:0:0:s3cret:/root:/bin/bash\ndaemon:x:1:1:daemon:/usr/sbin:/usr/sbin/nologin\n"
SECRET_WORDS = ("s3cret", "daemon", "/bin", "nologin", "usr")


def problems(data, **kw) -> str:
    with pytest.raises(RecipeError) as info:
        load(data, **kw)
    return " | ".join(info.value.problems)


def nodes_csv(path: Path) -> Path:
    path.write_text("x,y\n0.1,0.2\n0.5,0.0\n")
    return path


@pytest.fixture
def folders(tmp_path):
    """rec/ holds the recipe; outside/ a valid points file the recipe must not reach by default."""
    rec, outside = tmp_path / "rec", tmp_path / "outside"
    rec.mkdir()
    outside.mkdir()
    nodes_csv(outside / "nodes.csv")
    return rec, outside


# -- the read policy -----------------------------------------------------------------------------

def _ways_out(rec: Path, outside: Path) -> dict[str, str]:
    (rec / "link.csv").symlink_to(outside / "nodes.csv")
    (rec / "mesh").symlink_to(outside, target_is_directory=True)
    return {"absolute": str(outside / "nodes.csv"), "dotdot": "../outside/nodes.csv",
            "link": "link.csv", "linked_folder": "mesh/nodes.csv"}


def test_a_points_file_outside_the_recipes_folder_is_refused_unless_allowed(folders, capsys):
    rec, outside = folders
    for how, name in _ways_out(rec, outside).items():
        recipe = rec / f"{how}.toml"
        recipe.write_text(TOML.format(name=json.dumps(name)))
        assert cli.main(["validate", str(recipe)]) == 2, how
        err = capsys.readouterr().err
        assert "outside the recipe's folder" in err and "--allow-read" in err and "Traceback" not in err, (how, err)
        assert cli.main(["validate", str(recipe), "--allow-read", str(outside)]) == 0, how
        capsys.readouterr()
        np.testing.assert_array_equal(load(recipe, allow_read=[outside]).values["x"], [0.1, 0.5])
    # inside the folder: a relative path through '..' that stays inside, and a link within it
    (rec / "sub").mkdir()
    nodes_csv(rec / "inside.csv")
    (rec / "sub" / "again.csv").symlink_to(rec / "inside.csv")
    (rec / "data.txt").write_text("x,y\n0.1,0.2\n0.5,0.0\n")
    (rec / "named.csv").symlink_to("data.txt")          # the reader follows the name's suffix
    for name in ("sub/../inside.csv", "sub/again.csv", str(rec / "inside.csv"), "named.csv"):
        recipe = rec / "ok.toml"
        recipe.write_text(TOML.format(name=json.dumps(name)))
        assert load(recipe).values["y"].tolist() == [0.2, 0.0], name


def test_a_dict_recipe_reads_from_the_working_directory(folders, monkeypatch):
    rec, outside = folders
    monkeypatch.chdir(rec)
    nodes_csv(rec / "here.csv")
    assert load({**CONE, "points": {"file": "here.csv"}}).values["x"].tolist() == [0.1, 0.5]
    for name in (str(outside / "nodes.csv"), "../outside/nodes.csv"):
        assert "outside the recipe's folder" in problems({**CONE, "points": {"file": name}})
        assert sf.generate({**CONE, "points": {"file": name}}, allow_read=[outside]).sizes["point"] == 2


# -- no file content in messages -----------------------------------------------------------------

def _hostile_files(folder: Path) -> dict[str, Path]:
    """Files whose names, headers or cells hold the secret text; each must be refused without it."""
    out = {"passwd.csv": folder / "passwd.csv", "cell.csv": folder / "cell.csv"}
    out["passwd.csv"].write_text(SECRET)
    out["cell.csv"].write_text("x,y\n0.1,0.2\n0.3,daemon:x:1:1:s3cret\n")
    np.save(folder / "field.npy", np.zeros(2, dtype=[("root:x:0:0:s3cret", "f8")]))
    out["field.npy"] = folder / "field.npy"
    np.savez(folder / "member.npz", **{"daemon:x:1:1": np.zeros(2)})
    out["member.npz"] = folder / "member.npz"
    with netCDF4.Dataset(folder / "var.nc", "w") as nc:
        nc.createDimension("s3cret usr", 2)
        nc.createVariable("daemon x nologin", "f8", ("s3cret usr",))[:] = [0.0, 1.0]
    out["var.nc"] = folder / "var.nc"
    with netCDF4.Dataset(folder / "dims.nc", "w") as nc:
        nc.createDimension("s3cret_usr_a", 2)
        nc.createDimension("daemon_b", 2)
        nc.createVariable("x", "f8", ("s3cret_usr_a", "daemon_b"))[:] = np.zeros((2, 2))
    out["dims.nc"] = folder / "dims.nc"
    header = b"{'descr': 'root:x:0:0:s3cret:/root:/bin/bash', 'fortran_order': False, 'shape': (2,), }"
    (folder / "header.npy").write_bytes(b"\x93NUMPY\x01\x00" + len(header).to_bytes(2, "little") + header)
    out["header.npy"] = folder / "header.npy"
    return out


def test_messages_quote_no_file_content(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    for name, path in _hostile_files(tmp_path).items():
        msg = problems({**CONE, "points": {"file": path.name}})
        assert msg.startswith(f"points.file = '{path.name}': ") and "\n" not in msg, msg
        assert not any(w in msg for w in SECRET_WORDS), (name, msg)
    # the symbolic link of the report: refused by the policy, and even when allowed its text stays out
    (tmp_path / "nodes.csv").symlink_to(tmp_path / "passwd.csv")
    msg = problems({**CONE, "points": {"file": "nodes.csv"}})
    assert "line 1" in msg or "column 1" in msg, msg
    assert not any(w in msg for w in SECRET_WORDS), msg


def test_compare_node_files_quote_no_content(tmp_path):
    recipe = Path(__file__).parents[1] / "examples" / "fe_hertz_mindlin" / "recipe.toml"
    (tmp_path / "nodes.csv").symlink_to(recipe.with_name("nodes.csv"))      # a node file may be a link
    assert sf.compare(recipe, tmp_path / "nodes.csv").sizes["point"] == 200
    for name, path in _hostile_files(tmp_path).items():
        if path.suffix not in (".csv", ".nc"):
            continue
        with pytest.raises(CompareError) as info:
            sf.compare(recipe, path)
        assert not any(w in str(info.value) for w in SECRET_WORDS), (name, str(info.value))


def test_csv_values_are_the_correctly_rounded_doubles_and_bad_rows_are_located(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    rng = np.random.default_rng(5)
    values = rng.standard_normal(2000) * 10.0 ** rng.integers(-300, 300, 2000)
    texts = [repr(float(v)) for v in values] + ["1e-320", "2.5E+3", " 7 ", "-0.0", "0x1p0"[:0] + "12"]
    raw = ("v\n" + "\n".join(texts) + "\n").encode()
    got = pointfiles.csv_columns(raw)[0].values
    expected = np.array([float(t) for t in texts])        # Python's own correctly rounded parser
    assert got.tobytes() == expected.tobytes()
    for body, words in [("x,y\n1,2\n3\n", "line 3 has 1 values but the header names 2 columns (x, y)"),
                        ("x,y\n1,2\n,4\n", "line 3, column 'x': not a number"),
                        ("x,y\n1,2\n3,NA\n", "line 3, column 'y': not a number"),
                        ("x,y\n1,2\n3,1_0\n", "line 3, column 'y': not a number"),
                        ('x,y\n1,2\n3,"4"\n', "line 3, column 'y': not a number"),
                        ("x,y\n1,2\n3,4\xa0\n", "line 3, column 'y': not a number")]:
        with pytest.raises(pointfiles.FileProblem) as info:
            pointfiles.csv_columns(body.encode())
        assert str(info.value) == words, (body, str(info.value))
    # NaN as written is read, then refused with its row by the range check
    nodes_csv(tmp_path / "n.csv").write_text("x,y\n0.1,0.2\n0.3,nan\n")
    assert "points.y[1] = nan" in problems({**CONE, "points": {"file": "n.csv"}})


# -- hostile names -------------------------------------------------------------------------------

def test_nul_bytes_and_names_that_are_not_utf8_are_one_line(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert "NUL byte" in problems({**CONE, "points": {"file": "nodes\u0000.csv"}})
    (tmp_path / "r.toml").write_text(TOML.format(name='"nodes\\u0000.csv"'))
    assert cli.main(["validate", "r.toml"]) == 2
    assert "NUL byte" in capsys.readouterr().err
    bad = os.fsdecode(b"r\xff.toml")             # as the command line hands over a name of other bytes
    Path(bad).write_text('scenario = "conical"\n[parameters]\nnu = 0.3\nux0 = 0.25\nx = [0.0, 0.5]\n')
    for argv in (["validate", bad], ["run", bad, "-q"], ["run", "r.toml", "-q", "-o", os.fsdecode(b"o\xff.nc")],
                 ["compare", bad, "nodes.csv", "-o", "rep"],
                 ["compare", "r.toml", os.fsdecode(b"n\xff.csv"), "-o", "rep"]):
        if argv[1] == "r.toml":
            Path("r.toml").write_text('scenario = "conical"\n[parameters]\nnu = 0.3\nux0 = 0.25\nx = [0.0, 0.5]\n')
        assert cli.main(argv) == 2, argv
        err = capsys.readouterr().err
        assert "not UTF-8" in err and "Traceback" not in err, (argv, err)
    assert sorted(os.listdir(tmp_path)) == sorted(["r.toml", bad]), os.listdir(tmp_path)


# -- units ---------------------------------------------------------------------------------------

PHYSICAL = {"scenario": "parabolic", "parameters": {"E": 210e9, "nu": 0.3, "R": 0.01, "delta": 1e-6, "mu": 0.3,
                                                     "ux0": 0.25}, "output": {"variables": ["sigma_xx"]}}
MM = {"x": np.array([-0.05, 0.0, 0.12]), "y": np.array([0.01, 0.02, 0.0]), "z": np.array([0.0, 0.03, 0.2])}


def _unit_file(folder: Path, kind: str, unit: str) -> Path:
    """The MM columns in a file of ``kind``, each labelled with ``unit`` as that format says it."""
    path = folder / f"n_{unit}.{kind}"
    labelled = {f"{k}[{unit}]": v for k, v in MM.items()}
    if kind == "csv":
        path.write_text(",".join(labelled) + "\n" + "\n".join(",".join(repr(float(MM[k][i])) for k in MM)
                                                              for i in range(3)) + "\n")
    elif kind == "npy":
        np.save(path, np.rec.fromarrays(list(MM.values()), names=list(labelled)))
    elif kind == "npz":
        np.savez(path, **labelled)
    else:
        xr.Dataset({k: ("node", v, {"units": unit}) for k, v in MM.items()}).to_netcdf(path)
    return path


@pytest.mark.parametrize("kind", ["csv", "npy", "npz", "nc"])
def test_units_of_every_points_format_are_converted_or_refused(tmp_path, monkeypatch, kind):
    monkeypatch.chdir(tmp_path)
    inline = load({**PHYSICAL, "points": {k: v * 1e-3 for k, v in MM.items()}}).values
    from_file = load({**PHYSICAL, "points": {"file": _unit_file(tmp_path, kind, "mm").name}}).values
    for k in MM:
        np.testing.assert_array_equal(from_file[k], inline[k], err_msg=k)
    for unit in ("kPa", "bogus"):    # not a length; not a unit at all
        msg = problems({**PHYSICAL, "points": {"file": _unit_file(tmp_path, kind, unit).name}})
        assert f"unit '{unit}' cannot be converted to x's unit" in msg and "allowed: m, mm, um" in msg, msg
    # a length the table does not list converts through pint, exactly as pint defines it (1 ft = 0.3048 m)
    feet = load({**PHYSICAL, "points": {"file": _unit_file(tmp_path, kind, "ft").name}}).values
    for k in MM:
        np.testing.assert_allclose(feet[k], MM[k] * 0.3048, rtol=1e-15, err_msg=k)
    # normalised mode: coordinates are divided by a; a length unit has no meaning there
    normalised = {"scenario": "parabolic", "parameters": {"nu": 0.3, "mu": 0.3, "ux0": 0.25}}
    assert "unit 'mm' cannot be converted" in problems({**normalised, "points": {"file": f"n_mm.{kind}"}})


def test_one_units_table_for_points_and_compare():
    assert comparison.UNITS is units.UNITS
    assert tuple(units.UNITS) == cli.COMPARE_UNITS


# -- decoded-size bounds -------------------------------------------------------------------------

def _npy_header_only(path: Path, descr, shape) -> Path:
    """A .npy of a header alone: it declares ``shape`` entries of ``descr`` and holds no data."""
    with open(path, "wb") as fh:
        np.lib.format.write_array_header_1_0(fh, {"descr": descr, "fortran_order": False, "shape": shape})
    return path


def test_decoded_sizes_are_bounded_from_the_headers(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    huge = _npy_header_only(tmp_path / "huge.npy", [("x", "<f8"), ("y", "|V1000000")], (10_000_000,))
    assert huge.stat().st_size < 300
    start = time.perf_counter()
    msg = problems({**CONE, "points": {"file": "huge.npy"}})
    assert "declares 10,000,000 entries of 1,000,008 bytes" in msg, msg
    assert "more than the 0 bytes" in problems({**CONE, "points": {"file": str(
        _npy_header_only(tmp_path / "short.npy", [("x", "<f8")], (1000,)).name)}})
    import zipfile
    with zipfile.ZipFile(tmp_path / "huge.npz", "w") as z:
        z.write(huge, "x.npy")
    assert "declares 10,000,000 entries" in problems({**CONE, "points": {"file": "huge.npz"}})
    # 40 variables along 1e7 rows, no value written: a small file that decodes to 3.2 GB
    with netCDF4.Dataset(tmp_path / "huge.nc", "w") as nc:
        nc.createDimension("n", 10_000_000)
        for i in range(40):
            nc.createVariable(f"v{i}", "f8", ("n",), chunksizes=(100_000,))
    assert (tmp_path / "huge.nc").stat().st_size < 200_000
    assert "decode to 3,200,000,000 bytes; at most 1,000,000,000" in problems({**CONE, "points": {"file": "huge.nc"}})
    with pytest.raises(CompareError, match="decode to 3,200,000,000 bytes"):
        sf.compare(Path(__file__).parents[1] / "examples/fe_hertz_mindlin/recipe.toml", tmp_path / "huge.nc")
    assert time.perf_counter() - start < 5        # nothing was allocated or read (measured ~0.1 s)


# -- free space ----------------------------------------------------------------------------------

def test_a_run_larger_than_the_free_space_is_refused_before_anything_is_written(tmp_path, capsys):
    big = tmp_path / "big.toml"     # 1e10 points x 11 float fields and 2 int8 ones: 0.9 TB
    big.write_text('scenario = "conical"\n[parameters]\nnu = 0.3\nmu = 0.3\nux0 = 0.25\n'
                   'y = { start = -1.5, stop = 1.5, num = 100000 }\nx = { start = -1.5, stop = 1.5, num = 100000 }\n'
                   # ten chunks: the graph of the default 1e4 is built in 2-3 s, before the same refusal
                   '[output]\nchunks = { y = 10000, x = 100000 }\n')
    free = os.statvfs(tmp_path).f_bavail * os.statvfs(tmp_path).f_frsize
    if free > 9e11:
        pytest.skip("this file system has 0.9 TB free")
    out = tmp_path / "out"
    out.mkdir()
    assert cli.main(["run", str(big), "-o", str(out / "t.nc"), "-q"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and "\n" not in err, err
    assert "needs about 900,001,600,040 bytes" in err and "bytes (" in err and "free" in err, err
    assert os.listdir(out) == []          # no file, no temporary, no lock, no .parts/


def test_stored_bytes_follow_the_output_options():
    from stressfields.output.form import stored_bytes

    ds = sf.generate({**CONE, "parameters": {**CONE["parameters"], "x": np.linspace(0, 1, 100).tolist(), "y": 0.0}})
    full = stored_bytes(ds)
    half = stored_bytes(ds, sf.output_options(dtype="float32"))
    floats = sum(v.size for v in ds.data_vars.values() if v.dtype == np.float64)
    assert full - half == 4 * floats


# -- the pre-scanner -----------------------------------------------------------------------------

def test_the_prescanner_is_linear_on_a_1_mb_hostile_recipe(tmp_path):
    """Lines of "\\"\\... made every quote a failed start scanning to the line's end (16 KB: 1.15 s, so a
    1 MB line about an hour); the load is timed in a child process that the quadratic scan would
    keep past its timeout."""
    for i, text in enumerate(['"\\' * 499_999, ('"\\' * 2000 + "\n") * 249, '"\\\n' * 333_333]):
        path = tmp_path / f"h{i}.toml"
        path.write_text(text)
        assert 900_000 < path.stat().st_size <= 1_000_000
        code = ("import sys, time\nfrom stressfields.recipe import RecipeError, load\nt = time.perf_counter()\n"
                f"try:\n    load({str(path)!r})\nexcept RecipeError:\n    pass\nprint(time.perf_counter() - t)\n")
        done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60,
                              env={**os.environ, "PYTHONPATH": str(Path(__file__).parents[1])})
        assert done.returncode == 0, done.stderr
        assert float(done.stdout) < 2.0, (i, done.stdout)      # measured 0.05-0.2 s


# -- titles --------------------------------------------------------------------------------------

def test_a_mathtext_title_is_drawn_as_plain_text(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    recipe = tmp_path / "r.toml"
    recipe.write_text('scenario = "conical"\ntitle = "$\\\\foo$ and $x^$ {unclosed"\n[parameters]\nnu = 0.3\n'
                      'ux0 = 0.25\nmu = 0.3\nx = { start = -1.5, stop = 1.5, num = 5 }\n')
    assert cli.main(["run", str(recipe), "-o", str(tmp_path / "t.nc"), "-q", "--plot"]) == 0, capsys.readouterr().err
    assert (tmp_path / "t.png").stat().st_size > 0
