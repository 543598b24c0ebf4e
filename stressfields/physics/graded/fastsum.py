"""Block-tree summation over panels: sum_j w_j phi_j K(t_j, x) for many targets x in O(log panels) each.

docs/theory/graded.md (G52)-(G54).  The sources t_j are quadrature nodes on consecutive panels
[e_0, e_1], ..., [e_(P-1), e_P] (spline pieces, knot panels of the contact); K(t, x) is analytic in t
except at a singular point s(x) (t = x or t = r) and at its mirror image -s(x).  A binary tree groups
consecutive panels into blocks; each block stores the moments

    M_i = sum_(j in block) w_j phi_j l_i(t_j),

l_i the Lagrange polynomials of the block's p Chebyshev points c_i.  A block at least ``sep`` block
widths away from s(x) then contributes sum_i M_i K(c_i, x): the same panel rule with K replaced by
its Chebyshev interpolant on the block, so the interpolation error is the only error added (G53).
Blocks too close to s(x) are split down to single panels, which the caller takes directly or exactly.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["BlockTree", "chebyshev_order", "chebyshev_rule", "lagrange", "split", "local_fields", "local_values"]


def chebyshev_order(rtol: float, sep: float, exponent: float = 0.5) -> int:
    """Chebyshev points per block for a relative interpolation error rtol/20 of a kernel
    (distance)^(-exponent) on a block ``sep`` widths from its singular point (G53).

    The singular point lies delta = 1 + 2 sep half widths from the block centre; the kernel is
    analytic inside the Bernstein ellipse of parameter rho = delta + sqrt(delta^2 - 1), and on 0.8 of
    it its largest value is M = ((delta - 1)/gap)^exponent times the largest on the block, gap the
    ellipse's distance to the singular point; the interpolation error is at most 4 M rho'^-p/(rho' - 1).
    """
    delta = 1.0 + 2.0 * sep
    rho = 0.8 * (delta + math.sqrt(delta * delta - 1.0))
    gap = delta - 0.5 * (rho + 1.0 / rho)
    bound = 4.0 * ((delta - 1.0) / gap) ** exponent / (rho - 1.0)
    return max(4, int(math.ceil(math.log(20.0 * bound / rtol) / math.log(rho))))


def chebyshev_rule(p: int):
    """The p Chebyshev points of the first kind on [-1, 1] and their barycentric weights."""
    k = np.arange(p)
    return np.cos((2 * k + 1) * math.pi / (2 * p)), (-1.0) ** k * np.sin((2 * k + 1) * math.pi / (2 * p))


def lagrange(x, xi, lam):
    """The Lagrange polynomials l_i(x) of the points ``xi`` (barycentric weights ``lam``) at x in
    [-1, 1], shape x.shape + (p,), by the barycentric formula: each value to a few ulps and O(p) per
    point (the Chebyshev sum T(x) @ V^-1 costs O(p^2) and carries ~p ulps of its terms, which the
    downward pass of ``local_fields`` repeated once per level: 1e-14 of g' on a 200-piece table,
    measured)."""
    q = np.clip(x, -1.0, 1.0)[..., None] - xi
    hit = q == 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        np.divide(lam, q, out=q)
        out = np.divide(q, np.sum(q, axis=-1, keepdims=True), out=q)
    if hit.any():           # x on a node: that node's Lagrange polynomial is 1, the others 0
        rows = hit.any(axis=-1)
        out[rows] = hit[rows]
    return out


class BlockTree:
    """Moments of one source density on a binary tree over the panels of ``edges`` (G52).

    ``t``: source positions (1-D); ``wphi``: their weighted values w_j phi_j (1-D: one density; a
    second axis: several, whose moments then carry that axis last); ``panel``: the panel index of
    each source; ``p``: Chebyshev points per block.
    """

    def __init__(self, edges, t, wphi, panel, p: int):
        edges = np.asarray(edges, float)
        self.P = edges.size - 1
        self.L = max(1, int(math.ceil(math.log2(max(self.P, 1)))))
        self.p = int(p)
        self.xi, self.lam = chebyshev_rule(self.p)          # Chebyshev points, first kind
        # node b of level l (root l = 0) covers panels [b 2^(L-l), (b+1) 2^(L-l)) (clipped to P)
        self.lo, self.hi = [], []
        for level in range(self.L + 1):
            span = 1 << (self.L - level)
            b = np.arange(1 << level)
            self.lo.append(edges[np.minimum(b * span, self.P)])
            self.hi.append(edges[np.minimum((b + 1) * span, self.P)])
        self.M = self._moments(np.asarray(t, float), np.asarray(wphi, float), np.asarray(panel))

    def _lagrange(self, x):
        """l_i(x) for x in [-1, 1], shape x.shape + (p,) (``lagrange``)."""
        return lagrange(x, self.xi, self.lam)

    def _local(self, x, lo, hi):
        """x mapped to [-1, 1] on [lo, hi] (zero-width blocks: 0).  As (x - lo) - (hi - x), both exact
        for x in a block away from 0 (Sterbenz): 2x - lo - hi would carry the rounding of x, eps x, an
        error of eps x / width in the block's coordinate, which the interpolation of a leaf's field
        turned into 1e-14 of g' on a 200-piece table (measured)."""
        width = hi - lo
        return np.where(width > 0.0, ((x - lo) - (hi - x)) / np.where(width > 0.0, width, 1.0), 0.0)

    def chebyshev_points(self, level, b):
        """The Chebyshev points of the blocks b of ``level``, shape b.shape + (p,)."""
        lo, hi = self.lo[level][b], self.hi[level][b]
        return 0.5 * (lo + hi)[..., None] + 0.5 * (hi - lo)[..., None] * self.xi

    def _moments(self, t, wphi, panel):
        """Per level the moments, shape (blocks, p) + wphi.shape[1:] (several densities share one pass)."""
        extra = wphi.shape[1:]
        leaves = np.zeros((1 << self.L, self.p) + extra)
        x = self._local(t, self.lo[self.L][panel], self.hi[self.L][panel])
        np.add.at(leaves, panel, np.einsum("ni,n...->ni...", self._lagrange(x), wphi))
        levels = [leaves]
        for level in range(self.L - 1, -1, -1):
            # a parent's Lagrange polynomial is a polynomial of degree p - 1 on each child, so the
            # child's p-point interpolation reproduces it: parent moment = child moments at its values
            child = levels[-1]
            b = np.arange(1 << level)
            lo, hi = self.lo[level][b], self.hi[level][b]
            M = np.zeros((b.size, self.p) + extra)
            for side in (0, 1):
                c = self.chebyshev_points(level + 1, 2 * b + side)
                at = self._lagrange(self._local(c, lo[:, None], hi[:, None]))
                # (batched matmul: several times faster than the equivalent einsum)
                kid = child[2 * b + side]
                M += (np.swapaxes(at, 1, 2) @ kid.reshape(kid.shape[:2] + (-1,))).reshape(M.shape)
            levels.append(M)
        return levels[::-1]

    def far_sum(self, level_pairs, kernel, n):
        """sum over each target's accepted blocks of sum_i M_i kernel(c_i, x) (``kernel(c, idx)`` gets
        the Chebyshev points, shape (pairs, p), and the target index per pair)."""
        out = np.zeros(n)
        for level, pt, b in level_pairs:
            if pt.size == 0:
                continue
            c = self.chebyshev_points(level, b)
            vals = np.einsum("ij,ij->i", self.M[level][b], kernel(c, pt))
            out += np.bincount(pt, weights=vals, minlength=n)
        return out


def local_fields(tree: BlockTree, moments, kernel, sep: float):
    """Far field of the sources below every leaf, as values at the leaf's Chebyshev points.

    The target points lie in the tree's own panels (the sources of a panel act on points above it
    only: those of panels above a point add nothing).  A dual traversal of the tree with itself pairs
    a source block S with a target block B at the same level; the pair is accepted when S lies below
    B at least ``sep`` times the wider of the two, so that ``kernel(x, t)`` is analytic in t on S (the
    moments of S serve, (G53)) and in x on B (its values at B's Chebyshev points interpolate it on B),
    dropped when S lies above B, else split into its four child pairs.  Accepted pairs add
    sum_j M_j kernel(x_i, c_j) to B's values, which then pass down to the children by interpolation
    (exact for the polynomial they are): O(p^2) per accepted pair, O(panels p^2) in all instead of
    O(p) per (point, block) pair of ``split``.  ``moments``: one list of per-level moment arrays
    (``BlockTree.M`` of a tree with the same panels) per density.  Returns the leaf values, shape
    (densities, 2^L, p), and the (source, target) pairs of panels left near each other, for the
    caller to sum exactly.
    """
    p, L = tree.p, tree.L
    S = B = np.zeros(1, dtype=np.int64)
    values = np.zeros((len(moments), 1, p))
    for level in range(L + 1):
        loS, hiS, loB, hiB = tree.lo[level][S], tree.hi[level][S], tree.lo[level][B], tree.hi[level][B]
        live = (hiS > loS) & (hiB > loB)       # zero-width blocks: padding beyond the last panel
        accept = live & (loB - hiS >= sep * np.maximum(hiS - loS, hiB - loB))
        keep = live & ~accept & (loS < hiB)
        if accept.any():
            sa, ba = S[accept], B[accept]
            order = np.argsort(ba, kind="stable")
            sa, ba = sa[order], ba[order]
            for c0 in range(0, sa.size, _PAIRS):         # bounds the (pair, p, p) kernel matrices
                s_, b_ = sa[c0:c0 + _PAIRS], ba[c0:c0 + _PAIRS]
                K = kernel(tree.chebyshev_points(level, b_)[:, :, None], tree.chebyshev_points(level, s_)[:, None, :])
                vals = K @ np.stack([M[level][s_] for M in moments], axis=-1)      # (pair, p, densities)
                start = np.flatnonzero(np.r_[True, b_[1:] != b_[:-1]])
                values[:, b_[start]] += np.moveaxis(np.add.reduceat(vals, start, axis=0), -1, 0)
        if level == L:
            return values, (S[keep], B[keep])
        # the next level: every block's values at its children's points, then the kept pairs' children
        nxt = np.empty((len(moments), 1 << (level + 1), p))
        for c0 in range(0, nxt.shape[1], _CHILDREN):     # bounds the (child, p, p) interpolation matrices
            child = np.arange(c0, min(c0 + _CHILDREN, nxt.shape[1]))
            parent = child >> 1
            x = tree.chebyshev_points(level + 1, child)
            basis = tree._lagrange(tree._local(x, tree.lo[level][parent][:, None], tree.hi[level][parent][:, None]))
            nxt[:, child] = np.moveaxis(basis @ np.moveaxis(values[:, parent], 0, -1), -1, 0)
        values = nxt
        S, B = S[keep], B[keep]
        S = (2 * S[:, None] + np.array([0, 0, 1, 1])).ravel()
        B = (2 * B[:, None] + np.array([0, 1, 0, 1])).ravel()
    raise AssertionError("unreachable")  # pragma: no cover


#: accepted pairs per pass of ``local_fields`` (p = 24: 19 MB kernel matrices)
_PAIRS = 4096
#: points per pass of ``local_values``
_POINTS = 4096
#: children per pass of the downward interpolation of ``local_fields`` (p = 24: 9 MB of matrices)
_CHILDREN = 2048


def local_values(tree: BlockTree, values, x, leaf):
    """The leaf fields of ``local_fields`` at points x in the leaves ``leaf`` (one per point)."""
    out = [np.empty(x.size) for _ in values]
    for s in range(0, x.size, _POINTS):      # cache-sized (point, p) work arrays: 3x faster than one pass
        sl = slice(s, s + _POINTS)
        basis = tree._lagrange(tree._local(x[sl], tree.lo[tree.L][leaf[sl]], tree.hi[tree.L][leaf[sl]]))
        for o, v in zip(out, values):
            o[sl] = np.einsum("ij,ij->i", basis, v[leaf[sl]])
    return out


def split(tree: BlockTree, n: int, classify):
    """Per level, the (target, block) pairs that ``classify`` accepts, and the leaves it hands back.

    ``classify(pt, lo, hi)`` -> (accept, keep) boolean arrays per pair: accepted blocks are summed
    by their moments; the others that are kept are split (at the leaves: handed back).
    Returns ([(level, pt, b), ...], (pt, panel)).
    """
    pt = np.arange(n)
    b = np.zeros(n, dtype=np.int64)
    accepted = []
    for level in range(tree.L + 1):
        lo, hi = tree.lo[level][b], tree.hi[level][b]
        accept, keep = classify(pt, lo, hi)
        live = hi > lo                    # zero-width blocks (padding, cuts rounded to a) hold no weight
        accept, keep = accept & live, keep & ~accept & live
        if accept.any():
            accepted.append((level, pt[accept], b[accept]))
        if level == tree.L:
            return accepted, (pt[keep], b[keep])
        pt, b = np.repeat(pt[keep], 2), (2 * b[keep][:, None] + np.arange(2)).ravel()
    raise AssertionError("unreachable")  # pragma: no cover
