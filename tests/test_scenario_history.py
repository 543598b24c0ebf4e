"""`axisymmetric_history` end to end: recipe -> lazy dataset -> values, against the monotonic
scenarios and closed forms derived by hand (Mindlin, Mindlin–Deresiewicz, Hertz)."""
import math
from pathlib import Path

import numpy as np
import pytest

import stressfields as sf
from stressfields import cli

ROOT = Path(__file__).resolve().parents[1]
FIELDS = ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "von_mises", "sigma_1", "sigma_2",
          "sigma_3", "dpdz", "region", "stick_radius"]


def gen(params, variables=None, **extra):
    recipe = {"scenario": "axisymmetric_history", "parameters": params, **extra}
    if variables:
        recipe["output"] = {"variables": variables}
    return sf.generate(recipe)


def kappa(nu):
    return 2 * (1 - nu) / (2 - nu)


def mono(u, ustar):
    """Mindlin: F/(mu P) = 1 - (1 - u/u*)^(3/2), saturating at 1."""
    return np.where(u >= ustar, 1.0, 1 - np.clip(1 - u / ustar, 0, None) ** 1.5)


def test_step_is_a_dimension_with_every_step_by_default():
    ds = gen({"nu": 0.3, "mu": 0.3, "ux0_history": [0.1, -0.1, 0.2], "amplitude": [0.5, 1.0],
              "x": [0.0, 0.5], "y": 0.0}, ["sigma_xz", "tangential_force", "ux0"])
    assert dict(ds.sizes)["step"] == 3 and ds.step.values.tolist() == [0, 1, 2]
    assert ds.sigma_xz.dims == ("amplitude", "step", "x")
    assert ds.tangential_force.dims == ("amplitude", "step")
    np.testing.assert_array_equal(ds.ux0.values, [[0.05, -0.05, 0.1], [0.1, -0.1, 0.2]])
    assert ds.attrs["stressfields_profile"] == "paraboloid"
    # one step only: a dimension of length 1
    one = gen({"nu": 0.3, "mu": 0.3, "ux0_history": [0.1, -0.1, 0.2], "step": 1, "x": [0.5]},
              ["tangential_force"]).compute()
    assert one.step.values.tolist() == [1]
    assert float(one.tangential_force[0]) == pytest.approx(float(ds.tangential_force.values[1, 1]), abs=1e-15)


def test_step_beyond_history_is_refused():
    with pytest.raises(sf.RecipeError, match="step = 3 is beyond the history"):
        gen({"ux0_history": [0.1, 0.2, 0.3], "step": [0, 3], "x": [0.0]})
    with pytest.raises(sf.RecipeError, match="ux0_history"):
        gen({"x": [0.0]})
    with pytest.raises(sf.RecipeError, match="only used when profile = 'cone'"):
        gen({"profile": "paraboloid", "theta": 0.1, "E": 1e9, "delta": 1e-6, "R": 1e-2,
             "ux0_history": [0.1], "x": [0.0]})


@pytest.mark.parametrize("profile, scenario, extra", [("paraboloid", "parabolic", {}), ("cone", "conical", {}),
                                                      ("power_law", "axisymmetric", {"n": 1.5})])
def test_monotonic_history_equals_cattaneo_mindlin_scenario(profile, scenario, extra):
    x = {"start": -1.3, "stop": 1.3, "num": 27}
    y = [0.0, 0.45]
    hist = gen({"profile": profile, **extra, "nu": 0.3, "mu": [0.2, 0.4], "ux0_history": [0.05, 0.15, 0.25],
                "x": x, "y": y}, FIELDS).compute()
    mono_ds = sf.generate({"scenario": scenario, "parameters": {**extra, "nu": 0.3, "mu": [0.2, 0.4], "ux0": 0.25,
                                                                 "x": x, "y": y},
                           "output": {"variables": FIELDS}}).compute()
    for name in FIELDS:
        got, want = hist[name].isel(step=2).values, mono_ds[name].values
        ok = np.isfinite(want)
        np.testing.assert_allclose(got[ok], want[ok], rtol=1e-12, atol=1e-12, err_msg=name)
        assert np.array_equal(np.isfinite(got), ok), name
    assert np.array_equal(hist.validity.isel(step=2).values, mono_ds.validity.values)


def test_hertz_fretting_recipe_mindlin_deresiewicz():
    recipe = ROOT / "recipes" / "history_hertz_fretting.toml"
    ds = sf.generate(recipe)[["tangential_force", "cycle_energy", "dissipated_energy", "stick_radius", "ux0",
                              "region"]].compute()
    nu, mu = 0.3, 0.3
    ustar = mu / kappa(nu)
    for i, amp in enumerate(ds.amplitude.values):
        u = ds.ux0.values[i]
        F = ds.tangential_force.values[i]
        A = amp
        F1 = mono(A, ustar)
        virgin, down, up = slice(0, 21), slice(20, 61), slice(60, 101)
        np.testing.assert_allclose(F[virgin], mono(u[virgin], ustar), atol=1e-10)
        np.testing.assert_allclose(F[down], F1 - 2 * mono((A - u[down]) / 2, ustar), atol=1e-10)
        np.testing.assert_allclose(F[up], -F1 + 2 * mono((u[up] + A) / 2, ustar), atol=1e-10)
        # Mindlin-Deresiewicz loop energy, in units of mu F_N delta (x = F*/(mu F_N)):
        # (24/5) u* [1 - (1-x)^(5/3) - (5x/6)(1 + (1-x)^(2/3))]
        x = F1
        md = 24 / 5 * ustar * (1 - (1 - x) ** (5 / 3) - 5 * x / 6 * (1 + (1 - x) ** (2 / 3)))
        assert ds.cycle_energy.values[i, -1] == pytest.approx(md, rel=1e-9)
        assert np.all(ds.cycle_energy.values[i, :-1] == 0.0)
        # stick radius on the unloading branch: c/a = sqrt(1 - (A - u)/(2 u*))
        np.testing.assert_allclose(ds.stick_radius.values[i, 21:60],
                                   np.sqrt(1 - (A - u[21:60]) / (2 * ustar)), rtol=1e-12)
    # at A = u* the loop touches gross slip at its turning points
    assert ds.stick_radius.values[2, 60] == pytest.approx(0.0, abs=1e-7)
    assert ds.tangential_force.values[2, 60] == pytest.approx(-1.0, abs=1e-12)
    assert set(np.unique(ds.region.values).tolist()) <= {0, 1, 2, 3}
    inside = np.abs(ds.x.values) <= 1
    assert np.all(ds.region.values[:, 0][:, inside] == 3)  # step 0: u_x0 = 0, no traction yet
    assert np.all(ds.region.values[:, :, ~inside] == 0)


def test_cone_loop_recipe_turning_points():
    ds = sf.generate(ROOT / "recipes" / "history_cone_loop.toml").compute()
    # steps 0, 2, 4 are one and the same state (the small loop and the full loop both close)
    for name in ("sigma_xx", "sigma_xy", "sigma_xz", "dpdz", "von_mises", "region", "validity"):
        v = ds[name].values
        assert np.array_equal(v[0], v[2], equal_nan=True) and np.array_equal(v[0], v[4], equal_nan=True), name
    # step 3 is the mirror image of step 0 in the tangential part: sigma_xz changes sign
    np.testing.assert_allclose(ds.sigma_xz.values[3], -ds.sigma_xz.values[0], rtol=1e-14)
    # step 1: Mindlin-Deresiewicz traction, docs/theory/axisymmetric.md (A74): q = mu[(p_a - p_c1) - 2(p_a - p_cr)]
    nu, mu = 0.3, 0.4
    c1, cr = 1 - kappa(nu) * 0.25 / mu, 1 - kappa(nu) * 0.15 / mu
    r = np.abs(ds.x.values)
    with np.errstate(divide="ignore"):
        def p(c):
            return np.where(r < c, np.arccosh(c / np.minimum(np.maximum(r, 1e-300), c)), 0.0)
        q = mu * ((p(1) - p(c1)) - 2 * (p(1) - p(cr)))
    ok = r > 0
    np.testing.assert_allclose(ds.sigma_xz.values[1][ok], -q[ok], rtol=1e-13, atol=1e-15)
    assert float(ds.stick_radius[1]) == pytest.approx(cr, rel=1e-13)
    # the cone tip is flagged as in the monotonic scenario: sigma_xy there depends on the direction
    assert ds.validity.sel(x=0.0).values.tolist() == [2] * 5
    assert np.all(ds.validity.values[:, ds.x.values != 0.0] != 2)
    region = ds.region.values[1]
    assert np.all(region[r > 1] == 0) and np.all(region[(r < cr - 1e-9)] == 1)
    assert np.all(region[(r > cr + 1e-9) & (r <= 1)] == 2)
    # force and energy: loop 1/4 -> -1/4 -> 1/4 closes at step 4, the small loop at step 2
    assert ds.cycle_energy.values[2] > 0 and ds.cycle_energy.values[4] > ds.cycle_energy.values[2]
    assert ds.cycle_energy.values[[0, 1, 3]].tolist() == [0, 0, 0]


def test_physical_units():
    E, nu, R, delta, mu = 210e9, 0.3, 0.01, 2e-6, 0.3
    hist = [0.1, -0.05]
    phys = gen({"E": E, "nu": nu, "R": R, "delta": delta, "mu": mu, "ux0_history": hist,
                "x": [-1e-4, 5e-5, 1.2e-4], "y": 0.0},
               ["sigma_xx", "sigma_xz", "dpdz", "stick_radius", "tangential_force", "dissipated_energy",
                "contact_radius", "normal_force"]).compute()
    a = math.sqrt(R * delta)
    estar = E / (1 - nu ** 2)
    fn = 4 * estar * a ** 3 / (3 * R)
    pm = fn / (math.pi * a * a)
    assert float(phys.contact_radius) == pytest.approx(a, rel=1e-14)
    assert float(phys.normal_force) == pytest.approx(fn, rel=1e-13)
    norm = gen({"nu": nu, "mu": mu, "ux0_history": hist, "x": list(np.array([-1e-4, 5e-5, 1.2e-4]) / a),
                "y": 0.0}, ["sigma_xx", "sigma_xz", "dpdz", "stick_radius", "tangential_force",
                            "dissipated_energy"]).compute()
    np.testing.assert_allclose(phys.sigma_xx.values, norm.sigma_xx.values * pm, rtol=1e-11)
    np.testing.assert_allclose(phys.sigma_xz.values, norm.sigma_xz.values * pm, rtol=1e-11, atol=1e-6)
    np.testing.assert_allclose(phys.dpdz.values, norm.dpdz.values * pm / a, rtol=1e-11)
    np.testing.assert_allclose(phys.stick_radius.values, norm.stick_radius.values * a, rtol=1e-13)
    np.testing.assert_allclose(phys.tangential_force.values, norm.tangential_force.values * mu * fn, rtol=1e-13)
    np.testing.assert_allclose(phys.dissipated_energy.values, norm.dissipated_energy.values * mu * fn * delta,
                               rtol=1e-12)
    # Mindlin, loading to 0.1 delta: F_x = mu F_N [1 - (1 - u/u*)^(3/2)]
    assert float(phys.tangential_force[0]) == pytest.approx(mu * fn * mono(0.1, mu / kappa(nu)), rel=1e-12)
    assert phys.sigma_xx.attrs["units"] == "Pa" and phys.tangential_force.attrs["units"] == "N"
    assert phys.dissipated_energy.attrs["units"] == "J"


def test_amplitude_scales_the_history_and_describe(capsys):
    base = {"profile": "cone", "nu": 0.25, "mu": 0.35, "x": [-0.7, 0.2, 0.9], "y": 0.3}
    names = ["sigma_xx", "sigma_xz", "dpdz", "tangential_force", "dissipated_energy", "cycle_energy"]
    swept = gen({**base, "ux0_history": [0.2, -0.1, 0.2], "amplitude": [0.5, 2.0]}, names).compute()
    for i, amp in enumerate((0.5, 2.0)):
        single = gen({**base, "ux0_history": [0.2 * amp, -0.1 * amp, 0.2 * amp]}, names).compute()
        for n in names:
            np.testing.assert_allclose(swept[n].values[i], single[n].values, rtol=1e-13, atol=1e-14, err_msg=n)
    assert cli.main(["describe", "axisymmetric_history"]) == 0
    assert "ux0_history" in capsys.readouterr().out
