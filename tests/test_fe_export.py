"""`stressfields export FILE -o OUT.vtu` (stressfields/fe/vtu.py): a grid output as structured cells
and a [points] output as vertices read back in meshio with the dataset's bounds (depth drawn as -z),
every array at the right node (checked against the NetCDF by coordinates, not by index), the units
in the array names, and the stress as one tensor in the drawn frame."""
import numpy as np
import pytest
import xarray as xr

from stressfields.cli import main

meshio = pytest.importorskip("meshio")

GRID = """scenario = "parabolic"
[parameters]
nu = 0.3
mu = 0.2
ux0 = 0.1
y = 0.25
x = { start = -2.0, stop = 2.0, num = 9 }
z = { start = 0.0, stop = 1.5, num = 4 }
"""
POINTS = """scenario = "parabolic"
[parameters]
nu = 0.3
[points]
x = [0.1, 0.5, -0.3]
y = [0.0, 0.2, 0.4]
z = [0.0, 0.3, 1.2]
"""


def _export(tmp_path, name, recipe):
    (tmp_path / f"{name}.toml").write_text(recipe)
    assert main(["run", str(tmp_path / f"{name}.toml"), "-d", str(tmp_path), "-q"]) == 0
    assert main(["export", str(tmp_path / f"{name}.nc"), "-o", str(tmp_path / f"{name}.vtu")]) == 0
    return xr.open_dataset(tmp_path / f"{name}.nc"), meshio.read(tmp_path / f"{name}.vtu")


def test_grid_as_quads_depth_down_with_a_tensor(tmp_path):
    ds, mesh = _export(tmp_path, "grid", GRID)
    with ds:
        assert [c.type for c in mesh.cells] == ["quad"] and len(mesh.cells[0].data) == 8 * 3
        assert mesh.points.min(axis=0) == pytest.approx([-2.0, 0.25, -1.5])
        assert mesh.points.max(axis=0) == pytest.approx([2.0, 0.25, 0.0])
        tensor = mesh.point_data["stress [1] (z up)"]
        assert tensor.shape == (9 * 4, 9)
        for k in (0, 7, 20, 35):                    # each node's values where the NetCDF has them
            x, y, z = mesh.points[k]
            here = ds.sel(x=x, z=-z, method="nearest")
            assert float(here.x) == pytest.approx(x) and float(here.z) == pytest.approx(-z)
            assert mesh.point_data["sigma_xx [1]"][k] == float(here.sigma_xx)
            t = tensor[k].reshape(3, 3)
            np.testing.assert_array_equal(t, t.T)
            assert t[0, 2] == -float(here.sigma_xz) and t[1, 2] == -float(here.sigma_yz)   # z up
            assert t[2, 2] == float(here.sigma_zz) and t[0, 1] == float(here.sigma_xy)


def test_points_as_vertices(tmp_path):
    ds, mesh = _export(tmp_path, "pts", POINTS)
    with ds:
        assert [c.type for c in mesh.cells] == ["vertex"]
        np.testing.assert_array_equal(mesh.points, np.column_stack([ds.x, ds.y, -ds.z]))
        np.testing.assert_array_equal(mesh.point_data["sigma_zz [1]"], ds.sigma_zz.values)
        assert "stress [1] (z up)" in mesh.point_data


def test_a_sweep_is_refused_in_one_line(tmp_path, capsys):
    (tmp_path / "sweep.toml").write_text(GRID.replace("mu = 0.2", "mu = [0.1, 0.2]"))
    assert main(["run", str(tmp_path / "sweep.toml"), "-d", str(tmp_path), "-q"]) == 0
    assert main(["export", str(tmp_path / "sweep.nc"), "-o", str(tmp_path / "sweep.vtu")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "sweeps 'mu' (2 values)" in err
    assert not (tmp_path / "sweep.vtu").exists()
