"""The peaks of tau_max and von Mises below the surface and where they sit
(physics.axisymmetric.peaks and the scenarios' peak variables), against routes independent of the
search: Johnson's closed forms on the Hertz axis with a bounded 1-D search, a zooming grid search
over the fields, the logarithmic cone tip, physical against normalised units."""
import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

import stressfields as sf
from stressfields.physics import axisymmetric as ax
from stressfields.physics.axisymmetric.peaks import NOT_CONVERGED, UNBOUNDED
from stressfields.scenarios import axisymmetric as sa

NU = 0.3
P0 = 2.0 / math.pi          # Hertz peak pressure per E* for a = R = 1: p0 = 2 E* a/(pi R) (Johnson 4.23)
PEAK_NAMES = ["tau_max_peak", "tau_max_peak_r", "tau_max_peak_depth",
              "von_mises_peak", "von_mises_peak_r", "von_mises_peak_depth", "peak_validity"]


def _johnson_axis(zeta, nu=NU):
    """Johnson (1985) eq. 3.45 on the Hertz axis, per p0: (sigma_r, sigma_z) at depth zeta = z/a."""
    sz = -1.0 / (1.0 + zeta * zeta)
    sr = -(1.0 + nu) * (1.0 - zeta * math.atan(1.0 / zeta)) + 0.5 / (1.0 + zeta * zeta)
    return sr, sz


def _johnson_tau_peak():
    res = minimize_scalar(lambda t: -0.5 * np.subtract(*_johnson_axis(t)), bounds=(0.1, 1.0), method="bounded",
                          options={"xatol": 1e-12})
    return -res.fun, res.x


def _grid_zoom(f, x_range, z_range, steps=10, n=41):
    """The maximum of f(x, z) by a grid zoomed five-fold around the best point at each step."""
    (x0, x1), (z0, z1) = x_range, z_range
    for _ in range(steps):
        xs, zs = np.linspace(x0, x1, n), np.linspace(z0, z1, n)
        grid = f(xs[None, :], zs[:, None])
        i, j = np.unravel_index(np.argmax(grid), grid.shape)
        hx, hz = (x1 - x0) / 10, (z1 - z0) / 10
        x0, x1 = max(xs[j] - hx, x_range[0]), min(xs[j] + hx, x_range[1])
        z0, z1 = max(zs[i] - hz, z_range[0]), min(zs[i] + hz, z_range[1])
    return float(grid[i, j]), float(xs[j]), float(zs[i])


def _field(name, profile, **case):
    return lambda x, z: ax.fields([name], profile, x, 0.0, z, a=1.0, nu=NU, **case)[0][name]


def test_hertz_tau_max_peak_against_johnson():
    value, depth = _johnson_tau_peak()
    assert value == pytest.approx(0.310020, abs=1e-6) and depth == pytest.approx(0.4809, abs=5e-5)
    out = ax.peaks(ax.paraboloid(1.0), a=1.0, nu=NU, mu=0.0, ux0=0.0)
    assert out["peak_validity"] == 0
    # the value of a smooth maximum is second order in the position: far below 1e-6
    assert out["tau_max_peak"] / P0 == pytest.approx(value, rel=1e-10)
    assert out["tau_max_peak_depth"] == pytest.approx(depth, abs=1e-6)
    assert abs(out["tau_max_peak_r"]) <= 1e-6
    # in units of p_m = (2/3) p0: 0.465031 p_m
    assert out["tau_max_peak"] / float(ax.mean_pressure(1.0, ax.paraboloid(1.0))) == pytest.approx(0.465031, abs=5e-7)


def test_hertz_von_mises_peak_against_grid_and_axis():
    out = ax.peaks(ax.paraboloid(1.0), a=1.0, nu=NU, mu=0.0, ux0=0.0)
    grid, x, z = _grid_zoom(_field("von_mises", ax.paraboloid(1.0), mu=0.0, ux0=0.0), (0.0, 2.0), (0.0, 3.0))
    assert grid <= out["von_mises_peak"] * (1 + 1e-12)
    assert grid == pytest.approx(out["von_mises_peak"], rel=1e-9)
    assert (out["von_mises_peak_r"], out["von_mises_peak_depth"]) == pytest.approx((x, z), abs=1e-4)
    # on the axis sigma_r = sigma_theta, so von Mises = |sigma_r - sigma_z| = 2 tau_max (Johnson's axis)
    value, depth = _johnson_tau_peak()
    assert abs(out["von_mises_peak_r"]) <= 1e-6
    assert out["von_mises_peak"] / P0 == pytest.approx(2 * value, rel=1e-10)
    assert out["von_mises_peak_depth"] == pytest.approx(depth, abs=1e-6)


def test_partial_slip_moves_tau_max_peak_off_axis():
    case = dict(mu=0.5, ux0=0.1)
    c = float(ax.fields(["stick_radius"], ax.paraboloid(1.0), a=1.0, nu=NU, **case)[0]["stick_radius"])
    assert 0.0 < c < 1.0                      # partial slip
    out = ax.peaks(ax.paraboloid(1.0), a=1.0, nu=NU, **case)
    assert out["peak_validity"] == 0
    assert out["tau_max_peak_r"] > 0.05       # off the axis, towards +x
    grid, x, z = _grid_zoom(_field("tau_max", ax.paraboloid(1.0), **case), (-2.0, 2.0), (0.0, 3.0))
    assert grid <= out["tau_max_peak"] * (1 + 1e-12)
    assert grid == pytest.approx(out["tau_max_peak"], rel=1e-9)
    assert (out["tau_max_peak_r"], out["tau_max_peak_depth"]) == pytest.approx((x, z), abs=1e-4)
    # and the tangential traction raises the peak above the normal-load one
    assert out["tau_max_peak"] > ax.peaks(ax.paraboloid(1.0), a=1.0, nu=NU, mu=0.0, ux0=0.0)["tau_max_peak"]


def test_cone_tip_is_unbounded():
    out = ax.peaks(ax.cone(1.0), a=1.0, nu=NU, mu=[0.0, 0.3], ux0=0.1)
    assert np.all(out["peak_validity"] == UNBOUNDED) and UNBOUNDED != NOT_CONVERGED
    for name in ("tau_max", "von_mises"):
        assert np.all(np.isposinf(out[f"{name}_peak"]))
        assert np.all(out[f"{name}_peak_r"] == 0.0) and np.all(out[f"{name}_peak_depth"] == 0.0)
    # independently: on the axis the cone's tau_max grows like log(a/z) without bound (Johnson 5.4)
    tau = _field("tau_max", ax.cone(1.0), mu=0.0, ux0=0.0)(0.0, np.array([1e-2, 1e-4, 1e-6]))
    steps = np.diff(tau)
    assert np.all(steps > 0) and steps[1] == pytest.approx(steps[0], rel=0.05)


def _gen(params, names):
    return sf.generate({"scenario": "parabolic", "parameters": params, "output": {"variables": names}}).compute()


def test_scenario_physical_equals_normalised():
    case = {"nu": NU, "mu": [0.0, 0.5], "ux0": 0.1, "x": 0.0}
    norm = _gen(case, PEAK_NAMES)
    phys = _gen({**case, "E": 2e11, "delta": 1e-5, "R": 0.01}, PEAK_NAMES + ["mean_pressure", "contact_radius"])
    assert norm.tau_max_peak.dims == ("mu",)
    a, pm = float(phys.contact_radius), float(phys.mean_pressure)
    for name in ("tau_max", "von_mises"):
        np.testing.assert_allclose(phys[f"{name}_peak"].values / pm, norm[f"{name}_peak"].values, rtol=1e-9)
        for pos in ("_r", "_depth"):
            np.testing.assert_allclose(phys[f"{name}_peak{pos}"].values / a, norm[f"{name}_peak{pos}"].values,
                                       rtol=0, atol=1e-6)
    assert norm.tau_max_peak.values[0] == pytest.approx(0.465031, abs=5e-7)
    assert np.all(norm.peak_validity.values == 0)
    assert norm.tau_max_peak.attrs["units"] == "1" and phys.tau_max_peak.attrs["units"] == "Pa"
    assert phys.tau_max_peak_depth.attrs["units"] == "m"


def test_scenario_cone_flag_and_not_default():
    ds = sf.generate({"scenario": "conical", "parameters": {"nu": NU, "x": 0.0},
                      "output": {"variables": ["tau_max_peak", "peak_validity"]}}).compute()
    assert np.isposinf(float(ds.tau_max_peak)) and int(ds.peak_validity) == UNBOUNDED
    meanings = ds.peak_validity.attrs["flag_meanings"].split()
    assert meanings[list(ds.peak_validity.attrs["flag_values"]).index(UNBOUNDED)] == "unbounded_at_singular_point"
    for scen in (sa.CONICAL, sa.PARABOLIC, sa.AXISYMMETRIC):   # computed only when requested
        assert not set(PEAK_NAMES) & set(scen.default_variables)


def test_the_peak_flag_comes_with_any_peak_and_only_then():
    """A peak value is never written without the flag that says whether the search converged, and
    an ordinary field request does not start the search."""
    import stressfields as sf

    base = {"scenario": "parabolic", "parameters": {"x": [0.1], "nu": [0.3]}}
    peaks = sf.generate({**base, "output": {"variables": ["tau_max_peak"]}})
    plain = sf.generate({**base, "output": {"variables": ["sigma_xx"]}})
    assert "peak_validity" in peaks and "peak_validity" not in plain
