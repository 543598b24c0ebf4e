"""Stability at the delicate places (docs/theory/axisymmetric.md section 9): r -> 0, r -> a from both
sides, r -> c,
c -> 0 and c -> a, nu = 0 and 1/2, the far field r = 100a; and the documented +-inf / NaN points."""
import math

import numpy as np
import pytest

from stressfields.physics import axisymmetric as ax

KEYS = ("xx", "yy", "zz", "xy", "xz", "yz")
METHODS = ["closed", "quadrature"]


def _s(x, y, a, c, nu, mu, prof, method, **kw):
    return ax.surface_stress(x, y, a, c, nu, mu, prof, method=method, **kw)


@pytest.mark.parametrize("method", METHODS)
def test_cone_near_tip(method):
    """r = 1e-8 a: sigma_zz = -p0 arccosh(a/r) (log-singular), dp/dz = -(2(1+nu)/3) p0/r exactly,
    partial-slip shear -mu p0 ln((a+sqrt(a^2-r^2))/(c+sqrt(c^2-r^2))) -> -mu p0 ln(a/c), and the
    partial-slip tangential dp/dz -> -(2(1+nu)/3) mu p0 x (a^-2 - c^-2)/2 (docs/theory/axisymmetric.md
    (A89))."""
    t, a, c, nu, mu = 0.6, 2.0, 0.8, 0.3, 0.4
    p0 = 0.5 * t
    prof = ax.cone(t)
    r = 1e-8 * a
    x, y = r * math.cos(0.3), r * math.sin(0.3)
    s = _s(x, y, a, c, nu, mu, prof, method)
    L = math.log(2 * a / r) - (r / (2 * a)) ** 2          # arccosh(a/r) to O((r/a)^4)
    assert s["zz"] == pytest.approx(-p0 * L, rel=1e-15)
    assert s["xz"] == pytest.approx(-mu * p0 * math.log(a / c), rel=1e-13)
    dp = ax.surface_dpdz(x, y, a, c, nu, mu, prof, method=method)
    normal = -2 * (1 + nu) / 3 * p0 / r
    tang = -2 * (1 + nu) / 3 * mu * p0 * x * 0.5 * (1 / a ** 2 - 1 / c ** 2)
    assert dp == pytest.approx(normal + tang, rel=1e-14)


@pytest.mark.parametrize("method", METHODS)
def test_partial_slip_pressure_gradient_near_centre(method):
    """The tangential dp/dz of partial slip vanishes linearly at r -> 0; eq. (26)'s bracket cancels
    like r^2 there (docs/theory/axisymmetric.md (A87)).  Paraboloid:
    -(4(1+nu)mu/(3 pi R)) x (1/sqrt(a^2-r^2) - 1/sqrt(c^2-r^2)) (eq. 21, difference a - c); the
    normal part is the constant -2(1+nu)/(3R)."""
    R, a, c, nu, mu = 1.5, 1.0, 0.35, 0.3, 0.4
    r = np.array([1e-8, 1e-5, 1e-3])
    x, y = r * 0.6, r * 0.8
    dp = ax.surface_dpdz(x, y, a, c, nu, mu, ax.paraboloid(R), method=method)
    tang = -4 * (1 + nu) * mu / (3 * math.pi * R) * x * (1 / np.sqrt(a * a - r * r) - 1 / np.sqrt(c * c - r * r))
    np.testing.assert_allclose(dp + 2 * (1 + nu) / (3 * R), tang, rtol=1e-7, atol=0)


@pytest.mark.parametrize("method", METHODS)
def test_paraboloid_near_centre_is_smooth(method):
    """r = 1e-8 a: Hertz is isotropic at the centre, sigma_xx = sigma_yy = -(1+2nu) p0/2, no
    0/0 loss (docs/theory/axisymmetric.md (A81)-(A82))."""
    R, a, nu = 2.0, 0.5, 0.27
    p0 = 2 * a / (math.pi * R)
    for mu, c in ((0.0, 0.0), (0.3, 0.25), (0.3, 0.0)):
        s0 = _s(0.0, 0.0, a, c, nu, mu, ax.paraboloid(R), method)
        s1 = _s(1e-8 * a, 0.7e-8 * a, a, c, nu, mu, ax.paraboloid(R), method)
        assert float(s0["xx"]) == pytest.approx(-(1 + 2 * nu) * p0 / 2, rel=1e-14)
        for k in KEYS:
            assert abs(float(s1[k]) - float(s0[k])) <= 1e-7 * p0, (mu, k)


@pytest.mark.parametrize("profile", [ax.cone(0.5), ax.paraboloid(1.0), ax.power_law(0.4, 3.5),
                                     ax.tabulated(np.linspace(0, 1.5, 16), 0.3 * np.linspace(0, 1.5, 16) ** 2.2)],
                         ids=["cone", "paraboloid", "power_law", "tabulated"])
def test_contact_edge_from_both_sides(profile):
    """r = a (1 -+ 1e-9): stresses continuous across the edge (to the sqrt(1e-9) of their
    derivative), normal dp/dz jumps to C g'(a)/sqrt(r^2 - a^2) outside (docs/theory/axisymmetric.md (A26)), tangential
    dp/dz ~ -C_T x a g'(a)/(r^2 sqrt(a^2 - r^2)) inside (eq. 26)."""
    a, nu, mu, c = 1.0, 0.3, 0.3, 0.5
    method = "closed" if profile.has_closed_form else "quadrature"
    pm = float(ax.mean_pressure(a, profile))
    phi = 0.4
    r_in, r_out = a * (1 - 1e-9), a * (1 + 1e-9)
    si = _s(r_in * math.cos(phi), r_in * math.sin(phi), a, c, nu, mu, profile, method)
    so = _s(r_out * math.cos(phi), r_out * math.sin(phi), a, c, nu, mu, profile, method)
    for k in KEYS:
        assert np.isfinite(si[k]) and np.isfinite(so[k])
        assert abs(si[k] - so[k]) / pm < 1e-3, k
    C = 2 * (1 + nu) / (3 * math.pi)
    gpa = float(profile.dg(a))
    d_out = ax.surface_dpdz(r_out, 0.0, a, c, nu, 0.0, profile, method=method)
    assert d_out * math.sqrt(r_out ** 2 - a ** 2) == pytest.approx(C * gpa, rel=1e-3)
    d_in_t = ax.surface_dpdz(r_in, 0.0, a, c, nu, mu, profile, method=method) - \
        ax.surface_dpdz(r_in, 0.0, a, c, nu, 0.0, profile, method=method)
    assert d_in_t * math.sqrt(a ** 2 - r_in ** 2) == pytest.approx(-mu * C * gpa, rel=1e-3)


@pytest.mark.parametrize("method", METHODS)
def test_stick_radius_limits(method):
    """c -> 0 tends to gross slip, c -> a to no tangential load (tangential part
    mu [sigma(a) - sigma(c)], docs/theory/axisymmetric.md (A34))."""
    prof = ax.paraboloid(1.0)
    a, nu, mu = 1.0, 0.3, 0.25
    rho = np.array([0.05, 0.3, 0.6, 0.95, 1.05, 2.0])
    x, y = rho * 0.8, rho * -0.6
    g = _s(x, y, a, 0.0, nu, mu, prof, method)
    g2 = _s(x, y, a, 1e-10, nu, mu, prof, method)
    n = _s(x, y, a, 0.0, nu, 0.0, prof, method)
    n2 = _s(x, y, a, a * (1 - 1e-12), nu, mu, prof, method)
    for k in KEYS:
        np.testing.assert_allclose(g2[k], g[k], rtol=0, atol=1e-9)
        np.testing.assert_allclose(n2[k], n[k], rtol=0, atol=1e-6)   # sqrt(1 - c^2/a^2) ~ 1.4e-6
    cone = ax.cone(1.0)
    for c in (1e-12, 1 - 1e-12):
        s = _s(x, y, a, c, nu, mu, cone, method)
        assert all(np.all(np.isfinite(s[k])) for k in KEYS)
    assert np.all(np.isfinite(ax.surface_dpdz(x, y, a, 1e-12, nu, mu, cone, method=method)))


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("nu", [0.0, 0.5])
def test_extreme_poisson_ratios(method, nu):
    """nu = 0 and nu = 1/2 are valid: finite values; sigma_rr + sigma_phiphi = (1+2nu) sigma_zz
    (docs/theory/axisymmetric.md (A16)) for the normal part; for nu = 1/2 the normal in-plane stresses vanish
    outside and sigma_xy vanishes at the tip of a cone; for nu = 0 the tangential sigma_yy
    vanishes (it carries a factor nu)."""
    x = np.array([0.2, 0.5, -0.7, 1.3, 3.0])
    y = np.array([0.1, -0.4, 0.3, 0.5, -1.0])
    for prof in (ax.cone(1.0), ax.paraboloid(1.0)):
        s = _s(x, y, 1.0, 0.0, nu, 0.0, prof, method)
        assert all(np.all(np.isfinite(s[k])) for k in KEYS)
        np.testing.assert_allclose(s["xx"] + s["yy"], (1 + 2 * nu) * s["zz"], rtol=1e-13, atol=1e-15)
        st = _s(x, y, 1.0, 0.3, nu, 0.4, prof, method)
        if nu == 0.0:
            np.testing.assert_allclose(st["yy"], s["yy"], rtol=0, atol=1e-15)
        else:
            out = np.hypot(x, y) > 1.0
            assert np.all(np.abs(s["xx"][out]) < 1e-16) and np.all(np.abs(s["yy"][out]) < 1e-16)
    if nu == 0.5:
        assert float(_s(0.0, 0.0, 1.0, 0.0, nu, 0.0, ax.cone(1.0), method)["xy"]) == 0.0


def _moments(B, m, lo, hi, k):
    """int_lo^hi u^k B u^m du."""
    p = k + m + 1
    return B * (hi ** p - lo ** p) / p


#: the profiles and routes held against the far-field expansions
FAR_FIELD_CASES = [("paraboloid", ax.paraboloid(1.3), "closed"), ("paraboloid", ax.paraboloid(1.3), "quadrature"),
                   ("cone", ax.cone(0.7), "closed"), ("cone", ax.cone(0.7), "quadrature"),
                   ("power_law", ax.power_law(0.5, 2.7), "quadrature")]


@pytest.mark.parametrize("name,profile,method", FAR_FIELD_CASES)
def test_far_field_against_series(name, profile, method):
    """r = 100a: against the far-field expansions (kernels expanded in (u/r)^2, 4 terms, error
    ~ (a/r)^8 relative), to 1e-10 relative to each value.  The naive Hertz F, H lose (r/a)^2 and
    (r/a)^4 digits here (docs/theory/axisymmetric.md (A93)-(A94); about 1e-8 for H at 100a)."""
    a, c, nu, mu = 1.0, 0.4, 0.3, 0.35
    r = 100.0 * a
    phi = 0.9
    x, y = r * math.cos(phi), r * math.sin(phi)
    s = _s(x, y, a, c, nu, mu, profile, method)
    expected, dp = _far_expected(profile, x, y, a, c, nu, mu)
    for k, v in expected.items():
        assert s[k] == pytest.approx(v, rel=1e-10), k
    assert s["zz"] == 0.0 and s["xz"] == 0.0
    got = ax.surface_dpdz(x, y, a, c, nu, mu, profile, method=method)
    assert got == pytest.approx(dp, rel=1e-10)


def test_documented_singular_points():
    """Exactly where the docstrings say: +-inf with a definite sign, NaN for direction-dependent
    limits, finite everywhere else on a dense grid."""
    cone, par = ax.cone(1.0), ax.paraboloid(1.0)
    for method in METHODS:
        # cone tip, normal load
        s = _s(0.0, 0.0, 1.0, 0.0, 0.3, 0.0, cone, method)
        assert s["xx"] == -np.inf and s["yy"] == -np.inf and s["zz"] == -np.inf and np.isnan(s["xy"])
        assert ax.surface_dpdz(0.0, 0.0, 1.0, 0.0, 0.3, 0.0, cone, method=method) == -np.inf
        # cone tip, gross slip: normal part dominates sigma_xx, sigma_yy; sigma_xz -inf
        s = _s(0.0, 0.0, 1.0, 0.0, 0.3, 0.3, cone, method)
        assert s["xx"] == -np.inf and s["xz"] == -np.inf and np.isnan(s["xy"])
        assert ax.surface_dpdz(0.0, 0.0, 1.0, 0.0, 0.3, 0.3, cone, method=method) == -np.inf
        assert np.isnan(ax.surface_dpdz(0.0, 0.0, 1.0, 0.0, 0.3, 1.5, cone, method=method))   # mu >= 1
        # partial slip: finite at the tip except the normal log singularity
        s = _s(0.0, 0.0, 1.0, 0.4, 0.3, 0.3, cone, method)
        assert np.isfinite(s["xz"]) and s["xz"] == pytest.approx(-0.3 * 0.5 * math.log(1 / 0.4), rel=1e-13)
        # stick edge r = c (stick side): +inf sgn(x); contact edge r = a: -inf sgn(x); 0 on x = 0
        for prof in (cone, par):
            xs = np.array([0.4, -0.4, 0.0, 1.0, -1.0, 0.0, 0.6 * 0.4])
            ys = np.array([0.0, 0.0, 0.4, 0.0, 0.0, 1.0, 0.8 * 0.4])
            dp = ax.surface_dpdz(xs, ys, 1.0, 0.4, 0.3, 0.3, prof, method=method)
            dp0 = ax.surface_dpdz(xs, ys, 1.0, 0.4, 0.3, 0.0, prof, method=method)
            assert np.all(np.isfinite(dp0))
            with np.errstate(invalid="ignore"):
                tang = dp - dp0
            assert list(np.sign(tang[:6])) == [1, -1, 0, -1, 1, 0] and np.all(np.isinf(dp[[0, 1, 3, 4]]))
            assert dp[6] == np.inf
        # paraboloid: finite everywhere, r = 0 included
        g = np.linspace(-3, 3, 121)
        X, Y = np.meshgrid(g, g)
        s = _s(X, Y, 1.0, 0.0, 0.3, 0.3, par, method)
        assert all(np.all(np.isfinite(s[k])) for k in KEYS)
        s = _s(X, Y, 1.0, 0.5, 0.3, 0.3, cone, method)
        bad = ~np.isfinite(s["xx"])
        assert np.array_equal(np.argwhere(bad), np.argwhere((X == 0) & (Y == 0)))
    # flat punch edge: unbounded stresses; its dp/dz outside finite, tangential inside edge +inf
    fp = ax.flat_punch(1.0, 0.01)
    s = ax.surface_stress(np.array([1.0, 0.6, 0.5]), np.array([0.0, 0.8, 0.0]), 1.0, 0.0, 0.3, 0.2, fp)
    assert s["zz"][0] == -np.inf and s["xx"][1] == -np.inf and s["xz"][0] == -np.inf and np.isfinite(s["xx"][2])
    assert ax.surface_dpdz(1.0, 0.0, 1.0, 0.0, 0.3, 0.2, fp) == np.inf


@pytest.mark.parametrize("kw,match", [
    (dict(nu=0.51), "nu"), (dict(nu=-0.1), "nu"), (dict(mu=-1.0), "mu"), (dict(c=1.5), "c"),
    (dict(c=-0.1), "c"), (dict(a=0.0), "a"), (dict(a=-1.0), "a"), (dict(nu=np.nan), "nu"),
])
def test_rejects_out_of_range_arguments(kw, match):
    args = dict(x=0.3, y=0.1, a=1.0, c=0.2, nu=0.3, mu=0.2) | kw
    with pytest.raises(ValueError, match=match):
        ax.surface_stress(profile=ax.cone(1.0), **args)
    with pytest.raises(ValueError, match=match):
        ax.surface_dpdz(profile=ax.paraboloid(1.0), method="quadrature", **args)


def test_rejects_bad_method_and_missing_closed_form():
    tab = ax.tabulated([0, 0.5, 1.0, 1.5], [0, 0.1, 0.4, 0.9])
    with pytest.raises(ValueError, match="tabulated.*no closed form"):
        ax.surface_stress(0.1, 0.0, 1.0, 0.0, 0.3, 0.0, tab, method="closed")
    with pytest.raises(ValueError, match="power_law.*no closed form"):
        ax.surface_dpdz(0.1, 0.0, 1.0, 0.0, 0.3, 0.0, ax.power_law(1.0, 3.0))
    with pytest.raises(ValueError, match="method"):
        ax.surface_stress(0.1, 0.0, 1.0, 0.0, 0.3, 0.0, ax.cone(1.0), method="exact")
    with pytest.raises(ValueError, match="rtol"):
        ax.surface_stress(0.1, 0.0, 1.0, 0.0, 0.3, 0.0, ax.cone(1.0), rtol=1e-17)
    with pytest.raises(ValueError, match="component"):
        ax.surface_stress(0.1, 0.0, 1.0, 0.0, 0.3, 0.0, ax.cone(1.0), components=("rr",))
    with pytest.raises(ValueError, match="exceeds the end"):
        ax.surface_stress(0.1, 0.0, 2.0, 0.0, 0.3, 0.0, tab, method="quadrature")
    with pytest.raises(ValueError, match="punch radius"):
        ax.surface_stress(0.1, 0.0, 2.0, 0.0, 0.3, 0.0, ax.flat_punch(1.0))


# -- the printed forms that cancel, and the forms the code evaluates instead -------------------------
# Each test below checks the code against a route that shares nothing with its rewrite, to a tolerance
# that the printed formula, evaluated in double precision, misses (shown in the test itself).


@pytest.mark.parametrize("method", METHODS)
def test_cone_pressure_near_edge(method):
    """sigma_zz = -p0 arccosh(a/r) keeps its relative accuracy as r -> a (docs/theory/axisymmetric.md
    (A79)): against the series arccosh(1 + e) = sqrt(2e) (1 - e/12 + 3e^2/160 - ...), e = a/r - 1.
    The paper's logarithm ln(a/r + sqrt(a^2/r^2 - 1)) loses digits like 1/sqrt(e) there."""
    a, t = 1.3, 0.6
    p0 = 0.5 * t
    for h in (1e-6, 1e-10, 1e-14):
        r = a * (1.0 - h)
        e = (a - r) / r                                   # a - r is exact here
        ref = math.sqrt(2.0 * e) * (1.0 - e / 12.0 + 3.0 * e * e / 160.0)
        got = ax.surface_stress(r, 0.0, a, 0.0, 0.3, 0.0, ax.cone(t), method=method, components=("zz",))["zz"]
        assert -float(got) / p0 == pytest.approx(ref, rel=1e-14), h
        printed = math.log(a / r + math.sqrt(a * a / (r * r) - 1.0))
        if h == 1e-14:
            assert abs(printed - ref) > 1e-6 * ref


@pytest.mark.parametrize("name,profile", [("paraboloid", ax.paraboloid(1.4)),
                                          ("power_law_2", ax.power_law(1.0 / 2.8, 2.0)),
                                          ("power_law_3", ax.power_law(0.8, 3.0)),
                                          ("tabulated_paraboloid",
                                           ax.tabulated(np.linspace(0, 1.5, 16), np.linspace(0, 1.5, 16) ** 2 / 2.8))])
def test_gross_slip_pressure_gradient_near_centre(name, profile):
    """Gross slip, smooth tip, r -> 0 on the integral route: the slip branch of eq. (26) written with
    psi (docs/theory/axisymmetric.md (A88)) against the exact tangential dp/dz = (2(1+nu)/3) mu dp/dx,
    from the pressure in closed form (no eq. 26): paraboloid p = (2/(pi R)) sqrt(a^2 - r^2); power law
    g' = B u^2: p = (B/(2 pi)) (a sqrt(a^2 - r^2) + r^2 arccosh(a/r)), so
    dp/dx = (B x/pi) (arccosh(a/r) - a/sqrt(a^2 - r^2)).  As printed, eq. (26) multiplies a bracket
    that cancels like r^2 by x/r^2: an error of eps / r (2e-8 of p_m/a at r = 1e-8 a)."""
    a, nu, mu = 1.0, 0.3, 0.35
    r = np.array([1e-8, 1e-6, 1e-4, 1e-2])
    x, y = r * math.cos(0.6), r * math.sin(0.6)
    k = 2.0 * (1.0 + nu) / 3.0 * mu
    if profile.tip_exponent == 1.0:
        R = 1.4
        ref = -k * 2.0 / (math.pi * R) * x / np.sqrt(a * a - r * r)
    else:
        B = profile.tip_coefficient
        ref = k * B * x / math.pi * (np.arccosh(a / r) - a / np.sqrt(a * a - r * r))
    scale = float(ax.mean_pressure(a, profile)) / a
    d = ax.surface_dpdz(x, y, a, 0.0, nu, mu, profile, method="quadrature", rtol=1e-12)
    d0 = ax.surface_dpdz(x, y, a, 0.0, nu, 0.0, profile, method="quadrature", rtol=1e-12)
    np.testing.assert_allclose((d - d0) / scale, ref / scale, rtol=0, atol=1e-13)
    if name == "paraboloid":
        # eq. (26) as printed, with its integral in closed form: int_r^a u g'' / sqrt(u^2-r^2) du
        # = (2/R) sqrt(a^2 - r^2)
        s = np.sqrt(a * a - r * r)
        printed = -k / math.pi * x / r ** 2 * (a * (2.0 * a / R) / s - 2.0 / R * s)
        assert abs(printed[0] - ref[0]) / scale > 1e-9


def _far_expected(profile, x, y, a, c, nu, mu):
    """Far-field expansions of the stresses and the normal dp/dz at r >> a: the kernels of eq. (25)
    and (11) expanded in (u/r)^2 (4 terms, relative error ~ (a/r)^8), moments of g' = B u^m exact."""
    r = math.hypot(x, y)
    B, m = profile.tip_coefficient, profile.tip_exponent
    coef = [1.0, 0.5, 0.375, 0.3125]                  # (1 - t)^(-1/2) = sum coef_j t^j
    J = {k: sum(cj * _moments(B, m, c, a, k + 1 + 2 * j) / r ** (2 * j + 1) for j, cj in enumerate(coef))
         for k in (0, 2)}                               # int_c^a u^k u g' / sqrt(r^2 - u^2) du
    expected = {
        "xx": -2 * mu * x / (math.pi * r ** 6) * (((1 + nu) * r ** 4 - 3 * nu * r ** 2 * y ** 2) * J[0]
                                                  - nu * (r ** 2 - 4 * y ** 2) * J[2]),
        "yy": -2 * nu * mu * x / (math.pi * r ** 6) * (3 * r ** 2 * y ** 2 * J[0] + (r ** 2 - 4 * y ** 2) * J[2]),
        "xy": -mu * y / (math.pi * r ** 6) * (((1 - 2 * nu) * r ** 4 + 6 * nu * r ** 2 * x ** 2) * J[0]
                                              + 2 * nu * (r ** 2 - 4 * x ** 2) * J[2]),
    }
    FN = float(profile.normal_force(a))
    srr = (1 - 2 * nu) * FN / (2 * math.pi * r ** 2)
    X, Y = x / r, y / r
    expected["xx"] += srr * (X * X - Y * Y)
    expected["yy"] += srr * (Y * Y - X * X)
    expected["xy"] += 2 * srr * X * Y
    d = [1.0, 1.5, 1.875, 2.1875]                     # (1 - t)^(-3/2) = sum d_j t^j
    C = 2 * (1 + nu) / (3 * math.pi)
    dp = C * sum(dj * _moments(B, m, 0.0, a, 1 + 2 * j) / r ** (2 * j + 3) for j, dj in enumerate(d))
    return expected, dp


@pytest.mark.parametrize("name,profile,method", FAR_FIELD_CASES)
def test_far_field_without_cancellation(name, profile, method):
    """r = 1e3 a ... 1e6 a: stresses and dp/dz to 1e-13 relative to each value, against the far-field
    expansions.  The printed forms cancel there (docs/theory/axisymmetric.md (A90)-(A94)): Hertz F
    and H of eq. (16)-(17) lose (r/a)^2 and (r/a)^4 digits, the cone's C - A and A^3 - C^3 of eq.
    (39)-(40) lose (r/a)^2, and the outside dp/dz of eq. (5) and (37) loses (r/a)^2 as well (a
    relative error of ~1e-7 at r = 3e4 a for each of them, checked below)."""
    a, c, nu, mu = 1.0, 0.4, 0.3, 0.35
    for rho in (1e3, 3e4, 1e6):
        x, y = rho * math.cos(0.9), rho * math.sin(0.9)
        expected, dp = _far_expected(profile, x, y, a, c, nu, mu)
        s = _s(x, y, a, c, nu, mu, profile, method)
        for k, v in expected.items():
            assert s[k] == pytest.approx(v, rel=1e-13), (rho, k)
        assert ax.surface_dpdz(x, y, a, c, nu, mu, profile, method=method) == pytest.approx(dp, rel=1e-13), rho
    if method != "closed":
        return
    # the printed forms at r = 3e4 a, against the same expansions
    r = 3e4
    s = math.sqrt(r * r - a * a)
    series = [1.0, 0.5, 0.375, 0.3125]
    if name == "paraboloid":
        F = r * r * math.atan(a / s) - a * s                          # eq. (17)
        H = 0.75 * r ** 4 * math.atan(a / s) - (a ** 3 / 2 + 0.75 * a * r * r) * s
        F_ref = 2 * sum(cj * a ** (3 + 2 * j) / (3 + 2 * j) / r ** (2 * j + 1) for j, cj in enumerate(series))
        H_ref = 2 * sum(cj * a ** (5 + 2 * j) / (5 + 2 * j) / r ** (2 * j + 1) for j, cj in enumerate(series))
        assert abs(F / F_ref - 1) > 1e-9 and abs(H / H_ref - 1) > 1e-3
        q = a / r                                                     # eq. (5): a/sqrt(r^2-a^2) - arcsin(a/r)
        assert abs((a / s - math.asin(q)) / (q ** 3 / 3 + 0.3 * q ** 5) - 1) > 1e-9
    else:
        A, Cc = math.sqrt(1 - a * a / (r * r)), math.sqrt(1 - c * c / (r * r))
        assert abs((Cc - A) / ((a * a - c * c) / (r * r) / (A + Cc)) - 1) > 1e-9     # eq. (39)-(40)
        assert abs((1 / s - 1 / r) / (a * a / (r * s * (r + s))) - 1) > 1e-9         # eq. (37)


def test_cone_stick_zone_pressure_gradient_near_centre():
    """The cone's tangential dp/dz in the stick zone, eq. (41) first branch, at r = 1e-8 a ... 1e-2 a
    (the tangential kernel alone, so that no normal part hides it): the code's factored form
    (docs/theory/axisymmetric.md (A89)) against the binomial series
    (a/sqrt(a^2 - r^2) - 1)/r^2 = sum_k>=1 binom(2k, k)/4^k r^(2k-2)/a^(2k), to 1e-13 relative.  As
    printed, (a/sqrt(a^2-r^2) - c/sqrt(c^2-r^2))/r^2 is a difference of two numbers next to 1 divided
    by r^2: no correct digit at r = 1e-8 a, 2e-4 relative error at 1e-6 a (checked below)."""
    from stressfields.physics.axisymmetric import tangential

    t, a, c, nu, mu = 0.6, 2.0, 0.8, 0.3, 0.4
    p0 = 0.5 * t
    r = np.array([1e-8, 1e-6, 1e-4, 1e-2])
    x = r * math.cos(0.3)
    k = 2 * (1 + nu) / 3 * mu * p0

    def series(rr, b):
        return sum(math.comb(2 * j, j) / 4.0 ** j * rr ** (2 * j - 2) / b ** (2 * j) for j in range(1, 12))

    ref = np.array([-k * xi * (series(ri, a) - series(ri, c)) for xi, ri in zip(x, r)])
    got = tangential.dpdz_closed(("cone", t), x, r, np.full(4, a), np.full(4, c), np.full(4, nu), np.full(4, mu))
    np.testing.assert_allclose(got, ref, rtol=1e-13, atol=0)
    printed = -k * x / r ** 2 * (a / np.sqrt(a * a - r * r) - c / np.sqrt(c * c - r * r))
    assert abs(printed[0] / ref[0] - 1) > 0.5 and abs(printed[1] / ref[1] - 1) > 1e-5
