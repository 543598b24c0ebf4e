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


TANGENTIAL = {"mu": 0.3, "ux0": [0.1, 2.0]}      # partial slip and gross slip


def _gen(scenario, params, names=NAMES, method=None):
    recipe = {"scenario": scenario, "parameters": params, "output": {"variables": names}}
    if method:
        recipe["method"] = method
    return sf.generate(recipe).compute()


def _half_spread(tau, s1, s3):
    """tau_max = (sigma_1 - sigma_3)/2 exactly: the invariants are formed together from the scaled tensor."""
    np.testing.assert_array_equal(tau, (s1 - s3) / 2)


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
    _half_spread(tau, deep.sigma_1.values, deep.sigma_3.values)
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


@pytest.mark.parametrize("load", [{}, {"mu": 0.3, "ux0": 0.1}, {"mu": 0.3, "ux0": 2.0}],
                         ids=["normal", "partial_slip", "gross_slip"])
@pytest.mark.parametrize("kind", sorted(PROFILES))
def test_dpdz_is_the_z_derivative_of_the_trace(kind, load):
    """dpdz against a central difference of p_h = -trace/3 from the dataset's own stresses, whose
    error falls by 4 when the step halves (second order); under tangential load this checks the
    trace of the Cerruti superposition, docs/theory/interior.md (I34)-(I35)."""
    scenario, extra = PROFILES[kind]
    extra = {**extra, **load}
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
    # the cone's normal part below the surface is closed (docs/theory/interior.md (I46)-(I52)); its
    # tangential part is the 1-D superposition, which has no closed route and reaches rtol 1e-12
    ({"z": 0.5, "mu": 0.3, "ux0": 0.1}, 'method = "closed"', "has no closed form below the surface"),
    ({"z": 0.5, "mu": 0.3, "ux0": 0.1}, "rtol = 1e-13", "below 1e-12"),
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


# -- tangential (Cattaneo-Mindlin) load below the surface ---------------------------------------------

EDGE_FREE_X = [-1.6, -0.4, 0.0, 0.3, 1.4]        # r = |(x, 0.1)| away from r = a and every stick radius


@pytest.mark.parametrize("kind", sorted(PROFILES))
def test_tangential_depth_every_profile(kind):
    """z = 0 is the surface recipe bit for bit; z = 1e-12 a is continuous with it away from the edge
    rings (the field is Lipschitz in z there: the change is z times a bounded derivative); below the
    surface every value is finite with validity 0, edge rings included (r = a, r = c at z > 0)."""
    scenario, extra = PROFILES[kind]
    p = {"nu": NU, **extra, **TANGENTIAL, "y": 0.1}
    names = NAMES + ["region", "stick_radius"]
    ds = _gen(scenario, {**p, "z": [0.0, 1e-12, 0.05, 0.5, 2.0], "x": X}, names)
    surface = _gen(scenario, {**p, "x": X}, names)
    assert ds.sigma_xx.dims == ("ux0", "z", "x")
    for name in names + ["validity"]:
        got = ds[name].sel(z=0.0).values if "z" in ds[name].dims else ds[name].values
        np.testing.assert_array_equal(got, surface[name].values, err_msg=name)
    top = ds.sel(z=0.0, x=EDGE_FREE_X, method="nearest")
    near = ds.sel(z=1e-12, x=EDGE_FREE_X, method="nearest")
    for name in NAMES:
        tol = 1e-8 if name == "dpdz" else 1e-9
        np.testing.assert_allclose(near[name].values, top[name].values, rtol=0, atol=tol, err_msg=name)
    # the edge rings r = a and r = c just below the surface, and the axis
    c = surface.stick_radius.values
    rings = _gen(scenario, {**p, "y": 0.0, "ux0": float(TANGENTIAL["ux0"][0]), "z": [1e-12, 1e-6],
                            "x": sorted({-1.0, -float(c[0]), 0.0, float(c[0]), 1.0})}, NAMES)
    deep = ds.sel(z=slice(1e-13, None))
    for part in (deep, rings):
        assert np.all(part.validity.values == 0)
        for name in NAMES:
            assert np.all(np.isfinite(part[name].values)), name
    tau = deep.tau_max.values
    _half_spread(tau, deep.sigma_1.values, deep.sigma_3.values)
    for s in ("sigma_xy", "sigma_xz", "sigma_yz"):
        assert np.all(np.abs(deep[s].values) <= tau * (1 + 1e-12) + 1e-15)


def _axis_hertz_mindlin(z, c):
    """On the axis, per p0 (a = 1), in extended precision: Johnson's normal part (eq. 3.63) and the
    Hamilton sliding shear sigma_xz(0, z) = -mu N H/2 with N = 1, M = z, H = 3F(z) - 1/(1 + z^2),
    F(z) = 1 - z atan(1/z), minus (c/a) times the same at z/c (Cattaneo-Mindlin, (I23))."""
    def f(t):
        return 1 - t * np.arctan(1 / t)

    def shear(t):
        return -(3 * f(t) - 1 / (1 + t * t)) / 2

    zz, rr = -1 / (1 + z * z), -(1 + NU) * f(z) + 0.5 / (1 + z * z)
    xz = 0.3 * (shear(z) - (c * shear(z / c) if c > 0 else 0))
    return rr, zz, xz


@pytest.mark.parametrize("ux0", [0.1, 2.0])
def test_hertz_mindlin_axis_against_johnson_and_hamilton(ux0):
    """sigma_xz, sigma_zz, sigma_xx and tau_max on the axis under Hertz-Mindlin partial and gross
    slip against the printed axis formulas; c/a = sqrt(1 - k u_x0/mu), k = 2(1-nu)/(2-nu) (MDR,
    G* (u_x0) = mu E* (delta - g(c)) with g = r^2/R).  On the axis the tensor is
    [[rr, 0, xz], [0, rr, 0], [xz, 0, zz]], so tau_max = sqrt(((rr - zz)/2)^2 + xz^2).  z <= 3 a: the
    extended-precision reference loses about z^4 ulps to 3F - 1/(1 + z^2) (1.5e-12 at z = 40 a, where
    the code agrees with 50-digit decimals to 5e-16)."""
    z = np.array([0.05, 0.3, 0.4808645, 1.0, 3.0])
    ds = _gen("parabolic", {"nu": NU, "mu": 0.3, "ux0": ux0, "z": list(z), "x": 0.0},
              ["sigma_xx", "sigma_zz", "sigma_xz", "tau_max", "stick_radius"])
    k = 2 * (1 - NU) / (2 - NU)
    c = math.sqrt(max(1 - k * ux0 / 0.3, 0.0))
    assert float(ds.stick_radius) == pytest.approx(c, rel=1e-12)
    rr, zz, xz = _axis_hertz_mindlin(z.astype(np.longdouble), c)
    tau = np.sqrt(((rr - zz) / 2) ** 2 + xz * xz)
    for name, v in (("sigma_xx", rr), ("sigma_zz", zz), ("sigma_xz", xz), ("tau_max", tau)):
        np.testing.assert_allclose(ds[name].values.ravel(), (1.5 * v).astype(float), rtol=1e-12, err_msg=name)


def test_hertz_mindlin_partial_slip_tau_max_peak():
    """The largest tau_max on the axis under Hertz-Mindlin partial slip (mu = 0.3, c/a = 0.8518)
    from the recipe equals the maximum of the printed axis formulas (bounded scalar search)."""
    from scipy.optimize import minimize_scalar

    ux0, k = 0.1, 2 * (1 - NU) / (2 - NU)
    c = math.sqrt(1 - k * ux0 / 0.3)

    def neg(t):
        rr, zz, xz = _axis_hertz_mindlin(np.longdouble(t), c)
        return -float(np.sqrt(((rr - zz) / 2) ** 2 + xz * xz))

    best = minimize_scalar(neg, bounds=(0.1, 1.0), method="bounded", options={"xatol": 1e-10})
    ds = _gen("parabolic", {"nu": NU, "mu": 0.3, "ux0": ux0, "z": [float(best.x)], "x": 0.0}, ["tau_max"])
    assert float(ds.tau_max.squeeze()) == pytest.approx(-1.5 * best.fun, rel=1e-12)
    assert abs(best.x - 0.4769) < 1e-3 and -1.5 * best.fun == pytest.approx(0.46687, abs=1e-5)


@pytest.mark.parametrize("kind", ["paraboloid", "flat_punch"])
def test_tangential_depth_closed_equals_superposition(kind):
    """The 1-D route (sliding punches, (I33)) against the closed forms (paraboloid (I23); the flat
    punch, one sliding punch (I33)): |difference| <= rtol max(|value|, p_m), mu = 0.3 < 1."""
    scenario, extra = PROFILES[kind]
    p = {"nu": NU, **extra, **TANGENTIAL, "z": [1e-8, 0.1, 0.7, 3.0], "x": X, "y": 0.3}
    closed = _gen(scenario, p, NAMES)
    quad = _gen(scenario, p, NAMES, method={"method": "quadrature", "rtol": 1e-10})
    for name in NAMES:
        u, v = closed[name].sel(z=slice(1e-9, None)).values, quad[name].sel(z=slice(1e-9, None)).values
        assert np.all(np.abs(u - v) <= 1e-10 * np.maximum(np.abs(u), 1.0) + 1e-12 * np.abs(u)), name


def test_tangential_depth_physical_equals_normalised():
    """Hertz-Mindlin partial slip at depth: metres and pascals = a and p_m times the normalised."""
    E, R, delta = 210e9, 5e-3, 1e-6
    a, e_star = math.sqrt(R * delta), E / (1 - NU ** 2)
    pm = 4 * e_star * a / (3 * math.pi * R)
    xs, zs = np.array([-1.2, 0.0, 0.5]), np.array([0.0, 0.3, 1.0])
    load = {"nu": NU, "mu": 0.3, "ux0": 0.1}
    names = ["sigma_xx", "sigma_xz", "tau_max", "dpdz"]
    phys = _gen("parabolic", {"E": E, "R": R, "delta": delta, **load, "x": list(xs * a), "z": list(zs * a)}, names)
    norm = _gen("parabolic", {**load, "x": list(xs), "z": list(zs)}, names)
    for name in names[:3]:
        np.testing.assert_allclose(phys[name].values / pm, norm[name].values, rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(phys.dpdz.values * a / pm, norm.dpdz.values, rtol=1e-12, atol=1e-13)


def test_tangential_tip_rtol_reaches_1e_12(tmp_path, capsys):
    """A power law with n < 1 under tangential load below the surface reaches rtol 1e-12 (the
    partial-slip part integrated over [c, a] directly, docs/theory/interior.md (I45)): accepted;
    rtol 1e-13 is refused in one line."""
    body = ['scenario = "axisymmetric"', "[parameters]", "n = 0.5", "x = [0.0, 0.5]", "z = 0.5", "mu = 0.3",
            "ux0 = 0.1", "[method]"]
    path = tmp_path / "r.toml"
    path.write_text("\n".join(body + ["rtol = 1e-12"]) + "\n")
    assert cli.main(["run", str(path), "-o", str(tmp_path / "o.nc"), "-q"]) == 0
    path.write_text("\n".join(body + ["rtol = 1e-13"]) + "\n")
    assert cli.main(["run", str(path), "-o", str(tmp_path / "p.nc"), "-q"]) == 2
    err = capsys.readouterr().err
    problems = [line for line in err.splitlines() if line.startswith("  - ")]
    assert len(problems) == 1 and "below 1e-12" in problems[0], err


def test_tangential_depth_is_cf_clean(tmp_path):
    from test_cf_and_docs import cf_failures

    path = tmp_path / "hm_depth.toml"
    path.write_text("\n".join(['scenario = "parabolic"', "[parameters]", "mu = 0.3", "ux0 = [0.1, 2.0]",
                               "x = {start = -1.5, stop = 1.5, num = 7}", "z = [0.0, 0.25, 1.0]",
                               "[output]", 'variables = ["sigma_xz", "tau_max", "dpdz", "region", "validity"]']) + "\n")
    assert cli.main(["run", str(path), "--out-dir", str(tmp_path), "-q"]) == 0
    assert cf_failures(tmp_path / "hm_depth.nc") == []
    ds = sf.generate(path)
    assert "sliding" not in ds.sigma_xz.attrs["stressfields_method"]          # closed for both parts
    assert "tangential" in ds.sigma_xz.attrs["stressfields_method"]


def test_points_the_routes_do_not_resolve_are_flagged_not_silent():
    """Below the surface every exact value is finite; where the 1-D route returns NaN (a point
    within ~1e-100 a of the axis or the surface) the flag says the point is not resolved (3),
    never 'direction-dependent limit' (2), and resolved points keep 0."""
    ds = sf.generate({"scenario": "axisymmetric", "parameters": {
        "profile": "power_law", "n": 0.5, "x": [1e-200, 0.3], "y": 0.0, "z": [1e-150, 1e-3]},
        "output": {"variables": ["sigma_xx", "dpdz", "validity"]}}).compute()
    finite = np.isfinite(ds.sigma_xx) & np.isfinite(ds.dpdz)
    assert not bool(finite.all())                       # the probe reaches the unresolved corner
    assert bool(((ds.validity == 3) == ~finite).all())
    assert int(ds.validity.sel(z=1e-3, x=0.3)) == 0
