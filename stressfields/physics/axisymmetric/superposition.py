"""The 1-D superposition engine of the family: a field below the surface as the superposition of
flat punches (or sliding punches) over the radius of integration, docs/theory/interior.md (I15).

The stresses (``interior``, ``interior_tangential``), dp_h/dz and the displacements
(``displacement``) are integrals of one form, sigma(x) = int_lower^a K(x; rho) g'(rho) d rho, with
K the field of a punch of radius rho; they differ only in the integrand.  This module owns what
they share: the argument prelude and checks, the panels that grow geometrically away from the
layer of width about z at rho = min(r, a) (I16)-(I17), the Gauss rules on them, the a-priori node
count per panel (I54) and the flat evaluation by blocks.  A caller passes a *kernel*: the function
that sums its integrand over the nodes of a group of points (``Nodes`` for ``superpose``, ``Flat``
for ``superpose_flat``) and the names of the values it returns.

Accuracy: |error| <= rtol * max(|value|, scale) with the scale of the field (p_m for stresses);
the table ``_ORDERS`` records how the rules were measured.  Pure NumPy.
"""
from __future__ import annotations

import functools
import math
from typing import NamedTuple

import numpy as np

from ..quadrature import gauss_jacobi, gauss_legendre, group_by

__all__ = ["METHODS", "flat_arguments", "check_arguments", "interior_orders", "superpose", "superpose_flat",
           "unresolved_as_nan", "Nodes", "Flat", "live_nodes", "direction", "radial_cartesian"]

METHODS = ("auto", "closed", "quadrature")


def flat_arguments(what: str, method: str, *values) -> tuple[tuple[int, ...], list[np.ndarray]]:
    """The entry points' prelude: refuse an unknown method, broadcast the arguments and flatten
    them (the routes work on 1-D arrays): (the broadcast shape, the flat arrays)."""
    if method not in METHODS:
        raise ValueError(f"unknown {what} method {method!r}; allowed: {', '.join(METHODS)}")
    arrays = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in values))
    return arrays[0].shape, [np.ascontiguousarray(v).ravel() for v in arrays]

#: points per block of the quadrature route (the (points x nodes) work arrays stay small)
_CHUNK = 2048

# rtol -> (Gauss nodes per panel, ratio of consecutive panel lengths).  Measured against the rule
# (32, 1.6) for cone, paraboloid, power laws n = 0.5, 1.5, 3 and a 13-knot spline at 400 points
# with r/a in [0, 3] (axis and r/a = 1e-12 ... 1e-3 included) and z/a in [1e-12, 30]: worst
# |error| / max(|value|, p_m) per row 3.4e-5, 2.9e-7, 1.1e-9 (spline), 2.4e-11 (spline), 1.3e-13
# (the rounding floor of the n = 0.5 power law, whose g' ~ rho^(-1/2) tip dominates).  Per core at
# rtol = 1e-10: about 25 000 points/s (cone, power laws), 5 000 points/s (spline: panels per knot).
_ORDERS = (
    (1e-4, (6, 4.0)),
    (1e-6, (8, 4.0)),
    (1e-8, (10, 3.0)),
    (1e-10, (12, 3.0)),
    (1e-12, (16, 2.5)),
)


def interior_orders(rtol: float) -> tuple[int, float]:
    """(nodes per panel, panel growth ratio) of the quadrature route for ``rtol``."""
    rtol = float(rtol)
    if not (math.isfinite(rtol) and rtol > 0.0):
        raise ValueError(f"rtol must be a positive finite number, got {rtol!r}")
    if rtol < _ORDERS[-1][0]:
        raise ValueError(f"rtol = {rtol!r} is below the reachable {_ORDERS[-1][0]:g} in double precision")
    for tol, o in _ORDERS:
        if rtol >= tol:
            return o
    return _ORDERS[-1][1]  # pragma: no cover - guarded above


def check_arguments(z, a, nu, profile, c=None, mu=None, mu_name="mu (coefficient of friction)"):
    """The interior entry points' argument check (flat arrays): ValueError naming the first bad one.
    ``c`` (stick radius) and ``mu`` are checked when given; ``mu_name`` is how messages call ``mu``."""
    if np.any(~(z >= 0.0)):
        raise ValueError("z (depth below the surface) must be >= 0 and not NaN")
    if np.any(~(a > 0.0)) or not np.all(np.isfinite(a)):
        raise ValueError("a (contact radius) must be positive and finite (a > 0)")
    if c is not None and np.any(~((c >= 0.0) & (c <= a))):
        raise ValueError("c (stick radius) must be in [0, a]")
    if np.any(~((nu >= 0.0) & (nu <= 0.5))):
        raise ValueError("nu (Poisson's ratio) must be in [0, 0.5]")
    if mu is not None and (np.any(~(mu >= 0.0)) or not np.all(np.isfinite(mu))):
        raise ValueError(f"{mu_name} must be finite and >= 0")
    if profile.kind == "flat_punch" and not np.allclose(a, profile.radius, rtol=1e-12, atol=0.0):
        raise ValueError(f"flat punch: the contact radius a must equal the punch radius {profile.radius!r}")
    if np.any(a > profile.max_radius * (1.0 + 1e-12)):
        raise ValueError(f"a (contact radius) exceeds the end of the tabulated profile, r = {profile.max_radius!r}")


def superpose(x, y, z, a, nu, profile, rtol, kernel, lower=None):
    """(I15) at points z > 0 for ``kernel`` = (integrate, names): ``integrate(nodes, profile)`` ->
    {name: array} sums the punch fields of a group of points over their nodes (``Nodes``).
    ``lower`` (optional, per point, 0 <= lower < a): integrate over [lower, a] instead of [0, a]
    ((I45): the partial-slip difference over [c, a] directly, without the tip's large parts)."""
    n, q = interior_orders(rtol)
    lower = np.zeros(x.size) if lower is None else np.broadcast_to(np.asarray(lower, dtype=float), x.shape)
    out: dict[str, np.ndarray] = {k: np.empty(x.size) for k in kernel[1]}
    for lo in range(0, x.size, _CHUNK):
        sl = slice(lo, lo + _CHUNK)
        part = _superpose_chunk(x[sl], y[sl], z[sl], a[sl], nu[sl], profile, n, q, kernel, lower[sl])
        for k, v in part.items():
            out[k][sl] = v
    return unresolved_as_nan(out)


def unresolved_as_nan(out):
    """Every exact value of (I15), (I28), (I33), (I42) at z > 0 is finite: a non-finite sum is a
    point the rule does not resolve (e.g. z = 5e-324 a, where z / rho is subnormal and the layer
    has no width in double precision); it is NaN, never +-inf, which would claim an infinite limit."""
    return {k: np.where(np.isfinite(v), v, math.nan) for k, v in out.items()}


def _breakpoints(r, z, a, profile, q, lower):
    """rho_s = min(r, a) (clipped to [lower, a]) and the panel ends per point as offsets from
    rho_s (rows, sorted, padded with a - rho_s): b1 - rho_s (b1 the end of the first panel
    [0, b1]; b1 = lower where lower > 0, the first panel then carries no weight), geometric
    panels +- h0 q^k about rho_s with h0 the layer width d = |(r, z) - (rho_s, 0)| (h0 <= rho_s / 2
    for a tip g' ~ rho^m0 with non-integer m0, whose scale is rho), 0, a - rho_s and the knots of
    a tabulated profile (docs/theory/interior.md (I16), (I45)).  Offsets keep the distance
    rho - r of the nodes next to the layer free of rounding."""
    rho_s = np.clip(r, lower, a)
    h0 = np.hypot(r - rho_s, z)
    smooth_tip = profile.kind == "tabulated" or float(profile.tip_exponent).is_integer()
    if not smooth_tip:
        h0 = np.where(rho_s > 0.0, np.minimum(h0, 0.5 * rho_s), h0)
    cut = lower > 0.0
    b1 = np.where(cut, lower, np.where(rho_s > 0.0, 0.5 * rho_s, np.minimum(h0, a)))
    knots = np.asarray(profile.r, dtype=float) if profile.kind == "tabulated" else np.zeros(0)
    knots = knots[knots > 0.0]
    if knots.size:
        b1 = np.where(cut, b1, np.minimum(b1, knots[0]))   # the first panel must not straddle a knot's cusp
    right = np.maximum(a - rho_s, 0.0)
    left = np.where(cut, rho_s - lower, 0.5 * rho_s)
    # log(right) - log(h0), not log(right / h0), and h0 q^k by repeated products, not q ** k: at a
    # subnormal depth (z = 5e-324 a) the ratio and q^k overflowed (OverflowError)
    with np.errstate(divide="ignore", invalid="ignore"):
        log_h0 = np.log(h0)
        kr = np.where(right > h0, np.ceil((np.log(right) - log_h0) / math.log(q)), 0.0)
        kl = np.where(left > h0, np.ceil((np.log(left) - log_h0) / math.log(q)), 0.0)
    kmax = int(max(kr.max(initial=0.0), kl.max(initial=0.0)))
    cols = [b1 - rho_s, np.zeros_like(r), right]
    step = h0.copy()
    for k in range(kmax):
        cols.append(np.where(k < kr, step, right))
        cols.append(np.where(k < kl, -step, right))
        step = step * q
    offsets = np.column_stack(cols)
    for kn in knots:
        # a geometric end within 1e-6 of a knot would leave the knot's cusp just inside a panel
        ko = (kn - rho_s)[:, None]
        offsets = np.where(np.abs(offsets - ko) <= 1e-6 * np.abs(offsets), ko, offsets)
    offsets = np.column_stack([offsets] + [np.where(kn < a, kn - rho_s, right) for kn in knots])
    start = (b1 - rho_s)[:, None]
    offsets = np.where(offsets < start, right[:, None], offsets)  # before b1: in panel 1
    # b1 again: a knot within 1e-6 of lower = b1 may have moved that end below it (then cut off)
    offsets = np.sort(np.column_stack([start, offsets]), axis=1)
    if knots.size:
        offsets = _grade_after_knots(offsets, knots, rho_s, right)
    return rho_s, offsets


def _grade_after_knots(offsets, knots, rho_s, right):
    """The panel that starts at a knot is graded (t = w^2); the panels after it must see the cusp
    no closer than half their length, as the panels about rho_s do: if the next two ends lie at
    distances e1 << e2 from the knot, ends at e1 * 3^j (j >= 1) are added up to e2."""
    extra = []
    for kn in knots:
        ko = (kn - rho_s)[:, None]
        later = np.where(offsets > ko, offsets, np.inf)
        e1 = np.min(later, axis=1, keepdims=True)
        e2 = np.min(np.where(later > e1, later, np.inf), axis=1, keepdims=True)
        with np.errstate(invalid="ignore", divide="ignore"):
            ratio = np.where(np.isfinite(e2), (e2 - ko) / (e1 - ko), 1.0)
        jmax = int(min(np.ceil(np.log(np.max(ratio)) / math.log(3.0)), 60)) if np.max(ratio) > 3.0 else 0
        for j in range(1, jmax):
            cand = ko + (e1 - ko) * 3.0 ** j
            extra.append(np.where((cand < e2) & (cand < right[:, None]), cand, right[:, None]))
    if not extra:
        return offsets
    return np.sort(np.concatenate([offsets] + extra, axis=1), axis=1)


def _superpose_chunk(x, y, z, a, nu, profile, n, q, kernel, lower):
    r = np.hypot(x, y)
    rho_s, offsets = _breakpoints(r, z, a, profile, q, lower)
    out: dict[str, np.ndarray] = {}
    # rows with more panels need more nodes: evaluate points with equal panel counts together
    count = np.sum(np.diff(offsets, axis=1) > 0.0, axis=1)
    for _, idx in group_by(count):
        rho, delta, weights = _rule(rho_s[idx], offsets[idx], profile, n, lower[idx] > 0.0)
        nodes = Nodes(x[idx], y[idx], z[idx], nu[idx], rho_s[idx], r[idx] - rho_s[idx], rho_s[idx] + offsets[idx, 0],
                       a[idx], rho, delta, weights, n + 4)
        for k, v in kernel[0](nodes, profile).items():
            out.setdefault(k, np.zeros(x.size))[idx] = v
    return out


# -- the flat rule: a node count per panel from its distance to the integrand's singularities ----

#: the a-priori node count of a panel (I54): n = ceil((ln(1/rtol) + _SLACK) / (2 ln min(rho_B, _RHO_CAP))),
#: rho_B the Bernstein ellipse through the nearest singularity (Gauss–Legendre error ~ rho_B^(-2n)),
#: at least _N_MIN and at most the table's n (n + 4 on [0, b1]).  Measured against the panel rule
#: (32, 1.6) at 412 points (r/a in [0, 3], z/a in [1e-12, 30], axis, r = a, far field), worst
#: |error| / (rtol max(|value|, p_m)) over n = 0.5, 3, the 13-knot spline and partial slip: slack 4
#: gave 0.89 (n = 0.5, rtol 1e-6), slack 6 0.45 (spline, rtol 1e-10, as the panel rule); without
#: the cap 0.78 at r = 0.06 a, z = 3.8 a (the integrand grows on large ellipses), with it 0.04.
_SLACK = 6.0
_N_MIN = 3
_RHO_CAP = 8.0
#: points per block of the flat rule: ~1.3e4 nodes (n = 3, rtol = 1e-10), work arrays of ~100 kB.
#: Per core 1.3-1.8x faster than 2048 points (large temporaries are returned to the system and
#: fault their pages in again: with glibc's trim and mmap thresholds raised, 2048 was as fast);
#: 128 points slower (per-block overhead)
_FLAT_CHUNK = 256


class Flat(NamedTuple):
    """All nodes of a block of points in one flat array: per point x, y, z, nu, r; per node its
    point ``row``, rho (1 where dead), rm1 = r/rho - 1 free of rounding, and the weight times g'(rho)
    (0 where dead)."""

    x: np.ndarray
    y: np.ndarray
    z: np.ndarray
    nu: np.ndarray
    r: np.ndarray
    row: np.ndarray
    rho: np.ndarray
    rm1: np.ndarray
    w: np.ndarray

    def node_nu(self):
        """nu per node, or the one value of the block (a scalar saves array operations)."""
        return float(self.nu[0]) if np.all(self.nu == self.nu[0]) else self.nu[self.row]

    def sum(self, values):
        """Per point: sum over its nodes of ``values``."""
        return np.bincount(self.row, weights=values, minlength=self.x.size)


def superpose_flat(x, y, z, a, nu, profile, rtol, kernel, lower=None):
    """(I15) at points z > 0 by the flat rule (I54): ``kernel`` = (integrate, names, fallback) with
    ``integrate(flat, profile)`` -> {name: array} per point, or None where a node lies on a punch's
    edge ring (z/rho underflowed); then that block is summed by ``fallback`` (a kernel of
    ``superpose``, whose Cartesian punch carries the edge-ring values (I14)).  ``lower`` as in
    ``superpose`` ((I45))."""
    n, q = interior_orders(rtol)
    lower = np.zeros(x.size) if lower is None else np.broadcast_to(np.asarray(lower, dtype=float), x.shape)
    out: dict[str, np.ndarray] = {k: np.empty(x.size) for k in kernel[1]}
    for lo in range(0, x.size, _FLAT_CHUNK):
        sl = slice(lo, lo + _FLAT_CHUNK)
        args = (x[sl], y[sl], z[sl], a[sl], nu[sl], profile)
        flat = _flat_nodes(*args, n, q, rtol, lower[sl])
        part = kernel[0](flat, profile)
        if part is None:
            part = _superpose_chunk(*args, n, q, (kernel[2], kernel[1]), lower[sl])
        for k, v in part.items():
            out[k][sl] = v
    return unresolved_as_nan(out)


def _bernstein(re, im):
    """rho_B of the ellipse with foci -1, 1 through the point re + i im: a + sqrt(a^2 - 1) with
    a the half sum of the distances to the foci."""
    semi = 0.5 * (np.hypot(re - 1.0, im) + np.hypot(re + 1.0, im))
    return semi + np.sqrt(np.maximum(semi * semi - 1.0, 0.0))


def _panel_orders(r, z, lo, hi, profile, rtol, n_max, knots, first=False):
    """The a-priori node count of each panel [lo, hi] (absolute rho) (I54): the nearest of the
    kernel's branch points rho = r +- i z ((I2): S = 0), the tip rho = 0 where g' ~ rho^m0 is not
    analytic (not on [0, b1], whose Jacobi weight carries it) and the knots below the panel (g' of
    a tabulated profile has a one-sided square-root cusp after each knot)."""
    c, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):     # rho_B = inf: a far singularity
        rb = _bernstein((r - c) / half, z / half)
        if not first and not (profile.kind == "tabulated" or float(profile.tip_exponent).is_integer()):
            rb = np.minimum(rb, _bernstein(c / half, 0.0))
        for kn in knots:
            sk = (kn - c) / half
            rb = np.where((kn <= lo) | first, np.minimum(rb, _bernstein(sk, 0.0)), rb)
        m = np.ceil((math.log(1.0 / rtol) + _SLACK) / (2.0 * np.log(np.minimum(rb, _RHO_CAP))))
    return np.clip(np.nan_to_num(m, nan=n_max, posinf=n_max), _N_MIN, n_max).astype(int)


@functools.lru_cache(maxsize=None)
def _padded_rules(n_max, kind, m0=0.0):
    """Row k (0 <= k <= n_max): the k-node rule on [0, 1] padded to n_max columns with weight 0,
    so that panels of different node counts are built in one vectorised step: "legendre",
    "knot" (t = w^2, (I17)) or "jacobi" (weight rho^m0 divided out: the weights of g' itself)."""
    T, W = np.full((n_max + 1, n_max), 0.5), np.zeros((n_max + 1, n_max))
    for k in range(1, n_max + 1):
        if kind == "jacobi" and m0 != 0.0:
            t, w = gauss_jacobi(k, m0)
            w = w / t ** m0
        else:
            t, w = gauss_legendre(k)
        if kind == "knot":
            t, w = t * t, 2.0 * t * w
        T[k, :k], W[k, :k] = t, w
    T.setflags(write=False)
    W.setflags(write=False)
    return T, W


def _flat_nodes(x, y, z, a, nu, profile, n, q, rtol, lower):
    """The panels of (I16) with the node counts of (I54), flattened: ``Flat``."""
    r = np.hypot(x, y)
    rho_s, offsets = _breakpoints(r, z, a, profile, q, lower)
    knots = np.asarray(profile.r, dtype=float) if profile.kind == "tabulated" else np.zeros(0)
    knots = knots[knots > 0.0]
    # [0, b1]: Gauss–Jacobi with the tip weight rho^m0 (none where the integral starts at lower > 0)
    idx = np.flatnonzero(~(lower > 0.0))
    b1 = rho_s[idx] + offsets[idx, 0]
    m1 = _panel_orders(r[idx], z[idx], 0.0 * b1, b1, profile, rtol, n + 4, knots, first=True)
    T, W = _padded_rules(n + 4, "jacobi", float(profile.tip_exponent))
    first = (idx, -rho_s[idx], b1, T[m1], W[m1])
    # the other panels: Gauss–Legendre (t = w^2 on those that start at a knot)
    lo, hi = offsets[:, :-1], offsets[:, 1:]
    pr, pc = np.nonzero(hi > lo)
    lo, hi = lo[pr, pc], hi[pr, pc]
    at_knot = np.zeros(lo.size, bool)
    for kn in knots:
        at_knot |= lo == kn - rho_s[pr]
    m = _panel_orders(r[pr], z[pr], rho_s[pr] + lo, rho_s[pr] + hi, profile, rtol, n, knots)
    m = np.where(at_knot, n, m)
    T, W = _padded_rules(n, "legendre")
    if knots.size:
        Tk, Wk = _padded_rules(n, "knot")
        T, W = np.where(at_knot[:, None], Tk[m], T[m]), np.where(at_knot[:, None], Wk[m], W[m])
    else:
        T, W = T[m], W[m]
    rows, deltas, ws = [], [], []
    for p_row, p_lo, length, t, w in (first, (pr, lo, hi - lo, T, W)):
        keep = w > 0.0                               # the padding
        rows.append(np.broadcast_to(p_row[:, None], t.shape)[keep])
        deltas.append((p_lo[:, None] + length[:, None] * t)[keep])
        ws.append((length[:, None] * w)[keep])
    row, delta, w = np.concatenate(rows), np.concatenate(deltas), np.concatenate(ws)
    rho = rho_s[row] + delta
    # a punch of radius rho << R = |(r, z)| adds O(g'(rho) rho^2 / R^2): below 1e-60 R nothing (1e-90 of the
    # value for g' ~ rho^(-1/2)); nearer 0, z/rho ~ 1e150 overflowed the products of (I53) (-inf on the axis
    # at z = 1e-12 a for n = 0.5 with the panel rule's 1e-150)
    live = rho > 1e-60 * np.hypot(r, z)[row]
    rho = np.where(live, rho, 1.0)
    rm1 = np.where(live, ((r - rho_s)[row] - delta) / rho, 0.0)
    w = np.where(live, w * profile.dg(rho), 0.0)
    return Flat(x, y, z, nu, r, row, rho, rm1, w)


def direction(x, y, r):
    """(x/r, y/r), (0, 0) on the axis (where every term it multiplies vanishes)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        on = r > 0.0
        return np.where(on, x / np.where(on, r, 1.0), 0.0), np.where(on, y / np.where(on, r, 1.0), 0.0)


def radial_cartesian(x, y, s_sum, zz_sum, e_sum, t_sum):
    """(I8) per point from the summed radial functions (times pi), with the E sum carrying r^2 and
    the T sum r, so that (x, y) may be the direction (x/r, y/r) or the point itself (then r^2 and r
    are the sums' powers of 1/rho)."""
    d = 0.5 * e_sum * (x - y) * (x + y)
    k = 1.0 / math.pi
    return {"xx": k * (0.5 * s_sum + d), "yy": k * (0.5 * s_sum - d), "zz": k * zz_sum, "xy": k * e_sum * x * y,
            "xz": k * x * t_sum, "yz": k * y * t_sum}


class Nodes(NamedTuple):
    """One group of points and their quadrature rule: coordinates, rho_s, r - rho_s, the end b1 of
    the first panel, the contact radius, nodes rho, offsets delta = rho - rho_s, weights (rows),
    and the number of nodes of the first panel (the first columns)."""

    x: np.ndarray
    y: np.ndarray
    z: np.ndarray
    nu: np.ndarray
    rho_s: np.ndarray
    r_minus_rho_s: np.ndarray
    b1: np.ndarray
    a: np.ndarray
    rho: np.ndarray
    delta: np.ndarray
    weights: np.ndarray
    first: int


def _rule(rho_s, offsets, profile, n, cut=False):
    """Nodes rho, their offsets delta = rho - rho_s and weights (rows): the first panel [0, b1] by
    Gauss–Jacobi with the tip weight rho^m0 (m0 > -1), the others by Gauss–Legendre (after
    t = w^2 on the panels of a tabulated profile that start at a knot, where g' has a one-sided
    square-root cusp), (I17); with ``cut`` (per row: the integral starts at lower = b1 > 0, (I45))
    the first panel carries no weight.  Zero-length panels are moved to the end of each row and cut off at the
    longest row's count."""
    b1 = rho_s[:, None] + offsets[:, :1]
    m0 = float(profile.tip_exponent)
    tj, wj = gauss_jacobi(n + 4, m0) if m0 != 0.0 else gauss_legendre(n + 4)
    first = b1 * tj[None, :]
    # b1^(1 + m0) w_j / rho_j^m0 = b1 w_j / t_j^m0 (t_j > 0): the powers of b1 under- or overflow
    # next to the axis (b1 = 5e-301 at r = 1e-300 a: NaN weights for m0 = 2)
    first_w = b1 * (wj / tj ** m0)[None, :]
    first_w = np.where(np.reshape(cut, (-1, 1)), 0.0, first_w)      # [0, lower] is not integrated
    lo, hi = offsets[:, :-1], offsets[:, 1:]
    empty = hi <= lo
    order = np.argsort(empty, axis=1, kind="stable")
    keep = max(int(np.max(np.sum(~empty, axis=1))), 1)
    lo, hi = (np.take_along_axis(v, order, axis=1)[:, :keep] for v in (lo, hi))
    t, w = gauss_legendre(n)
    t, w = np.broadcast_to(t, lo.shape + (n,)), np.broadcast_to(w, lo.shape + (n,))
    if profile.kind == "tabulated":
        # panels that start at a knot: t = w^2 turns the one-sided sqrt cusp into a polynomial
        knots = np.asarray(profile.r, dtype=float)
        at_knot = np.any(lo[:, :, None] == (knots[None, :] - rho_s[:, None])[:, None, :], axis=2)[:, :, None]
        t, w = np.where(at_knot, t * t, t), np.where(at_knot, 2.0 * t * w, w)
    length = (hi - lo)[:, :, None]
    delta = (lo[:, :, None] + length * t).reshape(len(lo), -1)
    weights = (length * w).reshape(len(lo), -1)
    rho = np.concatenate([first, rho_s[:, None] + delta], axis=1)
    delta = np.concatenate([first - rho_s[:, None], delta], axis=1)
    return rho, delta, np.concatenate([first_w, weights], axis=1)


def live_nodes(nd: Nodes):
    """The nodes that carry weight, rho (1 elsewhere) and r / rho - 1 = (r - rho_s - delta) / rho,
    free of the rounding of r / rho.  The nodes of zero-length panels and nodes so close to 0 that
    x / rho would overflow carry no weight (a punch of radius rho contributes O(rho^2) there)."""
    live = nd.weights > 0.0
    reach = np.hypot(np.hypot(nd.x, nd.y), nd.z)[:, None]
    live &= nd.rho > 1e-60 * reach          # as ``_flat_nodes``: nearer 0, z/rho overflowed (I53)
    rho = np.where(live, nd.rho, 1.0)
    rm1 = np.where(live, (nd.r_minus_rho_s[:, None] - nd.delta) / rho, 0.0)
    return live, rho, rm1
