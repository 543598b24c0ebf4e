"""Scenario `wavy` below the surface: depth z, partial slip, peaks, [points], physical units and the
refusals, end to end against direct physics calls and the surface values."""
import math

import numpy as np
import pytest

import stressfields as sf
from stressfields.physics.flags import Validity
from stressfields.physics.wavy import contact

from test_scenario_wavy import _exit_2

F2 = {"amplitudes": [1.0, 0.02], "wavenumbers": [1, 11]}
STRESS = ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz", "tau_max", "von_mises", "dpdz")


def generate(params, **top):
    return sf.generate({"scenario": "wavy", "parameters": {**F2, "a": 0.6, **params}, **top}).compute()


def test_depth_is_a_dimension_with_the_surface_at_z_0():
    ds = generate({"domain": ["periodic", "nonperiodic"], "x": {"start": -1.5, "stop": 1.5, "num": 13},
                   "z": [0.0, 0.05, 1.0]})
    assert ds.sigma_zz.dims == ("domain", "z", "x") and ds.pressure.dims == ("domain", "x")
    assert float(ds.nu) == 0.3                      # normalised mode with z: the default, recorded
    for name in STRESS:
        assert name in ds
    np.testing.assert_array_equal(ds.sigma_zz.sel(z=0.0), 0.0 - ds.pressure)
    np.testing.assert_array_equal(ds.sigma_xz.sel(z=0.0), 0.0 * ds.pressure)
    assert (ds.validity.sel(z=[0.05, 1.0]) == 0).all()
    # the edges x = +-1 at z = 0: dpdz has a direction-dependent limit there
    edge = ds.sel(z=0.0, x=[-1.0, 1.0])
    assert np.isnan(edge.dpdz).all() and (edge.validity == Validity.undefined_direction_dependent_limit).all()
    assert "below the surface: complex potential" in ds.sigma_xx.attrs["stressfields_method"]
    assert "stresses below the surface" in ds.sigma_xx.attrs["stressfields_accuracy"]


def test_values_equal_direct_physics_calls():
    x, z = np.linspace(-2, 2, 9), np.array([0.0, 0.3, 2.0])
    ds = generate({"domain": "nonperiodic", "x": list(x), "z": list(z), "nu": 0.25}, method={"rtol": 1e-10})
    v, _ = contact.subsurface(("sigma_xx", "sigma_zz", "sigma_xz", "sigma_yy"), x, z[:, None], 0.6, *F2.values(),
                              periodic=False, nu=0.25, rtol=1e-10)
    for k in v:
        np.testing.assert_array_equal(ds[k].values, v[k])


def test_points_table_and_compare_shape():
    ds = sf.generate({"scenario": "wavy", "parameters": {**F2, "a": 0.4},
                      "points": {"x": [0.0, 0.5, 1.2], "z": [0.1, 0.2, 0.0]}}).compute()
    assert ds.sigma_zz.dims == ("point",)
    v, _ = contact.subsurface(("sigma_zz",), np.array([0.0, 0.5, 1.2]), np.array([0.1, 0.2, 0.0]), 0.4, *F2.values(),
                              periodic=True, rtol=1e-10)
    np.testing.assert_array_equal(ds.sigma_zz.values, v["sigma_zz"])


def test_physical_units_and_tangential_force_equals_fx():
    E, nu, lam = 2e11, 0.3, 1e-3
    amps = [1e-6, 2e-8]
    a_phys = 0.6 * lam / 2
    pstar = math.pi * E / (1 - nu ** 2) * amps[0] / lam
    P = float(contact.mean_pressure(0.6, amps, F2["wavenumbers"], periodic=True)) * pstar * lam
    common = {"amplitudes": amps, "wavenumbers": F2["wavenumbers"], "E": E, "nu": nu, "lambda_1": lam, "a": 0.6,
              "x": [0.0, 0.5 * a_phys], "z": [0.2 * a_phys], "mu": 0.4}
    phys = sf.generate({"scenario": "wavy", "parameters": {**common, "tangential_force": 0.5 * 0.4 * P}}).compute()
    norm = generate({"x": [0.0, 0.5], "z": [0.2], "mu": 0.4, "fx": 0.5, "nu": nu})
    np.testing.assert_allclose(phys.sigma_xz.values / pstar, norm.sigma_xz.values, rtol=1e-9, atol=1e-13)
    np.testing.assert_allclose(phys.dpdz.values / (pstar / a_phys), norm.dpdz.values, rtol=1e-9, atol=1e-12)
    assert phys.sigma_xx.attrs["units"] == "Pa" and phys.z.attrs["units"] == "m"
    np.testing.assert_allclose(phys.stick_half_width.values / a_phys, norm.stick_half_width.values, rtol=1e-9)


def test_partial_slip_variables_and_peaks():
    ds = generate({"domain": "periodic", "x": {"start": -1.2, "stop": 1.2, "num": 25}, "z": [0.0, 0.4],
                   "mu": 0.3, "fx": [0.0, 0.5]},
                  output={"variables": ["shear_traction", "stick_half_width", "sigma_xz", "tau_max_peak",
                                        "tau_max_peak_x", "tau_max_peak_depth"]})
    assert float(ds.stick_half_width.sel(fx=0.0)) == 1.0 and 0 < float(ds.stick_half_width.sel(fx=0.5)) < 1
    assert (ds.shear_traction.sel(fx=0.0) == 0).all()
    np.testing.assert_array_equal(ds.sigma_xz.sel(z=0.0, fx=0.5), -ds.shear_traction.sel(fx=0.5))
    assert (ds.tau_max_peak.sel(fx=0.5) > ds.tau_max_peak.sel(fx=0.0)).all()
    assert (ds.peak_validity == 0).all()


@pytest.mark.parametrize("change, words", [
    ({"z": -0.5}, ["z = -0.5", "[0, 1000000]"]),
    ({"z": 2e6}, ["z = 2000000", "[0, 1000000]"]),
    ({"z": 0.5, "mu": 0.3, "fx": 1.5}, ["fx = 1.5", "[0, 1]"]),
    ({"z": 0.5, "fx": 0.5}, ["fx is a tangential load", "mu"]),
    ({"E": 2e11, "lambda_1": 1e-3, "z": 0.0}, ["missing parameter 'nu'"]),
    ({"E": 2e11, "nu": 0.3, "lambda_1": 1e-3, "mu": 0.3, "tangential_force": 1e12},
     ["tangential_force = 1e+12 N/m exceeds mu P", "allowed: [0, mu P]"]),
])
def test_hostile_depth_and_tangential_load(tmp_path, capsys, change, words):
    _exit_2(tmp_path, capsys, {"scenario": "wavy", "parameters": {**F2, "a": 0.3, **change}}, words)


@pytest.mark.parametrize("change, words", [
    ({"z": 0.5}, ["approximate_eq18", "field below the surface (z) needs an exact method"]),
    ({"mu": 0.3, "fx": 0.5}, ["approximate_eq18", "a tangential load (fx) needs an exact method"]),
])
def test_approximate_methods_refuse_depth_and_tangential_load(tmp_path, capsys, change, words):
    _exit_2(tmp_path, capsys, {"scenario": "wavy", "method": {"method": "approximate_eq18"},
                               "parameters": {**F2, "a": 0.3, "domain": "nonperiodic", **change}}, words)


def test_displacements_below_the_single_indenter():
    """u_x, u_z by name: the direct physics call, u_z at z = 0 the surface uz to its accuracy, metres in
    physical mode (scaled by Delta_1)."""
    x, z = np.linspace(-2, 2, 9), np.array([0.0, 0.3, 2.0])
    ds = generate({"domain": "nonperiodic", "x": list(x), "z": list(z), "nu": 0.25},
                  method={"rtol": 1e-10}, output={"variables": ["u_x", "u_z", "uz"]})
    ux, uz, _ = contact.subsurface_displacement(x, z[:, None], 0.6, *F2.values(), periodic=False, nu=0.25, rtol=1e-10)
    np.testing.assert_array_equal(ds.u_x.values, ux)
    np.testing.assert_array_equal(ds.u_z.values, uz)
    np.testing.assert_allclose(ds.u_z.sel(z=0.0), ds.uz, rtol=0, atol=1e-13)
    assert (ds.validity == 0).all()
    amps = [1e-6, 2e-8]
    phys = sf.generate({"scenario": "wavy", "parameters": {
        "amplitudes": amps, "wavenumbers": F2["wavenumbers"], "E": 2e11, "nu": 0.25, "lambda_1": 1e-3, "a": 0.6,
        "domain": "nonperiodic", "x": [0.0, 0.3 * 0.6 * 1e-3 / 2], "z": [0.5 * 0.6 * 1e-3 / 2]},
        "output": {"variables": ["u_x", "u_z"]}}).compute()
    ref = generate({"domain": "nonperiodic", "x": [0.0, 0.3], "z": [0.5], "nu": 0.25},
                   output={"variables": ["u_x", "u_z"]})
    assert phys.u_x.attrs["units"] == "m"
    np.testing.assert_allclose(phys.u_z.values / amps[0], ref.u_z.values, rtol=1e-12)
    np.testing.assert_allclose(phys.u_x.values / amps[0], ref.u_x.values, rtol=1e-12, atol=1e-15)


def test_displacements_refused_with_an_approximate_method(tmp_path, capsys):
    top = {"parameters": {**F2, "a": 0.3, "z": 0.5, "domain": "nonperiodic"}, "method": {"method": "approximate_eq18"}}
    _exit_2(tmp_path, capsys, {"scenario": "wavy", **top, "output": {"variables": ["u_x", "u_z"]}},
            ["approximate_eq18", "u_x, u_z need an exact method"])


def test_displacements_below_the_periodic_surface():
    """Both domains side by side: the direct physics calls, u_z at z = 0 the surface uz to 1e-13 Delta_1
    (periodic datum: zero mean over a period), validity 0 where the bounds hold."""
    x, z = np.linspace(-2, 2, 9), np.array([0.0, 0.3, 2.0])
    ds = generate({"domain": ["periodic", "nonperiodic"], "x": list(x), "z": list(z), "nu": 0.25},
                  method={"rtol": 1e-12}, output={"variables": ["u_x", "u_z", "uz"]})
    assert ds.u_x.dims == ("domain", "z", "x")
    per = ds.sel(domain="periodic")
    ux, uz, _ = contact.subsurface_displacement(x, z[:, None], 0.6, *F2.values(), periodic=True, nu=0.25, rtol=1e-12)
    np.testing.assert_array_equal(per.u_x.values, ux)
    np.testing.assert_array_equal(per.u_z.values, uz)
    np.testing.assert_allclose(ds.u_z.sel(z=0.0), ds.uz, rtol=0, atol=1e-13)
    assert (ds.validity == 0).all()


def test_stick_zone_not_admissible_in_the_periodic_domain():
    """A ripple that makes the load fall with the contact width (amplitudes [1, 0.2], wavenumbers [1, 3]:
    P decreases for 2a/lambda_1 between about 0.39 and 0.48, periodic): at 2a/lambda_1 = 0.6 and fx = 0.5 the
    stick width c = 0.34 a lies below that fall, so the superposition (W43) is not the loading history's
    solution; every point of that case says so (stick_zone_not_admissible) and its stresses and
    displacements are NaN, never a finite value of the wrong superposition, while fx = 0.1 (c = 0.95 a,
    above the fall) stays valid and finite."""
    ds = sf.generate({"scenario": "wavy", "parameters": {
        "amplitudes": [1.0, 0.2], "wavenumbers": [1, 3], "a": 0.6, "domain": "periodic", "mu": 0.5,
        "fx": [0.1, 0.5], "x": [-0.5, 0.0, 0.7], "z": [0.0, 0.3]},
        "output": {"variables": ["sigma_xz", "u_x", "stick_half_width", "continuous_contact", "validity"]}}).compute()
    assert int(ds.continuous_contact) == 1             # the contact itself is continuous: only the slip fails
    c = ds.stick_half_width
    assert 0.3 < float(c.sel(fx=0.5)) < 0.39 / 0.6 and float(c.sel(fx=0.1)) > 0.48 / 0.6
    P = contact.mean_pressure(np.array([0.39, 0.43, 0.48]), [1.0, 0.2], [1, 3], periodic=True)
    assert P[1] < P[0] and P[2] < P[1]                 # the load falls inside [c, a]: not admissible
    assert (ds.validity.sel(fx=0.5) == Validity.stick_zone_not_admissible).all()
    assert (ds.validity.sel(fx=0.1) == Validity.within_stated_accuracy).all()
    assert np.isnan(ds.sigma_xz.sel(fx=0.5)).all() and np.isnan(ds.u_x.sel(fx=0.5)).all()
    assert np.isfinite(ds.sigma_xz.sel(fx=0.1)).all() and np.isfinite(ds.u_x.sel(fx=0.1)).all()
    codes = dict(zip(ds.validity.attrs["flag_values"].tolist(), ds.validity.attrs["flag_meanings"].split()))
    assert codes[int(Validity.stick_zone_not_admissible)] == "stick_zone_not_admissible"
