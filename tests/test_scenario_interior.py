"""The axisymmetric scenarios below the surface (parameter z) end to end, against routes independent
of the code: Johnson's closed forms on the Hertz axis, finite differences in z of the trace, the
z = 0 surface recipe bit for bit, physical against normalised units, the refusals and CF."""
import math
from pathlib import Path

import numpy as np
import pytest

import stressfields as sf
from stressfields import cli

ROOT = Path(__file__).resolve().parents[1]
NU = 0.3
STRESSES = ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "sigma_yz"]
NAMES = STRESSES + ["von_mises", "sigma_1", "sigma_2", "sigma_3", "tau_max", "dpdz"]
KNOTS = [0.0, 0.25, 0.5, 0.75, 1.0, 1.25]
PROFILES = {
    "cone": ("conical", {}),
    "paraboloid": ("parabolic", {}),
    "power_law": ("axisymmetric", {"n": 1.5}),
    "tabulated": ("axisymmetric", {"profile": "tabulated", "profile_r": KNOTS,
                                   "profile_f": [r * r / 2 + 0.2 * r ** 4 for r in KNOTS]}),
    "flat_punch": ("axisymmetric", {"profile": "flat_punch"}),
}
X = {"start": -2.0, "stop": 2.0, "num": 21}


def _gen(scenario, params, names=NAMES, method=None):
    recipe = {"scenario": scenario, "parameters": params, "output": {"variables": names}}
    if method:
        recipe["method"] = method
    return sf.generate(recipe).compute()


@pytest.mark.parametrize("kind", sorted(PROFILES))
def test_depth_sweep_every_profile(kind):
    scenario, extra = PROFILES[kind]
    ds = _gen(scenario, {"nu": NU, **extra, "z": {"start": 0, "stop": 3, "num": 31}, "x": X, "y": 0.1},
              NAMES + ["region"])
    surface = _gen(scenario, {"nu": NU, **extra, "x": X, "y": 0.1}, NAMES + ["region"])
    assert ds.sigma_xx.dims == ("z", "x") and ds.region.dims == ("x",)
    for name in NAMES + ["validity", "region"]:           # z = 0 is the surface recipe, bit for bit
        np.testing.assert_array_equal(ds[name].sel(z=0.0).values if "z" in ds[name].dims else ds[name].values,
                                      surface[name].values)
    deep = ds.sel(z=slice(0.05, None))
    assert np.all(deep.validity.values == 0)
    for name in NAMES:
        assert np.all(np.isfinite(deep[name].values)), name
    # tau_max is half the spread of the principal stresses, and bounds every shear component
    tau = deep.tau_max.values
    np.testing.assert_allclose(tau, (deep.sigma_1.values - deep.sigma_3.values) / 2, rtol=0, atol=0)
    for s in ("sigma_xy", "sigma_xz", "sigma_yz"):
        assert np.all(np.abs(deep[s].values) <= tau * (1 + 1e-12) + 1e-15)


def test_hertz_axis_against_johnson():
    """Johnson (1985) eq. 3.63 on the axis, per p0 = (3/2) p_m: sigma_zz = -1/(1+z^2),
    sigma_rr = -(1+nu)(1 - z atan(1/z)) + 1/(2(1+z^2)); p_h = (2/3)(1+nu)(1 - z atan(1/z)).
    Evaluated in extended precision: 1 - z atan(1/z) loses 4 digits at z = 40."""
    z = np.array([0.01, 0.3, 0.48, 1.0, 2.5, 40.0])
    ds = _gen("parabolic", {"nu": NU, "z": list(z), "x": 0.0}, ["sigma_xx", "sigma_zz", "tau_max", "dpdz"])
    z = z.astype(np.longdouble)
    f = 1 - z * np.arctan(1 / z)
    zz, rr = -1 / (1 + z * z), -(1 + NU) * f + 0.5 / (1 + z * z)
    np.testing.assert_allclose(ds.sigma_zz.values, (1.5 * zz).astype(float), rtol=1e-12)
    np.testing.assert_allclose(ds.sigma_xx.values, (1.5 * rr).astype(float), rtol=1e-12)
    np.testing.assert_allclose(ds.tau_max.values, (1.5 * np.abs(rr - zz) / 2).astype(float), rtol=1e-12)
    dpdz = (2 / 3) * (1 + NU) * (-np.arctan(1 / z) + z / (1 + z * z))
    np.testing.assert_allclose(ds.dpdz.values, (1.5 * dpdz).astype(float), rtol=1e-12)


@pytest.mark.parametrize("kind", sorted(PROFILES))
def test_dpdz_is_the_z_derivative_of_the_trace(kind):
    """dpdz against a central difference of p_h = -trace/3 from the dataset's own stresses, whose
    error falls by 4 when the step halves (second order)."""
    scenario, extra = PROFILES[kind]
    z0 = np.array([0.2, 0.7, 1.5])
    x = [-1.3, -0.4, 0.0, 0.6, 1.1]
    ds = _gen(scenario, {"nu": NU, **extra, "z": list(z0), "x": x, "y": 0.2}, ["dpdz"],
              method={"rtol": 1e-12})
    err = []
    for h in (4e-3, 2e-3):
        ph = [-sum(_gen(scenario, {"nu": NU, **extra, "z": list(z0 + s * h), "x": x, "y": 0.2}, STRESSES[:3],
                        method={"rtol": 1e-12})[c].values for c in STRESSES[:3]) / 3 for s in (1, -1)]
        err.append(np.max(np.abs((ph[0] - ph[1]) / (2 * h) - ds.dpdz.values)))
    assert err[1] < 1e-4 and 3.5 < err[0] / err[1] < 4.5


def test_hertz_tau_max_peak_from_the_recipe():
    """0.31 p0 at z = 0.48 a on the axis (nu = 0.3), docs/theory/interior.md section 5; p0 = 1.5 p_m."""
    ds = sf.generate(ROOT / "recipes" / "hertz_subsurface.toml").compute()
    tau = ds.tau_max
    peak = tau.where(tau == tau.max(), drop=True)
    assert float(peak.x[0]) == 0.0 and abs(float(peak.z[0]) - 0.4808645) < 0.0125 + 1e-9
    assert float(tau.max()) / 1.5 == pytest.approx(0.3100205, abs=2e-5)   # the grid misses the top by 1e-6
    assert np.all(ds.validity.values == 0)


def test_physical_equals_normalised():
    """Steel-like paraboloid: a = sqrt(R delta); x, z in metres = a times the normalised ones."""
    E, R, delta = 210e9, 5e-3, 1e-6
    a, e_star = math.sqrt(R * delta), E / (1 - NU ** 2)
    pm = 4 * e_star * a / (3 * math.pi * R)
    xs, zs = np.array([-1.2, 0.0, 0.5]), np.array([0.0, 0.3, 1.0])
    phys = _gen("parabolic", {"E": E, "R": R, "delta": delta, "nu": NU, "x": list(xs * a), "z": list(zs * a)},
                ["sigma_xx", "tau_max", "dpdz"])
    norm = _gen("parabolic", {"nu": NU, "x": list(xs), "z": list(zs)}, ["sigma_xx", "tau_max", "dpdz"])
    for name in ("sigma_xx", "tau_max"):
        np.testing.assert_allclose(phys[name].values / pm, norm[name].values, rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(phys.dpdz.values * a / pm, norm.dpdz.values, rtol=1e-12, atol=1e-14)


@pytest.mark.parametrize("params, method, words", [
    ({"mu": 0.3, "ux0": 0.25, "z": [0.0, 0.5]}, None,
     "fields below the surface under tangential load are not available yet; use ux0 = 0 or mu = 0, or z = 0"),
    ({"z": 0.5}, 'method = "closed"', "has no closed form below the surface"),
    ({"z": 0.5}, "rtol = 1e-13", "below 1e-12"),
])
def test_refusals_exit_2_with_one_line(tmp_path, capsys, params, method, words):
    lines = ['scenario = "conical"', "[parameters]", "x = [0.0, 0.5]"]
    lines += [f"{k} = {v!r}" for k, v in params.items()]
    if method:
        lines += ["[method]", method]
    path = tmp_path / "r.toml"
    path.write_text("\n".join(lines) + "\n")
    assert cli.main(["run", str(path), "-o", str(tmp_path / "o.nc"), "-q"]) == 2
    err = capsys.readouterr().err
    problems = [line for line in err.splitlines() if line.startswith("  - ")]
    assert "Traceback" not in err and len(problems) == 1 and words in problems[0], err
    assert not (tmp_path / "o.nc").exists()


def test_z_recipes_are_cf_clean(tmp_path):
    from test_cf_and_docs import cf_failures

    recipes = [ROOT / "recipes" / f"{n}_subsurface.toml" for n in ("hertz", "cone")]
    assert cli.main(["run", *map(str, recipes), "--out-dir", str(tmp_path), "-q"]) == 0
    for recipe in recipes:
        assert cf_failures(tmp_path / f"{recipe.stem}.nc") == []


def test_tau_max_at_the_cone_apex():
    """Surface apex r = 0: the pressure grows like ln(1/r) with sigma_rr, sigma_tt, sigma_zz ->
    -p (rho_r, rho_t, 1), a deviatoric limit for nu < 1/2 (tau_max = +inf, flag 1) and a
    hydrostatic one at nu = 1/2 (tau_max -> 0, the value inside the contact, where the surface
    stress is -p (1, 1, 1) for an incompressible half-space)."""
    ds = _gen("conical", {"nu": [0.3, 0.5], "x": [0.0, 0.5]}, ["tau_max", "von_mises"])
    assert ds.tau_max.sel(nu=0.3, x=0.0) == np.inf and int(ds.validity.sel(nu=0.3, x=0.0)) == 1
    assert np.all(ds.tau_max.sel(nu=0.5).values == 0.0) and np.all(ds.validity.sel(nu=0.5).values == 0)
