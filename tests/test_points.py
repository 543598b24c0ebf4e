"""The [points] table: the user's own points (mesh nodes) along one dimension `point`, after the swept ones.

Values at a point equal the grid's at the same coordinates bit for bit (the scenario receives the
columns as arrays along the block's last axis), and agree with an independent closed form.
"""
import hashlib
import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import stressfields as sf
from stressfields.build import build
from stressfields.build import estimate as build_estimate
from stressfields.recipe import MAX_POINTS, MAX_SWEEP, RecipeError, load

NU = 0.3
CONE = {"scenario": "conical", "parameters": {"nu": NU, "ux0": 0.25}}


def problems(data) -> str:
    with pytest.raises(RecipeError) as info:
        load(data)
    return " | ".join(info.value.problems)


def at_points(grid: xr.Dataset, ds: xr.Dataset, name: str, columns) -> np.ndarray:
    """The grid's values of ``name`` at the points of ``ds`` (vectorised selection), in ds's dim order."""
    sel = {c: xr.DataArray(ds[c].values, dims="point") for c in columns if c in grid[name].dims}
    return grid[name].sel(sel).transpose(*ds[name].dims).values


def test_toml_table_gives_one_point_dimension_last(tmp_path):
    path = tmp_path / "p.toml"
    path.write_text('scenario = "conical"\n[parameters]\nnu = 0.3\nmu = [0.0, 0.2]\nux0 = 0.25\n'
                    "[points]\nx = [0.1, 0.5, 2.0]\ny = [0.0, 0.3, -1.0]\n")
    r = load(path)
    # columns in declaration order (y before x for this scenario)
    assert r.swept == ("mu",) and r.points == ("y", "x") and r.dims == ("mu", "point")
    assert r.shape == {"mu": 2, "point": 3} and r.size == 6
    ds = build(r)
    assert ds.sigma_xx.dims == ("mu", "point")
    for c, v in (("x", [0.1, 0.5, 2.0]), ("y", [0.0, 0.3, -1.0])):
        assert ds[c].dims == ("point",) and ds[c].values.tolist() == v
        assert ds[c].attrs["units"] == "1" and "long_name" in ds[c].attrs
    assert "featureType" not in ds.attrs          # mu is a dimension too: a grid of point sets


@pytest.mark.parametrize("scenario, params, columns", [
    ("conical", {"nu": NU, "ux0": 0.25, "mu": [0.0, 0.1, 0.4]}, {"x": [1.3, -0.2, 0.0, 1.0, -0.2, 3.0],
                                                                  "y": [0.0, 0.7, 0.0, 0.0, 0.7, -2.0]}),
    # below the surface: the interior quadrature routes
    ("parabolic", {"nu": NU, "mu": 0.3, "ux0": 0.1}, {"x": [-1.3, 0.4, 0.0, 0.4], "y": [0.2, 0.2, 0.0, -0.5],
                                                      "z": [0.7, 0.2, 1.5, 0.7]}),
    # any sweepable parameter is a column: material and load vary from point to point
    ("conical", {"ux0": 0.25, "y": 0.1}, {"x": [0.3, 0.9, 1.4], "nu": [0.0, 0.3, 0.5], "mu": [0.1, 0.3, 0.2]}),
])
def test_points_equal_the_grid_bit_for_bit(scenario, params, columns):
    ds = sf.generate({"scenario": scenario, "parameters": params, "points": columns}).compute()
    # the grid over the distinct coordinates of each column (a sweep must be ordered and distinct)
    grid_params = {**params, **{c: sorted(set(v)) for c, v in columns.items()}}
    grid = sf.generate({"scenario": scenario, "parameters": grid_params}).compute()
    assert set(ds.data_vars) == set(grid.data_vars)
    for name in ds.data_vars:
        assert ds[name].dims == tuple(d for d in grid[name].dims if d not in columns) + (
            ("point",) if set(columns) & set(grid[name].dims) else ())
        np.testing.assert_array_equal(ds[name].values, at_points(grid, ds, name, columns), err_msg=name)


def test_hertz_axis_points_against_johnson():
    """Unordered, repeated points on the axis against Johnson (1985) eq. 3.63, per p0 = (3/2) p_m:
    sigma_zz = -1/(1+z^2), sigma_rr = -(1+nu)(1 - z atan(1/z)) + 1/(2(1+z^2)), in extended precision."""
    z = np.array([2.5, 0.3, 40.0, 0.01, 0.3, 1.0])
    ds = sf.generate({"scenario": "parabolic", "parameters": {"nu": NU},
                      "points": {"x": np.zeros(z.size), "y": np.zeros(z.size), "z": z},
                      "output": {"variables": ["sigma_xx", "sigma_zz"]}}).compute()
    assert ds.attrs["featureType"] == "point" and ds.sigma_zz.dims == ("point",)
    zl = z.astype(np.longdouble)
    zz = -1 / (1 + zl * zl)
    rr = -(1 + NU) * (1 - zl * np.arctan(1 / zl)) + 0.5 / (1 + zl * zl)
    np.testing.assert_allclose(ds.sigma_zz.values, (1.5 * zz).astype(float), rtol=1e-12)
    np.testing.assert_allclose(ds.sigma_xx.values, (1.5 * rr).astype(float), rtol=1e-12)
    assert (ds.validity.values == 0).all()
    assert ds.sigma_xx.values[1] == ds.sigma_xx.values[4]      # a repeated point, the same value


def test_chunks_along_point_and_columns_as_arrays():
    rng = np.random.default_rng(3)
    cols = {"x": rng.uniform(-2, 2, 1000), "y": rng.uniform(-2, 2, 1000)}
    whole = sf.generate({**CONE, "points": cols}).compute()
    cut = sf.generate({**CONE, "points": {k: list(v) for k, v in cols.items()},
                       "output": {"chunks": {"point": 128}}})
    assert cut.sigma_xx.chunks == ((128,) * 7 + (104,),)
    xr.testing.assert_identical(cut.compute().drop_attrs(), whole.drop_attrs())
    as_lists = {k: list(v) for k, v in cols.items()}
    assert load({**CONE, "points": cols}).sha256 == load({**CONE, "points": as_lists}).sha256


def test_canonical_form_keeps_the_hash_of_recipes_without_points():
    plain = load({**CONE, "parameters": {**CONE["parameters"], "x": [0.5]}})
    assert "points" not in json.loads(plain.canonical) and plain.points == ()
    r = load({**CONE, "points": {"x": [0.5, 0.5], "y": [0.0, 0.1]}})
    canon = json.loads(r.canonical)
    # the columns by their digest (the file holds the values as coordinates): names, count, SHA-256
    # of each name and its little-endian float64 values, in sorted order
    digest = hashlib.sha256(b"x\0" + np.array([0.5, 0.5], "<f8").tobytes()
                            + b"y\0" + np.array([0.0, 0.1], "<f8").tobytes()).hexdigest()
    assert canon["points"] == {"columns": ["x", "y"], "n": 2, "sha256": digest} and "x" not in canon["parameters"]


@pytest.mark.parametrize("points, words", [
    ({"x": [0.1, 0.5, 2.0], "mu": [0.3, -0.2, 0.1]}, ["points.mu[1] = -0.2", "[0, 10]"]),
    ({"x": np.array([0.1, np.nan])}, ["points.x[1] = nan", "finite"]),
    ({"x": [0.1, "far"]}, ["points.x[1] = 'far'", "a number", "got a str"]),
    ({"x": [0.1, True]}, ["points.x[1] = True"]),
    ({"x": [0.1, 0.5], "y": [0.0]}, ["one length", "x has 2", "y has 1"]),
    ({"x": []}, ["empty"]),
    ({"x": 0.5}, ["points.'x' = 0.5 must be a list"]),
    ({"x": [0.5], "friction": [0.1]}, ["unknown parameter 'friction'", "allowed: nu, mu"]),
    ({"x": [0.5], "muu": [0.1]}, ["did you mean 'mu'?"]),
])
def test_bad_points_are_named(points, words):
    msg = problems({**CONE, "points": points})
    for w in words:
        assert w in msg, (w, msg)
    assert "missing parameter" not in msg           # a refused column is said once


def test_points_conflicts_and_other_tables():
    assert "also given in [parameters]" in problems({**CONE, "parameters": {"nu": NU, "x": 0.5},
                                                     "points": {"x": [0.1]}})
    assert "'theta' cannot be a points column (a single-value parameter)" in problems(
        {**CONE, "points": {"x": [0.1], "theta": [0.1]}})
    assert "'control' cannot be a points column (a choice parameter)" in problems(
        {"scenario": "graded_adhesive", "parameters": {}, "points": {"control": ["fixed_load"]}})
    assert "'points' must be a table" in problems({**CONE, "points": [0.1, 0.2]})
    assert "[points] has no column" in problems({**CONE, "parameters": {"nu": NU, "x": 0.5}, "points": {}})
    assert "not available with [points]" in problems({**CONE, "points": {"x": [0.1, 0.2]}, "plot": {"x": "x"}})
    msg = problems({**CONE, "points": {"x": [0.1]}, "output": {"chunks": {"x": 1}}})
    assert "'x' is not a swept dimension" in msg and "swept: point" in msg


def test_sizes_are_bounded_before_any_work():
    class Huge(list):           # a column claiming more values than allowed: only its length is read
        def __len__(self):
            return MAX_SWEEP + 1

        def __iter__(self):
            raise AssertionError("a refused column was read")

    assert f"at most {MAX_SWEEP:,}" in problems({**CONE, "points": {"x": Huge()}})
    n = MAX_POINTS // MAX_SWEEP + 1
    msg = problems({**CONE, "parameters": {"nu": {"start": 0.0, "stop": 0.5, "num": n}},
                    "points": {"x": np.zeros(MAX_SWEEP)}})
    assert "point=10,000,000" in msg and "at most" in msg


def test_estimate_cuts_the_points():
    rng = np.random.default_rng(5)
    r = load({**CONE, "points": {"x": rng.uniform(-2, 2, 4000), "y": rng.uniform(-2, 2, 4000)}})
    est = build_estimate(r, sample_points=1000)
    assert est["dims"] == {"point": 4000} and est["points"] == 4000 and est["sample_points"] == 1000


@pytest.mark.parametrize("suffix", [".nc", ".zarr"])
def test_written_file_round_trips(tmp_path, suffix):
    rec = {**CONE, "parameters": {**CONE["parameters"], "mu": [0.0, 0.3]},
           "points": {"x": [0.1, 0.5, 2.0, 0.5], "y": [0.0, 0.3, -1.0, 0.3]}}
    ds = sf.generate(rec).compute()
    path = sf.write(sf.generate(rec), tmp_path / f"p{suffix}")
    with sf.open_dataset(path) as back:
        assert back.sigma_xx.dims == ("mu", "point") and back.x.dims == ("point",)
        np.testing.assert_array_equal(back.sigma_xx.values, ds.sigma_xx.values)


@pytest.mark.parametrize("params, feature", [({"mu": 0.2}, "point"), ({"mu": [0.0, 0.2]}, None)],
                         ids=["only_points", "points_and_sweep"])
def test_cf_compliance(tmp_path, params, feature):
    pytest.importorskip("compliance_checker")
    from test_cf_and_docs import cf_failures

    rec = {**CONE, "parameters": {**CONE["parameters"], **params},
           "points": {"x": [0.1, 0.5, 2.0, 0.5], "y": [0.0, 0.3, -1.0, 0.3]}}
    path = Path(sf.write(sf.generate(rec), tmp_path / "p.nc"))
    assert cf_failures(path) == []
    with xr.open_dataset(path, decode_coords=False) as ds:
        assert ds.attrs.get("featureType") == feature
        # CF auxiliary coordinates: each field names the columns it is located by
        assert {"x", "y"} <= set(ds.sigma_xx.attrs["coordinates"].split())


def test_graded_tangential_columns_pair_the_material_point_by_point():
    """(k, nu) on the Holl ratio nu = 1/(2+k), as [points] columns, decouple at every point and are
    accepted, though the grid of the same columns (k crossed with every nu) would not decouple.
    The stick radius is held against the MDR line-load integral (Hess & Popov 2016, eq. 43) by scipy."""
    from scipy import integrate

    def fx_of(s, k):        # F_x/(mu F_N) at stick radius c = s a, paraboloid, independent of eq. (51)
        u = lambda x: 1 - x * x
        slip = integrate.quad(lambda x: x ** k * u(x), s, 1, epsabs=0, epsrel=1e-13)[0]
        whole = integrate.quad(lambda x: x ** k * u(x), 0, 1, epsabs=0, epsrel=1e-13)[0]
        return (u(s) * s ** (1 + k) / (1 + k) + slip) / whole

    k = np.array([0.0, 0.2, 0.5, 0.9])
    nu = 1.0 / (2.0 + k)
    s = np.array([0.3, 0.8, 0.5, 0.65])
    fx = np.array([fx_of(si, ki) for si, ki in zip(s, k)])
    base = {"scenario": "graded_tangential",
            "parameters": {"body2": "rigid", "E0": 1e9, "R": 0.05, "contact_radius": 1e-3}}
    ds = sf.generate({**base, "points": {"k": k, "nu": nu, "fx": fx}}).compute()
    assert ds.coupling.dims == ("point",) and (ds.coupling.values == 0).all() and (ds.validity.values == 0).all()
    np.testing.assert_allclose(ds.stick_radius.values, s, rtol=1e-9)
    for i in range(k.size):         # each point: the run at its own k with nu = 1/(2+k) set by the scenario
        one = sf.generate({**base, "parameters": {**base["parameters"], "k": k[i], "fx": fx[i],
                                                  "poisson": "holl_ratio"}}).compute()
        for name in ("stick_radius", "tangential_displacement", "normal_force", "shear_traction"):
            np.testing.assert_allclose(ds[name].values[i], one[name].values, rtol=1e-15, err_msg=name)
    grid = problems({**base, "parameters": {**base["parameters"], "k": k.tolist(), "nu": sorted(nu.tolist())}})
    assert "do not decouple" in grid
    msg = problems({**base, "points": {"k": k, "nu": nu[::-1]}})
    assert "do not decouple" in msg and "at point 0" in msg


def test_graded_tangential_sweep_beside_material_columns():
    """A swept E0 (its own axis) beside (k, nu, nu_2) columns (one shared axis): every combination of
    E0 with each point decouples; a column off the Holl ratio is named by its point."""
    k = np.array([0.1, 0.4, 0.7])
    holl = 1.0 / (2.0 + k)
    base = {"scenario": "graded_tangential",
            "parameters": {"body2": "elastic", "E0": [1e9, 3e9], "E0_2": 2e9, "R": 0.05, "contact_radius": 1e-3,
                           "fx": 0.5}}
    ds = sf.generate({**base, "points": {"k": k, "nu": holl, "nu_2": holl}}).compute()
    assert ds.coupling.dims == ("E0", "point") and (ds.coupling.values == 0).all()
    off = holl.copy()
    off[2] = 0.3
    msg = problems({**base, "points": {"k": k, "nu": holl, "nu_2": off}})
    assert "do not decouple" in msg and "at point 2" in msg and "nu_2 = 0.3" in msg
