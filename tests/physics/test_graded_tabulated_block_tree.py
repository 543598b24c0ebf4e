"""Tabulated (cubic-spline) profiles on the graded half-space: the block-tree route (G52)-(G55).

g' of the table nodes by the block tree of h = d(r f')/dr (far pieces by Chebyshev moments, near
pieces by the exact beta sums); the pressure (G17) and u_z (G49) by the block tree of the table
(far) plus the adaptive near part; the orders chosen once from rtol.  Held against the exact beta
sums (G14) at random nodes, the power-law closed forms of a sampled paraboloid plus cubic (reproduced
exactly by the spline), and quadpack of (G17)/(G49) with the exact g' for a hyperboloid at 25, 200
and 1000 samples, k from 1e-6 to 0.9, rtol 1e-6 ... 1e-12.  The work is counted in kernel terms.
"""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import betainc, roots_legendre

from stressfields.physics.graded import normal as N
from stressfields.physics.graded import profiles as P
from stressfields.physics.graded.material import c_N_star

# reference quadratures of the defining integrals take ~25 s of set-up: run by .ci/run with the
# other slow tests, not by the Quick start
pytestmark = pytest.mark.slow

A = 0.6
MAT = dict(nu=0.3, E0=2.0e9, c0=1.0e-3)
RTOLS = (1e-6, 1e-8, 1e-10, 1e-12)
KS = (1e-6, 0.3, 0.5, 0.9)
RHO_P = np.array([0.0, 1e-9, 0.05, 0.3, 0.5, 0.77, 0.95, 0.999, 1.0 - 1e-9])
RHO_U = np.array([1.0 + 1e-9, 1.0 + 1e-6, 1.001, 1.05, 1.3, 2.0, 3.0])
SAMPLES = (25, 200, 1000)


def rel(x, ref):
    x, ref = np.asarray(x, float), np.asarray(ref, float)
    return np.max(np.abs(x / ref - 1))


def hyperboloid(n):
    """sqrt(r^2 + 0.04) - 0.2 (in units of A) sampled at n radii on [0, 1.2 A], smooth tip."""
    knots = np.linspace(0.0, 1.2, n) * A
    return P.Tabulated(knots, np.sqrt(knots ** 2 + 0.04 * A * A) - 0.2 * A, slope_at_0=0.0), knots


def cubic_table(n=401):
    """f = r^2/(2 1.7) + 0.9 r^3 on [0, A]: clamped f'(0) = 0 and not-a-knot keep it exact."""
    rt = np.linspace(0.0, A, n)
    return P.Tabulated(rt, rt ** 2 / (2 * 1.7) + 0.9 * rt ** 3, slope_at_0=0.0), [(2.0, 1 / (2 * 1.7)), (3.0, 0.9)]


# ------------------------------------------------------------------------------ g' of the nodes

@pytest.mark.parametrize("k", KS)
@pytest.mark.parametrize("n", SAMPLES)
def test_fast_dg_against_exact_beta_sums(n, k):
    prof, knots = hyperboloid(n)
    rng = np.random.default_rng(7)
    x = np.concatenate([rng.uniform(0.0, knots[-1], 300), knots[1:6], knots[1:6] * (1 + 1e-12),
                        knots[-3:], [1e-9 * A]])
    exact = prof._beta_sum(x, k, (1.0, 2.0, 3.0)) / x          # (G14) summed over every piece
    assert rel(prof.dg_fast(x, k), exact) <= 1e-13
    assert prof.dg_fast(np.array([0.0]), k)[0] == prof.dg(np.array([0.0]), k)[0]


def test_setup_work_grows_like_knots_log_knots():
    """Work of the g' table (G54) per (a, k, order), counted in terms: the exact sums of (G14) at
    every node take nodes x pieces incomplete-beta terms (~knots^2); the tree takes a bounded number
    of exact piece terms per node and O(log knots) kernel values of far blocks per node."""
    exact, blocks, nodes = {}, {}, {}
    for n in (250, 1000):
        prof, _ = hyperboloid(n)
        t, _, _ = prof.dg_panels(0.83 * A, 0.5, 16)
        exact[n], blocks[n], nodes[n] = prof.exact_terms, prof.block_terms, t.size
    for n in (250, 1000):
        assert exact[n] <= 4 * nodes[n]                    # pieces within 1.5 widths of the node
    pieces = 0.83 / 1.2 * 1000
    assert exact[1000] < 0.01 * nodes[1000] * pieces
    # per node: 250 -> 1000 knots adds two tree levels (a few blocks of p = 24 values each)
    assert blocks[1000] / nodes[1000] - blocks[250] / nodes[250] < 4 * 2 * 24
    assert blocks[1000] / nodes[1000] < 0.6 * pieces


def test_setup_cost_falls_as_rtol_loosens():
    counts = []
    for rtol in (1e-12, 1e-10, 1e-6):
        prof, _ = hyperboloid(1000)
        N.pressure_quad(None, 0.83 * A, prof, rtol=rtol, rho=np.array([0.5]), k=0.5, **MAT)
        N.surface_displacement_quad(None, 0.83 * A, prof, k=0.5, rtol=rtol, rho=np.array([1.5]))
        counts.append((prof.evaluations, prof.exact_terms + prof.block_terms))
    assert counts[0][0] > counts[1][0] > counts[2][0]
    assert counts[0][1] > counts[1][1] > counts[2][1]


def test_tables_are_reused_across_rows():
    prof, _ = hyperboloid(200)
    kw = dict(rtol=1e-10, k=0.5)
    N.pressure_quad(None, 0.83 * A, prof, rho=RHO_P[:2], **kw, **MAT)
    N.surface_displacement_quad(None, 0.83 * A, prof, rho=RHO_U[:1], **kw)
    first = (prof.evaluations, prof.exact_terms + prof.block_terms)
    N.pressure_quad(None, 0.83 * A, prof, rho=np.linspace(0.0, 0.999, 300), **kw, **MAT)
    N.surface_displacement_quad(None, 0.83 * A, prof, rho=np.linspace(1.001, 3.0, 300), **kw)
    assert (prof.evaluations, prof.exact_terms + prof.block_terms) == first


# ---------------------------------------------------------------------- power-law closed forms

@pytest.mark.parametrize("knots", [41, 401])
@pytest.mark.parametrize("rtol", RTOLS)
@pytest.mark.parametrize("k", KS)
def test_against_power_law_closed_forms(k, rtol, knots):
    tab, parts = cubic_table(knots)
    m = dict(MAT, k=k)
    p = N.pressure_quad(None, A, tab, rtol=rtol, rho=RHO_P, **m)
    ref = sum(N.pressure(None, A, n=n, A_n=An, rho=RHO_P, **m) for n, An in parts)
    # the contract: |error| <= rtol |value| (the closed forms are good to 1e-12 themselves)
    assert rel(p, ref) <= max(rtol, 2e-12)
    u = N.surface_displacement_quad(None, A, tab, k=k, rtol=rtol, rho=RHO_U)
    ref = sum(N.surface_displacement(None, A, k=k, n=n, A_n=An, rho=RHO_U) for n, An in parts)
    assert rel(u, ref) <= max(rtol, 2e-12)


# ------------------------------------------------------------- quadpack of the defining integrals

_GX, _GW = roots_legendre(24)
_GX, _GW = 0.5 * (_GX + 1.0), 0.5 * _GW


def _graded_rule(lo, hi):
    """Gauss-Legendre in s with x = lo + L s^2 on each piece (smooths the knot terms (x - lo)^((3+k)/2))."""
    L = (hi - lo)[:, None]
    return (lo[:, None] + L * _GX ** 2).ravel(), (L * 2.0 * _GX * _GW).ravel()


class Reference:
    """(G17)/c_N* and (G49) in units of a (x = a xi): quadpack with the exact g' (G14) on the pieces
    next to the kernel's singular point, a graded 24-point Gauss rule with the exact g' on the pieces
    at least one piece width away (there the kernel is analytic on a disc of the piece's size)."""

    def __init__(self, n, k, a):
        self.prof, knots = hyperboloid(n)
        self.k, self.a = k, a
        self.edges = np.append(0.0, np.append(knots[(knots > 0) & (knots < a)], a) / a)
        self.edges[-1] = 1.0
        self.xi, self.w = _graded_rule(self.edges[:-1], self.edges[1:])
        self.piece = np.repeat(np.arange(self.edges.size - 1), _GX.size)
        self.dg_nodes = np.concatenate([self.prof.dg(a * self.xi[i:i + 512], k) for i in range(0, self.xi.size, 512)])

    def dg(self, xi):
        return self.prof.dg(np.array([self.a * xi]), self.k)[0]

    def pressure(self, rho):
        """(a^k/pi) int_rho^1 g'(a xi) (xi^2 - rho^2)^(-(1-k)/2) dxi."""
        k, q, e = self.k, 0.5 * (1.0 - self.k), self.edges
        j = int(np.searchsorted(e, rho, side="right"))           # first edge above rho
        x1 = e[j]
        width = 1.0 - rho if j == e.size - 1 else x1 - rho        # 1 - rho exact (Sterbenz)
        if rho == 0.0:
            head = quad(lambda s: self.dg(s), 0.0, width, weight="alg", wvar=(k - 1, 0), epsabs=0, epsrel=2e-14)[0]
        else:
            head = quad(lambda s: self.dg(rho + s) * (2 * rho + s) ** -q, 0.0, width, weight="alg", wvar=(-q, 0),
                        epsabs=0, epsrel=2e-14)[0]
        total, start = head, j
        if rho > 0.0 and j < e.size - 1:            # the next piece: the singularity may be close to its start
            total += quad(lambda x: self.dg(x) * (x * x - rho * rho) ** -q, e[j], e[j + 1], epsabs=0,
                          epsrel=2e-14, limit=200)[0]
            start = j + 1
        total += self._graded(start, self.edges.size - 1, lambda x: (x * x - rho * rho) ** -q)
        return self.a ** k * total / np.pi

    def displacement(self, rho):
        """(G49): a int_0^1 g'(a xi) I_(xi^2/rho^2)((1+k)/2, (1-k)/2) dxi, quadpack on the first
        piece (I ~ xi^(1+k)) and the last (the kernel's singularity at xi = rho next to 1)."""
        q, e = 0.5 * (1.0 + self.k), self.edges

        def kernel(x):
            return betainc(q, 1.0 - q, (x / rho) ** 2)

        first = quad(lambda x: self.dg(x) * kernel(x), 0.0, e[1], epsabs=0, epsrel=2e-14, limit=200)[0]
        gap = rho - 1.0
        last = quad(lambda x: self.dg(x) * kernel(x), e[-2], 1.0, epsabs=0, epsrel=2e-14, limit=400,
                    points=[1.0 - c * gap for c in (1e0, 1e1, 1e2, 1e3, 1e4) if 1.0 - c * gap > e[-2]])[0] \
            if e.size > 2 else 0.0
        return self.a * (first + last + self._graded(1, self.edges.size - 2, kernel))

    def _graded(self, start, stop, kernel):
        """The graded rule on the pieces start ... stop - 1."""
        sel = (self.piece >= start) & (self.piece < stop)
        return float(np.sum(self.w[sel] * self.dg_nodes[sel] * kernel(self.xi[sel])))


@pytest.fixture(scope="module")
def references():
    """Per (samples, k): pressure and u_z of the hyperboloid at RHO_P, RHO_U (a between knots)."""
    out = {}
    for n, k in REFERENCE_CASES:
        ref = Reference(n, k, 0.83 * A)
        out[n, k] = (np.array([ref.pressure(x) for x in RHO_P]) * c_N_star(k, **MAT),
                     np.array([ref.displacement(x) for x in RHO_U]))
    return out


#: (samples, k) of the quadpack references: every k at 25 and 200 samples; at 1000 samples (whose
#: exact-g' reference costs ~10 s per k) the k of the bench and the near-homogeneous end
REFERENCE_CASES = [(n, k) for n in SAMPLES[:2] for k in KS] + [(SAMPLES[2], 0.5), (SAMPLES[2], 1e-6)]


@pytest.mark.parametrize("rtol", RTOLS)
@pytest.mark.parametrize("n,k", REFERENCE_CASES)
def test_against_quadrature_of_the_defining_integrals(n, k, rtol, references):
    prof, _ = hyperboloid(n)
    p_ref, u_ref = references[n, k]
    p = N.pressure_quad(None, 0.83 * A, prof, rtol=rtol, rho=RHO_P, k=k, **MAT)
    assert rel(p, p_ref) <= max(rtol, 2e-12)
    u = N.surface_displacement_quad(None, 0.83 * A, prof, k=k, rtol=rtol, rho=RHO_U)
    assert rel(u, u_ref) <= max(rtol, 2e-12)


def test_reference_against_the_exact_route_of_the_old_tests(references):
    """The graded-rule reference agrees with the closed forms too (cubic, where the spline is exact)."""
    rt = np.linspace(0.0, 1.2, 200) * A
    tab = P.Tabulated(rt, rt ** 2 / (2 * 1.7) + 0.9 * rt ** 3, slope_at_0=0.0)
    ref = Reference(25, 0.5, 0.83 * A)
    ref.prof = tab
    ref.dg_nodes = tab.dg(ref.a * ref.xi, 0.5)
    m = dict(MAT, k=0.5)
    parts = [(2.0, 1 / (2 * 1.7)), (3.0, 0.9)]
    for rho in (0.0, 0.3, 0.999):
        closed = sum(N.pressure(None, 0.83 * A, n=n, A_n=An, rho=np.array([rho]), **m) for n, An in parts)[0]
        assert rel(ref.pressure(rho) * c_N_star(0.5, **MAT), closed) < 1e-12
    for rho in (1.0 + 1e-9, 1.3, 3.0):
        closed = sum(N.surface_displacement(None, 0.83 * A, k=0.5, n=n, A_n=An, rho=np.array([rho]))
                     for n, An in parts)[0]
        assert rel(ref.displacement(rho), closed) < 1e-12
