"""The graded scenarios below the surface, end to end: the depth z, the stress variables and their flag,
the peaks, the refusals (docs/theory/graded.md section 10).  Held against the axisymmetric family's
`parabolic` scenario (another scenario, another entry point) and Johnson's axis formulas for the peak."""
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

import stressfields as sf
from stressfields import cli

ROOT = Path(__file__).resolve().parents[1]
E0, A_RAD, R = 2.0e9, 1e-3, 0.02
BASE = {"E0": E0, "contact_radius": A_RAD, "R": R, "c0": 1e-3}
STRESS = ["sigma_rr", "sigma_tt", "sigma_zz", "sigma_rz", "tau_max"]


def run(params, variables, scenario="graded_normal"):
    return sf.generate({"scenario": scenario, "parameters": {**BASE, **params},
                        "output": {"variables": variables}}).compute()


def test_surface_stress_is_minus_the_pressure_bit_for_bit():
    for scenario, extra in (("graded_normal", {}), ("graded_adhesive", {"delta_gamma": 0.4})):
        ds = run({"k": [0.0, 0.5], "poisson": "holl_ratio", "rho": np.linspace(0, 1.5, 7).tolist(), "z": 0.0,
                  **extra},
                 ["pressure", "sigma_zz"], scenario)
        assert np.array_equal(ds.sigma_zz.values, -ds.pressure.transpose(*ds.sigma_zz.dims).values)


def test_k0_equals_the_axisymmetric_parabolic_scenario():
    nu = 0.3
    rho, z = [0.0, 0.4, 1.0, 1.6], [0.05, 0.5, 1.2]
    g = run({"k": 0.0, "nu": nu, "rho": rho, "z": z}, STRESS)
    ax = sf.generate({"scenario": "parabolic", "parameters": {
        "nu": nu, "E": E0, "R": R, "delta": A_RAD ** 2 / R, "y": 0.0, "x": [v * A_RAD for v in rho],
        "z": [v * A_RAD for v in z]}, "output": {"variables": ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz",
                                                               "tau_max"]}}).compute()
    for mine, theirs in zip(STRESS, ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz", "tau_max")):
        want = ax[theirs].transpose("z", "x").values
        np.testing.assert_allclose(g[mine].transpose("z", "rho").values, want, rtol=1e-12,
                                   atol=1e-12 * np.max(np.abs(want)))


def test_cone_and_power_law_at_k_above_zero_below_the_surface():
    """k > 0, nu = 1/(2+k): the cone and f = A r^0.6 (n + k < 1: p(0) = +inf) are solved; the surface is -pressure
    bit for bit, the centre of the sharp power law on the surface is unbounded (flag 1), the rest finite (0)."""
    for profile, geometry in (("conical", {"tan_theta": 0.1}), ("power_law", {"n": 0.6, "A": 0.05})):
        params = {**{k: v for k, v in BASE.items() if k != "R"}, **geometry, "profile": profile, "k": 0.3,
                  "poisson": "holl_ratio", "rho": [0.0, 0.5, 1.2], "z": [0.0, 0.3]}
        ds = sf.generate({"scenario": "graded_normal", "parameters": params, "output": {
            "variables": ["pressure", "sigma_zz", "tau_max", "stress_validity"]}}).compute()
        surf = ds.sel(z=0.0)
        assert np.array_equal(surf.sigma_zz.values, -surf.pressure.transpose(*surf.sigma_zz.dims).values)
        tip = profile == "power_law"
        assert int(surf.stress_validity.sel(rho=0.0)) == int(tip) and np.isposinf(surf.tau_max.sel(rho=0.0)) == tip
        rest = ds.where(~((ds.rho == 0.0) & (ds.z == 0.0)))
        assert int(rest.stress_validity.max()) == 0 and np.isfinite(ds.sigma_zz.sel(z=0.3)).all()


def test_graded_tangential_peaks_are_the_axisymmetric_familys_times_the_pair_modulus():
    """k = 0, rigid counter-body (the uncoupled traction, as the axisymmetric family's): c_N* = E*, so the peaks
    are those of the axisymmetric `parabolic` scenario under the same force ratio (another scenario, another
    entry point)."""
    nu, mu, fx = 0.3, 0.3, 0.6
    g = run({"k": 0.0, "nu": nu, "mu": mu, "fx": fx, "body2": "rigid", "uncoupled_approximation": "flag"},
            ["tau_max_peak", "tau_max_peak_x", "tau_max_peak_depth", "peak_validity"], "graded_tangential")
    ax = sf.generate({"scenario": "parabolic", "parameters": {
        "nu": nu, "E": E0, "R": R, "delta": A_RAD ** 2 / R, "mu": mu, "fx": fx, "x": 0.0, "y": 0.0},
        "output": {"variables": ["tau_max_peak", "tau_max_peak_r", "tau_max_peak_depth"]}}).compute()
    assert float(g.tau_max_peak) == pytest.approx(float(ax.tau_max_peak), rel=1e-9)
    assert float(g.tau_max_peak_x) == pytest.approx(float(ax.tau_max_peak_r) / A_RAD, abs=1e-6)
    assert float(g.tau_max_peak_depth) == pytest.approx(float(ax.tau_max_peak_depth) / A_RAD, abs=1e-6)
    assert int(g.peak_validity) == 0


def _johnson_axis_tau(z, nu):
    """tau_max / p0 on the Hertz axis (Johnson 1985, sec. 3.4)."""
    sz = -1.0 / (1.0 + z * z)
    sr = -(1.0 + nu) * (1.0 - z * math.atan(1.0 / z)) + 0.5 / (1.0 + z * z)
    return 0.5 * (sr - sz)


def test_peak_of_the_homogeneous_case_is_johnsons():
    ds = run({"k": 0.0, "poisson": "holl_ratio"}, ["tau_max_peak", "tau_max_peak_rho", "tau_max_peak_depth"])
    best = minimize_scalar(lambda z: -_johnson_axis_tau(z, 0.5), bounds=(0.2, 1.0), method="bounded",
                           options={"xatol": 1e-10})
    p0 = 2 * A_RAD * E0 / (1 - 0.25) / (math.pi * R)
    assert float(ds.tau_max_peak) == pytest.approx(-best.fun * p0, rel=1e-9)
    assert float(ds.tau_max_peak_depth) == pytest.approx(best.x, abs=1e-6)
    assert float(ds.tau_max_peak_rho) == 0.0 and int(ds.peak_validity) == 0


def test_adhesive_edge_is_flagged_unbounded_and_the_interior_finite():
    ds = run({"k": 0.5, "poisson": "holl_ratio", "delta_gamma": 0.4, "rho": [0.5, 1.0], "z": [0.0, 0.01]},
             ["sigma_zz", "tau_max", "stress_validity"], "graded_adhesive")
    edge = ds.sel(rho=1.0, z=0.0)
    assert np.isposinf(edge.sigma_zz) and np.isposinf(edge.tau_max) and int(edge.stress_validity) == 1
    rest = ds.where(~((ds.rho == 1.0) & (ds.z == 0.0)))
    assert int(rest.stress_validity.max()) == 0 and np.isfinite(ds.sigma_zz.sel(z=0.01)).all()


@pytest.mark.parametrize("extra,expect", [
    ({"k": 0.5, "nu": 0.3, "z": 0.5}, "z is given, but nu = 0.3 with k = 0.5 is not solved below the surface"),
    ({"k": 0.5, "poisson": "holl_ratio", "z": 0.5, "profile": "tabulated", "profile_r": [0.0, 1e-3, 2e-3, 3e-3],
      "profile_f": [0.0, 2.5e-5, 1e-4, 2.25e-4]},
     "z is given, but profile = 'tabulated' is solved below the surface at k = 0 only: at k > 0 the area integral "
     "of the point-load field needs the pressure at every radial node"),
    ({"k": 0.5, "poisson": "holl_ratio", "profile": "tabulated", "profile_r": [0.0, 1e-3, 2e-3, 3e-3],
      "profile_f": [0.0, 2.5e-5, 1e-4, 2.25e-4], "variables": "tau_max_peak"},
     "tau_max_peak is asked for, but profile = 'tabulated' is solved below the surface at k = 0 only"),
    ({"k": 0.5, "nu": 0.3, "variables": "von_mises_peak"},
     "von_mises_peak is asked for, but nu = 0.3 with k = 0.5 is not solved below the surface"),
    ({"k": 0.0, "z": -0.5}, "z = -0.5 must be a number in [0, 1000000]"),
    ({"scenario": "graded_tangential", "k": 0.5, "poisson": "holl_ratio", "z": 0.2, "x": 0.5},
     "z or x is given with k = 0.5: below the surface under tangential load the graded family solves k = 0"),
    ({"scenario": "graded_tangential", "k": 0.5, "poisson": "holl_ratio", "variables": "tau_max_peak"},
     "tau_max_peak is asked for with k = 0.5: below the surface under tangential load the graded family solves "
     "k = 0"),
])
def test_unsupported_cases_and_negative_depth_exit_2_in_one_line(tmp_path, capsys, extra, expect):
    params = {**BASE, **extra}
    scenario = params.pop("scenario", "graded_normal")
    variable = params.pop("variables", "sigma_zz")
    if "profile" in extra:
        params.pop("R")
    lines = [f"scenario = \"{scenario}\"", "[parameters]"] + [
        f"{k} = {v!r}".replace("'", "\"") for k, v in params.items()] + ["[output]", f"variables = [\"{variable}\"]"]
    recipe = tmp_path / "r.toml"
    recipe.write_text("\n".join(lines) + "\n")
    assert cli.main(["run", str(recipe), "-o", str(tmp_path / "x.nc"), "-q"]) == 2
    err = capsys.readouterr().err
    assert expect in err and "Traceback" not in err and len(err.strip().splitlines()) == 2
    assert not (tmp_path / "x.nc").exists()


TABLE_R = np.linspace(0.0, 2e-3, 13)
#: r^1.5 samples: a table that no closed form reproduces
TABLE = {"profile": "tabulated", "profile_r": TABLE_R.tolist(), "profile_f": (R * (TABLE_R / R) ** 1.5).tolist()}


def test_tabulated_profile_at_k0_equals_the_axisymmetric_scenario_of_the_same_table():
    """k = 0: graded_normal with a table and z gives finite stresses flagged 0, equal to the axisymmetric
    scenario of the same samples at the graded depth d (its own contact radius by bisection on d, physical
    units: E = E0, so E* = c_N*) within the superposition's accuracy."""
    rho, z = [0.0, 0.3, 0.8, 1.4], [1e-3, 0.5, 2.0]
    g = sf.generate({"scenario": "graded_normal", "parameters": {
        "E0": E0, "contact_radius": A_RAD, "c0": 1e-3, **TABLE, "k": 0.0, "nu": 0.3, "rho": rho, "z": z},
        "output": {"variables": ["depth", "normal_force", *STRESS, "stress_validity"]}}).compute()
    assert np.all(g.stress_validity.values == 0)
    for n in STRESS:
        assert np.all(np.isfinite(g[n].values)), n
    ax = sf.generate({"scenario": "axisymmetric", "parameters": {
        **TABLE, "nu": 0.3, "E": E0, "delta": float(g.depth), "y": 0.0, "x": [v * A_RAD for v in rho],
        "z": [v * A_RAD for v in z]}, "output": {"variables": ["contact_radius", "sigma_xx", "sigma_yy", "sigma_zz",
                                                               "sigma_xz", "tau_max"]}}).compute()
    assert float(ax.contact_radius) == pytest.approx(A_RAD, rel=1e-9)
    pm = float(g.normal_force) / (math.pi * A_RAD ** 2)
    for mine, theirs in (("sigma_rr", "sigma_xx"), ("sigma_tt", "sigma_yy"), ("sigma_zz", "sigma_zz"),
                         ("sigma_rz", "sigma_xz"), ("tau_max", "tau_max")):
        np.testing.assert_allclose(g[mine].transpose("z", "rho").values, ax[theirs].transpose("z", "x").values,
                                   rtol=0, atol=1e-8 * pm, err_msg=mine)


@pytest.mark.parametrize("scenario,extra,names", [
    ("graded_adhesive", {"delta_gamma": 0.4, "rho": [0.3, 0.8, 1.4]}, STRESS),
    ("graded_tangential", {"fx": 0.4, "mu": 0.3, "x": [-0.8, 0.3, 1.4]}, ["sigma_xx", "sigma_zz", "sigma_xz"]),
])
def test_tabulated_profile_at_k0_below_the_surface_is_finite_and_valid(scenario, extra, names):
    ds = sf.generate({"scenario": scenario, "parameters": {
        "E0": E0, "contact_radius": A_RAD, "c0": 1e-3, **TABLE, "k": 0.0, "nu": 0.3, "z": [1e-3, 0.5, 2.0], **extra},
        "output": {"variables": [*names, "stress_validity"]}}).compute()
    assert np.all(ds.stress_validity.values == 0)
    for n in names:
        assert np.all(np.isfinite(ds[n].values)) and np.any(ds[n].values != 0.0), n
    assert "axisymmetric family's spline" in ds[names[0]].attrs["stressfields_method"]
