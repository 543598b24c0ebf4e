"""Loading histories (eq. 27-28): the c-term memory against independent routes.

Independent routes used here: a brute-force simulation of every MDR spring as a stop operator
(clip by the Coulomb limit after each increment), the Mindlin–Deresiewicz closed forms derived in
the comments below, the cone pressure p(r; c) = p_m arccosh(c/r) (paper eq. 36,
docs/theory/axisymmetric.md (A20)) for the Mindlin–Deresiewicz traction (A74) of the paper's figure
case reversed, and a direct scipy quadrature of eq. (28) with the spring slope derived by hand.
Nothing is copied from the code under test.
"""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from stressfields.physics import axisymmetric as ax
from stressfields.physics.axisymmetric import history as h

COMPS = ("xx", "yy", "zz", "xy", "xz", "yz")


def kappa(nu):
    return 2 * (1 - nu) / (2 - nu)                     # G*/E*


# -- brute force: every spring a stop operator ---------------------------------------------------

def brute_springs(history, xs, nu, mu, profile, a=1.0):
    """u_x,1D/delta at xs after each step, and the energy each spring dissipated (per unit G* delta^2)."""
    L = mu / kappa(nu) * (1 - profile.g(xs) / profile.g(a))
    s = np.zeros_like(xs)
    u = 0.0
    states, diss = [], []
    d = np.zeros_like(xs)
    for target in history:
        # the increment is monotonic: clipping once at its end is exact for a stop operator
        new = np.clip(s + (target - u), -L, L)
        d = d + L * (abs(target - u) - np.abs(new - s))
        s, u = new, target
        states.append(s.copy())
        diss.append(d.copy())
    return states, diss


def gl_panels(a, panels=400, n=8):
    t, w = np.polynomial.legendre.leggauss(n)
    edges = np.linspace(0.0, a, panels + 1)
    mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
    return (mid[:, None] + half[:, None] * t).ravel(), (half[:, None] * w).ravel()


PROFILES = {"cone": ax.cone(1.0), "paraboloid": ax.paraboloid(1.0), "power_law": ax.power_law(1.0, 1.5),
            "tabulated": ax.tabulated(np.linspace(0, 1.2, 25),
                                      np.linspace(0, 1.2, 25) ** 2 / 2 + 0.1 * np.linspace(0, 1.2, 25) ** 4)}

HISTORY = [0.1, 0.3, -0.05, 0.2, 0.05, 0.15, 0.12, 0.4, -0.9, 0.1, -0.3, 0.0, 0.25]


@pytest.mark.parametrize("name", list(PROFILES))
def test_spring_field_equals_brute_force(name):
    profile, nu, mu = PROFILES[name], 0.3, 0.4           # gross slip at |u| = mu/kappa = 0.486
    xs = np.linspace(0.0, 1.0, 401)
    brute, _ = brute_springs(HISTORY, xs, nu, mu, profile)
    for s, expect in zip(h.states(HISTORY), brute):
        got = h.spring_state(xs, s.terms(), 1.0, nu, mu, profile)
        np.testing.assert_allclose(got, expect, rtol=0, atol=1e-14)


@pytest.mark.parametrize("name", ["cone", "paraboloid", "power_law"])
def test_force_and_energy_equal_brute_force(name):
    profile, nu, mu = PROFILES[name], 0.25, 0.35
    xs, ws = gl_panels(1.0)
    brute, diss = brute_springs(HISTORY, xs, nu, mu, profile)
    fn = profile.normal_force(1.0)                      # F_N / E*
    delta = profile.g(1.0)
    energy = h.dissipated_energy(HISTORY, 1.0, nu, mu, profile)
    for s, b, d, e in zip(h.states(HISTORY), brute, diss, energy):
        # F_x = 2 int_0^a G* u_1D dx ; W = 2 int_0^a G* L slip dx
        fx = 2 * kappa(nu) * delta * np.sum(ws * b) / (mu * fn)
        assert h.tangential_force(s.terms(), 1.0, nu, mu, profile) == pytest.approx(fx, abs=2e-6)
        assert e == pytest.approx(2 * kappa(nu) * delta * np.sum(ws * d) / (mu * fn), abs=2e-6)


# -- Mindlin–Deresiewicz (paraboloid) ------------------------------------------------------------
# Monotonic (Mindlin): F = mu P [1 - (1 - u/u*)^(3/2)], u* = mu/kappa (in units of delta).
# Masing: unloading from (U, F1) follows F = F1 - 2 F_mono((U - u)/2); reloading from (-U, -F1)
# follows F = -F1 + 2 F_mono((u + U)/2).  Loop energy (Mindlin & Deresiewicz 1953; Johnson,
# Contact Mechanics, eq. 7.66 in units of mu P u*, with 9 mu^2 P^2 (2-nu)/(10 G a) = (24/5) mu P u*):
# W = (24/5) [1 - (1 - x)^(5/3) - (5x/6) (1 + (1 - x)^(2/3))], x = F1/(mu P).

def mono(u, ustar):
    return np.where(u >= ustar, 1.0, 1 - np.clip(1 - u / ustar, 0, None) ** 1.5)


@pytest.mark.parametrize("nu, mu, U", [(0.3, 0.4, 0.25), (0.2, 0.25, 0.1), (0.45, 0.6, 0.5)])
def test_paraboloid_unloading_reloading_mindlin_deresiewicz(nu, mu, U):
    p = ax.paraboloid(1.0)
    ustar = mu / kappa(nu)
    assert U < ustar
    F1 = mono(U, ustar)
    down = np.linspace(U, -U, 9)[1:]
    up = np.linspace(-U, U, 9)[1:]
    hist = [U, *down, *up]
    sts = h.states(hist)
    F = [float(h.tangential_force(s.terms(), 1.0, nu, mu, p)) for s in sts]
    np.testing.assert_allclose(F[1:9], F1 - 2 * mono((U - down) / 2, ustar), rtol=0, atol=1e-10)
    np.testing.assert_allclose(F[9:], -F1 + 2 * mono((up + U) / 2, ustar), rtol=0, atol=1e-10)
    # the cycle closes on its starting state, exactly
    assert sts[-1] == sts[0]
    assert h.closed_cycles(sts)[-1] == 0
    W = h.dissipated_energy(hist, 1.0, nu, mu, p)
    x = F1
    md = 24 / 5 * (1 - (1 - x) ** (5 / 3) - 5 * x / 6 * (1 + (1 - x) ** (2 / 3)))
    assert (W[-1] - W[0]) / ustar == pytest.approx(md, rel=1e-10)
    # the loop area by the trapezoidal rule on the analytic branches converges to the same value
    fine_d = np.linspace(U, -U, 4001)
    fine_u = fine_d[::-1]
    area = np.trapezoid(-2 * mono((U - fine_d) / 2, ustar) + F1, fine_d) + \
        np.trapezoid(2 * mono((fine_u + U) / 2, ustar) - F1, fine_u)
    assert area / ustar == pytest.approx(md, rel=1e-5)


def test_gross_slip_histories():
    """Beyond gross slip the force saturates, the memory is wiped, and the loop energy is
    W = 4 mu P (A - 4 u*/5) for amplitude A >= u* (Masing with a saturated skeleton)."""
    nu, mu = 0.3, 0.3
    p = ax.paraboloid(1.0)
    ustar = mu / kappa(nu)
    A = 1.7 * ustar
    hist = [0.3 * ustar, A, 0.5 * ustar, -A, -0.2 * ustar, A, -A, A]
    sts = h.states(hist)
    F = [float(h.tangential_force(s.terms(), 1.0, nu, mu, p)) for s in sts]
    assert F[1] == pytest.approx(1.0, abs=1e-15) and F[3] == pytest.approx(-1.0, abs=1e-15)
    # after gross slip the reversal starts from the sliding state: F = 1 - 2 F_mono(du/2)
    assert F[2] == pytest.approx(1 - 2 * mono((A - 0.5 * ustar) / 2, ustar), abs=1e-12)
    assert F[4] == pytest.approx(-1 + 2 * mono((A - 0.2 * ustar) / 2, ustar), abs=1e-12)
    # a partial-slip stick zone after gross slip: current stick radius from the reversal alone
    c = h.current_stick_radius(sts[2].terms(), 1.0, nu, mu, p)
    assert float(c) == pytest.approx(math.sqrt(1 - (A - 0.5 * ustar) / 2 / ustar), rel=1e-12)
    W = h.dissipated_energy(hist, 1.0, nu, mu, p)
    assert h.closed_cycles(sts)[-1] == 5
    assert (W[-1] - W[5]) / ustar == pytest.approx(4 * (A / ustar - 0.8), rel=1e-10)
    # the stresses after gross slip do not remember anything before it
    x = np.linspace(-1.2, 1.2, 13)
    fresh = h.history_stress(x, 0.3, 1.0, nu, mu, p, h.states([A, 0.5 * ustar])[-1].terms())
    wiped = h.history_stress(x, 0.3, 1.0, nu, mu, p, sts[2].terms())
    for k in COMPS:
        np.testing.assert_allclose(wiped[k], fresh[k], rtol=1e-14, atol=1e-15)


# -- monotonic loading is the foundation's Cattaneo–Mindlin result ---------------------------------

GRID_X = np.array([-1.4, -1.0, -0.83, -0.5, -0.2, 0.0, 0.13, 0.5, 0.7, 0.99, 1.0, 1.3, 2.5])
GRID_Y = np.array([[0.0], [0.35], [-0.8]])


@pytest.mark.parametrize("name, method", [("cone", "closed"), ("paraboloid", "closed"),
                                          ("power_law", "quadrature"), ("tabulated", "quadrature")])
@pytest.mark.parametrize("u", [0.2, 0.6])              # partial slip, gross slip (mu = 0.3)
def test_monotonic_equals_cattaneo_mindlin(name, method, u):
    profile, nu, mu = PROFILES[name], 0.3, 0.3
    c = ax.stick_radius(1.0, nu, mu, u, profile)
    ref = ax.surface_stress(GRID_X, GRID_Y, 1.0, c, nu, mu, profile, method=method)
    normal = ax.surface_stress(GRID_X, GRID_Y, 1.0, 1.0, nu, 0.0, profile, method=method)
    refd = ax.surface_dpdz(GRID_X, GRID_Y, 1.0, c, nu, mu, profile, method=method)
    normald = ax.surface_dpdz(GRID_X, GRID_Y, 1.0, 1.0, nu, 0.0, profile, method=method)
    for sign in (1, -1):
        terms = h.states([0.5 * u * sign, u * sign])[-1].terms()
        got = h.history_stress(GRID_X, GRID_Y, 1.0, nu, mu, profile, terms, method=method)
        gotd = h.history_dpdz(GRID_X, GRID_Y, 1.0, nu, mu, profile, terms, method=method)
        for k in COMPS:
            # reversed load: the tangential part (by subtraction here) changes sign
            with np.errstate(invalid="ignore"):
                expect = ref[k] if sign > 0 else 2 * normal[k] - ref[k]
            ok = np.isfinite(expect)
            np.testing.assert_allclose(got[k][ok], expect[ok], rtol=0, atol=1e-12 * max(1, np.abs(expect[ok]).max()))
        with np.errstate(invalid="ignore"):
            expect = refd if sign > 0 else 2 * normald - refd
        ok = np.isfinite(expect)
        np.testing.assert_allclose(gotd[ok], expect[ok], rtol=1e-12, atol=1e-12)
        assert np.array_equal(np.isinf(gotd), np.isinf(refd))
        assert float(h.tangential_force(terms, 1.0, nu, mu, profile)) == pytest.approx(
            sign * (1 - profile.normal_force(c) / profile.normal_force(1.0)), abs=1e-15)


# -- the paper's figure case reversed: cone, nu = 0.3, mu = 0.4, load to delta/4, reverse by 0.3 delta --

def test_paper_case_cone_reversal():
    nu, mu = 0.3, 0.4
    cone = ax.cone(1.0)                                  # a = 1, delta = pi/2, p_m = E*/2
    k = kappa(nu)
    c1, cr = 1 - k * 0.25 / mu, 1 - k * 0.15 / mu        # eq. (38): g(a) - g(c) = (G*/mu E*) u
    terms = h.states([0.25, -0.05])[-1].terms()
    r = np.array([0.05, 0.2, 0.4, 0.55, 0.7, 0.8, 0.9, 0.99])
    pm = ax.mean_pressure(1.0, cone)

    def p(rr, c):                                        # cone pressure / p_m at contact radius c
        return np.where(rr < c, np.arccosh(c / np.minimum(rr, c)), 0.0)

    q = mu * ((p(r, 1) - p(r, c1)) - 2 * (p(r, 1) - p(r, cr)))
    for phi in (0.0, 0.7, 2.0):
        x, y = r * math.cos(phi), r * math.sin(phi)
        s = h.history_stress(x, y, 1.0, nu, mu, cone, terms)
        np.testing.assert_allclose(s["xz"] / pm, -q, rtol=1e-13, atol=1e-15)
    zones = h.slip_zones(terms, 1.0, nu, mu, cone)
    assert [(round(i, 12), round(o, 12), d, now) for i, o, d, now in zones] == [
        (round(cr, 12), 1.0, -1, True), (round(c1, 12), round(cr, 12), 1, False)]
    assert float(h.current_stick_radius(terms, 1.0, nu, mu, cone)) == pytest.approx(cr, rel=1e-14)

    # in-plane stresses by eq. (28) quadrature, with the spring slope derived by hand:
    # G* u'_1D = +mu E* g' on (c_r, a) (slipping back), -mu E* g' on (c_1, c_r), 0 inside c_1
    def sigma28(x, y):
        rr = math.hypot(x, y)
        gprime = math.pi / 2

        def slope(u):
            return mu * gprime * (1.0 if u > cr else (-1.0 if u > c1 else 0.0))

        def integral(fun):
            top = min(rr, 1.0)
            pts = [v for v in (c1, cr) if v < top]
            # u = r sin t removes the 1/sqrt(r^2 - u^2) endpoint
            g = lambda t: fun(rr * math.sin(t)) * rr * math.sin(t) * slope(rr * math.sin(t))  # noqa: E731
            bps = [math.asin(v / rr) for v in pts]
            return quad(g, 0.0, math.asin(top / rr), points=bps or None, epsabs=1e-14, epsrel=1e-13, limit=200)[0]

        r6 = rr ** 6
        xx = 2 * x / (math.pi * r6) * integral(
            lambda u: (1 + nu) * rr ** 4 - nu * (u * u * rr * rr + y * y * (3 * rr * rr - 4 * u * u)))
        yy = 2 * nu * x / (math.pi * r6) * integral(lambda u: u * u * rr * rr + y * y * (3 * rr * rr - 4 * u * u))
        xy = y / (math.pi * r6) * integral(
            lambda u: (1 - 2 * nu) * rr ** 4 + 2 * nu * (u * u * rr * rr + x * x * (3 * rr * rr - 4 * u * u)))
        return xx, yy, xy

    pts = [(0.5, 0.3), (-0.75, 0.2), (0.85, -0.3), (0.95, 0.05), (1.3, 0.4), (0.2, 2.1)]
    xs, ys = np.array(pts).T
    normal = ax.surface_stress(xs, ys, 1.0, 1.0, nu, 0.0, cone)
    got = h.history_stress(xs, ys, 1.0, nu, mu, cone, terms)
    for i, (x, y) in enumerate(pts):
        for kk, v in zip(("xx", "yy", "xy"), sigma28(x, y)):
            assert (got[kk][i] - normal[kk][i]) / pm == pytest.approx(v / pm, abs=1e-11)

    # tangential dp/dz is local: (2(1+nu)/3) dq/dx, checked by a central difference of sigma_xz
    x0, y0, eps = np.array([0.3, 0.6, 0.75, 0.93]), 0.1, 1e-5
    dq = -(h.history_stress(x0 + eps, y0, 1.0, nu, mu, cone, terms, components=("xz",))["xz"]
           - h.history_stress(x0 - eps, y0, 1.0, nu, mu, cone, terms, components=("xz",))["xz"]) / (2 * eps)
    tang = h.history_dpdz(x0, y0, 1.0, nu, mu, cone, terms) - ax.surface_dpdz(x0, y0, 1.0, 1.0, nu, 0.0, cone)
    np.testing.assert_allclose(tang, 2 * (1 + nu) / 3 * dq, rtol=1e-7)


def test_closed_cycle_returns_exactly_and_edges():
    nu, mu, p = 0.3, 0.4, ax.cone(1.0)
    hist = [0.25, -0.05, 0.1, 0.0, 0.25, -0.2, 0.25]
    sts = h.states(hist)
    assert h.closed_cycles(sts) == [None, None, None, None, 0, None, 4]
    x = np.linspace(-1.5, 1.5, 31)
    a = h.history_stress(x, 0.2, 1.0, nu, mu, p, sts[0].terms())
    b = h.history_stress(x, 0.2, 1.0, nu, mu, p, sts[-1].terms())
    for k in COMPS:
        assert np.array_equal(a[k], b[k], equal_nan=True)
    # dp/dz on the stick edges of a nested state: +inf sgn(x) times the net weight there
    terms = sts[2].terms()                             # (0.25,+1) (0.15,-2) (0.075,+2)
    cs = [float(c) for c in h.stick_radii(terms, 1.0, nu, mu, p)]
    d = h.history_dpdz(np.array([cs[1], -cs[1], cs[2], 0.0, 1.0, -1.0]), np.array([0, 0, 0, cs[1], 0, 0]),
                       1.0, nu, mu, p, terms)
    assert d.tolist() == [-math.inf, math.inf, math.inf, 0.0, -math.inf, math.inf]
    # the stick zone (r < c_1) never slipped: its in-plane tangential stresses are zero
    inner = h.history_stress(np.array([0.1, -0.2]), 0.1, 1.0, nu, mu, p, terms)
    normal = ax.surface_stress(np.array([0.1, -0.2]), 0.1, 1.0, 1.0, nu, 0.0, p)
    for k in ("xx", "yy", "xy"):
        np.testing.assert_allclose(inner[k], normal[k], rtol=1e-14)


def test_cone_tip_values_follow_the_monotonic_conventions():
    """r = 0 of a cone: the -inf normal stresses dominate.  sigma_xz is log-singular (like gross
    slip) whenever the springs at the centre carry a slip, i.e. after gross slip, with the sign of
    the slip locked in there; it is finite when the centre never slipped."""
    nu, mu, p = 0.3, 0.3, ax.cone(1.0)                  # gross slip at |u| = 0.364
    for hist, xz in (([0.6, 0.3], -math.inf), ([0.6, -0.6], math.inf), ([-0.6, -0.3], math.inf),
                     ([0.2, -0.1, 0.15], None)):
        terms = h.states(hist)[-1].terms()
        s = h.history_stress(0.0, 0.0, 1.0, nu, mu, p, terms)
        assert s["xx"] == -math.inf and s["zz"] == -math.inf
        if xz is None:
            assert np.isfinite(s["xz"])
        else:
            assert s["xz"] == xz


# -- cycles that close inside a step ---------------------------------------------------------------

def brute_path(history, xs, ws, nu, mu, profile, sub=4000):
    """Fine sub-steps of every monotonic step through the stop operators: u, F_x/(mu F_N) and the
    cumulative dissipation W/(mu F_N delta) at every sub-step (units of delta)."""
    L = mu / kappa(nu) * (1 - profile.g(xs) / profile.g(1.0))
    norm = mu * profile.normal_force(1.0) / (kappa(nu) * profile.g(1.0))   # mu F_N / (G* delta)
    s, u, W = np.zeros_like(xs), 0.0, 0.0
    path = [(0.0, 0.0, 0.0)]
    for target in history:
        for v in np.linspace(u, target, sub + 1)[1:]:
            new = np.clip(s + (v - u), -L, L)
            W += 2 * np.sum(ws * L * (abs(v - u) - np.abs(new - s))) / norm
            s, u = new, v
            path.append((u, 2 * np.sum(ws * s) / norm, W))
    return np.array(path)


@pytest.mark.parametrize("name", ["paraboloid", "cone", "power_law", "tabulated"])
def test_cycle_closing_inside_a_step_brute_force(name):
    """The reproducer: the loop u1 -> -u1 -> u1 closes during the move to 1.2 u1 (step 3).  Its
    energy is the brute-force dissipation between the two visits of u1, and equals the loop area
    closed integral F_x du of the brute-force force (the elastic energy returns)."""
    profile, nu, mu = PROFILES[name], 0.3, 0.3
    u1 = 0.5 * mu / kappa(nu)
    hist = [0.0, u1, -u1, 1.2 * u1]
    got = h.cycle_energy(hist, 1.0, nu, mu, profile)
    assert got[:3].tolist() == [0.0, 0.0, 0.0]
    xs, ws = gl_panels(1.0)
    sub = 5500
    path = brute_path(hist, xs, ws, nu, mu, profile, sub=sub)
    i_open = 2 * sub                                  # end of step 1 (u = u1)
    i_close = 3 * sub + 5000                          # u back at u1 during step 3 (2 u1 of 2.2 u1)
    assert path[i_close, 0] == pytest.approx(u1, rel=1e-12)
    brute_w = path[i_close, 2] - path[i_open, 2]
    assert got[3] == pytest.approx(brute_w, rel=2e-5)
    loop = path[i_open:i_close + 1]
    area = np.sum(0.5 * (loop[1:, 1] + loop[:-1, 1]) * np.diff(loop[:, 0]))
    assert got[3] == pytest.approx(area, rel=1e-4)            # the work of F_x over the loop
    if name == "paraboloid":                          # Mindlin–Deresiewicz (A77), x = F1/(mu F_N)
        x = 1 - 0.5 ** 1.5
        md = 24 / 5 * (1 - (1 - x) ** (5 / 3) - 5 * x / 6 * (1 + (1 - x) ** (2 / 3)))
        assert got[3] / (mu / kappa(nu)) == pytest.approx(md, rel=1e-10)


def test_nested_cycles_inside_one_step_count_the_outermost():
    """The move into the last step closes 0.6 -> 0.4 -> 0.6 and then 1 -> 0.2 -> 1 on the way: the
    outer cycle (which contains the inner one) is counted; a cycle closing at the end of a step is
    counted as before."""
    nu, mu, p = 0.3, 0.4, ax.paraboloid(1.0)
    ustar = mu / kappa(nu)
    hist = [s * ustar for s in (0.5, 0.1, 0.3, 0.2, 0.6, 0.1, 0.5)]
    got = h.cycle_energy(hist, 1.0, nu, mu, p)
    xs, ws = gl_panels(1.0)
    sub = 4000
    path = brute_path([0.0] + hist, xs, ws, nu, mu, p, sub=sub)
    # step 5 (0.2 -> 0.6 u*) passes 0.3 (inner) and 0.5 u* (outer, opened at step 1)
    i_close = 5 * sub + round(sub * 0.75)
    assert path[i_close, 0] == pytest.approx(0.5 * ustar, rel=1e-12)
    assert got[4] == pytest.approx(path[i_close, 2] - path[2 * sub, 2], rel=2e-5)
    # step 7 ends back at 0.5 u*: the loop 0.6 -> 0.1 -> 0.6 is not closed, nothing counted
    assert got[6] == 0.0 and got[:4].tolist() == [0.0] * 4
