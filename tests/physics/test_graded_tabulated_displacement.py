"""Tabulated (cubic-spline) profiles on the graded half-space: the surface displacement u_z.

Inside the contact u_z = d - f(r) (docs/theory/graded.md (G20)); outside the positive integral
(G49) on shared knot-panel nodes.  Held against the closed forms of a sampled paraboloid plus
cubic (reproduced exactly by the spline), against scipy quad of the defining integral (G20) for a
hyperboloid-like profile, at a near-homogeneous k = 1e-6 against the k = 0 closed form, and at
rtol = 1e-6 ... 1e-12; the work (nodes at which g' is formed) falls as rtol loosens.
"""

import numpy as np
import pytest
from scipy.integrate import quad

from stressfields.physics.graded import normal as N
from stressfields.physics.graded import profiles as P

A = 0.6
RTOLS = (1e-6, 1e-8, 1e-10, 1e-12)


def rel(x, ref):
    x, ref = np.asarray(x, float), np.asarray(ref, float)
    return np.max(np.abs(x / ref - 1))


def cubic_table(n=41):
    rt = np.linspace(0.0, 1.0, n)
    return P.Tabulated(rt, rt ** 2 / (2 * 1.7) + 0.9 * rt ** 3), [(2.0, 1 / (2 * 1.7)), (3.0, 0.9)]


def hyperboloid(n=25):
    rs = np.linspace(0.0, 1.2, n)
    return P.Tabulated(rs * A, (np.sqrt(rs ** 2 + 0.04) - 0.2) * A), rs * A


RHO = np.array([0.0, 0.3, 0.999, 1.0, 1.0 + 1e-12, 1.0 + 1e-6, 1.1, 2.0, 5.0, 100.0])


@pytest.mark.parametrize("rtol", RTOLS)
@pytest.mark.parametrize("k", [1e-6, 0.5, 0.9])
def test_uz_against_power_law_closed_forms(k, rtol):
    tab, parts = cubic_table()
    u = N.surface_displacement_quad(None, A, tab, k=k, rtol=rtol, rho=RHO)
    ref = sum(N.surface_displacement(None, A, k=k, n=n, A_n=An, rho=RHO) for n, An in parts)
    # the contract: |error| <= rtol |value| (closed forms good to 1e-12 themselves)
    assert rel(u, ref) <= max(rtol, 2e-12)


def test_uz_near_homogeneous_against_k0_closed_form():
    """k = 1e-6: the graded kernels tend to the homogeneous (k = 0) ones; the k = 0 closed form
    (Love's paraboloid + cubic superposition) differs from k = 1e-6 by O(k) only."""
    tab, parts = cubic_table()
    u6 = N.surface_displacement_quad(None, A, tab, k=1e-6, rtol=1e-12, rho=RHO)
    u0 = sum(N.surface_displacement(None, A, k=0.0, n=n, A_n=An, rho=RHO) for n, An in parts)
    assert rel(u6, u0) < 1e-5


def _uz_defining(r, a, prof, k, knots):
    """(G20) by scipy quad, split at the knots: (2/pi) cos(k pi/2) int_0^a x^k (d - g) (r^2-x^2)^-(1+k)/2."""
    d = prof.g(a, k)
    pts = [x for x in knots if 0 < x < a]

    def fn(x):
        return x ** k * (d - prof.g(x, k)) * (r * r - x * x) ** (-(1 + k) / 2)

    return 2 / np.pi * np.cos(k * np.pi / 2) * quad(fn, 0, a, points=pts, epsabs=0, epsrel=1e-13, limit=800)[0]


@pytest.mark.slow          # quadpack references, ~5 s in all: CI runs them with the slow tests
@pytest.mark.parametrize("rtol", RTOLS)
@pytest.mark.parametrize("k", [1e-6, 0.5])
def test_uz_against_quadrature_of_the_defining_integral(k, rtol):
    prof, knots = hyperboloid()
    a = 0.83 * A                          # between knots
    r = np.array([1.05, 1.3, 2.0, 7.0]) * a
    ref = [_uz_defining(x, a, prof, k, knots) for x in r]
    assert rel(N.surface_displacement_quad(r, a, prof, k=k, rtol=rtol), ref) <= rtol
    inner = np.array([0.0, 0.2, 0.7]) * a   # inside: d - f(r), the inverse transform (G12) of u_1D
    d = prof.g(a, k)

    def inverse(r):       # (G12) of u_1D by scipy's algebraic-weight rule (r - x)^(-(1+k)/2)
        def fn(x):
            return x ** k * (d - prof.g(x, k)) * (r + x) ** (-(1 + k) / 2)
        return 2 / np.pi * np.cos(k * np.pi / 2) * quad(fn, 0, r, weight="alg", wvar=(0, -(1 + k) / 2),
                                                         epsabs=0, epsrel=1e-12, limit=800)[0]

    inv = [d] + [inverse(x) for x in inner[1:]]
    # (scipy's rule meets the spline's kinks: its own accuracy is ~1e-9 here)
    assert rel(N.surface_displacement_quad(inner, a, prof, k=k, rtol=rtol), inv) < 1e-8


def test_uz_continuous_at_the_edge():
    prof, _ = hyperboloid()
    u = N.surface_displacement_quad(None, A, prof, k=0.5, rtol=1e-12, rho=np.array([1.0, 1.0 + 1e-15]))
    assert abs(u[1] / u[0] - 1) < 1e-12


def test_work_falls_as_rtol_loosens():
    counts = []
    for rtol in RTOLS:
        prof, _ = hyperboloid()
        N.surface_displacement_quad(None, A, prof, k=0.5, rtol=rtol, rho=np.array([1.2, 3.0]))
        counts.append(prof.evaluations)
    assert counts == sorted(counts) and counts[0] < counts[-1]


def test_cached_nodes_are_reused_across_rows():
    prof, _ = hyperboloid()
    N.surface_displacement_quad(None, A, prof, k=0.5, rtol=1e-10, rho=np.array([1.2]))
    first = prof.evaluations
    N.surface_displacement_quad(None, A, prof, k=0.5, rtol=1e-10, rho=np.linspace(1.01, 9.0, 500))
    assert prof.evaluations == first


# ----------------------------------------------------------------- pressure at the centre, k -> 0

MAT = dict(nu=0.3, E0=2.5, c0=0.8)


def clamped_cubic():
    """Paraboloid + cubic with f'(0) = 0 clamped: at k = 1e-6 the centre pressure carries
    g'(0)/k, so the not-a-knot spline's rounding-level tip slope (~1e-17) would count 1e6 times."""
    rt = np.linspace(0.0, 1.0, 9)
    return P.Tabulated(rt, rt ** 2 / (2 * 1.7) + 0.9 * rt ** 3, slope_at_0=0.0), [(2.0, 1 / (2 * 1.7)), (3.0, 0.9)]


@pytest.mark.parametrize("rtol", RTOLS)
@pytest.mark.parametrize("k", [1e-6, 1e-3, 0.5, 0.95])
def test_pressure_against_power_law_closed_forms(k, rtol):
    tab, parts = clamped_cubic()
    rho = np.array([0.0, 1e-9, 0.3, 0.999, 1.0 - 1e-12])
    m = dict(MAT, k=k)
    p = N.pressure_quad(None, A, tab, rtol=rtol, rho=rho, **m)
    ref = sum(N.pressure(None, A, n=n, A_n=An, rho=rho, **m) for n, An in parts)
    assert rel(p, ref) <= max(rtol, 2e-12)


def test_centre_pressure_near_homogeneous_probe():
    """k = 1e-6, r = 0, rtol = 1e-12: against the closed forms, and the k = 0 closed form limit."""
    tab, parts = clamped_cubic()
    m = dict(MAT, k=1e-6)
    p = N.pressure_quad(0.0, A, tab, rtol=1e-12, **m)
    assert rel(p, sum(N.pressure(0.0, A, n=n, A_n=An, **m) for n, An in parts)) <= 1e-12
    p0 = sum(N.pressure(0.0, A, n=n, A_n=An, **dict(MAT, k=0.0)) for n, An in parts)
    assert rel(p, p0) < 1e-5                     # O(k) from the homogeneous value


def test_centre_pressure_against_scipy_quad_of_the_defining_integral():
    """(G17) at r = 0: (c_N*/pi) int_0^a g'(x) x^(k-1) dx, scipy's algebraic-weight rule on the first
    piece (x^(k-1) exactly), quadpack beyond.  The tip is clamped smooth: a not-a-knot spline
    through this hyperboloid keeps a tip slope of order 1e-4, whose g'(0)/k term (a tensile cone
    tip, p(0) = -7e3 at k = 1e-6) is exact on both routes but leaves quadpack's x^(k-1) rule at 3e-11."""
    from stressfields.physics.graded.material import c_N_star
    _, knots = hyperboloid()
    prof = P.Tabulated(knots, np.sqrt(knots ** 2 + 0.04 * A * A) - 0.2 * A, slope_at_0=0.0)
    a = 0.83 * A
    for k in (1e-6, 0.3):
        x1 = knots[1]
        head = quad(lambda x: prof.dg(np.array([x]), k)[0], 0, x1, weight="alg", wvar=(k - 1, 0),
                    epsabs=0, epsrel=1e-13)[0]
        tail = quad(lambda x: prof.dg(np.array([x]), k)[0] * x ** (k - 1), x1, a,
                    points=[x for x in knots if x1 < x < a], epsabs=0, epsrel=1e-13, limit=400)[0]
        ref = c_N_star(k, MAT["nu"], MAT["E0"], MAT["c0"]) / np.pi * (head + tail)
        assert rel(N.pressure_quad(0.0, a, prof, rtol=1e-12, k=k, **MAT), ref) < 1e-11


def test_cone_centre_pressure_near_homogeneous():
    """f = A r (g'(0) != 0): p(0) ~ 1/k; the closed form's n + k - 1 is formed as (n - 1) + k."""
    m = dict(MAT, k=1e-6)
    p = N.pressure_quad(0.0, A, P.PowerLaw(A=0.8, n=1.0), rtol=1e-12, **m)
    assert rel(p, N.pressure(0.0, A, n=1.0, A_n=0.8, **m)) <= 1e-12


def _pressure_defining(r, a, prof, k, knots):
    """(G17)/c_N* by quadpack: (1/pi) int_r^a g'(x) (x^2 - r^2)^(-(1-k)/2) dx, the end-point factor
    (x - r)^(-(1-k)/2) by the algebraic-weight rule up to the next knot, split at the knots beyond."""
    q = 0.5 * (1 - k)
    above = [x for x in knots if r < x < a]
    x1 = above[0] if above else a
    head = quad(lambda x: prof.dg(np.array([x]), k)[0] * (x + r) ** -q, r, x1, weight="alg", wvar=(-q, 0),
                epsabs=0, epsrel=1e-13)[0]
    tail = quad(lambda x: prof.dg(np.array([x]), k)[0] * (x * x - r * r) ** -q, x1, a, points=above[1:],
                epsabs=0, epsrel=1e-13, limit=400)[0] if x1 < a else 0.0
    return (head + tail) / np.pi


@pytest.mark.slow          # quadpack references: CI runs them with the slow tests
@pytest.mark.parametrize("rtol", RTOLS)
@pytest.mark.parametrize("k", [1e-6, 0.5, 0.9])
def test_pressure_against_quadrature_of_the_defining_integral(k, rtol):
    """Near part (adaptive, exact g') and far part (shared panel nodes) against quadpack of (G17)."""
    from stressfields.physics.graded.material import c_N_star
    prof, knots = hyperboloid()
    a = 0.83 * A
    r = np.array([0.05, 0.3, 0.71, 0.99]) * a
    ref = np.array([_pressure_defining(x, a, prof, k, knots) for x in r]) * c_N_star(k, **MAT)
    assert rel(N.pressure_quad(r, a, prof, rtol=rtol, k=k, **MAT), ref) <= rtol


def test_pressure_work_falls_as_rtol_loosens():
    counts = []
    for rtol in RTOLS:
        prof, _ = hyperboloid()
        N.pressure_quad(np.array([0.1, 0.5]) * A, A, prof, rtol=rtol, k=0.5, **MAT)
        counts.append(prof.evaluations)
    assert counts == sorted(counts) and counts[0] < counts[-1]
