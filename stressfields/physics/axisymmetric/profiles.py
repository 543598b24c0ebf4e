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
from scipy.special import gammaln

from ..quadrature import gauss_legendre
from ..roots import bisect
from ..setup_cache import SETUP, content_key
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
# The sums are evaluated in each piece's own coefficients about its lower knot, with moments of
# t = r - r_j that keep their relative accuracy (``_piece_moments``, docs/theory/axisymmetric.md
# (A102)-(A103)): alpha, beta, gamma above cancel to 4e-11 of g' on a noisy 40-point table.

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

# The table's fit and check values come from the sums of (A103) at ~25 points per piece; summing
# every piece below each point would make the set-up O(knots^2) (1000 samples: 1.8 s).  The pieces
# far below a point enter instead by the Chebyshev moments of their integrands on a binary tree of
# pieces (``_far_trees``; the route of docs/theory/graded.md (G52)-(G54) at k = 0) and only the few
# pieces within _FAR_SEP block widths by their exact sums: O(log knots) per point, O(knots log knots)
# for the table.
_FAST_SUMS = True     # False: the exact sums over every piece (the reference of the tests)
_FAR_SEP = 1.5        # distance of a block of pieces below x, in block widths
_FAR_ORDER = 22       # Chebyshev points per block: fastsum.chebyshev_order(2e-16, _FAR_SEP), the bound of (G53)


def _far_kernel(x, u):
    """1/sqrt(x^2 - u^2), the kernel of g' and x g'' in u (A103)."""
    return 1.0 / np.sqrt((x - u) * (x + u))


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


# Taylor coefficients (in u^2) of u - sin u = u^3 sum_n D[n] u^(2n) and of
# E3(D) = int_0^D (1 - cos t)^2 dt = 2 (D - sin D) - (2D - sin 2D)/4 = D^5 sum_n E[n] D^(2n): both
# alternate with terms below 1e-18 of the sum by n = 15 for u <= pi and D <= pi/2 (the largest
# arguments), so no closed-form branch is needed, and neither loses digits as D -> 0.
_D_SERIES = np.array([(-1.0) ** n / math.factorial(2 * n + 3) for n in range(16)])
_E3_SERIES = np.array([(-1.0) ** (n + 1) * (2.0 - 2.0 ** (2 * n + 3)) / math.factorial(2 * n + 5)
                       for n in range(15)])


def _series(coef, u2):
    out = u2 * coef[-1] + coef[-2]
    for c in coef[-3::-1]:      # in place: the work arrays are (points x pieces)
        out *= u2
        out += c
    return out


# 9 terms of each series suffice up to D = 0.5 (the last below 1e-16 of the first), which holds all
# but the pieces next to x; those take the full series (the sums of a 1000-knot table's build:
# 0.63 s instead of 0.74 s, measured on a shared machine)
_SHORT = 9


def _angle_series(d, terms):
    """-(D - sin D), int_0^D (1 - cos t)^2 dt and (2D - sin 2D)/4 by the series above."""
    d2 = d * d
    return (-d * d2 * _series(_D_SERIES[:terms], d2), d2 * d2 * d * _series(_E3_SERIES[:terms], d2),
            2.0 * d * d2 * _series(_D_SERIES[:terms], 4.0 * d2))


def _piece_moments(x, k):
    """Angle increments and moments of the spline pieces [k0, k1] between consecutive columns of
    ``k`` (knots clipped to x, shape (points, pieces + 1)): with r = x sin(phi), t = r - k0 and
    D = phi(k1) - phi(k0), (D, int t dphi, int t^2 dphi) over each piece,
    docs/theory/axisymmetric.md (A102).
    All three keep their relative accuracy however narrow the piece: D from the angle difference
    (sin D = (k1 - k0)(k1 + k0)/(k1 C0 + k0 C1), C = sqrt(x^2 - k^2), cos D = (C0 C1 + k0 k1)/x^2),
    the moments from 1 - cos D = sin^2 D/(1 + cos D) and series in D (``_D_SERIES``,
    ``_E3_SERIES``) instead of differences of cosines, which lose the digits of (k0/(k1 - k0))^2."""
    ck = np.sqrt((x - k) * (x + k))
    k0, k1, c0, c1 = k[:, :-1], k[:, 1:], ck[:, :-1], ck[:, 1:]
    sin_d = (k1 - k0) * (k1 + k0)
    norm = k1 * c0 + k0 * c1
    cos_d = (c0 * c1 + k0 * k1) / (x * x)
    sin_d = np.divide(sin_d, norm, out=np.zeros_like(sin_d), where=norm > 0.0)  # k0 = k1 = x: empty
    d = np.arctan2(sin_d, cos_d)
    e2 = sin_d * sin_d / (1.0 + cos_d)                   # int sin = 1 - cos D
    e4 = -0.5 * e2 * e2                                   # int (cos - 1) sin = -(1 - cos D)^2 / 2
    e1, e3, e5 = _angle_series(d, _SHORT)                 # int (cos - 1), (cos - 1)^2, sin^2
    wide = d > 0.5
    if np.any(wide):
        for e, full in zip((e1, e3, e5), _angle_series(d[wide], _D_SERIES.size)):
            e[wide] = full
    # t = k0 (cos(tau) - 1) + C0 sin(tau), tau = phi - phi(k0)
    m1 = k0 * e1 + c0 * e2
    m2 = k0 * k0 * e3 + 2.0 * k0 * c0 * e4 + c0 * c0 * e5
    return d, m1, m2


def _trig_integral_series(i, j, terms=40):
    """Coefficients (in powers of D) of int_0^D (cos t - 1)^i sin^j t dt, from the Taylor series of
    cos t - 1 and sin t; 40 terms leave (pi/2)^40/40! ~ 1e-40 for D <= pi/2."""
    n = np.arange(terms)
    fact = np.array([float(math.factorial(k)) for k in range(terms)])
    cos_m1 = np.where((n % 2 == 0) & (n > 0), (-1.0) ** (n // 2) / fact, 0.0)
    sin = np.where(n % 2 == 1, (-1.0) ** ((n - 1) // 2) / fact, 0.0)
    poly = np.zeros(terms)
    poly[0] = 1.0
    for factor in [cos_m1] * i + [sin] * j:
        poly = np.convolve(poly, factor)[:terms]
    return np.concatenate([[0.0], poly / (n + 1.0)])


# int t^3 dphi and int t^4 dphi (the load (A10) in local coefficients): binomial terms of
# t = k0 (cos - 1) + C0 sin over (i, k - i)
_HIGH_MOMENTS = {k: [(math.comb(k, i), i, _trig_integral_series(i, k - i)) for i in range(k + 1)] for k in (3, 4)}


def _high_moments(d, k0, c0):
    """(int t^3 dphi, int t^4 dphi) over the pieces of ``_piece_moments`` (A102), by the series of
    ``_trig_integral_series`` in D (each binomial term keeps its relative accuracy)."""
    out = []
    for k in (3, 4):
        total = np.zeros_like(d)
        for comb, i, coef in _HIGH_MOMENTS[k]:
            total += comb * k0 ** i * c0 ** (k - i) * np.polynomial.polynomial.polyval(d, coef)
        out.append(total)
    return out


def _sum_pieces(which, magnitude, x, terms):
    """g (which=0), g' (1) or g'' (2) from the terms p_k M_k of the pieces (A103), (points, pieces)
    each; with ``magnitude`` the sum of their sizes (times a few epsilons: the rounding error)."""
    if magnitude:
        v = np.sum(np.abs(terms[0]) + np.abs(terms[1]) + np.abs(terms[2]), axis=1)
    else:
        v = np.sum(terms[0] + terms[1] + terms[2], axis=1)
    if which == 0:
        return x * v
    return v / x if which == 2 else v


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
    _local: np.ndarray = field(init=False, repr=False, compare=False)
    _integrands: tuple = field(init=False, repr=False, compare=False)
    _table: tuple = field(init=False, repr=False, compare=False, default=None)
    _key: tuple = field(init=False, repr=False, compare=False)

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
        # the content the set-up derives from: equal samples share it through the set-up cache
        object.__setattr__(self, "_key", ("tabulated",) + content_key(r, f))
        from scipy.interpolate import CubicSpline   # here: its import (0.1 s) only for tabulated profiles

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
        # the spline's own coefficients about each piece's lower knot (piece 0 about r = 0): the
        # global ones above grow like the third derivative times r^2 and cancel to 5e-12 of max|f'| on
        # noisy tables (measured on the 40-point test profile of tests/physics/test_axisymmetric_tabulated_abel_sums.py)
        local = np.stack([b, c, d])
        local[:, 0] = alpha[0], 0.5 * beta[0], gamma[0] / 3.0
        object.__setattr__(self, "_local", local)
        object.__setattr__(self, "_integrands", self._piece_integrands())

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
        ``magnitude`` (g', g'' only): instead the size of the terms, which times a few machine
        epsilons bounds the rounding error of the sum."""
        return self._abel(x, (-which if magnitude else which,))[0]

    def _abel(self, x, whiches):
        """The sums of ``_sums`` for several ``which`` at once (-1, -2: the magnitudes of g', g''),
        sharing the angles and moments of the pieces.

        g, g', g'' (docs/theory/axisymmetric.md (A9), (A103)) and F_N (A10): per piece, in the
        spline's own coefficients about its lower knot, with the moments of ``_piece_moments`` and
        ``_high_moments``.  Cost O(points x pieces below the largest x of a chunk): the points are
        sorted and every chunk only visits the pieces below its largest point (the pieces above
        contribute nothing)."""
        x = _arr(x)
        shape = x.shape
        xf = np.abs(x.ravel())
        order = np.argsort(xf, kind="stable")
        xsorted = xf[order]
        outs = np.zeros((len(whiches), xf.size))
        kn = self._knots
        pieces = kn.size - 1
        step = max(1, _CHUNK // (4 * pieces))
        with np.errstate(divide="ignore", invalid="ignore"):
            for s in range(0, xf.size, step):
                xc = xsorted[s:s + step, None]
                m = min(pieces, int(np.searchsorted(kn, xc[-1, 0], side="left")))   # pieces with k_j < max x
                if m == 0:
                    continue                                  # x = 0 only: limits below
                xs = np.where(xc > 0.0, xc, 1.0)
                kc = np.minimum(kn[None, :m + 1], xs)
                moments = _piece_moments(xs, kc)
                terms = {}          # a sum and its magnitude share the terms
                for q, which in enumerate(whiches):
                    if which == 3:
                        v = self._load_terms(xs, kc, moments)
                    else:
                        w = abs(which)
                        if w not in terms:
                            terms[w] = [pk[None, :m] * mk for pk, mk in zip(self._integrands[w], moments)]
                        v = _sum_pieces(w, which < 0, xs[:, 0], terms[w])
                    outs[q, order[s:s + step]] = v
        zero = xf == 0.0
        beyond = xf > self.max_radius * (1.0 + 1e-12)
        for q, which in enumerate(whiches):
            if np.any(zero):  # limits at x = 0
                outs[q, zero] = (0.0, 0.5 * math.pi * self._coef[0, 0], 2.0 * self._coef[1, 0], 0.0)[which] \
                    if which >= 0 else 0.0
            if np.any(beyond):
                outs[q, beyond] = np.nan  # outside the table: undefined (the public functions refuse it)
        return [o.reshape(shape) for o in outs]

    def _piece_integrands(self):
        """Per piece j the coefficients (p0, p1, p2) of the integrand P(t) = p0 + p1 t + p2 t^2
        (A103) of g/x (index 0), g' (1) and x g'' (2), t = r - r_j.  (Pieces above x have zero
        moments, so the unclipped knots serve every point.)"""
        b, c, d = self._local
        k0 = self._knots[:-1]
        return ((b, 2.0 * c, 3.0 * d),                                    # f'(r)
                (b + 2.0 * c * k0, 4.0 * c + 6.0 * d * k0, 9.0 * d),        # f'(r) + r f''(r)
                (k0 * (4.0 * c + 6.0 * d * k0), 4.0 * c + 24.0 * d * k0, 18.0 * d))  # x(2s f'' + x s^2 f''')

    def _load_terms(self, xs, kc, moments):
        """F_N/E* (A10) over the pieces of ``kc``: 2 sum int (k0 + t)^2 f'(k0 + t) dphi, a quartic in
        t with the moments (A102) and ``_high_moments`` (the global coefficients would cancel to
        2e-11 on the noisy test table, like g)."""
        m = kc.shape[1] - 1
        b, c, d = (v[None, :m] for v in self._local)
        k0 = kc[:, :-1]
        c0 = np.sqrt((xs - k0) * (xs + k0))
        angle, m1, m2 = moments
        m3, m4 = _high_moments(angle, k0, c0)
        q = (k0 * k0 * b, 2.0 * k0 * (k0 * c + b), k0 * (3.0 * k0 * d + 4.0 * c) + b, 6.0 * k0 * d + 2.0 * c, 3.0 * d)
        return 2.0 * np.sum(q[0] * angle + q[1] * m1 + q[2] * m2 + q[3] * m3 + q[4] * m4, axis=1)

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
        """The table of ``_make_table``, built once per content (``setup_cache.SETUP``: shared by
        every profile object with the same samples, across calls and dask chunks)."""
        key = ("g' table", _TABLE_DEGREE, _TABLE_ULPS, _TABLE_LEVELS, _FAST_SUMS) + self._key
        table = SETUP.get(key, self._make_table)
        object.__setattr__(self, "_table", table)
        return table

    def _table_sums(self, x, sizes, far=None):
        """g', g'' at x (any shape, 0 < x <= r_max) for the table, and with ``sizes`` also their
        magnitudes (the rounding bounds of ``_abel``'s -1, -2): by ``_fast_sums`` (with the far
        field ``far`` of ``_far_field``) in O(log knots) per point, or by the exact sums ``_abel`` in
        O(knots) when _FAST_SUMS is off."""
        if not _FAST_SUMS:
            return self._abel(x, (1, 2, -1, -2) if sizes else (1, 2))
        outs = self._fast_sums(np.ravel(x), sizes, far)
        return [o.reshape(np.shape(x)) for o in outs]

    def _far_field(self):
        """The far field of the table's sums ((A109)), per spline piece: the block tree (``graded.fastsum``) of
        phi = (r f')' and psi = r phi' over the pieces, g'(x) = int_0^x phi(u) du / sqrt(x^2 - u^2) and
        x g''(x) = int_0^x psi(u) du / sqrt(x^2 - u^2) (the integrands of (A103) in u; both
        polynomials of degree 2 on a piece, so _FAR_ORDER/2 + 1 Gauss nodes per piece make the
        moments exact), passed down to the pieces by ``fastsum.local_fields`` (with the moments'
        magnitudes alongside, for the rounding bounds).  Returns (tree, leaf values, near pairs
        sorted by target piece, the first pair of every piece).  Built for the table only (not kept:
        23 MB at 1e4 samples)."""
        def make():
            from ..graded import fastsum    # the shared block tree (here: not loaded with the family)

            kn = self._knots
            w, W = gauss_legendre(_FAR_ORDER // 2 + 1)
            h = np.diff(kn)[:, None]
            t = h * w                                   # about each piece's lower knot, as (A103)
            u = (kn[:-1, None] + t).ravel()
            panel = np.repeat(np.arange(kn.size - 1), w.size)
            density = []
            for which in (1, 2):
                p0, p1, p2 = (c[:, None] for c in self._integrands[which])
                density.append(((h * W) * (p0 + t * (p1 + t * p2))).ravel())
            tree = fastsum.BlockTree(kn, u, np.stack(density, axis=-1), panel, _FAR_ORDER)
            moments = [[m[..., q] for m in tree.M] for q in (0, 1)]
            moments += [[np.abs(m) for m in M] for M in moments]
            values, (src, dst) = fastsum.local_fields(tree, moments, _far_kernel, _FAR_SEP)
            order = np.argsort(dst, kind="stable")
            src, dst = src[order], dst[order]
            first = np.searchsorted(dst, np.arange(kn.size))
            return tree, values, src, first
        return make()

    def _fast_sums(self, x, sizes, far=None):
        """g', g'' (and their magnitudes) at 1-D x in (0, r_max]: the pieces at least _FAR_SEP block
        widths below x by the far field of ``_far_field`` (A109) (its kernel interpolated on blocks:
        below 2e-16 of a block's part by the bound of docs/theory/graded.md (G53); measured 17-34 ulps
        of max |g'|, the rounding of the downward pass), the pieces nearer x by their exact sums
        (A103)."""
        from ..graded import fastsum

        tree, values, src, first = self._far_field() if far is None else far
        kn = self._knots
        piece = np.clip(np.searchsorted(kn, x, side="right") - 1, 0, kn.size - 2)
        outs = fastsum.local_values(tree, values[:4 if sizes else 2], x, piece)
        if sizes:
            # the far field's rounding: a few ulps of its magnitude per level of the downward pass
            # (Lebesgue constant ~3 of 24 Chebyshev points), ~20 ulps of g' at 1000 samples (measured)
            for i in (2, 3):
                outs[i] *= 3.0 * (tree.L + 1)
        # the near pairs of each point's piece: pieces below x and the piece holding x, summed exactly
        count = first[piece + 1] - first[piece]
        pt = np.repeat(np.arange(x.size), count)
        near = src[np.repeat(first[piece] - np.cumsum(count) + count, count) + np.arange(pt.size)]
        xp = x[pt]
        moments = _piece_moments(xp[:, None], np.stack([kn[near], np.minimum(kn[near + 1], xp)], axis=1))
        for i, which in enumerate((1, 2)):
            terms = [pk[near] * mk[:, 0] for pk, mk in zip(self._integrands[which], moments)]
            outs[i] += np.bincount(pt, weights=terms[0] + terms[1] + terms[2], minlength=x.size)
            if sizes:
                outs[i + 2] += np.bincount(pt, weights=np.abs(terms[0]) + np.abs(terms[1]) + np.abs(terms[2]),
                                           minlength=x.size)
        for i in range(1, len(outs), 2):
            outs[i] /= x                                    # g'' = (x g'') / x
        return outs

    def _make_table(self):
        """Piecewise polynomials for g' and g'' (see the block comment above ``_TABLE_DEGREE``)."""
        kn = self._knots
        n = _TABLE_DEGREE
        far = self._far_field() if _FAST_SUMS else None
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
            fit, chk = self._table_sums(xf, False, far), self._table_sums(xc, True, far)
            vals, sizes = list(zip(fit, chk[:2])), chk[2:]
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
                noisy &= e <= eps * np.max(sizes[q], axis=1)
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
        return (xb[order], kn[j][order], 1.0 / h[order], wm[order], iw[order],
                np.ascontiguousarray(coef[:, order, :].transpose(0, 2, 1)))

    def depth(self, a):
        return self._sums(self._check_radius(a), 0)

    def normal_force(self, a):
        """F_N / E* = 2 int_0^a r^2 f'(r) / sqrt(a^2 - r^2) dr (Sneddon; equal to eq. 10), exact
        for the spline."""
        return self._sums(self._check_radius(a), 3)

    def contact_radius(self, delta):
        """Inverse of ``depth`` (eq. 7, docs/theory/axisymmetric.md (A3)) by ``_relative_root`` on
        [0, r_max] (g is increasing for a monotone profile)."""
        delta = _arr(delta)
        top = float(self.g(self.max_radius))
        if np.any(delta > top * (1.0 + 1e-12)) or np.any(delta < 0.0):
            raise ValueError(f"tabulated profile: depth must lie in [0, {top!r}] (the depth at the end "
                             f"of the table, r = {self.max_radius!r}); got {delta!r}")
        return _relative_root(self.g, delta, self.max_radius)


#: the smallest contact radius the tabulated inversions resolve (the recipe check refuses loads
#: whose contact radius would be smaller, docs/theory/axisymmetric.md (A107) and after)
SMALLEST_RADIUS = 1e-300


def _relative_root(increasing, target, top: float) -> np.ndarray:
    """r in [0, top] with increasing(r) = target, to relative accuracy: 14 halvings of log r on
    [SMALLEST_RADIUS, top] bracket it within 4.3 % (the ratio e^(log(top/SMALLEST_RADIUS)/2^14),
    padded), then 64 arithmetic halvings of that bracket leave 2^-64 of the root (an arithmetic
    bisection of [0, top] alone left an absolute 2^-80 top, so a contact 1e-20 of the table wide
    came out 1e-4 off, and 1e-100 N on a 4 mm table 1e11 times; the log route alone leaves the
    rounding of exp, 1e-15 relative); 0 for a zero target."""
    target = _arr(target)
    if top <= SMALLEST_RADIUS:
        return np.zeros(target.shape)
    above = lambda x: increasing(x) < target
    lo, hi = np.full(target.shape, SMALLEST_RADIUS), np.full(target.shape, top)
    width = math.log(top / SMALLEST_RADIUS) / 2.0 ** _LOG_HALVINGS
    mid = bisect(above, lo, hi, _LOG_HALVINGS, geometric=True)
    lo, hi = np.maximum(mid * math.exp(-width), lo), np.minimum(mid * math.exp(width), hi)
    r = bisect(above, lo, hi, 64)
    return np.where(target > 0.0, r, 0.0)


_LOG_HALVINGS = 14


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


# -- load control: the load relation inverted, and the tangential load ratio --------------------------

def _load_exponent(profile: Profile) -> float | None:
    """n of the power-law families, where g ∝ a^n and F_N ∝ a^(n+1) (docs/theory/axisymmetric.md
    (A5)-(A7)); None for the flat punch and tabulated profiles."""
    if profile.kind == "cone":
        return 1.0
    if profile.kind == "paraboloid":
        return 2.0
    if profile.kind == "power_law":
        return profile.n
    return None


def radius_at_force(profile: Profile, force) -> np.ndarray:
    """Contact radius a with F_N(a) / E* = ``force``, the inverse of docs/theory/axisymmetric.md (A4).

    Power-law families: F_N / E* = 2 B a^(n+1) / (n+1) with B = kappa_n A n (A5)-(A7), inverted in
    closed form; flat punch: the punch radius whatever the force (A8, the force fixes the depth);
    tabulated: the shared bisection (``roots.bisect`` on log a, ``_relative_root``, as
    ``Tabulated.contact_radius``) on F_N, which increases with a for a non-decreasing profile."""
    force = _arr(force)
    n = _load_exponent(profile)
    if n is not None:
        return ((n + 1.0) * force / (2.0 * profile.tip_coefficient)) ** (1.0 / (n + 1.0))
    if profile.kind == "flat_punch":
        return np.full_like(force, profile.radius)
    top = float(profile.normal_force(profile.max_radius))
    if np.any(force > top * (1.0 + 1e-12)) or np.any(force < 0.0):
        raise ValueError(f"tabulated profile: F_N / E* must lie in [0, {top!r}] (the force at the end of "
                         f"the table, r = {profile.max_radius!r}); got {force!r}")
    return _relative_root(profile.normal_force, force, float(profile.max_radius))


def remaining_force(force, limit_factor, limit_load) -> np.ndarray:
    """1 - F_x / (mu F_N) = F_N(c) / F_N(a) of a tangential force F_x = ``force`` and mu F_N =
    ``limit_factor`` * ``limit_load``, in [0, 1], without cancellation as F_x -> mu F_N: mu F_N is
    formed exactly as a sum p + e of two doubles (Dekker's product), p - F_x is exact there (Sterbenz),
    so the result keeps the relative accuracy of its inputs instead of 1e-16 / (1 - fx)."""
    x, y, q = (_arr(v) for v in (limit_factor, limit_load, force))
    p = x * y
    split = 134217729.0                                     # 2^27 + 1: halves of 26 bits
    with np.errstate(over="ignore", invalid="ignore"):
        xh = x * split - (x * split - x)
        yh = y * split - (y * split - y)
        xl, yl = x - xh, y - yh
        e = ((xh * yh - p) + xh * yl + xl * yh) + xl * yl   # x * y - p, exactly
        e = np.where(np.isfinite(e), e, 0.0)                # beyond 1e300 the split overflows: plain p
        keep = ((p - q) + e) / p
    # F_x = mu F_N as the product rounds is gross slip (fx = 1), as the recipe check counts it
    return np.where(q == 0.0, 1.0, np.where(q >= p, 0.0, np.clip(keep, 0.0, 1.0)))


def stick_radius_of_force(profile: Profile, a, keep) -> np.ndarray:
    """Stick radius c of the tangential force with F_N(c) = ``keep`` F_N(a), ``keep`` = 1 - fx
    (Cattaneo–Mindlin in the MDR, docs/theory/axisymmetric.md (A107)), computed from the force
    directly (not through u_x0, whose round trip lost up to 7.5e-8 of c as fx -> 1 and made it depend
    on nu and mu): power laws c = a keep^(1/(n+1)); flat punch: a (stick) below gross slip, 0 at it;
    tabulated: ``radius_at_force``.  keep = 0 (fx = 1, gross slip) gives 0, keep = 1 gives a."""
    a, keep = np.broadcast_arrays(_arr(a), _arr(keep))
    n = _load_exponent(profile)
    if n is not None:
        c = a * (np.sqrt(keep) if n == 1.0 else np.cbrt(keep) if n == 2.0 else keep ** (1.0 / (n + 1.0)))
    elif profile.kind == "flat_punch":
        c = np.where(keep > 0.0, a, 0.0)
    else:
        c = radius_at_force(profile, keep * profile.normal_force(a))
    return np.where(keep >= 1.0, a, np.where(keep <= 0.0, 0.0, np.minimum(c, a)))


def slip_ratio(profile: Profile, a, fx, keep=None) -> np.ndarray:
    """rho = G* u_x0 / (mu E* delta) = [g(a) - g(c)] / g(a) (docs/theory/axisymmetric.md (A32)) of the
    tangential force F_x = fx mu F_N, 0 <= fx <= 1.

    Cattaneo–Mindlin in the MDR: F_x = mu [F_N(a) - F_N(c)] ((A107), the integral of (A34)), so c solves
    F_N(c) = (1 - fx) F_N(a).  Power laws: (c/a)^(n+1) = 1 - fx and rho = 1 - (1 - fx)^(n/(n+1)),
    evaluated as -expm1 of a log1p (no cancellation as fx -> 0); tabulated: c by ``radius_at_force``;
    flat punch: it sticks whole up to gross slip with F_x = 2 a G* u_x0 (A37), so rho = fx.
    fx = 1 gives rho = 1, the onset of gross slip (A33).  ``keep``: 1 - fx where it is known more
    accurately than fx itself (``remaining_force``), used for fx >= 1/2."""
    fx = _arr(fx)
    keep = 1.0 - fx if keep is None else _arr(keep)
    n = _load_exponent(profile)
    if n is not None:
        with np.errstate(divide="ignore"):
            log_keep = np.where(fx < 0.5, np.log1p(-np.minimum(fx, 0.5)), np.log(np.maximum(keep, 0.0)))
            return np.where((fx >= 1.0) | (keep <= 0.0), 1.0, -np.expm1(n / (n + 1.0) * log_keep))
    if profile.kind == "flat_punch":
        return np.minimum(fx, 1.0)
    a = _arr(a)
    c = radius_at_force(profile, keep * profile.normal_force(a))
    ga = profile.g(a)
    return np.where(fx >= 1.0, 1.0, (ga - profile.g(c)) / ga)


def annulus_width(profile: Profile, a, c, ux0, nu, mu) -> np.ndarray:
    """The slip annulus' width a - c of the displacement ``ux0`` = u_x0/delta, from the slip ratio
    rho = G* u_x0 / (mu E* delta) (A32) and not from the rounded c: power laws (c/a)^n = 1 - rho, so
    a - c = -a expm1(log1p(-rho)/n), which keeps its relative accuracy as fx -> 0 where a - c of the
    rounded radii keeps only 1e-16 a (docs/theory/axisymmetric.md (A109)).  Where c is not the stick
    radius of this ux0 (to 1e-13 a: a stick radius given otherwise), beyond power laws (flat punch,
    tabulated) and outside partial slip, a - c."""
    a, c, ux0, nu, mu = np.broadcast_arrays(*(_arr(v) for v in (a, c, ux0, nu, mu)))
    n = _load_exponent(profile)
    plain = a - c
    if n is None:
        return plain
    rho = slip_of_displacement(ux0, nu, mu)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        w = -a * np.expm1(np.log1p(-np.clip(rho, 0.0, 1.0)) / n)
        own = (rho > 0.0) & (rho < 1.0) & (c > 0.0) & (np.abs(plain - w) <= 1e-13 * a)
    return np.where(own, w, plain)


def force_ratio(profile: Profile, a, rho) -> np.ndarray:
    """fx = F_x / (mu F_N) of rho = G* u_x0 / (mu E* delta), the inverse of ``slip_ratio``:
    fx = 1 - F_N(c) / F_N(a) with g(c) = (1 - rho) g(a) (docs/theory/axisymmetric.md (A32)); 1 at and
    beyond gross slip (rho >= 1, (A33)).  Power laws: 1 - (1 - rho)^((n+1)/n); flat punch: rho
    (whole stick, (A37)); tabulated: c by ``Tabulated.contact_radius``."""
    rho = _arr(rho)
    n = _load_exponent(profile)
    if n is not None:
        with np.errstate(divide="ignore"):
            return np.where(rho >= 1.0, 1.0, -np.expm1((n + 1.0) / n * np.log1p(-np.minimum(rho, 1.0))))
    if profile.kind == "flat_punch":
        return np.minimum(rho, 1.0)
    a = _arr(a)
    keep = np.clip(1.0 - rho, 0.0, 1.0)
    c = profile.contact_radius(profile.depth(a) * keep)
    return np.where(rho >= 1.0, 1.0, 1.0 - profile.normal_force(c) / profile.normal_force(a))


def _gstar(nu):
    """G*/E* = 2(1 - nu)/(2 - nu) (docs/theory/axisymmetric.md (A1)), written as ``surface.stick_radius``
    writes it, so that a displacement derived here meets its threshold there bit for bit."""
    return 2.0 * (1.0 - nu) / (2.0 - nu)


def displacement_ratio(rho, nu, mu) -> np.ndarray:
    """u_x0 / delta = mu (E*/G*) rho, the displacement of the slip ratio rho (docs/theory/axisymmetric.md
    (A32)); at rho >= 1 (gross slip, (A33)) raised by an ulp or two where G* u_x0/(mu E* delta) would
    round below 1 (5 % of 10^5 random (nu, mu), measured), so that ``stick_radius`` sees gross slip."""
    rho, nu, mu = (_arr(v) for v in (rho, nu, mu))
    gstar = _gstar(nu)
    ux0 = mu * rho / gstar
    for _ in range(4):          # one ulp sufficed in all 10^5 cases measured
        with np.errstate(divide="ignore", invalid="ignore"):
            short = (rho >= 1.0) & (mu > 0.0) & (gstar * ux0 / mu < 1.0)
        ux0 = np.where(short, np.nextafter(ux0, np.inf), ux0)
    return ux0


def slip_of_displacement(ux0, nu, mu) -> np.ndarray:
    """rho = G* u_x0 / (mu E* delta) as ``surface.stick_radius`` forms it (docs/theory/axisymmetric.md
    (A32)-(A33)): 0 without displacement, +inf for mu = 0 with u_x0 > 0 (gross slip)."""
    ux0, nu, mu = (_arr(v) for v in (ux0, nu, mu))
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(ux0 == 0.0, 0.0, np.where(mu > 0.0, _gstar(nu) * ux0 / mu, np.inf))
