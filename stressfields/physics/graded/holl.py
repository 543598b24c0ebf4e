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

Any other power-law indenter (G70): its pressure (1 - rho^2)^((1+k)/2) S(rho), with S interpolated once
(``PressureShape``) and evaluated at every radial node; two more panels towards the centre, where the
pressure goes like rho^(n+k-1), and the map rho = X u^m on the innermost one; for a steep profile panels
graded from the width of its edge layer.

Pure NumPy; arrays in, arrays out; lengths in units of the contact radius (rho = r/a, zeta = z/a).
"""
from __future__ import annotations

import math

import numpy as np

from ..quadrature import gauss_jacobi, gauss_legendre, table_row

__all__ = ["COMPONENTS", "orders", "disc_stress", "surface_limit", "PressureShape"]

COMPONENTS = ("rr", "tt", "zz", "rz")

#: rtol -> (Gauss nodes per radial panel, panel growth ratio, nodes per u-panel, u-panel length, nodes on
#: [pi/2, pi]).  Measured at k = 0 against the closed-form Hertz field at nu = 1/2 (the same kernel), 306
#: points r/a in [0, 3], z/a in [1e-6, 5] (edge and axis included), worst |error| / p0 per row: 8.7e-6,
#: 4.0e-7, 4.4e-9, 1.1e-11, 1.7e-13; the azimuth rule dominates the error.  The cost per row is measured
#: by benchmarks/graded_interior_rate.py (docs/bench/tuning.md)
_ORDERS = (
    (1e-4, (6, 4.0, 6, 2.0, 6)),
    (1e-6, (8, 3.0, 8, 2.0, 8)),
    (1e-8, (8, 3.0, 10, 2.0, 8)),
    (1e-10, (10, 3.0, 12, 1.5, 10)),
    (1e-12, (12, 2.5, 14, 1.5, 12)),
)
#: w beyond which the ring is far enough from the point for plain Gauss in psi on [0, pi/2]
_W_PLAIN = 0.5
_H_MIN = 1e-100         # the thinnest layer resolved (units of the disc radius)
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


def _radial_panels(r, z, q, tip=0, layer=None):
    """(base, offsets): the panel ends per point as offsets (rows, ascending) from ``base`` = r inside the
    contact, 1 (the edge) outside; the last panel [ends[-2], 1] ends at the edge.  Offsets keep the
    distance rho - r of the nodes next to a thin layer free of rounding (r + 1e-99 is r).  ``tip`` > 0:
    panels growing by q from the centre, cuts at rho = q^-j down to X q^-tip, X the first end beyond 0
    (G70).  ``layer``: ends at rho = 1 - layer q^j as well (G70), for a pressure that changes over a layer of
    that width at the edge."""
    inside = r < 1.0
    h = np.where(inside, np.minimum(z, 1.0 - r), np.minimum(np.hypot(r - 1.0, z), 1.0))
    base = np.where(inside, r, 1.0)
    start = np.where(inside, 0.0, -h)              # the ring next to the point (or the edge panel's start)
    edge = np.where(inside, 1.0 - r, 0.0)           # 1 - base, exact
    mid = np.where(inside, 0.5 * edge, start)
    with np.errstate(divide="ignore"):
        log_h = np.log(h)         # differences of logs: a ratio to a tiny h would overflow
        reach = np.maximum(base + start, 1e-300)
        n_left = np.where(base + start > 0.0, np.ceil((np.log(reach) - log_h) / math.log(q)), 0.0)
        n_right = np.where(inside, np.ceil((np.log(np.maximum(mid, 1e-300)) - log_h) / math.log(q)), 0.0)
    jl = int(np.max(n_left, initial=0.0)) + 1
    jr = int(np.max(np.maximum(n_right, 0.0), initial=0.0)) + 1
    cols = [start, mid, edge, -base]
    step = h.copy()
    for j in range(max(jl, jr)):
        if j < jl:
            cols.append(np.maximum(start - step, -base))
        if j < jr:
            cols.append(np.where(inside, np.minimum(step, mid), start))
        step = step * q
    ends = np.sort(np.column_stack(cols), axis=1)
    if tip:
        # X: the first end beyond the centre (the ends at or below -base are the centre, repeated); the
        # cuts q^-j reach from the disc's radius down to X q^-tip, so that no panel [u, v] near the centre
        # has v/u > q (a wider one would see the centre's rho^s as an end-point singularity)
        X = np.min(np.where(ends > -base[:, None], ends, np.inf), axis=1) + base
        low = X * q ** -float(tip)
        J = int(np.ceil(-np.log(np.min(low)) / math.log(q)))
        cuts = np.maximum(q ** -np.arange(1.0, J + 1.0), low[:, None])
        ends = np.sort(np.column_stack([ends, cuts - base[:, None]]), axis=1)
    if layer is not None:
        # from the edge inwards, widths layer q^j up to 1/2 (offsets from base, at least -base: the centre)
        steps = layer * q ** np.arange(0.0, max(math.ceil(math.log(0.5 / layer) / math.log(q)), 0) + 1.0)
        cuts = np.maximum((1.0 - base)[:, None] - steps, -base[:, None])
        ends = np.sort(np.column_stack([ends, cuts]), axis=1)
    return base, ends


def _radial_rule(r, z, e, q, n, shape=None, tip=(0, 1)):
    """Nodes as (rho, rho - r) (rows) and weights including the pressure (1 - rho^2)^e (Gauss-Jacobi on
    the last panel), times ``shape(rho)`` if given; ``tip`` = (panels, power): the panels of
    :func:`_radial_panels` towards the centre, and the power m of the map rho = X u^m on the panel [0, X]
    that touches it (G70)."""
    base, ends = _radial_panels(r, z, q, tip[0], None if shape is None else shape.layer)
    x0, x1 = ends[:, :-1], ends[:, 1:]
    t, wt = gauss_legendre(n)
    lo, hi = x0[:, :-1, None], x1[:, :-1, None]
    if tip[1] > 1:
        # on the centre's panel u^m turns A + rho^s B into smooth terms and u^(m(2+s)-1) (G70)
        centre = lo <= -base[:, None, None]
        tm = np.where(centre, t ** tip[1], t)
        wm = np.where(centre, tip[1] * t ** (tip[1] - 1) * wt, wt)
        off = lo + (hi - lo) * tm
        w = (hi - lo) * wm
    else:
        off = lo + (hi - lo) * t                      # rho - base
        w = (hi - lo) * wt
    b3, edge = base[:, None, None], (1.0 - base)[:, None, None]
    with np.errstate(invalid="ignore"):
        press = np.where(off < edge, ((edge - off) * (1.0 + b3 + off)) ** e[:, None, None], 0.0)
    w = (w * press).reshape(r.size, -1)
    off = off.reshape(r.size, -1)
    # last panel: int_{x0}^{1} (1 - rho)^e F(rho) drho = L^(e+1) int_0^1 s^e F(1 - L s) ds
    L = (x1[:, -1] - x0[:, -1])
    out_o, out_w = [off], [w]
    for ev in np.unique(e):
        tj, wj = gauss_jacobi(n, float(ev))
        sel = e == ev
        oj = (1.0 - base)[:, None] - L[:, None] * tj
        wjj = np.where(sel[:, None], L[:, None] ** (ev + 1.0) * wj * (1.0 + base[:, None] + oj) ** ev, 0.0)
        out_o.append(np.where(sel[:, None], oj, 0.0))
        out_w.append(wjj)
    off = np.concatenate(out_o, axis=1)
    rho = base[:, None] + off
    weights = np.concatenate(out_w, axis=1)
    if shape is not None:
        # a node rounded onto the centre (rho = base + off = 0) carries a share below rounding: dropped, as
        # the shape may be infinite there
        weights[rho <= 0.0] = 0.0
        live = weights != 0.0
        weights[live] = weights[live] * shape(rho[live])
    return rho, (r - base)[:, None] - off, weights


def _azimuth(r, z, rho, dr, chi, orders_):
    """Ring sums int_0^pi (d_xx, d_yy, d_zz, d_xz) z^(chi-2) R^-(chi+2) dpsi at nodes (flat arrays, one
    entry per radial node; ``dr`` = r - rho without rounding).  The nodes are grouped by the number of
    u-panels they need (0: plain Gauss in psi), so that a few rings next to the point do not pad the
    rule of all the others."""
    _, _, nu_, lu, nf = orders_
    D2 = dr * dr + z * z
    B = 2.0 * r * rho
    with np.errstate(over="ignore"):         # B = 0 (axis): w = inf, the plain rule
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
        zi, rhoi, chii, D2i = z[i, None], rho[i, None], chi[i, None], D2[i, None]
        s2 = s * s
        R2 = D2i + 2.0 * B[i, None] * s2
        dx = dr[i, None] + 2.0 * rhoi * s2               # r - rho cos(psi), no cancellation
        # z^(chi-2) R^-(chi+2) = (z^2/D^2)^((chi-2)/2) (D^2/R^2)^m D^-4: both ratios <= 1, and D^-4 is
        # shared with the numerators (over D^2) and the weights, so that a layer of 1e-100 neither
        # overflows nor underflows
        zd = zi * zi / D2i
        with np.errstate(divide="ignore", under="ignore"):
            g = np.exp(0.5 * (chii - 2.0) * np.log(zd) + 0.5 * (chii + 2.0) * np.log(D2i / R2)) * (wts / D2i)
        out["rr"][i] = np.sum(dx * dx / D2i * g, axis=1)
        out["tt"][i] = np.sum(rhoi * rhoi * 4.0 * s2 * (1.0 - s2) / D2i * g, axis=1)
        out["zz"][i] = zd[:, 0] * np.sum(g, axis=1)
        out["rz"][i] = np.sqrt(zd[:, 0]) * np.sum(dx / np.sqrt(D2i) * g, axis=1)
    return out


def disc_stress(rho, zeta, k, e, rtol: float = 1e-10, shape=None) -> dict[str, np.ndarray]:
    """The stress (G62) of the pressure p = (1 - rho^2)^e on the unit disc (e > -1), kernel chi = 3 + k,
    at (rho, zeta), zeta > 0; lengths in units of the disc radius, stresses per unit pressure amplitude.

    Components "rr", "tt", "zz", "rz" (tension positive, z into the body).  Relative error at most rtol
    of the largest component's magnitude scale (the pressure amplitude), by the rule of (G63)-(G65).

    ``shape`` (a :class:`PressureShape` of one k, e its edge exponent): the pressure is
    (1 - rho^2)^e shape(rho), smooth at the edge but with the centre behaviour rho^(n+k-1) of a power-law
    indenter, which the extra panels towards rho = 0 of (G70) resolve; the error is then at most
    rtol max(|value|, p_m), p_m the mean of the pressure over the disc (measured, (G70))."""
    rho, zeta, k, e = (np.ascontiguousarray(v, dtype=float).ravel()
                       for v in np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (rho, zeta, k, e))))
    o = orders(rtol)
    n, q = o[0], o[1]
    tip = (0, 1) if shape is None else _tip_panels(shape.centre, q, n, rtol)
    out = {c: np.empty(rho.size) for c in COMPONENTS}
    # blocks of points with similar panel counts (the rules are padded to the block's largest): by the
    # first panel width h of _radial_panels and the depth relative to the radius
    h = np.where(rho < 1.0, np.minimum(zeta, 1.0 - rho), np.minimum(np.hypot(rho - 1.0, zeta), 1.0))
    # a layer thinner than _H_MIN (a point within 1e-100 a of the surface, or of the surface and the edge
    # ring at once) would need ~250 panels a side: NaN, which the entry points flag as not resolved
    resolved = h >= _H_MIN
    for c in COMPONENTS:
        out[c][~resolved] = np.nan
    with np.errstate(divide="ignore"):
        order = np.lexsort((np.log(zeta / np.maximum(rho, zeta)).round(), np.log(h).round()))
    order = order[resolved[order]]
    for lo in range(0, order.size, _BLOCK):
        sl = order[lo:lo + _BLOCK]
        r, z, kk, ee = rho[sl], zeta[sl], k[sl], e[sl]
        nodes, dr, weights = _radial_rule(r, z, ee, q, n, shape, tip)
        chi = 3.0 + kk
        live = weights != 0.0             # empty panels and the other exponents' edge rules carry nothing
        rows = np.broadcast_to(np.arange(r.size)[:, None], nodes.shape)[live]
        ring = _azimuth(r[rows], z[rows], nodes[live], dr[live], chi[rows], o)
        for c in COMPONENTS:
            total = np.bincount(rows, weights=weights[live] * nodes[live] * ring[c], minlength=r.size)
            out[c][sl] = -(chi / math.pi) * total
    return out


def _tip_panels(s, q, n, rtol):
    """(panels, power) towards the centre where the pressure is A(rho^2) + rho^s B(rho^2) (G70): two panels
    growing by q, then on the innermost one rho = X u^m, which leaves u^(2m-1) (smooth) and u^(m(2+s)-1),
    whose n-point Gauss rule errs by about n^(-2m(2+s)): m(2+s) from rtol/100."""
    if s is None:       # a pressure smooth at the centre (even in rho, the paraboloid): no extra panels
        return 0, 1
    need = math.log(100.0 / rtol) / (2.0 * math.log(n))
    return 2, max(1, math.ceil(need / (2.0 + s)))


#: Chebyshev points per dyadic panel of PressureShape (the default; steep shapes take more)
_M = 20


class PressureShape:
    """S(rho) = Phi(rho) / (1 - rho^2)^e on 0 < rho < 1 (G70): the pressure shape ``phi`` of a power-law
    indenter (G18) without its edge factor, interpolated once and evaluated at every radial node.

    ``phi`` is called once, on the nodes of the interpolant: ``points`` Chebyshev points on each dyadic
    panel [2^-(j+1), 2^-j], j = 0..40 (S is analytic except at rho = 0, three half-widths beyond each
    panel: with 20 the interpolation error is of the order 5.8^-20 ~ 1e-15 of S there); below 2^-41
    ``phi`` itself.
    ``centre``: the exponent s of the part of S that goes like rho^s at the centre (s = n + k - 1 for a
    power law; rho^0 stands for log rho), None for a shape smooth in rho^2 there (the paraboloid); it
    decides the extra radial panels of :func:`disc_stress`.  ``points``: more than 20 for a shape that
    changes fast near the edge; ``layer``: the width of such an edge layer (f = A r^n: Phi is the flat
    punch's shape (1 - rho^2)^(-(1-k)/2)/n away from the edge and turns to (1 - rho)^((1+k)/2) within
    about a/n of it), None if there is none; :func:`disc_stress` then grades its radial panels towards the
    edge from that width.
    """

    _J = 41

    def __init__(self, phi, e: float, centre: float | None, points: int = _M, layer: float | None = None):
        self._phi, self.e, self.centre = phi, float(e), None if centre is None else float(centre)
        self.layer = layer
        self._M = int(points)
        i = np.arange(self._M)
        self._t = np.cos((2 * i + 1) * math.pi / (2 * self._M))          # Chebyshev points on [-1, 1]
        self._lam = (-1.0) ** i * np.sin((2 * i + 1) * math.pi / (2 * self._M))
        lo = 2.0 ** -np.arange(1.0, self._J + 1.0)                       # panel j: [lo_j, 2 lo_j]
        nodes = lo[:, None] * (1.5 + 0.5 * self._t)
        self._vals = self._direct(nodes.ravel()).reshape(nodes.shape)

    def _direct(self, rho):
        rho = np.asarray(rho, dtype=float)
        return self._phi(rho) / ((1.0 - rho) * (1.0 + rho)) ** self.e

    def __call__(self, rho):
        rho = np.asarray(rho, dtype=float)
        out = np.empty(rho.shape)
        flat, res = rho.ravel(), out.reshape(-1)
        small = flat < 2.0 ** -self._J
        if np.any(small):
            res[small] = self._direct(flat[small])
        big = np.flatnonzero(~small)
        for s in range(0, big.size, 8192):                  # bounds the (points x nodes) work arrays
            sl = big[s:s + 8192]
            x = np.minimum(flat[sl], 1.0)
            _, ex = np.frexp(x)                             # x = m 2^ex, m in [1/2, 1): panel j = -ex
            j = np.clip(-ex, 0, self._J - 1)
            lo = np.ldexp(0.5, -j)                          # 2^-(j+1)
            u = (x - lo) / lo * 2.0 - 1.0                   # [lo, 2 lo] -> [-1, 1]
            d = u[:, None] - self._t
            v = self._vals[j]
            with np.errstate(divide="ignore", invalid="ignore"):
                w = self._lam / d
                val = np.sum(w * v, axis=1) / np.sum(w, axis=1)
            hit = ~np.isfinite(val)
            if hit.any():
                val[hit] = v[hit, np.argmin(np.abs(d[hit]), axis=1)]
            res[sl] = val
        return out
