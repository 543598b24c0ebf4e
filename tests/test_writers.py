"""The writer seam: one table of formats, one target check, the same `write` for the API and the CLI."""
from pathlib import Path

import pytest
import xarray as xr

import stressfields as sf
from stressfields.output import formats
from stressfields.output.formats import file_hash

RECIPE = {"scenario": "conical", "parameters": {"mu": [0.0, 0.3], "x": {"start": -1.5, "stop": 1.5, "num": 31},
                                                "y": 0.0},
          "output": {"variables": ["sigma_xx", "von_mises"], "chunks": {"mu": 1}}}


def test_write_refuses_an_existing_target_and_replaces_it_only_with_overwrite(tmp_path):
    ds = sf.generate(RECIPE)
    target = sf.write(ds, tmp_path / "a.nc")
    first = file_hash(target)
    with pytest.raises(sf.OutputError, match="exists.*--overwrite"):
        sf.write(ds, target)
    sf.write(ds, target, overwrite=True)
    assert file_hash(target) == first and first[0] == first[1]


def test_parts_and_plain_writes_and_zarr_export_agree(tmp_path):
    ds = sf.generate(RECIPE)
    plain = sf.write(ds, tmp_path / "plain.nc")
    parted = sf.write(ds, tmp_path / "parted.nc", parts=True)
    store = sf.write(ds, tmp_path / "store.zarr")
    exported = sf.export(store, tmp_path / "exported.nc")
    digests = [file_hash(p) for p in (plain, parted, store, exported)]
    assert all(d == s for d, s in digests)                      # each stored hash verifies
    assert digests[0][0] == digests[1][0] == digests[3][0]      # NetCDF: same content however written
    assert not (tmp_path / "parted.nc.parts").exists()
    with xr.open_dataset(plain) as a, xr.open_zarr(store) as b:
        xr.testing.assert_identical(a.sigma_xx.load(), b.sigma_xx.load())


def test_a_zarr_target_is_not_written_in_parts(tmp_path):
    with pytest.raises(sf.OutputError, match="not written in parts"):
        sf.write(sf.generate(RECIPE), tmp_path / "s.zarr", parts=True)


def test_leftover_parts_block_a_fresh_write_and_name_the_way_out(tmp_path):
    (tmp_path / "a.nc.parts").mkdir()
    with pytest.raises(sf.OutputError, match="interrupted run.*--resume"):
        sf.write(sf.generate(RECIPE), tmp_path / "a.nc")


def test_a_new_format_is_one_row_of_the_table(tmp_path, monkeypatch):
    calls = []

    def fake_write(ds, target, *, progress=False, scheduler=None, overwrite=False):
        calls.append(Path(target).name)
        Path(target).write_text("x")
        return Path(target)

    row = formats.Format("fake", (".fake",), fake_write, read=None)
    monkeypatch.setitem(formats.FORMATS, "fake", row)
    assert formats.format_for("out.FAKE") is row
    sf.write(sf.generate(RECIPE), tmp_path / "out.fake")
    assert calls == ["out.fake"]
    with pytest.raises(sf.OutputError, match="exists"):
        sf.write(sf.generate(RECIPE), tmp_path / "out.fake")


def test_estimate_before_running():
    e = sf.estimate(RECIPE)
    assert e["dims"] == {"mu": 2, "x": 31} and e["points"] == 62
    assert e["bytes"] > 0 and e["seconds"] >= 0
