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

from ..roots import bisect
from . import _mdr, normal
from ._validate import check_interval, check_k, check_nu, check_positive
from .material import c_N_star, c_T_star, tangential_decoupled
from .profiles import g_quad

__all__ = ["stick_radius", "stiffness_ratio", "max_tangential_displacement",
           "tangential_displacement", "force_ratio_from_displacement", "shear_traction",
           "normal_force", "stick_radius_quad", "tangential_displacement_quad",
           "max_tangential_displacement_quad", "force_ratio_quad"]


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


def shear_traction(r, a, Fx_over_muFN, *, k, nu, mu, E0, c0, n, A_n, E0_2=None, nu_2=None,
                   require_decoupled=True, rho=None):
    """Shear traction tau_x(r) = mu [p(r; a) - p(r; c)], eqs. (44)-(45), docs/theory/graded.md (G32) [pressure].

    p is the normal pressure of the body pair (c_N of eq. 46 for identical bodies).  tau = mu p in
    the slip annulus c < r < a; finite at r = c (both terms are continuous there).  Both pressures
    are evaluated at r/a against the radii 1 and c/a (``rho = r/a`` may be given instead of r), so
    that the edge distances 1 - r/a and c/a - r/a are exact.  Closed form: relative error at most
    1e-12 of the value where the two terms do not cancel (the slip annulus and gross slip); in the
    stick zone at most 1e-12 of mu p(r; a).
    """
    k_, nu_, E0_, E0_2_, nu_2_ = _pair(k, nu, E0, E0_2, nu_2, require_decoupled)
    mu = check_positive("mu", mu, allow_zero=True)
    x, s, a = normal.position(r, a, rho)
    F = check_interval("Fx_over_muFN", Fx_over_muFN, 0.0, 1.0)
    sc = s * (1.0 - F) ** (1.0 / (check_positive("n", n) + k_ + 1.0))    # stick radius in the unit of x
    mat = dict(k=k_, nu=nu_, E0=E0, c0=c0, E0_2=E0_2_, nu_2=nu_2_)
    pa = normal._pressure_at(x, s, a, mat, n, A_n)
    c = a * sc / s
    pc = np.where(np.broadcast_to(sc, np.broadcast(sc, x).shape) > 0,
                  normal._pressure_at(x, np.where(sc > 0, sc, 1.0), np.where(c > 0, c, 1.0), mat, n, A_n), 0.0)
    return mu * (pa - pc)


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
