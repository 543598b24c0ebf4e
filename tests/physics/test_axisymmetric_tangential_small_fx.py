"""The Cattaneo–Mindlin tangential stresses and dp/dz keep their relative accuracy as fx -> 0.

As c -> a the tangential field is the difference of two terms at a and at c (or an integral over the
rounded [c, a]); the kernels take the annulus width a - c from the slip ratio
(``profiles.annulus_width``) and, below the surface, the superposition of sliding punches over a thin
annulus (docs/theory/axisymmetric.md (A109), docs/theory/interior.md (I59)).  References, with the
exact c = a (1 - fx)^(1/(n+1)) in 40 digits:

* on the surface, the defining integrals (A34), (A39)-(A41) by tanh-sinh and the closed dp/dz
  (A56)-(A58), all in 40-digit mpmath;
* below it, the superposition mu int_c^a g'(t) K(p/t) t^k dt of the unit sliding punch (I45)
  (stresses k = -1, dp/dz k = -2) by mpmath's tanh-sinh quadrature in the offset a - t (its range
  a - c from the 40-digit c; the punch kernel in doubles, its r/t - 1 formed in extended
  precision), split at the ring point nearest to p: another rule and another switch than the
  code's (8-point Gauss far, graded panels near).
"""
import importlib
import math

import mpmath as mp
import numpy as np
import pytest

from stressfields.physics.axisymmetric import profiles as P
from stressfields.physics.axisymmetric.interior_hertz import sliding_punch_unit
from stressfields.physics.axisymmetric.interior_tangential import (interior_dpdz_tangential,
                                                                   interior_stress_tangential,
                                                                   sliding_punch_dpdz_unit)
from stressfields.physics.axisymmetric.surface import mean_pressure
from stressfields.physics.axisymmetric.tangential import dpdz_closed, inplane_closed

# the package re-exports a function named ``fields``: the module itself
F = importlib.import_module("stressfields.physics.axisymmetric.fields")

R, A, MU = 1.0, 0.5, 0.3
PROFILE = P.paraboloid(R)
PROFILES = {"paraboloid": PROFILE, "cone": P.cone(0.2), "power_law_0.7": P.power_law(1.0, 0.7),
            "power_law_3": P.power_law(1.0, 3.0)}
KEYS = ("xx", "yy", "zz", "xy", "xz", "yz")


def load(fx, nu, profile=PROFILE):
    """(ux0, c, w, c exact in mpmath) as the scenarios form them from fx: F_N ~ a^(n+1), so
    c = a (1 - fx)^(1/(n+1)) (A107)."""
    n = getattr(profile, "n", None) or (2 if profile.closed[0] == "paraboloid" else 1)
    with mp.workdps(40):
        c_exact = mp.mpf(A) * (1 - mp.mpf(fx)) ** (mp.mpf(1) / (n + 1))
    ux0 = P.displacement_ratio(P.slip_ratio(profile, A, fx), nu, MU)
    c = P.stick_radius_of_force(profile, A, 1.0 - fx)
    w = P.annulus_width(profile, A, c, ux0, nu, MU)
    return float(ux0), float(c), float(w), c_exact


def points(w):
    """Stick zone (off and on the axis y = 0), the middle of the thin slip annulus (from the outer
    edge, on y = 0 so that r - a is exact), outside the contact."""
    return [(0.3 * A, 0.2 * A), (A - 0.5 * w, 0.0), (0.6 * A * math.cos(0.3), 0.6 * A * math.sin(0.3)),
            (1.4 * A, 0.5 * A)]


def surface_reference(profile, x, y, nu, c):
    """Tangential sigma_xz, sigma_xx, sigma_yy, sigma_xy and dp/dz / E* on the surface, 40 digits:
    (A34) and (A39)-(A41) by tanh-sinh over u = r cosh t, r sin t (g' = 2u/R or pi tan(theta)/2), dp/dz (A56)-(A58)."""
    with mp.workdps(40):
        x, y, nu, a, c = mp.mpf(x), mp.mpf(y), mp.mpf(nu), mp.mpf(A), mp.mpf(c)
        r = mp.hypot(x, y)
        kind = profile.closed[0] if profile.closed else profile.kind
        cone = kind == "cone"
        k1 = mp.mpf(profile.closed[1]) if profile.closed else None
        n = mp.mpf(getattr(profile, "n", 1))
        kn = mp.mpf(float(profile.dg(A))) / a ** (n - 1)

        def dg(u):
            if kind == "power_law":
                return kn * u ** (n - 1)
            return mp.pi * k1 / 2 if cone else 2 * u / k1

        # u = r cosh(t) and u = r sin(t) take the square roots out of the integrands
        xz = -MU / mp.pi * mp.quad(lambda t: dg(r * mp.cosh(t)), [mp.acosh(max(r, c) / r), mp.acosh(a / r)]) \
            if r < a else 0
        lo, hi = mp.asin(min(r, c) / r), mp.asin(min(r, a) / r)
        ints = [mp.quad(lambda t: h(r * mp.sin(t)) * r * mp.sin(t) * dg(r * mp.sin(t)), [lo, hi]) if lo < hi else 0
                for h in (lambda u: (1 + nu) * r ** 4 - nu * (u * u * r * r + y * y * (3 * r * r - 4 * u * u)),
                          lambda u: u * u * r * r + y * y * (3 * r * r - 4 * u * u),
                          lambda u: (1 - 2 * nu) * r ** 4 + 2 * nu * (u * u * r * r + x * x * (3 * r * r - 4 * u * u)))]
        xx = -2 * MU * x / (mp.pi * r ** 6) * ints[0]
        yy = -2 * nu * MU * x / (mp.pi * r ** 6) * ints[1]
        xy = -MU * y / (mp.pi * r ** 6) * ints[2]
        C2 = 2 * (1 + nu) / 3
        if r >= a or kind == "power_law":
            dp = 0
        elif cone:
            p0 = k1 / 2
            inner = c / mp.sqrt(c * c - r * r) if r < c else 0
            dp = -C2 * MU * p0 * (x / r ** 2) * (a / mp.sqrt(a * a - r * r) - inner)
        else:
            inner = 1 / mp.sqrt(c * c - r * r) if r < c else 0
            dp = -2 * C2 * MU / (mp.pi * k1) * x * (1 / mp.sqrt(a * a - r * r) - inner)
        return {k: float(v) for k, v in dict(xz=xz, xx=xx, yy=yy, xy=xy, dpdz=dp).items()}


def interior_reference(x, y, z, nu, c, dpdz=False, profile=PROFILE):
    """mu int_c^a g'(t) K(p/t) t^k dt (I45) by tanh-sinh, split at the ring point nearest to p.  The
    kernel is a double, so the rule runs at 20 digits (far below the kernel's rounding) in the
    offset s = a - t, whose range a - c is taken from the 40-digit c.  One kernel call per node
    serves all components."""
    with mp.workdps(40):
        width = mp.mpf(A) - c                     # the annulus' width, in offsets s = a - t from a
        gap = mp.mpf(A) - mp.hypot(x, y)          # a - r
    with mp.workdps(20):
        cut = [0, gap, width] if 0 < gap < width else [0, width]
        memo = {}

        def kernel(s):
            if s not in memo:
                t = mp.mpf(A) - s
                rm1, tf = float((s - gap) / t), float(t)        # r/t - 1 = (s - (a - r))/t
                g = float(profile.dg(tf)) / tf
                if dpdz:
                    memo[s] = {"dpdz": g * float(sliding_punch_dpdz_unit(x / tf, y / tf, z / tf, nu, rm1=rm1)) / tf}
                else:
                    memo[s] = {k: g * float(v)
                               for k, v in sliding_punch_unit(x / tf, y / tf, z / tf, nu, rm1=rm1).items()}
            return memo[s]

        keys = ("dpdz",) if dpdz else KEYS
        return {k: float(MU * mp.quad(lambda s: kernel(s)[k], cut)) for k in keys}


@pytest.mark.parametrize("name", ["paraboloid", "cone"])
@pytest.mark.parametrize("fx", [1e-6, 1e-9, 1e-12])
@pytest.mark.parametrize("nu", [0.0, 0.3, 0.5])
def test_surface_tangential_part_keeps_relative_accuracy(name, fx, nu):
    profile = PROFILES[name]
    ux0, c, w, c_exact = load(fx, nu, profile)
    for x, y in points(w):
        ref = surface_reference(profile, x, y, nu, c_exact)
        # sigma_xz through the product's own route (it has no normal part)
        out, _ = F.fields(["sigma_xz"], profile, x, y, a=A, nu=nu, mu=MU, ux0=ux0, stick=c, method="closed")
        got = {"xz": float(out["sigma_xz"])}
        # the tangential in-plane part and dp/dz from their kernels (the normal parts are O(1) against O(fx))
        args = [np.array([v]) for v in (x, y, math.hypot(x, y), A, c, nu, MU)]
        got.update(zip(("xx", "yy", "xy"), (float(v[0]) for v in inplane_closed(profile.closed, *args, np.array([w])))))
        got["dpdz"] = float(dpdz_closed(profile.closed, *args[:1], *args[2:], np.array([w]))[0])
        scale = max(abs(ref[k]) for k in ("xz", "xx", "yy", "xy"))
        for k in ("xz", "xx", "yy", "xy"):
            assert abs(got[k] - ref[k]) <= 1e-12 * scale, (name, fx, nu, x, y, k, got[k], ref[k])
        assert abs(got["dpdz"] - ref["dpdz"]) <= 1e-12 * abs(ref["dpdz"]), (name, fx, nu, x, y, got["dpdz"], ref)
        # and the full surface dp/dz carries that part on top of the normal one
        total = float(F.surface_dpdz(x, y, A, c, nu, MU, profile, width=w))
        normal = float(F.surface_dpdz(x, y, A, c, nu, 0.0, profile))
        assert abs((total - normal) - got["dpdz"]) <= 1e-15 * abs(normal) + 1e-12 * abs(got["dpdz"])


@pytest.mark.parametrize("name", ["power_law_0.7", "power_law_3"])
@pytest.mark.parametrize("fx", [1e-9, 1e-12])
def test_surface_1d_route_meets_its_contract(name, fx):
    """Power laws other than n = 1, 2 take the 1-D route on the surface: |error| <= rtol max(|v|, mu p_m)
    (rtol = 1e-10), met as fx -> 0 although its range [c, a] is the rounded one."""
    profile, nu = PROFILES[name], 0.3
    ux0, c, w, c_exact = load(fx, nu, profile)
    floor = MU * float(mean_pressure(A, profile))
    for x, y in points(w):
        ref = surface_reference(profile, x, y, nu, c_exact)
        tot = F.surface_stress(x, y, A, c, nu, MU, profile, method="quadrature", components=("xx", "yy", "xy", "xz"),
                               width=w)
        nor = F.surface_stress(x, y, A, c, nu, 0.0, profile, method="quadrature", components=("xx", "yy", "xy"))
        for k in ("xx", "yy", "xy", "xz"):
            got = float(tot[k]) - (float(nor[k]) if k != "xz" else 0.0)
            assert abs(got - ref[k]) <= 1e-10 * max(abs(ref[k]), floor), (name, fx, x, y, k, got, ref[k])


@pytest.mark.parametrize("fx", [1e-6, 1e-9, 1e-12])
@pytest.mark.parametrize("z", [1e-9, 0.1, 1.0])
def test_interior_tangential_keeps_relative_accuracy(fx, z):
    nu = [0.0, 0.3, 0.5][int(round(-math.log10(fx) / 3)) % 3]   # every nu over the fx
    check_interior(PROFILE, fx, z, nu)


@pytest.mark.parametrize("name", ["cone", "power_law_0.7", "power_law_3"])
@pytest.mark.parametrize("fx", [1e-9, 1e-12])
def test_interior_tangential_of_the_1d_route_profiles(name, fx):
    """Cone and power laws: the 1-D route integrates over [c, a] of the rounded c (1e-16/rho of the
    annulus' part: 1e-7 of dp/dz next to the ring at fx = 1e-9); the thin annulus takes w."""
    for z in (1e-9, 0.1):
        check_interior(PROFILES[name], fx, z, 0.3)


def check_interior(profile, fx, z, nu):
    ux0, c, w, c_exact = load(fx, nu, profile)
    for x, y in points(w):
        got = interior_stress_tangential(x, y, z * A, A, c, nu, MU, profile, width=w)
        ref = interior_reference(x, y, z * A, nu, c_exact, profile=profile)
        scale = max(abs(v) for v in ref.values())
        for k in KEYS:
            assert abs(float(got[k]) - ref[k]) <= 1e-12 * scale, (fx, z, x, y, k, float(got[k]), ref[k])
        got_dp = float(interior_dpdz_tangential(x, y, z * A, A, c, nu, MU, profile, width=w))
        ref_dp = interior_reference(x, y, z * A, nu, c_exact, dpdz=True, profile=profile)["dpdz"]
        assert abs(got_dp - ref_dp) <= 1e-12 * abs(ref_dp), (fx, z, x, y, got_dp, ref_dp)


def test_fields_below_the_surface_take_the_exact_width():
    """The product's own route (fields with depth) gives the superposition's values."""
    fx, nu, z = 1e-9, 0.3, 1e-9
    ux0, c, w, c_exact = load(fx, nu)
    x, y = 0.3 * A, 0.2 * A
    out, _ = F.fields(["sigma_xz"], PROFILE, x, y, z * A, a=A, nu=nu, mu=MU, ux0=ux0, stick=c, method="closed")
    normal, _ = F.fields(["sigma_xz"], PROFILE, x, y, z * A, a=A, nu=nu, mu=0.0, ux0=0.0, method="closed")
    ref = interior_reference(x, y, z * A, nu, c_exact)["xz"]
    tangential = float(out["sigma_xz"]) - float(normal["sigma_xz"])
    assert abs(tangential - ref) <= 1e-12 * abs(ref) + 1e-15 * abs(float(normal["sigma_xz"]))


def test_continuous_across_the_thin_annulus_switch():
    """Just below and just above the slip ratio 1e-3 where the superposition takes over from the
    difference of the two Hertz fields: both routes within 1e-12 of the reference, so no jump."""
    nu = 0.3
    for slip in (1e-3 * (1 - 1e-9), 1e-3 * (1 + 1e-9)):
        w = A * slip / (1 + math.sqrt(1 - slip))
        c = A - w
        with mp.workdps(40):
            c_exact = mp.mpf(A) - mp.mpf(w)
        # (next to the ring at depths below ~1e-4 a the difference route itself errs by more)
        for x, y, z in [(0.3 * A, 0.2 * A, 1e-3), (A - 0.5 * w, 0.0, 1e-2), (1.2 * A, 0.1, 0.1)]:
            got = interior_stress_tangential(x, y, z, A, c, nu, MU, PROFILE, width=w)
            ref = interior_reference(x, y, z, nu, c_exact)
            scale = max(abs(v) for v in ref.values())
            for k in KEYS:
                assert abs(float(got[k]) - ref[k]) <= 1e-12 * scale, (slip, x, z, k)
            got_dp = float(interior_dpdz_tangential(x, y, z, A, c, nu, MU, PROFILE, width=w))
            ref_dp = interior_reference(x, y, z, nu, c_exact, dpdz=True)["dpdz"]
            assert abs(got_dp - ref_dp) <= 1e-12 * abs(ref_dp), (slip, x, z)
