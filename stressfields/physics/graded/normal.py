"""Non-adhesive normal contact of a rigid axisymmetric indenter and a power-law graded half-space.

Hess & Popov 2016 (Facta Univ. Mech. Eng. 14(3) 251-268), eqs. (10)-(26) and Table 2, for the
power-law profile f = A_n r^n (n = 2, A_2 = 1/(2R): paraboloid, eqs. 16-23; n = 1,
A_1 = tan(theta): cone, Table 2; generic n: docs/theory/graded.md (G15)-(G21)), and the quadrature route
of the MDR rules for any profile object (``profiles.PowerLaw``, ``profiles.Tabulated``).

Units: any consistent system (SI by default).  a, r, d, u_z in length; E0 in pressure; c0 in
length; F_N in force; p in pressure.  ``r`` is the absolute radial coordinate (not r/a).
Material: E(z) = E0 (z/c0)^k; the counter-body is rigid (``E0_2 = inf``, eq. 21) unless E0_2
(and nu_2) are given, eq. (14).  Every argument broadcasts (numpy rules), including k and nu.
"""
from __future__ import annotations

import numpy as np
from scipy.special import betainc

from .. import quadrature
from . import _mdr
from ._validate import check_k, check_positive
from .material import c_N_star, cos_half_pi_k
from .profiles import dg_quad, g_quad, kappa

__all__ = ["depth", "normal_force", "pressure", "surface_displacement", "pressure_shape",
           "depth_quad", "normal_force_quad", "pressure_quad", "surface_displacement_quad"]

#: Tolerance of the adaptive tanh-sinh evaluation of the cosh-form pressure integral; tanh-sinh
#: roughly doubles the correct digits per halving, so the returned value is near round-off.
_COSH_RTOL = 1e-13
_BLOCK = 2048          # points per block: bounds the (points x nodes) work array to ~30 MB


def _power_law(n, A_n):
    return check_positive("n", n), check_positive("A_n", A_n)


def _radii(r, a):
    return check_positive("r", r, allow_zero=True), check_positive("a", a)


def depth(a, *, k, n, A_n):
    """Indentation depth d(a) = g(a) = kappa(n,k) A_n a^n [length].

    Eqs. (11), (18), Table 2, docs/theory/graded.md (G15).
    """
    n, A_n = _power_law(n, A_n)
    return kappa(n, k) * A_n * check_positive("a", a) ** n


def normal_force(a, *, k, nu, E0, c0, n, A_n, E0_2=np.inf, nu_2=None):
    """Normal force F_N(a) = 2 c_N* n kappa A_n a^(n+k+1) / ((1+k)(n+k+1)), eqs. (12), (19), Table 2,
    docs/theory/graded.md (G16).

    Units of E0 * length^2.
    """
    n, A_n = _power_law(n, A_n)
    cN = c_N_star(k, nu, E0, c0, E0_2, nu_2)
    k = np.asarray(k, float)
    a = check_positive("a", a)
    return 2.0 * cN * n * kappa(n, k) * A_n * a ** (n + k + 1.0) / ((1.0 + k) * (n + k + 1.0))


def _log_cosh(t):
    return t + np.log1p(np.exp(-2.0 * t)) - np.log(2.0)


def _log_sinhc(t):
    # log(sinh(t)/t), accurate for all t >= 0 (both branches evaluated on safe arguments)
    small = np.minimum(t, 1.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        direct = np.where(small > 0.0, np.log(np.sinh(small) / np.where(small > 0, small, 1.0)), 0.0)
    big = np.maximum(t, 1.0)
    asympt = big + np.log1p(-np.exp(-2.0 * big)) - np.log(2.0) - np.log(big)
    return np.where(t < 1.0, direct, asympt)


def _cosh_integral(T, n, k):
    """Phi = int_0^T (cosh t/cosh T)^(n-1) (sinh t/cosh T)^k dt for T > 0 (cosh form, docs/theory/graded.md (G18)).

    The substitution t = T u^(1/(1+k)) removes the t^k end-point behaviour; the integrand is
    assembled in logarithms so that large T (r -> 0) cannot overflow.
    """
    T, n, k = (np.ravel(v) for v in np.broadcast_arrays(T, n, k))
    out = np.empty(T.shape)
    for s in range(0, T.size, _BLOCK):
        Tb, nb, kb = (v[s:s + _BLOCK, None] for v in (T, n, k))
        lcT = _log_cosh(Tb)
        lpre = (1.0 + kb) * np.log(Tb) - np.log1p(kb)

        def integrand(u, uc, Tb=Tb, nb=nb, kb=kb, lcT=lcT, lpre=lpre):
            t = Tb * u ** (1.0 / (1.0 + kb))
            return np.exp(lpre + (nb - 1.0) * (_log_cosh(t) - lcT) + kb * (_log_sinhc(t) - lcT))

        out[s:s + _BLOCK] = quadrature.integrate(integrand, rtol=_COSH_RTOL, level=4, max_level=11)
    return out


def pressure_shape(rho, *, k, n):
    """Dimensionless pressure Phi(rho) with p = (c_N* n kappa A_n / pi) a^(n+k-1) Phi(r/a).

    Phi(rho) = int_0^arccosh(1/rho) (cosh t rho)^(n-1) (sinh t rho)^k dt for 0 < rho < 1 (cosh
    form of docs/theory/graded.md (G18), equal to B(1 - rho^2; (1+k)/2, (1-n-k)/2)/2 * rho^(n+k-1));
    Phi(0) = 1/(n+k-1) for n+k > 1 and +inf otherwise; Phi = 0 for rho >= 1.
    For n = 2: Phi = (1 - rho^2)^((1+k)/2)/(1+k), i.e. eq. (22).
    """
    rho = check_positive("rho", rho, allow_zero=True)
    return _shape(rho, 1.0, check_k(k), check_positive("n", n))


def _shape(r, a, k, n):
    r, a, k, n = np.broadcast_arrays(np.asarray(r, float), np.asarray(a, float), k, n)
    out = np.zeros(r.shape)
    centre = r == 0.0
    nk1 = n[centre] + k[centre] - 1.0
    with np.errstate(divide="ignore"):
        out[centre] = np.where(nk1 > 0.0, 1.0 / np.where(nk1 > 0, nk1, 1.0), np.inf)
    m = (r > 0.0) & (r < a)
    if m.any():
        ri, ai = r[m], a[m]
        # arccosh(a/r) without forming a/r - 1: a - r is exact for r close to a
        T = np.arcsinh(np.sqrt((ai - ri) * (ai + ri)) / ri)
        nm, km = n[m], k[m]
        para = nm == 2.0       # paraboloid: Phi = tanh(T)^(1+k)/(1+k) = (1-rho^2)^((1+k)/2)/(1+k), eq. (22)
        vals = np.empty(T.shape)
        vals[para] = np.tanh(T[para]) ** (1.0 + km[para]) / (1.0 + km[para])
        if (~para).any():
            vals[~para] = _cosh_integral(T[~para], nm[~para], km[~para])
        out[m] = vals
    return out


def pressure(r, a, *, k, nu, E0, c0, n, A_n, E0_2=np.inf, nu_2=None):
    """Contact pressure p(r; a), eqs. (13), (22), Table 2 (generalised to A_n r^n, docs/theory/graded.md (G18)).

    Evaluated by the cosh form p = (c_N* n kappa A_n / pi) a^(n+k-1) Phi(r/a) (see
    :func:`pressure_shape`), which is regular at k -> 0 (no pole of B(-k/2, .)) and at r -> 0, and
    keeps full accuracy as r -> a (docs/theory/graded.md (G39)).  p = 0 for r >= a; p(0) = +inf for the cone at k = 0.
    Units of E0.
    """
    n, A_n = _power_law(n, A_n)
    r, a = _radii(r, a)
    cN = c_N_star(k, nu, E0, c0, E0_2, nu_2)
    k = np.asarray(k, float)
    pref = cN * n * kappa(n, k) * A_n * a ** (n + k - 1.0) / np.pi
    return pref * _shape(r, a, k, n)


def surface_displacement(r, a, *, k, n, A_n):
    """Surface displacement u_z(r; a) (positive into the body) for a rigid power-law indenter.

    Inside (r <= a): d - f(r).  Outside: eq. (15) in closed form, eq. (23) for n = 2 and Table 2
    for n = 1 with the corrected second beta parameter (n+1+k)/2 (Errata 1 of docs/theory/graded.md),
    written with regularised incomplete betas (the cos(k pi/2) Gamma((1-k)/2) product is cancelled
    analytically), docs/theory/graded.md (G21):
        u_z = A_n [kappa a^n I_z((1+k)/2, (1-k)/2) - r^n I_z((n+1+k)/2, (1-k)/2)],  z = a^2/r^2.
    Independent of the elastic constants.  Units of length.
    """
    n, A_n = _power_law(n, A_n)
    r, a = _radii(r, a)
    k = check_k(k)
    kap = kappa(n, k)
    r, a, k, n, A_n, kap = np.broadcast_arrays(r, a, k, n, A_n, kap)
    out = np.array(kap * A_n * a ** n - A_n * r ** n, dtype=float)   # ndarray even for 0-d input
    far = r > _SERIES_R_OVER_A * a
    m = (r > a) & ~far
    if m.any():
        rm, am, km, nm = r[m], a[m], k[m], n[m]
        z = (am / rm) ** 2
        q = 0.5 * (1.0 - km)
        out[m] = A_n[m] * (kap[m] * am ** nm * betainc(0.5 * (1.0 + km), q, z)
                           - rm ** nm * betainc(0.5 * (nm + 1.0 + km), q, z))
    if far.any():
        out[far] = A_n[far] * kap[far] * _far_field(r[far], a[far], k[far], n[far])
    return out


#: Beyond r = 2a the two incomplete-beta terms of u_z cancel (both ~ (a/r)^(1+k)); there the
#: positive series below is used instead (z = a^2/r^2 <= 1/4, 40 terms reach 1e-24).
_SERIES_R_OVER_A = 2.0
_SERIES_TERMS = 40


def _far_field(r, a, k, n):
    """u_z/(kappa A_n) for r > a from eq. (15) with (r^2 - x^2)^(-(1+k)/2) expanded in x^2/r^2
    (docs/theory/graded.md (G40)):
    (2/pi) cos(k pi/2) n a^(n+k+1) r^(-(1+k)) sum_j ((1+k)/2)_j/j! z^j / ((k+1+2j)(n+k+1+2j))."""
    z = (a / r) ** 2
    term = np.ones_like(z)
    total = np.zeros_like(z)
    for j in range(_SERIES_TERMS):
        total += term / ((k + 1.0 + 2 * j) * (n + k + 1.0 + 2 * j))
        term = term * z * (0.5 * (1.0 + k) + j) / (j + 1.0)
    return (2.0 / np.pi) * cos_half_pi_k(k) * n * a ** n * (a / r) ** (1.0 + k) * total


# --------------------------------------------------------------------------- quadrature route

def _u1d(profile, rtol):
    def fn(x, k, d):
        return d - g_quad(x, profile, k=k, rtol=rtol)
    return fn


def _dg(profile, rtol):
    def fn(x, k):
        return dg_quad(x, profile, k=k, rtol=rtol)
    return fn


def _check_profile_range(a, profile):
    if np.any(np.asarray(a) > profile.r_max):
        raise ValueError(f"a = {float(np.max(a))!r} is outside the profile range a <= {profile.r_max!r}")


def depth_quad(a, profile, *, k, rtol=1e-10):
    """d(a) = g(a) with g from the quadrature of eq. (5) (eq. 11); any profile object."""
    a = check_positive("a", a)
    _check_profile_range(a, profile)
    return g_quad(a, profile, k=k, rtol=rtol)


def normal_force_quad(a, profile, *, k, nu, E0, c0, E0_2=np.inf, nu_2=None, rtol=1e-10):
    """F_N(a) = 2 c_N* int_0^a x^k [d - g(x)] dx by quadrature, eq. (12)."""
    cN = c_N_star(k, nu, E0, c0, E0_2, nu_2)
    d = depth_quad(a, profile, k=k, rtol=rtol)
    return 2.0 * cN * _mdr.foundation_integral(a, _u1d(profile, rtol), {"k": k, "d": d}, rtol, profile.breaks)


def pressure_quad(r, a, profile, *, k, nu, E0, c0, E0_2=np.inf, nu_2=None, rtol=1e-10):
    """p(r; a) = (c_N*/pi) int_r^a g'(x) (x^2 - r^2)^(-(1-k)/2) dx by quadrature.

    Eq. (13), docs/theory/graded.md (G17).
    """
    r, a = _radii(r, a)
    _check_profile_range(a, profile)
    cN = c_N_star(k, nu, E0, c0, E0_2, nu_2)
    return cN * _mdr.pressure_integral(r, a, _dg(profile, rtol), {"k": check_k(k)}, rtol, profile.breaks)


def surface_displacement_quad(r, a, profile, *, k, rtol=1e-10):
    """u_z(r; a) by quadrature of eq. (15) outside and of its inverse-transform form inside.

    docs/theory/graded.md (G20).
    """
    r, a = _radii(r, a)
    d = depth_quad(a, profile, k=k, rtol=rtol)
    return _mdr.displacement_integral(r, a, _u1d(profile, rtol), {"k": check_k(k), "d": d}, rtol, profile.breaks)
