"""Physical loads across 600 decades of magnitude: the contact radius a, the depth delta and the mean
pressure p_m of every physical-load scenario agree with their closed forms evaluated in 50-digit
arithmetic (mpmath; Hertz a^3 = 3 F_N R/(4 E*), the cone's F_N = (pi/2) tan(theta) E* a^2, Sneddon's
power law, the flat punch's delta = F_N/(2 E* radius)) to 1e-12, or the recipe is refused before any
work (RecipeError, `validate` exit code 2) naming the load and its valid range. A refusal is allowed
only where some quantity of the contact leaves [1e-280, 1e280], so the check cannot pass by
refusing everything."""
import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

import stressfields as sf
from stressfields import cli

mp.mp.dps = 50
TABLE = [4e-3 * i / 40 for i in range(41)]
TABULATED = {"profile": "tabulated", "profile_r": TABLE, "profile_f": [r * r / (2 * 0.01) for r in TABLE]}
#: every quantity of an accepted contact within this range must be accepted (the refusal's bound,
#: 1e-300 .. 1e300, with room for the profiles' constants)
SAFE = (mp.mpf("1e-280"), mp.mpf("1e280"))
DECLARED = {"normal_force": 1e15, "delta": 1e3, "E": 1e15, "R": 1e6, "radius": 1e6, "A": 1e30}


def _kappa(n):
    return mp.sqrt(mp.pi) * mp.gamma(n / 2 + 1) / mp.gamma(n / 2 + mp.mpf(1) / 2)


def reference(kind, geometry, load, control, E, nu):
    """(a, delta, p_m, every quantity the contact forms) in 50 digits; the power-law families through
    n and B = kappa_n A n (g = (B/n) a^n, F_N/E* = 2B a^(n+1)/(n+1)), the punch through its radius."""
    e_star = mp.mpf(E) / (1 - mp.mpf(nu) ** 2)
    if kind == "flat_punch":
        a = mp.mpf(geometry["radius"])
        delta = mp.mpf(load) / (2 * e_star * a) if control == "normal_force" else mp.mpf(load)
        force = 2 * e_star * a * delta
        powers = [a * a]
    else:
        n, B = {"cone": lambda: (mp.mpf(1), mp.pi / 2 * mp.tan(mp.mpf(geometry.get("theta", 0.0)))),
                "paraboloid": lambda: (mp.mpf(2), 2 / mp.mpf(geometry.get("R", 1.0))),
                "power_law": lambda: (mp.mpf(geometry["n"]), _kappa(mp.mpf(geometry["n"])) * mp.mpf(geometry["A"])
                                      * mp.mpf(geometry["n"]))}[kind]()
        if control == "normal_force":
            a = ((n + 1) * mp.mpf(load) / (2 * B * e_star)) ** (1 / (n + 1))
        else:
            a = (n * mp.mpf(load) / B) ** (1 / n)
        delta = B / n * a ** n
        force = 2 * B * e_star * a ** (n + 1) / (n + 1)
        powers = [a * a, a ** n, a ** (n + 1)]
    pm = force / (mp.pi * a * a)
    return a, delta, pm, [a, delta, force, force / e_star, pm, pm / e_star, e_star] + powers


GEOMETRY = {
    "parabolic": ("paraboloid", st.builds(lambda e: {"R": 10.0 ** e}, st.floats(-320, 8))),
    "conical": ("cone", st.builds(lambda t: {"theta": t}, st.floats(1e-6, 1.5707))),
    "axisymmetric": ("power_law", st.builds(lambda e, n: {"A": 10.0 ** e, "n": n}, st.floats(-300, 32),
                                            st.floats(0.3, 50.0))),
    "flat_punch": ("flat_punch", st.builds(lambda e: {"profile": "flat_punch", "radius": 10.0 ** e},
                                           st.floats(-320, 8))),
    # a paraboloid (R = 10 mm) tabulated to 4 mm: the spline of a quadratic is the quadratic, so the
    # contact obeys Hertz, which the tabulated inversion (a bisection on log a) does not use
    "tabulated": ("paraboloid", st.just(TABULATED)),
    # the loading history of a cone shares the load control
    "axisymmetric_history": ("cone", st.builds(lambda t: {"profile": "cone", "theta": t, "mu": 0.3,
                                                          "ux0_history": [0.1]}, st.floats(1e-6, 1.5707))),
}
TABLE_END = 4e-3
EXAMPLE = {"parabolic": {"R": 0.01}, "conical": {"theta": 0.2}, "axisymmetric": {"A": 2e3, "n": 3.0},
           "flat_punch": {"profile": "flat_punch", "radius": 1e-3}, "tabulated": TABULATED,
           "axisymmetric_history": {"profile": "cone", "theta": 0.2, "mu": 0.3, "ux0_history": [0.1]}}


def _recipe(scenario, geometry, control, load, E, nu):
    name = "axisymmetric" if scenario in ("flat_punch", "tabulated") else scenario
    return {"scenario": name, "parameters": {**geometry, "E": E, "nu": nu, control: load, "x": 0.0},
            "output": {"variables": ["mean_pressure"] + (["contact_radius", "delta"] if control == "normal_force"
                                                         else [])}}


def _inside_declared(params, control):
    return all(0.0 < params[k] <= DECLARED[k] for k in ("E", control, "R", "radius", "A") if k in params)


@pytest.mark.parametrize("scenario", sorted(GEOMETRY))
@pytest.mark.parametrize("control", ["normal_force", "delta"])
def test_loads_across_600_decades_are_right_or_refused(scenario, control):
    kind, geometries = GEOMETRY[scenario]
    seen = {"accepted": 0, "refused": 0}

    @settings(max_examples=15, deadline=None, derandomize=True,
              suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
    # besides the draws, one real contact and one 1e-320 load, so that both outcomes are always seen
    @example(geometry=EXAMPLE[scenario], load_exp=0.0 if control == "normal_force" else -6.0, e_exp=11.0, nu=0.3)
    @example(geometry=EXAMPLE[scenario], load_exp=-320.0, e_exp=11.0, nu=0.3)
    @given(geometry=geometries, load_exp=st.floats(-330.0, 20.0), e_exp=st.floats(-330.0, 16.0),
           nu=st.floats(0.0, 0.5))
    def check(geometry, load_exp, e_exp, nu):
        if kind == "flat_punch" and control == "delta":
            return                        # a flat punch's delta is a plain scale: nothing is derived from it
        load, E = 10.0 ** load_exp, 10.0 ** e_exp
        recipe = _recipe(scenario, geometry, control, load, E, nu)
        if not (load > 0.0 and E > 0.0):  # 10^-330 is 0 in float64: the declared range refuses it
            return
        a, delta, pm, quantities = reference(kind, {"R": 0.01} if scenario == "tabulated" else geometry, load,
                                             control, E, nu)
        safe = (_inside_declared(recipe["parameters"], control)
                and all(SAFE[0] <= q <= SAFE[1] for q in quantities)
                and (scenario != "tabulated" or a < TABLE_END * (1 - 1e-9)))
        try:
            ds = sf.generate(recipe).compute()
        except sf.RecipeError as exc:
            assert not safe, f"refused although every quantity is well inside float64: {exc}"
            assert control in str(exc) or "E =" in str(exc) or any(k in str(exc) for k in ("R", "theta", "radius",
                                                                                            "A", "n")), str(exc)
            seen["refused"] += 1
            return
        seen["accepted"] += 1
        got = {"mean_pressure": pm, "contact_radius": a, "delta": delta}
        for name in recipe["output"]["variables"]:
            value = float(ds[name].values)
            assert value == pytest.approx(float(got[name]), rel=1e-12), (name, recipe)

    check()
    if not (kind == "flat_punch" and control == "delta"):
        assert seen["accepted"] >= 2 and seen["refused"] >= 1, seen     # both sides of the range were drawn


@pytest.mark.parametrize("scenario, params", [
    ("parabolic", {"R": 0.01, "normal_force": 1e-320}),        # a underflowed to 0: ValueError in run
    ("parabolic", {"R": 0.01, "normal_force": 1e-310}),        # a^3 52 % off, flagged valid
    ("parabolic", {"R": 1e6, "delta": 1e-300}),                # F_N/E* = 4 a^3/(3R) underflows
    ("conical", {"theta": 0.1, "normal_force": 1e-320}),
    ("axisymmetric", {"n": 50.0, "A": 1e30, "normal_force": 1e-280}),   # a^51 = 2e-323 (a = 1e-6 m)
])
def test_the_extreme_loads_of_the_reports_are_refused_before_work(tmp_path, capsys, scenario, params):
    recipe = tmp_path / "r.toml"
    body = "\n".join(f"{k} = {v!r}" for k, v in {"E": 210e9, "nu": 0.3, "x": 0.0, **params}.items())
    recipe.write_text(f'scenario = "{scenario}"\n[parameters]\n{body}\n')
    assert cli.main(["validate", str(recipe)]) == 2
    assert cli.main(["run", str(recipe), "-o", str(tmp_path / "r.nc"), "-q"]) == 2
    err = capsys.readouterr().err
    load = "normal_force" if "normal_force" in params else "delta"
    assert f"give {load} in [" in err and "Traceback" not in err
    assert len([line for line in err.splitlines() if load + " =" in line]) == 2   # one line per command
    assert not list(tmp_path.glob("r.nc*"))


def test_the_stated_range_is_accepted_and_right_at_both_ends():
    """The range the refusal names is accepted at its ends and gives Hertz there."""
    base = {"R": 0.01, "E": 210e9, "nu": 0.3, "x": 0.0}
    with pytest.raises(sf.RecipeError) as info:
        sf.generate({"scenario": "parabolic", "parameters": {**base, "normal_force": 1e-310}})
    text = str(info.value)
    low, high = (float(v) for v in text.split("give normal_force in [")[1].split("]")[0].split(","))
    for force in (low * (1 + 1e-3), high):
        ds = sf.generate({"scenario": "parabolic", "parameters": {**base, "normal_force": force},
                          "output": {"variables": ["contact_radius", "mean_pressure"]}}).compute()
        a, _, pm, _ = reference("paraboloid", base, force, "normal_force", base["E"], base["nu"])
        assert float(ds.contact_radius) == pytest.approx(float(a), rel=1e-12)
        assert float(ds.mean_pressure) == pytest.approx(float(pm), rel=1e-12)
    assert math.isclose(high, 1e15)      # the declared maximum binds first for a steel ball
    assert np.isfinite(low) and low < 1e-250


@pytest.mark.parametrize("control, load", [("normal_force", 1e-60), ("normal_force", 1e-200), ("delta", 1e-100)])
def test_a_tabulated_contact_far_below_the_table_spacing_is_right(control, load):
    """The tabulated inversion bisected [0, r_max] arithmetically to 2^-80 r_max: 1e-60 N on this 4 mm
    table came out 0.5 % off and 1e-100 N 1e11 times too large, flagged valid."""
    geometry = TABULATED
    E, nu = 2e11, 0.3
    ds = sf.generate(_recipe("tabulated", geometry, control, load, E, nu)).compute()
    a, delta, pm, _ = reference("paraboloid", {"R": 0.01}, load, control, E, nu)
    assert float(ds.mean_pressure) == pytest.approx(float(pm), rel=1e-12)
    if control == "normal_force":
        assert float(ds.contact_radius) == pytest.approx(float(a), rel=1e-12)
        assert float(ds.delta) == pytest.approx(float(delta), rel=1e-12)
