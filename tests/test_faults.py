"""Faults: runs killed at random moments, concurrent runs onto one target, damaged parts, manifests
and stores, hostile targets. Each ends in a complete verified target or nothing, one line of
explanation, and no temporaries after the next run."""
import json
import os
import random
import signal
import subprocess
import sys
import time

import netCDF4
import pytest

import stressfields as sf
from stressfields import cli
from stressfields.output import atomic, formats, netcdf, parts
from stressfields.output.formats import file_hash

RECIPE = """scenario = "conical"
[parameters]
nu = { start = 0.0, stop = 0.5, num = 8 }
mu = [0.2, 0.3, 0.4]
ux0 = 0.25
y = { start = -1.5, stop = 1.5, num = 81 }
x = { start = -1.5, stop = 1.5, num = 101 }
[output]
chunks = { nu = 1 }
"""
SMALL = ('scenario = "parabolic"\n[parameters]\nmu = [0.2, 0.3]\nux0 = 0.25\n'
         'y = { start = -1.5, stop = 1.5, num = 21 }\nx = { start = -1.5, stop = 1.5, num = 31 }\n'
         '[output]\nchunks = { mu = 1 }\n')


@pytest.fixture(scope="module")
def whole(tmp_path_factory):
    """The recipe and the content hash of an uninterrupted run."""
    folder = tmp_path_factory.mktemp("whole")
    recipe = folder / "r.toml"
    recipe.write_text(RECIPE)
    assert cli.main(["run", str(recipe), "-o", str(folder / "whole.nc"), "-q"]) == 0
    return recipe, file_hash(folder / "whole.nc")[0]


def _run(*args, **kw):
    return subprocess.Popen([sys.executable, "-m", "stressfields", *map(str, args)], stderr=subprocess.PIPE,
                            stdout=subprocess.DEVNULL, text=True, **kw)


def _leftovers(folder, keep=()):
    """Temporaries, locks and parts folders beside the outputs."""
    return sorted(p.name for p in folder.iterdir() if p.name not in keep
                  and (p.name.startswith(".") or p.name.endswith(".parts")))


def _verified(path):
    digest, stored = file_hash(path)
    assert digest == stored
    return digest


# the moment of each kill, counted from the first file the run writes (its temporary or its parts
# folder); a run writes for ~0.4-0.6 s here
TRIALS = [(mode, sig, delay) for (mode, sig), delay in zip(
    [("single", signal.SIGKILL), ("single", signal.SIGTERM), ("parts", signal.SIGKILL),
     ("parts", signal.SIGTERM), ("single", signal.SIGHUP), ("parts", signal.SIGKILL)],
    [round(random.Random(2026 + i).uniform(0.0, 0.4), 2) for i in range(6)])]


def _started(proc, folder):
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline and proc.poll() is None:
        if any(p.name.startswith(".out.nc.") or p.name == "out.nc.parts" for p in folder.iterdir()):
            return
        time.sleep(0.005)


@pytest.mark.slow
@pytest.mark.parametrize("mode,sig,delay", TRIALS)
def test_killed_run_leaves_nothing_or_a_complete_target(tmp_path, whole, mode, sig, delay):
    recipe, digest = whole
    target = tmp_path / "out.nc"
    extra = ["--parts"] if mode == "parts" else []
    proc = _run("run", recipe, "-o", target, "-q", *extra)
    _started(proc, tmp_path)
    time.sleep(delay)
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    print(f"{mode} {sig!r} at {delay} s: exit {proc.returncode}, target {'complete' if target.exists() else 'absent'}")
    if sig != signal.SIGKILL and proc.returncode > 0:     # caught: one line, 128 + signal, nothing left
        assert proc.returncode == 128 + sig and err.strip().count("\n") == 0 and "terminated" in err
        assert _leftovers(tmp_path, keep={"out.nc.parts"}) == []
    if target.exists():                   # finished before the signal: complete and verified
        assert _verified(target) == digest
        return
    again = _run("run", recipe, "-o", target, "-q", *(["--resume"] if mode == "parts" else []))
    assert again.wait(timeout=60) == 0, again.stderr.read()
    assert _verified(target) == digest
    assert _leftovers(tmp_path) == []


def test_stale_temporaries_of_dead_runs_are_removed_and_live_ones_kept(tmp_path):
    recipe = tmp_path / "r.toml"
    recipe.write_text(SMALL)
    host = atomic.OWNER.split("-")[0]
    sleeper = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    try:
        stale = [tmp_path / f".o.nc.{host}-{dead.pid}.abcd1234.tmp", tmp_path / f".o.zarr.{host}-{dead.pid}.x1.partial"]
        live = [tmp_path / f".o.nc.{host}-{sleeper.pid}.abcd1234.tmp", tmp_path / f".o.nc.000000-{dead.pid}.q.tmp"]
        for p in stale[:1] + live:
            p.write_text("x")
        stale[1].mkdir()
        (tmp_path / ".o.zarr.lock").write_text(f"{host}-{dead.pid}")       # the lock of a killed run
        assert cli.main(["run", str(recipe), "-o", str(tmp_path / "o.nc"), "-q"]) == 0
        assert cli.main(["run", str(recipe), "-o", str(tmp_path / "o.zarr"), "-q"]) == 0
        assert not any(p.exists() for p in stale) and all(p.exists() for p in live)
        assert not (tmp_path / ".o.zarr.lock").exists()
    finally:
        sleeper.kill()
        sleeper.wait()


@pytest.mark.slow
@pytest.mark.parametrize("suffix", [".nc", ".zarr"])
def test_two_concurrent_runs_onto_one_target(tmp_path, suffix):
    pytest.importorskip("zarr")
    a, b = tmp_path / "a.toml", tmp_path / "b.toml"
    a.write_text(SMALL)
    b.write_text(SMALL.replace("mu = [0.2, 0.3]", "mu = [0.4, 0.5]"))
    target = tmp_path / f"t{suffix}"
    procs = [_run("run", r, "-o", target, "-q") for r in (a, b)]
    codes = [p.wait(timeout=60) for p in procs]
    assert sorted(codes) == [0, 2], [p.stderr.read() for p in procs]
    winner = (a, b)[codes.index(0)]
    _verified(target)
    with sf.generate(winner) as expected, (netcdf.read(target) if suffix == ".nc"
                                             else formats.FORMATS["zarr"].read(target)) as got:
        assert got.attrs["stressfields_recipe_sha256"] == expected.attrs["stressfields_recipe_sha256"]
    assert _leftovers(tmp_path) == []


def test_publishing_never_replaces_a_target_that_appeared_meanwhile(tmp_path):
    """The claim itself, without the run lock: a second writer of a new name loses and cleans up."""
    ds = sf.generate(SMALL_DICT)
    for suffix in (".nc", ".zarr"):
        target = tmp_path / f"t{suffix}"
        first = formats.format_for(target).write(ds, target)
        digest = _verified(first)
        with pytest.raises(sf.OutputError, match="created by another run"):
            formats.format_for(target).write(ds.isel(mu=[0]), target)
        assert _verified(target) == digest
    assert _leftovers(tmp_path) == []


SMALL_DICT = {"scenario": "parabolic", "parameters": {"mu": [0.2, 0.3], "ux0": 0.25, "x": [0.0, 0.5, 1.0],
                                                     "y": [0.0, 0.1]}, "output": {"chunks": {"mu": 1}}}


def test_a_second_run_holding_no_lock_is_refused_before_computing(tmp_path):
    target = tmp_path / "t.nc"
    with atomic.target_lock(target):
        with pytest.raises(sf.OutputError, match="being written by another run"):
            sf.write(sf.generate(SMALL_DICT), target)
    assert not target.exists() and _leftovers(tmp_path) == []


def _interrupted_parts(tmp_path, whole, monkeypatch):
    """All parts written, the file never hashed nor published (as if killed just before)."""
    recipe, _ = whole
    target = tmp_path / "out.nc"

    def killed(*args, **kwargs):
        raise KeyboardInterrupt
    with monkeypatch.context() as m:
        m.setattr(netcdf, "finish", killed)
        with pytest.raises(KeyboardInterrupt):
            sf.write(sf.generate(recipe), target, parts=True)
    return recipe, target, tmp_path / "out.nc.parts"


def _computed_parts(monkeypatch):
    """The first row of every part computed from here on."""
    rows = []
    real = parts._store

    def spy(nc, sources, *args):
        rows.append(next(region[0].start for name, _, region in sources if name == "sigma_xx"))
        return real(nc, sources, *args)
    monkeypatch.setattr(parts, "_store", spy)
    return rows


def test_damaged_parts_are_computed_again(tmp_path, whole, monkeypatch):
    recipe, target, folder = _interrupted_parts(tmp_path, whole, monkeypatch)
    manifest = json.loads((folder / "manifest.json").read_text())
    assert sorted(manifest["parts"]) == [str(i) for i in range(8)]
    with netCDF4.Dataset(folder / "data.nc", "a") as nc:     # one value of part 1 changed on disk
        nc["sigma_xx"][1, 0, 3, 4] += 1e-12
    manifest["parts"]["3"] = manifest["parts"]["3"][:-1]       # a record of the wrong length
    manifest["parts"]["5"][0] ^= 1                              # a record that does not match the file
    manifest["parts"]["6"] = {"crc": "x"}                       # a record of the wrong shape
    del manifest["parts"]["7"]                                  # not finished
    (folder / "manifest.json").write_text(json.dumps(manifest))
    computed = _computed_parts(monkeypatch)
    assert cli.main(["run", str(recipe), "-o", str(target), "-q", "--resume"]) == 0
    assert computed == [1, 3, 5, 6, 7]
    assert _verified(target) == whole[1]
    assert _leftovers(tmp_path) == []


@pytest.mark.parametrize("damage", ["truncated", "signature", "emptied", "missing", "not laid out"])
def test_a_damaged_file_of_parts_is_laid_out_again(tmp_path, whole, monkeypatch, damage):
    recipe, target, folder = _interrupted_parts(tmp_path, whole, monkeypatch)
    data = folder / "data.nc"
    if damage == "truncated":
        with open(data, "r+b") as fh:
            fh.truncate(os.path.getsize(data) // 2)
    elif damage == "signature":          # a flipped byte in the HDF5 signature
        with open(data, "r+b") as fh:
            fh.seek(1)
            byte = fh.read(1)
            fh.seek(1)
            fh.write(bytes([byte[0] ^ 0xFF]))
    elif damage == "emptied":
        data.write_bytes(b"")
    elif damage == "missing":
        data.unlink()
    else:                                # killed while laying it out: the manifest does not say it is
        manifest = json.loads((folder / "manifest.json").read_text())
        del manifest["laid_out"]
        (folder / "manifest.json").write_text(json.dumps(manifest))
    computed = _computed_parts(monkeypatch)
    assert cli.main(["run", str(recipe), "-o", str(target), "-q", "--resume"]) == 0
    assert len(computed) == 8
    assert _verified(target) == whole[1]
    assert _leftovers(tmp_path) == []


def test_blocks_come_from_the_plan_never_from_the_manifest(tmp_path, whole, monkeypatch):
    recipe, target, folder = _interrupted_parts(tmp_path, whole, monkeypatch)
    outside = tmp_path / "evil.nc"
    outside.write_bytes(b"not to be read or written")
    manifest = json.loads((folder / "manifest.json").read_text())
    for key in ("../evil.nc", "/etc/passwd", "-1", "99", "0.5"):
        manifest["parts"][key] = [0, 1, 2]
    (folder / "manifest.json").write_text(json.dumps(manifest))
    computed = _computed_parts(monkeypatch)
    assert cli.main(["run", str(recipe), "-o", str(target), "-q", "--resume"]) == 0
    assert computed == []                  # the eight parts of the plan verified; the rest ignored
    assert _verified(target) == whole[1]
    assert outside.read_bytes() == b"not to be read or written"


@pytest.mark.parametrize("text", ["[]", "{}", '{"parts": []}', "not json", '"x"'])
def test_a_manifest_of_the_wrong_shape_is_refused_in_one_line(tmp_path, text, capsys):
    recipe = tmp_path / "r.toml"
    recipe.write_text(SMALL)
    (tmp_path / "o.nc.parts").mkdir()
    (tmp_path / "o.nc.parts" / "manifest.json").write_text(text)
    assert cli.main(["run", str(recipe), "-o", str(tmp_path / "o.nc"), "-q", "--resume"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and ("manifest" in err or "another recipe" in err)
    assert not (tmp_path / "o.nc").exists()


def _chunk(store, var="sigma_xx"):
    files = sorted(p for p in (store / var).rglob("*") if p.is_file() and p.name[0].isdigit())
    return files[len(files) // 2]


@pytest.mark.parametrize("damage", ["flip", "delete", "unfinished", "no store"])
def test_export_refuses_damaged_or_unfinished_stores(tmp_path, damage, capsys):
    pytest.importorskip("zarr")
    store = sf.write(sf.generate(SMALL_DICT), tmp_path / "s.zarr")
    chunk = _chunk(store)
    if damage == "flip":
        data = bytearray(chunk.read_bytes())
        data[len(data) // 2] ^= 0x10
        chunk.write_bytes(bytes(data))
    elif damage == "delete":
        chunk.unlink()
    elif damage == "unfinished":          # as a killed run leaves it: complete chunks, no content hash
        import zarr

        group = zarr.open_group(store, mode="r+")
        del group.attrs["stressfields_content_sha256"]
        zarr.consolidate_metadata(store)
        store = store.rename(tmp_path / ".s.zarr.000000-1.abc.partial")
    else:
        store = tmp_path / "folder"
        store.mkdir()
        (store / "notes.txt").write_text("x")
    capsys.readouterr()
    assert cli.main(["export", str(store), "-o", str(tmp_path / "e.nc")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert not (tmp_path / "e.nc").exists() and _leftovers(tmp_path, keep={store.name}) == []


def test_hash_of_unstamped_and_corrupted_files(tmp_path, capsys):
    plain = tmp_path / "plain.nc"
    sf.generate(SMALL_DICT).to_netcdf(plain)
    assert cli.main(["hash", str(plain)]) == 1
    assert "unverified" in capsys.readouterr().out
    bad = tmp_path / "bad.nc"
    data = bytearray(plain.read_bytes())
    data[0:8] = b"\x00" * 8
    bad.write_bytes(bytes(data))
    assert cli.main(["hash", str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "not a readable" in err


def test_hostile_targets_are_refused_before_any_work(tmp_path, capsys):
    recipe = tmp_path / "r.toml"
    recipe.write_text(SMALL)
    fifo = tmp_path / "fifo.nc"
    os.mkfifo(fifo)
    dangling = tmp_path / "link.nc"
    dangling.symlink_to(tmp_path / "nowhere.nc")
    afile = tmp_path / "afile"
    afile.write_text("x")
    adir = tmp_path / "adir"
    adir.mkdir()
    (adir / "keep.txt").write_text("x")
    cases = [
        ["-o", "/dev/null", "--overwrite"],                     # a character device
        ["-o", str(fifo), "--overwrite"],
        ["-o", str(dangling)],                                  # a dangling link counts as existing
        ["-o", str(tmp_path / ("n" * 250 + ".nc"))],            # name too long for its temporaries
        ["-o", str(adir), "--overwrite", "--parts"],            # a store cannot be written in parts
        ["-o", str(adir), "--overwrite"],                       # a directory that is not a store
        ["-d", str(afile)],                                     # --out-dir names a file
        ["-d", str(afile / "sub")],
    ]
    for case in cases:
        capsys.readouterr()
        assert cli.main(["run", str(recipe), "-q", *case]) == 2, case
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and err.startswith("error: "), (case, err)
    assert os.path.exists("/dev/null") and not os.path.isfile("/dev/null")
    assert dangling.is_symlink() and not dangling.exists() and (adir / "keep.txt").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["adir", "afile", "fifo.nc", "link.nc", "r.toml"]


def test_plot_without_matplotlib_is_refused_before_any_work(tmp_path, monkeypatch, capsys):
    recipe = tmp_path / "r.toml"
    recipe.write_text(SMALL)
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    assert cli.main(["run", str(recipe), "-o", str(tmp_path / "o.nc"), "-q", "--plot"]) == 2
    assert "matplotlib" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.toml"]


def test_a_failed_scheduler_leaves_the_local_one_working(tmp_path, capsys):
    """A server that is not a dask scheduler: the half-made client must not stay dask's default."""
    pytest.importorskip("distributed")
    import socket
    import threading

    server = socket.create_server(("127.0.0.1", 0))

    def answer():
        with server:
            for _ in range(20):
                conn, _ = server.accept()
                with conn:
                    conn.sendall(b"HTTP/1.0 400 not a dask scheduler\r\n\r\n" * 100)
    threading.Thread(target=answer, daemon=True).start()
    recipe = tmp_path / "r.toml"
    recipe.write_text(SMALL)
    out = tmp_path / "o.nc"
    address = f"tcp://127.0.0.1:{server.getsockname()[1]}"
    assert cli.main(["run", str(recipe), "-o", str(out), "-q", "--scheduler", address]) == 2
    err = capsys.readouterr().err
    assert "cannot connect" in err and err.count("\n") == 1 and not out.exists()
    assert cli.main(["run", str(recipe), "-o", str(out), "-q"]) == 0
    _verified(out)


def test_a_closed_pipe_is_one_line(tmp_path):
    code = "import sys; from stressfields.cli import main; sys.exit(main(['describe', 'conical']))"
    proc = subprocess.Popen([sys.executable, "-c", code],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    proc.stdout.close()            # the reader is gone before anything is written (the import takes ~1 s)
    err = proc.stderr.read()
    assert proc.wait(timeout=60) == 2
    assert err.count("\n") == 1 and "pipe" in err


# -- compare's report folder ------------------------------------------------------------------------

COMPARE = ("examples/fe_hertz_mindlin/recipe.toml", "examples/fe_hertz_mindlin/nodes.csv")
REPORT = {"comparison.nc", "comparison.png", "report.md", "report.json"}
# the moment of each kill, counted from the report's temporary folder's appearance; the folder is
# filled in ~0.5-1.5 s here (comparison.nc, then the PNG, then report.md)
COMPARE_TRIALS = [(sig, round(random.Random(2126 + i).uniform(0.0, 1.2), 2))
                  for i, sig in enumerate([signal.SIGTERM, signal.SIGKILL, signal.SIGHUP])]


def _compare(out, *extra):
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    return _run("compare", *(os.path.join(root, p) for p in COMPARE), "-o", out, "--tolerance", "0.1", *extra)


@pytest.mark.slow
@pytest.mark.parametrize("sig,delay", COMPARE_TRIALS)
def test_killed_compare_leaves_no_report_or_a_complete_one(tmp_path, sig, delay):
    out = tmp_path / "report"
    proc = _compare(out)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and proc.poll() is None:
        if any(p.name.startswith(".report.") and p.name.endswith(".partial") for p in tmp_path.iterdir()):
            break
        time.sleep(0.005)
    time.sleep(delay)
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    print(f"{sig!r} at {delay} s: exit {proc.returncode}, report {'complete' if out.exists() else 'absent'}")
    if sig != signal.SIGKILL and proc.returncode > 0:     # caught: one true line, nothing left
        assert proc.returncode == 128 + sig and err.strip().count("\n") == 0 and "terminated" in err, err
        assert not out.exists() and _leftovers(tmp_path) == []
        return
    if out.exists():                        # finished before the signal: the whole report
        assert set(os.listdir(out)) == REPORT
        _verified(out / "comparison.nc")
        return
    again = _compare(out)
    assert again.wait(timeout=120) == 0, again.stderr.read()
    assert set(os.listdir(out)) == REPORT and _leftovers(tmp_path) == []
    _verified(out / "comparison.nc")


def test_a_report_folder_is_new_empty_or_a_report_replaced_with_overwrite(tmp_path, capsys):
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    recipe, nodes = (os.path.join(root, p) for p in COMPARE)

    def compare(out, *extra):
        return cli.main(["compare", recipe, nodes, "-o", str(out), "--tolerance", "0.1", *extra])

    (tmp_path / "file").write_text("x")
    (tmp_path / "mixed").mkdir()
    (tmp_path / "mixed" / "notes.txt").write_text("mine")
    (tmp_path / "mixed" / "report.md").write_text("old")
    (tmp_path / "link").symlink_to(tmp_path / "mixed")
    for out, extra, words in [("file", [], "is not a directory"), ("mixed", ["--overwrite"], "not of a report"),
                              ("link", ["--overwrite"], "symbolic link"), ("no/such/parent", [], "not a directory")]:
        assert compare(tmp_path / out, *extra) == 2, out
        err = capsys.readouterr().err.strip()
        assert words in err and err.count("\n") == 0, (out, err)
    assert (tmp_path / "mixed" / "notes.txt").read_text() == "mine"
    (tmp_path / "empty").mkdir()
    assert compare(tmp_path / "empty") == 0
    assert set(os.listdir(tmp_path / "empty")) == REPORT
    assert compare(tmp_path / "empty") == 2 and "use --overwrite" in capsys.readouterr().err
    before = (tmp_path / "empty" / "comparison.nc").stat().st_ino
    assert compare(tmp_path / "empty", "--overwrite") == 0
    assert set(os.listdir(tmp_path / "empty")) == REPORT
    assert (tmp_path / "empty" / "comparison.nc").stat().st_ino != before
    assert _leftovers(tmp_path) == []
