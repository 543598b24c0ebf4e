"""Axisymmetric scenarios end to end, against closed forms derived by hand (not by the code)."""
import numpy as np
import pytest

import stressfields as sf


def _gen(params, variables, scenario="axisymmetric"):
    return sf.generate({"scenario": scenario, "parameters": params,
                        "output": {"variables": variables}}).compute()


@pytest.mark.parametrize("nu, mu, ux0", [(0.3, 0.5, 0.25), (0.2, 0.1, 0.25), (0.5, 0.4, 0.0)])
def test_flat_punch_normal_and_tangential(nu, mu, ux0):
    x = np.array([-0.9, -0.3, 0.2, 0.7, 0.95])
    ds = _gen({"profile": "flat_punch", "nu": nu, "mu": mu, "ux0": ux0, "x": list(x), "y": 0.0},
              ["sigma_zz", "sigma_xz", "stick_radius", "region"])
    # Boussinesq punch: p = E* delta/(pi sqrt(a^2-r^2)), p_m = 2 E* delta/(pi a)
    root = np.sqrt(1 - x ** 2)
    np.testing.assert_allclose(ds.sigma_zz.values, -0.5 / root, rtol=1e-13)
    gs = 2 * (1 - nu) / (2 - nu)                    # G*/E*
    if ux0 == 0:
        expect_q, stick = 0.0 * root, 1.0
    elif gs * ux0 < mu:                             # whole punch sticks: q = G* u_x0 / (pi sqrt)
        expect_q, stick = gs * ux0 * 0.5 / root, 1.0
    else:                                           # slides: q = mu p
        expect_q, stick = mu * 0.5 / root, 0.0
    np.testing.assert_allclose(ds.sigma_xz.values, -expect_q, rtol=1e-13, atol=1e-15)
    assert float(ds.stick_radius) == stick
    assert set(ds.region.values.tolist()) == {3 if ux0 == 0 else (1 if stick else 2)}


def test_flat_punch_physical_units():
    E, nu, delta, radius = 100e9, 0.25, 1e-6, 2e-3
    r = np.array([0.0, 1e-3, 1.9e-3])
    ds = _gen({"profile": "flat_punch", "E": E, "nu": nu, "delta": delta, "radius": radius,
               "x": list(r), "y": 0.0}, ["sigma_zz", "normal_force", "contact_radius"])
    e_star = E / (1 - nu ** 2)
    np.testing.assert_allclose(ds.sigma_zz.values, -e_star * delta / (np.pi * np.sqrt(radius ** 2 - r ** 2)),
                               rtol=1e-13)
    assert float(ds.normal_force) == pytest.approx(2 * e_star * delta * radius, rel=1e-13)
    assert float(ds.contact_radius) == radius
    with pytest.raises(sf.RecipeError, match="delta cannot be swept"):
        sf.generate({"scenario": "axisymmetric", "parameters": {
            "profile": "flat_punch", "E": E, "delta": [1e-6, 2e-6], "radius": radius, "x": [0.0]}})


def test_power_law_two_is_hertz_mindlin():
    """n = 2 through the integral route equals the paraboloid's closed forms (Hamilton-Goodman)."""
    params = {"nu": 0.3, "mu": 0.3, "ux0": 0.25, "x": [-1.3, -0.7, 0.1, 0.5, 0.9, 1.2], "y": [0.0, 0.4]}
    names = ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "dpdz"]
    quad = sf.generate({"scenario": "axisymmetric", "parameters": {"n": 2.0, **params},
                        "output": {"variables": names}, "method": {"method": "quadrature"}}).compute()
    closed = _gen(params, names, scenario="parabolic")
    for name in names:
        np.testing.assert_allclose(quad[name].values, closed[name].values, rtol=1e-10, atol=1e-10)
    # Hertz inside the contact, normal part: sigma_zz = -p, p = (3/2) p_m sqrt(1 - r^2)
    r = np.hypot(0.1, 0.4)
    assert float(closed.sigma_zz.sel(x=0.1, y=0.4)) == pytest.approx(-1.5 * np.sqrt(1 - r ** 2), rel=1e-13)


def test_a_table_with_a_vanishing_step_is_refused_before_it_is_built():
    """A 1e-300 step stalled the table construction: the check refuses it first, naming the key."""
    import stressfields as sf
    from stressfields.recipe import RecipeError

    r = [0.0, 1e-300, 2e-300, 3e-300, 0.5, 1.0, 1.2]
    with pytest.raises(RecipeError, match="profile_r has a step of 1e-300"):
        sf.generate({"scenario": "axisymmetric", "parameters": {
            "profile": "tabulated", "profile_r": r, "profile_f": [x * x for x in r], "x": [0.5]}})
