"""The stress below the surface of a power-law graded half-space with Holl's Poisson ratio nu = 1/(2+k):
the area integral of the purely radial point-load field over the contact (docs/theory/graded.md (G60)-(G66)).

For E(z) = E0 (z/c0)^k and nu = 1/(2+k) the field of a normal point load P at the origin is purely
radial (Holl 1940; Frohlich's concentration factor chi = 3 + k):

    sigma_R = -chi P cos^(chi-2)(theta) / (2 pi R^2),  every other spherical component 0,      (G60)

theta measured from the depth axis.  A pressure p(rho) on the disc rho < a then gives, at the point
(r, 0, z) of the plane y = 0 through the axis, with d = (r - rho cos psi, -rho sin psi, z) the vector
from the load point (rho cos psi, rho sin psi, 0), R = |d|:

    sigma_ij = -(chi/pi) z^(chi-2) int_0^a p(rho) rho int_0^pi d_i d_j R^-(chi+2) dpsi drho        (G62)

(sigma_rr = sigma_xx, sigma_tt = sigma_yy, sigma_rz = sigma_xz there; the other two vanish by symmetry).
The quadrature (G63)-(G65): the radial integral on panels that grow geometrically away from the ring
rho = min(r, a) next to the point (first width: the distance z, or the distance to the edge if
smaller), Gauss-Jacobi with the edge exponent of the pressure on the last panel [., a]; the azimuth on
[0, pi/2] by the substitution sin(psi/2) = w sinh u, w = D/sqrt(4 r rho), D^2 = (r - rho)^2 + z^2,
which turns the near-singular ring kernel R^-(chi+2) = (D cosh u)^-(chi+2) into a smooth one, on
Gauss panels of fixed length in u (their number grows like log(r/D)), and plain Gauss on [pi/2, pi].
Node counts from rtol (``orders``).

Pure NumPy; arrays in, arrays out; lengths in units of the contact radius (rho = r/a, zeta = z/a).
"""
from __future__ import annotations

import math

import numpy as np

from ..quadrature import gauss_jacobi, gauss_legendre, table_row

__all__ = ["COMPONENTS", "orders", "disc_stress", "surface_limit"]

COMPONENTS = ("rr", "tt", "zz", "rz")

#: rtol -> (Gauss nodes per radial panel, panel growth ratio, nodes per u-panel, u-panel length, nodes on
#: [pi/2, pi]).  Measured at k = 0 against the closed-form Hertz field at nu = 1/2 (the same kernel), 306
#: points r/a in [0, 3], z/a in [1e-6, 5] (edge and axis included), worst |error| / p0 per row: 8.7e-6,
#: 4.0e-7, 4.4e-9, 1.1e-11, 7.0e-13; the azimuth rule dominates the error.  Cost per CPU second (k = 0.5,
#: benchmarks/graded_interior_rate.py, medians of 5, a loaded 2-core machine): a rho-z map 41 x 25 with
#: z/a >= 0.02: 128 000, 77 000, 79 000, 52 000, 38 000 points; shallow points z/a in [1e-6, 1]: 30 000,
#: 14 000, 12 000, 7 800, 5 200
_ORDERS = (
    (1e-4, (6, 4.0, 6, 2.0, 6)),
    (1e-6, (8, 3.0, 8, 2.0, 8)),
    (1e-8, (8, 3.0, 10, 2.0, 8)),
    (1e-10, (10, 3.0, 12, 1.5, 10)),
    (1e-12, (12, 2.5, 14, 1.5, 12)),
)
#: w beyond which the ring is far enough from the point for plain Gauss in psi on [0, pi/2]
_W_PLAIN = 0.5
_BLOCK = 256            # points per block: (points x radial nodes x azimuth nodes) stays ~ 30 MB


def orders(rtol: float) -> tuple[int, float, int, float, int]:
    """(radial nodes per panel, growth ratio, nodes per u-panel, u-panel length, nodes on [pi/2, pi])."""
    return table_row(_ORDERS, rtol, "the 2-D quadrature")


def surface_limit(p, k) -> dict[str, np.ndarray]:
    """The limit z -> 0+ of (G62) at a point where the pressure is p (G66): sigma_zz = -p,
    sigma_rr = sigma_tt = -p/(1+k), sigma_rz = 0 (0 outside the contact, where p = 0)."""
    p = np.asarray(p, dtype=float)
    k = np.asarray(k, dtype=float)
    with np.errstate(invalid="ignore"):
        side = -p / (1.0 + k)
    zero = np.zeros(np.broadcast_shapes(p.shape, k.shape))
    return {"rr": side + zero, "tt": side + zero, "zz": -p + zero, "rz": zero}


def _radial_panels(r, z, q):
    """Panel ends per point (rows, ascending), the last panel [ends[-2], 1] ending at the edge."""
    inside = r < 1.0
    h = np.where(inside, np.minimum(z, 1.0 - r), np.minimum(np.hypot(r - 1.0, z), 1.0))
    start = np.where(inside, r, 1.0 - h)       # the ring next to the point (or the edge panel's start)
    mid = np.where(inside, 0.5 * (r + 1.0), start)
    with np.errstate(divide="ignore"):
        n_left = np.where(start > 0.0, np.ceil(np.log(np.maximum(start, 1e-300) / h) / math.log(q)), 0.0)
        n_right = np.where(inside, np.ceil(np.log(np.maximum(mid - r, 1e-300) / h) / math.log(q)), 0.0)
    jl = int(np.max(n_left, initial=0.0)) + 1
    jr = int(np.max(np.maximum(n_right, 0.0), initial=0.0)) + 1
    cols = [start, mid, np.ones_like(r), np.zeros_like(r)]
    step = h.copy()
    for j in range(max(jl, jr)):
        if j < jl:
            cols.append(np.maximum(start - step, 0.0))
        if j < jr:
            cols.append(np.where(inside, np.minimum(r + step, mid), start))
        step = step * q
    return np.sort(np.column_stack(cols), axis=1)


def _radial_rule(r, z, e, q, n):
    """Nodes rho (rows) and weights including the pressure (1 - rho^2)^e (Gauss-Jacobi on the last panel)."""
    ends = _radial_panels(r, z, q)
    x0, x1 = ends[:, :-1], ends[:, 1:]
    t, wt = gauss_legendre(n)
    lo, hi = x0[:, :-1, None], x1[:, :-1, None]
    rho = lo + (hi - lo) * t
    w = (hi - lo) * wt
    with np.errstate(invalid="ignore"):
        press = np.where(rho < 1.0, ((1.0 - rho) * (1.0 + rho)) ** e[:, None, None], 0.0)
    w = w * press
    rho, w = rho.reshape(r.size, -1), w.reshape(r.size, -1)
    # last panel: int_{x0}^{1} (1 - rho)^e F(rho) drho = L^(e+1) int_0^1 s^e F(1 - L s) ds
    L = (x1[:, -1] - x0[:, -1])
    out_r, out_w = [rho], [w]
    for ev in np.unique(e):
        tj, wj = gauss_jacobi(n, float(ev))
        sel = e == ev
        rj = 1.0 - L[:, None] * tj
        wjj = np.where(sel[:, None], L[:, None] ** (ev + 1.0) * wj * (1.0 + rj) ** ev, 0.0)
        out_r.append(np.where(sel[:, None], rj, 0.5))
        out_w.append(wjj)
    return np.concatenate(out_r, axis=1), np.concatenate(out_w, axis=1)


def _azimuth(r, z, rho, chi, orders_):
    """Ring sums int_0^pi (d_xx, d_yy, d_zz, d_xz) z^(chi-2) R^-(chi+2) dpsi at nodes (flat arrays, one
    entry per radial node).  The nodes are grouped by the number of u-panels they need (0: plain Gauss
    in psi), so that a few rings next to the point do not pad the rule of all the others."""
    _, _, nu_, lu, nf = orders_
    D2 = (r - rho) ** 2 + z ** 2
    B = 2.0 * r * rho
    w = np.sqrt(D2 / np.maximum(2.0 * B, 1e-300))
    near = w < _W_PLAIN
    U = np.arcsinh(np.sqrt(0.5) / np.where(near, w, 1.0))
    count = np.where(near, np.maximum(np.ceil(U / lu), 1.0), 0.0).astype(int)
    out = {c: np.empty(r.size) for c in COMPONENTS}
    tf, wf = gauss_legendre(nf)
    s_far = np.sin(0.25 * math.pi * (1.0 + tf))
    w_far = 0.5 * math.pi * wf
    tu, wu = gauss_legendre(nu_)
    for panels in np.unique(count):
        i = np.flatnonzero(count == panels)
        if panels == 0:             # plain Gauss in psi on [0, pi/2], as many nodes as one u-panel
            s = np.broadcast_to(np.sin(0.25 * math.pi * tu), (i.size, nu_))
            wts = np.broadcast_to(0.5 * math.pi * wu, (i.size, nu_))
        else:                       # u-panels of length lu, the last clipped at U
            Ui, wi = U[i, None], w[i, None]
            parts = []
            for j in range(panels):
                a0, a1 = np.minimum(j * lu, Ui), np.minimum((j + 1) * lu, Ui)
                u = a0 + (a1 - a0) * tu
                sj = wi * np.sinh(u)
                parts.append((sj, (a1 - a0) * wu * 2.0 * wi * np.cosh(u) / np.sqrt(np.maximum(1.0 - sj * sj, 0.5))))
            s = np.concatenate([p_[0] for p_ in parts], axis=1)
            wts = np.concatenate([p_[1] for p_ in parts], axis=1)
        s = np.concatenate([s, np.broadcast_to(s_far, (i.size, nf))], axis=1)
        wts = np.concatenate([wts, np.broadcast_to(w_far, (i.size, nf))], axis=1)
        ri, zi, rhoi, chii = r[i, None], z[i, None], rho[i, None], chi[i, None]
        s2 = s * s
        R2 = D2[i, None] + 2.0 * B[i, None] * s2
        dx = (ri - rhoi) + 2.0 * rhoi * s2               # r - rho cos(psi), no cancellation
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            kern = np.exp((chii - 2.0) * np.log(zi) - 0.5 * (chii + 2.0) * np.log(R2)) * wts
        out["rr"][i] = np.sum(dx * dx * kern, axis=1)
        out["tt"][i] = np.sum(rhoi * rhoi * 4.0 * s2 * (1.0 - s2) * kern, axis=1)
        out["zz"][i] = zi[:, 0] ** 2 * np.sum(kern, axis=1)
        out["rz"][i] = zi[:, 0] * np.sum(dx * kern, axis=1)
    return out


def disc_stress(rho, zeta, k, e, rtol: float = 1e-10) -> dict[str, np.ndarray]:
    """The stress (G62) of the pressure p = (1 - rho^2)^e on the unit disc (e > -1), kernel chi = 3 + k,
    at (rho, zeta), zeta > 0; lengths in units of the disc radius, stresses per unit pressure amplitude.

    Components "rr", "tt", "zz", "rz" (tension positive, z into the body).  Relative error at most rtol
    of the largest component's magnitude scale (the pressure amplitude), by the rule of (G63)-(G65)."""
    rho, zeta, k, e = (np.ascontiguousarray(v, dtype=float).ravel()
                       for v in np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (rho, zeta, k, e))))
    o = orders(rtol)
    n, q = o[0], o[1]
    out = {c: np.empty(rho.size) for c in COMPONENTS}
    # blocks of points with similar panel counts (the rules are padded to the block's largest): by the
    # first panel width h of _radial_panels and the depth relative to the radius
    h = np.where(rho < 1.0, np.minimum(zeta, 1.0 - rho), np.minimum(np.hypot(rho - 1.0, zeta), 1.0))
    with np.errstate(divide="ignore"):
        order = np.lexsort((np.log(zeta / np.maximum(rho, zeta)).round(), np.log(h).round()))
    for lo in range(0, rho.size, _BLOCK):
        sl = order[lo:lo + _BLOCK]
        r, z, kk, ee = rho[sl], zeta[sl], k[sl], e[sl]
        nodes, weights = _radial_rule(r, z, ee, q, n)
        chi = 3.0 + kk
        live = weights != 0.0             # empty panels and the other exponents' edge rules carry nothing
        rows = np.broadcast_to(np.arange(r.size)[:, None], nodes.shape)[live]
        ring = _azimuth(r[rows], z[rows], nodes[live], chi[rows], o)
        for c in COMPONENTS:
            total = np.bincount(rows, weights=weights[live] * nodes[live] * ring[c], minlength=r.size)
            out[c][sl] = -(chi / math.pi) * total
    return out
