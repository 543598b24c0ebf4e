"""Public kernels: surface stress tensor, d p_h/dz, stick radius and mean pressure.

E. Willert, F. Forsbach, V. L. Popov, "Stress tensor and gradient of hydrostatic pressure in the
contact plane of axisymmetric bodies under normal and tangential loading".  Normal part eq. (9)
(closed: (1), (36); flat punch (3) times depth), Cattaneo–Mindlin tangential part eq. (24)-(25)
(closed: (14)-(17), (39)-(40); flat punch (18)-(19)), pressure gradient eq. (11) + (26) (closed:
(5), (21), (37), (41); flat punch regular parts of (6), (22)); in the package's numbering
docs/theory/axisymmetric.md (A11)-(A59).  Conventions of docs/theory/axisymmetric.md section 2:
tension positive, z into the body, sigma_zz(z=0) = -p, traction on the half-space along +x so
sigma_xz = -q <= 0, p_h = -trace/3.

Values are divided by E* = E/(1 - nu^2): stresses dimensionless, dp/dz in 1/length.  All array
arguments broadcast; evaluation is vectorised in chunks of points (no loop over points).

Singular and undefined points (the caller flags every non-finite value):

* Points with r <= a count as contact and r <= c as stick zone; values there are the radial limits
  from inside.
* +-inf where the exact value is unbounded with a definite sign: conical (or sharper) tip r = 0
  for sigma_xx, sigma_yy, sigma_zz and dp/dz; tangential dp/dz on r = a (-inf sgn x, contact side)
  and on r = c (+inf sgn x, stick side), 0 on those circles where x = 0; flat-punch edge r = a for
  sigma_xx, sigma_yy, sigma_zz, sigma_xy (off the axes) and sigma_xz, and for its tangential dp/dz.
  The normal dp/dz jumps at r = a; its inside value is returned there (it is +inf only for
  r -> a from outside, like g'(a)/sqrt(r^2 - a^2)).
* NaN where the limit depends on the direction of approach: r = 0 for sigma_xy of a conical tip
  (unless nu = 1/2), for the tangential in-plane stresses of a conical tip in gross slip (the total
  sigma_xx, sigma_yy are still -inf there, the normal part dominates), and for dp/dz of a conical
  (or sharper, power law n < 2) tip in gross slip when mu >= the ratio of the two 1/r terms
  (mu >= 1 for a cone); for power laws with n < 1 in gross slip also sigma_xx, sigma_yy at r = 0.
  Also NaN where x or y is not finite.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.special import gammaln

from ..flags import quiet
from ..quadrature import orders
from . import integrals, normal, tangential
from .common import arccosh_ratio
from .integrals import log_integral, tau_integrals, theta_moments
from .routes import resolve

__all__ = ["surface_stress", "surface_dpdz", "stick_radius", "mean_pressure", "min_pressure"]

COMPONENTS = ("xx", "yy", "zz", "xy", "xz", "yz")
#: points per block. The quadrature route's (nodes x points) arrays stay in cache at 4096; the
#: closed forms make many short NumPy calls per block, whose interpreter overhead serialises
#: threaded dask workers at 4096, and one thread is fastest at 16384 (docs/bench/tuning.md)
_CHUNK = 4096
_CLOSED_CHUNK = 16384


# -- argument handling --------------------------------------------------------------------------

def _check_range(name, v, lo, hi, allowed):
    v = np.asarray(v, dtype=float)
    ok = (v >= lo) & (v <= hi)
    if not np.all(ok):
        bad = v[~ok] if v.ndim else v
        raise ValueError(f"{name} must be {allowed}; got {np.ravel(bad)[0]!r}")


def _validate(a, c, nu, mu):
    _check_range("a (contact radius)", a, np.nextafter(0.0, 1.0), math.inf, "positive and finite (a > 0)")
    if not np.all(np.isfinite(a)):
        raise ValueError("a (contact radius) must be positive and finite (a > 0); got inf")
    _check_range("nu (Poisson's ratio)", nu, 0.0, 0.5, "in [0, 0.5]")
    _check_range("mu (coefficient of friction)", mu, 0.0, math.inf, "finite and >= 0")
    if not np.all(np.isfinite(mu)):
        raise ValueError("mu (coefficient of friction) must be finite and >= 0; got inf")
    c_b, a_b = np.broadcast_arrays(np.asarray(c, dtype=float), np.asarray(a, dtype=float))
    ok = (c_b >= 0.0) & (c_b <= a_b)
    if not np.all(ok):
        raise ValueError(f"c (stick radius) must be in [0, a]; got c = {c_b[~ok].ravel()[0]!r} with "
                         f"a = {a_b[~ok].ravel()[0]!r}")


def _width(width, shape):
    """The annulus width per flat point: ``width`` broadcast to ``shape``; where not given NaN (not
    thin: the kernels take a - c of the radii)."""
    width = math.nan if width is None else width
    return np.ascontiguousarray(np.broadcast_to(np.asarray(width, dtype=float), shape)).ravel()


def _prepare(x, y, a, c, nu, mu, profile):
    a_, c_, nu_, mu_ = (np.asarray(v, dtype=float) for v in (a, c, nu, mu))
    _validate(a_, c_, nu_, mu_)
    arrays = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(y, dtype=float), a_, c_, nu_, mu_)
    shape = arrays[0].shape
    flat = [np.ascontiguousarray(v).ravel() for v in arrays]
    if profile.kind == "flat_punch":
        if not np.allclose(flat[2], profile.radius, rtol=1e-12, atol=0.0):
            raise ValueError(f"flat punch: the contact radius a must equal the punch radius "
                             f"{profile.radius!r}; got a = {flat[2].max()!r}")
    elif np.any(flat[2] > profile.max_radius * (1.0 + 1e-12)):
        raise ValueError(f"a (contact radius) = {flat[2].max()!r} exceeds the end of the tabulated "
                         f"profile, r = {profile.max_radius!r}")
    return shape, flat


def _route(profile, method):
    """The closed-form family to use, or None for the quadrature route."""
    if method not in ("closed", "quadrature"):
        raise ValueError(f"method must be 'closed' or 'quadrature', got {method!r}")
    if profile.kind == "flat_punch":
        return profile.closed           # both methods: eq. (3), (6), (19), (22)
    if method == "closed":
        if not profile.has_closed_form:       # decided by routes.has_closed_form
            raise ValueError(f"method='closed': the {profile.kind} profile {profile!r} has no closed form; "
                             "use method='quadrature'")
        return profile.closed
    return None


def _components(components):
    comps = tuple(components)
    for k in comps:
        if k not in COMPONENTS:
            raise ValueError(f"unknown stress component {k!r}; allowed: {', '.join(COMPONENTS)}")
    return comps


def _tip(profile, closed):
    """(m0, B, log-integral function, g''(0)) describing the tip, for the r = 0 limits."""
    if closed is not None and closed[0] == "cone":
        B = 0.5 * math.pi * closed[1]
        return 0.0, B, (lambda lo, hi: np.where(lo > 0, B * np.log(hi / np.where(lo > 0, lo, 1.0)), math.inf)), 0.0
    if closed is not None and closed[0] == "paraboloid":
        R = closed[1]
        return 1.0, 2.0 / R, (lambda lo, hi: 2.0 * (hi - lo) / R), 2.0 / R
    return profile.tip_exponent, profile.tip_coefficient, None, float(profile.d2g(0.0))


def _ratio_kN_kT(m):
    """Coefficients of the r^(m-1) terms of the normal and gross-slip tangential dp/dz at r -> 0 for
    g' ~ B u^m (m < 1): k_N = Gamma(m/2+1)/Gamma(m/2+1/2), k_T = Gamma(1-m/2)/Gamma((1-m)/2)."""
    kN = math.exp(gammaln(0.5 * m + 1.0) - gammaln(0.5 * m + 0.5))
    kT = math.exp(gammaln(1.0 - 0.5 * m) - gammaln(0.5 * (1.0 - m)))
    return kN, kT


class _BlockLoad:
    """A tabulated profile as ``normal.polar_from_integrals`` reads it, with the load F(r) of the
    block route (docs/theory/axisymmetric.md (A106), O(log knots) per point; the exact sums of
    ``Tabulated.normal_force`` visit every piece below r: 88 us per point at 1000 samples, more
    than all the integrals)."""

    def __init__(self, profile, ords):
        self.profile, self.ords = profile, ords
        self.tip_exponent, self.tip_coefficient = profile.tip_exponent, profile.tip_coefficient

    def normal_force(self, h):
        return integrals.normal_force(self.profile, np.asarray(h, dtype=float), self.ords)


def _load_view(profile, ords):
    return _BlockLoad(profile, ords) if integrals.blocks_apply(profile) else profile


# -- Cartesian components of the axisymmetric normal part --------------------------------------

def _cartesian(srr, sff, dev, X, Y):
    """sigma_xx, sigma_yy, sigma_xy from the polar ones; on the axes the pure components are used so
    that an infinite srr or sff does not meet a zero weight (0 * inf)."""
    X2, Y2 = X * X, Y * Y
    with np.errstate(invalid="ignore"):
        xx = np.where(Y == 0.0, srr, np.where(X == 0.0, sff, srr * X2 + sff * Y2))
        yy = np.where(Y == 0.0, sff, np.where(X == 0.0, srr, srr * Y2 + sff * X2))
        xy = np.where((X == 0.0) | (Y == 0.0), 0.0, 2.0 * dev * X * Y)
    return xx, yy, xy


# -- stresses --------------------------------------------------------------------------------------

def _stress_main(profile, closed, ords, comps, x, y, r, a, c, nu, mu, w):
    """All requested components at points with r > 0."""
    n = r.size
    act = (mu > 0.0) & (c < a)
    need_inplane = any(k in comps for k in ("xx", "yy", "xy"))
    need_normal = need_inplane or "zz" in comps
    need_shear = "xz" in comps and bool(np.any(act))
    res = {}
    tx = {k: np.zeros(n) for k in ("xx", "yy", "xy", "xz")}
    ia = np.flatnonzero(act)
    if closed is not None:
        if need_normal:
            szz, srr, sff, dev = normal.polar_closed(closed, r, a, nu)
        if ia.size and need_inplane:
            v = tangential.inplane_closed(closed, x[ia], y[ia], r[ia], a[ia], c[ia], nu[ia], mu[ia], w[ia])
            for k, val in zip(("xx", "yy", "xy"), v):
                tx[k][ia] = val
        if need_shear:
            tx["xz"][ia] = tangential.shear_closed(closed, r[ia], a[ia], c[ia], mu[ia], w[ia])
    elif need_normal or need_shear:
        inside = r < a
        ii = np.flatnonzero(inside & (need_normal | act))
        ri, ai, ci = r[ii], a[ii], c[ii]
        L = arccosh_ratio(ai, ri)
        split = act[ii] & (ri < ci)
        tm = np.where(split, arccosh_ratio(ci, np.minimum(ri, ci)), 0.0)
        kinds = (("G", "GE") if need_inplane else ("G",)) if need_normal else ("G",)
        hi_part = tau_integrals(profile, ri, tm, L, ords, kinds)
        G_slip = hi_part["G"]
        if need_normal:
            G = np.zeros(n)
            GE = np.zeros(n)
            lo_part = {k: np.zeros(ii.size) for k in kinds}
            js = np.flatnonzero(split)
            if js.size:
                sub = tau_integrals(profile, ri[js], np.zeros(js.size), tm[js], ords, kinds)
                for k in kinds:
                    lo_part[k][js] = sub[k]
            G[ii] = hi_part["G"] + lo_part["G"]
            if "GE" in kinds:
                GE[ii] = hi_part["GE"] + lo_part["GE"]
            szz, srr, sff, dev = normal.polar_from_integrals(_load_view(profile, ords), r, a, nu, G, GE)
        if need_shear:
            Gs = np.zeros(n)
            Gs[ii] = G_slip
            tx["xz"][ia] = tangential.shear_from_integrals(r[ia], a[ia], mu[ia], Gs[ia])
        if need_inplane:
            ip = np.flatnonzero(act & (r > c))
            if ip.size:
                th_lo, th_hi = tangential.inplane_angles(r[ip], a[ip], c[ip], w[ip])
                P0, P2 = theta_moments(profile, r[ip], th_lo, th_hi, ords)
                v = tangential.inplane_from_moments(x[ip], y[ip], r[ip], nu[ip], mu[ip], P0, P2)
                for k, val in zip(("xx", "yy", "xy"), v):
                    tx[k][ip] = val
    if need_inplane:
        xx, yy, xy = _cartesian(srr, sff, dev, x / r, y / r)
        res.update(xx=xx + tx["xx"], yy=yy + tx["yy"], xy=xy + tx["xy"])
    if "zz" in comps:
        res["zz"] = szz
    res["xz"] = tx["xz"]
    res["yz"] = np.zeros(n)
    return res


def _stress_origin(profile, closed, ords, a, c, nu, mu, w):
    """Limits at r = 0 (see the module docstring)."""
    act = (mu > 0.0) & (c < a)
    gross = act & (c == 0.0)
    if closed is not None and closed[0] == "flat_punch":
        szz, sxx, sxy, _ = normal.origin(closed, a, nu, None, None)
        xz = np.where(act, -mu * closed[2] / (math.pi * a), 0.0)
        return dict(xx=sxx, yy=sxx.copy(), zz=szz, xy=sxy, xz=xz, yz=np.zeros_like(a))
    m0, B, logint, d2g0 = _tip(profile, closed)

    def LI(lo, hi):
        return logint(lo, hi) if logint is not None else log_integral(profile, lo, hi, ords)

    log0 = LI(np.zeros_like(a), a) if m0 > 0.0 else np.full(a.shape, math.inf)
    szz, sxx, sxy, _ = normal.origin(("tip", m0, B), a, nu, log0, d2g0)
    syy = sxx.copy()
    if m0 < 0.0:
        # both parts grow like r^m with direction-dependent weights: not resolved
        sxx = np.where(gross, np.nan, sxx)
        syy = np.where(gross, np.nan, syy)
    if m0 <= 0.0:
        sxy = np.where(gross, np.nan, sxy)
    # shear: -(mu/pi) int_c^a g'(u)/u du (r -> 0 of eq. 24)
    xz = np.zeros_like(a)
    if np.any(act):
        if m0 > 0.0:
            lim = LI(np.where(act, c, a), a)
            if closed is not None and closed[0] == "paraboloid":     # LI(c, a) with a - c = w (A109)
                lim = np.where(tangential.thin(a, w), 2.0 * w / closed[1], lim)
        else:   # int_0^a g'(u)/u du diverges for a conical tip: only partial slip is finite
            part = act & (c > 0.0)
            cone = closed is not None and closed[0] == "cone"
            # the cone's B ln(a/c) as -B log1p(-w/a): no ratio next to 1 as c -> a
            inner = LI(np.where(part, c, a), a)
            if cone:
                inner = np.where(tangential.thin(a, w), -B * np.log1p(-np.where(part, w, 0.0) / a), inner)
            lim = np.where(part, inner, math.copysign(math.inf, B))
        xz = np.where(act, -mu / math.pi * lim, 0.0)
    return dict(xx=sxx, yy=syy, zz=szz, xy=sxy, xz=xz, yz=np.zeros_like(a))


def _stress_chunk(profile, closed, ords, comps, x, y, a, c, nu, mu, w):
    n = x.size
    r = np.hypot(x, y)
    finite = np.isfinite(r)
    res = {k: np.full(n, np.nan) for k in COMPONENTS}
    main = np.flatnonzero(finite & (r > 0.0))
    if main.size:
        part = _stress_main(profile, closed, ords, comps, x[main], y[main], r[main], a[main], c[main],
                            nu[main], mu[main], w[main])
        for k in comps:
            res[k][main] = part[k]
    zero = np.flatnonzero(r == 0.0)
    if zero.size:
        part = _stress_origin(profile, closed, ords, a[zero], c[zero], nu[zero], mu[zero], w[zero])
        for k in comps:
            res[k][zero] = part[k]
    return res


@quiet
def surface_stress(x, y, a, c, nu, mu, profile, *, components=COMPONENTS, method="closed", rtol=1e-10,
                   width=None):
    """Surface (z = 0) stress tensor / E* under normal load and Cattaneo–Mindlin tangential load.

    Normal part eq. (9) (closed forms eq. 1, 36; flat punch eq. 3 times its depth) plus the
    tangential part for stick radius c: shear traction eq. (24) (closed 14, 39; flat punch 18),
    in-plane stresses eq. (25) (closed 15-17, 39-40; flat punch 19/20).  Willert, Forsbach & Popov,
    "Stress tensor and gradient of hydrostatic pressure in the contact plane of axisymmetric bodies
    under normal and tangential loading".

    Parameters
    ----------
    x, y : surface coordinates (x along the tangential load), in the profile's length unit.
    a : contact radius (> 0); c : stick radius, 0 <= c <= a (c = 0 gross slip; c = a: no
        tangential load); nu : Poisson's ratio in [0, 0.5]; mu : coefficient of friction >= 0
        (mu = 0: no tangential load).  All broadcast together.
    profile : a ``Profile``.  A flat punch slides (q = mu p) for every c < a; a sticking punch
        (eq. 20) is the sliding one with mu replaced by G* u_x0 / (E* delta).
    components : any of "xx", "yy", "zz", "xy", "xz", "yz"; only these are computed.
    method : "closed" (cone, paraboloid, power law n = 1 or 2, flat punch; ValueError otherwise)
        or "quadrature" (the 1-D integrals of eq. 9, 24, 25 for any profile; the flat punch
        always uses its closed forms).
    rtol : accuracy of the quadrature route, |error| <= rtol * max(1, |value|) in units of the
        mean pressure; 1e-14 <= rtol.
    width : the slip annulus' width a - c where it is known more accurately than the difference of
        the rounded radii (``profiles.annulus_width``, from the slip ratio); None: a - c.  The
        closed forms of the cone and the paraboloid take it, so that as c -> a (fx -> 0) the
        tangential part keeps its relative accuracy (docs/theory/axisymmetric.md (A109)).

    Returns
    -------
    dict component -> array of the broadcast shape, divided by E*.  sigma_yz = 0 at the surface.
    See the module docstring for the points that give +-inf or NaN.
    """
    comps = _components(components)
    ords = orders(rtol)
    closed = _route(profile, method)
    shape, (x, y, a, c, nu, mu) = _prepare(x, y, a, c, nu, mu, profile)
    w = _width(width, shape)
    n = x.size
    out = {k: np.empty(n) for k in comps}
    step = _CHUNK if closed is None else _CLOSED_CHUNK
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for s in range(0, n, step):
            sl = slice(s, s + step)
            part = _stress_chunk(profile, closed, ords, comps, x[sl], y[sl], a[sl], c[sl], nu[sl], mu[sl], w[sl])
            for k in comps:
                out[k][sl] = part[k]
    return {k: out[k].reshape(shape) for k in comps}


# -- pressure gradient -----------------------------------------------------------------------------

def _dpdz_main(profile, closed, ords, x, r, a, c, nu, mu, w):
    act = (mu > 0.0) & (c < a)
    if closed is not None:
        v = normal.dpdz_closed(closed, r, a, nu)
        ia = np.flatnonzero(act)
        if ia.size:
            v[ia] += tangential.dpdz_closed(closed, x[ia], r[ia], a[ia], c[ia], nu[ia], mu[ia], w[ia])
        return v
    v = normal.dpdz_quadrature(profile, r, a, nu, ords)
    ia = np.flatnonzero(act & (r <= a))
    if ia.size:
        ri, ai, ci = r[ia], a[ia], c[ia]
        inner = ri < ai
        L = np.where(inner, arccosh_ratio(ai, np.minimum(ri, ai)), 0.0)
        tm = np.where(inner & (ri < ci), arccosh_ratio(ci, np.minimum(ri, ci)), 0.0)
        H = tau_integrals(profile, ri, tm, L, ords, ("H",))["H"]
        v[ia] += tangential.dpdz_from_integrals(profile, x[ia], ri, ai, ci, nu[ia], mu[ia], H)
    return v


def _dpdz_origin(profile, closed, ords, a, c, nu, mu):
    act = (mu > 0.0) & (c < a)
    gross = act & (c == 0.0)
    if closed is not None and closed[0] == "flat_punch":
        return np.zeros_like(a)
    m0, B, _, d2g0 = _tip(profile, closed)
    _, _, _, dp = normal.origin(("tip", m0, B), a, nu, np.zeros_like(a), d2g0)
    if m0 < 1.0 and np.any(gross):
        kN, kT = _ratio_kN_kT(m0)
        # normal ~ -C B kN r^(m-1), tangential ~ -C mu B kT cos(phi) r^(m-1)
        dp = np.where(gross, np.where(mu * kT < kN, -math.inf, np.nan), dp)
    return dp


@quiet
def surface_dpdz(x, y, a, c, nu, mu, profile, *, method="closed", rtol=1e-10, width=None):
    """d p_h / dz at z = 0+ (z into the material), divided by E* (units 1/length).

    Normal part eq. (11) (stable forms docs/theory/axisymmetric.md (A26), (A85)-(A86): the by-parts
    form near the edge, the direct outside integral far from it; closed eq. 5, 37; flat punch regular
    part of eq. 6 times its depth) plus tangential part eq. (26) in the form (A87)-(A88) (closed 21,
    41; flat punch regular part of eq. 22).  Willert, Forsbach & Popov (see ``surface_stress`` for the
    arguments, ``width`` included).

    Infinite on r = c (stick side, +inf sgn x) and r = a (contact side, -inf sgn x) when a
    tangential load acts (0 there on x = 0), and at a conical tip r = 0 (-inf); NaN at r = 0 of a
    conical/sharp tip in gross slip when the tangential 1/r term can outweigh the normal one (mu >= 1
    for a cone).  On r = a without tangential load the inside value is returned (the outside limit
    is +inf)."""
    ords = orders(rtol)
    closed = _route(profile, method)
    shape, (x, y, a, c, nu, mu) = _prepare(x, y, a, c, nu, mu, profile)
    w = _width(width, shape)
    n = x.size
    out = np.full(n, np.nan)
    step = _CHUNK if closed is None else _CLOSED_CHUNK
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for s in range(0, n, step):
            sl = slice(s, s + step)
            xs, ys = x[sl], y[sl]
            r = np.hypot(xs, ys)
            part = np.full(xs.size, np.nan)
            main = np.flatnonzero(np.isfinite(r) & (r > 0.0))
            if main.size:
                part[main] = _dpdz_main(profile, closed, ords, xs[main], r[main], a[sl][main], c[sl][main],
                                        nu[sl][main], mu[sl][main], w[sl][main])
            zero = np.flatnonzero(r == 0.0)
            if zero.size:
                part[zero] = _dpdz_origin(profile, closed, ords, a[sl][zero], c[sl][zero], nu[sl][zero],
                                          mu[sl][zero])
            out[sl] = part
    return out.reshape(shape)


# -- load relations -------------------------------------------------------------------------------

def stick_radius(a, nu, mu, ux0_over_delta, profile):
    """Stick radius c of the Cattaneo–Mindlin problem, eq. (38) with gross slip eq. (42):
    G* u_x0 = mu E* [g(a) - g(c)], G*/E* = 2(1-nu)/(2-nu).  Returns c (length units, the shape of
    the broadcast arguments): c = a when ux0_over_delta == 0 (no tangential load); c = 0 at and
    beyond the onset of gross slip (including mu == 0 with u_x0 > 0).  For a flat punch g(a) - g(c)
    is the whole depth for every c < a: c = a (full stick, eq. 20) below gross slip, 0 beyond."""
    a_, nu_, mu_, u_ = (np.asarray(v, dtype=float) for v in (a, nu, mu, ux0_over_delta))
    _validate(a_, np.zeros_like(a_), nu_, mu_)
    _check_range("ux0_over_delta", u_, 0.0, math.inf, "finite and >= 0")
    if not np.all(np.isfinite(u_)):
        raise ValueError("ux0_over_delta must be finite and >= 0; got inf")
    a_, nu_, mu_, u_ = np.broadcast_arrays(a_, nu_, mu_, u_)
    gstar = 2.0 * (1.0 - nu_) / (2.0 - nu_)
    with np.errstate(divide="ignore", invalid="ignore"):
        rho = np.where(u_ == 0.0, 0.0, np.where(mu_ > 0.0, gstar * u_ / mu_, math.inf))
    slipping = rho >= 1.0
    keep = np.clip(1.0 - rho, 0.0, 1.0)          # g(c) / g(a)
    closed = profile.closed
    kind = closed[0] if closed is not None else profile.kind
    if kind == "cone":
        c = a_ * keep
    elif kind == "paraboloid":
        c = a_ * np.sqrt(keep)
    elif kind == "power_law":
        c = a_ * keep ** (1.0 / profile.n)
    elif kind == "flat_punch":
        c = np.where(slipping, 0.0, a_)
    else:
        c = np.asarray(profile.contact_radius(profile.depth(a_) * keep), dtype=float)
    c = np.where(u_ == 0.0, a_, np.where(slipping, 0.0, np.clip(c, 0.0, a_)))
    return c


def mean_pressure(a, profile):
    """Mean contact pressure p_m / E* = F_N / (pi a^2 E*), with F_N from eq. (10)."""
    a_ = np.asarray(a, dtype=float)
    _check_range("a (contact radius)", a_, np.nextafter(0.0, 1.0), math.inf, "positive and finite (a > 0)")
    return np.asarray(profile.normal_force(a_), dtype=float) / (math.pi * a_ * a_)


def min_pressure(profile, a) -> tuple[float, float]:
    """The smallest contact pressure p(r) / p_m on 0 <= r < a and where it lies, for a scalar
    contact radius a: a negative value means the profile needs tensile (adhesive) traction to be
    in contact up to r = a, outside the model (docs/theory/axisymmetric.md (A98)).

    p = -sigma_zz (A14) by the quadrature route (rtol 1e-10) on 1025 equal steps, 16 points per
    table piece (a tabulated profile's pressure bends at its knots) and points next to the edge,
    where p ~ g'(a) sqrt(2 (a - r)/a) / pi takes the sign of g'(a) (down to a - r = 1e-12 a).
    A tabulated profile's answer is kept in the set-up cache under its content and a (the recipe
    check asks it on every call)."""
    a = float(a)
    key = getattr(profile, "_key", None)
    if key is not None:
        from ..setup_cache import SETUP

        return SETUP.get(("min pressure", a) + key, lambda: _min_pressure(profile, a))
    return _min_pressure(profile, a)


def _min_pressure(profile, a: float) -> tuple[float, float]:
    grid = [np.linspace(0.0, a, 1025), a * (1.0 - np.logspace(-12, -3, 10))]
    knots = np.asarray(getattr(profile, "_knots", ()), dtype=float)
    inner = knots[(knots > 0.0) & (knots < a)]
    if inner.size:
        grid.append((inner[:, None] + np.outer(np.diff(np.append(inner, a)), np.linspace(0, 1, 16))).ravel())
    r = np.unique(np.concatenate(grid))
    r = r[r < a]
    method = resolve(profile, "auto", 1e-10).kernel       # what auto means: the route table's
    p = -surface_stress(r, 0.0, a, a, 0.3, 0.0, profile, components=("zz",), method=method)["zz"]
    p = p / mean_pressure(a, profile)
    i = int(np.argmin(p))
    return float(p[i]), float(r[i])
