"""Recipe -> lazy dataset -> NetCDF, end to end: laziness, chunking, atomic writes, physical mode."""
import os

import dask.array as dsa
import numpy as np
import pytest
import xarray as xr

import stressfields as sf
from stressfields import cli
from stressfields.scenarios import REGISTRY

CONE = {"scenario": "conical",
        "parameters": {"nu": 0.3, "ux0": 0.25, "mu": [0.0, 0.3, 0.4], "y": [0.0, 0.3],
                       "x": {"start": -1.5, "stop": 1.5, "num": 31}}}


def test_generate_is_lazy_and_chunked():
    ds = sf.generate({**CONE, "output": {"chunks": {"x": 10}}})
    assert isinstance(ds.sigma_xx.data, dsa.Array)
    assert ds.sigma_xx.dims == ("mu", "y", "x")
    assert ds.sigma_xx.chunks == ((3,), (2,), (10, 10, 10, 1))
    assert ds.stick_radius.dims == ("mu",)
    ds2 = sf.generate(CONE, chunks={"mu": 1})
    assert ds2.sigma_xx.chunks[0] == (1, 1, 1)
    # the chunking does not change a single bit
    a, b = ds.compute(), ds2.compute()
    for name in ("sigma_xx", "von_mises", "dpdz", "region"):
        np.testing.assert_array_equal(a[name].values, b[name].values)


def test_only_requested_variables_are_written():
    ds = sf.generate({**CONE, "output": {"variables": ["von_mises"]}})
    assert set(ds.data_vars) == {"von_mises", "validity"}


def test_scalar_parameters_become_scalar_coordinates():
    ds = sf.generate(CONE)
    assert ds.nu.ndim == 0 and float(ds.nu) == 0.3
    assert ds.nu.attrs["units"] == "1" and "Poisson" in ds.nu.attrs["long_name"]


def test_every_variable_has_units_and_long_name():
    for scen in REGISTRY.values():
        for var in scen.variables:
            assert var.long_name
            assert var.flag_values or var.units_in(False) and var.units_in(True)
        for par in scen.parameters:
            assert par.meaning and (par.choices or par.units)


def test_atomic_write_and_refusal(tmp_path):
    ds = sf.generate(CONE)
    target = tmp_path / "cone.nc"
    sf.to_netcdf(ds, target)
    with pytest.raises(sf.OutputError, match="refusing to overwrite"):
        sf.to_netcdf(ds, target)
    sf.to_netcdf(ds, target, overwrite=True)
    assert sorted(os.listdir(tmp_path)) == ["cone.nc"]
    back = xr.open_dataset(target)
    np.testing.assert_array_equal(back.sigma_xx.values, ds.sigma_xx.values)
    assert back.attrs["stressfields_recipe_sha256"] == ds.attrs["stressfields_recipe_sha256"]


def test_written_file_has_the_usual_permissions(tmp_path):
    """The temporary file is private while written; the published one follows the umask."""
    old = os.umask(0o027)
    try:
        sf.to_netcdf(sf.generate(CONE), tmp_path / "cone.nc")
    finally:
        os.umask(old)
    assert (tmp_path / "cone.nc").stat().st_mode & 0o777 == 0o640


def test_failure_mid_write_leaves_nothing(tmp_path, monkeypatch):
    ds = sf.generate(CONE)
    ds["boom"] = ds.sigma_xx.copy(data=ds.sigma_xx.data.map_blocks(_explode, dtype=float))
    with pytest.raises(RuntimeError, match="boom"):
        sf.to_netcdf(ds, tmp_path / "x.nc")
    assert os.listdir(tmp_path) == []


def _explode(block):
    raise RuntimeError("boom")


def test_unwritable_target(tmp_path):
    ds = sf.generate(CONE)
    with pytest.raises(sf.OutputError, match="does not exist"):
        sf.to_netcdf(ds, tmp_path / "no" / "such" / "dir.nc")


@pytest.mark.parametrize("scenario, geometry, e_star_over_pm", [
    # cone: p_m = E* tan(theta)/2 ; paraboloid: p_m = (2/3) * 2 E* a / (pi R)
    ("conical", {"theta": 0.2}, None),
    ("parabolic", {"R": 0.01}, None),
])
def test_physical_mode_matches_normalised(scenario, geometry, e_star_over_pm):
    nu, E, delta = 0.25, 70e9, 2e-6
    phys = sf.generate({"scenario": scenario, "parameters": {
        "E": E, "delta": delta, **geometry, "nu": nu, "mu": 0.3, "ux0": 0.2,
        "x": [-1e-4, -3e-6, 1e-6, 2.5e-6, 4e-5], "y": [0.0, 1e-6]},
        "output": {"variables": ["sigma_xx", "sigma_xz", "dpdz", "stick_radius", "contact_radius",
                                 "mean_pressure", "normal_force"]}}).compute()
    a = float(phys.contact_radius)
    pm = float(phys.mean_pressure)
    assert float(phys.normal_force) == pytest.approx(pm * np.pi * a ** 2, rel=1e-13)
    e_star = E / (1 - nu ** 2)
    if scenario == "conical":
        assert a == pytest.approx(delta / (np.pi / 2 * np.tan(0.2)), rel=1e-13)
        assert pm == pytest.approx(e_star * np.tan(0.2) / 2, rel=1e-13)
    else:
        assert a == pytest.approx(np.sqrt(0.01 * delta), rel=1e-13)
        assert pm == pytest.approx(2 / 3 * 2 * e_star * a / (np.pi * 0.01), rel=1e-13)
    norm = sf.generate({"scenario": scenario, "parameters": {
        "nu": nu, "mu": 0.3, "ux0": 0.2, "x": list(phys.x.values / a), "y": list(phys.y.values / a)},
        "output": {"variables": ["sigma_xx", "sigma_xz", "dpdz", "stick_radius"]}}).compute()
    np.testing.assert_allclose(phys.sigma_xx.values, norm.sigma_xx.values * pm, rtol=1e-12)
    np.testing.assert_allclose(phys.sigma_xz.values, norm.sigma_xz.values * pm, rtol=1e-12, atol=1e-12 * pm)
    np.testing.assert_allclose(phys.dpdz.values, norm.dpdz.values * pm / a, rtol=1e-12)
    assert float(phys.stick_radius) == pytest.approx(float(norm.stick_radius) * a, rel=1e-12)
    assert phys.sigma_xx.attrs["units"] == "Pa" and phys.dpdz.attrs["units"] == "Pa/m"
    assert phys.x.attrs["units"] == "m"


def test_singular_points_are_flagged_never_silent():
    ds = sf.generate({"scenario": "conical", "parameters": {
        "mu": [0.0, 0.2], "ux0": 0.25, "x": [-1.0, 0.0, 0.5, 1.0, 1.5], "y": 0.0}}).compute()
    fields = [ds[v] for v in ("sigma_xx", "sigma_zz", "von_mises", "sigma_1", "dpdz")]
    nonfinite = np.zeros(ds.validity.shape, bool)
    for f in fields:
        nonfinite |= ~np.isfinite(f.values)
    assert nonfinite.any(), "the cone tip x = 0 must be singular"
    np.testing.assert_array_equal(ds.validity.values != 0, nonfinite)
    tip = ds.sel(x=0.0)
    assert np.all(tip.validity.values > 0)
    assert ds.validity.attrs["flag_meanings"].split()[0] == "within_stated_accuracy"


def test_region_flags():
    ds = sf.generate({"scenario": "parabolic", "parameters": {
        "mu": [0.0, 0.3], "ux0": 0.25, "x": [0.1, 0.9, 1.2], "y": 0.0}}).compute()
    c = float(ds.stick_radius.sel(mu=0.3))
    assert c == pytest.approx(np.sqrt(16 / 51), rel=1e-14)
    assert ds.region.sel(mu=0.3).values.tolist() == [1, 2, 0]
    assert ds.region.sel(mu=0.0).values.tolist() == [3, 3, 0]


def test_cli_bad_recipe_exits_2_and_writes_nothing(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text('scenario = "conical"\n[parameters]\nnu = 0.7\nx = [0.1]\n')
    out = tmp_path / "o.nc"
    assert cli.main(["run", str(bad), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "nu = 0.7" in err and "[0, 0.5]" in err and "Traceback" not in err
    assert not out.exists()
    assert cli.main(["validate", str(bad)]) == 2


def test_cli_run_list_describe(tmp_path, capsys):
    good = tmp_path / "good.toml"
    good.write_text('scenario = "conical"\n[parameters]\nmu = [0.0, 0.3]\nux0 = 0.25\n'
                    'x = { start = -2.0, stop = 2.0, num = 41 }\n')
    out = tmp_path / "o.nc"
    assert cli.main(["run", str(good), "-o", str(out), "--chunks", "x=7", "-q"]) == 0
    assert out.exists()
    assert cli.main(["run", str(good), "-o", str(out), "-q"]) == 2          # no overwrite
    assert cli.main(["run", str(good), "-o", str(out), "-q", "--overwrite", "--chunks", "k=2"]) == 2
    assert cli.main(["validate", str(good)]) == 0
    assert cli.main(["list"]) == 0
    assert cli.main(["describe", "conical"]) == 0
    text = capsys.readouterr().out
    assert "conical" in text and "parabolic" in text and "| `nu` |" in text
    assert cli.main(["describe", "nothing"]) == 2


def test_cli_distributed_scheduler(tmp_path):
    distributed = pytest.importorskip("distributed")
    good = tmp_path / "good.toml"
    good.write_text('scenario = "parabolic"\n[parameters]\nmu = 0.3\nux0 = 0.25\n'
                    'x = { start = -2.0, stop = 2.0, num = 41 }\n')
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster:
        assert cli.main(["run", str(good), "-o", str(tmp_path / "d.nc"), "-q",
                         "--scheduler", cluster.scheduler_address]) == 0
    assert cli.main(["run", str(good), "-o", str(tmp_path / "t.nc"), "-q"]) == 0
    a, b = xr.open_dataset(tmp_path / "d.nc"), xr.open_dataset(tmp_path / "t.nc")
    np.testing.assert_array_equal(a.von_mises.values, b.von_mises.values)


def test_method_used_is_recorded_per_variable():
    closed = sf.generate(CONE)
    assert closed.sigma_xx.attrs["stressfields_method"] == "closed form"
    assert "stressfields_method" not in closed.region.attrs
    quad = sf.generate({"scenario": "axisymmetric", "parameters": {"n": 3.0, "x": [0.5]},
                        "method": {"rtol": 1e-8}})
    assert "quadrature" in quad.sigma_xx.attrs["stressfields_method"]
    assert "1e-08" in quad.sigma_xx.attrs["stressfields_accuracy"]
