"""Input checks shared by the graded kernels.

Every check raises ``ValueError`` naming the parameter, the first offending value and the
allowed range, so that a sweep never produces a silent NaN.
"""
from __future__ import annotations

import numpy as np


def _first(bad: np.ndarray, values: np.ndarray) -> float:
    return float(np.broadcast_to(values, bad.shape)[bad].flat[0])


def as_array(name: str, value) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} = {value!r} is not a real number or array of real numbers") from exc
    return arr


def check_k(k) -> np.ndarray:
    """Grading exponent of E(z) = E0 (z/c0)^k (eq. 1): 0 <= k < 1."""
    k = as_array("k", k)
    bad = ~((k >= 0.0) & (k < 1.0))
    if bad.any():
        raise ValueError(f"k = {_first(bad, k)!r} is outside the allowed range 0 <= k < 1 "
                         "(grading exponent of E(z) = E0 (z/c0)^k, Hess & Popov 2016 eq. 1)")
    return k


def check_nu(nu, k, name: str = "nu") -> np.ndarray:
    """Poisson ratio: -1 < nu <= 1/2.

    beta(k, nu) of eq. 56 is real only for nu <= 1/(1+k) (> 1/2 for k < 1), and an isotropic
    material with nu > 1/2 has a negative bulk modulus, so 1/2 is the binding upper bound.
    """
    nu = as_array(name, nu)
    k = np.asarray(k, dtype=float)
    bad = ~((nu > -1.0) & (nu <= 0.5))
    if bad.any():
        kb = np.broadcast_to(k, np.broadcast(k, nu).shape)
        badb = np.broadcast_to(bad, kb.shape)
        kv = float(kb[badb].flat[0])
        raise ValueError(
            f"{name} = {_first(bad, nu)!r} is outside the allowed range -1 < {name} <= 0.5 "
            f"(at k = {kv!r}: beta(k, nu) of eq. 56 is real only for {name} <= 1/(1+k) = "
            f"{1.0 / (1.0 + kv):.6g}, and {name} > 0.5 is thermodynamically inadmissible)")
    return nu


def check_positive(name: str, value, *, allow_zero: bool = False, allow_inf: bool = False) -> np.ndarray:
    arr = as_array(name, value)
    ok = (arr >= 0.0) if allow_zero else (arr > 0.0)
    if not allow_inf:
        ok &= np.isfinite(arr)
    ok &= ~np.isnan(arr)
    if not ok.all():
        lo = "0 <=" if allow_zero else "0 <"
        hi = "<= inf" if allow_inf else "< inf"
        raise ValueError(f"{name} = {_first(~ok, arr)!r} is outside the allowed range {lo} {name} {hi}")
    return arr


def check_interval(name: str, value, lo: float, hi: float) -> np.ndarray:
    """Closed interval lo <= value <= hi."""
    arr = as_array(name, value)
    bad = ~((arr >= lo) & (arr <= hi))
    if bad.any():
        raise ValueError(f"{name} = {_first(bad, arr)!r} is outside the allowed range {lo} <= {name} <= {hi}")
    return arr


def check_mode(mode: str) -> str:
    if mode not in ("fixed_load", "fixed_grips"):
        raise ValueError(f"mode = {mode!r} is not allowed: use 'fixed_load' or 'fixed_grips'")
    return mode
