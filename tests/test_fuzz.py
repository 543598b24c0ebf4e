"""Seeded fuzzing of recipe files and command lines: every case exits 0 or 2, prints no traceback,
and leaves nothing in the output folder when it fails."""
import os

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from stressfields import cli, recipe
from stressfields.recipe import RecipeError, load
from stressfields.scenarios import REGISTRY

def fast(n):
    return settings(max_examples=n, derandomize=True, deadline=None, database=None,
                    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])

PARAMS = sorted({p.name for s in REGISTRY.values() for p in s.parameters}) + ["bogus", "x.y"]
VALUES = ["0.3", "-1", "1e308", "1e-300", "nan", "inf", "-inf", "true", '"text"', "[]", "[0.3, 0.0, 0.1]",
          "[0.0, 0.1]", "[[1.0]]", "{start = -1.0, stop = 1.0, num = 100000000}",
          "{start = 0.0, stop = 1.0, num = 5}", "{start = 1, stop = 1, num = 3}", "{num = 1}",
          "{start = 1e-300, stop = 2e-300, num = 9, log = true}", "99999999999999999999", "1979-05-27",
          '"power_law"', '"tabulated"', "[0.0, 1e-300, 2e-300, 3e-300, 1.0]", "{}", '["conical"]']
TABLES = ['[output]\nvariables = ["sigma_xx", "nope"]\n', "[output]\nchunks = { x = 1 }\n",
          "[output]\nchunks = { x = -5 }\n", '[method]\nmethod = "fft"\nrtol = 0.5\n', "[method]\nrtol = 1e-12\n",
          '[plot]\nx = "nope"\n', '[plot]\nhue = ["a"]\n', '[plot]\nkind = "map"\n', '[plot]\nkind = "line"\n',
          '[plot]\nmarker = 3\nylim = [1.0, 0.0]\n', '[plot]\nvariables = []\n', "[plot]\nfrobnicate = 1\n",
          "[[parameters]]\n", "[parameters.x]\nstart = 0\n"]
SCENARIOS = ['"conical"', '"wavy"', '"axisymmetric"', '"graded_normal"', "3"]
HOSTILE = ["a" + ".a" * 40 + " = 1\n", "x = " + "[" * 2000 + "]" * 2000 + "\n",
           "x = " + "{a=" * 50 + "1" + "}" * 50 + "\n", "x = 1" + "0" * 5000 + "\n", '"""', "\x00\x01\x02",
           "scenario = 'conical'\n" * 2]


@st.composite
def recipe_texts(draw):
    lines = []
    if draw(st.integers(0, 9)):
        lines.append("scenario = " + draw(st.sampled_from(SCENARIOS)))
    lines.append("[parameters]")
    for name in draw(st.lists(st.sampled_from(PARAMS), max_size=4, unique=True)):
        lines.append(f"{name} = {draw(st.sampled_from(VALUES))}")
    if draw(st.booleans()):
        lines.append("x = [0.5, 1.0]")
    text = "\n".join(lines) + "\n" + "".join(draw(st.lists(st.sampled_from(TABLES), max_size=2)))
    if draw(st.integers(0, 4)) == 0:
        text += draw(st.sampled_from(HOSTILE))
    return text.encode() + (draw(st.binary(max_size=8)) if draw(st.integers(0, 5)) == 0 else b"")


def _run(argv, folder, capsys):
    before = sorted(os.listdir(folder))
    try:
        code = cli.main(argv)
    except SystemExit as exc:           # argparse's own usage errors
        code = exc.code
    err = capsys.readouterr().err
    assert "Traceback" not in err, err
    assert code in (0, 2), (code, err)
    if code == 2:
        assert err.strip()
        assert sorted(os.listdir(folder)) == before
    return code


@pytest.mark.slow   # ~6 s of fuzzed files; the property tests of bad input stay
@fast(1200)
@given(text=recipe_texts())
def test_hostile_recipe_files(text, tmp_path_factory, capsys):
    folder = tmp_path_factory.mktemp("fuzz")
    path = folder / "r.toml"
    path.write_bytes(text)
    _run(["validate", str(path)], folder, capsys)


@fast(200)
@given(text=recipe_texts())
def test_hostile_recipe_runs_write_nothing_on_error(text, tmp_path_factory, capsys):
    folder = tmp_path_factory.mktemp("fuzzrun")
    path = folder / "r.toml"
    path.write_bytes(text)
    try:
        load(path)
    except RecipeError:
        _run(["run", str(path), "-o", str(folder / "o.nc"), "-q"], folder, capsys)


TOKENS = ["run", "validate", "describe", "hash", "export", "list", "--chunks", "x=1", "x=0", "mu=1", "=",
          "--scheduler", "nowhere", "-o", "--out-dir", "--resume", "--parts", "--overwrite", "--frobnicate",
          "conical", "-q", "--dry-run", "missing.toml", "bad.toml", "deep.toml", "big.toml", "/dev/null",
          "out.nc", "out.zarr", "--plot", ".", ""]


@fast(700)
@given(argv=st.lists(st.sampled_from(TOKENS), min_size=1, max_size=6))
def test_hostile_command_lines(argv, tmp_path_factory, monkeypatch, capsys):
    folder = tmp_path_factory.mktemp("argv")
    (folder / "bad.toml").write_text('scenario = "conical"\n[parameters]\nnu = 2.0\n')
    (folder / "deep.toml").write_text("x = " + "[" * 2000 + "]" * 2000 + "\n")
    (folder / "big.toml").write_text('scenario = "conical"\n[parameters]\n'
                                     'x = {start=-1.0, stop=1.0, num=100000000}\n')
    monkeypatch.chdir(folder)
    _run(argv, folder, capsys)


@pytest.mark.parametrize("special", ["/dev/zero", "fifo"])
def test_special_files_are_refused_at_once(special, tmp_path, capsys):
    path = special
    if special == "fifo":
        path = tmp_path / "r.toml"
        os.mkfifo(path)
    assert cli.main(["validate", str(path)]) == 2
    assert "not a regular file" in capsys.readouterr().err


def test_limits_are_checked_before_parsing(tmp_path):
    big = tmp_path / "big.toml"
    big.write_text("# " + "x" * recipe.MAX_RECIPE_BYTES)
    with pytest.raises(RecipeError, match="at most 1,000,000"):
        load(big)
    dotted = tmp_path / "dotted.toml"
    dotted.write_text("a" + ".a" * 100_000 + " = 1\n")      # 24 GB in the TOML parser if not refused
    with pytest.raises(RecipeError, match="dotted parts"):
        load(dotted)
    latin = tmp_path / "latin.toml"
    latin.write_bytes('title = "Poisson\xe9"\n'.encode("latin-1"))
    with pytest.raises(RecipeError, match="not UTF-8"):
        load(latin)
