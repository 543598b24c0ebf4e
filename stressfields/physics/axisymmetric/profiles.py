"""Axisymmetric indenter profiles f(r) and their MDR equivalent profiles g(x).

Willert, Forsbach & Popov, "Stress tensor and gradient of hydrostatic pressure in the contact plane
of axisymmetric bodies under normal and tangential loading": eq. (12) (Abel transform
g(x) = |x| int_0^|x| f'(r) dr / sqrt(x^2 - r^2)), eq. (7) (depth delta = g(a)) and eq. (10)
(F_N / E* = 2 int_0^a u g'(u) du).  Everything is per unit E*: forces are F_N / E*.

All lengths are in one unit, the profile's.  Profiles are immutable and hashable.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.special import gammaln

from ..roots import bisect
from .routes import has_closed_form, power_law_family

__all__ = ["Profile", "Cone", "Paraboloid", "PowerLaw", "FlatPunch", "Tabulated",
           "cone", "paraboloid", "power_law", "flat_punch", "tabulated"]


def _positive(name: str, value) -> float:
    v = float(value)
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} must be a positive finite number, got {value!r}")
    return v


def _arr(x) -> np.ndarray:
    return np.asarray(x, dtype=float)


class Profile:
    """Base class of the profiles.  Subclasses define ``g``, ``dg``, ``d2g``, ``depth``,
    ``normal_force`` and ``contact_radius``.

    Internal attributes used by the kernels:
    ``tip_exponent`` m0 and ``tip_coefficient`` B with g'(u) ~ B u**m0 as u -> 0 (they decide the
    limits at r = 0); ``closed`` names the closed-form family (("cone", tan_theta),
    ("paraboloid", R), ("flat_punch", radius, depth)) or is None; ``max_radius`` is the largest
    contact radius the profile is defined for.
    """

    kind: ClassVar[str] = "profile"
    max_radius: ClassVar[float] = math.inf

    @property
    def has_closed_form(self) -> bool:
        """Whether closed forms exist for this profile (decided by ``routes.has_closed_form``)."""
        return has_closed_form(self.kind, getattr(self, "n", None))

    @property
    def closed(self):
        return None

    def depth(self, a):
        """Indentation depth delta = g(a), eq. (7)."""
        return self.g(a)

    def _check_radius(self, a, what="contact radius a"):
        a = _arr(a)
        if np.any(a > self.max_radius * (1.0 + 1e-12)):
            raise ValueError(f"{what} = {float(np.max(a))!r} exceeds the end of the tabulated profile, "
                             f"r = {self.max_radius!r}")
        return a


@dataclass(frozen=True)
class Cone(Profile):
    """Cone f = r tan(theta); g = (pi/2) tan(theta) |x| (eq. 12, 29)."""

    tan_theta: float
    kind: ClassVar[str] = "cone"

    def __post_init__(self):
        object.__setattr__(self, "tan_theta", _positive("tan_theta", self.tan_theta))

    @property
    def closed(self):
        return ("cone", self.tan_theta)

    @property
    def tip_exponent(self) -> float:
        return 0.0

    @property
    def tip_coefficient(self) -> float:
        return 0.5 * math.pi * self.tan_theta

    def g(self, x):
        return 0.5 * math.pi * self.tan_theta * np.abs(_arr(x))

    def dg(self, x):
        return np.full_like(_arr(x), 0.5 * math.pi * self.tan_theta)

    def d2g(self, x):
        return np.zeros_like(_arr(x))

    def normal_force(self, a):
        """F_N / E* = (pi/2) tan(theta) a^2 (eq. 10)."""
        return 0.5 * math.pi * self.tan_theta * _arr(a) ** 2

    def contact_radius(self, delta):
        return 2.0 * _arr(delta) / (math.pi * self.tan_theta)


@dataclass(frozen=True)
class Paraboloid(Profile):
    """Paraboloid f = r^2/(2R); g = x^2/R (eq. 12)."""

    R: float
    kind: ClassVar[str] = "paraboloid"

    def __post_init__(self):
        object.__setattr__(self, "R", _positive("R", self.R))

    @property
    def closed(self):
        return ("paraboloid", self.R)

    @property
    def tip_exponent(self) -> float:
        return 1.0

    @property
    def tip_coefficient(self) -> float:
        return 2.0 / self.R

    def g(self, x):
        return _arr(x) ** 2 / self.R

    def dg(self, x):
        return 2.0 * _arr(x) / self.R

    def d2g(self, x):
        return np.full_like(_arr(x), 2.0 / self.R)

    def normal_force(self, a):
        """F_N / E* = 4 a^3 / (3R) (eq. 10)."""
        return 4.0 * _arr(a) ** 3 / (3.0 * self.R)

    def contact_radius(self, delta):
        return np.sqrt(self.R * _arr(delta))


@dataclass(frozen=True)
class PowerLaw(Profile):
    """Power law f = A r^n (n > 0); g = kappa_n A |x|^n with
    kappa_n = sqrt(pi) Gamma(n/2 + 1) / Gamma(n/2 + 1/2) (eq. 12).

    n = 1 and n = 2 are the cone (tan(theta) = A) and the paraboloid (R = 1/(2A)); for them the
    closed forms are available (``has_closed_form``)."""

    A: float
    n: float
    kind: ClassVar[str] = "power_law"

    def __post_init__(self):
        object.__setattr__(self, "A", _positive("A", self.A))
        object.__setattr__(self, "n", _positive("n", self.n))

    @property
    def kappa(self) -> float:
        n = self.n
        return math.sqrt(math.pi) * math.exp(gammaln(0.5 * n + 1.0) - gammaln(0.5 * n + 0.5))

    @property
    def closed(self):
        family = power_law_family(self.n)      # the route table's n = 1 and n = 2
        if family == "cone":
            return ("cone", self.A)
        if family == "paraboloid":
            return ("paraboloid", 0.5 / self.A)
        return None

    @property
    def tip_exponent(self) -> float:
        return self.n - 1.0

    @property
    def tip_coefficient(self) -> float:
        return self.kappa * self.A * self.n

    def g(self, x):
        return self.kappa * self.A * np.abs(_arr(x)) ** self.n

    def dg(self, x):
        with np.errstate(divide="ignore"):
            return self.tip_coefficient * np.abs(_arr(x)) ** (self.n - 1.0)

    def d2g(self, x):
        if self.n == 1.0:
            return np.zeros_like(_arr(x))
        with np.errstate(divide="ignore", invalid="ignore"):
            return self.tip_coefficient * (self.n - 1.0) * np.abs(_arr(x)) ** (self.n - 2.0)

    def normal_force(self, a):
        """F_N / E* = 2 kappa A n a^(n+1) / (n+1) (eq. 10)."""
        return 2.0 * self.tip_coefficient * _arr(a) ** (self.n + 1.0) / (self.n + 1.0)

    def contact_radius(self, delta):
        return (_arr(delta) / (self.kappa * self.A)) ** (1.0 / self.n)


@dataclass(frozen=True)
class FlatPunch(Profile):
    """Rigid flat punch of radius ``radius`` pressed to the depth ``depth`` (default 1: results are
    per unit indentation depth, eq. 2-3).  g = 0 for |x| <= radius and +inf beyond (the punch wall);
    the contact radius is always the punch radius, whatever the depth.

    Stresses of the flat punch scale with the depth, which the contact radius does not fix: pass
    ``depth`` to get them for a given indentation (normalised by the mean pressure the depth cancels)."""

    radius: float
    depth_: float = 1.0
    kind: ClassVar[str] = "flat_punch"

    def __post_init__(self):
        object.__setattr__(self, "radius", _positive("radius", self.radius))
        object.__setattr__(self, "depth_", _positive("depth", self.depth_))

    @property
    def closed(self):
        return ("flat_punch", self.radius, self.depth_)

    def g(self, x):
        return np.where(np.abs(_arr(x)) <= self.radius, 0.0, np.inf)

    def dg(self, x):
        return np.where(np.abs(_arr(x)) <= self.radius, 0.0, np.inf)

    def d2g(self, x):
        return np.where(np.abs(_arr(x)) <= self.radius, 0.0, np.inf)

    def depth(self, a):
        """The punch's depth (independent of a)."""
        return np.full_like(_arr(a), self.depth_)

    def normal_force(self, a):
        """F_N / E* = 2 a delta (eq. 10 with g' = delta * Dirac(u - a))."""
        return 2.0 * _arr(a) * self.depth_

    def contact_radius(self, delta):
        return np.full_like(_arr(delta), self.radius)


# -- tabulated profile: exact Abel transform of a cubic spline --------------------------------------
#
# On every spline piece f'(r) = alpha + beta r + gamma r^2.  With r = x sin(phi) in eq. (12),
#   g(x)   = x   sum_j [alpha dS0 + beta x dS1 + gamma x^2 dS2],
#   g'(x)  =     sum_j [alpha dS0 + 2 beta x dS1 + 3 gamma x^2 dS2],
#   g''(x) =     sum_j [2 beta dS1 + 6 gamma x dS2],
# where dSk is the increment of S_k(phi) = int_0^phi sin^k over the piece's phi-range
# [arcsin(r_j/x), arcsin(min(r_j+1, x)/x)].  (The breakpoint terms of the x-derivatives cancel
# because f' is continuous.)  Likewise Sneddon's F_N/E* = 2 int_0^a r^2 f'(r)/sqrt(a^2-r^2) dr
# = 2 a^2 sum_j [alpha dS2 + beta a dS3 + gamma a^2 dS4].  So g, g', g'' and F_N are exact for the
# interpolant; only the interpolation of the data is approximate.  (``dg`` and ``d2g`` read g' and
# g'' from a table built from these sums, to their rounding; see _TABLE_DEGREE.)

_CHUNK = 1 << 20  # elements of the (points x pieces) work arrays

# g' and g'' are evaluated at every quadrature node, and the exact sums below cost O(knots) each
# (~3e-4 s per field point with 25 knots).  They are therefore tabulated once per profile, on first
# use: on the piece [k_j, k_j+1] both are analytic functions of w = sqrt((x - k_j)/(k_j+1 - k_j))
# (the cusp at k_j is a power series in sqrt(x^2 - k_j^2); the branch points of the knots below lie
# at imaginary w, the nearest at w = i sqrt((k_j - k_j-1)/(k_j+1 - k_j))).  A polynomial of degree
# _TABLE_DEGREE in w per sub-interval of [0, 1], the sub-intervals halved until it matches the exact
# sums to _TABLE_ULPS ulps of max |g'| (max |g''|, at least max |g'| / r_max), or to their own
# rounding when that is larger, is as accurate as the sums and costs a binary search and a Horner
# sum per point (~1e7 evaluations per second whatever the number of knots).  Piece 0, with no knot
# below, is the exact quadratic in x (a quartic in w, so _TABLE_DEGREE >= 4).
_TABLE_DEGREE = 10
_TABLE_ULPS = 8.0
_TABLE_LEVELS = 16    # halvings at most (a sub-interval of 2^-16 in w)


def _table_rules(n):
    """Fit nodes (Chebyshev points of the first kind), check points (the ends and the midpoints
    between fit nodes) and the Chebyshev -> monomial conversion matrix, degree n."""
    z_fit = np.cos(np.pi * (np.arange(n + 1) + 0.5) / (n + 1))
    mid = np.cos(np.pi * np.arange(1, n + 1) / (n + 1))
    z_chk = np.concatenate([[-1.0, 1.0], mid])
    to_monomial = np.zeros((n + 1, n + 1))
    for m in range(n + 1):
        c = np.polynomial.chebyshev.cheb2poly(np.eye(n + 1)[m])
        to_monomial[:c.size, m] = c
    return z_fit, z_chk, to_monomial


def _phi_terms(x, lo, hi):
    """sin, cos and angle at r = lo and r = hi (arrays broadcast to (points, pieces)), stable near
    r = x via sqrt((x - r)(x + r))."""
    out = []
    for r in (lo, hi):
        cr = np.sqrt(np.maximum((x - r) * (x + r), 0.0))
        out.append((r / x, cr / x, np.arctan2(r, cr)))
    return out


@dataclass(frozen=True, eq=False)
class Tabulated(Profile):
    """Profile f(r) given at sorted points r >= 0, interpolated by a not-a-knot cubic spline of
    f - f[0]; g by the exact Abel transform (eq. 12) of that spline, g' and g'' from a piecewise
    polynomial table of it (built on first use, as accurate as the exact sums).  If r[0] > 0 the
    first spline piece is continued down to r = 0.  Defined for contact radii up to r[-1].

    The tip exponent is 0 (conical tip, g'(0) != 0) when the spline's f'(0) exceeds 1e-10 of the
    largest |f'| at the knots, else 1 (smooth tip)."""

    r: tuple
    f: tuple
    kind: ClassVar[str] = "tabulated"
    _knots: np.ndarray = field(init=False, repr=False, compare=False)
    _coef: np.ndarray = field(init=False, repr=False, compare=False)
    _table: tuple = field(init=False, repr=False, compare=False, default=None)

    def __post_init__(self):
        r = np.asarray(self.r, dtype=float)
        f = np.asarray(self.f, dtype=float)
        if r.ndim != 1 or f.ndim != 1 or r.shape != f.shape:
            raise ValueError(f"tabulated profile: r and f must be 1-D of equal length, got shapes "
                             f"{r.shape} and {f.shape}")
        if r.size < 4:
            raise ValueError(f"tabulated profile: need at least 4 points, got {r.size}")
        if not (np.all(np.isfinite(r)) and np.all(np.isfinite(f))):
            raise ValueError("tabulated profile: r and f must be finite (found NaN or inf)")
        if r[0] < 0.0:
            raise ValueError(f"tabulated profile: r must be >= 0, got r[0] = {r[0]!r}")
        dr = np.diff(r)
        if np.any(dr <= 0.0):
            i = int(np.argmax(dr <= 0.0))
            raise ValueError(f"tabulated profile: r must be strictly increasing (sorted, no duplicates); "
                             f"r[{i}] = {r[i]!r}, r[{i + 1}] = {r[i + 1]!r}")
        df = np.diff(f)
        if np.any(df < 0.0):
            i = int(np.argmax(df < 0.0))
            raise ValueError(f"tabulated profile: f must be non-decreasing; f[{i}] = {f[i]!r} > "
                             f"f[{i + 1}] = {f[i + 1]!r}")
        if not np.any(df > 0.0):
            raise ValueError("tabulated profile: f is constant (a flat punch); use flat_punch()")
        object.__setattr__(self, "r", tuple(r.tolist()))
        object.__setattr__(self, "f", tuple(f.tolist()))
        spline = CubicSpline(r, f - f[0])
        d, c, b = spline.c[0], spline.c[1], spline.c[2]      # f' = b + 2c (r-rj) + 3d (r-rj)^2
        rj = r[:-1]
        alpha = b - 2.0 * c * rj + 3.0 * d * rj ** 2
        beta = 2.0 * c - 6.0 * d * rj
        gamma = 3.0 * d
        fprime_max = float(np.max(np.abs(spline(r, 1))))
        if abs(alpha[0]) <= 1e-10 * fprime_max:
            # f'(0) is zero up to rounding (e.g. a sampled paraboloid): make it exact, so that the
            # tip is smooth and the r = 0 limits are finite.
            alpha = alpha.copy()
            alpha[0] = 0.0
        knots = r.copy()
        knots[0] = 0.0
        object.__setattr__(self, "_knots", knots)
        object.__setattr__(self, "_coef", np.stack([alpha, beta, gamma]))

    def __hash__(self):
        return hash((self.kind, self.r, self.f))

    def __eq__(self, other):
        return isinstance(other, Tabulated) and (self.r, self.f) == (other.r, other.f)

    @property
    def max_radius(self) -> float:  # type: ignore[override]
        return self.r[-1]

    @property
    def tip_exponent(self) -> float:
        return 0.0 if self._coef[0, 0] != 0.0 else 1.0

    @property
    def tip_coefficient(self) -> float:
        a0 = self._coef[0, 0]
        return 0.5 * math.pi * a0 if a0 != 0.0 else 2.0 * self._coef[1, 0]

    # -- the exact Abel transform ------------------------------------------------------------------
    def _sums(self, x, which, magnitude=False):
        """Evaluate g (which=0), g' (1), g'' (2) or F_N/E* (3) at x >= 0, exactly for the spline.
        ``magnitude`` (g', g'' only): instead the size of the terms, which times the machine epsilon
        bounds the rounding error of the sum."""
        x = _arr(x)
        shape = x.shape
        xf = np.abs(x.ravel())
        out = np.empty(xf.size)
        alpha, beta, gamma = (c[None, :] for c in self._coef)
        k0, k1 = self._knots[None, :-1], self._knots[None, 1:]
        step = max(1, _CHUNK // k0.size)
        with np.errstate(divide="ignore", invalid="ignore"):
            for s in range(0, xf.size, step):
                xc = xf[s:s + step, None]
                xs = np.where(xc > 0.0, xc, 1.0)
                lo, hi = np.minimum(k0, xc), np.minimum(k1, xc)
                (s_lo, c_lo, p_lo), (s_hi, c_hi, p_hi) = _phi_terms(xs, lo, hi)
                d0 = p_hi - p_lo
                d1 = c_lo - c_hi
                d2 = 0.5 * (d0 - (s_hi * c_hi - s_lo * c_lo))
                if which == 0:
                    v = xs[:, 0] * np.sum(alpha * d0 + beta * xs * d1 + gamma * xs ** 2 * d2, axis=1)
                elif magnitude:
                    # d0, d1, d2 are differences of O(1) numbers (angles, cosines): each carries an
                    # absolute rounding error of an ulp or so, whatever its size
                    if which == 1:
                        terms = np.abs(alpha) + 2.0 * np.abs(beta) * xs + 3.0 * np.abs(gamma) * xs ** 2
                    else:
                        terms = 2.0 * np.abs(beta) + 6.0 * np.abs(gamma) * xs
                    v = np.sum(np.where(k0 < xc, terms, 0.0), axis=1)
                elif which == 1:
                    v = np.sum(alpha * d0 + 2.0 * beta * xs * d1 + 3.0 * gamma * xs ** 2 * d2, axis=1)
                elif which == 2:
                    v = np.sum(2.0 * beta * d1 + 6.0 * gamma * xs * d2, axis=1)
                else:
                    # S3 = 2/3 - cos + cos^3/3, S4 = 3 phi/8 - sin(2 phi)/4 + sin(4 phi)/32
                    d3 = (c_lo - c_hi) - (c_lo ** 3 - c_hi ** 3) / 3.0
                    sc_hi, sc_lo = s_hi * c_hi, s_lo * c_lo
                    d4 = (0.375 * d0 - 0.5 * (sc_hi - sc_lo)
                          + 0.125 * (sc_hi * (c_hi ** 2 - s_hi ** 2) - sc_lo * (c_lo ** 2 - s_lo ** 2)))
                    v = 2.0 * xs[:, 0] ** 2 * np.sum(alpha * d2 + beta * xs * d3 + gamma * xs ** 2 * d4,
                                                     axis=1)
                zero = xc[:, 0] == 0.0
                if np.any(zero):  # limits at x = 0
                    v = np.where(zero, (0.0, 0.5 * math.pi * self._coef[0, 0], 2.0 * self._coef[1, 0],
                                        0.0)[which], v)
                out[s:s + step] = v
        beyond = xf > self.max_radius * (1.0 + 1e-12)
        if np.any(beyond):
            out[beyond] = np.nan  # outside the table: undefined (the public functions refuse it)
        return out.reshape(shape)

    def g(self, x):
        return self._sums(x, 0)

    def dg(self, x):
        """g'(|x|), from the table of ``_build_table`` (as accurate as ``_sums``, O(log knots))."""
        return self._fast(x, 0)

    def d2g(self, x):
        """g''(|x|), from the table of ``_build_table``."""
        return self._fast(x, 1)

    # -- g' and g'' from a piecewise polynomial table ------------------------------------------------
    def _fast(self, x, which):
        """g' (which=0) or g'' (1) from the table of ``_build_table``: a binary search and one
        Horner sum, O(log knots) per point instead of the O(knots) sum of ``_sums``."""
        table = self._table if self._table is not None else self._build_table()
        xb, kk, ih, wm, iw, coef = table
        x = _arr(x)
        xf = np.abs(x.ravel())
        i = np.maximum(np.searchsorted(xb, xf, side="right") - 1, 0)
        with np.errstate(invalid="ignore"):
            z = (np.sqrt((xf - kk[i]) * ih[i]) - wm[i]) * iw[i]
            a = coef[which]
            v = a[-1][i]
            for row in a[-2::-1]:
                v = v * z + row[i]
            beyond = xf > self.max_radius * (1.0 + 1e-12)
            if np.any(beyond):
                v[beyond] = np.nan  # outside the table: undefined (the public functions refuse it)
        return v.reshape(x.shape)

    def _build_table(self):
        """Piecewise polynomials for g' and g'' (see the block comment above ``_TABLE_DEGREE``)."""
        kn = self._knots
        n = _TABLE_DEGREE
        z_fit, z_chk, to_monomial = _table_rules(n)
        # piece 0 (no knot below): g' = alpha pi/2 + 2 beta x + 3 pi gamma x^2/4 exactly, a polynomial
        # in w = sqrt(x/h) (z = w), which keeps its relative accuracy as x -> 0
        a0, b0, c0 = self._coef[:, 0]
        h0 = kn[1] - kn[0]
        first = np.zeros((2, n + 1))
        first[0, 0], first[0, 2], first[0, 4] = 0.5 * math.pi * a0, 2.0 * b0 * h0, 0.75 * math.pi * c0 * h0 * h0
        first[1, 0], first[1, 2] = 2.0 * b0, 1.5 * math.pi * c0 * h0
        rows = [(np.array([0]), np.array([0.0]), np.array([1.0]), first[:, None, :])]
        # start from sub-intervals graded towards w = 0 when the knot below is close: its branch point
        # sits at w = i sqrt(q), q = (k_j - k_j-1)/(k_j+1 - k_j), and a sub-interval much longer
        # than its distance to it would converge too slowly to tell convergence from rounding
        j, lo, hi = [], [], []
        for piece in range(1, kn.size - 1):
            d = math.sqrt((kn[piece] - kn[piece - 1]) / (kn[piece + 1] - kn[piece]))
            edges = [0.0] + [d * 2.0 ** m for m in range(max(0, math.ceil(-math.log2(d))))
                             if d * 2.0 ** m < 0.75] + [1.0]
            j += [piece] * (len(edges) - 1)
            lo += edges[:-1]
            hi += edges[1:]
        j, lo, hi = np.array(j, dtype=np.int64), np.array(lo), np.array(hi)
        last = np.full(j.size, np.inf)       # error of the parent interval, in ulps of the scale
        scale = None
        eps = np.finfo(float).eps
        for level in range(_TABLE_LEVELS + 1):
            if j.size == 0:
                break
            k, h = kn[j][:, None], (kn[j + 1] - kn[j])[:, None]
            wm, wh = 0.5 * (hi + lo)[:, None], 0.5 * (hi - lo)[:, None]

            def at(zz):
                # the x actually sampled (rounded) and its z by the same arithmetic as ``_fast``
                w = wm + wh * zz[None, :]
                x = np.minimum(k + h * w * w, kn[j + 1][:, None])
                return x, (np.sqrt((x - k) * (1.0 / h)) - wm) * (1.0 / wh)

            (xf, zf), (xc, zc) = at(z_fit), at(z_chk)
            vand = np.cos(np.arange(n + 1)[None, None, :] * np.arccos(np.clip(zf, -1.0, 1.0))[:, :, None])
            vals = [(self._sums(xf, q), self._sums(xc, q)) for q in (1, 2)]
            if scale is None:
                s1 = max(np.max(np.abs(vals[0][0])), np.max(np.abs(vals[0][1])), abs(first[0, 0]))
                s2 = max(np.max(np.abs(vals[1][0])), np.max(np.abs(vals[1][1])), s1 / kn[-1])
                scale = (s1, s2)
            coef, err, noisy = [], np.zeros(j.size), np.ones(j.size, dtype=bool)
            for q, (vf, vc) in enumerate(vals):
                try:
                    c = np.linalg.solve(vand, vf[:, :, None])[:, :, 0]
                except np.linalg.LinAlgError:   # nodes merged by rounding (a sub-interval of ulps)
                    c = (np.linalg.pinv(vand) @ vf[:, :, None])[:, :, 0]
                c = c @ to_monomial.T
                p = np.broadcast_to(c[:, -1:], vc.shape)
                for m in range(n - 1, -1, -1):
                    p = p * zc + c[:, m:m + 1]
                e = np.max(np.abs(p - vc), axis=1)
                err = np.maximum(err, e / (eps * scale[q]))
                # within a bound of the exact sum's own rounding
                noisy &= e <= eps * np.max(self._sums(xc, q + 1, magnitude=True), axis=1)
                coef.append(c)
            # converged; or stuck at the rounding of the exact sums (halving gained < 4x)
            ok = (err <= _TABLE_ULPS) | (noisy & (err > 0.25 * last)) | (level == _TABLE_LEVELS)
            if np.any(ok):
                rows.append((j[ok], lo[ok], hi[ok], np.stack([c[ok] for c in coef])))
            bad = ~ok
            mid = 0.5 * (lo + hi)
            j, last = np.repeat(j[bad], 2), np.repeat(err[bad], 2)
            lo, hi = np.column_stack([lo[bad], mid[bad]]).ravel(), np.column_stack([mid[bad], hi[bad]]).ravel()
        j = np.concatenate([r[0] for r in rows])
        lo = np.concatenate([r[1] for r in rows])
        hi = np.concatenate([r[2] for r in rows])
        coef = np.concatenate([r[3] for r in rows], axis=1)        # (2, intervals, n + 1)
        h = kn[j + 1] - kn[j]
        xb = kn[j] + h * lo * lo
        xb[lo == 0.0] = kn[j][lo == 0.0]
        order = np.argsort(xb, kind="stable")
        wm, iw = 0.5 * (hi + lo), 2.0 / (hi - lo)
        wm[j == 0], iw[j == 0] = 0.0, 1.0                          # piece 0: z = w
        table = (xb[order], kn[j][order], 1.0 / h[order], wm[order], iw[order],
                 np.ascontiguousarray(coef[:, order, :].transpose(0, 2, 1)))
        object.__setattr__(self, "_table", table)
        return table

    def depth(self, a):
        return self._sums(self._check_radius(a), 0)

    def normal_force(self, a):
        """F_N / E* = 2 int_0^a r^2 f'(r) / sqrt(a^2 - r^2) dr (Sneddon; equal to eq. 10), exact
        for the spline."""
        return self._sums(self._check_radius(a), 3)

    def contact_radius(self, delta):
        """Inverse of ``depth`` (eq. 7, docs/theory/axisymmetric.md (A3)) by 80 bisection steps on
        [0, r_max] (g is increasing for a monotone profile)."""
        delta = _arr(delta)
        top = float(self.g(self.max_radius))
        if np.any(delta > top * (1.0 + 1e-12)) or np.any(delta < 0.0):
            raise ValueError(f"tabulated profile: depth must lie in [0, {top!r}] (the depth at the end "
                             f"of the table, r = {self.max_radius!r}); got {delta!r}")
        return bisect(lambda r: self.g(r) < delta, np.zeros(delta.shape), np.full(delta.shape, self.max_radius),
                      80)


# -- constructors (the public API) -------------------------------------------------------------------

def cone(tan_theta: float) -> Profile:
    """Cone f = r tan(theta)."""
    return Cone(tan_theta)


def paraboloid(R: float) -> Profile:
    """Paraboloid f = r^2 / (2R)."""
    return Paraboloid(R)


def power_law(A: float, n: float) -> Profile:
    """Power law f = A r^n, n > 0."""
    return PowerLaw(A, n)


def flat_punch(radius: float, depth: float = 1.0) -> Profile:
    """Flat punch of the given radius; ``depth`` (default 1) scales its stresses."""
    return FlatPunch(radius, depth)


def tabulated(r, f) -> Profile:
    """Profile f(r) sampled at sorted r >= 0 (>= 4 points, f non-decreasing); see ``Tabulated``."""
    return Tabulated(tuple(np.asarray(r, dtype=float).ravel().tolist()) if np.ndim(r) <= 1 else r,
                     tuple(np.asarray(f, dtype=float).ravel().tolist()) if np.ndim(f) <= 1 else f)
