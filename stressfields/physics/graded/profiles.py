"""Profiles of axisymmetric indenters and the MDR profile transform for graded media.

Hess & Popov 2016 (Facta Univ. Mech. Eng. 14(3) 251-268), eqs. (5)-(9) and Table 1 (docs/theory/graded.md (G11)-(G14)):
the 3D profile f(r) maps onto the 1D profile
    g(x) = |x|^(1-k) int_0^|x| f'(r) (x^2 - r^2)^(-(1-k)/2) dr                         (5)
with inverse
    f(r) = (2/pi) cos(k pi/2) int_0^r x^k g(x) (r^2 - x^2)^(-(1+k)/2) dx                (6)
and, for power laws f = A_n r^n, g = kappa(n, k) A_n |x|^n with
    kappa(n, k) = (n/2) B(n/2, (1+k)/2)                                                  (9).

Closed-form kernels describe a profile by the two plain numbers (n, A_n): parabolic
f = r^2/(2R) is (2, 1/(2R)), conical f = r tan(theta) is (1, tan(theta)); see
:func:`parabolic` and :func:`conical`.  The quadrature route takes a profile *object*
(:class:`PowerLaw` or :class:`Tabulated`) that provides f, f' and f''.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import beta as _B, betainc, betaincc

from .. import quadrature
from ..setup_cache import SetupCache
from . import fastsum
from ._validate import as_array, check_k, check_positive
from .material import cos_half_pi_k

__all__ = ["kappa", "parabolic", "conical", "g_power_law", "PowerLaw", "Tabulated",
           "g_quad", "dg_quad", "f_from_g_quad"]


def kappa(n, k):
    """kappa(n, k) = (n/2) B(n/2, (1+k)/2), eq. (9), docs/theory/graded.md (G13).

    Dimensionless; broadcasts over n and k.
    """
    n = check_positive("n", n)
    k = check_k(k)
    return 0.5 * n * _B(0.5 * n, 0.5 * (1.0 + k))


def parabolic(R):
    """(n, A_n) of the paraboloid f = r^2/(2R), eq. (16).  R in length units."""
    R = check_positive("R", R)
    return 2.0, 0.5 / R


def conical(tan_theta):
    """(n, A_n) of the cone f = r tan(theta), eq. (25)."""
    return 1.0, check_positive("tan_theta", tan_theta)


def g_power_law(x, *, k, n, A_n):
    """1D profile g(x) = kappa(n,k) A_n |x|^n of f = A_n r^n, eqs. (7)-(8), Table 1."""
    x = as_array("x", x)
    return kappa(n, k) * check_positive("A_n", A_n) * np.abs(x) ** n


@dataclass(frozen=True)
class PowerLaw:
    """f(r) = A r^n for the quadrature route (which never uses kappa).

    Arguments in the order of ``physics.axisymmetric.profiles.PowerLaw(A, n)``; the closed-form
    kernels call the same amplitude ``A_n``.
    """

    A: float
    n: float

    def __post_init__(self):
        check_positive("n", self.n)
        check_positive("A", self.A)

    @classmethod
    def parabolic(cls, R):
        n, A = parabolic(float(R))
        return cls(A=A, n=n)

    @classmethod
    def conical(cls, tan_theta):
        n, A = conical(float(tan_theta))
        return cls(A=A, n=n)

    r_max = np.inf
    breaks = ()

    def f(self, r):
        return self.A * np.abs(r) ** self.n

    def df(self, r):
        return self.n * self.A * np.abs(r) ** (self.n - 1.0)

    def d2f(self, r):
        if self.n == 1.0:
            return np.zeros_like(np.asarray(r, dtype=float))
        return self.n * (self.n - 1.0) * self.A * np.abs(r) ** (self.n - 2.0)


class Tabulated:
    """Profile tabulated as f(r_i) on 0 = r_0 < r_1 < ... (length units), cubic-spline interpolated.

    f is shifted so that f(0) = 0.  ``slope_at_0`` clamps f'(0) (use 0 for a smooth, rounded
    tip; default: not-a-knot, which also fits a cone).  A cubic spline reproduces polynomials of
    degree <= 3 exactly, which the tests use.  Evaluating beyond the last tabulated radius raises.

    Because the spline is piecewise cubic, the transform (5) is done exactly, piece by piece, with
    regularised incomplete beta functions (:meth:`g`, :meth:`dg`; docs/theory/graded.md (G14)); the
    outer MDR integrals are split at the knots (``breaks``), where the integrands are not smooth.
    The panel rules (:meth:`dg_panels`) form g' once per (a, k, order) on a fixed number of nodes per
    panel, shared by every point, by the block tree of :meth:`dg_fast`: O(log knots) per node
    (docs/theory/graded.md (G52)-(G54)), where the sum (G14) over every piece costs O(knots).
    """

    def __init__(self, r, f, slope_at_0=None):
        r = np.asarray(r, dtype=float)
        f = np.asarray(f, dtype=float)
        if r.ndim != 1 or r.shape != f.shape or r.size < 4:
            raise ValueError("r and f must be 1-D arrays of equal length >= 4")
        if r[0] != 0.0 or not np.all(np.diff(r) > 0) or not np.all(np.isfinite(f)):
            raise ValueError("r must start at 0 and increase strictly; f must be finite")
        bc = "not-a-knot" if slope_at_0 is None else ((1, float(slope_at_0)), "not-a-knot")
        # the samples and the end condition: with slope_at_0 None the spline is the axisymmetric family's
        # (``axisymmetric.tabulated``, not-a-knot through f - f[0] too), whose interior serves k = 0
        self.samples = r.copy(), f.copy()
        self.slope_at_0 = None if slope_at_0 is None else float(slope_at_0)
        self.r_max = float(r[-1])
        self.breaks = r[1:-1].copy()
        from scipy.interpolate import CubicSpline   # here: its import (0.1 s) only for tabulated profiles

        self._s = CubicSpline(r, f - f[0], bc_type=bc)
        self._ds = self._s.derivative(1)
        self._d2s = self._s.derivative(2)
        # f'(r) = b0 + b1 r + b2 r^2 on each piece (global monomials; loses ~(r_max/h)^2 eps)
        c3, c2, c1, _ = self._s.c
        ri = r[:-1]
        self._b = np.stack([3 * c3 * ri ** 2 - 2 * c2 * ri + c1, 2 * c2 - 6 * c3 * ri, 3 * c3])
        self._lo, self._hi = r[:-1], r[1:]
        # the set-up derived from the samples (block tree of h, panel values of g' per (a, k, order),
        # their trees, the orders per rtol): built once per key, bounded, safe for dask's threads (a
        # profile object serves every chunk of a call and, through ``Indenter.tabulated``, every call)
        self._setup = SetupCache(max_entries=32, max_bytes=64 << 20)
        self.evaluations = 0          # nodes at which g' was formed for the panel rules (dg_panels)
        self.block_terms = 0          # dg_fast: kernel values at the Chebyshev points of far blocks
        self.exact_terms = 0          # dg_fast: (node, piece) pairs summed exactly by (G14)

    def _arg(self, r):
        r = np.abs(np.asarray(r, dtype=float))
        if np.any(r > self.r_max * (1 + 1e-12)):
            raise ValueError(f"r = {float(r.max())!r} is outside the tabulated range 0 <= r <= {self.r_max!r}")
        return r

    def f(self, r):
        return self._s(self._arg(r))

    def df(self, r):
        return self._ds(self._arg(r))

    def d2f(self, r):
        return self._d2s(self._arg(r))

    def dg_panels(self, a, k, order):
        """Nodes, weights and g' on the knot panels of [0, a] (one contact radius ``a``, one ``k``).

        Each panel [r_i, r_i+1] is mapped by x = r_i + L (3 w^2 - 2 w^3), w Gauss-Legendre of
        ``order``: the map vanishes quadratically at both panel ends, which smooths the
        (x - r_i)^((3+k)/2) terms that the knots leave in g' (docs/theory/graded.md (G14)) and the
        (a - x)^((1-k)/2) end of the displacement kernel of (G49).  Cached per (a, k, order), so
        every row of a sweep reuses one evaluation of g' (:meth:`dg_fast`); ``evaluations`` counts
        the nodes at which g' was formed.
        """
        def make():
            w, W = quadrature.gauss_legendre(int(order))
            smooth = w * w * (3.0 - 2.0 * w), 6.0 * w * (1.0 - w) * W
            x, wx = [], []
            for edges, (u, du) in zip(self._panel_edges(a), (smooth, (w, W))):
                L = np.diff(edges)[:, None]
                x.append((edges[:-1, None] + L * u).ravel())
                wx.append((L * du).ravel())
            x, wx = np.concatenate(x), np.concatenate(wx)
            self.evaluations += x.size
            # blocks of 8192 nodes bound the (node, block) pair arrays of the tree (~40 MB at p = 24)
            dg = np.concatenate([self.dg_fast(x[i:i + 8192], float(k)) for i in range(0, x.size, 8192)])
            return x, wx, dg
        return self._setup.get(("panels", float(a), float(k), int(order)), make)

    def _panel_edges(self, a):
        """Edges of the smoothed knot panels below the last knot, and of the cuts of the last panel."""
        # a knot within 1e-12 a of a (a chosen on a knot, rounded) would leave the edge
        # singularity on an ungraded panel: it joins the last panel
        knots = np.concatenate([[0.0], self.breaks[self.breaks < a * (1.0 - 1e-12)], [float(a)]])
        # the last panel is cut geometrically towards a (widths L 0.3^j, down to 1e-20 L): the
        # kernel of (G49) is singular at t = r, just beyond a as r -> a+; on each cut the
        # singularity is about as far away as the cut is wide, so each converges geometrically
        # (one smoothed panel needed 128 nodes for 1e-10 at r = a (1 + 1e-9), measured)
        last = knots[-1] - knots[-2]
        cuts = knots[-1] - last * _EDGE_GRADING ** np.arange(0, 39)
        return knots[:-1], np.append(cuts, knots[-1])

    def contact_knots(self, a):
        """0, the knots below a (as in :meth:`dg_panels`) and a."""
        return np.append(self._panel_edges(a)[0], float(a))

    def panel_edges(self, a):
        """Every panel edge of :meth:`dg_panels` on [0, a] in order: the knot panels, then the cuts of the last."""
        smooth, cuts = self._panel_edges(a)
        return np.concatenate([smooth, cuts[1:]])

    def panel_tree(self, a, k, order, p, power=0.0):
        """Block tree (G52) of the density w g'(t) t^power on the panel nodes of :meth:`dg_panels`,
        ``p`` Chebyshev points per block; cached per (a, k, order, p, power), no new g'."""
        def make():
            t, w, dg = self.dg_panels(a, k, order)
            edges = self.panel_edges(a)
            panel = np.repeat(np.arange(edges.size - 1), int(order))
            density = w * dg * (t ** power if power else 1.0)
            return fastsum.BlockTree(edges, t, density, panel, p)
        return self._setup.get(("tree", float(a), float(k), int(order), int(p), float(power)), make)

    def dg_interpolant(self, a, k, order):
        """g' on [0, a] from its values on the panel nodes of :meth:`dg_panels` (no new evaluation).

        On each panel g' is the degree ``order - 1`` polynomial through the ``order`` node values in
        the panel variable w (the smoothing map x = r_i + L (3 w^2 - 2 w^3) turns the knot terms
        (x - r_i)^((3+k)/2) of (G14) into w^(3+k)), evaluated in barycentric form,
        docs/theory/graded.md (G51).  Returns a function of x (any shape).
        """
        x_nodes, _, dg = self.dg_panels(a, k, order)
        w, W = quadrature.gauss_legendre(int(order))
        # barycentric weights of the Gauss-Legendre nodes: (-1)^j sqrt((1 - xi_j^2) W_j)
        lam = (-1.0) ** np.arange(w.size) * np.sqrt(w * (1.0 - w) * W)
        edges = self._panel_edges(a)
        ns = edges[0].size - 1
        vals = dg.reshape(-1, w.size)
        return lambda x: _barycentric(np.asarray(x, float), edges, ns, vals, w, lam)

    def dg_fast(self, x, k):
        """g'(x) of (G14) at many x (one k) by the block tree of h = d(r f')/dr, docs/theory/graded.md (G52)-(G54).

        g'(x) = x^(-k) int_0^x h(r) (x^2 - r^2)^(-(1-k)/2) dr: spline pieces at least _SEP piece
        widths below x enter by the Chebyshev moments of h on their block (interpolation error
        below 1e-15 of the block's part); the few pieces nearer x by their exact beta sums (G14).
        O(log knots) per node instead of O(knots): (G14) to 1e-13 relative (measured).
        """
        x = self._arg(x)
        shape = x.shape
        x = x.ravel()
        k = float(k)
        out = np.empty(x.shape)
        live = x > 0.0
        out[~live] = self._b[0, 0] * 0.5 * _B(0.5, 0.5 * (1.0 + k))
        xs = x[live]
        tree = self._h_tree()

        def classify(pt, lo, hi):
            xi = xs[pt]
            return (xi - hi) >= _SEP * (hi - lo), lo < xi       # pieces at or above x add nothing

        accepted, (pt, piece) = fastsum.split(tree, xs.size, classify)
        q = 0.5 * (1.0 - k)
        far = tree.far_sum(accepted, lambda c, i: ((xs[i, None] - c) * (xs[i, None] + c)) ** -q, xs.size)
        near = np.bincount(pt, weights=self._piece_terms(xs[pt], piece, k), minlength=xs.size)
        self.block_terms += sum(b.size for _, _, b in accepted) * tree.p
        self.exact_terms += pt.size
        out[live] = xs ** -k * far + near
        return out.reshape(shape)

    def _h_tree(self):
        """The block tree of h = f' + r f'' (cached): _H_ORDER/2 + 1 Gauss-Legendre nodes per spline
        piece, exact for h (degree 2) times the Lagrange polynomials (degree _H_ORDER - 1) of a block."""
        def make():
            w, W = quadrature.gauss_legendre(_H_ORDER // 2 + 1)
            L = (self._hi - self._lo)[:, None]
            t = (self._lo[:, None] + L * w).ravel()
            h = self._ds(t) + t * self._d2s(t)
            panel = np.repeat(np.arange(self._lo.size), w.size)
            return fastsum.BlockTree(np.append(self._lo, self._hi[-1]), t, (L * W).ravel() * h, panel, _H_ORDER)
        return self._setup.get(("h tree",), make)

    def _piece_terms(self, x, piece, k):
        """Exact part of g'(x) from the spline piece ``piece`` (one per x), the terms of (G14)."""
        q = 0.5 * (1.0 + k)
        z = np.minimum(np.stack([self._lo[piece], self._hi[piece]]) / x, 1.0) ** 2
        high = z > 0.5
        total = 0.0
        for m in range(3):
            pm = 0.5 * (m + 1.0)
            # differences of I near 1 from the complements (no cancellation), as in _beta_sum
            J = np.where(high, betaincc(pm, q, z), betainc(pm, q, z))
            dI = np.where(high[0], J[0] - J[1], np.where(high[1], (1.0 - J[1]) - J[0], J[1] - J[0]))
            total = total + (m + 1.0) * self._b[m, piece] * x ** m * dI * (0.5 * _B(pm, q))
        return total

    def _beta_sum(self, x, k, weights):
        # sum over pieces and m of w_m b_m x^(m+1) B((m+1)/2, (1+k)/2)/2 [I(hi^2/x^2) - I(lo^2/x^2)]
        x = self._arg(x)[..., None]
        k = np.asarray(k, float)[..., None]
        xs = np.where(x > 0, x, 1.0)
        # pieces above every x contribute I(1) - I(1) = 0: only the first `live` ones are formed
        live = max(1, int(np.searchsorted(self._lo, float(np.max(x)), side="left")))
        knots = np.append(self._lo[:live], self._hi[live - 1])
        q = 0.5 * (1.0 + k)
        z, qb = np.broadcast_arrays(np.minimum(knots / xs, 1.0) ** 2, q)     # k may vary where x does not
        high = z > 0.5
        total = 0.0
        for m in range(3):
            pm = 0.5 * (m + 1.0)
            # one incomplete beta per knot, shared by its two pieces: I where z <= 1/2, else the
            # complement (differences of I near 1 taken from the complements: no cancellation)
            J = np.empty(z.shape)
            J[high] = betaincc(pm, qb[high], z[high])
            J[~high] = betainc(pm, qb[~high], z[~high])
            Jl, Jh, hl, hh = J[..., :-1], J[..., 1:], high[..., :-1], high[..., 1:]
            dI = np.where(hl, Jl - Jh, np.where(hh, (1.0 - Jh) - Jl, Jh - Jl))
            total = total + weights[m] * np.sum(self._b[m, :live] * dI, axis=-1) * _B(pm, q[..., 0]) / 2 \
                * x[..., 0] ** (m + 1.0)
        return total

    def g(self, x, k):
        """Exact eq. (5) for the spline: g(x) = x^(1-k) int_0^x f'(r) (x^2-r^2)^(-(1-k)/2) dr."""
        return self._beta_sum(x, k, (1.0, 1.0, 1.0))

    def dg(self, x, k):
        """g'(x) = sum (m+1) b_m x^m B_m/2 dI (from d(r f')/dr = sum (m+1) b_m r^m);
        g'(0) = f'(0) B(1/2, (1+k)/2)/2."""
        x = self._arg(x)
        xs = np.where(x > 0, x, self.r_max)      # any radius inside the table (x = 0 takes `centre`)
        centre = self._b[0, 0] * 0.5 * _B(0.5, 0.5 * (1.0 + np.asarray(k, float)))
        return np.where(x > 0, self._beta_sum(xs, k, (1.0, 2.0, 3.0)) / xs, centre)


#: ratio of successive cuts of the last panel towards the contact edge (Tabulated.dg_panels)
_EDGE_GRADING = 0.3
#: distance of a block of spline pieces from the node x, in block widths, for its moments (G53)
_SEP = 1.5
#: Chebyshev points per block of the g' tree: the bound of (G53) for sep 1.5 gives 1e-17 (G54)
_H_ORDER = 24


def _unsmooth(s):
    """w in [0, 1] with 3 w^2 - 2 w^3 = s, as sin^2(e/2) + (sqrt 3/2) sin e, e = (2/3) asin(sqrt s):
    the trigonometric root 1/2 - sin(asin(1 - 2s)/3) written without its cancellation at s -> 0."""
    e = (2.0 / 3.0) * np.arcsin(np.sqrt(np.clip(s, 0.0, 1.0)))
    return np.sin(0.5 * e) ** 2 + 0.5 * np.sqrt(3.0) * np.sin(e)


def _barycentric(x, edges, ns, vals, w, lam):
    """Panel-wise barycentric interpolation of the node values ``vals`` at x (see dg_interpolant)."""
    smooth_edges, cut_edges = edges
    flat = x.ravel()
    out = np.empty(flat.shape)
    for s in range(0, flat.size, 4096):          # bounds the (points x order) work arrays
        xb = flat[s:s + 4096]
        smooth = xb < smooth_edges[-1]
        i = np.clip(np.searchsorted(smooth_edges, xb, side="right") - 1, 0, max(ns - 1, 0))
        j = np.clip(np.searchsorted(cut_edges, xb, side="right") - 1, 0, cut_edges.size - 2)
        lo = np.where(smooth, smooth_edges[i], cut_edges[j])
        hi = np.where(smooth, smooth_edges[np.minimum(i + 1, ns)], cut_edges[j + 1])
        # the finest cuts of the last panel round to zero width (a - 1e-20 L = a): any u there
        width = hi - lo
        u = np.clip((xb - lo) / np.where(width > 0.0, width, 1.0), 0.0, 1.0)
        u = np.where(smooth, _unsmooth(u), u)
        v = vals[np.where(smooth, i, ns + j)]
        d = u[:, None] - w[None, :]
        with np.errstate(divide="ignore", invalid="ignore"):
            q = lam / d
            bary = np.einsum("ij,ij->i", q, v) / np.sum(q, axis=1)
        # u on a node (q infinite there, bary NaN): the node value itself (few rows: a cheap repair)
        hit = ~np.isfinite(bary)
        if hit.any():
            bary[hit] = v[hit, np.argmin(np.abs(d[hit]), axis=1)]
        out[s:s + 4096] = bary
    return out.reshape(x.shape)


def _transform(x, profile, k, rtol, derivative):
    # eq. (5) with r = x t:  g(x) = x int_0^1 f'(x t) (1-t^2)^(-(1-k)/2) dt; the end-point factor
    # (1-t)^(-(1-k)/2) is removed by 1 - t = v^p, p = 2/(1+k).
    x = np.abs(as_array("x", x))
    k = check_k(k)
    # g(0) = 0 exactly; evaluate the integral at a dummy x there so that f'(0) = inf (n < 1)
    # cannot turn the product into NaN
    xs = x if derivative else np.where(x > 0.0, x, 1.0)
    xe, ke = xs[..., None], k[..., None]
    p = 2.0 / (1.0 + ke)

    def integrand(v, vc):
        t, tc = quadrature.power_map(v, vc, p)
        xt = xe * t
        if not derivative:
            return p * profile.df(xt) * (1.0 + t) ** (-0.5 * (1.0 - ke))
        with np.errstate(divide="ignore", invalid="ignore"):
            # d(r f')/dr; r f''(r) -> 0 at r = 0 for every profile with finite f'(0)
            val = profile.df(xt) + np.where(xt > 0.0, xt * profile.d2f(xt), 0.0)
        return p * val * (1.0 + t) ** (-0.5 * (1.0 - ke))

    out = quadrature.integrate(integrand, rtol=rtol)
    return out if derivative else np.where(x > 0.0, x * out, 0.0)


def g_quad(x, profile, *, k, rtol=1e-10):
    """g(x) by quadrature of eq. (5) (PowerLaw); exact piecewise beta sums for Tabulated."""
    if hasattr(profile, "g"):
        return profile.g(x, check_k(k))
    return _transform(x, profile, k, rtol, derivative=False)


def dg_quad(x, profile, *, k, rtol=1e-10):
    """g'(|x|) by quadrature of the x-derivative of eq. (5): int_0^1 [f'(xt) + xt f''(xt)] w(t) dt.

    Exact piecewise beta sums for Tabulated.
    """
    if hasattr(profile, "dg"):
        return profile.dg(x, check_k(k))
    return _transform(x, profile, k, rtol, derivative=True)


def f_from_g_quad(r, g, *, k, rtol=1e-10):
    """Inverse transform, eq. (6), docs/theory/graded.md (G12): f(r) from a callable 1D profile ``g`` (vectorised).

    With x = r t the kernel (1-t)^(-(1+k)/2) is removed by 1 - t = v^p, p = 2/(1-k); the
    vanishing cos(k pi/2) and the growing p combine to the finite 2 sin((1-k)pi/2)/(1-k).
    """
    r = np.abs(as_array("r", r))
    k = check_k(k)
    re, ke = r[..., None], k[..., None]
    p = 2.0 / (1.0 - ke)
    pref = (2.0 / np.pi) * cos_half_pi_k(ke) * p

    def integrand(v, vc):
        t, tc = quadrature.power_map(v, vc, p)
        return pref * t ** ke * g(re * t) * (1.0 + t) ** (-0.5 * (1.0 + ke))

    return quadrature.integrate(integrand, rtol=rtol)
