"""`history_fields` below the surface (z > 0): the normal interior field plus the weighted sum of
Cattaneo–Mindlin interior fields of the history's c-terms (docs/theory/axisymmetric.md (A69),
docs/theory/interior.md (I23), (I33)), against

* the surface computation at z = 0 (bit for bit) and its traction as z -> 0+;
* the monotonic ``fields`` at depth for a one-step history;
* the Mindlin–Deresiewicz superposition written out here from monotonic interior fields, with the
  stick radii from the Cattaneo–Mindlin relation G* lambda delta = mu E* [g(a) - g(c)] solved by hand;
* for the paraboloid, the 1-D superposition route against the closed forms.
"""
import math

import numpy as np
import pytest

import stressfields as sf
from stressfields.physics import axisymmetric as ax
from stressfields.recipe import RecipeError

NU, MU = 0.3, 0.3
KAPPA = 2 * (1 - NU) / (2 - NU)                      # G*/E*
PROFILES = {"paraboloid": ax.paraboloid(1.0), "cone": ax.cone(0.2)}
NAMES = list(ax.STRESS) + ["von_mises", "sigma_1", "sigma_3", "tau_max", "dpdz", "validity"]
# points of the plane y = 0.1 a and on the axis: inside, at and beyond the stick and contact edges
X = np.array([-1.4, -1.0, -0.7, -0.3, 0.0, 0.45, 0.8, 1.0, 2.5])
Y = np.array([0.1, 0.0])[:, None]


def stick_radius(profile, lam):
    """c/a from lambda = (mu/kappa)(1 - g(c)/g(a)): g ~ r^2 (paraboloid), g ~ r (cone)."""
    t = max(1.0 - KAPPA * lam / MU, 0.0)
    return math.sqrt(t) if profile.kind == "paraboloid" else t


def call(profile, history, step, z, names=NAMES, **kw):
    a = 1.0 if profile.kind == "paraboloid" else profile.contact_radius(0.3)
    return ax.history_fields(names, profile, X * a, Y * a, z, a=a, nu=NU, mu=MU, amplitude=1.0,
                             history=history, step=step, **kw)[0], a


@pytest.mark.parametrize("kind", list(PROFILES))
def test_z0_slice_is_the_surface_computation_bit_for_bit(kind):
    profile = PROFILES[kind]
    history, steps = [0.2, -0.05, 0.1], np.arange(3)[:, None, None, None]
    surface, a = call(profile, history, steps, None)
    mixed, _ = call(profile, history, steps, np.array([0.0, 0.4])[:, None, None] * a)
    zero, _ = call(profile, history, steps, 0.0)
    for n in NAMES:
        np.testing.assert_array_equal(mixed[n][:, 0], surface[n][:, 0])
        np.testing.assert_array_equal(zero[n], surface[n])
        assert np.all(np.isfinite(mixed[n][:, 1])) and mixed[n].shape == (3, 2, 2, X.size)
    assert np.all(mixed["validity"][:, 1] == 0)


@pytest.mark.parametrize("kind", list(PROFILES))
def test_one_loading_step_is_the_monotonic_field_at_depth(kind):
    profile = PROFILES[kind]
    z = np.array([0.05, 0.5, 2.0])[:, None, None]
    for u in (0.15, 0.5):                          # partial slip, gross slip (u* = mu/kappa = 0.364)
        hist, a = call(profile, [u], 0, z * (1.0 if kind == "paraboloid" else profile.contact_radius(0.3)))
        mono, _ = ax.fields(NAMES, profile, X * a, Y * a, z * a, a=a, nu=NU, mu=MU, ux0=u)
        pm = ax.mean_pressure(a, profile)
        for n in NAMES:
            scale = pm / a if n == "dpdz" else pm
            assert np.all(np.abs(hist[n] - mono[n]) <= 1e-12 * np.maximum(np.abs(mono[n]), scale)), (kind, u, n)


def _by_hand(profile, a, z, turning):
    """Normal interior field + sum_k w_k (monotonic interior tangential field of stick radius c_k)
    for the c-terms (lambda_k, w_k) ``turning``, stress and dpdz."""
    pt = (X * a, Y * a, z * a, a)
    out = dict(ax.interior_stress(*pt, NU, profile))
    out["dpdz"] = ax.interior_dpdz(*pt, NU, profile)
    for lam, w in turning:
        c = stick_radius(profile, lam) * a
        t = ax.interior_stress_tangential(*pt, c, NU, MU, profile)
        for k in ax.COMPONENTS:
            out[k] = out[k] + w * t[k]
        out["dpdz"] = out["dpdz"] + w * ax.interior_dpdz_tangential(*pt, c, NU, MU, profile)
    return out


@pytest.mark.parametrize("kind", list(PROFILES))
def test_loading_unloading_is_the_mindlin_deresiewicz_superposition(kind):
    profile = PROFILES[kind]
    a = 1.0 if kind == "paraboloid" else profile.contact_radius(0.3)
    z = np.array([0.1, 0.7])[:, None, None]
    history = [0.2, -0.05, 0.1, -0.2]
    # after loading to e1 = 0.2: q = mu (p_a - p_c1); back to -0.05: minus 2 mu (p_a - p_cr) with
    # lambda_r = (0.2 + 0.05)/2; on to 0.1: plus 2 mu (p_a - p_c) with lambda = 0.15/2; at -0.2 =
    # -e1 the memory is wiped: the monotonic field of -0.2
    expect = {1: [(0.2, 1.0), (0.125, -2.0)], 2: [(0.2, 1.0), (0.125, -2.0), (0.075, 2.0)], 3: [(0.2, -1.0)]}
    pm = ax.mean_pressure(a, profile)
    for step, turning in expect.items():
        got, _ = call(profile, history, step, z * a)
        ref = _by_hand(profile, a, z, turning)
        for n in list(ax.STRESS) + ["dpdz"]:
            k = n.removeprefix("sigma_")
            scale = pm / a if n == "dpdz" else pm
            # the by-hand sum adds the same terms in another order: rounding of a few terms of size S
            err = np.abs(got[n] - ref[k])
            assert np.all(err <= 1e-12 * np.maximum(np.abs(ref[k]), scale)), (kind, step, n, err.max() / scale)
        assert np.all(got["validity"] == 0)


def test_traction_tends_to_the_surface_history():
    """sigma_xz and sigma_zz at z = 1e-7 a equal the surface history's within O(z) (paraboloid:
    the traction is Lipschitz away from the edges r = a, r = c_k)."""
    profile = PROFILES["paraboloid"]
    history, steps = [0.2, -0.05, 0.1], np.arange(3)[:, None, None]
    deep, _ = call(profile, history, steps, 1e-7, names=["sigma_xz", "sigma_zz"])
    top, _ = call(profile, history, steps, None, names=["sigma_xz", "sigma_zz"])
    r = np.hypot(X, Y)
    # away from r = a = 1 and from the stick edges c_1 = 0.67, c_r = 0.81, c = 0.89 of the steps
    ok = np.broadcast_to((r < 0.6) | (r > 1.001), top["sigma_xz"].shape)
    pm = ax.mean_pressure(1.0, profile)
    for n in ("sigma_xz", "sigma_zz"):
        assert np.max(np.abs(deep[n] - top[n])[ok]) < 1e-5 * pm, n


def test_quadrature_route_against_the_closed_forms():
    """Paraboloid: the 1-D superposition (every term Sigma_T(a) - Sigma_T(c_k)) against the closed
    forms, each field within rtol * max(|value|, S) (S = p_m; p_m/a for dpdz)."""
    profile, rtol = PROFILES["paraboloid"], 1e-8
    z = np.array([0.02, 0.6])[:, None, None]
    history, steps = [0.2, -0.05, 0.1], np.arange(3)[:, None, None, None]
    closed, _ = call(profile, history, steps, z, names=list(ax.STRESS) + ["dpdz"], method="closed")
    quad, _ = call(profile, history, steps, z, names=list(ax.STRESS) + ["dpdz"], method="quadrature", rtol=rtol)
    pm = ax.mean_pressure(1.0, profile)
    for n, v in closed.items():
        scale = pm / 1.0 if n == "dpdz" else pm      # a = 1
        assert np.all(np.abs(quad[n] - v) <= rtol * np.maximum(np.abs(v), scale)), n


def test_every_value_below_the_surface_is_finite_with_validity_0():
    """Cone tip, stick and contact edges, gross slip and reversals: all finite at z > 0."""
    x = np.concatenate([np.linspace(-1.5, 1.5, 13), [0.0]])
    for kind, profile in PROFILES.items():
        a = 1.0 if kind == "paraboloid" else profile.contact_radius(0.3)
        got = ax.history_fields(NAMES + ["region", "stick_radius", "tangential_force"], profile, x * a, 0.0,
                                np.array([1e-3, 0.3])[:, None, None] * a, a=a, nu=NU, mu=MU, amplitude=1.0,
                                history=[0.5, -0.1, 0.3, -0.6], step=np.arange(4)[:, None, None, None])[0]
        for n in NAMES:
            assert np.all(np.isfinite(got[n])), (kind, n)
        assert np.all(got["validity"] == 0)
        assert got["region"].shape == got["sigma_xx"].shape


def test_route_below_the_surface_is_the_interior_route():
    profile = PROFILES["cone"]
    _, route = ax.history_fields(["sigma_xz"], profile, 0.1, 0.0, 0.5, a=1.0, nu=NU, mu=MU, amplitude=1.0,
                                 history=[0.2, -0.1], step=1)
    assert route == ax.resolve_interior(profile, "auto", 1e-10, tangential=True)
    with pytest.raises(ValueError, match="z"):
        ax.history_fields(["sigma_xz"], profile, 0.1, 0.0, np.array([0.5, -0.1]), a=1.0, nu=NU, mu=MU,
                          amplitude=1.0, history=[0.2], step=0)


# -- the scenario: recipe -> dataset ---------------------------------------------------------------

def _gen(scenario, params, variables):
    return sf.generate({"scenario": scenario, "parameters": params, "output": {"variables": variables}})


FIELDS = ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "von_mises", "dpdz", "region"]


@pytest.mark.parametrize("kind, scenario", [("paraboloid", "parabolic"), ("cone", "conical")])
def test_scenario_one_step_equals_the_monotonic_scenario_at_depth(kind, scenario):
    point = {"nu": NU, "mu": MU, "x": [-1.2, -0.4, 0.3, 0.95], "y": 0.2, "z": [0.0, 0.25, 1.5]}
    hist = _gen("axisymmetric_history", {**point, "profile": kind, "ux0_history": [0.15]}, FIELDS)
    mono = _gen(scenario, {**point, "ux0": 0.15}, FIELDS)
    assert hist.sigma_xx.dims == ("step", "z", "x") and hist.region.dims == ("step", "x")
    assert "z > 0" in hist.sigma_xz.attrs["stressfields_method"]
    assert hist.sigma_xz.attrs["stressfields_method"] == mono.sigma_xz.attrs["stressfields_method"]
    for n in FIELDS:
        h, m = hist[n].values[0], mono[n].values
        if n == "region":
            np.testing.assert_array_equal(h, m)
            continue
        deep = np.isfinite(m)
        assert np.all(np.abs(h - m)[deep] <= 1e-12 * np.maximum(np.abs(m[deep]), 1.0)), n   # S = p_m = 1
        np.testing.assert_array_equal(np.isfinite(h), deep)
    assert np.all(hist.validity.values[:, 1:] == 0)


def test_scenario_z0_slice_equals_the_surface_dataset():
    params = {"nu": NU, "mu": MU, "x": [-1.0, -0.3, 0.0, 0.7], "y": 0.0, "profile": "cone",
              "ux0_history": [0.2, -0.05, 0.1]}
    surface = _gen("axisymmetric_history", params, FIELDS + ["validity"])
    deep = _gen("axisymmetric_history", {**params, "z": [0.0, 0.5]}, FIELDS + ["validity"])
    for n in FIELDS + ["validity"]:
        got = deep[n].values if n == "region" else deep[n].isel(z=0).values
        np.testing.assert_array_equal(got, surface[n].values)


def test_scenario_refuses_closed_below_the_surface_for_the_cone():
    with pytest.raises(RecipeError, match="closed form below the surface"):
        sf.generate({"scenario": "axisymmetric_history", "method": {"method": "closed"},
                     "parameters": {"profile": "cone", "mu": MU, "x": 0.1, "z": 0.5, "ux0_history": [0.1]}})
