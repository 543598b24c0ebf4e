"""Tangential contact with partial slip (Cattaneo-Mindlin) of power-law graded bodies.

Hess & Popov 2016 (Facta Univ. Mech. Eng. 14(3) 251-268), eqs. (39)-(52), and the exact
extension to f = A_n r^n, docs/theory/graded.md (G30)-(G37):
    c/a = (1 - F_x/(mu F_N))^(1/(n+k+1)),   delta_x = mu (c_N/c_T) kappa A_n (a^n - c^n),
    tau_x(r) = mu [p(r; a) - p(r; c)]                                          (45)
(n = 2, A_n = 1/(2R): eqs. 49-51; Holl ratio nu = 1/(2+k): eq. 52).

Bodies: body 1 is graded (E0, nu, k, c0).  Body 2 defaults to an identical body (``E0_2=None``,
eqs. 46-47); ``E0_2=inf`` is rigid; a finite E0_2 with nu_2 an elastic graded body of the same k
and c0.  The MDR solution is exact only where the normal and tangential problems decouple (see
:func:`material.tangential_decoupled`); otherwise the functions raise ``ValueError`` unless
``require_decoupled=False`` asks for the uncoupled approximation (docs/theory/graded.md (G37)).
Units: consistent system; delta_x in length, tau in pressure.  Every argument broadcasts.
"""
from __future__ import annotations

import numpy as np

from .. import quadrature
from ..roots import bisect
from . import _mdr, normal
from ._validate import check_interval, check_k, check_nu, check_positive
from .material import c_N_star, c_T_star, tangential_decoupled
from .profiles import dg_quad, g_quad

__all__ = ["stick_radius", "stiffness_ratio", "max_tangential_displacement",
           "tangential_displacement", "force_ratio_from_displacement", "shear_traction",
           "normal_force", "stick_radius_quad", "tangential_displacement_quad",
           "max_tangential_displacement_quad", "force_ratio_quad", "slip_width", "stick_zone_integral",
           "slip_width_quad", "stick_zone_integral_quad"]


def _pair(k, nu, E0, E0_2, nu_2, require_decoupled):
    """Resolve body 2 and enforce the decoupling condition of sec. 5."""
    k = check_k(k)
    nu = check_nu(nu, k)
    if E0_2 is None:                   # identical bodies (eqs. 46-47)
        E0_ = 1.0 if E0 is None else E0
        E0_2_, nu_2_ = E0_, nu
    else:
        if E0 is None and not np.all(np.isinf(E0_2)):
            raise ValueError("E0 is required when an elastic body 2 (finite E0_2) is given")
        E0_ = 1.0 if E0 is None else E0
        E0_2_, nu_2_ = E0_2, nu_2
    if require_decoupled and E0_2 is not None:
        ok = tangential_decoupled(k, nu, E0=E0_, E0_2=E0_2_, nu_2=nu_2_)
        if not np.all(ok):
            kb, nub = (np.broadcast_to(v, ok.shape)[~ok].flat[0] for v in (k, nu))
            rigid = np.all(np.isinf(E0_2))
            raise ValueError(
                f"nu = {float(nub)!r} (k = {float(kb)!r}) is outside the allowed range for which the normal and "
                f"tangential problems decouple: "
                + ("with a rigid body 2 it must be nu = 1/(2+k) = " + f"{1 / (2 + float(kb)):.12g}" if rigid else
                   "two elastic bodies must be identical or both have nu = 1/(2+k) = " + f"{1 / (2 + float(kb)):.12g}")
                + " (Hess & Popov 2016, sec. 5); pass require_decoupled=False for the uncoupled approximation")
    return k, nu, E0_, E0_2_, nu_2_


def stick_radius(a, Fx_over_muFN, *, k, n=2.0):
    """Stick radius c(a, F_x/(mu F_N)) = a (1 - F_x/(mu F_N))^(1/(n+k+1)), eq. (51), docs/theory/graded.md (G33).

    Material independent.  F_x/(mu F_N) in [0, 1]; 1 is the onset of gross slip (c = 0).
    """
    a = check_positive("a", a)
    F = check_interval("Fx_over_muFN", Fx_over_muFN, 0.0, 1.0)
    k = check_k(k)
    n = check_positive("n", n)
    return a * (1.0 - F) ** (1.0 / (n + k + 1.0))


def stiffness_ratio(*, k, nu, E0=None, E0_2=None, nu_2=None, require_decoupled=True):
    """c_N/c_T of the body pair: h_N/((1-nu^2) h_T) for identical bodies (eqs. 46-47, 49). Dimensionless."""
    k, nu, E0_, E0_2_, nu_2_ = _pair(k, nu, E0, E0_2, nu_2, require_decoupled)
    return c_N_star(k, nu, E0_, 1.0, E0_2_, nu_2_) / c_T_star(k, nu, E0_, 1.0, E0_2_, nu_2_)


def max_tangential_displacement(a, *, k, nu, mu, n, A_n, E0=None, E0_2=None, nu_2=None,
                                require_decoupled=True):
    """delta_x,max = mu (c_N/c_T) kappa A_n a^n at the onset of gross slip, eq. (50), docs/theory/graded.md (G34).

    At nu = 1/(2+k) for both bodies, n = 2: (3+k)/2 mu a^2/R, eq. (52), docs/theory/graded.md (G36).  Units of length.
    """
    ratio = stiffness_ratio(k=k, nu=nu, E0=E0, E0_2=E0_2, nu_2=nu_2, require_decoupled=require_decoupled)
    mu = check_positive("mu", mu, allow_zero=True)
    return mu * ratio * normal.depth(a, k=k, n=n, A_n=A_n)


def tangential_displacement(a, Fx_over_muFN, *, k, nu, mu, n, A_n, E0=None, E0_2=None, nu_2=None,
                            require_decoupled=True):
    """Relative tangential displacement delta_x = mu (c_N/c_T) kappa A_n (a^n - c^n) [length].

    Eq. (49), docs/theory/graded.md (G34).
    """
    dmax = max_tangential_displacement(a, k=k, nu=nu, mu=mu, n=n, A_n=A_n, E0=E0, E0_2=E0_2,
                                       nu_2=nu_2, require_decoupled=require_decoupled)
    F = check_interval("Fx_over_muFN", Fx_over_muFN, 0.0, 1.0)
    # 1 - (c/a)^n without cancellation for small loads: -expm1(n/(n+k+1) log1p(-F)), docs/theory/graded.md (G41)
    k = np.asarray(k, float)
    with np.errstate(divide="ignore"):           # F = 1: log1p(-1) = -inf, expm1(-inf) = -1 exactly
        return dmax * -np.expm1(n / (n + k + 1.0) * np.log1p(-F))


def force_ratio_from_displacement(delta_over_delta_max, *, k, n=2.0):
    """F_x/(mu F_N) = 1 - (1 - delta_x/delta_x,max)^((n+k+1)/n), eq. (51) (second form), docs/theory/graded.md (G35)."""
    D = check_interval("delta_over_delta_max", delta_over_delta_max, 0.0, 1.0)
    k = check_k(k)
    n = check_positive("n", n)
    with np.errstate(divide="ignore"):
        return -np.expm1((n + k + 1.0) / n * np.log1p(-D))


def normal_force(a, *, k, nu, E0, c0, n, A_n, E0_2=None, nu_2=None):
    """Normal force F_N(a) of the body pair (identical bodies by default: half the rigid-indenter value)."""
    k_, nu_, E0_, E0_2_, nu_2_ = _pair(k, nu, E0, E0_2, nu_2, False)
    return normal.normal_force(a, k=k_, nu=nu_, E0=E0, c0=c0, n=n, A_n=A_n, E0_2=E0_2_, nu_2=nu_2_)


def slip_width(Fx_over_muFN, *, k, n=2.0):
    """(c/a, 1 - c/a) of (G33), docs/theory/graded.md (G46): both without rounding.

    log(c/a) = log1p(-F)/(n+k+1) and 1 - c/a = -expm1(log(c/a)): forming 1 - c/a from the rounded
    c/a would lose all digits of the slip width at F = 1e-16 (and 4 of 12 at F = 1e-12).
    """
    log_s = _log_stick(Fx_over_muFN, k, n)
    return np.exp(log_s), -np.expm1(log_s)


def _log_stick(Fx_over_muFN, k, n):
    """log(c/a) = log1p(-F)/(n+k+1), (G33); -inf at F = 1."""
    F = check_interval("Fx_over_muFN", Fx_over_muFN, 0.0, 1.0)
    with np.errstate(divide="ignore"):          # F = 1: log1p(-1) = -inf, c/a = 0, 1 - c/a = 1
        return np.log1p(-F) / (check_positive("n", n) + check_k(k) + 1.0)


def _stick_distances(rho, e, sc, D):
    """(c/a - rho, 1 - rho^2, c^2/a^2 - rho^2) for rho < c/a, without cancellation: c/a - rho as
    (1 - rho) - (1 - c/a) where c/a > 1/2 (there 1 - c/a is small and exact, 1 - rho given exactly),
    else as c/a - rho (there c/a carries the relative error of its logarithm only)."""
    delta = np.where(sc > 0.5, e - D, sc - rho)
    return delta, e * (1.0 + rho), delta * (sc + rho)


def _power_width(A, B, q, AmB):
    """A^q - B^q (A > B >= 0) with full relative accuracy also for A - B << B, given A - B exactly:
    B^q expm1(q log1p((A-B)/B)) where B > A/2, the plain difference elsewhere (there it keeps at
    least 1 - 2^-q >= 0.29 of A^q, so no digit is lost)."""
    close = B > 0.5 * A
    Bs = np.where(close, B, 1.0)
    return np.where(close, Bs ** q * np.expm1(q * np.log1p(AmB / Bs)), A ** q - B ** q)


def stick_zone_integral(rho, Fx_over_muFN, *, k, n, one_minus_rho=None):
    """J = int_c^1 xi^(n-1) (xi^2 - rho^2)^(-(1-k)/2) dxi (c = c/a, 0 <= rho < c), docs/theory/graded.md (G45).

    The stick-zone traction is tau = mu (c_N* n kappa A_n / pi) a^(n+k-1) J: the one integral of
    (G32), not the difference of two pressures (whose relative error grows like eps/F for small
    F = F_x/(mu F_N)).  With xi^2 - rho^2 = u^(2/(1+k)) the kernel is removed exactly:
    J = (1/(1+k)) int_{B^q}^{A^q} (rho^2 + u^(1/q))^((n-2)/2) du, q = (1+k)/2, A = 1 - rho^2,
    B = c^2 - rho^2 (G45), whose width A^q - B^q is formed without cancellation (G46).  n = 2:
    the integrand is 1 (exact); otherwise tanh-sinh to the closed-form tolerance; rho = 0:
    (1 - c^(n+k-1))/(n+k-1), and ln(a/c) at n + k = 1 (G47).  ``one_minus_rho`` (exact) may be
    given with rho.  Closed form: relative error at most 1e-12 of |value|.  Dimensionless.
    """
    rho = check_positive("rho", rho, allow_zero=True)
    k = check_k(k)
    n = check_positive("n", n)
    log_s = _log_stick(Fx_over_muFN, k, n)
    sc, D = np.exp(log_s), -np.expm1(log_s)
    e = 1.0 - rho if one_minus_rho is None else np.asarray(one_minus_rho, float)
    rho, e, sc, D, log_s, k, n = np.broadcast_arrays(rho, e, sc, D, log_s, k, n)
    out = np.full(rho.shape, np.nan)            # rho >= c: outside the stick zone, not defined here
    centre = (rho == 0.0) & (sc > 0.0)
    if centre.any():
        m = (n[centre] - 1.0) + k[centre]       # n - 1 first: exact near n + k = 1
        ls = log_s[centre]                      # not log(c/a) of the rounded c/a: 1 - c/a may be ~F
        ms = np.where(m == 0.0, 1.0, m)
        out[centre] = np.where(m == 0.0, -ls, -np.expm1(m * ls) / ms)
    inner = (rho > 0.0) & (rho < sc)
    if inner.any():
        out[inner] = _stick_u_integral(rho[inner], e[inner], sc[inner], D[inner], k[inner], n[inner])
    return out


def _stick_u_integral(rho, e, sc, D, k, n):
    """(G45) at 0 < rho < c in the u form (see :func:`stick_zone_integral`)."""
    q = 0.5 * (1.0 + k)
    _, A, B = _stick_distances(rho, e, sc, D)
    W = _power_width(A, B, q, D * (1.0 + sc))     # A - B = 1 - c^2 = (1 - c)(1 + c)
    mean = np.ones(rho.shape)
    curved = n != 2.0
    if curved.any():
        mean[curved] = _mean_power(rho[curved], B[curved] ** q[curved], W[curved], q[curved], n[curved])
    return W * mean / (1.0 + k)


def _mean_power(rho, Bq, W, q, n):
    """int_0^1 (rho^2 + u^(1/q))^((n-2)/2) ds, u = B^q + W s, by tanh-sinh (blocks of points)."""
    out = np.empty(rho.shape)
    for s in range(0, rho.size, normal._BLOCK):
        b = [v[s:s + normal._BLOCK, None] for v in (rho, Bq, W, q, n)]

        def integrand(t, tc, rho=b[0], Bq=b[1], W=b[2], q=b[3], n=b[4]):
            return (rho * rho + (Bq + W * t) ** (1.0 / q)) ** (0.5 * (n - 2.0))

        out[s:s + normal._BLOCK] = quadrature.integrate(integrand, rtol=normal._COSH_RTOL, level=4, max_level=11)
    return out


def shear_traction(r, a, Fx_over_muFN, *, k, nu, mu, E0, c0, n, A_n, E0_2=None, nu_2=None,
                   require_decoupled=True, rho=None):
    """Shear traction tau_x(r) = mu [p(r; a) - p(r; c)], eqs. (44)-(45), docs/theory/graded.md (G32) [pressure].

    p is the normal pressure of the body pair (c_N of eq. 46 for identical bodies).  tau = mu p in
    the slip annulus c < r < a and in gross slip; in the stick zone r < c the one integral
    mu (c_N* n kappa A_n / pi) a^(n+k-1) J of :func:`stick_zone_integral` ((G45)-(G47)), never the
    difference of the two pressures, finite also at r = 0 where n + k <= 1 (G47).  The point is
    taken as r/a (``rho = r/a`` may be given instead of r), so that the edge distances 1 - r/a and
    c/a - r/a are exact.  Closed form: relative error at most 1e-12 of |value| everywhere the value
    is finite, far field and next to edges included; +inf only at r = 0 in gross slip (F = 1)
    where n + k <= 1.
    """
    k_, nu_, E0_, E0_2_, nu_2_ = _pair(k, nu, E0, E0_2, nu_2, require_decoupled)
    mu = check_positive("mu", mu, allow_zero=True)
    x, s, a = normal.position(r, a, rho)
    n = check_positive("n", n)
    sc, _ = slip_width(Fx_over_muFN, k=k_, n=n)
    mat = dict(k=k_, nu=nu_, E0=E0, c0=c0, E0_2=E0_2_, nu_2=nu_2_)
    rel = x / s                                   # exact where rho is given (s = 1)
    stick = np.broadcast_to(rel < sc, np.broadcast(rel, sc).shape)
    out = mu * normal._pressure_at(x, s, a, mat, n, A_n)
    if np.any(stick):
        e = (s - x) / s                           # 1 - r/a, exact where rho is given
        J = stick_zone_integral(np.where(stick, rel, 0.0), Fx_over_muFN, k=k_, n=n,
                                one_minus_rho=np.where(stick, e, 1.0))
        tau = mu * normal._prefactor(a, mat, n, A_n) * J
        out = np.where(stick, tau, out)
    return out


# --------------------------------------------------------------------------- quadrature route

def stick_radius_quad(a, Fx_over_muFN, profile, *, k, nu, E0, c0=1.0, E0_2=None, nu_2=None,
                      require_decoupled=True, rtol=1e-10):
    """Stick radius by vectorised bisection on eqs. (41)-(43) with quadrature; any profile object.

    F_x(c) = 2 int_0^c c_T(x) delta_x dx + 2 mu int_c^a c_N(x) u_1D(x) dx with
    delta_x = mu c_N(c) u_1D(c)/c_T(c) (eq. 42) and u_1D = g(a) - g(x), g by quadrature of eq. (5).
    """
    k_, nu_, E0_, E0_2_, nu_2_ = _pair(k, nu, E0, E0_2, nu_2, require_decoupled)
    a = check_positive("a", a)
    F = check_interval("Fx_over_muFN", Fx_over_muFN, 0.0, 1.0)
    if hasattr(profile, "dg_panels"):      # tabulated: (G48) on the shared knot panels
        return _tabulated_slip(a, F, profile, k_, rtol)[0] * a
    cN = c_N_star(k_, nu_, E0_, c0, E0_2_, nu_2_)
    cT = c_T_star(k_, nu_, E0_, c0, E0_2_, nu_2_)
    a, F, k_, cN, cT = np.broadcast_arrays(a, F, k_, cN, cT)
    u1d = normal._u1d(profile, rtol)
    d = g_quad(a, profile, k=k_, rtol=rtol)
    total = _mdr.foundation_integral(a, u1d, {"k": k_, "d": d}, rtol, profile.breaks)
    FN_over_mu = 2.0 * cN * total

    def ratio(s):                        # F_x/(mu F_N) at stick radius c = s a
        c = s * a
        uc = d - g_quad(c, profile, k=k_, rtol=rtol)
        stick = 2.0 * cN * uc * c ** (1.0 + k_) / (1.0 + k_)          # 2 int_0^c c_T delta_x / mu
        inner = _mdr.foundation_integral(c, u1d, {"k": k_, "d": d}, rtol, profile.breaks)
        return (stick + 2.0 * cN * (total - inner)) / FN_over_mu

    # bisection to 2^-56 in c/a; the ratio decreases from 1 (c = 0) to 0 (c = a)
    return bisect(lambda s: ratio(s) > F, np.zeros(a.shape), np.ones(a.shape), 56) * a


def tangential_displacement_quad(a, Fx_over_muFN, profile, *, k, nu, mu, E0, c0=1.0, E0_2=None,
                                 nu_2=None, require_decoupled=True, rtol=1e-10):
    """delta_x = mu c_N(c) u_1D(c)/c_T(c) (eq. 42) at the stick radius of :func:`stick_radius_quad`."""
    c = stick_radius_quad(a, Fx_over_muFN, profile, k=k, nu=nu, E0=E0, c0=c0, E0_2=E0_2, nu_2=nu_2,
                          require_decoupled=require_decoupled, rtol=rtol)
    k_, nu_, E0_, E0_2_, nu_2_ = _pair(k, nu, E0, E0_2, nu_2, require_decoupled)
    ratio = c_N_star(k_, nu_, E0_, c0, E0_2_, nu_2_) / c_T_star(k_, nu_, E0_, c0, E0_2_, nu_2_)
    mu = check_positive("mu", mu, allow_zero=True)
    return mu * ratio * (g_quad(a, profile, k=k_, rtol=rtol) - g_quad(c, profile, k=k_, rtol=rtol))


def max_tangential_displacement_quad(a, profile, *, k, nu, mu, E0=None, E0_2=None, nu_2=None,
                                     require_decoupled=True, rtol=1e-10):
    """delta_x,max = mu (c_N/c_T) g(a) (eq. 50, docs/theory/graded.md (G34)) with g(a) by quadrature."""
    ratio = stiffness_ratio(k=k, nu=nu, E0=E0, E0_2=E0_2, nu_2=nu_2, require_decoupled=require_decoupled)
    return mu * ratio * normal.depth_quad(a, profile, k=k, rtol=rtol)


def _moment_quad(a, lo_off, hi_off, profile, k, rtol, from_edge):
    """int g'(a xi) xi^(1+k) dxi over xi in [1 - hi_off, 1 - lo_off] (from_edge) or [lo_off, hi_off],
    split at the profile's break points; the offsets are kept exact (no 1 - xi is formed)."""
    a, lo_off, hi_off, k = (v[..., None] for v in np.broadcast_arrays(a, lo_off, hi_off, k))
    cuts = [(1.0 - b / a) if from_edge else b / a for b in np.asarray(profile.breaks, float)]
    edges = [lo_off] + [np.clip(c, lo_off, hi_off) for c in cuts] + [hi_off]
    total = 0.0
    for x0, x1 in zip(edges[:-1], edges[1:]):
        L = x1 - x0

        def integrand(t, tc, x0=x0, L=L):
            off = x0 + L * t
            xi = 1.0 - off if from_edge else off
            # below xi = 1e-100 the integrand ~ xi^(n+k) adds < 1e-100 of the total, and f''(x t) inside
            # g' overflows for x t < ~1e-200 (n = 0.4: measured failure of dg_quad at x = 1e-200)
            live = xi > 1e-100
            xs = np.where(live, xi, 1.0)
            return np.where(live, L * dg_quad(a * xs, profile, k=k, rtol=rtol) * xs ** (1.0 + k), 0.0)

        total = total + quadrature.integrate(integrand, rtol=rtol)
    return total


def slip_width_quad(a, Fx_over_muFN, profile, *, k, rtol=1e-10):
    """(c/a, 1 - c/a) for any profile object, each with relative error near rtol, docs/theory/graded.md (G48).

    1 - F = F_N(c)/F_N(a) and F F_N(a) = (2 c_N*/(1+k)) int_c^a g'(x) x^(1+k) dx, both without a
    difference: bisection in log(1 - c/a) on the second where F <= 1/2 (a thin slip annulus), in
    log(c/a) on the first elsewhere (a small stick zone); 1074 bits of exponent range / 2^60 steps.
    """
    F = check_interval("Fx_over_muFN", Fx_over_muFN, 0.0, 1.0)
    k = check_k(k)
    a = check_positive("a", a)
    if hasattr(profile, "dg_panels"):      # tabulated: on the shared knot panels
        return _tabulated_slip(a, F, profile, k, rtol)
    a, F, k = np.broadcast_arrays(a, F, k)
    ones = np.ones(a.shape)
    total = _moment_quad(a, np.zeros(a.shape), ones, profile, k, rtol, from_edge=False)
    tiny = np.full(a.shape, 1e-300)
    thin = F <= 0.5
    D = bisect(lambda w: _moment_quad(a, 0.0 * w, w, profile, k, rtol, True) < F * total, tiny, ones, 60,
               geometric=True)
    sc = bisect(lambda s: _moment_quad(a, 0.0 * s, s, profile, k, rtol, False) < (1.0 - F) * total, tiny, ones,
                60, geometric=True)
    D = np.where(F == 0.0, 0.0, np.where(thin, D, 1.0 - sc))
    sc = np.where(F == 1.0, 0.0, np.where(thin, 1.0 - D, sc))
    return sc, D


def _tabulated_slip(a, F, profile, k, rtol):
    """(c/a, 1 - c/a) of a tabulated profile, (G48) as (G56): 1 - F = M(c)/M(a) with M(c) = int_0^c g'(x) x^(1+k) dx
    (F_N(c) up to a constant, (G32) by parts), on the knot panels of ``Tabulated.dg_panels``.

    The panel sums of w g' x^(1+k) on those nodes (``normal.panel_moments``: their order from rtol,
    (G55); computed once per (a, k, order), shared with the pressure and the normal force) give M at
    every panel edge, from below and from above;
    the panel holding c is found from them, and c inside it by bisection on the partial panel
    integral from the panel's lower edge (the panels' smoothing map x = e + (c - e)(3w^2 - 2w^3)
    and the exact g' of ``dg_fast``).  As in ``slip_width_quad``, F <= 1/2 (a thin slip annulus)
    is solved for int_c^a = F M(a) and 1 - c/a formed from the edge distances; F > 1/2 for
    M(c) = (1 - F) M(a), geometrically in the first panel (a small stick zone).  ceil(log2(100/rtol))
    halvings (20 at rtol 1e-4, 40 at 1e-10): the cost falls as rtol loosens, with the order."""
    a, F, k = (np.asarray(v, float) for v in np.broadcast_arrays(a, F, k))
    sc, D = np.empty(a.shape), np.empty(a.shape)
    for ak in np.unique(np.stack([a.ravel(), k.ravel()], axis=-1), axis=0):
        m = (a == ak[0]) & (k == ak[1])
        sc[m], D[m] = _slip_at(float(ak[0]), float(ak[1]), F[m], profile, rtol)
    return sc, D


def _slip_at(a, k, F, profile, rtol):
    """``_tabulated_slip`` for one contact radius a and one k (F a 1-D array)."""
    order, S = normal.panel_moments(profile, a, k, rtol)
    edges = profile.panel_edges(a)
    below = np.concatenate([[0.0], np.cumsum(S)])                  # M at the edges
    above = np.concatenate([np.cumsum(S[::-1])[::-1], [0.0]])       # M(a) - M, summed from the top
    total = below[-1]
    thin = F <= 0.5
    last = S.size - 1
    i = np.where(thin, np.searchsorted(-above, -F * total, side="right") - 1,
                 np.searchsorted(below, (1.0 - F) * total, side="right") - 1)
    i = np.clip(i, 0, last)
    lo, width = edges[i], edges[i + 1] - edges[i]
    u, W = quadrature.gauss_legendre(int(order))
    smooth, dsmooth = u * u * (3.0 - 2.0 * u), 6.0 * u * (1.0 - u) * W

    def partial(s, sel):
        # int over [e_i, e_i + s (e_i+1 - e_i)] of g' x^(1+k), the smoothing map on the partial panel
        span = (s * width[sel])[:, None]
        x = lo[sel, None] + span * smooth
        return np.sum(span * dsmooth * profile.dg_fast(x, k) * x ** (1.0 + k), axis=1)

    steps = min(56, int(np.ceil(np.log2(100.0 / rtol))))
    s = np.empty(F.shape)
    for sel, geometric in ((thin, False), (~thin & (i > 0), False), (~thin & (i == 0), True)):
        idx = np.flatnonzero(sel & (F > 0.0) & (F < 1.0))
        if idx.size == 0:
            continue
        if thin[idx[0]]:
            # above[i+1] + S_i - partial(c) = F M(a): the left side falls as c rises
            def up(x, idx=idx):
                return above[i[idx] + 1] + S[i[idx]] - partial(x, idx) > F[idx] * total
        else:
            def up(x, idx=idx):
                return below[i[idx]] + partial(x, idx) < (1.0 - F[idx]) * total
        lo_s = np.full(idx.size, 1e-300 if geometric else 0.0)
        n = steps + (int(np.ceil(np.log2(690.0))) if geometric else 0)   # 690: ln(1e300)
        s[idx] = bisect(up, lo_s, np.ones(idx.size), n, geometric=geometric)
    # c = e_i + s (e_i+1 - e_i); 1 - c/a from the edge distance a - e_i+1 (exact for the cuts near a)
    D = ((a - edges[i + 1]) + (1.0 - s) * width) / a
    sc = (lo + s * width) / a
    sc = np.where(F <= 0.0, 1.0, np.where(F >= 1.0, 0.0, sc))
    D = np.where(F <= 0.0, 0.0, np.where(F >= 1.0, 1.0, D))
    return sc, D


def stick_zone_integral_quad(rho, sc, D, a, profile, *, k, rtol=1e-10, one_minus_rho=None):
    """int_c^1 g'(a xi) (xi^2 - rho^2)^(-(1-k)/2) dxi (0 <= rho < c = c/a) by tanh-sinh, (G45) for any
    profile: (1/(1+k)) int_{B^q}^{A^q} g'(a xi)/xi du with xi = sqrt(rho^2 + u^(1/q)), split at the
    profile's break points; the width A^q - B^q as in (G46).  NaN outside the stick zone."""
    rho, sc, D, a, k = np.broadcast_arrays(*(np.asarray(v, float) for v in (rho, sc, D, a, k)))
    e = 1.0 - rho if one_minus_rho is None else np.broadcast_to(np.asarray(one_minus_rho, float), rho.shape)
    out = np.full(rho.shape, np.nan)
    m = rho < sc
    if not m.any():
        return out
    rho, e, sc, D, a, k = (v[m][:, None] for v in (rho, e, sc, D, a, k))
    q = 0.5 * (1.0 + k)
    _, A, B = _stick_distances(rho, e, sc, D)
    W = _power_width(A, B, q, D * (1.0 + sc))
    Bq = B ** q
    cuts = [np.clip(np.maximum(b * b / (a * a) - rho * rho, 0.0) ** q - Bq, 0.0, W)
            for b in np.asarray(profile.breaks, float)]
    edges = [np.zeros_like(W)] + cuts + [W]
    total = 0.0
    for x0, x1 in zip(edges[:-1], edges[1:]):
        L = x1 - x0

        def integrand(t, tc, x0=x0, L=L):
            xi = np.sqrt(rho * rho + (Bq + x0 + L * t) ** (1.0 / q))
            return L * dg_quad(a * xi, profile, k=k, rtol=rtol) / xi

        total = total + quadrature.integrate(integrand, rtol=rtol)
    out[m] = total / (1.0 + k[:, 0])
    return out


def force_ratio_quad(a, delta_x, profile, *, k, nu, mu, E0=None, E0_2=None, nu_2=None,
                     require_decoupled=True, rtol=1e-10):
    """F_x/(mu F_N) under an imposed displacement delta_x, any profile object (1 beyond delta_x,max).

    Inverts delta_x = delta_x,max (1 - g(c)/g(a)) (eq. 42, docs/theory/graded.md (G30)) for the stick
    radius c by bisection, then F_x/(mu F_N) = 1 - F_N(c)/F_N(a) ((G32) integrated).  F_N(c)/F_N(a)
    does not depend on the elastic constants: nominal ones are used there.
    """
    dmax = max_tangential_displacement_quad(a, profile, k=k, nu=nu, mu=mu, E0=E0, E0_2=E0_2, nu_2=nu_2,
                                            require_decoupled=require_decoupled, rtol=rtol)
    D = np.minimum(delta_x / dmax, 1.0)
    target = normal.depth_quad(a, profile, k=k, rtol=rtol) * (1.0 - D)
    s = bisect(lambda s: normal.depth_quad(np.maximum(s * a, 1e-300), profile, k=k, rtol=rtol) < target,
               np.zeros(np.shape(target)), np.ones(np.shape(target)), 56)
    c = s * a
    nominal = dict(nu=0.0, E0=1.0, c0=1.0)
    fa = normal.normal_force_quad(a, profile, k=k, **nominal, rtol=rtol)
    fc = normal.normal_force_quad(np.where(c > 0, c, a), profile, k=k, **nominal, rtol=rtol)
    return np.where(D >= 1.0, 1.0, 1.0 - np.where(c > 0, fc, 0.0) / fa)
