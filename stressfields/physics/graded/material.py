"""Material mapping of the power-law graded half-space onto a 1D Winkler foundation.

M. Hess, V. L. Popov, "Method of dimensionality reduction in contact mechanics and friction:
a user's handbook. II. Power-law graded materials", Facta Universitatis Mech. Eng. 14(3),
2016, 251-268 — eqs. (1)-(4), (14), (21), (46)-(47) and appendix (53)-(56), stated in
docs/theory/graded.md (G1)-(G10), with the correction of (54) (``(1 - nu^2)``, not ``(1 - nu)``,
in the first denominator term; docs/theory/graded.md (G7), Errata 2).

Young's modulus E(z) = E0 (z/c0)^k with 0 <= k < 1 and constant Poisson ratio nu.  The
foundation stiffness is c_N(x) = c_N_star |x|^k (normal) and c_T(x) = c_T_star |x|^k
(tangential); ``c_N_star`` has units of E0 / length^k.  All functions broadcast over their
arguments (k and nu may be arrays).
"""
from __future__ import annotations

import numpy as np
from scipy.special import gamma

from ._validate import check_k, check_nu, check_positive

__all__ = ["beta", "C_gs", "h_N", "h_T", "holl_ratio", "c_N_star", "c_T_star",
           "tangential_decoupled", "cos_half_pi_k"]


def cos_half_pi_k(k):
    """cos(k pi / 2) evaluated as sin((1-k) pi / 2): full relative accuracy as k -> 1, docs/theory/graded.md (G38)."""
    return np.sin(0.5 * np.pi * (1.0 - np.asarray(k, dtype=float)))


def _beta(k, nu):
    return np.sqrt((1.0 + k) * (1.0 - k * nu / (1.0 - nu)))


def _C(k, b):
    return 2.0 ** (k + 1.0) * gamma(0.5 * (3.0 + k + b)) * gamma(0.5 * (3.0 + k - b)) / (np.pi * gamma(2.0 + k))


def _h_N(k, nu):
    b = _beta(k, nu)
    return (2.0 * (1.0 + k) * cos_half_pi_k(k) * gamma(1.0 + 0.5 * k)
            / (np.sqrt(np.pi) * _C(k, b) * b * np.sin(0.5 * np.pi * b) * gamma(0.5 * (1.0 + k))))


def _h_T(k, nu):
    b = _beta(k, nu)
    g1 = gamma(1.0 + 0.5 * k)
    den = ((1.0 - nu * nu) * (1.0 + k) * np.sqrt(np.pi) * _C(k, b) * np.sin(0.5 * np.pi * b)
           * gamma(0.5 * (1.0 + k)) + 2.0 * b * (1.0 + nu) * g1)
    return 4.0 * b * cos_half_pi_k(k) * g1 / den


def beta(k, nu):
    """beta(k, nu) = sqrt((1+k)(1 - k nu/(1-nu))), eq. (56), docs/theory/graded.md (G4). Dimensionless."""
    k = check_k(k)
    return _beta(k, check_nu(nu, k))


def C_gs(k, nu):
    """C(k, nu) of the appendix, eq. (55), docs/theory/graded.md (G5). Dimensionless.

    The point-load constant of the paper's refs. [9, 15]; not the adhesion coefficient C_adh(k).
    """
    k = check_k(k)
    return _C(k, _beta(k, check_nu(nu, k)))


def h_N(k, nu):
    """Normal stiffness factor h_N(k, nu), eq. (53), docs/theory/graded.md (G6). Dimensionless.

    h_N(0, nu) = 1 (eq. 4).
    """
    k = check_k(k)
    return _h_N(k, check_nu(nu, k))


def h_T(k, nu):
    """Tangential stiffness factor h_T(k, nu), eq. (54) corrected: docs/theory/graded.md (G7), Errata 2.

    h_T(0, nu) = 2/((1+nu)(2-nu)) (eq. 4). Dimensionless.
    """
    k = check_k(k)
    return _h_T(k, check_nu(nu, k))


def holl_ratio(k):
    """Poisson ratio nu = 1/(2+k) at which normal and tangential problems decouple (sec. 5).

    docs/theory/graded.md (G10).
    """
    return 1.0 / (2.0 + check_k(k))


def _second_body(nu, E0_2, nu_2, k):
    E0_2 = check_positive("E0_2", E0_2, allow_inf=True)
    nu_2 = nu if nu_2 is None else check_nu(nu_2, k, name="nu_2")
    return E0_2, nu_2


def c_N_star(k, nu, E0, c0, E0_2=np.inf, nu_2=None):
    """Normal foundation stiffness c_N(x) / |x|^k, eqs. (2), (14), docs/theory/graded.md (G2); units of E0 / length^k.

    Body 1 is graded (E0, nu); body 2 has the same k and c0 and modulus E0_2, Poisson ratio nu_2
    (default: nu).  ``E0_2 = inf`` (default) is a rigid indenter, eq. (21):
    c_N_star = h_N E0 / ((1 - nu^2) c0^k).  Two identical bodies (E0_2 = E0) give half that, eq. (46).
    """
    k = check_k(k)
    nu = check_nu(nu, k)
    E0 = check_positive("E0", E0)
    c0 = check_positive("c0", c0)
    E0_2, nu_2 = _second_body(nu, E0_2, nu_2, k)
    comp = (1.0 - nu * nu) / (_h_N(k, nu) * E0)
    with np.errstate(divide="ignore"):
        comp = comp + np.where(np.isinf(E0_2), 0.0, (1.0 - nu_2 * nu_2) / (_h_N(k, nu_2) * E0_2))
    return 1.0 / (comp * c0 ** k)


def c_T_star(k, nu, E0, c0, E0_2=np.inf, nu_2=None):
    """Tangential foundation stiffness c_T(x) / |x|^k, eq. (3), docs/theory/graded.md (G3); units of E0 / length^k.

    Same conventions as :func:`c_N_star`; two identical bodies give h_T E0 / (2 c0^k), eq. (47).
    """
    k = check_k(k)
    nu = check_nu(nu, k)
    E0 = check_positive("E0", E0)
    c0 = check_positive("c0", c0)
    E0_2, nu_2 = _second_body(nu, E0_2, nu_2, k)
    comp = 1.0 / (_h_T(k, nu) * E0)
    with np.errstate(divide="ignore"):
        comp = comp + np.where(np.isinf(E0_2), 0.0, 1.0 / (_h_T(k, nu_2) * E0_2))
    return 1.0 / (comp * c0 ** k)


def tangential_decoupled(k, nu, *, E0=None, E0_2=None, nu_2=None, rtol=1e-9):
    """Boolean array: do the normal and tangential contact problems decouple? (sec. 5, eqs. 39-52)

    Decoupling holds (Hess & Popov 2016, sec. 5; docs/theory/graded.md (G10)) for
    (i) identical materials, (ii) a rigid body against a body with nu = 1/(2+k), or
    (iii) both bodies with nu = 1/(2+k).  Body 2: ``E0_2=None`` means identical to body 1
    (always decoupled); ``E0_2=inf`` rigid; a finite ``E0_2`` with ``nu_2`` (default nu) an
    elastic graded body with the same k and c0 (then ``E0`` is needed to test identity).
    nu is compared with 1/(2+k) to relative tolerance ``rtol``.  Broadcasts over all inputs.
    """
    k = check_k(k)
    nu = check_nu(nu, k)
    if E0_2 is None:
        return np.broadcast_to(True, np.broadcast(k, nu).shape).copy()
    E0_2, nu_2 = _second_body(nu, E0_2, nu_2, k)
    holl = 1.0 / (2.0 + k)
    holl1 = np.isclose(nu, holl, rtol=rtol, atol=0.0)
    holl2 = np.isclose(nu_2, holl, rtol=rtol, atol=0.0)
    if E0 is None:
        identical = np.zeros(np.broadcast(nu, nu_2, E0_2).shape, dtype=bool)
    else:
        E0 = check_positive("E0", E0)
        identical = np.isclose(E0_2, E0, rtol=rtol, atol=0.0) & np.isclose(nu_2, nu, rtol=rtol, atol=0.0)
    return np.where(np.isinf(E0_2), holl1, identical | (holl1 & holl2))
