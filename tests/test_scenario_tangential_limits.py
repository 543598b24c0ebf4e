"""The Cattaneo–Mindlin load given as a force, near its limits fx -> 1 (gross slip) and fx -> 0: the
stick radius against 50-digit closed forms (c/a = (1 - fx)^(1/(n+1)) for the power laws, from
F_N(c) = (1 - fx) F_N(a), docs/theory/axisymmetric.md (A107); a paraboloid table, whose spline is the
quadratic itself, obeys the same law), independent of nu and mu as the exact c is, and through
tangential_force with 1 - F_x/(mu F_N) formed in 50 digits from the very doubles of the recipe."""
import math

import mpmath as mp
import numpy as np
import pytest

import stressfields as sf

mp.mp.dps = 50
TABLE = [i / 16 for i in range(17)]
PROFILES = {          # scenario, geometry, exponent n of F_N ~ a^(n+1) (None: the flat punch)
    "cone": ("conical", {}, 1),
    "paraboloid": ("parabolic", {}, 2),
    "power_law_3": ("axisymmetric", {"n": 3.0}, 3),
    "power_law_0.7": ("axisymmetric", {"n": 0.7}, 0.7),
    "tabulated_paraboloid": ("axisymmetric", {"profile": "tabulated", "profile_r": TABLE,
                                              "profile_f": [r * r for r in TABLE]}, 2),
    "flat_punch": ("axisymmetric", {"profile": "flat_punch"}, None),
}
FX = [1e-12, 1e-9, 1e-4, 0.5, 1 - 1e-4, 1 - 1e-9, 0.999999999999, 1 - 2.0 ** -52]


def exact_ratio(keep, n):
    """c/a of F_N(c) = keep F_N(a): keep^(1/(n+1)) (power laws); the punch sticks whole below fx = 1."""
    if n is None:
        return mp.mpf(1) if keep > 0 else mp.mpf(0)
    return mp.mpf(keep) ** (1 / (mp.mpf(n) + 1))


@pytest.mark.parametrize("name", sorted(PROFILES))
def test_stick_radius_of_fx_near_both_limits_and_free_of_nu_and_mu(name):
    scenario, geometry, n = PROFILES[name]
    ds = sf.generate({"scenario": scenario, "parameters": {**geometry, "nu": [0.0, 0.3, 0.5], "mu": [0.05, 0.3, 2.0],
                                                           "fx": FX, "x": 0.0},
                      "output": {"variables": ["stick_radius"]}}).compute()
    c = ds.stick_radius.transpose("fx", "nu", "mu").values
    # the exact c does not depend on nu or mu: neither may the computed one (it did through u_x0)
    assert np.all(c == c[:, :1, :1])
    for got, fx in zip(c[:, 0, 0], FX):
        want = exact_ratio(1 - mp.mpf(fx), n)
        assert abs(got - want) <= 1e-12 * want, (name, fx, got, want)


@pytest.mark.parametrize("name", ["cone", "paraboloid", "power_law_3"])
def test_stick_radius_of_a_tangential_force_next_to_mu_F_N(name):
    """F_x within 1e-12 of mu F_N: 1 - F_x/(mu F_N) was formed after rounding the ratio (4e-11 off);
    the reference forms it in 50 digits from the same doubles."""
    scenario, geometry, n = PROFILES[name]
    physical = {"cone": {"theta": 0.2}, "paraboloid": {"R": 0.01}, "power_law_3": {"n": 3.0, "A": 2e3}}[name]
    force, mu = 100.0, 0.3
    limit = mp.mpf(mu) * mp.mpf(force)
    loads = [float(limit * (1 - mp.mpf(e))) for e in (1e-4, 1e-9, 1e-12, 1e-14)]
    ds = sf.generate({"scenario": scenario, "parameters": {**geometry, **physical, "E": 2e11, "nu": [0.2, 0.4],
                                                           "mu": mu, "normal_force": force, "tangential_force": loads,
                                                           "x": 0.0},
                      "output": {"variables": ["stick_radius", "contact_radius"]}}).compute()
    ratio = (ds.stick_radius / ds.contact_radius).transpose("tangential_force", "nu").values
    for got, q in zip(ratio, loads):
        want = exact_ratio(1 - mp.mpf(q) / limit, n)
        assert np.all(np.abs(got - float(want)) <= 1e-12 * float(want)), (q, got, want)
    # F_x = mu F_N as the product rounds is the onset of gross slip, c = 0
    at = sf.generate({"scenario": scenario, "parameters": {**geometry, **physical, "E": 2e11, "nu": 0.3, "mu": mu,
                                                           "normal_force": force, "tangential_force": mu * force,
                                                           "x": 0.0},
                      "output": {"variables": ["stick_radius", "fx"]}}).compute()
    assert float(at.stick_radius) == 0.0 and float(at.fx) == 1.0


def test_hertz_mindlin_displacement_keeps_its_digits_as_fx_goes_to_0():
    """At nu = 0.5 the normal pressure moves the surface only vertically, so at the surface inside the
    stick zone u_x is the rigid-body displacement u_x0 itself and u_y = 0 (docs/theory/axisymmetric.md
    (A32)); the two Cattaneo–Mindlin terms cancel as fx -> 0 and lost 1e-16/fx of it (8e-8 at 1e-9)."""
    fx = [1e-12, 1e-9, 1e-6, 1e-3]
    ds = sf.generate({"scenario": "parabolic", "parameters": {"nu": 0.5, "mu": 0.3, "fx": fx, "y": [0.0, 0.4],
                                                              "x": [-0.5, 0.0, 0.3]},
                      "output": {"variables": ["u_x", "u_y", "ux0"]}}).compute()
    ux0 = ds.ux0.values[:, None, None]
    assert np.all(np.abs(ds.u_x.transpose("fx", "y", "x").values - ux0) <= 1e-12 * ux0)
    assert np.all(np.abs(ds.u_y.transpose("fx", "y", "x").values) <= 1e-12 * ux0)


def test_hertz_mindlin_displacement_below_the_centre_as_fx_goes_to_0():
    """On the axis the normal load has no horizontal displacement, so u_x/u_x0 there is the tangential
    field per unit load, which tends to its fx -> 0 limit by O(fx): from fx = 1e-12 to 1e-9 it moves by
    about 1e-9 (it moved by 1.6e-7 at z = 1e-9 a, and 1e-4 at fx = 1e-12, with the cancellation)."""
    z = [1e-9, 0.1, 1.0, 3.0]
    base = {"nu": 0.2, "mu": 0.3, "x": 0.0, "y": 0.0, "z": z}
    ds = sf.generate({"scenario": "parabolic", "parameters": {**base, "fx": [1e-12, 1e-9]},
                      "output": {"variables": ["u_x", "ux0"]}}).compute()
    ratio = (ds.u_x / ds.ux0).transpose("fx", "z").values
    assert np.all(np.abs(ratio[1] - ratio[0]) <= 5e-9 * np.abs(ratio[0]))


@pytest.mark.parametrize("fx", [1e-6, 1e-5])
def test_hertz_mindlin_tangential_field_across_the_thin_slip_annulus(fx):
    """The tangential part of (I41), mu (2/pi) [V(p/a) - (c/a)^2 V(p/c)], against the same difference in
    80-bit extended precision (c from (1 - fx)^(1/3) there too), whose cancellation costs it
    1e-19/rho, 1.5e-13 at fx = 1e-6: at points inside, across and outside the slip annulus and close
    above it, where the plain double difference missed by 3e-10 to 7e-10."""
    from stressfields.physics.axisymmetric.displacement import _hertz_mindlin, hertz_sliding_displacement_unit

    ld = np.longdouble
    nu, mu = 0.3, 0.3
    s = np.cbrt(ld(1) - ld(fx))
    r = np.array([0.0, 0.5, 1 - 1e-5, 1 - 5e-7, 1 - 1e-7, 1.0, 1 + 1e-7, 1 + 1e-5, 1.5])
    R, Z = (v.ravel() for v in np.meshgrid(r, [0.0, 1e-12, 1e-8, 1e-6, 1e-4, 0.1]))
    x, y = 0.8 * R, 0.6 * R
    n = x.size
    got = _hertz_mindlin(x, y, Z, np.ones(n), np.full(n, float(s)), np.full(n, nu), np.full(n, mu),
                         np.full(n, float(1 - s * s)))
    xl, yl, zl = (v.astype(ld) for v in (x, y, Z))
    outer = hertz_sliding_displacement_unit(xl, yl, zl, ld(nu))
    inner = hertz_sliding_displacement_unit(xl / s, yl / s, zl / s, ld(nu))
    scale = mu * float(1 - s * s)                  # the tangential displacement's size, ~ u_x0/delta
    for k in "xyz":
        want = (ld(2) / ld(math.pi) * ld(mu) * (outer[k] - s * s * inner[k])).astype(float)
        assert np.all(np.abs(got[k] - want) <= 1e-12 * np.maximum(np.abs(want), scale)), k


def test_tangential_force_with_delta_near_gross_slip_is_refused_or_right():
    """With delta given, F_N is derived and carries its rounding, which 1 - fx magnifies (c/a was 7e-5
    off at 1 - fx = 1e-12): within 1e-3 of mu F_N the recipe is refused naming the way out, below it
    the stick radius meets 1e-12 against 50 digits."""
    E, nu, R, delta, mu = 2e11, 0.3, 0.01, 1e-6, 0.3
    e_star = mp.mpf(E) / (1 - mp.mpf(nu) ** 2)
    a = mp.sqrt(mp.mpf(R) * mp.mpf(delta))
    limit = mu * 4 * e_star * a ** 3 / (3 * R)              # Hertz F_N of delta
    base = {"E": E, "nu": nu, "R": R, "delta": delta, "mu": mu, "x": 0.0}
    with pytest.raises(sf.RecipeError, match="give normal_force instead of delta, or the load as fx"):
        sf.generate({"scenario": "parabolic",
                     "parameters": {**base, "tangential_force": float(limit * (1 - mp.mpf(1e-6)))}})
    loads = [float(limit * (1 - mp.mpf(e))) for e in (0.5, 1e-2, 1.001e-3)]
    ds = sf.generate({"scenario": "parabolic", "parameters": {**base, "tangential_force": loads},
                      "output": {"variables": ["stick_radius"]}}).compute()
    for got, q in zip(ds.stick_radius.values, loads):
        want = a * mp.cbrt(1 - mp.mpf(q) / limit)
        assert abs(got - want) <= 1e-12 * want, (q, got, want)
