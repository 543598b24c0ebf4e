"""Routes per variable group and scales declared once.

* Every float variable of a recipe of each scenario, under every method the scenario offers, carries
  the route and accuracy the family's route table (``routes.resolve``) gives for the variable's own
  group, asked here directly; a method the table refuses is one "method." message of the check.
* The scale arithmetic lives in the Scale declarations and ``scenarios.scales``: E* = E/(1-nu^2) is
  written once, ``comparison.py`` holds no scale table and parses no scale text, and the scenarios
  call the axisymmetric kernels per unit E*.
* Applying the stress scale after the invariants (as the kernels per unit E* require) moves von Mises,
  the principal stresses and tau_max by rounding only: bounded here against the invariants of the
  scaled tensor, at the points of real fields.
* The scales' values: p_m of the Scale equals F_N/(pi a^2) from the written force and radius.
"""
from __future__ import annotations

import re
import tomllib
from pathlib import Path

import numpy as np
import pytest

import stressfields as sf
from stressfields.build import build
from stressfields.recipe import RecipeError, load
from stressfields.scenarios import REGISTRY

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "stressfields"
AXISYMMETRIC = {"conical": "cone", "parabolic": "paraboloid", "axisymmetric": None, "axisymmetric_history": None}
#: variables added to an axisymmetric recipe's list so that every group of the family is stamped
EXTRA = ("u_x", "u_z", "tau_max_peak", "von_mises_peak_depth", "mean_pressure", "stick_radius", "dpdz")


def _tangential(values) -> bool:
    mu = np.asarray(values.get("mu", 0.0), dtype=float)
    moved = [np.asarray(values.get(k, 0.0), dtype=float) for k in ("ux0", "fx", "tangential_force")]
    history = np.asarray(values.get("ux0_history", ()), dtype=float)
    if history.size:
        moved.append(np.max(np.asarray(values.get("amplitude", 1.0))) * np.abs(history))
    return bool(np.any(mu > 0.0) and any(np.any(m > 0.0) for m in moved))


def _expected(scenario: str, values, method: str, rtol: float, group: str) -> tuple[str, str]:
    """What the family's route table says for the group, asked directly."""
    if scenario in AXISYMMETRIC:
        from stressfields.physics.axisymmetric.routes import GROUPS, resolve

        assert group in GROUPS
        kind = AXISYMMETRIC[scenario] or values.get("profile", "paraboloid" if "history" in scenario else "power_law")
        return tuple(resolve(kind, method, rtol, values.get("n"), group=group, z=values.get("z"),
                             tangential=_tangential(values)))
    if scenario == "wavy":
        from stressfields.physics.wavy.routes import GROUPS, resolve

        assert group in GROUPS
        return tuple(resolve(method, rtol, below=values.get("z") is not None, group=group))
    from stressfields.physics.graded.routes import GROUPS, resolve

    assert group in GROUPS
    k = values.get("k", 0.5) if values.get("z") is not None else None
    return tuple(resolve(values.get("profile", "parabolic"), method, rtol, group=group, k=k))


#: one recipe of every scenario, below the surface where it has depths (each file of recipes/ took 85 s)
RECIPES = ("cone_subsurface", "hertz_subsurface", "power_law_n4_subsurface", "tabulated_hyperboloid",
           "history_hertz_fretting_subsurface", "wavy_fig2", "wavy_subsurface_slip", "graded_subsurface",
           "graded_subsurface_adhesive", "graded_fig9_stick_radius")


def _cases():
    for path in (ROOT / "recipes" / f"{name}.toml" for name in RECIPES):
        data = tomllib.loads(path.read_text())
        for method in REGISTRY[data["scenario"]].methods:
            yield pytest.param(path, method, id=f"{path.stem}-{method}")


@pytest.mark.parametrize(("path", "method"), list(_cases()))
def test_every_float_variable_carries_its_groups_route(path, method):
    data = tomllib.loads(path.read_text())
    data.pop("plot", None)
    data["method"] = {**data.get("method", {}), "method": method}
    scen = REGISTRY[data["scenario"]]
    if data["scenario"] in AXISYMMETRIC:
        physical = "E" in data.get("parameters", {})
        listed = data.setdefault("output", {}).get("variables") or list(
            scen.defaults(physical, set(data.get("parameters", {}))))
        names = {v.name for v in scen.available(physical, set(data.get("parameters", {})))}
        data["output"]["variables"] = list(dict.fromkeys([*listed, *(n for n in EXTRA if n in names)]))
    try:
        recipe = load(data)
    except RecipeError as exc:
        # the route table refuses the method for this recipe: said once, in its words, after "method."
        routed = [p for p in exc.problems if "method.method" in p or p.startswith("method.")]
        assert routed, exc.problems
        return
    ds = build(recipe)              # lazy: the attributes, nothing computed
    stamped = 0
    for name, var in ds.variables.items():
        if name not in {v.name for v in scen.variables} or name in recipe.values or var.dtype.kind != "f":
            continue
        group = scen.variable(name).group
        want = _expected(scen.name, recipe.values, recipe.method, recipe.rtol, group)
        assert (var.attrs["stressfields_method"], var.attrs["stressfields_accuracy"]) == want, (name, group)
        stamped += 1
    assert stamped


def test_displacements_say_their_own_route():
    """The cone's stresses have closed forms, its displacements do not: each says its own route."""
    ds = sf.generate({"scenario": "conical", "parameters": {"x": [0.5, 1.5], "z": [0.0, 0.5]},
                      "output": {"variables": ["sigma_xx", "u_z", "tau_max_peak"]}, "method": {"method": "closed"}})
    assert ds.sigma_xx.attrs["stressfields_method"].startswith("z = 0: closed form")
    assert "superposition of punches" in ds.u_z.attrs["stressfields_method"]
    assert "no closed form" in ds.u_z.attrs["stressfields_method"] and "delta" in ds.u_z.attrs["stressfields_accuracy"]
    assert ds.tau_max_peak.attrs["stressfields_method"].startswith("converged search")
    para = sf.generate({"scenario": "parabolic", "parameters": {"x": [0.5]}, "output": {"variables": ["u_z"]}})
    assert para.u_z.attrs["stressfields_method"] == "closed form"


@pytest.mark.parametrize(("scenario", "parameters", "method", "words"), [
    ("conical", {"x": [0.5], "z": [0.5], "mu": 0.3, "ux0": 0.1}, {"method": "closed"},
     "method.method = 'closed' has no closed form below the surface (z > 0) under tangential load"),
    ("axisymmetric", {"n": 1.5, "x": [0.5], "z": [0.5]}, {"rtol": 1e-13}, "method.rtol = 1e-13 is below 1e-12"),
    ("axisymmetric", {"n": 1.5, "x": [0.5]}, {"method": "closed"},
     "method.method = 'closed' has no closed form for profile = 'power_law'"),
])
def test_route_refusals_are_one_check_message(scenario, parameters, method, words):
    with pytest.raises(RecipeError) as info:
        load({"scenario": scenario, "parameters": parameters, "method": method})
    assert any(p.startswith(words) for p in info.value.problems), info.value.problems


def test_every_table_takes_the_defaults():
    """A recipe that names no [method] is not route-checked (no kernel is loaded to validate it): every
    scenario's table must take auto at the default rtol for every group it declares."""
    for scen in REGISTRY.values():
        groups = tuple(dict.fromkeys(v.group for v in scen.variables if not v.flag_values))
        values = {"z": np.array([0.0, 1.0]), "mu": 0.3, "ux0": 0.5, "k": 0.5}
        assert set(scen.route(values, "auto", 1e-10, groups)) == set(groups), scen.name


# -- the scale arithmetic lives in one place -------------------------------------------------------

def _sources():
    return {p.relative_to(PACKAGE).as_posix(): p.read_text() for p in PACKAGE.rglob("*.py")}


def test_effective_modulus_is_formed_once():
    pattern = re.compile(r"1(\.0)?\s*-\s*[\w\"'\[\](), .]*nu[\w\"'\[\]()]*\s*\*\*\s*2")
    found = {name for name, text in _sources().items() if pattern.search(text)}
    # physics/graded/material.py forms the graded material's own compliance (1 - nu*nu)/(h E0), not E*
    assert found == {"scenarios/scales.py"}, found


def test_comparison_has_no_scale_table():
    text = (PACKAGE / "comparison.py").read_text()
    assert "_SCALES" not in text and "SCALE_SYMBOLS" not in text
    assert not re.search(r"scale\w*\.startswith", text)
    assert "math.pi" not in text and "lambda_1" not in text.split('"""', 2)[2]
    for name, text in _sources().items():
        assert "SCALE_SYMBOLS" not in text, name


def test_scenarios_call_the_kernels_per_unit_e_star():
    """The axisymmetric entry points are called without a scale (or with 1, while they still take one):
    every factor is the Scale's, applied after."""
    for name in ("scenarios/axisymmetric.py", "scenarios/history.py"):
        text = (PACKAGE / name).read_text()
        calls = re.findall(r"ax\.(?:history_)?fields\((.*?)\)\n", text, flags=re.S)
        assert calls, name
        for call in calls:
            assert set(re.findall(r"\b(?:dpdz_)?scale=([\w.]+)", call)) <= {"1.0"}, (name, call)


# -- the invariants of the scaled tensor, and the scales' values ---------------------------------------

@pytest.mark.parametrize("recipe", [
    {"scenario": "parabolic", "parameters": {"R": 0.01, "E": 2.1e11, "nu": 0.3, "normal_force": 100.0, "mu": 0.3,
                                             "fx": 0.5, "x": {"start": -2e-4, "stop": 2e-4, "num": 9},
                                             "z": [0.0, 5e-5]}},
    {"scenario": "axisymmetric", "parameters": {"n": 4.0, "mu": 0.2, "ux0": 0.05, "x": [-1.5, -0.3, 0.2, 0.9],
                                                "y": [0.0, 0.4], "z": [0.0, 0.3]}},
], ids=["physical-hertz-mindlin", "normalised-power-law"])
def test_invariants_are_those_of_the_scaled_tensor(recipe):
    """The invariants are formed from the tensor in the variables' units (normalised by p_m, or in
    pascals), not scaled from per unit E*: to the last bit the invariants of the dataset's own tensor
    (scaling them instead moves von Mises by up to 4 eps, the principal stresses by up to 16 eps of
    the largest |component|)."""
    from stressfields.physics.invariants import principal_stresses, von_mises

    names = ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "sigma_yz", "von_mises", "sigma_1",
             "sigma_2", "sigma_3", "tau_max"]
    ds = sf.generate({**recipe, "output": {"variables": names}}).compute()
    tensor = [ds[n].values for n in names[:6]]
    finite = np.all([np.isfinite(t) for t in tensor], axis=0)
    assert finite.sum() > 10
    np.testing.assert_array_equal(ds.von_mises.values[finite], von_mises(*tensor)[finite])
    s1, s2, s3 = (v[finite] for v in principal_stresses(*tensor))
    for name, want in (("sigma_1", s1), ("sigma_2", s2), ("sigma_3", s3), ("tau_max", 0.5 * (s1 - s3))):
        np.testing.assert_array_equal(ds[name].values[finite], want, err_msg=name)


def test_scale_values_are_the_contact_quantities():
    """p_m of the Scale (what compare divides by) against F_N/(pi a^2) of the written force and radius;
    the wavy p* against its definition pi E/(1-nu^2) Delta_1/lambda_1."""
    from stressfields.scenarios.axisymmetric import PM, PM_PER_A
    from stressfields.scenarios.wavy import PSTAR

    ds = sf.generate({"scenario": "parabolic", "parameters": {"R": 0.01, "E": 2.1e11, "nu": 0.3, "delta": 1e-5,
                                                              "x": [0.0]},
                      "output": {"variables": ["mean_pressure", "contact_radius", "normal_force"]}}).compute()
    q = {n: ds[n] for n in ("mean_pressure", "contact_radius")}
    a, force = float(ds.contact_radius), float(ds.normal_force)
    assert float(PM.value(q)) == pytest.approx(force / (np.pi * a * a), rel=1e-14)
    assert float(PM_PER_A.value(q)) == pytest.approx(force / (np.pi * a ** 3), rel=1e-14)
    E, nu, amp, lam = 7e10, 0.25, 2e-6, 1e-3
    assert float(PSTAR.value({"E": E, "nu": nu, "amplitudes": [amp], "lambda_1": lam})) == pytest.approx(
        np.pi * E / (1 - nu * nu) * amp / lam, rel=1e-15)
