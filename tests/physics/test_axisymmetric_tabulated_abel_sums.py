"""The tabulated profile's g, g', g'' (exact Abel sums, docs/theory/axisymmetric.md (A9), and the
piecewise-polynomial table the quadrature reads g' and g'' from) against routes that share nothing
with them:

* adaptive scipy quad of the defining integral (A2) after r = x sin(phi), which removes the
  end-point root: g(x) = x int_0^(pi/2) f'(x s) dphi, differentiated under the integral for g' and
  g'', with f the scipy CubicSpline of the samples, split where x s crosses a knot;
* closed forms where the not-a-knot spline reproduces the samples' function exactly (a sampled
  paraboloid, cone and cubic f = A r^3): (A5)-(A7);
* the cost of a table build does not grow with the square of the sample count any more than the
  sums themselves: the build visits only the pieces below each point (checked by counting).
"""
import math
import warnings

import numpy as np
import pytest
from scipy.integrate import IntegrationWarning, quad
from scipy.interpolate import CubicSpline

from stressfields.physics import axisymmetric as ax

QUAD = dict(limit=400, epsabs=0.0, epsrel=2e-14)
REL = 1e-12


def _shapes():
    rng = np.random.default_rng(7)
    rh = np.linspace(0.0, 1.2, 25)
    # measured-like: irregular spacing, noisy but monotone heights on a blunt tip
    rm = np.concatenate([[0.0], np.sort(rng.uniform(0.02, 1.5, 38)), [1.6]])
    fm = 0.3 * rm ** 2 + 0.05 * rm + 1e-3 * np.cumsum(rng.random(rm.size))
    rp = np.linspace(0.0, 2.0, 30)
    return {"hyperboloid": (rh, np.sqrt(rh ** 2 + 0.04) - 0.2),
            "measured_like": (rm, fm),
            "paraboloid_sampled": (rp, rp ** 2 / (2.0 * 0.8))}


SHAPES = _shapes()


def _reference(r, f, x):
    """(g, g', g'') at x by quad of (A2) in phi, split at the knot angles."""
    sp = CubicSpline(r, f - f[0])
    # a slope at the axis below 1e-10 of the largest is rounding and set to 0 on the first piece (the
    # documented rule of ``Tabulated``; a sampled paraboloid's spline has f'(0) ~ 1e-17)
    tip = float(sp(0.0, 1)) if abs(sp(0.0, 1)) <= 1e-10 * np.max(np.abs(sp(r, 1))) else 0.0

    def d1(u):
        return sp(u, 1) - (tip if u < r[1] else 0.0)

    integrands = (lambda t: x * d1(x * math.sin(t)),
                  lambda t: d1(x * math.sin(t)) + x * math.sin(t) * sp(x * math.sin(t), 2),
                  lambda t: 2.0 * math.sin(t) * sp(x * math.sin(t), 2) + x * math.sin(t) ** 2 * sp(x * math.sin(t), 3))
    # the knot angles as atan2(k, sqrt((x - k)(x + k))): asin(k/x) is off by 1e-16/sqrt(1 - (k/x)^2),
    # 2.5e-12 for x = k (1 + 1e-9), which moves the jump of f''' and costs the reference 1e-8
    edges = [0.0] + [math.atan2(k, math.sqrt((x - k) * (x + k))) for k in r if 0.0 < k < x] + [0.5 * math.pi]
    out = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)
        for fn in integrands:
            out.append(sum(quad(lambda t: float(fn(t)), p, q, **QUAD)[0] for p, q in zip(edges[:-1], edges[1:])))
    return out


def _points(r):
    knots = r[1:-1]
    return np.concatenate([[1e-6, 1e-3], np.linspace(0.01, r[-1], 23), knots, knots * (1 + 1e-9),
                           knots * (1 - 1e-9), [r[-1]]])


@pytest.mark.parametrize("name", list(SHAPES))
def test_g_dg_d2g_against_quadrature_of_a2(name):
    r, f = SHAPES[name]
    prof = ax.tabulated(r, f)
    x = _points(r)
    ref = np.array([_reference(r, f, xi) for xi in x]).T
    # g'' is held to 1e-12 of max(|g''|, its largest value over the table): where it passes through
    # zero (the hyperboloid's cone flank) or where the pieces' terms are 1e3 x larger than their sum
    # (the noisy table, |g''| up to 4552 and down to 0.7) a relative figure measures the conditioning
    s2 = np.max(np.abs(ref[2]))
    floors = (0.0, 0.0, s2, 0.0, s2)
    got = (prof.g(x), prof.dg(x), prof.d2g(x), prof._sums(x, 1), prof._sums(x, 2))
    for k, (value, want) in enumerate(zip(got, (ref[0], ref[1], ref[2], ref[1], ref[2]))):
        err = np.abs(value - want) / np.maximum(np.abs(want), floors[k])
        assert err.max() <= REL, (name, k, x[np.argmax(err)], err.max())


@pytest.mark.parametrize("case", ["paraboloid", "cone", "cubic"])
def test_closed_forms_where_the_spline_is_exact(case):
    """A sampled paraboloid, cone or cubic is its own not-a-knot spline up to the rounding of the
    samples, which the spline solve amplifies (the third derivative by ~eps max|f| / h^3: 2e-12
    for 40 samples).  By (A2) differentiated under the integral, |dg| <= (pi/2) x max|df1|,
    |dg'| <= (pi/2)(max|df1| + x max|df2|), |dg''| <= (pi/2)(2 max|df2| + x max|df3|), where dfk
    is the scipy spline's k-th derivative minus the exact one: the closed forms (A5)-(A7) must hold
    to that bound plus 1e-12 relative."""
    r = np.linspace(0.0, 1.5, 40)
    A, R, kappa = 0.7, 1.3, 0.75 * math.pi         # kappa_3 = sqrt(pi) Gamma(5/2) / Gamma(2), (A7)
    exact = {"paraboloid": [lambda t: t ** 2 / (2 * R), lambda t: t / R, lambda t: 1 / R + 0 * t, lambda t: 0 * t],
             "cone": [lambda t: A * t, lambda t: A + 0 * t, lambda t: 0 * t, lambda t: 0 * t],
             "cubic": [lambda t: A * t ** 3, lambda t: 3 * A * t ** 2, lambda t: 6 * A * t,
                       lambda t: 6 * A + 0 * t]}[case]
    closed = {"paraboloid": (lambda x: x ** 2 / R, lambda x: 2 * x / R, lambda x: 2 / R + 0 * x),
              "cone": (lambda x: 0.5 * math.pi * A * x, lambda x: 0.5 * math.pi * A + 0 * x, lambda x: 0 * x),
              "cubic": (lambda x: kappa * A * x ** 3, lambda x: 3 * kappa * A * x ** 2,
                        lambda x: 6 * kappa * A * x)}[case]
    f = exact[0](r)
    sp = CubicSpline(r, f - f[0])
    fine = np.concatenate([r, np.linspace(0.0, r[-1], 4001), 0.5 * (r[1:] + r[:-1])])
    dev = [np.max(np.abs(sp(fine, k) - exact[k](fine))) for k in (1, 2, 3)]
    prof = ax.tabulated(r, f)
    x = _points(r)
    bounds = (0.5 * math.pi * x * dev[0], 0.5 * math.pi * (dev[0] + x * dev[1]),
              0.5 * math.pi * (2 * dev[1] + x * dev[2]))
    got = (prof.g(x), prof.dg(x), prof.d2g(x))
    for k in range(3):
        want = closed[k](x)
        excess = np.abs(got[k] - want) - bounds[k] - REL * np.abs(want)
        assert excess.max() <= 0.0, (case, k, x[np.argmax(excess)], excess.max())
    # depth and load: (A3) and (A10) against (A5)-(A7)
    a = np.array([0.3, 0.77, 1.5])
    force = {"paraboloid": 4 * a ** 3 / (3 * R), "cone": 0.5 * math.pi * A * a ** 2,
             "cubic": 2 * kappa * A * 3 * a ** 4 / 4}[case]
    np.testing.assert_allclose(prof.depth(a), closed[0](a), rtol=REL, atol=0)
    np.testing.assert_allclose(prof.normal_force(a), force, rtol=REL, atol=0)


def test_sums_visit_only_the_pieces_below_each_point(monkeypatch):
    """The sums over pieces skip the pieces above the largest point of a chunk (they contribute
    nothing): points near the axis of a 400-piece table touch a few pieces, not all of them, and the
    values are unchanged."""
    from stressfields.physics.axisymmetric import profiles

    r = np.linspace(0.0, 1.0, 401)
    prof = ax.tabulated(r, r ** 2 + 0.1 * r)
    seen = []
    real = profiles._piece_moments
    monkeypatch.setattr(profiles, "_piece_moments", lambda x, k: seen.append(k.shape[1] - 1) or real(x, k))
    x = np.array([0.004, 0.0101, 0.5])
    want = [_reference(r, r ** 2 + 0.1 * r, xi)[1] for xi in x]
    small = prof._sums(x[:2], 1)
    assert seen == [5]                       # the pieces starting at 0, 0.0025, ..., 0.01 < 0.0101
    np.testing.assert_allclose(np.concatenate([small, prof._sums(x[2:], 1)]), want, rtol=REL, atol=0)


@pytest.mark.parametrize("name", list(SHAPES))
def test_load_against_quadrature_of_a10(name):
    """F_N/E* = 2 int_0^a r^2 f'(r) dr / sqrt(a^2 - r^2) (A10) by quad after r = a sin(phi), split
    at the knot angles; the depth g(a) (A3) with it."""
    r, f = SHAPES[name]
    sp = CubicSpline(r, f - f[0])
    prof = ax.tabulated(r, f)
    a = np.concatenate([[1e-3, 0.05], 0.5 * (r[1:] + r[:-1])[::3], r[2:-1:4] * (1 + 1e-9), [r[-1]]])
    ref = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)
        for av in a:
            edges = [0.0] + [math.atan2(k, math.sqrt((av - k) * (av + k))) for k in r if 0.0 < k < av] + [0.5 * math.pi]
            ref.append(sum(quad(lambda t: 2 * av * av * math.sin(t) ** 2 * float(sp(av * math.sin(t), 1)), p, q,
                                **QUAD)[0] for p, q in zip(edges[:-1], edges[1:])))
    err = np.abs(prof.normal_force(a) - ref) / np.abs(ref)
    assert err.max() <= REL, (name, a[np.argmax(err)], err.max())
    depth = np.array([_reference(r, f, av)[0] for av in a])
    err = np.abs(prof.depth(a) - depth) / np.abs(depth)
    assert err.max() <= REL, (name, a[np.argmax(err)], err.max())
