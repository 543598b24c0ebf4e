"""Every recipe's output is CF-1.8 clean; data_schema.md and the README's quick start stay true."""
import json
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import stressfields as sf
from stressfields.scenarios import REGISTRY
from stressfields.scenarios.base import LABEL_CHARS, PLOT_LABEL_CHARS
from stressfields.scenarios.scales import Scale
from stressfields.schema import document

ROOT = Path(__file__).resolve().parents[1]
RECIPES = sorted((ROOT / "recipes").glob("*.toml"))


@pytest.fixture
def outputs(recipe_outputs):
    """Every recipe's NetCDF output (tests/conftest.py: made once per test process)."""
    return recipe_outputs


def cf_failures(path: Path) -> list:
    from compliance_checker.runner import CheckSuite, ComplianceChecker

    CheckSuite.load_all_available_checkers()
    report = path.with_suffix(".cf.json")
    _, checker_errors = ComplianceChecker.run_checker(str(path), ["cf:1.8"], 0, "lenient",
                                                      output_filename=str(report), output_format="json")
    result = json.loads(report.read_text())["cf:1.8"]
    failures = [("checker", "exceptions while checking", [])] if checker_errors else []
    for level in ("high_priorities", "medium_priorities", "low_priorities"):
        for item in result.get(level, []):
            if item["value"][0] < item["value"][1]:
                failures.append((level, item["name"], item["msgs"]))
    return failures


def dimension_order_only(path: Path, failures: list) -> bool:
    """Whether ``failures`` are only CF §2.4's recommended dimension order, on a file that sweeps the
    depth z together with x, y or the radius rho: compliance-checker sees z as vertical (``positive``)
    but cannot see that x, y and rho are horizontal without ``axis = "X"/"Y"``, which ParaView reads as
    longitude and latitude (cf.py); the order stored is z, y, x (z, rho), the one recommended."""
    with xr.open_dataset(path) as ds:
        sweeps_depth = "z" in ds.dims and bool({"x", "y", "rho"} & set(ds.dims))
    return sweeps_depth and [name for _, name, _ in failures] == ["§2.4 Dimensions"]


@pytest.mark.parametrize("recipe", RECIPES, ids=lambda p: p.stem)
def test_recipe_output_is_cf_clean(outputs, recipe):
    path = outputs / f"{recipe.stem}.nc"
    failures = cf_failures(path)
    assert failures == [] or dimension_order_only(path, failures), failures
    with xr.open_dataset(path) as ds:
        for name, var in ds.variables.items():
            assert "long_name" in var.attrs, name
            assert "units" in var.attrs or "flag_values" in var.attrs or var.dtype.kind in "OSU", name


def acdd_high_failures(path: Path) -> list[str]:
    """The messages of the ACDD-1.3 high-priority items ``path`` does not meet."""
    from compliance_checker.runner import CheckSuite, ComplianceChecker

    CheckSuite.load_all_available_checkers()
    report = path.with_suffix(".acdd.json")
    ComplianceChecker.run_checker(str(path), ["acdd:1.3"], 0, "lenient", output_filename=str(report),
                                  output_format="json")
    result = json.loads(report.read_text())["acdd:1.3"]
    return [msg for item in result.get("high_priorities", []) if item["value"][0] < item["value"][1]
            for msg in item["msgs"]]


@pytest.mark.parametrize("recipe", RECIPES, ids=lambda p: p.stem)
def test_readers_find_axes_short_labels_and_acdd(outputs, recipe):
    pytest.importorskip("cf_xarray")
    path = outputs / f"{recipe.stem}.nc"
    # standard_name is the one ACDD high-priority item that does not apply (data_schema.md says why)
    assert [m for m in acdd_high_failures(path) if "standard_name" not in m] == []
    with xr.open_dataset(path) as ds:
        assert ds.attrs["Conventions"] == "CF-1.8, ACDD-1.3"
        assert ds.attrs["id"] == ds.attrs["stressfields_content_sha256"]
        for key in ("summary", "keywords", "license", "creator_name", "date_created", "product_version", "history"):
            assert ds.attrs[key], key
        axes = {"x": "X", "y": "Y", "z": "Z"}
        for name, axis in axes.items():
            if name in ds.variables:
                assert ds.cf[axis].name == name
                assert "axis" not in ds[name].attrs or name == "z"      # ParaView: x, y stay planar
        if "z" in ds.variables:
            assert ds.cf["Z"].attrs["positive"] == "down"
        for name, var in ds.variables.items():
            if var.dtype.kind not in "OSU":
                assert len(var.attrs["long_name"]) <= LABEL_CHARS, (name, var.attrs["long_name"])
                assert var.attrs["description"] and var.attrs["coverage_content_type"], name


def test_every_declaration_has_a_short_label():
    """Each parameter and variable of every scenario has a long_name of at most LABEL_CHARS characters
    in both modes: its label, or its meaning where that is short enough."""
    problems = []
    for scen in REGISTRY.values():
        for kind, items in (("Parameter", scen.parameters), ("Variable", scen.variables)):
            for item in items:
                for physical in (False, True):
                    label, shown = item.label_in(physical), item.plot_label(physical)
                    if len(label) > LABEL_CHARS or len(shown) > PLOT_LABEL_CHARS:
                        problems.append(f"{scen.name}: {kind}({item.name!r}) needs a shorter label= (at most "
                                        f"{LABEL_CHARS} characters, and {PLOT_LABEL_CHARS} with its units, the width "
                                        f"at which xarray wraps plot labels): {shown!r}")
                    scale = getattr(item, "scale", None)
                    if scale is not None and not (isinstance(scale, Scale) and scale.symbol and scale.text):
                        problems.append(f"{scen.name}: scale {scale!r} of {item.name!r} must be a Scale with a "
                                        "symbol and a text (scenarios.scales)")
    assert problems == [], "\n".join(problems)


def test_default_plot_labels_fit_one_line():
    plt = pytest.importorskip("matplotlib.pyplot")
    ds = sf.generate({"scenario": "conical", "parameters": {"mu": [0.0, 0.3], "x": {"start": -2, "stop": 2, "num": 9},
                                                            "z": [0.0, 0.5]},
                      "output": {"variables": ["sigma_xx", "tau_max", "dpdz", "stick_radius"]}})
    for name in ("sigma_xx", "tau_max", "dpdz", "stick_radius"):
        fig, ax = plt.subplots(figsize=(4.6, 3.8))
        da = ds[name]
        keep = "x" if "x" in da.dims else da.dims[0]
        da.isel({d: -1 for d in da.dims if d != keep}).plot(ax=ax)
        for text in (ax.get_xlabel(), ax.get_ylabel()):
            assert "\n" not in text and len(text) <= PLOT_LABEL_CHARS, text
        plt.close(fig)


def test_date_created_honours_source_date_epoch_and_stays_out_of_the_hash(tmp_path, monkeypatch):
    from stressfields.output.formats import file_hash

    recipe = {"scenario": "conical", "parameters": {"x": [0.0, 0.5]}, "output": {"variables": ["sigma_xx"]}}
    paths = []
    for epoch in ("86400", "1700000000"):
        monkeypatch.setenv("SOURCE_DATE_EPOCH", epoch)
        paths.append(sf.write(sf.generate(recipe), tmp_path / f"{epoch}.nc"))
    with xr.open_dataset(paths[0]) as one, xr.open_dataset(paths[1]) as two:
        assert one.attrs["date_created"] == "1970-01-02T00:00:00Z" and two.attrs["date_created"] != one.attrs[
            "date_created"]
        assert one.attrs["history"].startswith("1970-01-02T00:00:00Z")
        assert one.attrs["id"] == two.attrs["id"]
    assert file_hash(paths[0]) == file_hash(paths[1]) == (one.attrs["id"],) * 2


def test_a_file_written_before_the_acdd_attributes_still_verifies(tmp_path):
    """A file in the form of earlier versions (no id, no date_created): its stored hash verifies."""
    import netCDF4

    from stressfields.output.formats import verify
    from stressfields.output.hashing import ATTR
    from stressfields.output.netcdf import stamp

    path = sf.write(sf.generate({"scenario": "conical", "parameters": {"x": [0.5]}}), tmp_path / "old.nc")
    with netCDF4.Dataset(path, "a") as nc:
        for key in ("id", "date_created", "summary", "keywords", ATTR):
            nc.delncattr(key)
        nc.setncattr("Conventions", "CF-1.8")
    digest = stamp(path)                    # hashed as the earlier version hashed it
    with netCDF4.Dataset(path, "a") as nc:
        nc.delncattr("id")
    assert verify(path) == digest


def test_paraview_draws_planar_bounds_with_depth_downwards(tmp_path):
    pytest.importorskip("vtk")
    ds = sf.generate({"scenario": "conical", "parameters": {"x": {"start": -1.5, "stop": 1.5, "num": 7},
                                                            "y": [0.0, 0.5], "z": [0.0, 0.5]},
                      "output": {"variables": ["sigma_xx"]}})
    path = sf.write(ds, tmp_path / "c.nc")
    # VTK in a process of its own: its NetCDF and HDF5 libraries beside netCDF4's and h5py's in one
    # process made later HDF5 writes fail ("NetCDF: HDF error") and crashed a test worker
    code = ("import json, sys, vtk; vtk.vtkObject.GlobalWarningDisplayOff(); r = vtk.vtkNetCDFCFReader(); "
            "r.SetFileName(sys.argv[1]); r.UpdateMetaData(); r.Update(); print(json.dumps(r.GetOutput().GetBounds()))")
    done = subprocess.run([sys.executable, "-c", code, str(path)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    # spherical mode (the default) would put x, y on the unit sphere: bounds within [-1, 1]
    assert json.loads(done.stdout) == pytest.approx([-1.5, 1.5, 0.0, 0.5, -0.5, 0.0])


#: VTK's CF reader in a process of its own (see above): per file and set of dimensions, what it builds
VTK_PROBE = """
import json, sys, vtk
vtk.vtkObject.GlobalWarningDisplayOff()
out = []
for path, dims in json.loads(sys.stdin.read()):
    reader = vtk.vtkNetCDFCFReader()
    reader.SetFileName(path)
    reader.SphericalCoordinatesOff()
    reader.UpdateMetaData()
    offered = [reader.GetVariableDimensions().GetValue(i)
               for i in range(reader.GetVariableDimensions().GetNumberOfValues())]
    if dims is not None:
        reader.SetDimensions(dims)
    reader.Update()
    grid = reader.GetOutput()
    data = grid.GetPointData()
    out.append([path, dims, dims is None or dims in offered, grid.GetNumberOfPoints(), grid.GetNumberOfCells(),
                sorted(data.GetArrayName(i) for i in range(data.GetNumberOfArrays()))])
print(json.dumps(out))
"""


def test_paraview_opens_every_recipe_output_with_its_fields_on_their_grids(outputs):
    """VTK's NetCDF CF reader (ParaView's) opens every recipe's output (as ParaView first shows it, and
    on each set of dimensions the fields lie on) without error: a grid of as many points as the
    dimensions give (the product of their sizes) and cells (the product of size - 1 over the
    dimensions longer than one; a single point is one vertex), every field on those dimensions a point
    array of it."""
    pytest.importorskip("vtk")
    import netCDF4

    jobs, expected = [], {}
    for recipe in RECIPES:
        path = str(outputs / f"{recipe.stem}.nc")
        jobs.append([path, None])
        with netCDF4.Dataset(path) as nc:
            fields = {}
            for name, var in nc.variables.items():
                if var.dimensions and name not in nc.dimensions and var.dtype != np.dtype("S1"):
                    fields.setdefault(var.dimensions, []).append(name)
            for dims, names in fields.items():
                sizes = [len(nc.dimensions[d]) for d in dims]
                key = "(" + ", ".join(dims) + ")"
                cells = int(np.prod([n - 1 for n in sizes if n > 1])) if max(sizes) > 1 else 1
                expected[(path, key)] = (int(np.prod(sizes)), cells, sorted(names))
                jobs.append([path, key])
    done = subprocess.run([sys.executable, "-c", VTK_PROBE], input=json.dumps(jobs), capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr
    results = json.loads(done.stdout)
    assert len(results) == len(jobs)
    for path, dims, offered, points, cells, arrays in results:
        if dims is None:            # as ParaView first shows the file: some grid, read without error
            assert points >= 1, path
            continue
        want_points, want_cells, names = expected[(path, dims)]
        assert offered, (path, dims)
        assert (points, cells) == (want_points, want_cells), (path, dims)
        assert set(names) <= set(arrays), (path, dims, sorted(set(names) - set(arrays)))


def test_schema_file_is_in_sync():
    assert (ROOT / "data_schema.md").read_text() == document(), \
        "data_schema.md is stale: run `stressfields schema > data_schema.md`"


def quick_start() -> list[str]:
    text = (ROOT / "README.md").read_text()
    section = re.search(r"^## Quick start\n(.*?)(?=^## )", text, re.S | re.M).group(1)
    block = re.search(r"```(?:\w+)?\n(.*?)```", section, re.S).group(1)
    return [line for line in block.splitlines() if line.strip()]


def test_readme_quick_start_is_two_commands_and_ci_runs_the_second():
    commands = quick_start()
    assert len(commands) == 2
    assert "pytest" in commands[1] and "stressfields run" in commands[0]
    ci = (ROOT / ".ci" / "run").read_text()
    assert "Quick start" in ci  # .ci/run reads the test command from the README itself


def test_module_entry_point():
    done = subprocess.run([sys.executable, "-m", "stressfields", "list"], capture_output=True, text=True)
    assert done.returncode == 0 and "conical" in done.stdout


def test_accuracy_contract_is_written_once_and_quoted():
    """The contract lives in cf.ACCURACY_CONTRACT; the README and the schema quote it verbatim and
    every file carries it."""
    from stressfields.cf import ACCURACY_CONTRACT
    from stressfields.schema import document

    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert ACCURACY_CONTRACT in readme
    assert ACCURACY_CONTRACT in document()
    ds = sf.generate({"scenario": "conical", "parameters": {"x": [0.5]}})
    assert ds.attrs["stressfields_accuracy_contract"] == ACCURACY_CONTRACT
