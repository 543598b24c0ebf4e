"""The data as real clients read it: both NetCDF engines, Zarr, the stressfields backend, CF-1.8,
dask chunks on reopening, float32, compression and non-finite values; choice dimensions labelled in
memory, units that pint, cf_xarray and cf-units read, no compliance-checker warning, quick-look labels."""
import json
import warnings
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import stressfields as sf
from stressfields import cli
from stressfields.output import options as outopts
from stressfields.output.form import encode_choices
from stressfields.output.formats import file_hash
from stressfields.output.netcdf import _layout
from stressfields.scenarios import REGISTRY

from test_cf_and_docs import cf_failures, dimension_order_only

pytest.importorskip("zarr")

#: a sweep over choices (`control`) beside a numeric one
CHOICES = {"scenario": "graded_adhesive", "parameters": {"profile": "parabolic", "R": 0.01, "E0": 1e6,
                                                         "delta_gamma": 0.05, "contact_radius": 1e-4,
                                                         "k": {"start": 0.0, "stop": 0.9, "num": 4}},
           "output": {"variables": ["critical_radius", "critical_force"]}}
#: the cone's stresses are unbounded at the contact edge |x| = 1 and the apex x = 0: +-inf there
CONE = {"scenario": "conical", "parameters": {"mu": [0.0, 0.3], "x": {"start": -1.5, "stop": 1.5, "num": 61},
                                              "y": 0.0},
        "output": {"variables": ["sigma_xx", "von_mises"], "chunks": {"mu": 1}}}


@pytest.fixture(scope="module")
def choice_files(tmp_path_factory):
    out = tmp_path_factory.mktemp("choices")
    ds = sf.generate(CHOICES)
    return ds, sf.write(ds, out / "c.nc"), sf.write(ds, out / "c.zarr")


@pytest.mark.parametrize("engine", ["netcdf4", "h5netcdf"])
def test_both_netcdf_engines_read_the_same_values_and_flags(choice_files, engine):
    pytest.importorskip({"netcdf4": "netCDF4"}.get(engine, engine))
    ds, nc, _ = choice_files
    with xr.open_dataset(nc, engine=engine) as got:
        np.testing.assert_array_equal(got.critical_force.values, ds.critical_force.values)
        assert got.control.dtype == np.int8 and got.control.attrs["flag_values"].dtype == np.int8
        assert list(got.control_name.values) == ["fixed_load", "fixed_grips"]


def test_choice_names_are_char_arrays_not_netcdf4_strings(choice_files):
    """ParaView's CF reader crashes on a netCDF-4 string coordinate; a UTF-8 char array reads as text."""
    import netCDF4

    _, nc, _ = choice_files
    with netCDF4.Dataset(nc) as raw:
        assert [name for name, var in raw.variables.items() if var.dtype is str] == []
        assert raw["control_name"].dtype == np.dtype("S1") and raw["control_name"].getncattr("_Encoding") == "utf-8"
    with xr.open_dataset(nc) as ds:
        assert list(ds.control_name.values) == ["fixed_load", "fixed_grips"]


@pytest.mark.parametrize("kind", ["nc", "zarr"])
def test_choice_dimensions_reopen_labelled(choice_files, kind):
    ds, nc, store = choice_files
    path = nc if kind == "nc" else store
    expected = ds.critical_force.isel(control=1).values        # code 1 is the second choice, by build
    for opened in (sf.open_dataset(path), xr.open_dataset(path, engine="stressfields", chunks={})):
        with opened as got:
            assert list(got.control.values) == ["fixed_load", "fixed_grips"] and "control_name" not in got
            np.testing.assert_array_equal(got.critical_force.sel(control="fixed_grips").values, expected)


def test_a_labelled_dataset_is_written_in_the_cf_flag_form(tmp_path, choice_files):
    ds, nc, _ = choice_files
    labelled = sf.open_dataset(nc).load()
    assert labelled.control.dtype.kind in "OU"
    again = sf.write(labelled, tmp_path / "again.nc")
    zarr_again = sf.write(labelled, tmp_path / "again.zarr")
    assert file_hash(again) == file_hash(nc)                    # the same file, bit for bit in content
    with xr.open_zarr(zarr_again) as z, xr.open_dataset(nc) as n:
        assert z.control.attrs["flag_meanings"] == n.control.attrs["flag_meanings"] == "fixed_load fixed_grips"


def test_zarr_export_keeps_types_order_and_cf(tmp_path, choice_files):
    _, nc, store = choice_files
    exported = sf.export(store, tmp_path / "e.nc")
    assert file_hash(exported)[0] == file_hash(nc)[0]           # attribute dtypes are hashed too
    with xr.open_dataset(exported) as e, xr.open_dataset(nc) as d:
        assert list(e.variables) == list(d.variables)
        assert e.control.attrs["flag_values"].dtype == np.int8
    assert cf_failures(exported) == []


def test_zarr_commands_print_no_zarr_warning(tmp_path, capfd):
    recipe = tmp_path / "w.toml"
    recipe.write_text('scenario = "wavy"\n[parameters]\ndomain = ["periodic", "nonperiodic"]\namplitudes = [0.5]\n'
                      'wavenumbers = [1]\na = 0.3\nx = { start = -1.0, stop = 1.0, num = 21 }\n'
                      '[output]\nvariables = ["pressure"]\n')
    with warnings.catch_warnings():
        warnings.simplefilter("error")          # any warning fails the commands below
        assert cli.main(["run", str(recipe), "-o", str(tmp_path / "w.zarr"), "-q"]) == 0
        assert cli.main(["hash", str(tmp_path / "w.zarr")]) == 0
        assert cli.main(["export", str(tmp_path / "w.zarr"), "-o", str(tmp_path / "w.nc")]) == 0
    assert "Warning" not in capfd.readouterr().err
    with sf.open_dataset(tmp_path / "w.nc") as got:
        assert list(got.domain.values) == ["periodic", "nonperiodic"]
        assert got.pressure.sel(domain="nonperiodic").shape == (21,)


def test_float32_and_compression_stay_cf_clean_and_within_the_rounding_note(tmp_path):
    ds = sf.generate(CONE)
    exact = ds.compute()
    single = sf.write(ds, tmp_path / "f32.nc", dtype="float32")
    packed = sf.write(ds, tmp_path / "z.nc", compression=4)
    for path in (single, packed):
        assert cf_failures(path) == []
        assert file_hash(path)[0] == file_hash(path)[1]
    with xr.open_dataset(single) as got, xr.open_dataset(packed) as z:
        assert got.sigma_xx.dtype == np.float32 and got.x.dtype == np.float64
        assert "float32" in got.sigma_xx.attrs["stressfields_accuracy"]
        assert "dtype=float32" in got.attrs[outopts.OPTIONS_ATTR]
        ref = exact.sigma_xx.values
        finite = np.isfinite(ref)
        # float32 keeps 24 bits: |rounded - exact| <= 2^-24 |exact| (the note's 6e-8)
        assert np.all(np.abs(got.sigma_xx.values[finite] - ref[finite]) <= 2.0 ** -24 * np.abs(ref[finite]))
        np.testing.assert_array_equal(got.sigma_xx.values[~finite], ref[~finite])   # +-inf stay +-inf
        np.testing.assert_array_equal(z.sigma_xx.values, ref)                      # zlib is lossless
        assert z.sigma_xx.encoding["zlib"] and z.sigma_xx.encoding["shuffle"]
    assert file_hash(sf.write(ds, tmp_path / "again.nc", dtype="float32")) == file_hash(single)


def test_float32_error_estimate_stays_an_upper_bound(tmp_path):
    recipe = {"scenario": "wavy", "parameters": {"amplitudes": [0.5, 0.01], "wavenumbers": [1, 11],
                                                 "a": [0.05, 0.3, 0.8], "x": 0.0},
              "output": {"variables": ["error_estimate"]}, "method": {"rtol": 1e-6}}
    ds = sf.generate(recipe)
    exact = ds.error_estimate.values
    with xr.open_dataset(sf.write(ds, tmp_path / "e.nc", dtype="float32")) as got:
        stored = got.error_estimate.values
    assert stored.dtype == np.float32 and np.all(stored.astype(np.float64) >= exact)
    assert np.all(stored.astype(np.float64) <= exact * (1 + 2.0 ** -23))


def test_float32_below_its_normal_range_meets_the_stated_absolute_rule(tmp_path):
    """Subnormal float32 keeps fewer than 24 bits: there the note (and the README) promise 1.4e-45
    absolute, not 6e-8 relative. A physical cone with a tiny modulus puts its stresses across
    float32's normal/subnormal border (1.2e-38) and below its smallest subnormal."""
    recipe = {"scenario": "conical", "parameters": {"E": 1e-33, "theta": 0.1, "delta": 1e-3, "mu": 0.3,
                                                    "ux0": 0.01, "x": {"start": -3e-3, "stop": 3e-3, "num": 41},
                                                    "z": [0.0, 1e-3, 1e-1, 10.0]},
              "output": {"variables": ["sigma_xx", "sigma_zz"]}}
    ds = sf.generate(recipe)
    exact = ds.compute()
    with xr.open_dataset(sf.write(ds, tmp_path / "f32.nc", dtype="float32")) as got:
        for name in ("sigma_xx", "sigma_zz"):
            ref, stored = exact[name].values, got[name].values.astype(np.float64)
            assert "1.4e-45 absolute below |value| = 1.2e-38" in got[name].attrs["stressfields_accuracy"]
            small = np.isfinite(ref) & (np.abs(ref) < 2.0 ** -126)
            assert small.any() and (np.abs(ref) >= 2.0 ** -126).any()     # both sides of the border
            error = np.abs(stored - ref)
            assert np.all(error[small] <= 1.4e-45)
            big = np.isfinite(ref) & ~small
            assert np.all(error[big] <= 2.0 ** -24 * np.abs(ref[big]))
            # the relative promise alone would not hold there: the rule is needed
            assert np.any(error[small] > 2.0 ** -24 * np.abs(ref[small]))


def test_a_float_beyond_float32_is_refused_not_stored_as_inf(tmp_path):
    ds = xr.Dataset({"f": ("x", np.array([1.0, 1e300]))}, coords={"x": [0.0, 1.0]})
    with pytest.raises(sf.OutputError, match="exceeds the float32 range"):
        sf.write(ds, tmp_path / "big.nc", dtype="float32")
    assert not (tmp_path / "big.nc").exists()


@pytest.mark.parametrize("mode", ["keep", "nan", "fill"])
def test_nonfinite_modes(tmp_path, mode):
    ds = sf.generate(CONE)
    exact = ds.compute()
    inf = np.isinf(exact.sigma_xx.values)
    assert inf.any() and np.all(exact.validity.values[inf] != 0)
    path = sf.write(ds, tmp_path / f"{mode}.nc", nonfinite=mode)
    with xr.open_dataset(path) as got, xr.open_dataset(path, mask_and_scale=False) as raw:
        np.testing.assert_array_equal(got.validity.values, exact.validity.values)    # the flag says why
        np.testing.assert_array_equal(got.sigma_xx.values[~inf], exact.sigma_xx.values[~inf])
        values = raw.sigma_xx.values[inf]
        if mode == "keep":
            np.testing.assert_array_equal(values, exact.sigma_xx.values[inf])
        elif mode == "nan":
            assert np.isnan(values).all() and "_FillValue" not in raw.sigma_xx.attrs
        else:
            assert np.all(values == raw.sigma_xx.attrs["_FillValue"]) and np.isnan(got.sigma_xx.values[inf]).all()
        assert not np.isinf(got.sigma_xx.values).any() or mode == "keep"


def test_reopened_chunks_follow_dask_and_stay_below_64_mb(tmp_path):
    """Compressed variables (and uncompressed ones above 256 MB) are stored in HDF5 chunks that
    follow the dask chunks; smaller uncompressed ones contiguous, one chunk when reopened."""
    ds = sf.generate({**CONE, "output": {"variables": ["sigma_xx"], "chunks": {"mu": 1, "x": 16}}})
    path = sf.write(ds, tmp_path / "c.nc", compression=1)
    with xr.open_dataset(path, chunks={}) as got:
        assert got.sigma_xx.chunks == ((1, 1), (16, 16, 16, 13))
    plain = sf.write(ds, tmp_path / "p.nc")
    with xr.open_dataset(plain, chunks={}) as got:
        assert got.sigma_xx.chunks == ((2,), (61,)) and got.sigma_xx.encoding["contiguous"]
    # the HDF5 chunk of a large dask chunk is capped: leading dimensions shrink, a line along x stays whole
    big = xr.DataArray(np.broadcast_to(np.float64(0), (4000, 5000))).chunk({"dim_0": 4000}).variable
    chunks = _layout(big, 1)["chunksizes"]
    assert np.prod(chunks) * 8 <= 64 * 2 ** 20 and chunks[1] == 5000


def test_output_options_are_checked_together():
    assert outopts.output_options("float32", 9, "fill") == outopts.OutputOptions("float32", 9, "fill")
    problems = outopts.output_option_problems("float16", 12, "drop")
    assert len(problems) == 3 and all(key in " ".join(problems) for key in ("dtype", "compression", "nonfinite"))
    with pytest.raises(sf.OutputError, match="float16"):
        sf.write(sf.generate(CONE), "unused.nc", dtype="float16")
    option = outopts.OutputOptions("float32", 3, "nan")
    assert outopts.OutputOptions.from_attrs({outopts.OPTIONS_ATTR: option.text()}) == option


def test_recipe_output_table_sets_the_storage(tmp_path):
    """[output] dtype/compression/nonfinite reach the file; a flag on the command line overrides them."""
    import xarray as xr

    from stressfields import cli

    recipe = tmp_path / "r.toml"
    recipe.write_text('scenario = "conical"\n[parameters]\nx = [0.0, 0.5, 2.0]\n'
                      '[output]\nvariables = ["sigma_xx"]\ndtype = "float32"\nnonfinite = "nan"\n')
    assert cli.main(["run", str(recipe), "-o", str(tmp_path / "a.nc"), "-q"]) == 0
    assert cli.main(["run", str(recipe), "-o", str(tmp_path / "b.nc"), "-q", "--dtype", "float64"]) == 0
    with xr.open_dataset(tmp_path / "a.nc") as a, xr.open_dataset(tmp_path / "b.nc") as b:
        assert a.sigma_xx.dtype == "float32" and b.sigma_xx.dtype == "float64"
        assert not bool((abs(a.sigma_xx) == float("inf")).any())    # the cone tip's -inf became NaN
        assert bool(a.sigma_xx.isnull()[0]) and int(a.validity[0]) != 0
    bad = tmp_path / "bad.toml"
    bad.write_text(recipe.read_text().replace('"float32"', '"float16"'))
    assert cli.main(["validate", str(bad)]) == 2


# -- what other clients read: labels in memory, units, CF warnings, plots ----------------------------

ROOT = Path(__file__).resolve().parents[1]
RECIPES = sorted((ROOT / "recipes").glob("*.toml"))


def test_choice_dimensions_are_labelled_in_memory():
    ds = sf.generate(CHOICES)
    assert list(ds.control.values) == ["fixed_load", "fixed_grips"] and "control_name" not in ds.coords
    assert ds.control.attrs["description"] == REGISTRY["graded_adhesive"].parameter("control").meaning
    # pull-off forces of a paraboloid, Hess & Popov 2016 eq. (34) (independent of E0 and c0): the
    # evaluate of each block received the right choice
    k, pi_dgam_R = ds.k.values, np.pi * 0.05 * 0.01
    np.testing.assert_allclose(ds.critical_force.sel(control="fixed_load"), -(3 + k) / 2 * pi_dgam_R, rtol=1e-12)
    np.testing.assert_allclose(ds.critical_force.sel(control="fixed_grips"),
                               -(1 - k) * (5 + 3 * k) / (2 * (3 + k)) * pi_dgam_R, rtol=1e-12)


def test_a_swept_choice_equals_each_choice_given_alone_and_hashes_as_its_cf_form(tmp_path):
    params = {"amplitudes": [0.5, 0.05], "wavenumbers": [1, 3], "a": [0.2, 0.6], "x": [0.0, 0.5, 1.2]}
    both = sf.generate({"scenario": "wavy", "parameters": {**params, "domain": ["periodic", "nonperiodic"]}})
    assert list(both.domain.values) == ["periodic", "nonperiodic"]
    for domain in both.domain.values:
        alone = sf.generate({"scenario": "wavy", "parameters": {**params, "domain": str(domain)}})
        for name in ("pressure", "uz", "validity"):
            np.testing.assert_array_equal(both[name].sel(domain=domain).values, alone[name].values)
    # the labelled dataset and the CF flag form build.py wrote before are the same file content
    labelled = sf.write(both, tmp_path / "labelled.nc")
    flagged = sf.write(encode_choices(both), tmp_path / "flagged.nc")
    assert file_hash(labelled) == file_hash(flagged)


@pytest.mark.parametrize("recipe", RECIPES, ids=lambda p: p.stem)
def test_every_units_string_reads_in_pint_cf_xarray_and_cf_units(recipe_outputs, recipe):
    pint = pytest.importorskip("pint")
    pytest.importorskip("pint_xarray")
    # pint-xarray's default registry is pint's application registry: a plain UnitRegistry until
    # cf_xarray.units replaces it on import, so a fresh one is that default whatever ran before
    plain = pint.UnitRegistry(force_ndarray_like=True)
    with xr.open_dataset(recipe_outputs / f"{recipe.stem}.nc") as ds:
        units = {n: v.attrs["units"] for n, v in ds.variables.items() if "units" in v.attrs}
        quantified = ds.pint.quantify(unit_registry=plain)
        for name in set(units) & set(ds.data_vars):
            assert quantified[name].pint.units == plain.Unit(units[name]), name
    cf_units = pytest.importorskip("cf_units")
    cfx = pytest.importorskip("cf_xarray.units").units
    for name, text in units.items():
        assert not cf_units.Unit(text).is_unknown(), (name, text)
        assert cfx.Unit(text).dimensionality == plain.Unit(text).dimensionality, (name, text)


def cf_warnings(path: Path) -> list:
    """Every item of compliance-checker cf:1.8 that is not fully met or carries a message (strict)."""
    from compliance_checker.runner import CheckSuite, ComplianceChecker

    CheckSuite.load_all_available_checkers()
    report = path.with_suffix(".strict.json")
    _, errors = ComplianceChecker.run_checker(str(path), ["cf:1.8"], 2, "strict", output_filename=str(report),
                                              output_format="json")
    result = json.loads(report.read_text())["cf:1.8"]
    found = [("checker", "exceptions while checking", [])] if errors else []
    for level in ("high_priorities", "medium_priorities", "low_priorities"):
        found += [(level, item["name"], item["msgs"]) for item in result.get(level, [])
                  if item["value"][0] < item["value"][1] or item["msgs"]]
    return found


@pytest.mark.parametrize("stem", [p.stem for p in RECIPES])
def test_no_compliance_checker_warning(recipe_outputs, stem):
    # graded files warned "Variables are not case sensitive" on r/R and a/A before the renames; the one
    # warning allowed is CF §2.4's dimension order on files sweeping z with x or y (see dimension_order_only)
    path = recipe_outputs / f"{stem}.nc"
    found = cf_warnings(path)
    assert found == [] or dimension_order_only(path, found), found


HISTORY = {"scenario": "axisymmetric_history", "parameters": {
    "mu": 0.3, "ux0_history": [0.0, 0.5, -0.5, 0.5], "amplitude": [0.5, 1.0], "x": [0.0, 0.5]},
    "output": {"variables": ["tangential_force"]}}


def test_a_history_file_plots_against_ux0(tmp_path):
    plt = pytest.importorskip("matplotlib.pyplot")
    path = sf.write(sf.generate(HISTORY), tmp_path / "h.nc")
    with xr.open_dataset(path) as raw:
        assert "ux0" in raw.coords and "ux0" not in raw.data_vars        # a coordinate for every reader
    with sf.open_dataset(path) as ds:
        lines = ds.tangential_force.plot.line(x="ux0", hue="amplitude")
        for amplitude, line in zip(ds.amplitude.values, lines):            # u_x0/delta = amplitude * history
            np.testing.assert_array_equal(line.get_xdata(), amplitude * np.array([0.0, 0.5, -0.5, 0.5]))
    plt.close("all")


@pytest.mark.parametrize("stem", ["graded_adhesive_pulloff", "history_hertz_fretting", "wavy_fig4"])
def test_quick_look_labels_are_one_short_line(recipe_outputs, stem):
    plt = pytest.importorskip("matplotlib.pyplot")
    from stressfields import plot
    from stressfields.recipe import load

    recipe = load(ROOT / "recipes" / f"{stem}.toml")
    with sf.open_dataset(recipe_outputs / f"{stem}.nc") as ds:
        fig = plot._figure(plt, ds, recipe)
        axes = [ax for ax in fig.axes if ax.get_visible() and ax.get_xlabel()]
        assert axes
        for ax in axes:
            for text in (ax.get_xlabel(), ax.get_ylabel(), ax.get_title()):
                assert "\n" not in text and len(text) <= plot.TITLE_CHARS, text
            legend = ax.get_legend()
            if legend and recipe.plot.get("hue") in ("control", "domain"):     # choices by name, not code
                assert {t.get_text() for t in legend.get_texts()} <= set(ds[recipe.plot["hue"]].values.tolist())
        plt.close(fig)


def _physical_meanings(scen):
    """Parameters of the scenario whose physical-mode long_name still says what they are divided by."""
    return [p.name for p in scen.parameters if p.units_in(True) != p.units_in(False)
            and ("divided by" in p.meaning_in(True) or "normalised mode" in p.meaning_in(True))]


@pytest.mark.parametrize("name", list(REGISTRY))
def test_physical_long_names_do_not_say_divided_by(name):
    assert _physical_meanings(REGISTRY[name]) == []


def test_a_physical_wavy_file_says_metres_from_the_centre():
    ds = sf.generate({"scenario": "wavy", "parameters": {"E": 2e11, "nu": 0.3, "lambda_1": 1e-3,
                                                         "amplitudes": [1e-6], "wavenumbers": [1], "a": 0.3,
                                                         "x": [0.0, 1e-4]}, "output": {"variables": ["pressure"]}})
    for name in ("x", "amplitudes"):
        for text in (ds[name].attrs["long_name"], ds[name].attrs["description"]):
            assert ds[name].attrs["units"] == "m" and "divided by" not in text and "/ a" not in text
            assert "normalised" not in text
