"""A full disk or an unwritable target: a clear error, exit code 2, and no partial file."""
import os
import shutil
import subprocess

import pytest

from stressfields import cli

RECIPE = ('scenario = "parabolic"\n[parameters]\nmu = 0.3\nux0 = 0.25\n'
          'y = { start = -1.5, stop = 1.5, num = 200 }\nx = { start = -1.5, stop = 1.5, num = 200 }\n')


def _tmpfs(mount, size: str):
    """A tmpfs of ``size`` mounted at ``mount`` for the test, unmounted after it."""
    mount.mkdir()
    if os.geteuid() != 0 or subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(mount)],
                                           capture_output=True).returncode:
        pytest.skip("cannot mount a small tmpfs here (needs root)")
    yield mount
    # lazy: a file handle the failed HDF5 write still holds must not keep the mount busy
    subprocess.run(["umount", "-l", str(mount)], check=False)


@pytest.fixture
def small_disk(tmp_path):
    yield from _tmpfs(tmp_path / "disk", "256k")


def test_full_disk(tmp_path, small_disk, capsys):
    recipe = tmp_path / "r.toml"
    recipe.write_text(RECIPE)
    # past the free-space check (tested below): the disk fills during the write
    assert cli.main(["run", str(recipe), "-o", str(small_disk / "o.nc"), "-q", "--no-space-check"]) == 2
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
        assert cli.main(["run", str(recipe), "-o", str(small_disk / "o.zarr"), "-q", "--no-space-check"]) == 2
        err = capsys.readouterr().err
        assert "cannot write" in err and "Traceback" not in err
        assert os.listdir(small_disk) == []


COMPARE = [os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "examples", "fe_hertz_mindlin", p)
           for p in ("recipe.toml", "nodes.csv")]


@pytest.fixture
def report_disk(tmp_path):
    yield from _tmpfs(tmp_path / "rdisk", "1m")


def test_compare_on_a_full_disk_leaves_nothing_at_any_stage(report_disk, capsys):
    """The free space ends inside comparison.nc, inside the PNG, at report.md: each one line, exit 2
    and no folder; the sizes are those of a first, complete report on the same disk."""
    pytest.importorskip("matplotlib")
    report = report_disk / "report"
    assert cli.main(["compare", *COMPARE, "-o", str(report)]) == 0
    size = {name: os.stat(report / name).st_blocks * 512 for name in os.listdir(report)}
    assert set(size) == {"comparison.nc", "comparison.png", "report.md", "report.json"}
    shutil.rmtree(report)
    nc, png = size["comparison.nc"], size["comparison.png"]
    capsys.readouterr()
    total = os.statvfs(report_disk).f_blocks * os.statvfs(report_disk).f_frsize
    for free, stage in [(nc // 2, "comparison.nc"), (nc + png // 2, "comparison.png"), (nc + png, "report.md")]:
        free = free // 4096 * 4096
        with open(report_disk / "filler", "wb") as fh:
            fh.write(b"\0" * (total - free))
        code = cli.main(["compare", *COMPARE, "-o", str(report)])
        err = capsys.readouterr().err.strip()
        assert code == 2, (stage, code, err)
        assert err.startswith(f"error: cannot write {report}"), (stage, err)
        assert "partial" not in err and "\n" not in err and "Traceback" not in err, (stage, err)
        assert os.listdir(report_disk) == ["filler"], (stage, os.listdir(report_disk))
        os.unlink(report_disk / "filler")


def test_the_free_space_is_checked_before_a_run_and_the_check_can_be_skipped(tmp_path, small_disk, capsys):
    recipe = tmp_path / "r.toml"
    recipe.write_text(RECIPE)           # 40 000 points x 13 variables: 3.7 MB on a 256 KB disk
    assert cli.main(["run", str(recipe), "-o", str(small_disk / "o.nc"), "-q"]) == 2
    err = capsys.readouterr().err
    assert "needs about" in err and "free" in err and os.listdir(small_disk) == []
    # skipped: the run starts, and the full disk is the one line
    assert cli.main(["run", str(recipe), "-o", str(small_disk / "o.nc"), "-q", "--no-space-check"]) == 2
    err = capsys.readouterr().err
    assert "cannot write" in err and "needs about" not in err and os.listdir(small_disk) == []


def test_a_quick_look_on_a_full_disk_is_one_line(tmp_path, report_disk, capsys):
    """The file fits, its PNG does not: one line, exit 2, the complete file and no temporary."""
    pytest.importorskip("matplotlib")
    recipe = tmp_path / "r.toml"
    recipe.write_text(RECIPE.replace("num = 200", "num = 40"))
    assert cli.main(["run", str(recipe), "-o", str(report_disk / "o.nc"), "-q", "--plot"]) == 0
    nc, png = (os.stat(report_disk / f"o.{s}").st_blocks * 512 for s in ("nc", "png"))
    os.unlink(report_disk / "o.nc")
    os.unlink(report_disk / "o.png")
    total = os.statvfs(report_disk).f_blocks * os.statvfs(report_disk).f_frsize
    with open(report_disk / "filler", "wb") as fh:
        fh.write(b"\0" * (total - (nc + png // 2) // 4096 * 4096))
    assert cli.main(["run", str(recipe), "-o", str(report_disk / "o.nc"), "-q", "--plot"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"error: cannot write {report_disk / 'o.png'}") and "\n" not in err, err
    assert sorted(os.listdir(report_disk)) == ["filler", "o.nc"]
