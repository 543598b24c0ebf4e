"""Recipe validation: every invalid recipe gets a message naming the key, the value and what is allowed."""
import numpy as np
import pytest

from stressfields.recipe import RecipeError, load

BASE = {"scenario": "conical", "parameters": {"x": [0.5]}}


def recipe(**params):
    return {"scenario": "conical", "parameters": {"x": [0.5], **params}}


def problems(data):
    with pytest.raises(RecipeError) as info:
        load(data)
    return " | ".join(info.value.problems)


def test_minimal_recipe_gets_defaults():
    r = load(BASE)
    assert r.values["nu"] == 0.3 and r.values["mu"] == 0.0 and r.values["ux0"] == 0.0
    assert r.swept == ("x",)
    assert not r.physical


def test_sweep_forms():
    r = load(recipe(mu=[0.0, 0.1], nu={"start": 0.0, "stop": 0.5, "num": 6},
                    x={"start": 0.01, "stop": 10.0, "num": 4, "log": True}))
    assert r.swept == ("nu", "mu", "x")
    np.testing.assert_allclose(r.values["nu"], np.linspace(0, 0.5, 6))
    np.testing.assert_allclose(r.values["x"], [0.01, 0.1, 1.0, 10.0])
    assert r.shape == {"nu": 6, "mu": 2, "x": 4}


@pytest.mark.parametrize("params, words", [
    ({"nu": 0.6}, ["nu = 0.6", "[0, 0.5]"]),
    ({"nu": -0.1}, ["nu = -0.1", "[0, 0.5]"]),
    ({"mu": -0.2}, ["mu = -0.2", "[0, 10]"]),
    ({"mu": [0.1, -0.1]}, ["mu sweep value -0.1", "[0, 10]"]),
    ({"nu": "soft"}, ["nu = 'soft'", "a number"]),
    ({"nu": True}, ["nu = True"]),
    ({"mu": {"start": 0, "stop": 1}}, ["mu", "start, stop, num", "missing", "num"]),
    ({"mu": {"start": 0, "stop": 1, "num": 0}}, ["mu.num = 0", "integer"]),
    ({"mu": {"start": 0, "stop": 1, "num": 3, "step": 1}}, ["unknown key", "step"]),
    ({"x": {"start": -1, "stop": 1, "num": 3, "log": True}}, ["log sweep", "start > 0"]),
    ({"mu": []}, ["empty sweep"]),
    ({"mu": [0.1, 0.1]}, ["repeats a value"]),
    ({"friction": 0.3}, ["unknown parameter 'friction'", "allowed: nu, mu"]),
    ({"theta": 0.1}, ["'theta' is only used in physical mode", "give 'E'"]),
])
def test_bad_parameters_are_named(params, words):
    msg = problems(recipe(**params))
    for w in words:
        assert w in msg, (w, msg)


def test_unknown_scenario_and_keys():
    assert "scenario = 'sphere' is unknown; one of: conical, parabolic" in problems({"scenario": "sphere"})
    assert "missing key 'scenario'" in problems({"parameters": {}})
    msg = problems({**BASE, "outputs": {}})
    assert "unknown key 'outputs'" in msg and "allowed top-level keys" in msg
    assert "unknown key 'method.order'" in problems({**BASE, "method": {"order": 3}})


def test_missing_required_parameter():
    msg = problems({"scenario": "conical", "parameters": {}})
    assert "missing parameter 'x'" in msg


def test_physical_mode_needs_geometry_and_depth():
    msg = problems(recipe(E=2e11))
    assert "missing parameter 'delta'" in msg and "missing parameter 'theta'" in msg
    r = load(recipe(E=2e11, delta=1e-6, theta=0.1))
    assert r.physical


def test_output_and_method_checks():
    msg = problems({**BASE, "output": {"variables": ["sigma_xx", "tau"], "chunks": {"mu": 3}}})
    assert "unknown variable 'tau'" in msg and "available: sigma_xx" in msg
    assert "output.chunks.mu: 'mu' is not a swept dimension" in msg
    assert "method.method = 'fft'" in problems({**BASE, "method": {"method": "fft"}})
    assert "method.rtol = 0.5 must be a number in [1e-14, 0.01]" in problems({**BASE, "method": {"rtol": 0.5}})
    msg = problems({**BASE, "output": {"variables": ["contact_radius"]}})
    assert "'contact_radius'" in msg and "in this mode" in msg


def test_axisymmetric_profile_rules():
    base = {"scenario": "axisymmetric", "parameters": {"x": [0.5]}}
    assert "missing parameter 'n'" in problems(base)
    tab = {"scenario": "axisymmetric",
           "parameters": {"x": [0.5], "profile": "tabulated", "profile_r": [0.0, 0.5, 1.0, 1.5],
                          "profile_f": [0.0, 0.1, 0.4]}}
    assert "profile_r has 4 values but profile_f has 3" in problems(tab)
    tab["parameters"]["profile_f"] = [0.0, 0.1, 0.4, 0.9]
    tab["parameters"]["n"] = 2.0
    assert "'n' is only used when profile = 'power_law'" in problems(tab)
    del tab["parameters"]["n"]
    tab["parameters"]["profile_r"] = [0.0, 0.2, 0.4, 0.6]
    assert "must cover the contact" in problems(tab)
    msg = problems({"scenario": "axisymmetric", "parameters": {"x": [0.5], "n": 3.0},
                    "method": {"method": "closed"}})
    assert "no closed form" in msg
    msg = problems({"scenario": "axisymmetric", "parameters": {"x": [0.5], "profile": "cylinder"}})
    assert "profile = 'cylinder' must be one of 'power_law', 'tabulated', 'flat_punch'" in msg


def test_all_problems_reported_at_once():
    msg = problems(recipe(nu=0.9, mu=-1.0))
    assert "nu = 0.9" in msg and "mu = -1.0" in msg


def test_hash_is_canonical():
    a = load(recipe(mu=[0.1, 0.2], nu=0.3))
    b = load({"parameters": {"nu": 0.3, "mu": [0.1, 0.2], "x": [0.5]}, "scenario": "conical"})
    c = load(recipe(mu=[0.1, 0.25]))
    assert a.sha256 == b.sha256 != c.sha256


def test_toml_file_errors(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("scenario = conical\n")
    with pytest.raises(RecipeError, match="not valid TOML"):
        load(bad)
    with pytest.raises(RecipeError, match="cannot read"):
        load(tmp_path / "missing.toml")


def test_sweep_sizes_are_checked_from_the_specification():
    import time

    start = time.perf_counter()
    msg = problems(recipe(x={"start": -1.0, "stop": 1.0, "num": 100_000_000}))
    assert "x: a sweep of 100,000,000 values; at most 10,000,000" in msg
    msg = problems(recipe(x={"start": -1.0, "stop": 1.0, "num": 9_000_000},
                          mu={"start": 0.0, "stop": 1.0, "num": 9_000}))
    assert "at most 1e+10 are allowed" in msg and "mu=9,000" in msg
    assert time.perf_counter() - start < 5      # nothing was expanded (was 125 s and 7.3 GB)


def test_unsorted_sweeps_and_bad_tables_are_named():
    assert "goes both ways (0.3, 0.0, 0.1)" in problems(recipe(mu=[0.3, 0.0, 0.1]))
    assert "scenario = ['conical'] is unknown" in problems({"scenario": ["conical"]})
    assert "profile_r has 10,001 values; at most 10,000" in problems(
        {"scenario": "axisymmetric", "parameters": {"x": [0.5], "profile": "tabulated",
                                                    "profile_r": [0.0] * 10001, "profile_f": [0.0] * 10001}})
    assert "plot.x = 'nope'" in problems({**BASE, "plot": {"x": "nope"}})
    assert "plot.hue = ['a']" in problems({**BASE, "plot": {"hue": ["a"]}})
    assert "needs x and y swept" in problems({**BASE, "plot": {"kind": "map"}})
    assert "needs a swept parameter" in problems({"scenario": "conical", "parameters": {"x": 0.5},
                                                  "plot": {"kind": "line"}})
    assert "output.chunks x=1 makes 200,000 chunks" in problems(
        {**BASE, "parameters": {"x": {"start": -1.0, "stop": 1.0, "num": 200_000}}, "output": {"chunks": {"x": 1}}})


def test_renamed_graded_parameters_say_their_new_names():
    bad = problems({"scenario": "graded_normal", "parameters": {"R": 0.01, "E0": 1e9, "a": 1e-3,
                                                                 "r": [0.0, 0.5]}}).split(" | ")
    assert len(bad) == 2                   # the new name is not reported missing as well
    assert "unknown parameter 'a'" in bad[0] and "now 'contact_radius'" in bad[0]
    assert "unknown parameter 'r'" in bad[1] and "now 'rho'" in bad[1]
    typo = problems({**BASE, "parameters": {"x": [0.5], "muu": 0.2}})
    assert " | " not in typo and "did you mean 'mu'?" in typo


#: the smallest valid parameters of each scenario
MINIMAL = {
    "conical": {"x": [0.5]}, "parabolic": {"x": [0.5]}, "axisymmetric": {"n": 3.0, "x": [0.5]},
    "axisymmetric_history": {"ux0_history": [0.1], "x": [0.5]},
    "wavy": {"amplitudes": [0.5], "wavenumbers": [1], "a": 0.3},
    "graded_normal": {"R": 0.01, "E0": 1e9, "contact_radius": 1e-3},
    "graded_adhesive": {"R": 0.01, "E0": 1e9, "contact_radius": 1e-3, "delta_gamma": 0.05},
    "graded_tangential": {"R": 0.01, "E0": 1e9, "contact_radius": 1e-3},
}


#: variables produced only under a further parameter: (scenario, variable) -> the parameters they need
#: what a variable needs beyond the minimal recipe: the graded peaks are solved at k = 0 (or, for the normal and
#: adhesive load, nu = 1/(2+k)); the minimal recipes take the defaults k = 0.5, nu = 0.3
NEEDS = {(scenario, f"{field}_peak{tail}"): {"k": 0.0} for scenario, position in (
    ("graded_tangential", "_x"), ("graded_normal", "_rho"), ("graded_adhesive", "_rho"))
    for field in ("tau_max", "von_mises") for tail in ("", position, "_depth")}
NEEDS.update({(scenario, "peak_validity"): {"k": 0.0}
              for scenario in ("graded_tangential", "graded_normal", "graded_adhesive")})


def test_every_declared_variable_can_be_requested():
    from stressfields.scenarios import REGISTRY

    assert set(MINIMAL) == set(REGISTRY)
    for name, scen in REGISTRY.items():
        physical = scen.physical_switch is None
        given = load({"scenario": name, "parameters": MINIMAL[name]}).values
        for var in scen.variables_in(physical):         # validity and converged included
            recipe = {"scenario": name, "parameters": {**MINIMAL[name], **NEEDS.get((name, var.name), {})},
                      "output": {"variables": [var.name]}}
            if var.name in given:       # a derived load named like a parameter given: a coordinate
                with pytest.raises(RecipeError, match=f"'{var.name}' is a parameter of this recipe"):
                    load(recipe)
            else:
                assert load(recipe).variables == (var.name,)


def test_points_is_a_top_level_table():
    """[points] (tests/test_points.py) is a known table; a misspelt one is named with the allowed keys."""
    r = load({**BASE, "parameters": {}, "points": {"x": [0.5, 0.1, 0.5]}})
    assert r.points == ("x",) and r.swept == () and r.shape == {"point": 3}
    msg = problems({**BASE, "point": {"x": [0.5]}})
    assert "unknown key 'point'" in msg and "points" in msg
