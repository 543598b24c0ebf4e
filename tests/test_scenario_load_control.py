"""Load control of the axisymmetric scenarios: normal_force instead of delta, fx or tangential_force
instead of ux0, and the derived loads recorded as variables; against closed forms derived by hand
(Hertz, Sneddon, Cattaneo–Mindlin), round trips and quadrature of the surface shear traction."""
import decimal
from pathlib import Path

import numpy as np
import pytest
from scipy.special import gamma

import stressfields as sf
from stressfields import recipe as recipe_module
from stressfields.scenarios import REGISTRY

ROOT = Path(__file__).resolve().parents[1]
E, NU = 105e9, 0.3
E_STAR = E / (1 - NU ** 2)
GSTAR = 2 * (1 - NU) / (2 - NU)          # G*/E*, docs/theory/axisymmetric.md (A1)
THETA = 0.2
TABLE_R = list(np.linspace(0.0, 4e-3, 41))
R_BALL = 0.01
# a paraboloid tabulated: the not-a-knot cubic spline reproduces a quadratic exactly, so its contact
# obeys Hertz, which the tabulated inversion (bisection) does not use
TABULATED = {"profile": "tabulated", "profile_r": TABLE_R, "profile_f": [r * r / (2 * R_BALL) for r in TABLE_R]}
GEOMETRIES = {
    "cone": ("conical", {"theta": THETA}),
    "paraboloid": ("parabolic", {"R": R_BALL}),
    "power_law_3": ("axisymmetric", {"n": 3.0, "A": 2e3}),
    "power_law_0.7": ("axisymmetric", {"n": 0.7, "A": 0.05}),
    "tabulated": ("axisymmetric", TABULATED),
    "flat_punch": ("axisymmetric", {"profile": "flat_punch", "radius": 1e-3}),
}


def gen(scenario, params, variables, **extra):
    return sf.generate({"scenario": scenario, "parameters": params, "output": {"variables": variables},
                        **extra}).compute()


def problems(scenario, params):
    with pytest.raises(sf.RecipeError) as info:
        sf.generate({"scenario": scenario, "parameters": params})
    return str(info.value)


def hertz_radius(force, radius=R_BALL):
    return (3 * force * radius / (4 * E_STAR)) ** (1 / 3)


def power_law_force(a, A, n):
    """Sneddon: F_N = 2 E* kappa_n A n a^(n+1)/(n+1), kappa_n = sqrt(pi) Gamma(n/2+1)/Gamma(n/2+1/2)."""
    kappa = np.sqrt(np.pi) * gamma(n / 2 + 1) / gamma(n / 2 + 0.5)
    return 2 * E_STAR * kappa * A * n * a ** (n + 1) / (n + 1)


# -- normal force ---------------------------------------------------------------------------------

def test_contact_radius_of_the_force_against_closed_forms():
    forces = [1e-3, 1.0, 100.0, 1e4]
    base = {"E": E, "nu": NU, "normal_force": forces, "x": 0.0}
    ds = gen("parabolic", {**base, "R": R_BALL}, ["contact_radius", "delta"])
    a = hertz_radius(np.array(forces))
    np.testing.assert_allclose(ds.contact_radius.values, a, rtol=1e-13)
    np.testing.assert_allclose(ds.delta.values, a * a / R_BALL, rtol=1e-13)
    ds = gen("conical", {**base, "theta": THETA}, ["contact_radius", "delta"])
    a = np.sqrt(2 * np.array(forces) / (np.pi * E_STAR * np.tan(THETA)))     # F_N = (pi/2) E* tan(theta) a^2
    np.testing.assert_allclose(ds.contact_radius.values, a, rtol=1e-13)
    np.testing.assert_allclose(ds.delta.values, np.pi / 2 * a * np.tan(THETA), rtol=1e-13)
    for n, A in ((3.0, 2e3), (0.7, 0.05)):
        ds = gen("axisymmetric", {**base, "n": n, "A": A}, ["contact_radius"])
        np.testing.assert_allclose(power_law_force(ds.contact_radius.values, A, n), forces, rtol=1e-13)
    # the tabulated paraboloid (bisection) meets Hertz to the spline's reproduction of x^2
    ds = gen("axisymmetric", {**base, **TABULATED, "normal_force": [1.0, 100.0]}, ["contact_radius"])
    np.testing.assert_allclose(ds.contact_radius.values, hertz_radius(np.array([1.0, 100.0])), rtol=1e-12)


def test_flat_punch_depth_of_the_force():
    radius, force = 1e-3, 50.0
    ds = gen("axisymmetric", {"profile": "flat_punch", "radius": radius, "E": E, "nu": NU, "normal_force": force,
                              "x": [0.0, 5e-4], "y": 0.0}, ["delta", "contact_radius", "sigma_zz"])
    delta = force / (2 * E_STAR * radius)                 # F_N = 2 E* a delta
    assert float(ds.delta) == pytest.approx(delta, rel=1e-15) and float(ds.contact_radius) == radius
    # Boussinesq: p = F_N/(2 pi a sqrt(a^2 - r^2))
    r = np.array([0.0, 5e-4])
    np.testing.assert_allclose(ds.sigma_zz.values, -force / (2 * np.pi * radius * np.sqrt(radius ** 2 - r ** 2)),
                               rtol=1e-13)


@pytest.mark.parametrize("name", sorted(GEOMETRIES))
def test_round_trip_delta_force_delta(name):
    scenario, geometry = GEOMETRIES[name]
    deltas = [2e-6] if name == "flat_punch" else [1e-7, 2e-6, 3e-5]     # a punch's delta is not swept
    base = {"E": E, "nu": NU, "x": 0.0, **geometry}
    forward = gen(scenario, {**base, "delta": deltas if len(deltas) > 1 else deltas[0]}, ["normal_force"])
    for delta, force in zip(deltas, np.atleast_1d(forward.normal_force.values)):
        back = gen(scenario, {**base, "normal_force": float(force)}, ["delta"])
        assert float(back.delta) == pytest.approx(delta, rel=1e-13), name


def test_fields_of_the_force_equal_those_of_its_depth():
    """Every field of a force-controlled case is that of the depth the force gives (here Hertz)."""
    names = ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz", "dpdz", "von_mises"]
    x = list(np.linspace(-3e-4, 3e-4, 13))
    force = 20.0
    delta = hertz_radius(force) ** 2 / R_BALL
    base = {"E": E, "nu": NU, "R": R_BALL, "mu": 0.3, "ux0": 0.1, "x": x, "y": 5e-5}
    by_force = gen("parabolic", {**base, "normal_force": force}, names)
    by_depth = gen("parabolic", {**base, "delta": delta}, names)
    for n in names:
        np.testing.assert_allclose(by_force[n].values, by_depth[n].values, rtol=1e-12, atol=0)


# -- tangential force -----------------------------------------------------------------------------

FXS = [0.0, 1e-6, 0.1, 0.5, 0.9, 1 - 1e-9, 1.0]


def _one_minus_power(fx: float, k: float) -> float:
    """1 - (1 - fx)^k in 40-digit decimal arithmetic (in double precision it cancels as fx -> 0)."""
    with decimal.localcontext() as ctx:
        ctx.prec = 40
        one = decimal.Decimal(1)
        base = one - decimal.Decimal(fx)
        return float(one - (decimal.Decimal(k) * base.ln()).exp()) if base > 0 else 1.0


@pytest.mark.parametrize("name", sorted(GEOMETRIES))
def test_fx_ux0_and_stick_radius_agree(name):
    """fx -> ux0 (Cattaneo–Mindlin in the MDR), and that ux0 fed back gives the same stick radius (the
    existing stick_radius) and the same fx."""
    scenario, geometry = GEOMETRIES[name]
    mu = 0.4
    base = {"E": E, "nu": NU, "mu": mu, "delta": 2e-6, "x": 0.0, **geometry}
    ds = gen(scenario, {**base, "fx": FXS}, ["ux0", "stick_radius", "contact_radius"])
    a = float(ds.contact_radius)
    c = ds.stick_radius.values
    n = {"cone": 1.0, "paraboloid": 2.0, "tabulated": 2.0, "power_law_3": 3.0, "power_law_0.7": 0.7}.get(name)
    fx = np.array(FXS)
    if n is None:          # the flat punch sticks whole until gross slip: Q = 2 a G* u_x0, mu F_N = 2 a mu E* delta
        np.testing.assert_array_equal(c, np.where(fx < 1, a, 0.0))
        np.testing.assert_allclose(ds.ux0.values, mu * fx / GSTAR, rtol=1e-15)
    else:                  # F_N ~ a^(n+1): (c/a)^(n+1) = 1 - fx;  u_x0/delta = (mu/G*) (1 - (c/a)^n)
        np.testing.assert_allclose(c / a, (1 - fx) ** (1 / (n + 1)), rtol=1e-12, atol=1e-12)
        expect = mu / GSTAR * np.array([_one_minus_power(f, n / (n + 1)) for f in FXS])
        np.testing.assert_allclose(ds.ux0.values, expect, rtol=1e-9 if name == "tabulated" else 1e-13)
    back = gen(scenario, {**base, "ux0": list(ds.ux0.values)}, ["stick_radius", "fx"])
    np.testing.assert_allclose(back.stick_radius.values, c, rtol=1e-12, atol=1e-12 * a)
    np.testing.assert_allclose(back.fx.values, fx, rtol=1e-12, atol=1e-15)
    assert back.stick_radius.values[-1] == 0.0     # fx = 1: gross slip, also after the round trip


def _traction_nodes(a, c, order=80):
    """Nodes r and weights w of int_0^a h(r) r dr: r = c sin t on [0, c], r = a sin t on [c, a]."""
    t, w = np.polynomial.legendre.leggauss(order)
    nodes, weights = [], []
    for radius, lo, hi in ((c, 0.0, np.pi / 2), (a, np.arcsin(min(c / a, 1.0)), np.pi / 2)):
        if radius == 0.0 or hi <= lo:
            continue
        tt = 0.5 * (hi - lo) * t + 0.5 * (hi + lo)
        nodes.append(radius * np.sin(tt))
        weights.append(0.5 * (hi - lo) * w * radius * np.sin(tt) * radius * np.cos(tt))
    return np.concatenate(nodes), np.concatenate(weights)


@pytest.mark.parametrize("scenario, geometry, force", [
    ("parabolic", {"R": R_BALL}, 6.0), ("conical", {"theta": THETA}, 0.3 * 0.4 * 20.0),
    ("parabolic", {"R": R_BALL}, 0.3 * 20.0), ("axisymmetric", {"n": 3.0, "A": 2e3}, 2.5)])
def test_tangential_force_is_the_resultant_of_the_shear_traction(scenario, geometry, force):
    mu, normal = 0.3, 20.0
    base = {"E": E, "nu": NU, "mu": mu, "normal_force": normal, **geometry}
    head = gen(scenario, {**base, "tangential_force": force, "x": 0.0},
               ["fx", "ux0", "stick_radius", "contact_radius"])
    a, c = float(head.contact_radius), float(head.stick_radius)
    assert float(head.fx) == pytest.approx(force / (mu * normal), rel=1e-14)
    r, w = _traction_nodes(a, c)
    ds = gen(scenario, {**base, "tangential_force": force, "x": list(np.unique(r)), "y": 0.0}, ["sigma_xz"])
    q = -ds.sigma_xz.sel(x=r).values
    assert 2 * np.pi * np.sum(q * w) == pytest.approx(force, rel=1e-10)


def test_gross_slip_at_fx_one():
    x = [-0.9, -0.5, 0.0, 0.3, 0.8]
    ds = gen("parabolic", {"nu": NU, "mu": 0.3, "fx": 1.0, "x": x, "y": 0.0},
             ["sigma_zz", "sigma_xz", "stick_radius", "region", "ux0"])
    assert float(ds.stick_radius) == 0.0
    assert set(ds.region.values.tolist()) == {2}
    np.testing.assert_allclose(ds.sigma_xz.values, 0.3 * ds.sigma_zz.values, rtol=1e-13)    # q = mu p
    assert float(ds.ux0) == pytest.approx(0.3 / GSTAR, rel=1e-15)       # onset: G* u_x0 = mu E* delta


def test_normalised_mode_with_fx():
    """Hertz–Mindlin, normalised: (c/a)^3 = 1 - fx, q(0) = mu p_max (1 - c/a), p_max = (3/2) p_m."""
    mu, fx = 0.3, 0.5
    ds = gen("parabolic", {"nu": NU, "mu": mu, "fx": fx, "x": 0.0, "y": 0.0},
             ["sigma_xz", "stick_radius", "ux0"])
    c = (1 - fx) ** (1 / 3)
    assert float(ds.stick_radius) == pytest.approx(c, rel=1e-14)
    assert float(ds.sigma_xz) == pytest.approx(-mu * 1.5 * (1 - c), rel=1e-13)
    assert float(ds.ux0) == pytest.approx(mu / GSTAR * (1 - c * c), rel=1e-13)
    assert "fx" in ds.coords and "ux0" not in ds.coords
    # a tabulated paraboloid in units of a (bisection for c) gives the same stick radius
    r = list(np.linspace(0.0, 1.5, 16))
    tab = gen("axisymmetric", {"profile": "tabulated", "profile_r": r, "profile_f": [v * v / 2 for v in r], "nu": NU,
                               "mu": mu, "fx": fx, "x": 0.0}, ["stick_radius", "ux0"])
    assert float(tab.stick_radius) == pytest.approx(c, rel=1e-12)
    assert float(tab.ux0) == pytest.approx(mu / GSTAR * (1 - c * c), rel=1e-12)


def test_fx_of_a_displacement_is_mindlin():
    """ux0 given: fx = 1 - (1 - rho)^(3/2), rho = G* u_x0/(mu E* delta) (Mindlin 1949); 1 in gross slip and,
    at mu = 0 with u_x0 > 0, the limit mu -> 0+."""
    ux0 = [0.0, 0.05, 0.25, 0.5]
    ds = gen("parabolic", {"nu": NU, "mu": [0.0, 0.3], "ux0": ux0, "x": 0.0}, ["fx"])
    rho = GSTAR * np.array(ux0) / 0.3
    expect = np.where(rho >= 1, 1.0, 1 - np.clip(1 - rho, 0, None) ** 1.5)
    np.testing.assert_allclose(ds.fx.sel(mu=0.3).values, expect, rtol=1e-14)
    np.testing.assert_array_equal(ds.fx.sel(mu=0.0).values, [0.0, 1.0, 1.0, 1.0])


def test_flat_punch_tangential_force():
    """A sticking punch carries Q = 2 a G* u_x0 (the integral of (A37) with mu E* delta -> G* u_x0)."""
    radius, normal, mu, force = 1e-3, 50.0, 0.5, 10.0
    ds = gen("axisymmetric", {"profile": "flat_punch", "radius": radius, "E": E, "nu": NU, "normal_force": normal,
                              "mu": mu, "tangential_force": force, "x": [0.0, 5e-4], "y": 0.0},
             ["sigma_xz", "ux0", "delta", "stick_radius"])
    delta = float(ds.delta)
    u = float(ds.ux0) * delta
    assert 2 * radius * GSTAR * E_STAR * u == pytest.approx(force, rel=1e-14)
    assert float(ds.stick_radius) == radius
    r = np.array([0.0, 5e-4])
    np.testing.assert_allclose(-ds.sigma_xz.values, force / (2 * np.pi * radius * np.sqrt(radius ** 2 - r ** 2)),
                               rtol=1e-13)


# -- refusals ----------------------------------------------------------------------------------------

PHYS = {"E": E, "nu": NU, "R": R_BALL, "x": 0.0}


def test_refusals_name_the_keys():
    msg = problems("parabolic", {**PHYS, "delta": 1e-6, "normal_force": 10.0})
    assert "'delta'" in msg and "normal_force" in msg
    msg = problems("parabolic", PHYS)
    assert "missing parameter 'delta'" in msg and "normal_force" in msg
    msg = problems("parabolic", {**PHYS, "normal_force": 10.0, "ux0": 0.1, "fx": 0.5})
    assert "'ux0'" in msg and "fx" in msg
    msg = problems("parabolic", {**PHYS, "normal_force": 10.0, "mu": 0.3, "fx": 0.5, "tangential_force": 1.0})
    assert "'tangential_force'" in msg and "fx" in msg
    msg = problems("parabolic", {**PHYS, "normal_force": 10.0, "fx": 0.5})       # mu defaults to 0
    assert "fx = 0.5 with mu = 0" in msg
    msg = problems("parabolic", {**PHYS, "normal_force": 10.0, "mu": [0.0, 0.3], "tangential_force": 1.0})
    assert "tangential_force = 1.0 with mu = 0" in msg
    msg = problems("parabolic", {"nu": NU, "normal_force": 10.0, "x": 0.0})
    assert "'normal_force' is only used in physical mode" in msg
    msg = problems("parabolic", {"nu": NU, "mu": 0.3, "tangential_force": 1.0, "x": 0.0})
    assert "'tangential_force' is only used in physical mode" in msg
    msg = problems("axisymmetric", {"profile": "flat_punch", "radius": 1e-3, "E": E, "normal_force": [1.0, 2.0],
                                    "x": 0.0})
    assert "normal_force cannot be swept for profile = 'flat_punch'" in msg


@pytest.mark.parametrize("load", [{"normal_force": 10.0}, {"delta": hertz_radius(10.0) ** 2 / R_BALL}])
def test_tangential_force_beyond_mu_normal_force_is_refused(load):
    mu = 0.3
    limit = mu * 10.0
    msg = problems("parabolic", {**PHYS, **load, "mu": [mu, 0.5], "tangential_force": limit * 1.001})
    assert f"tangential_force = {limit * 1.001!r} N exceeds mu F_N = 3.0" in msg and "mu = 0.3" in msg
    assert "give tangential_force <= 3.0" in msg            # the limit is named
    near = {**PHYS, **load, "mu": mu, "tangential_force": limit * (1 - 1e-12)}
    if "delta" in load:    # F_N(delta) is derived, and its rounding would decide c there: refused
        assert "give normal_force instead of delta, or the load as fx" in problems("parabolic", near)
    else:
        ds = gen("parabolic", near, ["fx", "stick_radius"])
        assert float(ds.fx) == pytest.approx(1.0, abs=1e-9)
    ds = gen("parabolic", {**PHYS, "normal_force": 10.0, "mu": mu, "tangential_force": limit}, ["stick_radius", "fx"])
    assert float(ds.stick_radius) == 0.0 and float(ds.fx) == 1.0


def test_tabulated_force_beyond_the_table_is_refused():
    top = 4 * E_STAR * TABLE_R[-1] ** 3 / (3 * R_BALL)
    msg = problems("axisymmetric", {**TABULATED, "E": E, "nu": NU, "normal_force": 1.01 * top, "x": 0.0})
    assert "normal_force" in msg and "extend profile_r" in msg


# -- derived variables: dims, naming, defaults ---------------------------------------------------------

def test_dims_keep_only_what_is_swept():
    ds = gen("parabolic", {"E": [1e11, 2e11], "nu": NU, "R": R_BALL, "normal_force": [1.0, 2.0, 3.0], "mu": 0.3,
                           "fx": [0.2, 0.4], "x": 0.0}, ["delta", "contact_radius", "ux0", "tangential_force"])
    assert ds.delta.dims == ("E", "normal_force") and ds.contact_radius.dims == ("E", "normal_force")
    # declared on the whole case: a tabulated profile's u_x0/delta depends on the load too
    assert ds.ux0.dims == ds.tangential_force.dims == ("fx", "E", "normal_force")
    np.testing.assert_allclose(ds.ux0.values, 0.3 / GSTAR * (1 - (1 - np.array([0.2, 0.4])[:, None, None])
                                                              ** (2 / 3)) + 0 * ds.delta.values, rtol=1e-14)
    expect = 0.3 * np.array([0.2, 0.4])[:, None, None] * np.array([1.0, 2.0, 3.0])
    np.testing.assert_allclose(ds.tangential_force.values, np.broadcast_to(expect, (2, 2, 3)), rtol=1e-14)


def test_a_variable_named_like_a_given_parameter_is_not_produced():
    scen = REGISTRY["parabolic"]
    given = {"E", "nu", "R", "normal_force", "fx", "mu", "x"}
    names = [v.name for v in scen.available(True, given)]
    assert "normal_force" not in names and "fx" not in names and "delta" in names
    defaults = scen.defaults(True, given)
    for name in ("delta", "contact_radius", "ux0", "tangential_force"):
        assert name in defaults
    assert scen.defaults(True, {"E", "delta", "ux0"}) == scen.default_variables     # hashes unchanged
    problems_ = []
    recipe_module._variables(scen, ["sigma_xx", "fx"], True, problems_, given)
    assert problems_ and "'fx' is a parameter of this recipe" in problems_[0]


# -- recipe and history ------------------------------------------------------------------------------------

def test_force_recipe_reproduces_the_depth_recipe():
    force = sf.generate(ROOT / "recipes" / "hertz_mindlin_force.toml").compute()
    a = hertz_radius(100.0)
    assert float(force.contact_radius) == pytest.approx(a, rel=1e-13)
    assert float(force.tangential_force) == pytest.approx(15.0, rel=1e-14)
    assert float(force.stick_radius) == pytest.approx(a * 0.5 ** (1 / 3), rel=1e-13)
    params = {"E": 105e9, "nu": 0.3, "R": 0.01, "mu": 0.3, "delta": float(force.delta), "ux0": float(force.ux0),
              "y": 0.0, "x": {"start": -3e-4, "stop": 3e-4, "num": 601}}
    names = ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz", "von_mises", "dpdz"]
    depth = gen("parabolic", params, names)
    for n in names:
        np.testing.assert_allclose(force[n].values, depth[n].values, rtol=1e-12, atol=0)


def test_history_under_normal_force():
    base = {"E": E, "nu": NU, "R": R_BALL, "mu": 0.3, "ux0_history": [0.1, -0.05, 0.2], "x": [-1e-4, 0.0, 1e-4],
            "y": 0.0}
    names = ["sigma_xz", "sigma_xx", "tangential_force", "stick_radius"]
    force = 20.0
    by_force = sf.generate({"scenario": "axisymmetric_history", "parameters": {**base, "normal_force": force},
                            "output": {"variables": names + ["delta"]}}).compute()
    by_depth = sf.generate({"scenario": "axisymmetric_history", "parameters": {**base, "delta": float(by_force.delta)},
                            "output": {"variables": names}}).compute()
    assert float(by_force.delta) == pytest.approx(hertz_radius(force) ** 2 / R_BALL, rel=1e-13)
    for n in names:
        np.testing.assert_allclose(by_force[n].values, by_depth[n].values, rtol=1e-12, atol=0)


# -- the physics functions directly --------------------------------------------------------------------

@pytest.mark.parametrize("n", [0.5, 1.0, 2.0, 3.7])
def test_slip_and_force_ratios_are_inverse_and_exact(n):
    from stressfields.physics import axisymmetric as ax
    from stressfields.physics.axisymmetric.profiles import force_ratio, radius_at_force, slip_ratio
    profile = ax.power_law(1.3, n)
    fx = np.array([1e-12, 1e-6, 0.3, 0.999999, 1.0])
    rho = slip_ratio(profile, 1.0, fx)
    expect = [_one_minus_power(f, n / (n + 1)) for f in fx]
    np.testing.assert_allclose(rho, expect, rtol=1e-14)
    np.testing.assert_allclose(force_ratio(profile, 1.0, rho), fx, rtol=1e-13)
    a = np.array([1e-9, 1e-3, 1.0, 1e4])
    np.testing.assert_allclose(radius_at_force(profile, profile.normal_force(a)), a, rtol=1e-14)
