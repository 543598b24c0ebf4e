"""Non-adhesive normal contact on the power-law graded half-space (Hess & Popov 2016, eqs. 5-26).

Closed forms and the quadrature route are each held against the reference points
(tests/data/graded_power_law.json, 30-digit values), against each other at the numerically delicate
probes of docs/theory/graded.md (G38)-(G42), and against the homogeneous (k = 0) Hertz and
Love/Sneddon solutions.
"""

import numpy as np
import pytest
from scipy.integrate import quad

from stressfields.physics.graded import material as M
from stressfields.physics.graded import normal as N
from stressfields.physics.graded import profiles as P
from graded_reference import REF, nu_of

CF = 1e-12          # closed forms
RTOL = 1e-10        # quadrature route tolerance passed to the *_quad functions
E0, C0, A = 2.5, 0.8, 0.6
E_STAR = lambda nu: E0 / (1 - nu ** 2)   # noqa: E731


def rel(x, ref):
    x, ref = np.asarray(x, float), np.asarray(ref, float)
    return np.max(np.abs(x / ref - 1))


def kw(case):
    return dict(k=case["k"], nu=nu_of(case), E0=E0, c0=C0)


@pytest.mark.parametrize("case", REF["normal"], ids=lambda c: f"{c['profile']}-k{c['k']}-nu{c['nu']}")
def test_reference_points(case):
    n, An = case["n"], float(case["A_n"])
    prof = P.PowerLaw(A=An, n=n)
    a = float(case["a"])
    assert a == A
    d_ref, F_ref = float(case["d"]["value_str"]), float(case["F_N"]["value_str"])
    assert rel(N.depth(a, k=case["k"], n=n, A_n=An), d_ref) < CF
    assert rel(N.normal_force(a, n=n, A_n=An, **kw(case)), F_ref) < CF
    assert rel(N.depth_quad(a, prof, k=case["k"], rtol=RTOL), d_ref) < RTOL
    assert rel(N.normal_force_quad(a, prof, rtol=RTOL, **kw(case)), F_ref) < RTOL

    pts = [p for p in case["p"] if p["value_str"] is not None]
    r = np.array([p["r_over_a"] for p in pts]) * a
    p_ref = np.array([float(p["value_str"]) for p in pts])
    assert rel(N.pressure(r, a, n=n, A_n=An, **kw(case)), p_ref) < CF
    assert rel(N.pressure_quad(r, a, prof, rtol=RTOL, **kw(case)), p_ref) < RTOL

    r = np.array([u["r_over_a"] for u in case["u_z_outside"]]) * a
    u_ref = np.array([float(u["value_str"]) for u in case["u_z_outside"]])
    assert rel(N.surface_displacement(r, a, k=case["k"], n=n, A_n=An), u_ref) < CF
    assert rel(N.surface_displacement_quad(r, a, prof, k=case["k"], rtol=RTOL), u_ref) < RTOL


def test_cone_centre_pressure_is_infinite_at_k0():
    p = N.pressure(0.0, A, k=0.0, nu=0.3, E0=E0, c0=C0, n=1.0, A_n=0.3)
    assert np.isinf(p) and p > 0
    assert np.isfinite(N.pressure(0.0, A, k=1e-3, nu=0.3, E0=E0, c0=C0, n=1.0, A_n=0.3))


# ----------------------------------------------------------------- homogeneous limits (k -> 0)

@pytest.mark.parametrize("k, tol", [(0.0, 1e-13), (1e-6, 1e-5)])
def test_hertz_limit(k, tol):
    R, nu = 1.7, 0.3
    n, An = P.parabolic(R)
    a = np.array([0.1, 0.6, 2.0])
    d = N.depth(a, k=k, n=n, A_n=An)
    F = N.normal_force(a, k=k, nu=nu, E0=E0, c0=C0, n=n, A_n=An)
    assert rel(d, a ** 2 / R) < tol                                   # a^2 = R d
    assert rel(F, 4 / 3 * E_STAR(nu) * R ** 0.5 * d ** 1.5) < tol       # Hertz
    rho = np.array([0.0, 0.3, 0.9, 0.999])
    p = N.pressure(rho * A, A, k=k, nu=nu, E0=E0, c0=C0, n=n, A_n=An)
    assert rel(p, 2 * E_STAR(nu) * A / (np.pi * R) * np.sqrt(1 - rho ** 2)) < tol
    r = np.array([1.0001, 1.5, 1.99, 2.01, 4.0]) * A     # both sides of the far-field switch at 2a
    u = N.surface_displacement(r, A, k=k, n=n, A_n=An)
    hertz = ((2 * A ** 2 - r ** 2) * np.arcsin(A / r) + A * np.sqrt(r ** 2 - A ** 2)) / (np.pi * R)
    assert rel(u, hertz) < max(tol, 1e-13)
    if k == 0.0:   # Boussinesq far field u_z -> F/(pi E* r) (1 + O(a^2/r^2))
        r = 1e4 * A
        F = N.normal_force(A, k=k, nu=nu, E0=E0, c0=C0, n=n, A_n=An)
        assert N.surface_displacement(r, A, k=k, n=n, A_n=An) == pytest.approx(F / (np.pi * E_STAR(nu) * r), rel=1e-7)


@pytest.mark.parametrize("k, tol", [(0.0, 1e-13), (1e-6, 2e-5)])
def test_cone_limit_love_sneddon(k, tol):
    tan, nu = 0.3, 0.25
    n, An = P.conical(tan)
    a = np.array([0.1, 0.6, 2.0])
    d = N.depth(a, k=k, n=n, A_n=An)
    F = N.normal_force(a, k=k, nu=nu, E0=E0, c0=C0, n=n, A_n=An)
    assert rel(d, np.pi / 2 * a * tan) < tol
    assert rel(F, 2 * E_STAR(nu) * d ** 2 / (np.pi * tan)) < tol
    rho = np.array([1e-4, 0.3, 0.9, 0.9999])
    p = N.pressure(rho * A, A, k=k, nu=nu, E0=E0, c0=C0, n=n, A_n=An)
    assert rel(p, E_STAR(nu) * tan / 2 * np.arccosh(1 / rho)) < tol     # Sneddon, no pole at k -> 0
    r = np.array([1.0001, 1.5, 1.99, 2.01, 4.0]) * A
    u = N.surface_displacement(r, A, k=k, n=n, A_n=An)
    love = tan * (np.sqrt(r ** 2 - A ** 2) - r + A * np.arcsin(A / r))
    assert rel(u, love) < max(tol, 1e-13)


# ----------------------------------------------------------------- stability probes (docs/theory/graded.md (G38)-(G42))

PROBE_K = [1e-6, 1e-3, 0.5, 0.999]
PROFILES = [(1.0, 0.3), (1.5, 0.9), (2.0, 0.3), (3.0, 0.9)]


@pytest.mark.parametrize("k", PROBE_K)
@pytest.mark.parametrize("n, An", PROFILES)
def test_closed_form_vs_quadrature_probes(k, n, An):
    prof = P.PowerLaw(A=An, n=n)
    m = dict(k=k, nu=0.3, E0=E0, c0=C0)
    r = np.array([1e-4, 0.25, 0.9, 0.9999]) * A
    assert rel(N.pressure(r, A, n=n, A_n=An, **m), N.pressure_quad(r, A, prof, rtol=RTOL, **m)) < 10 * RTOL
    r_all = np.array([0.0, 1e-4, 0.5, 0.9999, 1.0, 1.0001, 1.05, 3.0, 1e3]) * A
    u = N.surface_displacement(r_all, A, k=k, n=n, A_n=An)
    uq = N.surface_displacement_quad(r_all, A, prof, k=k, rtol=RTOL)
    assert rel(u, uq) < 10 * RTOL
    assert rel(N.normal_force(A, n=n, A_n=An, **m), N.normal_force_quad(A, prof, rtol=RTOL, **m)) < 10 * RTOL


@pytest.mark.parametrize("k", [1e-6, 1e-3, 0.5, 0.999])
def test_equilibrium_of_pressure(k):
    """2 pi int_0^a p r dr = F_N (eq. 12 vs eq. 13), integrated with a Jacobi-weighted rule."""
    for n, An in PROFILES:
        m = dict(k=k, nu=0.3, E0=E0, c0=C0, n=n, A_n=An)
        beta_edge = 0.5 * (1 + k)
        # p = (a - r)^((1+k)/2) * smooth; the cone's logarithmic centre is integrable

        def f(r):
            r = min(r, A * (1 - 1e-13))         # quadpack also samples the end point itself
            return 2 * np.pi * r * float(N.pressure(r, A, **m)) / (A - r) ** beta_edge

        val, err = quad(f, 0.0, A, weight="alg", wvar=(0.0, beta_edge), epsabs=0, epsrel=1e-11, limit=200)
        assert val == pytest.approx(float(N.normal_force(A, **m)), rel=1e-9)


def test_pressure_centre_limit():
    for k in [1e-3, 0.5, 0.999]:
        for n, An in [(1.5, 0.9), (2.0, 0.3), (3.0, 0.9)]:
            m = dict(k=k, nu=0.3, E0=E0, c0=C0)
            p0 = N.pressure(0.0, A, n=n, A_n=An, **m)
            assert p0 == pytest.approx(N.pressure_quad(0.0, A, P.PowerLaw(A=An, n=n), rtol=RTOL, **m), rel=1e-9)
            # p(r) - p(0) = O((r/a)^(n+k-1)) (and O((r/a)^2) once that exponent exceeds 2)
            tol = 10 * 1e-9 ** min(n + k - 1, 2)
            assert p0 == pytest.approx(N.pressure(1e-9 * A, A, n=n, A_n=An, **m), rel=tol)


def test_printed_table2_uz_is_wrong_and_corrected_form_right():
    """Table 2 u_z with second beta parameter (3+k)/2 (as printed) vs (2+k)/2 (docs/theory/graded.md (G21),
    Errata 1), both held against quadrature of eq. (15)."""
    from scipy.special import beta as B, betainc

    def Binc(z, x, y):
        return betainc(x, y, z) * B(x, y)

    k, tan = 0.5, 0.3
    r = np.array([1.05, 1.5, 2.0, 4.0]) * A
    z = (A / r) ** 2
    pref = np.cos(k * np.pi / 2) * B(0.5, (1 + k) / 2) * tan / (2 * np.pi)
    printed = pref * (A * Binc(z, (1 + k) / 2, (1 - k) / 2) - r * Binc(z, (3 + k) / 2, (1 - k) / 2))
    corrected = pref * (A * Binc(z, (1 + k) / 2, (1 - k) / 2) - r * Binc(z, (2 + k) / 2, (1 - k) / 2))
    quadrature = N.surface_displacement_quad(r, A, P.PowerLaw(A=tan, n=1.0), k=k, rtol=RTOL)
    assert rel(corrected, quadrature) < 1e-9
    assert np.min(np.abs(printed / quadrature - 1)) > 0.2


def test_printed_table2_cone_pressure_is_undefined_at_k0():
    """Table 2 cone pressure as printed, r^k [B(-k/2, (1+k)/2) - B(r^2/a^2; -k/2, (1+k)/2)] with the
    incomplete beta continued by eq. (26) (docs/theory/graded.md (G19)): equal to the code's cosh form
    (G18) for 0 < k < 1, but not finite at k = 0, where the code gives Sneddon's cone pressure
    (Errata 3)."""
    from scipy.special import beta as B, hyp2f1

    def printed(r, k, tan, nu):
        with np.errstate(all="ignore"):
            x, y = -k / 2, (1 + k) / 2
            z = (r / A) ** 2
            b_inc = z ** x / x * hyp2f1(x, 1 - y, 1 + x, z)                  # eq. (26)
            pref = M.h_N(k, nu) * E0 * tan * B(0.5, y) * r ** k / (4 * np.pi * (1 - nu ** 2) * C0 ** k)
            return pref * (B(x, y) - b_inc)

    tan, nu = 0.3, 0.3
    r = np.array([1e-3, 0.25, 0.5, 0.9]) * A
    for k in (0.2, 0.5, 0.9):
        assert rel(printed(r, k, tan, nu), N.pressure(r, A, k=k, nu=nu, E0=E0, c0=C0, n=1.0, A_n=tan)) < 1e-12
    assert not np.isfinite(printed(r, 0.0, tan, nu)).any()
    p0 = N.pressure(r, A, k=0.0, nu=nu, E0=E0, c0=C0, n=1.0, A_n=tan)
    assert rel(p0, E_STAR(nu) * tan / 2 * np.arccosh(A / r)) < 1e-13


# ----------------------------------------------------------------- profiles and transform (eqs. 5-9)

@pytest.mark.parametrize("k", [0.0, 1e-6, 0.5, 0.999])
@pytest.mark.parametrize("n", [0.5, 1.0, 1.5, 2.0, 3.0])
def test_transform_and_inverse(k, n):
    prof = P.PowerLaw(A=0.9, n=n)
    x = np.array([1e-3, 0.1, 0.6, 2.0])
    g = P.g_quad(x, prof, k=k, rtol=RTOL)
    assert rel(g, P.g_power_law(x, k=k, n=n, A_n=0.9)) < 1e-12
    assert rel(P.dg_quad(x, prof, k=k, rtol=RTOL), n * g / x) < 1e-12
    f = P.f_from_g_quad(x, lambda y: P.g_power_law(y, k=k, n=n, A_n=0.9), k=k, rtol=RTOL)
    assert rel(f, prof.f(x)) < 1e-12


def test_kappa_special_values():
    assert P.kappa(1.0, 0.0) == pytest.approx(np.pi / 2, rel=1e-15)
    assert P.kappa(2.0, 0.0) == pytest.approx(2.0, rel=1e-15)
    k = np.array([0.1, 0.5, 0.9])
    assert rel(P.kappa(2.0, k), 2 / (1 + k)) < 1e-14


@pytest.mark.parametrize("k", [0.0, 0.5, 0.95])
def test_tabulated_profile_reproduces_cubic_exactly(k):
    """A not-a-knot cubic spline reproduces r^2 and r^3 exactly, so the tabulated route must agree
    with the closed forms to quadrature accuracy (superposition of two power laws, linear in f)."""
    rt = np.linspace(0.0, 1.0, 9)
    R, c3 = 1.7, 0.9
    tab = P.Tabulated(rt, rt ** 2 / (2 * R) + c3 * rt ** 3)
    parts = [(2.0, 1 / (2 * R)), (3.0, c3)]
    m = dict(k=k, nu=0.3, E0=E0, c0=C0)
    r = np.array([0.0, 0.3, 0.9, 0.999]) * A
    ro = np.array([1.01, 2.0]) * A
    p = sum(N.pressure(r, A, n=n, A_n=An, **m) for n, An in parts)
    F = sum(N.normal_force(A, n=n, A_n=An, **m) for n, An in parts)
    u = sum(N.surface_displacement(ro, A, k=k, n=n, A_n=An) for n, An in parts)
    assert rel(N.pressure_quad(r, A, tab, rtol=RTOL, **m), p) < 1e-9
    assert rel(N.normal_force_quad(A, tab, rtol=RTOL, **m), F) < 1e-9
    assert rel(N.surface_displacement_quad(ro, A, tab, k=k, rtol=RTOL), u) < 1e-9
    with pytest.raises(ValueError, match="a = "):
        N.normal_force_quad(1.5, tab, **m)


def test_tabulated_profile_converges_for_a_quartic():
    rt = np.linspace(0.0, 1.0, 21)
    tab = P.Tabulated(rt, 2 * rt ** 4 + rt ** 2, slope_at_0=0.0)
    k = 0.5
    m = dict(k=k, nu=0.3, E0=E0, c0=C0)
    F = sum(N.normal_force(A, n=n, A_n=An, **m) for n, An in [(2.0, 1.0), (4.0, 2.0)])
    assert rel(N.normal_force_quad(A, tab, **m), F) < 1e-4   # spline interpolation error only


# ----------------------------------------------------------------- broadcasting and domain

def test_broadcasting_over_k_nu_r():
    k = np.array([0.0, 0.3, 0.9])[:, None, None]
    nu = np.array([0.2, 0.35])[None, :, None]
    r = np.array([0.0, 0.3, 0.9, 1.0, 1.5]) * A
    p = N.pressure(r, A, k=k, nu=nu, E0=E0, c0=C0, n=2.0, A_n=0.3)
    u = N.surface_displacement(r, A, k=k, n=1.5, A_n=0.3)
    assert p.shape == (3, 2, 5) and u.shape == (3, 1, 5)
    for i in range(3):
        for j in range(2):
            scalar = N.pressure(r, A, k=float(k[i, 0, 0]), nu=float(nu[0, j, 0]), E0=E0, c0=C0, n=2.0, A_n=0.3)
            np.testing.assert_array_equal(p[i, j], scalar)
    assert np.all(np.isfinite(p)) and np.all(p[..., 3:] == 0)


def test_sweep_has_no_nan():
    k = np.linspace(0.0, 0.999, 12)[:, None, None]
    nu = np.linspace(-0.5, 0.5, 5)[None, :, None]
    rho = np.concatenate([[0.0, 1e-6], np.linspace(0.01, 0.99, 15), [0.9999, 1.0, 1.2, 10.0]])
    for n, An in PROFILES:
        p = N.pressure(rho * A, A, k=k, nu=nu, E0=E0, c0=C0, n=n, A_n=An)
        u = N.surface_displacement(rho * A, A, k=k, n=n, A_n=An)
        assert not np.isnan(p).any() and not np.isnan(u).any()
        assert np.isfinite(u).all()
        inf = ~np.isfinite(p)
        assert not inf.any() or (n == 1.0 and np.all(np.argwhere(inf)[:, [0, 2]] == 0))


@pytest.mark.parametrize("bad, match", [
    (dict(a=-0.1), "a = "), (dict(a=0.0), "a = "), (dict(r=-0.1), "r = "),
    (dict(k=1.0), "k = "), (dict(nu=0.7), "nu = "), (dict(n=0.0), "n = "),
    (dict(A_n=-1.0), "A_n = "), (dict(E0=0.0), "E0 = "), (dict(c0=np.inf), "c0 = "),
])
def test_domain_errors(bad, match):
    args = dict(r=0.1, a=A, k=0.5, nu=0.3, E0=E0, c0=C0, n=2.0, A_n=0.3) | bad
    with pytest.raises(ValueError, match=match):
        N.pressure(args.pop("r"), args.pop("a"), **args)
