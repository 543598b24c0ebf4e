"""`stressfields compare` / `sf.compare` (stressfields/comparison.py): user nodal values against the
reference at the same points.

The shipped example's nodes carry known errors (examples/fe_hertz_mindlin/make_nodes.py: a smooth
~1e-3 p_m field and one planted 5e-2 p_m error); the reported sizes and places are checked against
those offsets and Hertz's p_m, not against values the comparison computes.
"""
import importlib.util
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from stressfields import cli
from stressfields.cli import main
from stressfields.api import compare
from stressfields.comparison import UNITS, CompareError, summary

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "fe_hertz_mindlin"
RECIPE, NODES = EXAMPLE / "recipe.toml", EXAMPLE / "nodes.csv"
#: the CSV keeps 10 significant digits of values below 2 GPa: at most ~1e-9 p_m of rounding
ROUNDING = 1e-8


def _generator():
    spec = importlib.util.spec_from_file_location("make_nodes", EXAMPLE / "make_nodes.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


GEN = _generator()


def read_csv(path: Path) -> tuple[list[str], np.ndarray]:
    lines = path.read_text().splitlines()
    return lines[0].split(","), np.array([[float(v) for v in line.split(",")] for line in lines[1:]])


def write_csv(path: Path, header: list[str], table: np.ndarray) -> Path:
    path.write_text(",".join(header) + "\n" + "\n".join(",".join(repr(float(v)) for v in row) for row in table) + "\n")
    return path


@pytest.fixture(scope="module")
def example() -> xr.Dataset:
    return compare(RECIPE, NODES, tolerance=1e-2)


def test_example_is_small_and_matches_its_generator():
    assert NODES.stat().st_size < 100_000
    header, table = read_csv(NODES)
    xyz = GEN.nodes()
    assert table.shape == (GEN.N_SURFACE + GEN.N_BELOW, 8)
    for k, name in enumerate(("x", "y", "z"), 1):       # the committed file is the seeded output
        assert header[k] == f"{name}[mm]"
        np.testing.assert_array_equal(table[:, k], xyz[name])


def test_planted_error_is_found_at_its_node_with_its_size(example):
    a, p_m = GEN.hertz()                                    # Hertz's formulas, not the code's
    xyz = GEN.nodes()
    off = GEN.offsets(xyz["x"], xyz["y"], xyz["z"])
    s = summary(example)
    planted = s[GEN.PLANTED_VARIABLE]
    assert planted["worst_point"] == GEN.PLANTED_INDEX
    assert planted["worst_node"] == GEN.FIRST_NODE_ID + GEN.PLANTED_INDEX
    assert abs(planted["max_abs_difference_over_scale"] - abs(off[GEN.PLANTED_VARIABLE][GEN.PLANTED_INDEX])) < ROUNDING
    assert planted["result"].startswith("FAIL: max") and example.attrs["compare_result"] == "FAIL"
    assert planted["worst_coordinates"] == ", ".join(
        f"{c} = {xyz[c][GEN.PLANTED_INDEX]:.6g} mm" for c in ("x", "y", "z"))
    for name in GEN.VARIABLES:
        assert math.isclose(s[name]["scale"], p_m, rel_tol=1e-12)
        np.testing.assert_allclose(example[f"{name}_difference"].values / p_m, off[name], rtol=0, atol=ROUNDING)
        assert abs(s[name]["rms_difference_over_scale"] - np.sqrt(np.mean(off[name] ** 2))) < ROUNDING
        ref = example[f"{name}_reference"].values
        assert math.isclose(s[name]["relative_l2"], np.linalg.norm(off[name] * p_m) / np.linalg.norm(ref),
                            rel_tol=1e-6)
        if name != GEN.PLANTED_VARIABLE:
            assert s[name]["max_abs_difference_over_scale"] <= GEN.SMOOTH_SIZE and s[name]["result"] == "PASS"


def test_reference_is_hertz_pressure_on_the_surface(example):
    """An independent route for the reference itself: sigma_zz = -(3/2) p_m sqrt(1 - r^2/a^2) on z = 0."""
    a, p_m = GEN.hertz()
    surface = example.z.values == 0
    r2 = (example.x.values ** 2 + example.y.values ** 2)[surface] / a ** 2
    hertz = -1.5 * p_m * np.sqrt(np.clip(1 - r2, 0, None))
    np.testing.assert_allclose(example.sigma_zz_reference.values[surface], hertz, rtol=1e-12, atol=1e-12 * p_m)
    assert surface.sum() == GEN.N_SURFACE and (example.reference_validity.values == 0).all()


def test_units_convert_mpa_and_pa_alike(tmp_path, example):
    header, table = read_csv(NODES)
    si = table.copy()
    si[:, 1:4] *= 1e-3
    si[:, 4:] *= 1e6
    for names in ([h.replace("[mm]", "[m]").replace("[MPa]", "[Pa]") for h in header],
                  [h.split("[")[0] for h in header]):          # no brackets: the declared units, m and Pa
        ds = compare(RECIPE, write_csv(tmp_path / "si.csv", names, si), tolerance=1e-2)
        for name in GEN.VARIABLES:
            np.testing.assert_allclose(ds[f"{name}_difference"].values, example[f"{name}_difference"].values,
                                       rtol=0, atol=1e-12 * GEN.hertz()[1])
        assert summary(ds)["sigma_xx"]["worst_point"] == GEN.PLANTED_INDEX
    assert tuple(UNITS) == cli.COMPARE_UNITS


def _cli(tmp_path, *extra, data=NODES) -> tuple[int, Path]:
    out = tmp_path / "report"
    return main(["compare", str(RECIPE), str(data), "-o", str(out), "--overwrite", *extra]), out


@pytest.mark.parametrize("tolerance, code", [("0.01", 1), ("0.1", 0), (None, 0)])
def test_exit_code_follows_the_tolerance(tmp_path, capsys, tolerance, code):
    rc, out = _cli(tmp_path, *(["--tolerance", tolerance] if tolerance else []))
    assert rc == code
    report = (out / "report.md").read_text()
    node = GEN.FIRST_NODE_ID + GEN.PLANTED_INDEX
    assert "| `sigma_xx` |" in report and f"{GEN.PLANTED_INDEX} (node {node})" in report
    assert ("FAIL" in report) == (code == 1)
    assert (out / "comparison.png").stat().st_size > 0


def test_only_the_named_variables(tmp_path):
    rc, out = _cli(tmp_path, "--tolerance", "0.01", "--variables", "sigma_yy", "sigma_zz")
    assert rc == 0
    with xr.open_dataset(out / "comparison.nc") as ds:
        assert ds.attrs["compare_variables"] == "sigma_yy sigma_zz" and "sigma_xx_user" not in ds


def test_netcdf_user_data(tmp_path, example):
    header, table = read_csv(NODES)
    data = {}
    for k, h in enumerate(header):
        name, _, unit = h.partition("[")
        data[name] = ("node_index", table[:, k], {"units": unit.rstrip("]")} if unit else {})
    path = tmp_path / "nodes.nc"
    xr.Dataset(data).to_netcdf(path)
    in_memory = compare(RECIPE, xr.Dataset(data), tolerance=0.01)        # the same as a dataset
    for name in GEN.VARIABLES:
        np.testing.assert_array_equal(in_memory[f"{name}_difference"].values, example[f"{name}_difference"].values)
    assert in_memory.node.values[GEN.PLANTED_INDEX] == GEN.FIRST_NODE_ID + GEN.PLANTED_INDEX
    rc, out = _cli(tmp_path, "--tolerance", "0.01", data=path)
    assert rc == 1
    with xr.open_dataset(out / "comparison.nc") as ds:
        for name in GEN.VARIABLES:
            np.testing.assert_array_equal(ds[f"{name}_difference"].values, example[f"{name}_difference"].values)
        assert ds.attrs["compare_sigma_xx_worst_point"] == GEN.PLANTED_INDEX


def test_comparison_file_has_units_everywhere(tmp_path):
    rc, out = _cli(tmp_path)
    with xr.open_dataset(out / "comparison.nc") as ds:
        assert ds.sizes == {"point": GEN.N_SURFACE + GEN.N_BELOW}
        for name, var in ds.variables.items():
            if "flag_values" not in var.attrs:          # CF flags carry flag_meanings instead
                assert var.attrs.get("units"), name
        assert "stressfields_recipe" in ds.attrs and "compare_recipe" in ds.attrs
        assert ds.attrs["compare_result"].startswith("not judged") and "compare_tolerance" not in ds.attrs
        assert "compare" in ds.attrs["history"] and ds.attrs["Conventions"] == "CF-1.8, ACDD-1.3"
        for name, var in ds.variables.items():
            assert len(var.attrs["long_name"]) <= 40 and var.attrs["coverage_content_type"], name
    pytest.importorskip("compliance_checker")
    from test_cf_and_docs import acdd_high_failures
    from test_clients import cf_warnings

    assert cf_warnings(out / "comparison.nc") == []         # strict: no warning either (history was one)
    assert [m for m in acdd_high_failures(out / "comparison.nc") if "standard_name" not in m] == []


def _csv(tmp_path, text: str) -> Path:
    path = tmp_path / "bad.csv"
    path.write_text(text)
    return path


GOOD = "x[mm],y[mm],z[mm],sigma_xx[MPa]\n0.01,0.02,0.0,-900\n0.03,0.0,0.05,-700\n"


@pytest.mark.parametrize("text, words", [
    ("sigma_xx[MPa]\n-900\n", ["no coordinate column"]),
    ("x[mm],y[mm],z[mm]\n0.01,0.02,0.0\n", ["no value column"]),
    (GOOD.replace("sigma_xx[MPa]", "sigma_xx[mm]"), ["column 'sigma_xx[mm]'", "unit 'mm' is not stress"]),
    (GOOD.replace("x[mm]", "x[MPa]"), ["unit 'MPa' is not length"]),
    (GOOD.replace("sigma_xx[MPa]", "sigma_xx[bar_foo]"), ["unit 'bar_foo' is not a unit pint knows"]),
    (GOOD.replace("-700", "nan"), ["data row 1 (from 0), column 'sigma_xx[MPa]'", "NaN"]),
    (GOOD.replace("-700", "abc"), ["data row 1 (from 0, line 3), column 'sigma_xx[MPa]': not a number"]),
    (GOOD.replace("-700", "-700,5"), ["data row 1 (from 0, line 3) has 5 values but the header names 4 columns"]),
    (GOOD.replace("-700", ""), ["data row 1 (from 0, line 3), column 'sigma_xx[MPa]': not a number"]),
    (GOOD.replace(",-700", ""), ["data row 1 (from 0, line 3) has 3 values but the header names 4 columns"]),
    ("# model output\n\n" + GOOD.replace("0.03,", "# a comment line\n0.03,").replace("-700", "-70x"),
     ["data row 1 (from 0, line 6), column 'sigma_xx[MPa]': not a number"]),
    (GOOD.replace("sigma_xx", "sigma_foo"), ["'sigma_foo[MPa]' is unknown"]),
    (GOOD.replace("sigma_xx", "validity"), ["a flag"]),
    (GOOD.replace("0.0,0.05", "0.0,-0.05"), ["data row 1 (from 0), column 'z[mm]'", "give --z-up"]),
    ("x[mm],x[m],sigma_xx\n0,0,1\n", ["'x[mm]' and 'x[m]' both name 'x'"]),
    ("", ["the file is empty"]),
    ("x,sigma_xx\n", ["header but no rows"]),
])
def test_bad_input_exits_2_with_one_line(tmp_path, capsys, text, words):
    rc, _ = _cli(tmp_path, data=_csv(tmp_path, text))
    err = capsys.readouterr().err.strip()
    assert rc == 2 and len(err.splitlines()) == 1 and err.startswith("error:"), err
    for w in words:
        assert w in err, (w, err)


def _file(folder: Path, name: str, content: bytes) -> Path:
    (folder / name).write_bytes(content)
    return folder / name


@pytest.mark.parametrize("make, words", [
    (lambda p: p / "missing.csv", ["cannot read it"]),
    (lambda p: p, ["not a regular file"]),
    (lambda p: _file(p, "junk.nc", b"\x89HDF\r\n\x1a\nrubbish" * 10), ["not a readable NetCDF file"]),
    (lambda p: _file(p, "bin.csv", b"\xff\xfe\x00garbage"), ["unknown format", "not text"]),
    (lambda p: _file(p, "latin.csv", "x,sigma_xx\n0,1 \xe9\n".encode("latin-1")), ["not UTF-8 text"]),
])
def test_unreadable_files_exit_2(tmp_path, capsys, make, words):
    rc, _ = _cli(tmp_path, data=make(tmp_path))
    err = capsys.readouterr().err.strip()
    assert rc == 2 and len(err.splitlines()) == 1, err
    for w in words:
        assert w in err, (w, err)


def test_bad_options_exit_2(tmp_path, capsys):
    for extra, words in ((["--variables", "sigma_zz", "tau_max"], "'tau_max': not value columns"),
                         (["--tolerance", "nan"], "positive finite")):
        rc, _ = _cli(tmp_path, *extra)
        err = capsys.readouterr().err.strip()
        assert rc == 2 and len(err.splitlines()) == 1 and words in err, err


def test_recipe_sweeps_what_the_nodes_do_not_give(tmp_path):
    swept = {"scenario": "parabolic", "parameters": {"nu": 0.3, "y": [0.0, 0.5]}}
    with pytest.raises(CompareError, match="sweeps 'y' .2 values. but the user data has no 'y' column"):
        compare(swept, {"x": [0.1, 0.2], "sigma_xx": [-1.0, -1.0]})
    # normalised mode: a column in mm cannot become the dimensionless x
    with pytest.raises(CompareError, match=r"unit 'mm' is not a pure number .* normalised mode \('1'\)"):
        compare({"scenario": "parabolic", "parameters": {"nu": 0.3}}, {"x[mm]": [0.1], "sigma_xx": [-1.0]})


def test_normalised_mode_scale_is_one():
    """In normalised mode the values are already divided by p_m: S = 1. Hertz on the axis, z = 0:
    sigma_zz = -(3/2) p_m, so a user value of -1.4 differs by 0.1 of p_m."""
    ds = compare({"scenario": "parabolic", "parameters": {"nu": 0.3}},
                 {"x": [0.0, 2.0], "y": [0.0, 0.0], "sigma_zz": [-1.4, 0.0]}, tolerance=0.05)
    s = summary(ds)["sigma_zz"]
    assert math.isclose(s["max_abs_difference_over_scale"], 0.1, rel_tol=1e-12) and s["worst_point"] == 0
    assert s["scale"] == 1.0 and s["result"].startswith("FAIL: max")


def test_readme_says_what_the_example_reports(example):
    s = summary(example)["sigma_xx"]
    readme = (EXAMPLE.parents[1] / "README.md").read_text(encoding="utf-8")
    assert f"point {s['worst_point']} (node {s['worst_node']}, {s['worst_coordinates']})" in readme


def test_sf_compare_is_the_function():
    """In a fresh interpreter, as a user meets it: `sf.compare` is the function, also after a call."""
    code = ("import stressfields as sf, stressfields.comparison, stressfields.api as m; f = sf.compare; "
            "sf.compare({'scenario': 'parabolic', 'parameters': {}}, {'x': [0.5], 'sigma_zz': [-1.0]}); "
            "print(f is m.compare and sf.compare is m.compare)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.stdout.strip() == "True", done.stderr


def test_singular_points_are_left_out_and_counted():
    """The cone tip (x = y = 0) is log-singular: the reference is -inf there, flagged, and not compared."""
    recipe = {"scenario": "conical", "parameters": {"nu": 0.3}}
    ref = compare(recipe, {"x": [0.5], "y": [0.0], "sigma_xx": [0.0]}).sigma_xx_reference.values[0]
    ds = compare(recipe, {"x": [0.0, 0.5], "y": [0.0, 0.0], "sigma_xx": [-5.0, ref + 0.01]}, tolerance=0.02)
    s = summary(ds)["sigma_xx"]
    assert s["excluded_points"] == 1 and s["compared_points"] == 1 and s["worst_point"] == 1
    assert abs(s["max_abs_difference_over_scale"] - 0.01) < 1e-14 and s["result"] == "PASS"
    assert ds.reference_validity.values.tolist() == [1, 0] and np.isneginf(ds.sigma_xx_reference.values[0])


def test_wavy_scales_in_physical_mode():
    """p* = pi E/(1-nu^2) Delta_1/lambda_1 for the pressure and Delta_1 for uz (Tsukanov's scales)."""
    e, nu, d1, lam = 1e9, 0.4, 1e-6, 1e-3
    recipe = {"scenario": "wavy", "parameters": {"amplitudes": [d1], "wavenumbers": [1], "E": e, "nu": nu,
                                                 "lambda_1": lam, "a": 0.3}}
    s = summary(compare(recipe, {"x[mm]": [0.0, 0.05], "pressure[MPa]": [0.0, 0.0], "uz[um]": [0.0, 0.0]}))
    assert math.isclose(s["pressure"]["scale"], math.pi * e / (1 - nu ** 2) * d1 / lam, rel_tol=1e-12)
    assert math.isclose(s["uz"]["scale"], d1, rel_tol=1e-12)


def test_columns_of_different_lengths():
    with pytest.raises(CompareError, match="one length"):
        compare({"scenario": "parabolic", "parameters": {"nu": 0.3}}, {"x": [0.1, 0.2], "sigma_xx": [-1.0]})


# -- the API is the command's path: its switches as keywords, units from the recipe --------------------

CONVERGENCE = EXAMPLE.parent / "fe_convergence"


def _recipe_with(tmp_path, extra: str) -> Path:
    path = tmp_path / "recipe.toml"
    path.write_text((CONVERGENCE / "recipe.toml").read_text() + "\n" + extra)
    return path


def test_z_up_keyword_flips_z_and_the_shears_exactly(tmp_path, example):
    """The model with z up: z, sigma_xz negated (a body at z <= 0) gives the same differences, exactly."""
    header, table = read_csv(NODES)
    up = table.copy()
    for k, h in enumerate(header):
        if h.split("[")[0] in ("z", "sigma_xz"):
            up[:, k] = -up[:, k]
    path = write_csv(tmp_path / "up.csv", header, up)
    with pytest.raises(CompareError, match="give --z-up"):
        compare(RECIPE, path)
    ds = compare(RECIPE, path, tolerance=0.01, z_up=True)
    for name in GEN.VARIABLES:
        np.testing.assert_array_equal(ds[f"{name}_difference"].values, example[f"{name}_difference"].values)
    assert ds.attrs["compare_result"] == "FAIL" and "z up in the file" in ds.attrs["compare_frame"]


def test_recipe_units_serve_a_file_without_units_and_the_keyword_overrides_them(tmp_path):
    """A VTU carries no units: the recipe's [compare] units (mm, N/mm^2) read it as the Abaqus-style CSV
    of the same nodes, whose header says mm and N/mm^2; `units=` (the CLI's --units) wins over them."""
    pytest.importorskip("meshio")
    csv = compare(CONVERGENCE / "recipe.toml", CONVERGENCE / "L1.csv", axisymmetric=True)
    with pytest.raises(CompareError, match="give --units"):
        compare(CONVERGENCE / "recipe.toml", CONVERGENCE / "L1.vtu", axisymmetric=True)
    good = _recipe_with(tmp_path, '[compare]\nunits = { length = "mm", stress = "N/mm^2" }\n')
    vtu = compare(good, CONVERGENCE / "L1.vtu", axisymmetric=True)
    wrong = _recipe_with(tmp_path, '[compare]\nunits = { length = "m", stress = "Pa" }\n')
    override = compare(wrong, CONVERGENCE / "L1.vtu", axisymmetric=True, units={"length": "mm", "stress": "N/mm^2"})
    # the CSV keeps 10 significant digits of the stress (make_meshes.py): at most 5e-10 of each value apart
    np.testing.assert_array_equal(override.sigma_zz_difference.values, vtu.sigma_zz_difference.values)
    np.testing.assert_allclose(override.x.values, csv.x.values, rtol=1e-15)      # the CSV's 9 digits, 1 ulp
    assert np.all(np.abs(vtu.sigma_zz_difference.values - csv.sigma_zz_difference.values)
                  <= 5e-10 * np.abs(csv.sigma_zz_user.values))
    assert not np.allclose(compare(wrong, CONVERGENCE / "L1.vtu", axisymmetric=True).x.values, csv.x.values)
    rc = main(["compare", str(wrong), str(CONVERGENCE / "L1.vtu"), "--axisymmetric", "--no-plot",
                    "--units", "length=mm,stress=N/mm^2", "-o", str(tmp_path / "r")])
    assert rc == 0
    with xr.open_dataset(tmp_path / "r" / "comparison.nc") as ds:
        np.testing.assert_array_equal(ds.sigma_zz_difference.values, vtu.sigma_zz_difference.values)


@pytest.mark.parametrize("table, words", [
    ('units = { stress = "mm" }', "compare.units.stress = 'mm'"),
    ('units = { pressure = "MPa" }', "unknown key 'compare.units.pressure'; allowed: length"),
    ('unit = { stress = "MPa" }', "unknown key 'compare.unit'; allowed: units"),
    ('units = "mm"', "compare.units must be a table"),
])
def test_bad_recipe_units_exit_2_before_any_work(tmp_path, capsys, table, words):
    recipe = _recipe_with(tmp_path, "[compare]\n" + table + "\n")
    rc = main(["compare", str(recipe), str(CONVERGENCE / "L1.csv"), "--axisymmetric", "-o", str(tmp_path / "r")])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and len(err.splitlines()) == 1 and words in err, err
    assert not (tmp_path / "r").exists()
    from stressfields.recipe import RecipeError, load

    with pytest.raises(RecipeError, match=words.replace("(", r"\(").replace(")", r"\)")):
        load(recipe)          # `generate` refuses it the same way


def test_keywords_are_checked_in_one_line():
    recipe = {"scenario": "parabolic", "parameters": {"nu": 0.3}}
    data = {"x": [0.5], "sigma_zz": [-1.0]}
    for kw, words in [({"tolerance": float("nan")}, "positive finite"),
                      ({"tolerance": {"median": 1}}, "--tolerance median"),
                      ({"units": "length=kg"}, "--units length=kg"), ({"scale": "p2"}, "--scale p2"),
                      ({"exclude_edge": -1.0}, "--exclude-edge -1"), ({"step": 2}, "only an Exodus II file")]:
        with pytest.raises(CompareError, match=words) as info:
            compare(recipe, data, **kw)
        assert "\n" not in str(info.value)


def test_an_exodus_history_gives_one_dataset_per_step_and_step_picks_one(tmp_path, example):
    """Three time steps of the example's nodes, z up, in mm and MPa (Exodus carries no units): steps 1
    and 3 are the CSV's values, so their differences are the example's; step 2 is 1.01 x them."""
    from test_fe_validate import _exodus

    header, table = read_csv(NODES)
    values = table[:, 4:] * np.array([1.0, 1.0, 1.0, -1.0])
    names = [h.split("[")[0] for h in header[4:]]
    up = table[:, 1:4] * np.array([1.0, 1.0, -1.0])
    exo = _exodus(tmp_path / "model.e", up, names, [values, values * 1.01, values])
    every = compare(RECIPE, exo, z_up=True, units="length=mm,stress=MPa")
    assert isinstance(every, list) and len(every) == 3
    third = compare(RECIPE, exo, z_up=True, units={"length": "mm", "stress": "MPa"}, step=3)
    for ds in (every[0], every[2], third):
        for name in GEN.VARIABLES:
            np.testing.assert_allclose(ds[f"{name}_difference"].values, example[f"{name}_difference"].values,
                                       rtol=0, atol=1e-12 * GEN.hertz()[1])
    np.testing.assert_allclose(every[1].sigma_zz_user.values, 1.01 * every[0].sigma_zz_user.values, rtol=1e-15)
    with pytest.raises(CompareError, match="--step 4 is not a time step of the file: it has 3"):
        compare(RECIPE, exo, z_up=True, units="length=mm,stress=MPa", step=4)
