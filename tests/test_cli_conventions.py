"""The command line's habits: results on stdout and nothing else there, progress on stderr and only on
a terminal, --json documents, a recipe from standard input, `-o -` refused, -v, no colour codes."""
import contextlib
import io
import json
import subprocess
import sys
from pathlib import Path

import pytest

from stressfields import cli
from stressfields.scenarios import REGISTRY

ROOT = Path(__file__).resolve().parents[1]
SMALL = 'scenario = "conical"\n[parameters]\nmu = [0.0, 0.3]\nx = { start = -2.0, stop = 2.0, num = 41 }\n'


def _stdin(monkeypatch, text: str) -> None:
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(text.encode())))


def test_a_run_writes_nothing_to_stdout(tmp_path):
    recipe = tmp_path / "r.toml"
    recipe.write_text(SMALL)
    with open(tmp_path / "o.txt", "w") as out:
        done = subprocess.run([sys.executable, "-m", "stressfields", "run", str(recipe), "-o", str(tmp_path / "x.nc")],
                              stdout=out, stderr=subprocess.PIPE, text=True, cwd=tmp_path,
                              env={"NO_COLOR": "1", "PATH": "/usr/bin:/bin", "PYTHONPATH": str(ROOT)})
    assert done.returncode == 0 and (tmp_path / "x.nc").exists()
    assert (tmp_path / "o.txt").read_text() == ""
    assert "[#" not in done.stderr and "r.toml ->" in done.stderr       # no bar into a pipe; the header stays
    assert "\x1b[" not in done.stderr                                   # no colour codes


def test_progress_bars_go_to_stderr(capsys):
    import time

    import dask

    from stressfields.output.compute import progress_bar

    with progress_bar(True):            # the bar shows after 0.5 s
        dask.delayed(time.sleep)(0.8).compute(scheduler="synchronous")
    out, err = capsys.readouterr()
    assert out == "" and "Completed" in err


def test_describe_json_is_the_declaration(capsys):
    assert cli.main(["describe", "conical", "--json"]) == 0
    record, scen = json.loads(capsys.readouterr().out), REGISTRY["conical"]      # what json.tool parses
    assert [p["name"] for p in record["parameters"]] == [p.name for p in scen.parameters]
    assert [v["name"] for v in record["variables"]] == [v.name for v in scen.variables]
    x = next(p for p in record["parameters"] if p["name"] == "x")
    assert x["long_name"] == "x / a" and x["units_physical"] == "m" and x["required"]


def test_list_validate_and_hash_json(tmp_path, capsys, monkeypatch):
    assert cli.main(["list", "--json"]) == 0
    assert set(json.loads(capsys.readouterr().out)) == set(REGISTRY)
    good, bad = tmp_path / "good.toml", tmp_path / "bad.toml"
    good.write_text(SMALL)
    bad.write_text(SMALL.replace("mu = [0.0, 0.3]", "mu = -1.0"))
    assert cli.main(["validate", str(good), str(bad), "--json"]) == 2
    out, err = capsys.readouterr()
    records = json.loads(out)
    assert err == "" and [r["ok"] for r in records] == [True, False]
    assert records[0]["dims"] == {"mu": 2, "x": 41} and "mu" in records[1]["problems"][0]
    assert cli.main(["run", str(good), "-o", str(tmp_path / "x.nc"), "-q"]) == 0
    capsys.readouterr()
    assert cli.main(["hash", str(tmp_path / "x.nc"), "--json"]) == 0
    (record,) = json.loads(capsys.readouterr().out)
    assert record["status"] == "ok" and record["sha256"] == record["stored"]


def test_a_recipe_from_standard_input(tmp_path, capsys, monkeypatch):
    _stdin(monkeypatch, SMALL)
    assert cli.main(["validate", "-"]) == 0
    assert capsys.readouterr().out.startswith("-: ok (conical; mu=2, x=41")
    _stdin(monkeypatch, SMALL)
    monkeypatch.chdir(tmp_path)
    assert cli.main(["run", "-", "-q"]) == 0                  # OUT_DIR/stdin.nc without -o
    assert (tmp_path / "out" / "stdin.nc").exists()
    recipe = ROOT / "recipes" / "cone_fig2_sigma_xx.toml"
    done = subprocess.run(f"cat {recipe} | {sys.executable} -m stressfields validate -", shell=True,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


def test_output_to_stdout_is_refused_in_one_line(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "r.toml").write_text(SMALL)
    for argv in (["run", "r.toml", "-o", "-"], ["export", "r.toml", "-o", "-"]):
        assert cli.main(argv) == 2
        out, err = capsys.readouterr()
        assert out == "" and err.count("\n") == 1 and err.startswith("error: -o -:")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.toml"]          # nothing written, no file "-"


def test_verbose_says_size_time_and_hash(tmp_path, capsys):
    (tmp_path / "r.toml").write_text(SMALL)
    assert cli.main(["run", str(tmp_path / "r.toml"), "-o", str(tmp_path / "x.nc"), "-v"]) == 0
    out, err = capsys.readouterr()
    assert out == "" and "chunks:" in err and "content sha256 " in err
    import xarray as xr

    with xr.open_dataset(tmp_path / "x.nc") as ds:
        assert ds.attrs["id"] in err


def test_no_colour_codes(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("NO_COLOR", "1")
    monkeypatch.chdir(tmp_path)
    for argv in (["describe", "wavy"], ["validate", "missing.toml"], ["run", "--help"]):
        with pytest.raises(SystemExit) if "--help" in argv else contextlib.nullcontext():
            cli.main(argv)
        out, err = capsys.readouterr()
        assert "\x1b[" not in out + err and (out or err), argv


def test_quiet_and_verbose_exclude_each_other_and_stdin_is_read_once(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "r.toml").write_text(SMALL)
    with pytest.raises(SystemExit):
        cli.main(["run", "-q", "-v", "r.toml"])
    assert "not allowed with" in capsys.readouterr().err
    _stdin(monkeypatch, SMALL)
    assert cli.main(["validate", "-", "-"]) == 2
    assert capsys.readouterr().err == "error: - (standard input) can be given once\n"


def test_example_prints_a_shipped_recipe(capsys):
    assert cli.main(["example"]) == 0
    assert "hertz_subsurface" in capsys.readouterr().out.split()
    assert cli.main(["example", "hertz_subsurface"]) == 0
    assert capsys.readouterr().out == (ROOT / "recipes" / "hertz_subsurface.toml").read_text()
    assert cli.main(["example", "nope"]) == 2
    assert capsys.readouterr().err.startswith("error: unknown example 'nope'; one of: ")
