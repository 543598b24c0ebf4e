"""The stress tensor below the surface (z >= 0) of a half-space indented by a rigid axisymmetric
profile under normal load (frictionless): the entry point ``interior_stress``.

Routes (docs/theory/interior.md):

* ``closed``: the paraboloid (Hertz; Huber 1904, Hamilton 1983; (I5)-(I9)), the flat punch
  (Sneddon 1946; the a-derivative of the Hertz field, (I10)-(I14)) and the cone (Sneddon 1948;
  the superposition (I15) integrated in closed form, (I46)-(I52), ``interior_cone``).  Accuracy: closed forms,
  relative error at most 1e-12 of |value| everywhere the value is finite, far field and next to
  edges included.
* ``quadrature``: every profile (cone, paraboloid, power law, tabulated) as the one-dimensional
  superposition of flat punches sigma(x) = int_0^a K_FP(x; rho) g'(rho) d rho, (I15), with
  K_FP(x; rho) the punch of radius rho and unit depth; vectorised Gauss rules on panels that
  grow geometrically away from rho = min(r, a), where the integrand has a layer of width about z,
  (I16)-(I17), each with a node count from its distance to the integrand's singularities (I54),
  the punch summed as its four radial functions (I53); the panels, rules and blocks are the
  family's superposition engine (``superposition``), this module the integrands.  Accuracy:
  |error| <= rtol * max(|value|, p_m) with p_m the mean contact pressure.  On the surface z = 0
  the surface kernels of the family are used (``surface.surface_stress``,
  docs/theory/axisymmetric.md (A14)-(A22)), which are the limits z -> 0+ of the interior field.

``interior_dpdz`` gives the depth derivative of the hydrostatic pressure p_h = -trace(sigma)/3 by
the same routes: the trace of the Hertz and punch fields in closed form, (I24)-(I27), and its
z-derivative superposed as in (I15), (I28).

Units as the surface kernels: lengths in the profile's unit, stresses divided by E*, dp_h/dz by
E*/length.  Components "xx", "yy", "zz", "xy", "xz", "yz"; tension positive, z into the body.
Pure NumPy/SciPy.
"""
from __future__ import annotations

import math

import numpy as np

from ..flags import quiet
from .hertz_geometry import geometry, one_minus_m_atan
from .interior_cone import cone_dpdz_unit, cone_unit
from .interior_hertz import COMPONENTS, hertz_unit, punch_radial, punch_unit
from .profiles import Profile
from .superposition import (Flat, Nodes, check_arguments, direction, flat_arguments, live_nodes, radial_cartesian,
                            superpose, superpose_flat)
from .surface import surface_dpdz, surface_stress

__all__ = ["COMPONENTS", "interior_stress", "interior_dpdz", "hertz_dpdz_unit",
           "punch_dpdz_unit"]

@quiet
def interior_stress(x, y, z, a, nu, profile: Profile, *, method: str = "auto",
                    rtol: float = 1e-10) -> dict[str, np.ndarray]:
    """Stress tensor / E* at (x, y, z), z >= 0 the depth, under a rigid axisymmetric ``profile``
    pressed to the contact radius ``a`` (normal load, no friction); docs/theory/interior.md.

    ``method``: "auto" (closed form for the paraboloid, the cone, the power laws n = 1, 2 and the
    flat punch, else the quadrature), "closed" (refused where no interior closed form exists: power
    law n != 1, 2, tabulated) or "quadrature" (the 1-D superposition (I15), also for the paraboloid; the
    flat punch always uses its closed form).  x, y, z, a, nu broadcast; returns
    {"xx", "yy", "zz", "xy", "xz", "yz": ndarray}.

    Singular points: the flat punch's edge ring (r = a, z = 0): -inf normal stresses, NaN shears
    (direction-dependent sign); on the surface z = 0 the values and flags of the surface kernels
    (e.g. -inf at a conical tip)."""
    shape, (x, y, z, a, nu) = flat_arguments("interior", method, x, y, z, a, nu)
    check_arguments(z, a, nu, profile)
    family = _closed_family(profile, method)
    if family == "paraboloid":
        p0 = 2.0 * a / (math.pi * profile.closed[1])
        out = {k: v * p0 for k, v in hertz_unit(x / a, y / a, z / a, nu).items()}
    elif family == "flat_punch":
        out = {k: v * (profile.depth_ / a) for k, v in punch_unit(x / a, y / a, z / a, nu).items()}
    elif family == "cone":
        out = _cone(x, y, z, a, nu, profile)
    else:
        out = _superposition(x, y, z, a, nu, profile, rtol)
    return {k: out[k].reshape(shape) for k in COMPONENTS}


def _cone(x, y, z, a, nu, profile):
    """(I46)-(I51) below the surface; at z = 0 the surface kernels' closed forms (their -inf at the tip)."""
    out = {k: np.empty(x.size) for k in COMPONENTS}
    surf = z == 0.0
    if np.any(surf):
        s = surface_stress(x[surf], y[surf], a[surf], a[surf], nu[surf], 0.0, profile, method="closed")
        for k in COMPONENTS:
            out[k][surf] = s[k]
    i = np.flatnonzero(~surf)
    k_cone = 0.5 * float(profile.closed[1])              # E* tan(theta)/2 per E*
    for k, v in cone_unit(x[i] / a[i], y[i] / a[i], z[i] / a[i], nu[i]).items():
        out[k][i] = k_cone * v
    return out


def _closed_family(profile, method):
    """"paraboloid", "cone", "flat_punch" or None (quadrature)."""
    closed = profile.closed
    family = closed[0] if closed is not None and closed[0] in ("paraboloid", "cone", "flat_punch") else None
    if profile.kind == "flat_punch":
        return "flat_punch"              # g' is a Dirac delta: the kernel itself
    if method == "closed" and family is None:
        raise ValueError(f"method='closed': no interior closed form for the {profile.kind} profile {profile!r}; "
                         "use method='quadrature'")
    return family if method in ("auto", "closed") else None


# -- the 1-D superposition (I15) ----------------------------------------------------------------

def _superposition(x, y, z, a, nu, profile, rtol):
    out = {k: np.empty(x.size) for k in COMPONENTS}
    surf = z == 0.0
    if np.any(surf):
        s = surface_stress(x[surf], y[surf], a[surf], a[surf], nu[surf], 0.0, profile, method="quadrature",
                           rtol=max(rtol, 1e-14))
        for k in COMPONENTS:
            out[k][surf] = s[k]
    inner = np.flatnonzero(~surf)
    part = superpose_flat(x[inner], y[inner], z[inner], a[inner], nu[inner], profile, rtol, _FLAT_STRESS_KERNEL)
    for k in COMPONENTS:
        out[k][inner] = part[k]
    return out


def _flat_stress(f: Flat, profile):
    """(I15) on the flat rule, summed as the four radial functions of ``punch_radial`` (I53) times
    the powers of r/rho of (I8) (bounded: rho > 1e-150 r; not 1/rho^3, which overflows next to a
    tip at r, z ~ 1e-300 a); None where a node is on a punch's edge ring (z/rho underflowed)."""
    inv = 1.0 / f.rho
    rs = f.r[f.row] * inv
    sigma, zz, e, t = punch_radial(rs, f.z[f.row] * inv, f.rm1, f.node_nu())
    if not np.all(np.isfinite(sigma)):
        return None
    w = f.w * inv                                  # K = punch(x / rho) / rho
    s_sum, zz_sum = f.sum(sigma * w), f.sum(zz * w)
    w *= rs
    t_sum = f.sum(t * w)
    w *= rs
    e_sum = f.sum(e * w)
    ux, uy = direction(f.x, f.y, f.r)
    return radial_cartesian(ux, uy, s_sum, zz_sum, e_sum, t_sum)


def _integrate_stress_direct(nd: Nodes, profile) -> dict[str, np.ndarray]:
    """(I15) with the Cartesian punch ``punch_unit`` at every node (its edge-ring values)."""
    live, rho, rm1 = live_nodes(nd)
    dg = np.where(live, profile.dg(rho), 0.0)
    k = punch_unit(nd.x[:, None] / rho, nd.y[:, None] / rho, nd.z[:, None] / rho, nd.nu[:, None], rm1=rm1)
    w = np.where(live, nd.weights * dg / rho, 0.0)
    return {c: np.sum(np.where(live, v, 0.0) * w, axis=1) for c, v in k.items()}


# -- the depth derivative of the hydrostatic pressure (I24)-(I28) ------------------------------

@quiet
def interior_dpdz(x, y, z, a, nu, profile: Profile, *, method: str = "auto", rtol: float = 1e-10) -> np.ndarray:
    """d p_h/dz / (E*/length) at (x, y, z), z >= 0, p_h = -trace(sigma)/3, under the rigid
    axisymmetric ``profile`` pressed to the contact radius ``a`` (normal load, no friction);
    docs/theory/interior.md (I24)-(I28).

    Routes and accuracy as ``interior_stress``: closed forms (I26)-(I27) for the paraboloid (and
    the power law n = 2) and the flat punch, (I52) for the cone (and the power law n = 1), relative
    error at most 1e-12 of |value| everywhere the value is finite (where the value passes through
    zero: of the largest term of its sum); else the 1-D superposition (I28) of the punch
    derivative, |error| <= rtol * max(|value|, p_m/a).  On the surface z = 0 the surface kernel
    (docs/theory/axisymmetric.md (A24)-(A27)), the limit z -> 0+, with its +-inf at the contact
    edge and at a conical tip."""
    shape, (x, y, z, a, nu) = flat_arguments("interior", method, x, y, z, a, nu)
    check_arguments(z, a, nu, profile)
    family = _closed_family(profile, method)
    out = np.empty(x.size)
    surf = z == 0.0
    if np.any(surf):
        kernel = "closed" if family is not None else "quadrature"
        out[surf] = surface_dpdz(x[surf], y[surf], a[surf], a[surf], nu[surf], 0.0, profile, method=kernel,
                                 rtol=max(rtol, 1e-14))
    i = np.flatnonzero(~surf)
    X, Y, Z, A, NU = x[i], y[i], z[i], a[i], nu[i]
    if family == "paraboloid":
        out[i] = hertz_dpdz_unit(X / A, Y / A, Z / A, NU) * (2.0 / (math.pi * profile.closed[1]))
    elif family == "flat_punch":
        out[i] = punch_dpdz_unit(X / A, Y / A, Z / A, NU) * (profile.depth_ / (A * A))
    elif family == "cone":
        out[i] = cone_dpdz_unit(X / A, Y / A, Z / A, NU) * (0.5 * float(profile.closed[1]) / A)
    else:
        out[i] = superpose(X, Y, Z, A, NU, profile, rtol, _DPDZ_KERNEL)["dpdz"]
    return out.reshape(shape)


def _f_prime(M):
    """F'(M) for F(M) = 1 - M arctan(1/M) (I4), (I25): -arctan(1/M) + M/(1 + M^2) for M <= 1 (no
    cancellation: arctan(1/M) >= pi/4 > M/(1+M^2) - 1/4); for M > 1 the two terms approach 1/M and
    cancel to -2/(3 M^3), so (F (1 + M^2) - 1)/(M (1 + M^2)), whose numerator tends to -2/3."""
    F = one_minus_m_atan(M)
    opm = 1.0 + M * M
    with np.errstate(invalid="ignore", divide="ignore"):
        far = (F * opm - 1.0) / np.where(M > 1.0, M * opm, 1.0)
    near = -(0.5 * math.pi - np.arctan(np.minimum(M, 1.0))) + M / opm
    return np.where(M <= 1.0, near, far), F


@quiet
def hertz_dpdz_unit(x, y, z, nu, rm1=None) -> np.ndarray:
    """d p_h/dz of the Hertz field, divided by p0/a, at coordinates divided by the contact radius:
    p_h = (2/3)(1 + nu) N F(M) (I24) and its z-derivative (I25)-(I26).  Finite for z > 0 and on
    the surface off the edge ring.  Closed form: relative error at most 1e-12 of |value| where
    the value is finite (where it passes through zero: of the larger of the two terms).  ``rm1``:
    r - 1 without rounding, optional (see ``geometry``)."""
    nu = np.asarray(nu, dtype=float)
    g = geometry(*np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (x, y, z))), rm1)
    M, N, S, Q = g["M"], g["N"], g["S"], g["Q"]
    fp, F = _f_prime(M)
    with np.errstate(invalid="ignore", divide="ignore"):
        n_z = M * Q / S                       # (I25): no M - N z cancellation
        m_z = N * (1.0 + M * M) / S
    return (2.0 / 3.0) * (1.0 + nu) * (n_z * F + N * fp * m_z)


@quiet
def punch_dpdz_unit(x, y, z, nu, rm1=None) -> np.ndarray:
    """d p_h/dz of the flat punch of radius 1 pressed to depth 1 into a half-space with E* = 1, at
    coordinates divided by the punch radius: p_h = 2(1 + nu) N/(3 pi S) (I24) and (I27).  Finite
    for z > 0 and on the surface off the edge ring (NaN there: S = 0).  Closed form: relative
    error at most 1e-12 of |value| where the value is finite (where it passes through zero: of
    the largest term of the bracket).  ``rm1``: r - 1 without rounding (see ``geometry``)."""
    nu = np.asarray(nu, dtype=float)
    g = geometry(*np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (x, y, z))), rm1)
    M, N, S = g["M"], g["N"], g["S"]
    m2, n2 = M * M, N * N
    with np.errstate(invalid="ignore", divide="ignore"):
        return 2.0 * (1.0 + nu) / (3.0 * math.pi) * M / S ** 3 * (m2 - 3.0 * n2 * (1.0 + m2) + n2 * n2)


def dpdz_integrator(punch, hertz):
    """The sum (I28) over the nodes of a group of points for a punch derivative ``punch`` and the
    matching ``hertz`` (K_d(x; rho) = (1/(pi rho)) d/drho hertz(x/rho), both (x, y, z, nu, rm1=None)
    at coordinates divided by the radius): the normal load's (I27), (I26) and the sliding ones
    (I35), (I34)."""
    return lambda nd, profile: _integrate_dpdz(nd, profile, punch, hertz)


def _integrate_dpdz(nd: Nodes, profile, punch=punch_dpdz_unit, hertz=hertz_dpdz_unit) -> dict[str, np.ndarray]:
    """(I28).  Where the layer lies well inside the contact (d < rho_s/2, d = |(r, z) - (rho_s, 0)|)
    the punch derivative K_d = (1/(pi rho)) d/drho H_d(x/rho) (H_d = ``hertz_dpdz_unit``) is
    integrated by parts against the constant c = g'(rho_s) on [b1, a]: the integrand becomes
    (g' - c) K_d + c H_d(x/rho)/(pi rho^2), plus the end values c (H_d(x/a)/a - H_d(x/b1)/b1)/pi.
    Why: K_d ~ d^(-3/2) next to the layer, and the value is what is left of parts of size
    d^(-1/2); at z = 1e-10 a the rule of rtol = 1e-8 left 1e-7 p_m/a, by parts 5e-13 (paraboloid
    against (I26) at r/a = 0.3, 0.65, 0.99)."""
    live, rho, rm1 = live_nodes(nd)
    x, y, z, nu = nd.x[:, None], nd.y[:, None], nd.z[:, None], nd.nu[:, None]
    d = np.hypot(nd.r_minus_rho_s, nd.z)
    layer = 2.0 * d < nd.rho_s          # else the parts are no larger than the value: nothing to gain
    c = np.where(layer, profile.dg(np.where(layer, nd.rho_s, 1.0)), 0.0)[:, None]
    after = np.arange(rho.shape[1])[None, :] >= nd.first              # the panels [b1, a]
    c_after = np.where(after, c, 0.0)
    dg = np.where(live, profile.dg(rho), 0.0)
    kd = punch(x / rho, y / rho, z / rho, nu, rm1=rm1) / (rho * rho)
    hd = np.where(after & live, hertz(x / rho, y / rho, z / rho, nu, rm1=rm1), 0.0) / (rho * rho)
    f = np.where(live, (dg - c_after) * kd + c_after * hd / math.pi, 0.0)
    inner = np.sum(f * nd.weights, axis=1)
    b1, a = nd.b1, nd.a
    ends = (hertz(nd.x / a, nd.y / a, nd.z / a, nd.nu, rm1=(np.hypot(nd.x, nd.y) - a) / a) / a
            - hertz(nd.x / b1, nd.y / b1, nd.z / b1, nd.nu) / np.where(b1 > 0.0, b1, 1.0))
    return {"dpdz": inner + np.where(c[:, 0] != 0.0, c[:, 0] * ends / math.pi, 0.0)}


#: (the integral of a group of points, its names) of (I15) for the stress tensor and of (I28) for dp_h/dz
_STRESS_KERNEL = (_integrate_stress_direct, COMPONENTS)
_FLAT_STRESS_KERNEL = (_flat_stress, COMPONENTS, _integrate_stress_direct)
_DPDZ_KERNEL = (_integrate_dpdz, ("dpdz",))
