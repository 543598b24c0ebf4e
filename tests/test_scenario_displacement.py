"""The displacements u_x, u_y, u_z of the axisymmetric scenarios end to end (the kernels are held
against Hooke's law, point-load quadrature and the far field in tests/physics/test_displacement.py).

At nu = 0.5 the normal pressure moves no surface point sideways and the tangential traction moves
none up or down (both coupling terms carry 1 - 2 nu), so the surface boundary conditions of the
contact hold exactly: u_z = delta - f(r) in the contact, u_x = u_x0 (u_y = 0) in the stick zone,
for the monotonic load and after every step of a history (Mindlin–Deresiewicz: the stick zone
moves rigidly with the indenter)."""
import numpy as np
import pytest

import stressfields as sf

PROFILES = {
    "parabolic": ({}, lambda r: r ** 2 / 2.0, 1.0),                    # R = a = 1: delta = 1
    "conical": ({}, lambda r: r, np.pi / 2.0),                         # tan theta = 1: delta = (pi/2) a
    "power_law_n3": ({"profile": "power_law", "n": 3.0}, lambda r: r ** 3, None),
}
DISP = ["u_x", "u_y", "u_z"]


def _scenario(name):
    return "axisymmetric" if name.startswith("power_law") else name


def _delta_n(n):
    """delta = g(a) = kappa_n a^n for f = r^n, a = 1 (docs/theory/axisymmetric.md (A4))."""
    from math import gamma, pi, sqrt
    return sqrt(pi) * gamma(n / 2 + 1) / gamma(n / 2 + 0.5)


@pytest.mark.parametrize("name", list(PROFILES))
def test_surface_conditions_in_the_contact_at_nu_one_half(name):
    extra, f, delta = PROFILES[name]
    delta = delta if delta is not None else _delta_n(3.0)
    mu, ux0 = 0.5, 0.2
    x = np.array([-0.9, -0.5, 0.0, 0.3, 0.7, 0.95])
    ds = sf.generate({"scenario": _scenario(name), "parameters": {"nu": 0.5, "mu": mu, "ux0": ux0, "x": x.tolist(),
                                                                   **extra},
                      "output": {"variables": DISP + ["stick_radius"]}}).compute()
    u = ds.squeeze()
    np.testing.assert_allclose(u.u_z.values, 1.0 - f(np.abs(x)) / delta, rtol=0, atol=1e-10)
    stick = np.abs(x) < float(ds.stick_radius)
    assert stick.sum() >= 2
    np.testing.assert_allclose(u.u_x.values[stick], ux0, rtol=0, atol=1e-10)
    np.testing.assert_allclose(u.u_y.values, 0.0, rtol=0, atol=1e-12)     # y = 0: symmetry


def test_physical_mode_is_metres_of_the_normalised_values():
    """Steel-like paraboloid: u [m] = (u / delta) * delta at x/a, z/a the same."""
    E, nu, R, delta = 2e11, 0.3, 0.01, 1e-6
    a = np.sqrt(R * delta)
    xs, zs = np.array([0.0, 0.4, 1.7]), np.array([0.0, 0.3])
    given = {"E": E, "nu": nu, "R": R, "delta": delta, "mu": 0.3, "ux0": 0.1, "x": (xs * a).tolist(),
             "z": (zs * a).tolist()}
    phys = sf.generate({"scenario": "parabolic", "parameters": given, "output": {"variables": DISP}}).compute()
    norm = sf.generate({"scenario": "parabolic", "parameters": {"nu": nu, "mu": 0.3, "ux0": 0.1, "x": xs.tolist(),
                                                                 "z": zs.tolist()},
                        "output": {"variables": DISP}}).compute()
    for v in DISP:
        assert phys[v].attrs["units"] == "m" and norm[v].attrs["units"] == "1"
        np.testing.assert_allclose(phys[v].values, norm[v].values * delta, rtol=1e-12, atol=1e-12 * delta)


def test_continuous_from_the_surface_downwards():
    """z = 0 (the surface rule) and z = 1e-9 a (the interior route) agree to the route's accuracy."""
    x = [-1.2, -0.6, 0.0, 0.45, 0.999, 1.001, 2.5]
    for scen, extra in (("conical", {}), ("parabolic", {}), ("axisymmetric", {"profile": "power_law", "n": 1.5})):
        ds = sf.generate({"scenario": scen, "parameters": {"nu": 0.3, "mu": 0.4, "ux0": 0.15, "x": x,
                                                            "z": [0.0, 1e-9], **extra},
                          "output": {"variables": DISP}}).compute()
        for v in DISP:
            top, below = ds[v].isel(z=0).values, ds[v].isel(z=1).values
            np.testing.assert_allclose(below, top, rtol=0, atol=1e-7, err_msg=f"{scen} {v}")


def test_history_stick_zone_follows_the_indenter_at_nu_one_half():
    """After each step of a load-unload-reload history the stick zone's u_x is the current u_x0."""
    hist = [0.1, 0.0, -0.1, 0.05]
    x = np.array([-0.2, 0.0, 0.15])      # inside every step's stick zone (c/a >= ~0.5 here)
    ds = sf.generate({"scenario": "axisymmetric_history",
                      "parameters": {"profile": "power_law", "n": 2.0, "nu": 0.5, "mu": 0.5, "ux0_history": hist,
                                     "x": x.tolist()},
                      "output": {"variables": DISP + ["stick_radius"]}}).compute().squeeze()
    for s, ux0 in enumerate(hist):
        c = float(ds.stick_radius.isel(step=s))
        assert np.all(np.abs(x) < c), (s, c)
        np.testing.assert_allclose(ds.u_x.isel(step=s).values, ux0, rtol=0, atol=1e-10)
        np.testing.assert_allclose(ds.u_z.isel(step=s).values, 1.0 - x ** 2 / 2.0, rtol=0, atol=1e-10)


def test_one_step_history_equals_the_monotonic_scenario():
    params = {"nu": 0.3, "mu": 0.3, "x": [-1.3, -0.2, 0.4, 0.9], "z": [0.0, 0.25, 1.0]}
    mono = sf.generate({"scenario": "parabolic", "parameters": {**params, "ux0": 0.12},
                        "output": {"variables": DISP}}).compute()
    hist = sf.generate({"scenario": "axisymmetric_history",
                        "parameters": {**params, "profile": "power_law", "n": 2.0, "ux0_history": [0.12]},
                        "output": {"variables": DISP}}).compute().squeeze("step", drop=True)
    for v in DISP:
        np.testing.assert_allclose(hist[v].values, mono[v].values, rtol=1e-12, atol=1e-14)


def test_closed_method_takes_the_1d_route_for_displacements_of_a_cone():
    """method = 'closed' gives the cone's closed-form stresses and its 1-D displacements (no closed
    form): the same displacements as 'auto'."""
    base = {"scenario": "conical", "parameters": {"nu": 0.3, "x": [0.2, 1.5], "z": [0.0]},
            "output": {"variables": ["u_z", "sigma_zz"]}}
    closed = sf.generate({**base, "method": {"method": "closed"}}).compute()
    auto = sf.generate(base).compute()
    np.testing.assert_array_equal(closed.u_z.values, auto.u_z.values)
