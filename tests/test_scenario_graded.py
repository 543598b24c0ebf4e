"""End-to-end tests of the graded scenarios (Hess & Popov 2016): recipe -> dataset -> NetCDF.

Values are held against direct physics calls and against routes independent of the code: the
homogeneous limits (Hertz, JKR, Cattaneo-Mindlin), eq. (9) by scipy quadrature, eqs. (43), (52), and
the reference points (tests/data/graded_power_law.json); equations as in docs/theory/graded.md (G1) onwards.
"""
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from scipy import integrate, optimize

import stressfields as sf
from stressfields import cli
from stressfields.physics.flags import Validity
from stressfields.physics.graded import normal as gno, tangential as gtg
from stressfields.recipe import RecipeError

from conftest import load_reference
from test_cf_and_docs import cf_failures

ROOT = Path(__file__).resolve().parents[1]
E0, A_RAD, R = 2.0e9, 1e-3, 0.05


def run(params, variables=None, method="auto", scenario="graded_normal"):
    recipe = {"scenario": scenario, "parameters": params, "method": {"method": method}}
    if variables:
        recipe["output"] = {"variables": variables}
    return sf.generate(recipe).compute()


# -- graded_normal ------------------------------------------------------------------------------

def test_normal_matches_physics_and_hertz_limit():
    rs = np.array([0.0, 0.3, 0.7, 0.99, 1.0, 1.5, 3.0])
    ds = run({"E0": E0, "contact_radius": A_RAD, "R": R, "k": [0.0, 0.4], "nu": [0.25, 0.5], "rho": rs.tolist()})
    assert set(ds.pressure.dims) == {"k", "nu", "rho"} and set(ds.uz.dims) == {"k", "rho"}
    assert (ds.validity == 0).all()
    k = ds.k.values[:, None, None]
    nu = ds.nu.values[None, :, None]
    r = rs * A_RAD
    kw = dict(k=k, nu=nu, E0=E0, c0=1.0, n=2.0, A_n=0.5 / R)
    np.testing.assert_allclose(ds.pressure.transpose("k", "nu", "rho"), gno.pressure(r, A_RAD, **kw), rtol=1e-14)
    np.testing.assert_allclose(ds.uz.transpose("k", "rho"), gno.surface_displacement(r, A_RAD, k=k[:, :, 0], n=2.0,
                                                                                   A_n=0.5 / R), rtol=1e-14)
    # Hertz (k = 0): d = a^2/R, F = 4 E* a^3/(3R), p = 2E*/(pi R) sqrt(a^2 - r^2), u_z outside
    hz = ds.sel(k=0.0)
    e_star = E0 / (1 - ds.nu.values ** 2)
    assert hz.depth == pytest.approx(A_RAD ** 2 / R, rel=1e-14)
    np.testing.assert_allclose(hz.normal_force, 4 * e_star * A_RAD ** 3 / (3 * R), rtol=1e-13)
    inside = np.clip(A_RAD ** 2 - r ** 2, 0, None)
    np.testing.assert_allclose(hz.pressure, 2 * e_star[:, None] / (np.pi * R) * np.sqrt(inside), rtol=1e-12,
                               atol=1e-6)
    out = r > A_RAD
    u_out = ((2 * A_RAD ** 2 - r[out] ** 2) * np.arcsin(A_RAD / r[out]) + A_RAD * np.sqrt(r[out] ** 2 - A_RAD ** 2)) \
        / (np.pi * R)
    np.testing.assert_allclose(hz.uz.values[out], u_out, rtol=1e-12)
    np.testing.assert_allclose(hz.uz.values[~out], A_RAD ** 2 / R - r[~out] ** 2 / (2 * R), rtol=1e-12)


def test_normal_reference_points_closed_and_quadrature():
    ref = load_reference("graded_power_law")
    inputs = ref["meta"]["inputs"]
    shapes = {"parabolic": {"R": float(inputs["R"])}, "conical": {"profile": "conical",
              "tan_theta": float(inputs["tan_theta"])}, "power_n3": {"profile": "power_law", "n": 3.0, "A": 0.9}}
    cases = [c for c in ref["normal"] if c["profile"] in shapes and c["nu"] == "0.3" and c["k"] in (0.5, 0.95)]
    assert len(cases) == 6
    for case in cases:
        geo = shapes[case["profile"]]
        rr = [p["r_over_a"] for p in case["p"]]
        for method in ("auto", "quadrature"):
            ds = run({**geo, "E0": float(inputs["E0"]), "c0": float(inputs["c0"]),
                      "contact_radius": float(case["a"]), "k": case["k"], "nu": 0.3, "rho": rr}, method=method)
            assert float(ds.depth) == pytest.approx(case["d"]["value"], rel=1e-12)
            assert float(ds.normal_force) == pytest.approx(case["F_N"]["value"], rel=1e-12)
            np.testing.assert_allclose(ds.pressure, [p["value"] for p in case["p"]], rtol=1e-9)


def test_kappa_fig4_against_eq9_by_scipy():
    ds = sf.generate(ROOT / "recipes" / "graded_fig4_kappa.toml").compute()
    assert ds.kappa.dims == ("n", "k")
    for n in ds.n.values[::17]:
        for k in ds.k.values:
            # eq. (9): kappa = n int_0^1 t^(n-1) (1 - t^2)^(-(1-k)/2) dt
            ref = n * integrate.quad(lambda t: t ** (n - 1) * (1 - t * t) ** (-(1 - k) / 2), 0, 1, limit=200)[0]
            assert float(ds.kappa.sel(n=n, k=k)) == pytest.approx(ref, rel=1e-7)
    assert float(ds.kappa.sel(k=0.0).interp(n=2.0)) == pytest.approx(2.0, rel=1e-3)  # kappa(2, 0) = 2


def test_tabulated_paraboloid_reproduces_closed_form():
    # a cubic spline is exact for r^2/(2R): the quadrature route must give the closed-form values
    r_tab = np.linspace(0.0, 2 * A_RAD, 9)
    common = {"E0": E0, "contact_radius": A_RAD, "k": [0.0, 0.5], "rho": [0.0, 0.5, 1.2]}
    tab = run({**common, "profile": "tabulated", "profile_r": r_tab.tolist(),
               "profile_f": (r_tab ** 2 / (2 * R)).tolist()}, ["kappa", "depth", "normal_force", "pressure", "uz"])
    ref = run({**common, "R": R}, ["kappa", "depth", "normal_force", "pressure", "uz"])
    for name in ("kappa", "depth", "normal_force", "pressure", "uz"):
        np.testing.assert_allclose(tab[name], ref[name], rtol=1e-8, atol=1e-12 * float(abs(ref[name]).max()))
    # pull-off: found inside the table; a table ending before a_c is flagged, not extrapolated
    adh = {"E0": 1e8, "contact_radius": A_RAD, "k": 0.5, "delta_gamma": 0.05}
    names = ["critical_radius", "critical_depth", "critical_force"]
    table = {"profile": "tabulated", "profile_r": r_tab.tolist(), "profile_f": (r_tab ** 2 / (2 * R)).tolist()}
    tab = run({**adh, **table}, names, scenario="graded_adhesive")
    ref = run({**adh, "R": R}, names, scenario="graded_adhesive")
    for name in names:
        np.testing.assert_allclose(tab[name], ref[name], rtol=1e-7)
    short = np.linspace(0.0, 1.2 * A_RAD, 7)
    tab = run({**adh, "profile": "tabulated", "profile_r": short.tolist(), "profile_f": (short ** 2 / (2 * R)).tolist(),
               "delta_gamma": 5.0}, names, scenario="graded_adhesive")
    # fixed load beyond the table, fixed grips inside
    assert tab.critical_validity.values.tolist() == [Validity.no_critical_point, Validity.within_stated_accuracy]
    assert np.isnan(tab.critical_force.sel(control="fixed_load"))
    assert np.isfinite(tab.critical_force.sel(control="fixed_grips"))
    # partial slip of a tabulated paraboloid, eqs. (49), (51)
    names = ["stick_radius", "tangential_displacement", "force_ratio"]
    slip = {"E0": E0, "contact_radius": A_RAD, "k": 0.5, "fx": [0.3, 0.9], "delta_x": [1e-6, 1e-5]}
    tab = run({**slip, **table}, names, scenario="graded_tangential")
    ref = run({**slip, "R": R}, names, scenario="graded_tangential")
    np.testing.assert_allclose(tab.stick_radius, (1 - tab.fx) ** (1 / 3.5), rtol=1e-9)
    for name in names:
        np.testing.assert_allclose(tab[name], ref[name], rtol=1e-8)


def test_cone_centre_is_flagged_and_quadrature_agrees():
    params = {"profile": "conical", "tan_theta": 0.1, "E0": E0, "contact_radius": A_RAD, "k": [0.0, 0.5],
              "rho": [0.0, 0.5, 2.0]}
    closed, quad = (run(params, method=m) for m in ("auto", "quadrature"))
    for ds in (closed, quad):
        assert np.isposinf(ds.pressure.sel(k=0.0, rho=0.0)) and int(ds.validity.sel(k=0.0, rho=0.0)) == 1
        assert int(ds.validity.sum()) == 1 and not np.isnan(ds.pressure).any()
    for name in ("depth", "normal_force", "pressure", "uz"):
        np.testing.assert_allclose(quad[name], closed[name], rtol=1e-9)
    # Love/Sneddon cone (k = 0): p = (E* tan(theta)/2) arccosh(a/r), d = (pi/2) a tan(theta)
    e_star = E0 / (1 - 0.3 ** 2)
    assert float(closed.pressure.sel(k=0.0, rho=0.5)) == pytest.approx(0.05 * e_star * np.arccosh(2.0), rel=1e-12)
    assert float(closed.depth.sel(k=0.0)) == pytest.approx(np.pi / 2 * A_RAD * 0.1, rel=1e-14)


# -- graded_adhesive ----------------------------------------------------------------------------

def test_adhesive_jkr_limit_and_control_dimension():
    dgam = 0.05
    ds = run({"E0": E0, "contact_radius": A_RAD, "R": R, "delta_gamma": dgam, "k": [0.0, 0.5], "nu": 0.3,
              "rho": [0.0, 1.0]},
             scenario="graded_adhesive")
    assert ds.control.values.tolist() == ["fixed_load", "fixed_grips"]
    fc = ds.critical_force.sel(k=0.0).values / (np.pi * dgam * R)
    np.testing.assert_allclose(fc, [-1.5, -5 / 6], rtol=1e-13)          # JKR pull-off
    np.testing.assert_allclose(ds.critical_force.sel(k=0.5).values / (np.pi * dgam * R),
                               [-(3.5) / 2, -(0.5 * 6.5) / (2 * 3.5)], rtol=1e-13)   # eq. (34)
    # JKR from its own d(a), F(a) (k = 0): fixed load minimises F, fixed grips minimises d
    e_star = E0 / (1 - 0.3 ** 2)
    d = lambda a: a * a / R - np.sqrt(2 * np.pi * dgam * a / e_star)                   # noqa: E731
    F = lambda a: 4 * e_star * a ** 3 / (3 * R) - np.sqrt(8 * np.pi * dgam * e_star * a ** 3)  # noqa: E731
    for fn, mode in ((F, "fixed_load"), (d, "fixed_grips")):
        a_c = optimize.minimize_scalar(fn, bounds=(1e-9, 1e-3), method="bounded",
                                       options={"xatol": 1e-16}).x
        sel = ds.sel(k=0.0, control=mode)
        assert float(sel.critical_radius) == pytest.approx(a_c, rel=1e-6)
        assert float(sel.critical_depth) == pytest.approx(d(float(sel.critical_radius)), rel=1e-12)
    hz = ds.sel(k=0.0)
    assert float(hz.depth) == pytest.approx(d(A_RAD), rel=1e-13)
    assert float(hz.normal_force) == pytest.approx(F(A_RAD), rel=1e-13)
    assert np.isneginf(ds.pressure.sel(rho=1.0)).all() and (ds.validity.sel(rho=1.0) == 1).all()
    assert (ds.validity.sel(rho=0.0) == 0).all() and (ds.critical_validity == 0).all()


def test_adhesive_quadrature_and_missing_critical_point():
    params = {"profile": "power_law", "A": 30.0, "n": [1.5, 3.0], "E0": E0, "contact_radius": A_RAD,
              "delta_gamma": 0.05, "k": [0.0, 0.5], "rho": [0.0, 0.5]}
    closed = run(params, scenario="graded_adhesive")
    quad = run(params, method="quadrature", scenario="graded_adhesive")
    for name in ("depth", "normal_force", "pressure", "critical_radius", "critical_depth", "critical_force"):
        np.testing.assert_allclose(quad[name].transpose(*closed[name].dims), closed[name], rtol=1e-8, atol=1e-15)
    # n = 1.5 = (3+k)/2 at k = 0: d_c = 0 exactly at fixed load (Table 3)
    assert float(closed.critical_depth.sel(n=1.5, k=0.0, control="fixed_load")) == pytest.approx(0.0, abs=1e-18)
    # n = 0.2 <= (1-k)/2: no pull-off instability (Table 3) -> NaN, flagged
    low = run({**params, "n": [0.2, 1.5]}, scenario="graded_adhesive")
    assert low.critical_radius.sel(n=0.2).isnull().all()
    assert (low.critical_validity.sel(n=0.2) == Validity.no_critical_point).all()
    assert (low.critical_validity.sel(n=1.5) == 0).all() and not low.depth.isnull().any()


# -- graded_tangential --------------------------------------------------------------------------

def test_stick_radius_against_mdr_line_load_integral():
    # eq. (43) by scipy for a paraboloid: F_x/(mu F_N) at a stick radius c, independent of eq. (51)
    def fx_of(s, k):
        u = lambda x: 1 - x * x                                                       # u_1D / (a^2/((1+k)R))
        stick = u(s) * s ** (1 + k) / (1 + k)
        slip = integrate.quad(lambda x: x ** k * u(x), s, 1)[0]
        return (stick + slip) / integrate.quad(lambda x: x ** k * u(x), 0, 1)[0]
    ks, ss = [0.0, 0.3, 0.9], np.array([0.2, 0.5, 0.8])
    for k in ks:
        fxs = [fx_of(s, k) for s in ss]
        for method in ("auto", "quadrature"):
            ds = run({"E0": E0, "contact_radius": A_RAD, "R": R, "k": k, "fx": fxs}, ["stick_radius"], method,
                     "graded_tangential")
            np.testing.assert_allclose(ds.stick_radius, ss, rtol=1e-9)
    fig9 = sf.generate(ROOT / "recipes" / "graded_fig9_stick_radius.toml").compute()
    assert fig9.stick_radius.dims == ("k", "fx")
    np.testing.assert_allclose(fig9.stick_radius.sel(fx=1.0), 0.0)
    np.testing.assert_allclose(fig9.stick_radius, ((1 - fig9.fx) ** (1 / (3 + fig9.k))).transpose("k", "fx"),
                               rtol=1e-13)


def test_cattaneo_mindlin_limit_and_physics():
    nu, mu = 0.3, 0.4
    ds = run({"E0": E0, "contact_radius": A_RAD, "R": R, "k": [0.0, 0.6], "nu": nu, "mu": mu, "fx": [0.0, 0.5, 1.0],
              "rho": [0.0, 0.5, 0.95]}, scenario="graded_tangential")
    hz = ds.sel(k=0.0)
    e_pair, G = E0 / (2 * (1 - nu ** 2)), E0 / (2 * (1 + nu))
    fn = 4 * e_pair * A_RAD ** 3 / (3 * R)
    assert float(hz.normal_force) == pytest.approx(fn, rel=1e-13)
    assert float(hz.max_tangential_displacement) == pytest.approx(3 * mu * fn * (2 - nu) / (8 * G * A_RAD), rel=1e-12)
    # Mindlin traction tau = mu [p_H(a) - p_H(c)], c = a (1 - fx)^(1/3)
    r = ds.rho.values * A_RAD
    for fx in (0.0, 0.5, 1.0):
        c = A_RAD * (1 - fx) ** (1 / 3)
        ph = lambda rad: 2 * e_pair / (np.pi * R) * np.sqrt(np.clip(rad ** 2 - r ** 2, 0, None))  # noqa: E731
        np.testing.assert_allclose(hz.shear_traction.sel(fx=fx), mu * (ph(A_RAD) - ph(c)), rtol=1e-12, atol=1e-6)
    kw = dict(k=0.6, nu=nu, mu=mu, n=2.0, A_n=0.5 / R, E0=E0, E0_2=E0, nu_2=nu)
    np.testing.assert_allclose(ds.tangential_displacement.sel(k=0.6),
                               gtg.tangential_displacement(A_RAD, ds.fx.values, **kw), rtol=1e-14)
    assert (ds.coupling == 0).all() and (ds.validity == 0).all()


def test_fig10_holl_ratio_and_displacement_control():
    ds = sf.generate(ROOT / "recipes" / "graded_fig10_force_displacement.toml").compute()
    mu, a, R_ = float(ds.mu), float(ds.contact_radius), float(ds.R)
    dmax = (3 + ds.k) / 2 * mu * a ** 2 / R_                                   # eq. (52), nu = 1/(2+k)
    np.testing.assert_allclose(ds.max_tangential_displacement, dmax, rtol=1e-12)
    assert float(ds.max_tangential_displacement.sel(k=0.9) / ds.max_tangential_displacement.sel(k=0.0)) == \
        pytest.approx(1.3, rel=1e-12)                                          # "30 % larger" (sec. 5.1)
    D = np.minimum(ds.delta_x / dmax, 1.0)
    expected = (1 - (1 - D) ** ((3 + ds.k) / 2)).transpose(*ds.force_ratio.dims)
    np.testing.assert_allclose(ds.force_ratio, expected, rtol=1e-12, atol=1e-15)
    quad = run({"R": R_, "contact_radius": a, "mu": mu, "E0": 1e9, "poisson": "holl_ratio", "k": [0.0, 0.9],
                "delta_x": [0.0, 3e-7, 1.1e-6, 1.4e-6]}, ["force_ratio"], "quadrature", "graded_tangential")
    np.testing.assert_allclose(quad.force_ratio, ds.force_ratio.sel(k=[0.0, 0.9], delta_x=quad.delta_x,
                                                                     method="nearest"), rtol=1e-8, atol=1e-12)


def test_uncoupled_approximation_is_flagged(tmp_path):
    params = {"E0": E0, "contact_radius": A_RAD, "R": R, "body2": "rigid", "k": [0.0, 0.5], "nu": [0.3, 0.4], "fx": 0.5,
              "rho": [0.0, 0.5]}
    with pytest.raises(RecipeError, match=r"nu = 0\.3 with k = 0\.0 .*1/\(2\+k\)"):
        sf.generate({"scenario": "graded_tangential", "parameters": params})
    ds = sf.generate({"scenario": "graded_tangential", "parameters": {**params, "uncoupled_approximation": "flag"}})
    path = tmp_path / "flag.nc"
    sf.to_netcdf(ds, path)
    assert cf_failures(path) == []
    with xr.open_dataset(path) as back:
        # only k = 0.5, nu = 0.4 = 1/(2+k) decouples for a rigid counter-body
        assert back.coupling.values.tolist() == [[1, 1], [1, 0]]
        assert back.coupling.attrs["flag_meanings"] == "decoupled_exact uncoupled_approximation"
        kw = dict(k=0.5, nu=0.3, mu=0.3, n=2.0, A_n=0.5 / R, E0=E0, E0_2=np.inf, require_decoupled=False)
        assert float(back.max_tangential_displacement.sel(k=0.5, nu=0.3)) == pytest.approx(
            float(gtg.max_tangential_displacement(A_RAD, **kw)), rel=1e-14)


# -- recipes through the command line ----------------------------------------------------------

BAD = [
    ("graded_normal", "k = 1.0", "k = 1.0", "[0, 1)"),
    ("graded_normal", "nu = 0.6", "nu = 0.6", "(-1, 0.5]"),
    ("graded_normal", "", "'R'", "(0, 1000000]"),
    ("graded_normal", 'profile = "sphere"\nR = 0.05', "profile = 'sphere'", "'parabolic', 'conical'"),
    ("graded_tangential", 'body2 = "rigid"\nnu = 0.3\nk = 0.5\nR = 0.05', "nu = 0.3 with k = 0.5", "0.4"),
    ("graded_adhesive", "R = 0.05\ndelta_gamma = -1.0", "delta_gamma = -1.0", "[0, 1000000]"),
    ("graded_tangential", "R = 0.05\nfx = 1.5", "fx = 1.5", "[0, 1]"),
]


@pytest.mark.parametrize("scenario,extra,key,allowed", BAD)
def test_bad_recipes_exit_2_naming_key_value_range(tmp_path, capsys, scenario, extra, key, allowed):
    recipe = tmp_path / "bad.toml"
    recipe.write_text(f'scenario = "{scenario}"\n[parameters]\nE0 = 1e9\ncontact_radius = 1e-3\n{extra}\n')
    assert cli.main(["run", str(recipe), "-o", str(tmp_path / "x.nc"), "-q"]) == 2
    err = capsys.readouterr().err
    assert key in err and allowed in err, err
    assert not (tmp_path / "x.nc").exists()


def test_control_flag_coordinate_round_trips_through_netcdf(tmp_path, capsys):
    out = tmp_path / "pulloff.nc"
    assert cli.main(["run", str(ROOT / "recipes" / "graded_adhesive_pulloff.toml"), "-o", str(out), "-q"]) == 0
    with xr.open_dataset(out) as ds:
        assert ds.control.dtype == np.int8 and ds.control.values.tolist() == [0, 1]
        assert ds.control.attrs["flag_meanings"] == "fixed_load fixed_grips"
        assert ds.control_name.values.tolist() == ["fixed_load", "fixed_grips"]
        ratio = ds.critical_force / (np.pi * ds.delta_gamma * ds.R)
        np.testing.assert_allclose(ratio.sel(control=0), -(3 + ds.k) / 2, rtol=1e-12)
        np.testing.assert_allclose(ratio.sel(control=1), -(1 - ds.k) * (5 + 3 * ds.k) / (2 * (3 + ds.k)), rtol=1e-12)
    assert cli.main(["describe", "graded_adhesive"]) == 0
    assert "fixed_grips" in capsys.readouterr().out


@pytest.mark.parametrize("r, message", [
    ([0, 1e-300, 2e-300, 3e-300, 0.5, 1.0, 1.2], "below 1e-12 of its span"),    # the quadrature broke here
    (list(np.linspace(0.0, 1.2, 10001)), "at most 10,000 are allowed"),       # MAX_TABLE_SIZE
])
def test_tabulated_tables_refused_before_work(r, message):
    f = [x + x * x for x in r]
    with pytest.raises(RecipeError, match=message):
        sf.generate({"scenario": "graded_normal", "parameters": {
            "profile": "tabulated", "profile_r": r, "profile_f": f, "E0": 1e9, "k": 0.5, "contact_radius": 1.0,
            "rho": [0.0]}})


@pytest.mark.parametrize("scenario, extra, singular", [
    # Love's cone at k = 0: p = (E* tan(theta)/2) arccosh(a/r) -> +inf at r = 0
    ("graded_normal", {"profile": "conical", "tan_theta": 0.1, "k": [0.0, 0.5]}, {"k": 0.0, "rho": 0.0}),
    # the adhesive edge: p ~ -(a - r)^(-(1-k)/2) -> -inf at r = a (eq. 37)
    ("graded_adhesive", {"R": R, "delta_gamma": 0.05, "k": [0.0, 0.5]}, {"rho": 1.0}),
    # gross slip of the cone at k = 0: tau = mu p -> +inf at r = 0
    ("graded_tangential", {"profile": "conical", "tan_theta": 0.1, "k": [0.0, 0.5], "mu": 0.3, "fx": [0.5, 1.0]},
     {"k": 0.0, "fx": 1.0, "rho": 0.0}),
])
def test_validity_requested_alone_flags_its_fields(scenario, extra, singular):
    params = {"E0": E0, "contact_radius": A_RAD, "rho": [0.0, 0.5, 1.0], **extra}
    field = "shear_traction" if scenario == "graded_tangential" else "pressure"
    alone = run(params, ["validity"], scenario=scenario)
    beside = run(params, [field], scenario=scenario)
    assert field not in alone.data_vars          # (the coupling flag joins the tangential one)
    np.testing.assert_array_equal(alone.validity.transpose(*beside.validity.dims), beside.validity)
    assert int(alone.validity.sel(singular).max()) == 1 and np.isinf(beside[field].sel(singular)).all()
    assert int((alone.validity == 1).sum()) == int(np.isinf(beside[field]).sum())
