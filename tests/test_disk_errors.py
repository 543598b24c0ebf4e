"""A full disk or an unwritable target: a clear error, exit code 2, and no partial file."""
import os
import subprocess

import pytest

from stressfields import cli

RECIPE = ('scenario = "parabolic"\n[parameters]\nmu = 0.3\nux0 = 0.25\n'
          'y = { start = -1.5, stop = 1.5, num = 200 }\nx = { start = -1.5, stop = 1.5, num = 200 }\n')


@pytest.fixture
def small_disk(tmp_path):
    mount = tmp_path / "disk"
    mount.mkdir()
    if os.geteuid() != 0 or subprocess.run(["mount", "-t", "tmpfs", "-o", "size=256k", "tmpfs", str(mount)],
                                           capture_output=True).returncode:
        pytest.skip("cannot mount a small tmpfs here (needs root)")
    yield mount
    # lazy: a file handle the failed HDF5 write still holds must not keep the mount busy
    subprocess.run(["umount", "-l", str(mount)], check=False)


def test_full_disk(tmp_path, small_disk, capsys):
    recipe = tmp_path / "r.toml"
    recipe.write_text(RECIPE)
    assert cli.main(["run", str(recipe), "-o", str(small_disk / "o.nc"), "-q"]) == 2
    err = capsys.readouterr().err
    assert "cannot write" in err and "Traceback" not in err
    assert os.listdir(small_disk) == []


def test_read_only_target(tmp_path, small_disk, capsys):
    recipe = tmp_path / "r.toml"
    recipe.write_text(RECIPE)
    subprocess.run(["mount", "-o", "remount,ro", str(small_disk)], check=True)
    assert cli.main(["run", str(recipe), "-o", str(small_disk / "o.nc"), "-q"]) == 2
    assert "cannot write" in capsys.readouterr().err
    assert os.listdir(small_disk) == []


def test_full_disk_zarr(tmp_path, small_disk, capsys):
    pytest.importorskip("zarr")
    recipe = tmp_path / "r.toml"
    recipe.write_text(RECIPE.replace("num = 200", "num = 400") + '[output]\nchunks = { y = 20 }\n')
    for _ in range(3):     # threads still writing chunks after the first failure once recreated the store
        assert cli.main(["run", str(recipe), "-o", str(small_disk / "o.zarr"), "-q"]) == 2
        err = capsys.readouterr().err
        assert "cannot write" in err and "Traceback" not in err
        assert os.listdir(small_disk) == []
