"""The tangential (Cattaneo–Mindlin) part of the stress tensor below the surface (z >= 0) of a
half-space indented by a rigid axisymmetric profile: the entry point ``interior_stress_tangential``.

The surface traction is the one of the surface kernels (docs/theory/axisymmetric.md (A34)):
along +x on the half-space, sigma_xz(z = 0) = -q with q = mu [p(r; a) - p(r; c)], c the stick
radius (c = 0 gross slip, c = a no tangential load).  The full field is the normal part
(``interior.interior_stress``) plus the part returned here.

Routes (docs/theory/interior.md (I18)-(I23), (I30)-(I33)):

* ``closed``: the paraboloid, mu p0 [T(x/a) - (c/a) T(x/c)] with T the Hertz sliding field per q0
  (Hamilton & Goodman 1966; Hamilton 1983; Cattaneo 1938; Mindlin 1949), ``sliding_unit``, (I23);
  the flat punch, mu (delta/a) K_T(x/a) with K_T the sliding punch ``sliding_punch_unit`` (I33)
  (for every c < a: a flat punch slides or sticks as a whole).  Accuracy: closed form, relative
  error at most 1e-12 of |value| everywhere the value is finite, far field and next to edges
  included.
* ``quadrature``: every profile as mu int_c^a K_T(x; rho) g'(rho) d rho, the superposition of
  sliding punches (I33) integrated over [c, a] directly (I45) on the panels of the normal route
  with their node counts (``interior.superpose_flat``, (I16)-(I17), (I54)), summed as radial
  functions (I55).  Accuracy: |error| <= rtol * max(|value|, mu p_m) with
  p_m the mean contact pressure (measured in docs/theory/interior.md section 5).  On the surface
  z = 0 the tangential part of the surface kernels (docs/theory/axisymmetric.md (A34)-(A41)),
  the limit z -> 0+, with their flags.

``interior_dpdz_tangential`` gives the tangential part of d p_h/dz by the same routes, from the
trace of the Cerruti superposition, (I34)-(I35).

Units as ``interior_stress``: lengths in the profile's unit, stresses divided by E*.  Components
"xx", "yy", "zz", "xy", "xz", "yz"; tension positive, z into the body.  Pure NumPy.
"""
from __future__ import annotations

import math

import numpy as np
from ..flags import quiet

from .hertz_geometry import geometry
from .interior import dpdz_integrator
from .interior_hertz import COMPONENTS, mns, sliding_punch_scalars, sliding_punch_unit, sliding_unit
from .displacement import thin_annulus
from .profiles import Profile, load_exponent
from .superposition import (Flat, Nodes, check_arguments, direction, flat_arguments, live_nodes, superpose,
                            superpose_flat)
from .surface import surface_dpdz, surface_stress

__all__ = ["COMPONENTS", "interior_stress_tangential", "interior_dpdz_tangential", "sliding_dpdz_unit",
           "sliding_punch_dpdz_unit"]

METHODS = ("auto", "closed", "quadrature")


@quiet
def interior_stress_tangential(x, y, z, a, c, nu, mu, profile: Profile, *, method: str = "auto",
                               rtol: float = 1e-10, width=None) -> dict[str, np.ndarray]:
    """Tangential part of the stress tensor / E* at (x, y, z), z >= 0 the depth, for the contact
    radius ``a``, stick radius ``c`` (0 <= c <= a; c = 0 gross slip) and coefficient of friction
    ``mu`` >= 0 (Cattaneo–Mindlin, traction along +x on the half-space); docs/theory/interior.md
    (I23), (I33).  x, y, z, a, c, nu, mu broadcast; returns {"xx", "yy", "zz", "xy", "xz", "yz": ndarray}.

    ``method``: "auto" (the closed form for the paraboloid, the power law n = 2 and the flat punch,
    else the 1-D superposition), "closed" (refused for cone, power law n != 2 and tabulated
    profiles) or "quadrature" (the 1-D superposition of sliding punches for every profile; the flat
    punch always uses its closed form).  Closed forms: relative error at most 1e-12 of |value|
    everywhere the value is finite; 1-D route: |error| <= rtol * max(|value|, mu p_m).

    Singular points: the flat punch's edge ring (r = a, z = 0), where sigma_xz = -inf and the other
    components follow (I32) (+-inf, 0 by symmetry, or NaN where the limit depends on the direction);
    on the surface z = 0 of the 1-D route the values and flags of the surface kernels (e.g. NaN for
    the in-plane components at a conical tip in gross slip).  Elsewhere finite and continuous.

    ``width``: the slip annulus' width a - c where it is known more accurately than the difference
    of the rounded radii (``profiles.annulus_width``); None: a - c.  With it the power-law profiles
    (cone, paraboloid, power law) below a slip ratio 1 - (c/a)^n of ``_THIN`` (1e-3) are, at z > 0,
    the superposition of sliding punches over the annulus of width w (``_thin_annulus``), which
    keeps its relative accuracy as c -> a, where the paraboloid's difference of two Hertz fields
    and the 1-D route's range a - c of the rounded c keep 1e-16/(1 - (c/a)^n) of it."""
    shape, (x, y, z, a, c, nu, mu, w) = flat_arguments("tangential interior", method, x, y, z, a, c, nu, mu,
                                                       a - c if width is None else width)
    if not (math.isfinite(float(rtol)) and float(rtol) > 0.0):
        raise ValueError(f"rtol must be a positive finite number, got {rtol!r}")
    check_arguments(z, a, nu, profile, c=c, mu=mu)
    family = _family(profile, method)
    if family == "paraboloid":
        out = _paraboloid(x, y, z, a, c, nu, mu, float(profile.closed[1]))
    elif family == "flat_punch":
        k = np.where(c < a, mu * profile.depth_ / a, 0.0)
        out = {key: k * v for key, v in sliding_punch_unit(x / a, y / a, z / a, nu).items()}
    else:
        out = _superposition(x, y, z, a, c, nu, mu, profile, rtol)
    if family != "flat_punch" and width is not None:
        _thin_annulus(out, x, y, z, a, c, w, nu, mu, profile, sliding_punch_unit, 0)
    return {key: out[key].reshape(shape) for key in COMPONENTS}


def _family(profile, method):
    """"paraboloid", "flat_punch" or None (the 1-D route)."""
    closed = profile.closed
    family = closed[0] if closed is not None and closed[0] in ("paraboloid", "flat_punch") else None
    if profile.kind == "flat_punch":
        return "flat_punch"              # g' is a Dirac delta at a: the kernel itself
    if method == "closed" and family is None:
        raise ValueError(f"method='closed': no tangential interior closed form for the {profile.kind} profile "
                         f"{profile!r}; use method='quadrature'")
    return family if method in ("auto", "closed") else None


def _paraboloid(x, y, z, a, c, nu, mu, R):
    k = mu * 2.0 * a / (math.pi * R)                     # mu p0 per E*, (I1)
    slide = sliding_unit(x / a, y / a, z / a, nu)
    out = {key: k * v for key, v in slide.items()}
    part = np.flatnonzero(c > 0.0)
    if part.size:
        cp = c[part]
        stick = sliding_unit(x[part] / cp, y[part] / cp, z[part] / cp, nu[part])
        for key in COMPONENTS:
            out[key][part] -= k[part] * (cp / a[part]) * stick[key]
    return out


#: below this slip ratio rho = 1 - (c/a)^n the superposition over the thin annulus replaces the
#: difference of the paraboloid's two Hertz fields and the 1-D route over [c, a]: the difference
#: loses 1e-16 |T|/|value| ~ 1e-16/rho times the ratio of one Hertz term to the value (up to ~100
#: in the stick zone), the 1-D route's range a - c of the rounded c 1e-16/rho of the annulus' part,
#: so 1e-3 keeps both within 1e-12 of the largest component
_THIN = 1e-3


def _thin_annulus(out, x, y, z, a, c, w, nu, mu, profile, unit, shift):
    """Replace in ``out`` the values at z > 0 where the slip annulus of a power-law profile is thin
    (rho = 1 - (c/a)^n < ``_THIN``) by the superposition of sliding punches over it, (I45) with
    g'(t) = g'(a) (t/a)^(n-1):  mu g'(a) a^(1-n) int_c^a t^(n-2+shift) unit(p/t) dt
    (docs/theory/interior.md (I59)): the stresses with ``sliding_punch_unit`` and shift 0, dp/dz
    with ``sliding_punch_dpdz_unit`` and shift -1.  The width w comes from the slip ratio
    (``profiles.annulus_width``), so the result keeps its relative accuracy as c -> a."""
    n = load_exponent(profile)
    if n is None:
        return out
    with np.errstate(invalid="ignore", divide="ignore"):
        rho = -np.expm1(n * np.log1p(-w / a))
    i = np.flatnonzero((c > 0.0) & (z > 0.0) & (rho < _THIN))
    if not i.size:
        return out
    part = thin_annulus(x[i], y[i], z[i], a[i], c[i], w[i], nu[i], unit, n - 2.0 + shift)
    k = mu[i] * profile.dg(a[i]) / a[i] ** (n - 1.0)
    for key, v in part.items():
        out[key][i] = k * v
    return out


# -- the 1-D superposition of sliding punches (I33) ---------------------------------------------

def _integrate_sliding(nd: Nodes, profile) -> dict[str, np.ndarray]:
    """sum_j w_j g'(rho_j) K_T(x; rho_j), K_T(x; rho) = sliding_punch_unit(x / rho) / rho (I33)."""
    live, rho, rm1 = live_nodes(nd)
    dg = np.where(live, profile.dg(rho), 0.0)
    k = sliding_punch_unit(nd.x[:, None] / rho, nd.y[:, None] / rho, nd.z[:, None] / rho, nd.nu[:, None], rm1=rm1)
    w = np.where(live, nd.weights * dg / rho, 0.0)
    return {comp: np.sum(np.where(live, v, 0.0) * w, axis=1) for comp, v in k.items()}


_SLIDING_KERNEL = (_integrate_sliding, COMPONENTS)


def _flat_sliding(f: Flat, profile):
    """(I33) on the flat rule of ``interior.superpose_flat`` (I54): the radial functions of the
    sliding punch (I30)-(I31) summed per point with the powers of 1/rho their monomials in x, y
    carry in (I21), and (I21) formed once per point (I55), with a1, a2, a3 in the far-field forms
    of (I57); None where a node is on a punch's
    edge ring (z/rho underflowed)."""
    inv = 1.0 / f.rho
    zs = f.z[f.row] * inv
    z2 = zs * zs
    S, M, N = mns(f.rm1, zs, z2)
    if not np.all(S > 0.0):
        return None
    v = sliding_punch_scalars(dict(M=M, N=N, S=S, z=zs))
    nu = f.node_nu()
    # D g = z D g_z - P - pi J (I57): formed from P, z D g_z and J, which do not cancel in the far field
    P, zdgz = v["P"], zs * v["Dgz"]
    q2, j2 = (1.0 - 2.0 * nu) * zdgz, 2.0 * math.pi * nu * v["J"]
    b = 4.0 * nu * v["D2g"] - 2.0 * v["zD2gz"]
    # x^p y^q / rho^(p+q) = ux^p uy^q (r/rho)^(p+q): bounded (rho > 1e-150 r), no 1/rho^4 overflow
    rs = f.r[f.row] * inv
    w = f.w * inv                                  # K_T = unit(x / rho) / rho
    x0 = f.sum(v["X"] * w)
    w *= rs
    a1 = f.sum((4.0 * (1.0 - 2.0 * nu) * P - 6.0 * (q2 + j2)) * w)
    a2 = f.sum(-2.0 * (q2 + j2) * w)
    a3 = f.sum((2.0 * (1.0 - 2.0 * nu) * P - 2.0 * (q2 + j2)) * w)
    cz = f.sum(v["zgzzz"] * w)
    w *= rs
    d = f.sum(v["zDgzz"] * w)
    w *= rs
    b = f.sum(b * w)
    x, y = direction(f.x, f.y, f.r)
    k = 1.0 / (4.0 * math.pi * math.pi)            # (I21)'s 1/(4 pi) and the punch's 1/pi
    return {"xx": k * x * (a1 + x * x * b), "yy": k * x * (a2 + y * y * b), "xy": k * y * (a3 + x * x * b),
            "zz": -2.0 * k * x * cz, "xz": x0 / math.pi - 2.0 * k * x * x * d, "yz": -2.0 * k * x * y * d}


_FLAT_SLIDING_KERNEL = (_flat_sliding, COMPONENTS, _integrate_sliding)


def _superposition(x, y, z, a, c, nu, mu, profile, rtol):
    out = {k: np.zeros(x.size) for k in COMPONENTS}
    act = (mu > 0.0) & (c < a)
    surf = act & (z == 0.0)
    if np.any(surf):
        s = _surface_part(x[surf], y[surf], a[surf], c[surf], nu[surf], mu[surf], profile, rtol)
        for k in COMPONENTS:
            out[k][surf] = s[k]
    inner = np.flatnonzero(act & (z > 0.0))
    if not inner.size:
        return out
    # one integral over [c, a] (I45), not Sigma_T(a) - Sigma_T(c): the difference lost
    # eps |Sigma_T(a)|, 2e-11 mu p_m for the n = 0.5 power law at z = 7.6e-10 a on the axis
    total = superpose_flat(x[inner], y[inner], z[inner], a[inner], nu[inner], profile, rtol, _FLAT_SLIDING_KERNEL,
                            lower=c[inner])
    for k in COMPONENTS:
        out[k][inner] = mu[inner] * total[k]
    return out


def _surface_part(x, y, a, c, nu, mu, profile, rtol):
    """The tangential part of the surface kernels at z = 0: sigma_xz as returned (it has no normal
    part), the in-plane components as the difference of the total and the normal part; where the
    normal part is infinite (a conical or sharper tip, r = 0) the tangential in-plane part is 0 in
    the stick zone (c > 0) and NaN in gross slip (direction-dependent, as the surface kernels)."""
    kw = dict(method="quadrature", rtol=max(rtol, 1e-14))
    total = surface_stress(x, y, a, c, nu, mu, profile, **kw)
    normal = surface_stress(x, y, a, a, nu, 0.0, profile, components=("xx", "yy", "xy"), **kw)
    out = {"xz": total["xz"], "zz": np.zeros(x.size), "yz": np.zeros(x.size)}
    for k in ("xx", "yy", "xy"):
        with np.errstate(invalid="ignore"):
            diff = total[k] - normal[k]
        out[k] = np.where(np.isfinite(normal[k]), diff, np.where(c > 0.0, 0.0, math.nan))
    return out


# -- the depth derivative of the hydrostatic pressure (I34)-(I35) -------------------------------

def sliding_dpdz_unit(x, y, z, nu, rm1=None) -> np.ndarray:
    """d p_h/dz of the Hertz sliding field, divided by q0/a, at coordinates divided by the contact
    radius: -(2/3)(1 + nu) x N/(S(1 + M^2)) (I34), one product (no cancellation).  Finite for
    z > 0 and on the surface off the edge ring.  Closed form: relative error at most 1e-12 of
    |value| where the value is finite.  ``rm1``: r - 1 without rounding (see ``geometry``)."""
    x, y, z = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (x, y, z)))
    g = geometry(x, y, z, rm1)
    M, N, S = g["M"], g["N"], g["S"]
    with np.errstate(invalid="ignore", divide="ignore"):
        return -(2.0 / 3.0) * (1.0 + np.asarray(nu, dtype=float)) * x * N / (S * (1.0 + M * M))


def sliding_punch_dpdz_unit(x, y, z, nu, rm1=None) -> np.ndarray:
    """d p_h/dz of the sliding punch (the traction (1/pi)/sqrt(1 - r^2) along +x, radius 1), at
    coordinates divided by the radius: (2(1 + nu)/(3 pi)) x N (N^2 - 3M^2)/S^3 (I35).  Finite for
    z > 0 and on the surface off the edge ring.  Closed form: relative error at most 1e-12 of
    |value| where the value is finite (where N^2 - 3M^2 passes through zero: of N^2 + 3M^2).
    ``rm1``: r - 1 without rounding (see ``geometry``)."""
    x, y, z = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (x, y, z)))
    g = geometry(x, y, z, rm1)
    M, N, S = g["M"], g["N"], g["S"]
    with np.errstate(invalid="ignore", divide="ignore"):
        return (2.0 * (1.0 + np.asarray(nu, dtype=float)) / (3.0 * math.pi)) * x * N * (N * N - 3.0 * M * M) / S ** 3


_SLIDING_DPDZ_KERNEL = (dpdz_integrator(sliding_punch_dpdz_unit, sliding_dpdz_unit), ("dpdz",))


@quiet
def interior_dpdz_tangential(x, y, z, a, c, nu, mu, profile: Profile, *, method: str = "auto",
                             rtol: float = 1e-10, width=None) -> np.ndarray:
    """Tangential part of d p_h/dz / (E*/length) at (x, y, z), z >= 0, p_h = -trace(sigma)/3;
    arguments and routes as ``interior_stress_tangential`` (docs/theory/interior.md (I34)-(I35)):
    the paraboloid mu (p0/a) [H_T(x/a) - H_T(x/c)] (H_T = ``sliding_dpdz_unit``), the flat punch
    mu (delta/a^2) ``sliding_punch_dpdz_unit``(x/a) for c < a, else the superposition (I28) of
    the sliding punches' derivatives over [c, a] directly (I45).  Closed forms:
    relative error at most 1e-12 of |value| where the value is finite; 1-D route: |error| <=
    rtol * max(|value|, mu p_m/a).  On the surface z = 0 the tangential part of the surface kernel
    (docs/theory/axisymmetric.md (A53)-(A59)), +-inf at r = c and r = a as there.  ``width`` as
    ``interior_stress_tangential``: on the surface it goes to the surface kernel, below it the thin
    annulus of a power-law profile is the superposition (``_thin_annulus``)."""
    shape, (x, y, z, a, c, nu, mu, w) = flat_arguments("tangential interior", method, x, y, z, a, c, nu, mu,
                                                       a - c if width is None else width)
    if not (math.isfinite(float(rtol)) and float(rtol) > 0.0):
        raise ValueError(f"rtol must be a positive finite number, got {rtol!r}")
    check_arguments(z, a, nu, profile, c=c, mu=mu)
    family = _family(profile, method)
    out = np.zeros(x.size)
    act = (mu > 0.0) & (c < a)
    surf = np.flatnonzero(act & (z == 0.0))
    if surf.size:
        kw = dict(method="closed" if family else "quadrature", rtol=max(rtol, 1e-14))
        X, Y, A, C, NU, MU = (v[surf] for v in (x, y, a, c, nu, mu))
        with np.errstate(invalid="ignore"):
            out[surf] = (surface_dpdz(X, Y, A, C, NU, MU, profile, width=w[surf], **kw)
                         - surface_dpdz(X, Y, A, A, NU, 0.0, profile, **kw))
    i = np.flatnonzero(act & (z > 0.0))
    if i.size:
        out[i] = _dpdz_below(x[i], y[i], z[i], a[i], c[i], nu[i], mu[i], profile, family, rtol)
        if family != "flat_punch" and width is not None:
            below = {"dpdz": out[i]}
            _thin_annulus(below, x[i], y[i], z[i], a[i], c[i], w[i], nu[i], mu[i], profile,
                          lambda *p, rm1=None: {"dpdz": sliding_punch_dpdz_unit(*p, rm1=rm1)}, -1)
            out[i] = below["dpdz"]
    return out.reshape(shape)


def _dpdz_below(x, y, z, a, c, nu, mu, profile, family, rtol):
    if family == "paraboloid":
        k = mu * 2.0 / (math.pi * float(profile.closed[1]))          # mu p0 / a per E*, (I1)
        v = sliding_dpdz_unit(x / a, y / a, z / a, nu)
        part = c > 0.0
        cs = np.where(part, c, 1.0)
        v = v - np.where(part, sliding_dpdz_unit(x / cs, y / cs, z / cs, nu), 0.0)
        return k * v
    if family == "flat_punch":
        return mu * profile.depth_ / (a * a) * sliding_punch_dpdz_unit(x / a, y / a, z / a, nu)
    return mu * superpose(x, y, z, a, nu, profile, rtol, _SLIDING_DPDZ_KERNEL, lower=c)["dpdz"]
