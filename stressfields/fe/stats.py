"""Statistics validators trust: max, RMS and percentiles of |difference| / scale, relative L2 (as a
sum over nodes, and as an integral when the file gives quadrature weights or cell volumes), the
relative energy-norm error of the stress, an edge ring reported apart, and the observed order of a
mesh sequence with a Richardson-style estimate of the difference that remains as h -> 0.
"""
from __future__ import annotations

import math

import numpy as np

#: `--tolerance` keys -> the statistic they bound
TOLERANCE_KEYS = {"max": "max_abs_difference_over_scale", "rms": "rms_difference_over_scale",
                  "p50": "p50_abs_difference_over_scale", "p95": "p95_abs_difference_over_scale",
                  "p99": "p99_abs_difference_over_scale", "l2": "relative_l2",
                  "wl2": "weighted_relative_l2", "wrms": "weighted_rms_difference_over_scale",
                  "energy": "energy_relative_error"}
#: the statistics a convergence table follows
CONVERGENCE_KEYS = ("max", "rms", "p95", "l2", "wl2", "energy")
#: scenario -> edges where the exact field is not smooth, and the orders a mesh sequence can show
EDGES = {
    "parabolic": ("contact edge r = a, stick edge r = c",
                  "max |Δ|: 0.5 (the pressure's square-root edge: the stress gradient is singular at r = a "
                  "and r = c); RMS and L2 over the nodes: below the smooth-field order p + 1, about 1.5 "
                  "with P2 elements"),
    "axisymmetric": ("contact (punch) edge r = a, stick edge r = c",
                     "max |Δ|: 0.5 for a smooth profile (square-root edge), none for a flat punch (the "
                     "stress is infinite at its edge: exclude the edge ring); RMS and L2: below p + 1"),
    "axisymmetric_history": ("contact edge r = a, stick edge r = c",
                             "max |Δ|: 0.5 (square-root edges); RMS and L2: below p + 1"),
    "conical": ("cone tip r = 0, contact edge r = a, stick edge r = c",
                "max |Δ|: none (the stress is logarithmically infinite at the tip: exclude it); RMS and L2: "
                "about 1, limited by the tip"),
}


def statistics(diff: np.ndarray, ref: np.ndarray, scale: np.ndarray, weights: np.ndarray | None,
               mask: np.ndarray) -> dict:
    """The statistics of the nodes in ``mask`` where the reference is finite (the others counted)."""
    ok = mask & np.isfinite(ref)
    out = {"compared_points": int(ok.sum()), "excluded_points": int((mask & ~np.isfinite(ref)).sum())}
    if not ok.any():
        return {**out, "max_abs_difference_over_scale": math.nan, "rms_difference": math.nan,
                "rms_difference_over_scale": math.nan, "relative_l2": math.nan, "worst_point": -1}
    ratio = np.where(ok, np.abs(diff) / scale, -np.inf)
    worst = int(np.argmax(ratio))
    d, r, s = diff[ok], ref[ok], scale[ok]
    a = np.abs(d) / s
    norm = _norm(r)
    out.update({
        "scale": float(scale[worst]), "max_abs_difference_over_scale": float(ratio[worst]),
        "max_abs_difference": float(abs(diff[worst])), "worst_point": worst,
        "rms_difference": float(np.sqrt(np.mean(d * d))), "rms_difference_over_scale": float(np.sqrt(np.mean(a * a))),
        **dict(zip(("p50_abs_difference_over_scale", "p95_abs_difference_over_scale",
                    "p99_abs_difference_over_scale"), np.percentile(a, (50, 95, 99)).tolist())),    # one sort
        "relative_l2": _ratio(_norm(d), norm)})
    if weights is not None:
        w = weights[ok]
        out["weighted_relative_l2"] = _ratio(math.sqrt(float(np.sum(w * d * d))), math.sqrt(float(np.sum(w * r * r))))
        out["weighted_rms_difference_over_scale"] = math.sqrt(float(np.sum(w * a * a) / np.sum(w)))
    return out


def _norm(x: np.ndarray) -> float:
    """The Euclidean norm by NumPy's pairwise sum, not BLAS: np.linalg.norm's dot of 1e5 values took
    7.6 ms here against 0.03 ms (OpenBLAS threads on a busy 2-core machine), 20 of them per comparison."""
    return math.sqrt(float(np.sum(x * x)))


def _ratio(num: float, den: float) -> float:
    return num / den if den > 0 else (0.0 if num == 0 else math.inf)


def sign_hint(user: np.ndarray, ref: np.ndarray) -> str | None:
    """A note when the user's values are close to minus the reference (a sign convention)."""
    ok = np.isfinite(ref)
    minus, plus = _norm(user[ok] + ref[ok]), _norm(user[ok] - ref[ok])
    if ok.any() and _norm(ref[ok]) > 0 and minus < 0.1 * plus:
        return ("user ≈ -reference: this looks like a sign-convention difference (tension positive, z into "
                "the body here; --z-up changes the sign of z, sigma_xz, sigma_yz, u_z)")
    return None


def energy_error(diff: dict[str, np.ndarray], ref: dict[str, np.ndarray], nu: float,
                 weights: np.ndarray | None, mask: np.ndarray) -> float | None:
    """Relative energy-norm error of the stress, sqrt(∫ Δσ:C⁻¹:Δσ / ∫ σ:C⁻¹:σ) with
    σ:C⁻¹:σ = ((1 + ν) σ:σ - ν (tr σ)²) / E (E cancels); None unless all six components are given."""
    names = ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "sigma_yz")
    if not all(n in diff for n in names):
        return None

    def density(t):
        xx, yy, zz, xy, xz, yz = (t[n] for n in names)
        return (1 + nu) * (xx * xx + yy * yy + zz * zz + 2 * (xy * xy + xz * xz + yz * yz)) - nu * (xx + yy + zz) ** 2

    ok = mask & np.all([np.isfinite(ref[n]) for n in names], axis=0)
    w = np.ones(ok.sum()) if weights is None else weights[ok]
    num = float(np.sum(w * density({n: diff[n][ok] for n in names})))
    den = float(np.sum(w * density({n: ref[n][ok] for n in names})))
    return _ratio(math.sqrt(max(num, 0.0)), math.sqrt(den))


def edge_distance(x: np.ndarray, y: np.ndarray, z: np.ndarray, radii: list[float], tip: bool) -> np.ndarray:
    """Distance of each node to the nearest edge: a circle of radius rho in the surface z = 0 (the
    contact or stick edge), or the point r = z = 0 (a cone tip)."""
    r = np.hypot(x, y)
    d = np.full(r.shape, np.inf)
    for rho in radii:
        d = np.minimum(d, np.hypot(r - rho, z))
    if tip:
        d = np.minimum(d, np.hypot(r, z))
    return d


def observed_orders(h: list[float], errors: list[float]) -> dict:
    """Orders between successive meshes, the least-squares order over all, and the Richardson-style
    estimate of the difference left as h -> 0, e_inf = e_n - (e_{n-1} - e_n) / ((h_{n-1}/h_n)^p - 1)
    with p the fitted order: a finite remainder is a modelling difference, not discretisation error."""
    h_, e_ = np.asarray(h, float), np.asarray(errors, float)
    good = np.isfinite(e_) & (e_ > 0)
    pairs = [float(math.log(e_[i] / e_[i + 1]) / math.log(h_[i] / h_[i + 1])) if good[i] and good[i + 1]
             and h_[i] != h_[i + 1] else math.nan for i in range(len(h_) - 1)]
    if good.sum() >= 2 and np.ptp(np.log(h_[good])) > 0:
        fitted = float(np.polyfit(np.log(h_[good]), np.log(e_[good]), 1)[0])
    else:
        fitted = math.nan
    remainder = math.nan
    if len(h_) >= 2 and math.isfinite(fitted) and fitted > 0:
        ratio = (h_[-2] / h_[-1]) ** fitted
        remainder = float(e_[-1] - (e_[-2] - e_[-1]) / (ratio - 1.0)) if ratio != 1 else math.nan
    return {"h": [float(v) for v in h_], "errors": [float(v) for v in e_], "orders": pairs,
            "fitted_order": fitted, "richardson_remainder": remainder}
