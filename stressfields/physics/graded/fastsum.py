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

__all__ = ["BlockTree", "chebyshev_order", "split"]


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


class BlockTree:
    """Moments of one source density on a binary tree over the panels of ``edges`` (G52).

    ``t``: source positions (1-D); ``wphi``: their weighted values w_j phi_j (one density per
    tree); ``panel``: the panel index of each source; ``p``: Chebyshev points per block.
    """

    def __init__(self, edges, t, wphi, panel, p: int):
        edges = np.asarray(edges, float)
        self.P = edges.size - 1
        self.L = max(1, int(math.ceil(math.log2(max(self.P, 1)))))
        self.p = int(p)
        k = np.arange(self.p)
        self.xi = np.cos((2 * k + 1) * math.pi / (2 * self.p))          # Chebyshev points, first kind
        # l_i(x) = sum_k T_k(x) C[k, i]: the inverse of the Chebyshev Vandermonde matrix
        C = (2.0 / self.p) * np.cos(np.outer(k, np.arccos(self.xi)))
        C[0] *= 0.5
        self.C = C
        # node b of level l (root l = 0) covers panels [b 2^(L-l), (b+1) 2^(L-l)) (clipped to P)
        self.lo, self.hi = [], []
        for level in range(self.L + 1):
            span = 1 << (self.L - level)
            b = np.arange(1 << level)
            self.lo.append(edges[np.minimum(b * span, self.P)])
            self.hi.append(edges[np.minimum((b + 1) * span, self.P)])
        self.M = self._moments(np.asarray(t, float), np.asarray(wphi, float), np.asarray(panel))

    def _basis(self, x):
        """l_i(x) for x in [-1, 1], shape x.shape + (p,)."""
        T = np.cos(np.arange(self.p) * np.arccos(np.clip(x, -1.0, 1.0))[..., None])
        return T @ self.C

    def _local(self, x, lo, hi):
        """x mapped to [-1, 1] on [lo, hi] (zero-width blocks: 0)."""
        width = hi - lo
        return np.where(width > 0.0, (2.0 * x - lo - hi) / np.where(width > 0.0, width, 1.0), 0.0)

    def chebyshev_points(self, level, b):
        """The Chebyshev points of the blocks b of ``level``, shape b.shape + (p,)."""
        lo, hi = self.lo[level][b], self.hi[level][b]
        return 0.5 * (lo + hi)[..., None] + 0.5 * (hi - lo)[..., None] * self.xi

    def _moments(self, t, wphi, panel):
        leaves = np.zeros((1 << self.L, self.p))
        x = self._local(t, self.lo[self.L][panel], self.hi[self.L][panel])
        np.add.at(leaves, panel, wphi[:, None] * self._basis(x))
        levels = [leaves]
        for level in range(self.L - 1, -1, -1):
            # a parent's Lagrange polynomial is a polynomial of degree p - 1 on each child, so the
            # child's p-point interpolation reproduces it: parent moment = child moments at its values
            child = levels[-1]
            b = np.arange(1 << level)
            lo, hi = self.lo[level][b], self.hi[level][b]
            M = np.zeros((b.size, self.p))
            for side in (0, 1):
                c = self.chebyshev_points(level + 1, 2 * b + side)
                M += np.einsum("bj,bji->bi", child[2 * b + side], self._basis(self._local(c, lo[:, None], hi[:, None])))
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
