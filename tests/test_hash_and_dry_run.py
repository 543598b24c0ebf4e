"""Content hash: equal across chunkings and schedulers, verified by `stressfields hash`; --dry-run."""
import netCDF4
import xarray as xr

from stressfields import cli
from stressfields.output.formats import file_hash
from stressfields.output.hashing import ATTR

RECIPE = ('scenario = "parabolic"\n[parameters]\nmu = [0.2, 0.3]\nux0 = 0.25\n'
          'y = { start = -1.5, stop = 1.5, num = 31 }\nx = { start = -1.5, stop = 1.5, num = 41 }\n')


def test_hash_independent_of_chunks_and_scheduler(tmp_path, capsys):
    recipe = tmp_path / "r.toml"
    recipe.write_text(RECIPE)
    a, b = tmp_path / "a.nc", tmp_path / "b.nc"
    assert cli.main(["run", str(recipe), "-o", str(a), "-q"]) == 0
    assert cli.main(["run", str(recipe), "-o", str(b), "-q", "--chunks", "x=7,y=5,mu=1",
                     "--scheduler", "synchronous"]) == 0
    (ha, sa), (hb, sb) = file_hash(a), file_hash(b)
    assert ha == sa == hb == sb
    with xr.open_dataset(a) as ds:
        assert ds.attrs[ATTR] == ha
    assert cli.main(["hash", str(a), str(b)]) == 0
    assert capsys.readouterr().out.count(" ok") == 2


def test_hash_detects_a_changed_value(tmp_path, capsys):
    recipe = tmp_path / "r.toml"
    recipe.write_text(RECIPE)
    a = tmp_path / "a.nc"
    assert cli.main(["run", str(recipe), "-o", str(a), "-q"]) == 0
    with netCDF4.Dataset(a, "a") as nc:
        nc["sigma_xx"][0, 3, 4] = nc["sigma_xx"][0, 3, 4] + 1e-12
    assert cli.main(["hash", str(a)]) == 1
    assert "MISMATCH" in capsys.readouterr().out
    assert cli.main(["hash", str(tmp_path / "none.nc")]) == 2


def test_dry_run_writes_nothing(tmp_path, capsys):
    recipe = tmp_path / "r.toml"
    recipe.write_text(RECIPE)
    out = tmp_path / "o.nc"
    assert cli.main(["run", str(recipe), "-o", str(out), "--dry-run"]) == 0
    text = capsys.readouterr().out
    assert "mu=2 x y=31 x x=41 = 2,542 points" in text and "MB" in text and "estimated" in text
    assert not out.exists() and list(tmp_path.iterdir()) == [recipe]


def test_slabs_cover_an_array_in_c_order():
    import numpy as np

    from stressfields.output.hashing import slabs

    a = np.arange(3 * 4 * 5 * 6, dtype=np.float64).reshape(3, 4, 5, 6)
    for limit in (8, 48, 100, 480, 10**6):
        pieces = [a[i] for i in slabs(a.shape, 8, limit)]
        assert all(p.nbytes <= max(limit, 8) for p in pieces)
        assert b"".join(p.tobytes() for p in pieces) == a.tobytes()
