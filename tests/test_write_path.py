"""The write path: the content hash by per-variable digests (earlier forms still verify), default
chunking that keeps both cores busy, parts written once into the output and hashed once."""
import hashlib
from pathlib import Path

import numpy as np
import pytest

import stressfields as sf
from stressfields.output import hashing
from stressfields.build import default_chunks
from stressfields.output.formats import file_hash, verify
from conftest import kill_after_two_parts

CONE = {"scenario": "conical",
        "parameters": {"nu": 0.3, "ux0": 0.25, "mu": [0.0, 0.3, 0.4], "y": [0.0, 0.3, 0.6],
                       "x": {"start": -1.5, "stop": 1.5, "num": 31}}}


@pytest.mark.parametrize("shape,chunks", [((7,), (3,)), ((4, 5), (1, 5)), ((4, 5), (4, 2)), ((3, 4, 5), (2, 3, 4)),
                                          ((2, 3, 4, 5), (1, 3, 2, 5))])
@pytest.mark.parametrize("limit", [8, 24, 10 ** 9])
def test_a_variables_digest_is_the_sha256_of_its_c_order_little_endian_bytes(shape, chunks, limit, monkeypatch):
    """Against hashlib on the array's own bytes, whatever the slabs it is read in."""
    import dask.array as da
    import xarray as xr

    monkeypatch.setattr(hashing, "_READ_BYTES", limit)
    a = np.random.default_rng(1).standard_normal(shape).astype(">f8")     # big-endian: hashed little
    ds = xr.Dataset({"v": (tuple(f"d{i}" for i in range(len(shape))), da.from_array(a, chunks=chunks)),
                     "w": ("e", np.arange(3, dtype="<i4"))})
    assert hashing._read_digests(ds, ["v", "w"]) == {"v": hashlib.sha256(a.astype("<f8").tobytes()).digest(),
                                                     "w": hashlib.sha256(np.arange(3, dtype="<i4").tobytes()).digest()}


def test_the_hash_covers_the_heads_and_digests_in_name_order():
    """The current form against its definition written out with hashlib: the global attributes, then
    per variable (by name) its head and the digest of its values."""
    import json

    import xarray as xr

    ds = xr.Dataset({"b": ("x", np.array([1.0, 2.0]), {"units": "Pa", "k": np.int8(3)}),
                     "a": ("x", np.array([3, 4], dtype=np.int16))}, attrs={"title": "t", "history": "now"})
    h = hashlib.sha256(json.dumps({"title": "t"}).encode())
    heads = (("a", "int16", {}), ("b", "float64", {"k": {"dtype": "int8", "value": 3}, "units": "Pa"}))
    for name, dtype, attrs in heads:
        h.update(json.dumps({"name": name, "dims": ["x"], "dtype": dtype, "shape": [2], "attrs": attrs},
                            sort_keys=True).encode())
        h.update(hashlib.sha256(ds[name].values.astype(ds[name].dtype.newbyteorder("<")).tobytes()).digest())
    assert hashing.content_hash(ds) == h.hexdigest()


@pytest.mark.parametrize("piece", [8, 24, 8 * 31 + 1, 10 ** 9])
def test_blocks_handed_to_hdf5_in_pieces_store_the_same_values(tmp_path, monkeypatch, piece):
    """A block is written in C-order pieces of at most WRITE_BYTES: single values, parts of a row,
    whole rows, the whole block; every piece lands where it belongs (the file's hash, read back, is
    that of a file written in whole blocks)."""
    from stressfields.output import netcdf

    ds = sf.generate(CONE, chunks={"mu": 2, "x": 17})
    whole = file_hash(sf.write(ds, tmp_path / "whole.nc"))
    monkeypatch.setattr(netcdf, "WRITE_BYTES", piece)
    assert file_hash(sf.write(ds, tmp_path / "pieces.nc")) == whole


def test_earlier_forms_of_the_content_hash_still_verify(tmp_path):
    """A file that stores its hash in an earlier form (one stream over all values; before that without
    attribute types) verifies, and a changed value is still caught."""
    import netCDF4

    from stressfields.output.netcdf import read

    path = sf.write(sf.generate(CONE), tmp_path / "a.nc")
    with read(path, raw=True) as ds:
        forms = {form: hashing.content_hash(ds, form) for form in hashing.FORMS}
    assert len(set(forms.values())) == 3
    for form, digest in forms.items():
        with netCDF4.Dataset(path, "a") as nc:
            nc.setncattr(hashing.ATTR, digest)
        assert file_hash(path) == (digest, digest) and verify(path) == digest, form
    with netCDF4.Dataset(path, "a") as nc:
        nc["sigma_xx"][0, 0, 0] = nc["sigma_xx"][0, 0, 0] + 1.0
    with pytest.raises(sf.errors.OutputError, match="damaged"):
        verify(path)


@pytest.mark.parametrize("options", [{"nonfinite": "fill"}, {"dtype": "float32", "nonfinite": "nan"},
                                     {"compression": 4}])
@pytest.mark.parametrize("suffix", [".nc", ".zarr"])
def test_the_stored_hash_is_of_the_stored_values(tmp_path, options, suffix):
    """+-inf and NaN as the fill value, float32, compressed: the hash stored is the hash read back."""
    ds = sf.generate({**CONE, "parameters": {**CONE["parameters"], "x": [-1.0, 0.0, 0.5, 1.0, 2.0]}})
    digest, stored = file_hash(sf.write(ds, tmp_path / f"a{suffix}", **options))
    assert digest == stored


@pytest.mark.parametrize("sizes", [{"x": 200_000}, {"y": 447, "x": 448}, {"y": 1000, "x": 1000},
                                   {"mu": 2, "x": 500_000}, {"mu": 3, "x": 100_000}, {"y": 3162, "x": 3162},
                                   {"y": 1500, "x": 1500}, {"nu": 12, "mu": 3, "y": 101, "x": 121},
                                   {"a": 5, "b": 7, "x": 6000}, {"y": 10_000, "x": 10_000},
                                   {"point": 1_000_003}, {"y": 300_000, "x": 2}])
def test_default_chunks_give_every_core_two_tasks(sizes):
    chunking = default_chunks(sizes, {})
    count = int(np.prod([-(-sizes[d] // chunking[d]) for d in sizes]))
    points = int(np.prod(list(chunking.values())))
    total = int(np.prod(list(sizes.values())))
    assert count >= 4
    assert points <= 1_000_000
    if total >= 1_000_000:
        assert points >= 250_000                # per-task overhead stays small


@pytest.mark.parametrize("sizes", [{"nu": 12, "mu": 3, "y": 101, "x": 121}, {"a": 5, "b": 7, "x": 6000},
                                   {"mu": 2, "x": 500_000}, {"y": 3162, "x": 3162}])
def test_only_trailing_dimensions_are_cut_further(sizes):
    """The sweep dimensions keep the blocks of the points-per-chunk rule (so per-case quantities over them
    keep their bits); only the trailing ones are cut to reach four tasks."""
    from stressfields.build import TARGET_CHUNK_POINTS

    old = {}
    budget = TARGET_CHUNK_POINTS
    for dim in reversed(list(sizes)):            # the rule before: trailing dimensions whole first
        old[dim] = max(1, min(sizes[dim], budget))
        budget = max(1, budget // old[dim])
    new = default_chunks(sizes, {})
    last = list(sizes)[-1]
    assert {d: c for d, c in new.items() if d != last} == {d: c for d, c in old.items() if d != last}


def test_every_family_is_cut_into_tasks_and_keeps_its_bits():
    """From 2e5 points a sweep is cut into four tasks or more, and every variable is bit for bit that
    of one chunk (the wavy route decides its substitution from the whole sweep and sums each point's
    series alone)."""
    wavy = {"scenario": "wavy", "parameters": {
        "domain": "periodic", "amplitudes": [0.5, 0.01], "wavenumbers": [1, 11], "n_harmonics": [1, 2],
        "a": [0.05, 0.2, 0.3, 0.5, 0.8], "x": {"start": -1.0, "stop": 1.0, "num": 20_000}}}
    graded = {"scenario": "graded_tangential", "parameters": {
        "profile": "parabolic", "R": 0.75, "contact_radius": 1e-3, "mu": 0.5, "E0": 1e9, "poisson": "holl_ratio",
        "k": [0.0, 0.3, 0.6, 0.9], "delta_x": {"start": 0.0, "stop": 1.4e-6, "num": 60_000}},
              "output": {"variables": ["force_ratio", "max_tangential_displacement"]}}
    cone = {**CONE, "parameters": {**CONE["parameters"], "y": {"start": -1, "stop": 1, "num": 30},
                                   "x": {"start": -1.5, "stop": 1.5, "num": 3000}}}
    for recipe in (wavy, graded, cone):
        cut = sf.generate(recipe)
        assert max(int(np.prod([len(c) for c in v.chunks])) for v in cut.data_vars.values() if v.chunks) >= 4
        one = sf.generate(recipe, chunks={d: -1 for d in cut.chunks}).compute()
        cut = cut.compute()
        for name in cut.data_vars:
            np.testing.assert_array_equal(cut[name].values, one[name].values, err_msg=name)


def test_small_sweeps_stay_one_chunk_and_requests_are_kept():
    assert default_chunks({"y": 300, "x": 600}, {}) == {"y": 300, "x": 600}
    assert default_chunks({"y": 1000, "x": 1000}, {"y": 10}) == {"y": 10, "x": 1000}
    ds = sf.generate({**CONE, "parameters": {**CONE["parameters"], "y": {"start": -1, "stop": 1, "num": 100},
                                             "x": {"start": -1.5, "stop": 1.5, "num": 2001}}})
    assert len(ds.sigma_xx.chunks[0]) * len(ds.sigma_xx.chunks[1]) * len(ds.sigma_xx.chunks[2]) >= 4


def test_parts_write_each_value_once_into_one_file_hashed_once(tmp_path, monkeypatch):
    """No file per part and no join: every block is written once, into the output's own file, which
    is read back once to hash it."""
    from stressfields.output import netcdf

    reads, writes = [], []
    real_hash, real_write = netcdf.stamp, netcdf.write
    monkeypatch.setattr(netcdf, "stamp", lambda p: reads.append(p) or real_hash(p))
    monkeypatch.setattr(netcdf, "write", lambda *a, **k: writes.append(a) or real_write(*a, **k))
    ds = sf.generate(CONE, chunks={"mu": 1})
    target = sf.write(ds, tmp_path / "p.nc", parts=True)
    assert writes == [] and [Path(r).name for r in reads] == ["data.nc"]
    monkeypatch.setattr(netcdf, "stamp", real_hash)
    monkeypatch.setattr(netcdf, "write", real_write)
    assert file_hash(target)[0] == file_hash(target)[1] == file_hash(sf.write(ds, tmp_path / "whole.nc"))[0]
    assert not (tmp_path / "p.nc.parts").exists()


@pytest.mark.parametrize("options", [{"nonfinite": "fill"}, {"dtype": "float32"}, {"compression": 4}])
def test_parts_store_what_a_whole_run_stores(tmp_path, options):
    """The parts' blocks pass the same encodings as a whole run (NaN/inf to the fill value, float32,
    compressed chunks): the same stored values, the same content hash."""
    recipe = {**CONE, "parameters": {**CONE["parameters"], "nu": [0.2, 0.3]}}
    ds = sf.generate(recipe, chunks={"nu": 1})
    parted = sf.write(ds, tmp_path / "parted.nc", parts=True, **options)
    digest, stored = file_hash(parted)
    assert digest == stored == file_hash(sf.write(ds, tmp_path / "whole.nc", **options))[0]


def test_large_rows_are_grouped_so_a_part_has_four_tasks_and_enough_points(monkeypatch):
    from stressfields.output import parts
    from stressfields.output.form import prepare
    from stressfields.output.parts import part_edges

    big = prepare(sf.generate({**CONE, "parameters": {
        **CONE["parameters"], "mu": list(np.linspace(0.1, 0.5, 10)),
        "y": {"start": -1, "stop": 1, "num": 400}, "x": {"start": -1.5, "stop": 1.5, "num": 500}}},
        chunks={"mu": 1}))
    assert part_edges(big, "mu") == [0, 10]                  # rows of 2e5 points: 4e6 points to a part
    monkeypatch.setattr(parts, "PART_POINTS", 1)
    assert part_edges(big, "mu") == [0, 4, 8, 10]            # ... and at least four tasks
    small = prepare(sf.generate(CONE, chunks={"mu": 1}))
    assert part_edges(small, "mu") == [0, 1, 2, 3]           # small rows: a part each, as before


KILLED = """scenario = "conical"
[parameters]
mu = { start = 0.1, stop = 0.5, num = 12 }
nu = 0.3
ux0 = 0.25
y = { start = -1.5, stop = 1.5, num = 1000 }
x = { start = -1.5, stop = 1.5, num = 1000 }
[output]
variables = ["sigma_xx", "von_mises"]
chunks = { mu = 1 }
"""


@pytest.mark.slow
def test_killed_parts_run_resumes_to_the_same_hash_and_recomputes_a_damaged_part(tmp_path, monkeypatch):
    import netCDF4

    from stressfields import cli
    from stressfields.output import parts

    recipe = tmp_path / "r.toml"
    recipe.write_text(KILLED)
    whole, target = tmp_path / "whole.nc", tmp_path / "out.nc"
    assert cli.main(["run", str(recipe), "-o", str(whole), "-q"]) == 0
    plan = kill_after_two_parts(recipe, target, timeout=120)
    assert plan["edges"] == [0, 4, 8, 12] and len(plan["parts"]) == 2     # rows of 1e6 points: 4e6 a part
    # a finished part damaged after the kill: one value changed on disk, its CRC now stale
    with netCDF4.Dataset(tmp_path / "out.nc.parts" / "data.nc", "a") as nc:
        nc["von_mises"][5, 5, 7] += 1e-9
    computed = []
    real = parts._store
    monkeypatch.setattr(parts, "_store", lambda nc, sources, *a: computed.append(sources[0][2][0].start)
                        or real(nc, sources, *a))
    assert cli.main(["run", str(recipe), "-o", str(target), "-q", "--resume"]) == 0
    done = {int(i) for i in plan["parts"]} - {1}
    assert set(computed) == {0, 4, 8} - {4 * i for i in done}     # the damaged part and the missing ones only
    assert file_hash(target)[0] == file_hash(target)[1] == file_hash(whole)[0]
    assert not (tmp_path / "out.nc.parts").exists()


@pytest.mark.slow
def test_processes_write_zarr_and_refuse_netcdf_before_any_work(tmp_path, capsys):
    """Other processes can write a Zarr store's chunks, not an HDF5 file's: `--scheduler processes`
    with a NetCDF target is one line and exit 2, with nothing computed or left behind."""
    pytest.importorskip("zarr")
    from stressfields import cli

    recipe = tmp_path / "r.toml"
    recipe.write_text('scenario = "conical"\n[parameters]\nmu = 0.3\nux0 = 0.25\n'
                      'x = { start = -1.5, stop = 1.5, num = 41 }\ny = { start = -1.5, stop = 1.5, num = 39 }\n')
    assert cli.main(["run", str(recipe), "-o", str(tmp_path / "o.nc"), "-q", "--scheduler", "processes"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Zarr" in err and list(tmp_path.iterdir()) == [recipe]
    assert cli.main(["run", str(recipe), "-o", str(tmp_path / "o.zarr"), "-q", "--scheduler", "processes"]) == 0
    assert cli.main(["run", str(recipe), "-o", str(tmp_path / "t.zarr"), "-q"]) == 0
    assert file_hash(tmp_path / "o.zarr") == file_hash(tmp_path / "t.zarr")


def test_a_file_closed_after_an_interrupt_refuses_the_blocks_still_arriving(tmp_path):
    """After an interrupt the main thread closes the file while worker threads may still hold blocks:
    each write then waits for the one in progress, and a write after the closing is refused (closing
    under a write crashed the process: 3 of 40 runs given SIGHUP)."""
    import threading

    from stressfields.output import netcdf

    ds = sf.generate(CONE)
    path = tmp_path / "laid_out.nc"
    netcdf.layout(ds, path)
    values = netcdf.open_values(path)
    name = "sigma_xx"
    shape = values[name].shape
    refused, wrote = [], []

    def worker():
        while True:             # until refused: the closing below comes after the first write
            try:
                values.write(name, tuple(slice(0, n) for n in shape), np.ones(shape))
                wrote.append(1)
            except sf.OutputError:
                refused.append(1)
                return
    thread = threading.Thread(target=worker)
    thread.start()
    while not wrote:
        pass
    values.close()
    thread.join(timeout=60)
    assert wrote and refused == [1] and values.closed and not thread.is_alive()
    values.close()              # closing twice is harmless
