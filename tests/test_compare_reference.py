"""compare's reference is computed at once, in NumPy (comparison._evaluate_now through
procedural.evaluate), not through a dask graph: its values, coordinates and attributes are those of
the lazy dataset `sf.generate` gives for the same recipe, bit for bit, whether the nodes are one
chunk or many evaluated on several threads; and a cold `stressfields compare` imports neither
dask.array nor dask.distributed, while xarray still knows a dask array once one exists."""
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import stressfields as sf
from stressfields.build import build
from stressfields.comparison import CompareError, _evaluate_now
from stressfields.recipe import load

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "fe_hertz_mindlin"

RNG = np.random.default_rng(20261128)
N = 40


def _nodes(*names, depth=True):
    """Scattered nodes, with the singular places among them: the centre, the contact edge r = a on the
    surface, points on the surface and below it."""
    out = {}
    for name in names:
        values = RNG.uniform(-2.0, 2.0, N)
        if name in ("z",):
            values = np.abs(values) if depth else np.zeros(N)
            values[:10] = 0.0
        out[name] = values
    first = names[0]
    out[first][:3] = [0.0, 1.0, -1.0]           # centre and contact edge (r = a, with y = z = 0)
    for name in names[1:]:
        out[name][:3] = 0.0
    return out


CASES = {
    "hertz_mindlin_physical": {
        "scenario": "parabolic", "parameters": {"E": 210e9, "nu": 0.3, "R": 0.01, "delta": 1e-6, "mu": 0.3,
                                                "ux0": 0.25},
        "points": {k: v * 1e-4 for k, v in _nodes("x", "y", "z").items()},
        "output": {"variables": ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz", "u_z", "mean_pressure",
                                 "contact_radius", "stick_radius"]}},
    "cone_tip": {
        "scenario": "conical", "parameters": {"nu": 0.3, "mu": 0.2, "ux0": 0.25},
        "points": _nodes("x", "y", "z"),
        "output": {"variables": ["sigma_xx", "sigma_zz", "sigma_xz", "von_mises", "dpdz"]}},
    "wavy_indenter_auto": {
        "scenario": "wavy", "parameters": {"domain": "nonperiodic", "amplitudes": [0.5, 0.01], "wavenumbers": [1, 11],
                                           "a": 0.3, "nu": 0.3},
        "points": _nodes("x", "z"),
        "output": {"variables": ["sigma_xx", "sigma_zz", "sigma_xz", "tau_max"]}},
    "graded_normal": {
        "scenario": "graded_normal", "parameters": {"profile": "parabolic", "R": 0.02, "E0": 2e9, "c0": 1e-3,
                                                    "k": 0.0, "poisson": "holl_ratio", "contact_radius": 1e-3},
        "points": {"rho": np.abs(_nodes("rho")["rho"]), "z": np.abs(_nodes("z")["z"])},
        "output": {"variables": ["pressure", "sigma_zz", "sigma_rz", "tau_max"]}},
}


def _same(now, lazy):
    assert sorted(now.variables) == sorted(lazy.variables)
    for name, var in lazy.variables.items():
        mine = now.variables[name]
        assert mine.dims == var.dims and mine.dtype == var.dtype, name
        assert mine.values.tobytes() == var.values.tobytes(), name
        assert repr(mine.attrs) == repr(var.attrs), name
    moving = ("date_created", "history")        # the time the dataset was made
    assert repr({k: v for k, v in now.attrs.items() if k not in moving}) == \
        repr({k: v for k, v in lazy.attrs.items() if k not in moving})


@pytest.mark.parametrize("case", CASES, ids=str)
def test_reference_now_is_the_lazy_dataset_bit_for_bit(case):
    recipe = load(CASES[case])
    lazy = build(recipe).compute(scheduler="synchronous")
    now = build(recipe, evaluate_group=_evaluate_now)
    assert not any(hasattr(v.data, "dask") for v in now.variables.values())
    if case == "cone_tip":          # the tip's infinite stresses are compared too
        assert not np.all(np.isfinite(lazy["sigma_zz"].values))
    _same(now, lazy)
    # many chunks, evaluated on a pool of threads, put back in order
    _same(build(recipe, {"point": 7}, evaluate_group=_evaluate_now), lazy)


def test_a_field_along_another_dimension_is_refused_in_one_line():
    history = {"scenario": "axisymmetric_history",
               "parameters": {"profile": "paraboloid", "nu": 0.3, "mu": 0.3, "amplitude": 0.2,
                              "ux0_history": [0.0, 0.5, 1.0]}}
    with pytest.raises(CompareError, match=r"along step as well as the nodes") as err:
        sf.compare(history, {"x": [0.1, 0.3], "y": [0.0, 0.1], "z": [0.2, 0.4], "sigma_xx": [0.5, 0.1]})
    assert "\n" not in str(err.value)


PROBE = """
import sys
from stressfields.cli import main
code = main(["compare", {recipe!r}, {nodes!r}, "-o", {out!r}, "--no-plot"])
print(code, sorted(m for m in ("dask.array", "distributed", "dask.distributed", "matplotlib", "meshio")
                   if m in sys.modules))
import dask.array as da
import xarray as xr
from xarray.namedarray import pycompat
lazy = xr.DataArray(da.ones(4, chunks=2), dims="point")
print(lazy.chunks, pycompat.array_type("dask") == (da.Array,), pycompat.mod_version("dask").major >= 2022,
      float((lazy * 2).sum()))
"""


def test_a_cold_compare_imports_no_dask_array_and_xarray_still_knows_dask(tmp_path):
    out = tmp_path / "report"
    done = subprocess.run([sys.executable, "-c", PROBE.format(recipe=str(EXAMPLE / "recipe.toml"),
                                                              nodes=str(EXAMPLE / "nodes.csv"), out=str(out))],
                          cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.strip().splitlines()
    assert lines[-2] == "0 []", done.stdout
    assert lines[-1] == "((2, 2),) True True 8.0"
    assert (out / "comparison.nc").is_file() and (out / "report.json").is_file()
