"""Property-based: any invalid recipe or command line gets a clear error and exit code 2, no
traceback, and nothing is written."""
import json
import tomllib

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from stressfields import cli
from stressfields.recipe import RecipeError, load
from stressfields.scenarios import REGISTRY

junk = st.one_of(st.none(), st.booleans(), st.integers(-10**6, 10**6), st.floats(allow_nan=True),
                 st.text(max_size=8), st.lists(st.floats(allow_nan=True), max_size=3),
                 st.dictionaries(st.sampled_from(["start", "stop", "num", "log", "step"]),
                                 st.one_of(st.integers(-3, 5), st.floats(-2, 2), st.booleans()), max_size=4))


@st.composite
def bad_recipes(draw):
    scenario = draw(st.sampled_from(sorted(REGISTRY)))
    scen = REGISTRY[scenario]
    names = [p.name for p in scen.parameters] + ["bogus", "Nu", "x0"]
    params = draw(st.dictionaries(st.sampled_from(names), junk, min_size=1, max_size=4))
    recipe = {"scenario": draw(st.sampled_from([scenario, scenario, "nope", 3])), "parameters": params}
    if draw(st.booleans()):
        recipe["output"] = {"variables": draw(st.one_of(st.lists(st.text(max_size=6), max_size=2), junk)),
                            "chunks": draw(st.one_of(st.dictionaries(st.text(max_size=3), junk, max_size=2), junk))}
    if draw(st.booleans()):
        recipe["method"] = {"method": draw(st.one_of(st.text(max_size=6), junk)), "rtol": draw(junk)}
    return recipe


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(bad_recipes())
def test_recipe_loader_never_raises_anything_but_recipe_error(recipe):
    try:
        load(recipe)
    except RecipeError as exc:
        assert exc.problems and all(isinstance(p, str) and p for p in exc.problems)


def _toml(value) -> str:
    return json.dumps(value)   # JSON scalars, arrays and inline tables of these types are valid TOML


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(recipe=bad_recipes())
def test_cli_run_on_bad_recipes(tmp_path_factory, recipe, capsys):
    folder = tmp_path_factory.mktemp("bad")
    lines = [f"scenario = {_toml(recipe['scenario'])}", "[parameters]"]
    for k, v in recipe["parameters"].items():
        if v is None or (isinstance(v, float) and v != v) or (isinstance(v, list) and any(x != x for x in v)):
            v = "nan?"   # TOML has no null; NaN spelled as a string is just as invalid
        lines.append(f"{k} = {_toml(v) if not isinstance(v, dict) else _inline(v)}")
    text = "\n".join(lines) + "\n"
    try:
        tomllib.loads(text)
    except tomllib.TOMLDecodeError:
        text = "scenario = 'conical'\n[parameters]\nnu = 'soft'\nx = [0.0]\n"
    path = folder / "r.toml"
    path.write_text(text)
    out = folder / "o.nc"
    try:
        load(path)
    except RecipeError:
        code = cli.main(["run", str(path), "-o", str(out), "-q"])
        err = capsys.readouterr().err
        assert code == 2 and "Traceback" not in err and err.startswith("error:")
        assert sorted(p.name for p in folder.iterdir()) == ["r.toml"]


def _inline(d: dict) -> str:
    return "{ " + ", ".join(f"{k} = {json.dumps(v)}" for k, v in d.items()) + " }"


@pytest.mark.parametrize("argv", [
    ["run"], ["run", "missing.toml"], ["frobnicate"], ["describe"], ["run", "recipes/cone_fig2_sigma_xx.toml",
                                                                     "--chunks", "x=abc"],
    ["run", "recipes/cone_fig2_sigma_xx.toml", "--chunks", "x=0"],
    ["run", "recipes/cone_fig2_sigma_xx.toml", "recipes/cone_fig3_von_mises.toml", "-o", "x.nc"],
    # waits out the connection timeout (10 s): with the fault-injection tests
    pytest.param(["run", "recipes/cone_fig2_sigma_xx.toml", "--scheduler", "tcp://127.0.0.1:1"],
                 marks=pytest.mark.slow),
])
def test_bad_command_lines_exit_2(argv, tmp_path, monkeypatch, capsys):
    import os
    from pathlib import Path
    root = Path(__file__).resolve().parents[1]
    monkeypatch.chdir(tmp_path)
    argv = [str(root / a) if a.startswith("recipes/") else a for a in argv]
    with pytest.raises(SystemExit) as info:
        raise SystemExit(cli.main(argv))
    assert info.value.code == 2
    assert "Traceback" not in capsys.readouterr().err
    assert os.listdir(tmp_path) == []


TOKENS = ["run", "validate", "describe", "hash", "export", "--chunks", "x=0", "x=-3", "mu=1", "=", "x=",
          "--scheduler", "nowhere", "-o", "--out-dir", "--resume", "--parts", "--overwrite", "--frobnicate",
          "conical", "nothing", "-q", "--dry-run", "missing.toml", "bad.toml", "out.nc"]


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(argv=st.lists(st.sampled_from(TOKENS), min_size=1, max_size=6))
def test_random_command_lines_never_trace_back(argv, tmp_path_factory, monkeypatch, capsys):
    import os

    folder = tmp_path_factory.mktemp("cli")
    (folder / "bad.toml").write_text('scenario = "conical"\n[parameters]\nnu = 2.0\n')
    monkeypatch.chdir(folder)
    try:
        code = cli.main(argv)
    except SystemExit as exc:         # argparse's own usage errors
        code = exc.code
    err = capsys.readouterr().err
    assert "Traceback" not in err
    assert code in (0, 2)
    if code == 2:
        assert err.strip()
        assert sorted(os.listdir(folder)) == ["bad.toml"]
