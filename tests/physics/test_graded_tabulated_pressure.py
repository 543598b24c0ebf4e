"""Tabulated (cubic-spline) profiles on the graded half-space: the pressure (G17) on the fast route.

The near part [r, X] takes g' from the panel interpolant (G51) of the cached knot-panel values; the
far part the panel nodes themselves. Held against scipy quad of the defining integral (G17) with the
exact g' (G14) for a hyperboloid at 25 and 200 samples, at r/a from the centre to 1 - 1e-9, k from
1e-6 to 0.9 and rtol = 1e-6 ... 1e-12. The work is counted in g' evaluations: fixed per (a, k),
independent of the number of points, linear in the knots. (The power-law closed forms, with 41 and
401 knots: tests/physics/test_graded_tabulated_block_tree.py.)
"""

import numpy as np
import pytest
from scipy.integrate import quad

from stressfields.physics.graded import normal as N
from stressfields.physics.graded.material import c_N_star

from test_graded_tabulated_block_tree import A, KS, MAT, RTOLS, hyperboloid, rel

# reference quadratures of the defining integral take ~15 s of set-up: run by .ci/run with the
# other slow tests, not by the Quick start
pytestmark = pytest.mark.slow

RHO = np.array([0.0, 1e-9, 0.05, 0.5, 0.99, 1.0 - 1e-9])


def _dg(prof, k):
    return lambda x: prof.dg(np.array([x]), k)[0]


def _pressure_defining(rho, a, prof, k, knots):
    """(G17)/c_N* by quadpack with the exact g', in units of a (x = a xi, so that the edge distance
    1 - rho is exact): (a^k/pi) int_rho^1 g'(a xi) (xi^2 - rho^2)^(-(1-k)/2) dxi.  The end-point
    factor by the algebraic-weight rule in s = xi - rho up to the next knot ((s)^(-(1-k)/2), or
    xi^(k-1) at the centre), split at the knots beyond."""
    q = 0.5 * (1 - k)
    above = [x / a for x in knots if rho * a < x < a]
    x1 = above[0] if above else 1.0
    width = 1.0 - rho if x1 == 1.0 else x1 - rho          # 1 - rho exact (Sterbenz)
    if rho == 0.0:
        head = quad(lambda s: _dg(prof, k)(a * s), 0.0, width, weight="alg", wvar=(k - 1, 0),
                    epsabs=0, epsrel=1e-13)[0]
    else:
        head = quad(lambda s: _dg(prof, k)(a * (rho + s)) * (2 * rho + s) ** -q, 0.0, width, weight="alg",
                    wvar=(-q, 0), epsabs=0, epsrel=1e-13)[0]
    tail = quad(lambda x: _dg(prof, k)(a * x) * (x * x - rho * rho) ** -q, x1, 1.0, points=above[1:],
                epsabs=0, epsrel=1e-13, limit=800)[0] if x1 < 1.0 else 0.0
    return a ** k * (head + tail) / np.pi


@pytest.fixture(scope="module")
def references():
    """quadpack of (G17) per (samples, k) at r/a = RHO (a between knots)."""
    out = {}
    for n in (25, 200):
        prof, knots = hyperboloid(n)
        a = 0.83 * A
        for k in KS:
            out[n, k] = np.array([_pressure_defining(x, a, prof, k, knots) for x in RHO]) \
                * c_N_star(k, **MAT)
    return out


@pytest.mark.parametrize("rtol", RTOLS)
@pytest.mark.parametrize("k", KS)
@pytest.mark.parametrize("n", [25, 200])
def test_pressure_against_quadrature_of_the_defining_integral(n, k, rtol, references):
    prof, _ = hyperboloid(n)
    p = N.pressure_quad(None, 0.83 * A, prof, rtol=rtol, rho=RHO, k=k, **MAT)
    assert rel(p, references[n, k]) <= max(rtol, 2e-12)


def _counting(prof):
    """Count the nodes at which the exact g' (G14) is formed, on every route."""
    exact = prof.dg
    count = [0]

    def dg(x, k):
        count[0] += np.size(x)
        return exact(x, k)

    prof.dg = dg
    return count


def test_work_is_per_contact_radius_and_linear_in_the_knots():
    """Every g' evaluation belongs to the shared panel nodes: the count does not depend on the
    number of points, and grows like the knots (at most 62 nodes per panel: orders 2 ... 32),
    not like knots^2 (formerly each point's near part formed g' at its own adaptive nodes)."""
    counts = {}
    for n in (50, 200):
        for points in (5, 400):
            prof, _ = hyperboloid(n)
            count = _counting(prof)
            N.pressure_quad(None, 0.83 * A, prof, rtol=1e-10, rho=np.linspace(0.0, 0.999, points), k=0.5, **MAT)
            counts[n, points] = count[0]
    for n in (50, 200):
        assert counts[n, 5] == counts[n, 400]
        assert counts[n, 400] <= 62 * (n + 40)
    assert counts[200, 400] < 4.5 * counts[50, 400]
