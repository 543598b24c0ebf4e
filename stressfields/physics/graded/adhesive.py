"""Adhesive (JKR-type) normal contact of a rigid indenter and a power-law graded half-space.

Hess & Popov 2016 (Facta Univ. Mech. Eng. 14(3) 251-268), eqs. (27)-(38) and Table 3, as stated in
docs/theory/graded.md (G22)-(G29) (C_adh(k) of eq. 28 renamed from the paper's C(k), Errata 4).
Profiles f = A_n r^n (paraboloid: n = 2, A_n = 1/(2R); cone: n = 1, A_n = tan(theta)).

Units: any consistent system.  delta_gamma (work of adhesion) in energy/area = E0 * length;
lengths, forces and pressures in the units of the inputs.  Tensile forces are negative.
The counter-body is rigid (``E0_2 = inf``) unless E0_2 (and nu_2) are given (eq. 14).
Every argument broadcasts (numpy rules), including k and nu.
"""
from __future__ import annotations

import numpy as np
from scipy.special import betainc

from ..roots import bisect
from . import _mdr, normal
from ._validate import check_k, check_mode, check_positive
from .material import c_N_star
from .profiles import Tabulated, dg_quad, kappa

__all__ = ["adhesion_constant", "delta_l_max", "depth", "normal_force", "pressure",
           "surface_displacement", "critical_radius", "critical_depth", "critical_force",
           "critical_state", "depth_quad", "normal_force_quad", "pressure_quad",
           "critical_state_quad", "critical_state_or_nan", "critical_state_search"]


def adhesion_constant(k, mode="fixed_load"):
    """C_adh(k) of eq. (28), docs/theory/graded.md (G26): 2/(3+k) at fixed load, 2/(1-k) at fixed grips."""
    k = check_k(k)
    return 2.0 / (3.0 + k) if check_mode(mode) == "fixed_load" else 2.0 / (1.0 - k)


def _cN(k, nu, E0, c0, E0_2, nu_2):
    return c_N_star(k, nu, E0, c0, E0_2, nu_2)


def _dl(a, cN, k, dgam):
    # eq. (27): Delta l_max = sqrt(2 pi dgam a / c_N(a)), c_N(a) = c_N* a^k
    return np.sqrt(2.0 * np.pi * dgam * a ** (1.0 - k) / cN)


def delta_l_max(a, *, k, nu, E0, c0, delta_gamma, E0_2=np.inf, nu_2=None):
    """Maximum stretch of the edge springs Delta l_max(a) = sqrt(2 pi dgam a/c_N(a)) [length].

    Eq. (27), docs/theory/graded.md (G22).
    """
    cN = _cN(k, nu, E0, c0, E0_2, nu_2)
    dgam = check_positive("delta_gamma", delta_gamma, allow_zero=True)
    return _dl(check_positive("a", a), cN, np.asarray(k, float), dgam)


def depth(a, *, k, nu, E0, c0, n, A_n, delta_gamma, E0_2=np.inf, nu_2=None):
    """d(a) = kappa A_n a^n - Delta l_max(a), eqs. (27), (30), Table 3, docs/theory/graded.md (G22) [length]."""
    dl = delta_l_max(a, k=k, nu=nu, E0=E0, c0=c0, delta_gamma=delta_gamma, E0_2=E0_2, nu_2=nu_2)
    return normal.depth(a, k=k, n=n, A_n=A_n) - dl


def normal_force(a, *, k, nu, E0, c0, n, A_n, delta_gamma, E0_2=np.inf, nu_2=None):
    """F_N(a) = F_N,Hertz-type(a) - 2 c_N* a^(1+k) Delta l_max/(1+k), eq. (31), Table 3, docs/theory/graded.md (G23)."""
    cN = _cN(k, nu, E0, c0, E0_2, nu_2)
    a = check_positive("a", a)
    k = np.asarray(k, float)
    dl = _dl(a, cN, k, check_positive("delta_gamma", delta_gamma, allow_zero=True))
    f0 = normal.normal_force(a, k=k, nu=nu, E0=E0, c0=c0, n=n, A_n=A_n, E0_2=E0_2, nu_2=nu_2)
    return f0 - 2.0 * cN * a ** (1.0 + k) * dl / (1.0 + k)


def _punch(r, a, k):
    # (1 - r^2/a^2)^(-(1-k)/2) for r < a, +inf at r = a, 0 outside; a - r is exact near the edge
    r, a, k = np.broadcast_arrays(r, a, k)
    out = np.zeros(r.shape)
    m = r < a
    out[m] = ((a[m] - r[m]) * (a[m] + r[m]) / a[m] ** 2) ** (-0.5 * (1.0 - k[m]))
    out[r == a] = np.inf
    return out


def _punch_term(x, s, radius, cN, k, dl):
    """(c_N*/pi) Delta l_max radius^(k-1) (1 - x^2/s^2)^(-(1-k)/2), docs/theory/graded.md (G24).

    Zero wherever Delta l_max = 0 (no adhesion), also at the edge: there the pressure is the
    non-adhesive one, whose exact limit at r = a is 0, not 0 * inf (G44).
    """
    with np.errstate(invalid="ignore"):
        term = cN * dl * radius ** (k - 1.0) / np.pi * _punch(x, s, k)
    return np.where(dl == 0.0, 0.0, term)


def pressure(r, a, *, k, nu, E0, c0, n, A_n, delta_gamma, E0_2=np.inf, nu_2=None, rho=None):
    """Adhesive pressure p(r; a), eq. (37) generalised to A_n r^n, docs/theory/graded.md (G24) [pressure].

    p = p_non-adhesive(r; a) - (c_N*/pi) Delta l_max a^(-(1-k)) (1 - r^2/a^2)^(-(1-k)/2);
    tensile (negative) and singular at the edge: -inf at r = a for delta_gamma > 0 (0 for
    delta_gamma = 0, (G44)), 0 for r > a.  ``rho = r/a`` may be given instead of r.
    Closed form: relative error at most 1e-12 of the value.
    """
    cN = _cN(k, nu, E0, c0, E0_2, nu_2)
    x, s, a = normal.position(r, a, rho)
    k = np.asarray(k, float)
    dl = _dl(a, cN, k, check_positive("delta_gamma", delta_gamma, allow_zero=True))
    p0 = normal.pressure(r, a, k=k, nu=nu, E0=E0, c0=c0, n=n, A_n=A_n, E0_2=E0_2, nu_2=nu_2, rho=rho)
    return p0 - _punch_term(x, s, a, cN, k, dl)


def surface_displacement(r, a, *, k, nu, E0, c0, n, A_n, delta_gamma, E0_2=np.inf, nu_2=None, rho=None):
    """u_z(r; a) with adhesion: eq. (15) applied to u_1D of eq. (35) (not printed in the paper),
    docs/theory/graded.md (G25).

    Inside: d(a) - f(r); outside: the non-adhesive u_z minus Delta l_max I_{a^2/r^2}((1+k)/2, (1-k)/2)
    (the flat-punch part).  ``rho = r/a`` may be given instead of r.  Units of length.
    """
    dl = delta_l_max(a, k=k, nu=nu, E0=E0, c0=c0, delta_gamma=delta_gamma, E0_2=E0_2, nu_2=nu_2)
    u0 = normal.surface_displacement(r, a, k=k, n=n, A_n=A_n, rho=rho)
    x, s, _ = normal.position(r, a, rho)
    x, s, k = np.broadcast_arrays(np.asarray(x, float), np.asarray(s, float), np.asarray(k, float))
    z = np.minimum((s / np.where(x > 0, x, 1.0)) ** 2, 1.0)
    punch = np.where(x > s, betainc(0.5 * (1.0 + k), 0.5 * (1.0 - k), z), 1.0)
    return u0 - dl * punch


def _critical_check(n, k):
    n = check_positive("n", n)
    bad = ~(2.0 * n + k - 1.0 > 0.0)
    if np.any(bad):
        nb = float(np.broadcast_to(n, bad.shape)[bad].flat[0])
        kb = float(np.broadcast_to(k, bad.shape)[bad].flat[0])
        raise ValueError(f"n = {nb!r} is outside the allowed range n > (1-k)/2 = {(1 - kb) / 2!r} "
                         "(no critical contact radius otherwise, Table 3)")
    return n


def critical_radius(*, k, nu, E0, c0, n, A_n, delta_gamma, mode="fixed_load", E0_2=np.inf, nu_2=None):
    """Critical contact radius a_c (pull-off), eq. (32) and Table 3, docs/theory/graded.md (G27) [length]:

    a_c = [2 pi dgam / (c_N* (C n kappa A_n)^2)]^(1/(2n+k-1)),  C = C_adh(k) (eq. 28).
    """
    cN = _cN(k, nu, E0, c0, E0_2, nu_2)
    k = np.asarray(k, float)
    n = _critical_check(n, k)
    A_n = check_positive("A_n", A_n)
    dgam = check_positive("delta_gamma", delta_gamma, allow_zero=True)
    C = adhesion_constant(k, mode)
    return (2.0 * np.pi * dgam / (cN * (C * n * kappa(n, k) * A_n) ** 2)) ** (1.0 / (2.0 * n + k - 1.0))


def critical_state(*, k, nu, E0, c0, n, A_n, delta_gamma, mode="fixed_load", E0_2=np.inf, nu_2=None):
    """(a_c, d_c, F_c) at the onset of pull-off, eqs. (32)-(34) and Table 3, docs/theory/graded.md (G27)-(G29).

    Uses Delta l_max(a_c) = C n kappa A_n a_c^n (eq. 28) to write
    d_c = (1 - nC) kappa A_n a_c^n (exactly 0 for n C = 1, e.g. n = (3+k)/2 at fixed load) and
    F_c = 2 c_N* n kappa A_n a_c^(n+k+1) [1/(n+k+1) - C]/(1+k).
    For n = 2, A_n = 1/(2R): F_c = -(3+k)/2 pi dgam R (fixed load), -(1-k)(5+3k)/(2(3+k)) pi dgam R
    (fixed grips), eq. (34).  Units: length, length, force.
    """
    a_c = critical_radius(k=k, nu=nu, E0=E0, c0=c0, n=n, A_n=A_n, delta_gamma=delta_gamma,
                          mode=mode, E0_2=E0_2, nu_2=nu_2)
    cN = _cN(k, nu, E0, c0, E0_2, nu_2)
    k = np.asarray(k, float)
    C = adhesion_constant(k, mode)
    g = kappa(n, k) * A_n * a_c ** n
    d_c = (1.0 - n * C) * g
    F_c = 2.0 * cN * n * g * a_c ** (k + 1.0) * (1.0 / (n + k + 1.0) - C) / (1.0 + k)
    return a_c, d_c, F_c


def critical_depth(**kw):
    """d_c of :func:`critical_state`, eq. (33), Table 3 [length]."""
    return critical_state(**kw)[1]


def critical_force(**kw):
    """F_c of :func:`critical_state`, eq. (34), Table 3 [force]."""
    return critical_state(**kw)[2]


# --------------------------------------------------------------------------- quadrature route

def depth_quad(a, profile, *, k, nu, E0, c0, delta_gamma, E0_2=np.inf, nu_2=None, rtol=1e-10):
    """d(a) = g(a) - Delta l_max(a) with g from quadrature of eq. (5)."""
    dl = delta_l_max(a, k=k, nu=nu, E0=E0, c0=c0, delta_gamma=delta_gamma, E0_2=E0_2, nu_2=nu_2)
    return normal.depth_quad(a, profile, k=k, rtol=rtol) - dl


def normal_force_quad(a, profile, *, k, nu, E0, c0, delta_gamma, E0_2=np.inf, nu_2=None, rtol=1e-10):
    """F_N(a) = 2 c_N* int_0^a x^k [d - g(x)] dx with u_1D of eq. (35), by quadrature (eqs. 12, 31)."""
    cN = _cN(k, nu, E0, c0, E0_2, nu_2)
    d = depth_quad(a, profile, k=k, nu=nu, E0=E0, c0=c0, delta_gamma=delta_gamma,
                   E0_2=E0_2, nu_2=nu_2, rtol=rtol)
    return 2.0 * cN * _mdr.foundation_integral(a, normal._u1d(profile, rtol), {"k": k, "d": d}, rtol, profile.breaks)


def pressure_quad(r, a, profile, *, k, nu, E0, c0, delta_gamma, E0_2=np.inf, nu_2=None, rtol=1e-10, rho=None):
    """p(r; a) from eq. (13) with u'_1D of eq. (36): the delta terms give the edge singularity.

    ``rho = r/a`` may be given instead of r.  Relative error below rtol.
    """
    cN = _cN(k, nu, E0, c0, E0_2, nu_2)
    x, s, a = normal.position(r, a, rho)
    k = check_k(k)
    dl = _dl(a, cN, k, check_positive("delta_gamma", delta_gamma, allow_zero=True))
    p0 = normal.pressure_quad(r, a, profile, k=k, nu=nu, E0=E0, c0=c0, E0_2=E0_2, nu_2=nu_2, rtol=rtol, rho=rho)
    # delta(x - a) in u'_1D contributes -(c_N*/pi) dl (a^2 - r^2)^(-(1-k)/2) directly
    return p0 - _punch_term(x, s, a, cN, k, dl)


def critical_state_quad(profile, *, k, nu, E0, c0, delta_gamma, mode="fixed_load",
                        a_bracket=(1e-6, 1e3), E0_2=np.inf, nu_2=None, rtol=1e-10):
    """(a_c, d_c, F_c) by root finding on the MDR rules, independent of eq. (28) and Table 3
    (docs/theory/graded.md (G42)).

    Fixed load: dF_N/da = 0 with dF_N/da = 2 (g'(a) - Delta l_max'(a)) int_0^a c_N dx - 2 c_N(a) Delta l_max
    (differentiating eq. 12 with u_1D = g(a) - Delta l_max - g(x)); fixed grips: dd/da = g'(a) - Delta l_max'(a) = 0.
    g' and int_0^a c_N come from quadrature, Delta l_max' = (1-k) Delta l_max/(2a) from eq. (27).
    Vectorised bisection in log a inside ``a_bracket`` (length units; must contain the root).
    """
    mode = check_mode(mode)
    cN = _cN(k, nu, E0, c0, E0_2, nu_2)
    k = check_k(k)
    dgam = check_positive("delta_gamma", delta_gamma, allow_zero=True)
    cN, k, dgam = np.broadcast_arrays(cN, k, dgam)

    def slope(a):
        dl = _dl(a, cN, k, dgam)
        dd = dg_quad(a, profile, k=k, rtol=rtol) - 0.5 * (1.0 - k) * dl / a
        if mode == "fixed_grips":
            return dd
        cint = cN * _mdr.foundation_integral(a, lambda x, k: np.ones_like(x), {"k": k}, rtol, profile.breaks)
        return 2.0 * dd * cint - 2.0 * cN * a ** k * dl

    lo, hi = (np.full(k.shape, float(end)) for end in a_bracket)
    if np.any(slope(lo) >= 0) or np.any(slope(hi) <= 0):
        raise ValueError(f"a_bracket = {a_bracket!r} does not bracket the critical contact radius")
    # 2^-64 of log(hi/lo): far below double precision in a_c; the slope rises through 0 at a_c
    a_c = bisect(lambda a: slope(a) < 0, lo, hi, 64, geometric=True)
    d_c = depth_quad(a_c, profile, k=k, nu=nu, E0=E0, c0=c0, delta_gamma=dgam, E0_2=E0_2, nu_2=nu_2, rtol=rtol)
    F_c = normal_force_quad(a_c, profile, k=k, nu=nu, E0=E0, c0=c0, delta_gamma=dgam,
                            E0_2=E0_2, nu_2=nu_2, rtol=rtol)
    return a_c, d_c, F_c


# --------------------------------------------------------------------------- pull-off of any profile

def critical_state_or_nan(*, k, nu, E0, c0, n, A_n, delta_gamma, mode="fixed_load", E0_2=np.inf, nu_2=None):
    """:func:`critical_state` with NaN where no critical point exists (n <= (1-k)/2, Table 3,
    docs/theory/graded.md (G27)) instead of an error: a sweep over n may cross that bound."""
    k = np.asarray(k, float)
    n = np.asarray(n, float)
    ok = 2.0 * n + k - 1.0 > 0.0
    state = critical_state(k=k, nu=nu, E0=E0, c0=c0, n=np.where(ok, n, 2.0), A_n=A_n,
                           delta_gamma=delta_gamma, mode=mode, E0_2=E0_2, nu_2=nu_2)
    return tuple(np.where(ok, s, np.nan) for s in state)


def critical_state_search(profile, *, k, nu, E0, c0, delta_gamma, mode="fixed_load", rtol=1e-10):
    """(a_c, d_c, F_c) of :func:`critical_state_quad` with the bracket chosen for the profile and
    NaN where there is no critical point (docs/theory/graded.md (G42)).

    A power law is bracketed around its closed-form a_c (eq. 32; the root itself comes from the MDR
    rules); a tabulated profile by its whole range, so a root beyond the table is NaN, never
    extrapolated.  Where one point of the block has no root in the bracket, the block is solved
    point by point.
    """
    kw = dict(k=k, nu=nu, E0=E0, c0=c0, delta_gamma=delta_gamma)
    shape = np.broadcast_shapes(*(np.shape(v) for v in kw.values()))
    nan = np.full(shape, np.nan)
    if isinstance(profile, Tabulated):
        bracket, exists = (profile.r_max * 1e-9, profile.r_max), np.ones(shape, bool)
    else:
        a_c = critical_state_or_nan(n=np.asarray(profile.n, float), A_n=np.asarray(profile.A, float),
                                    mode=mode, **kw)[0]
        exists = np.broadcast_to(~np.isnan(a_c), shape)
        if not exists.any():
            return nan, nan, nan
        bracket = (np.nanmin(a_c) / 4.0, np.nanmax(a_c) * 4.0)
    try:
        state = critical_state_quad(profile, mode=mode, a_bracket=bracket, rtol=rtol, **kw)
        return tuple(np.where(exists, s, np.nan) for s in state)
    except ValueError:
        pass
    out = [nan.copy() for _ in range(3)]
    for idx in zip(*np.nonzero(exists)) if shape else [()]:
        try:
            one = critical_state_quad(profile, mode=mode, a_bracket=bracket, rtol=rtol,
                                      **{key: np.broadcast_to(v, shape)[idx] for key, v in kw.items()})
        except ValueError:              # no root in the bracket: NaN there
            continue
        for o, v in zip(out, one):
            o[idx] = v
    return tuple(out)
