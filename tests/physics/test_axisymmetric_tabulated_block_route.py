"""The block route of tabulated profiles (docs/theory/axisymmetric.md (A104)-(A105)) against
routes that share nothing with it:

* every 1-D integral of the surface route (tau_integrals, theta_moments, pressure_gradient_D,
  pressure_gradient_far, normal_force) against scipy's adaptive quad_vec of its defining integral
  in u, split at the knots with u = e_i + (e_i+1 - e_i) sin^2(pi w/2) on each piece, which makes
  both the knot's cusp and the kernel's end-point root smooth in w; the load against the
  profile's exact sums (A10);
* the surface stresses and dp/dz end to end against the knot-resolving rules (the route the block
  route replaced, still reachable through ``integrals._BLOCKS``) at rtol 1e-14;
* the cost: table lookups and block nodes per point, counted (not timed), no longer grow with
  the sample count.

Profiles: the hyperboloid of recipes/tabulated_hyperboloid.toml sampled at 25, 200 and 1000
radii, and a measured-like table (jittered radii, noisy but monotone heights).  Points: r = 0,
r = c +- 1e-9, r = a +- 1e-9, the far field r = 1e3 a and a spread in between.
"""
import functools
import math

import numpy as np
import pytest
from scipy.integrate import quad_vec

from stressfields.physics import axisymmetric as ax
from stressfields.physics.axisymmetric import integrals as I
from stressfields.physics.axisymmetric.common import arccosh_ratio, sqrt_diff
from stressfields.physics.quadrature import orders

A, NU, MU = 1.0, 0.3, 0.4
RTOLS = (1e-6, 1e-8, 1e-10, 1e-12)


def _measured_like():
    rng = np.random.default_rng(11)
    n = 200
    h = 1.6 / (n - 1)
    r = np.linspace(0.0, 1.6, n) + np.concatenate([[0.0], rng.uniform(-0.25, 0.25, n - 2) * h, [0.0]])
    f = 0.3 * r ** 2 + 0.05 * r + 1e-4 * np.cumsum(rng.random(n))
    return r, f


def _hyperboloid(n):
    r = np.linspace(0.0, 1.2, n)
    return r, np.sqrt(r ** 2 + 0.04) - 0.2


SHAPES = {"hyperboloid_25": _hyperboloid(25), "hyperboloid_200": _hyperboloid(200),
          "hyperboloid_1000": _hyperboloid(1000), "measured_like": _measured_like()}


@functools.lru_cache(maxsize=None)
def _case(name):
    prof = ax.tabulated(*SHAPES[name])
    c = float(ax.stick_radius(A, NU, MU, 0.25, prof))
    pm = float(ax.mean_pressure(A, prof))
    return prof, c, pm


def _radii(c, few=False):
    special = [c - 1e-9, c + 1e-9, A - 1e-9, A + 1e-9, 1e3 * A]
    spread = np.geomspace(1e-6, 1.9, 6 if few else 22)
    return np.sort(np.concatenate([special, spread, [2.5]]))


# -- the defining integrals in u (A104) by adaptive quadrature ---------------------------------------

def _kernel(kind, u, gap, r):
    """k(u, r) of (A104); gap = u - r (cosh kinds) or r - u (sin kinds), formed without cancellation."""
    if kind in ("G", "GE", "H"):
        s = np.sqrt(gap * (u + r))
        return {"G": 1.0 / s, "GE": r * r / (s * (u + s) ** 2), "H": 1.0 / (s * (u + s))}[kind]
    cc = np.sqrt(gap * (r + u))
    return {"P0": u / (r * cc), "P2": (u / r) ** 3 / cc, "D": 1.0 / cc, "F": u * r / cc ** 3}[kind]


def _reference(prof, kind, r, U0, U1):
    """int_U0^U1 phi(u) k(u, r) du, phi = g'' for H and D, else g'."""
    if U1 <= U0:
        return 0.0
    kn = prof._knots
    e = np.concatenate([[U0], kn[(kn > U0) & (kn < U1)], [U1]])
    lo, hi = e[:-1], e[1:]
    d = hi - lo
    phi = prof.d2g if kind in ("H", "D") else prof.dg
    cosh = kind in ("G", "GE", "H")

    def f(w):
        q, q1 = math.sin(0.5 * math.pi * w) ** 2, math.cos(0.5 * math.pi * w) ** 2
        u = lo + d * q if q < 0.5 else hi - d * q1
        gap = (lo - r) + d * q if cosh else (r - hi) + d * q1
        return phi(u) * _kernel(kind, u, gap, r) * d * (0.5 * math.pi * math.sin(math.pi * w))

    val, _ = quad_vec(f, 0.0, 1.0, epsabs=1e-300, epsrel=1e-14, norm="max", limit=2000)
    return float(np.sum(val))


@functools.lru_cache(maxsize=None)
def _references(name):
    """{kind: (r, value)} of every integral the surface route takes, at the test radii."""
    prof, c, pm = _case(name)
    rs = _radii(c, few=name == "hyperboloid_1000")
    rs = rs[rs > 0]
    out = {}
    inside = rs[rs < A]
    out["G"] = (inside, [_reference(prof, "G", r, max(r, c), A) for r in inside])
    out["GE"] = (inside, [_reference(prof, "GE", r, r, A) for r in inside])
    out["H"] = (inside, [_reference(prof, "H", r, max(r, c), A) for r in inside])
    slip = rs[rs > c]
    out["P0"] = (slip, [_reference(prof, "P0", r, c, min(r, A)) for r in slip])
    out["P2"] = (slip, [_reference(prof, "P2", r, c, min(r, A)) for r in slip])
    near = rs[rs <= 2.0 * A]
    # D(r) = g'(0)/r + the integral (A85): a conical tip's 1/r term is part of the value
    out["D"] = (near, [float(prof.dg(0.0)) / r + _reference(prof, "D", r, 0.0, min(r, A)) for r in near])
    far = rs[rs > 2.0 * A]          # the direct outside integral serves r > 2a only (A86)
    out["F"] = (far, [_reference(prof, "F", r, 0.0, A) for r in far])
    return out


def _computed(prof, kind, r, c, ords):
    """The integral by the package's route, with the limits in the stable forms its callers use
    (A79): arccosh(a/r) as arccosh(1 + 1e-9) from a/r would be off by 3e-8 relative."""
    if kind in ("G", "GE", "H"):
        lo = np.where(r < c, arccosh_ratio(c, np.minimum(r, c)), 0.0) if kind != "GE" else np.zeros_like(r)
        return I.tau_integrals(prof, r, lo, arccosh_ratio(A, r), ords, (kind,))[kind]
    if kind in ("P0", "P2"):
        th_lo, th_hi = np.arctan2(c, sqrt_diff(r, c)), np.arctan2(np.minimum(r, A), sqrt_diff(r, np.minimum(r, A)))
        return I.theta_moments(prof, r, th_lo, th_hi, ords)[0 if kind == "P0" else 1]
    h = np.minimum(r, A)
    th = np.arctan2(h, sqrt_diff(r, h))
    if kind == "D":
        return I.pressure_gradient_D(prof, r, th, ords)
    return I.pressure_gradient_far(prof, r, th, ords)


def _scale(kind, r, pm):
    """The integral's share of the contract's scale S (p_m for stresses, p_m/a for dp/dz): the
    stresses are G/pi, (G - GE)/(2 pi), (2 mu/pi) P; dp/dz is C D, (C/r) F and C_T x H with
    C, C_T < 1 and |x| <= r."""
    return {"G": math.pi * pm, "GE": math.pi * pm, "P0": 0.5 * math.pi * pm, "P2": 0.5 * math.pi * pm,
            "D": pm / A, "F": r * pm / A, "H": pm / (A * r)}[kind]


@pytest.mark.slow   # adaptive-quadrature references, ~16 s
@pytest.mark.parametrize("rtol", RTOLS)
@pytest.mark.parametrize("name", list(SHAPES))
def test_integrals_against_adaptive_quadrature(name, rtol):
    prof, c, pm = _case(name)
    ords = orders(rtol)
    assert I.blocks_apply(prof)
    for kind, (r, ref) in _references(name).items():
        ref = np.asarray(ref)
        got = _computed(prof, kind, r, c, ords)
        bound = rtol * np.maximum(np.abs(ref), _scale(kind, r, pm))
        err = np.abs(got - ref)
        worst = int(np.argmax(err / bound))
        assert np.all(err <= bound), (kind, r[worst], got[worst], ref[worst], err[worst] / bound[worst])


@pytest.mark.parametrize("name", list(SHAPES))
def test_load_against_exact_sums(name):
    """F(h) of the block tree against the exact sums (A10), h from 1e-8 a to the table's end and
    next to knots; the load enters the stresses as F(r)/(2 r^2) (A84), so the contract asks
    |error| <= rtol pi p_m r^2 at least (here relative 1e-12)."""
    prof, _, pm = _case(name)
    kn = prof._knots
    h = np.concatenate([np.geomspace(1e-8, kn[-1], 40), kn[1:-1:7] * (1 + 1e-9), kn[1:-1:7] * (1 - 1e-9)])
    exact = prof.normal_force(h)
    for rtol in RTOLS:
        got = I.normal_force(prof, h, orders(rtol))
        np.testing.assert_array_less(np.abs(got - exact), 1e-12 * np.abs(exact) + 1e-300)


def _points(c):
    r = np.concatenate([[0.0], _radii(c)])
    phi = 0.7
    x = np.concatenate([r * math.cos(phi), [c - 1e-9, c + 1e-9, A - 1e-9, A + 1e-9]])
    y = np.concatenate([r * math.sin(phi), [0.0, 0.0, 0.0, 0.0]])
    return x, y


@functools.lru_cache(maxsize=None)
def _knot_route(name):
    """Stresses and dp/dz of the knot-resolving rules at rtol 1e-14."""
    prof, c, _ = _case(name)
    x, y = _points(c)
    I._BLOCKS = False
    try:
        s = ax.surface_stress(x, y, A, c, NU, MU, prof, method="quadrature", rtol=1e-14)
        d = ax.surface_dpdz(x, y, A, c, NU, MU, prof, method="quadrature", rtol=1e-14)
    finally:
        I._BLOCKS = True
    return s, d


@pytest.mark.parametrize("rtol", RTOLS)
@pytest.mark.parametrize("name", list(SHAPES))
def test_surface_route_against_knot_rules(name, rtol):
    """|error| <= rtol max(|value|, S), S = p_m for the stresses and p_m/a for dp/dz, with the
    knot-resolving rules at rtol 1e-14 as the reference (their own error: below 1e-13 S here)."""
    prof, c, pm = _case(name)
    x, y = _points(c)
    ref_s, ref_d = _knot_route(name)
    s = ax.surface_stress(x, y, A, c, NU, MU, prof, method="quadrature", rtol=rtol)
    d = ax.surface_dpdz(x, y, A, c, NU, MU, prof, method="quadrature", rtol=rtol)
    for k, v in list(s.items()) + [("dpdz", d)]:
        ref = ref_d if k == "dpdz" else ref_s[k]
        S = pm / A if k == "dpdz" else pm
        fin = np.isfinite(ref)
        np.testing.assert_array_equal(np.isfinite(v), fin)          # same infinities and NaNs
        np.testing.assert_array_equal(v[~fin], ref[~fin])
        err = np.abs(v[fin] - ref[fin])
        assert np.all(err <= rtol * np.maximum(np.abs(ref[fin]), S)), (k, np.max(err / np.maximum(np.abs(ref[fin]), S)))


def _cost(name, monkeypatch):
    """Table lookups and block nodes per point for the stresses and dp/dz at rtol 1e-10."""
    prof, c, _ = _case(name)
    rng = np.random.default_rng(3)
    rad, ang = 1.5 * np.sqrt(rng.random(400)), 2.0 * math.pi * rng.random(400)
    x, y = rad * np.cos(ang), rad * np.sin(ang)
    counts = {"lookups": 0, "nodes": 0}
    cls = type(prof)
    dg, d2g = cls.dg, cls.d2g

    def counted(fn):
        def wrapper(self, u):
            counts["lookups"] += np.size(u)
            return fn(self, u)
        return wrapper

    sums = I._Tree.sums

    def counted_sums(self, pt, flat, level, r, P, terms):
        counts["nodes"] += pt.size * self.xi.size
        return sums(self, pt, flat, level, r, P, terms)

    I._tree(prof, I._block_order(orders(1e-10)))              # built once per profile, not counted
    monkeypatch.setattr(cls, "dg", counted(dg))
    monkeypatch.setattr(cls, "d2g", counted(d2g))
    monkeypatch.setattr(I._Tree, "sums", counted_sums)
    ax.surface_stress(x, y, A, c, NU, MU, prof, method="quadrature", rtol=1e-10)
    ax.surface_dpdz(x, y, A, c, NU, MU, prof, method="quadrature", rtol=1e-10)
    monkeypatch.undo()
    return counts["lookups"] / x.size, counts["nodes"] / x.size, I._tree(prof, I._block_order(orders(1e-10))).L


def test_cost_does_not_grow_with_the_sample_count(monkeypatch):
    """The knot-resolving rules took 502, 3715 and 18516 lookups per point at 25, 200 and 1000
    samples; the block route's lookups stay about constant and its block nodes grow with the
    tree's depth, log2 of the sample count (measured: 154, 113, 139 lookups and 264, 468, 632
    nodes, depth 6, 9, 11)."""
    cost = {n: _cost(f"hyperboloid_{n}", monkeypatch) for n in (25, 200, 1000)}
    lookups = {n: v[0] for n, v in cost.items()}
    assert max(lookups.values()) < 200, cost
    assert lookups[1000] < 1.2 * lookups[25], cost
    assert all(nodes < 70 * depth for _, nodes, depth in cost.values()), cost


def test_pairs_per_pass_do_not_change_the_values(monkeypatch):
    """``_Tree.sums`` takes the (point, block) pairs _PAIRS at a time: 7 pairs per pass (the last
    pass short, many passes per point) give the one-pass values to rounding."""
    prof, c, pm = _case("measured_like")
    x, y = _points(c)
    one = ax.surface_stress(x, y, A, c, NU, MU, prof, method="quadrature", rtol=1e-10)
    d_one = ax.surface_dpdz(x, y, A, c, NU, MU, prof, method="quadrature", rtol=1e-10)
    monkeypatch.setattr(I, "_PAIRS", 7)
    many = ax.surface_stress(x, y, A, c, NU, MU, prof, method="quadrature", rtol=1e-10)
    d_many = ax.surface_dpdz(x, y, A, c, NU, MU, prof, method="quadrature", rtol=1e-10)
    for v, w, S in [(one[k], many[k], pm) for k in one] + [(d_one, d_many, pm / A)]:
        np.testing.assert_array_equal(np.isfinite(v), np.isfinite(w))
        fin = np.isfinite(v)
        np.testing.assert_allclose(w[fin], v[fin], rtol=0, atol=1e-14 * S)
