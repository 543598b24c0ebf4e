"""The displacement field (u_x, u_y, u_z) of the half-space, on the surface and below it (z >= 0),
under a rigid axisymmetric indenter with normal load and Cattaneo–Mindlin tangential load, divided
by the indentation depth delta: the entry point ``displacements``.

Conventions as the stress kernels (``interior``, ``interior_tangential``): x along the tangential
load, z the depth into the body, u_z positive into the body (at the surface inside the contact
u_z = delta - f(r)); the tangential traction q = mu [p(r; a) - p(r; c)] acts along +x on the
half-space, so that in the stick zone its displacement is the rigid-body displacement u_x0.

Routes (docs/theory/interior.md (I36)-(I44)):

* ``closed``: the flat punch, normal (I37) and tangential (I38)-(I39) (a punch slides or sticks
  whole), and the paraboloid, normal and Cattaneo–Mindlin (I40)-(I41).  Accuracy: closed forms,
  relative error at most 1e-12 of |value| everywhere the value is finite, far field and next to
  edges included (where a component passes through zero: of the largest of its terms).
* ``quadrature``: every other profile (and the paraboloid with method="quadrature") as the
  superposition of punches (I42) and of sliding punches (I43), on the panels of the stresses'
  1-D route (``interior.superpose``); on the surface inside the range of integration the panel
  rule (I44).  Accuracy: |error| <= rtol * max(|value|, delta) (the displacement scale is delta).

The displacement is the unique one that vanishes at infinity; every value is finite, the edge
rings included.  Pure NumPy.
"""
from __future__ import annotations

import math

import numpy as np
from ..flags import quiet

from ..quadrature import gauss_jacobi, gauss_legendre, group_by
from .hertz_geometry import geometry, one_minus_m_atan, x_minus_sin
from .interior_hertz import sliding_scalars
from .profiles import Profile
from .routes import has_displacement_closed_form  # noqa: F401 (the route table decides; re-exported)
from .superposition import Nodes, check_arguments, flat_arguments, interior_orders, live_nodes, superpose

__all__ = ["NAMES", "displacements", "tangential_displacements", "has_displacement_closed_form",
           "punch_displacement_unit", "sliding_punch_displacement_unit",
           "hertz_displacement_unit", "hertz_sliding_displacement_unit"]

NAMES = ("u_x", "u_y", "u_z")
_KEYS = ("x", "y", "z")
#: points per block of the surface rule (its (points x nodes) work arrays stay small)
_CHUNK = 2048
#: depths below this (times the radius of integration) take the surface rule (I44), see ``_sum``
_SURFACE_DEPTH = 1e-290


def _over_s(S, M, N):
    """M/S and N/S (each <= S^(-1/2)), set to 0 on the edge ring (S = 0), where they only appear
    with factors that vanish.  Not 1/S: at a subnormal depth next to the edge ring (z = 5e-324 a)
    1/S overflows and the bounded products M^2/S, M N/S became inf."""
    with np.errstate(invalid="ignore", divide="ignore"):
        safe = np.where(S > 0.0, S, 1.0)
        return np.where(S > 0.0, M / safe, 0.0), np.where(S > 0.0, N / safe, 0.0)


def _unit_coords(x, y, z, rm1):
    # float64, or np.longdouble if given (the tests' extended-precision reference)
    x, y, z = np.broadcast_arrays(*(np.asarray(v) + np.zeros((), np.result_type(v, np.float64)) for v in (x, y, z)))
    return x, y, geometry(x, y, z, rm1)


def punch_displacement_unit(x, y, z, nu, rm1=None) -> dict[str, np.ndarray]:
    """Displacement of the half-space under a rigid flat punch of radius 1 pressed to depth 1, at
    coordinates divided by the radius: docs/theory/interior.md (I37) (Boussinesq potentials of
    the pressure 1/(pi sqrt(1 - r^2)) per E*), u_z = 1 under the punch.  No division by r; finite
    and continuous everywhere, the edge ring included.  Closed form: relative error at most 1e-12
    of |value| everywhere.  ``rm1``: r - 1 without rounding (see ``interior_hertz.geometry``)."""
    x, y, g = _unit_coords(x, y, z, rm1)
    nu = np.asarray(nu, dtype=x.dtype)
    M, N = g["M"], g["N"]
    m_s, n_s = _over_s(g["S"], M, N)
    opm = 1.0 + M * M
    ur_r = (M * m_s * N - (1.0 - 2.0 * nu) / (1.0 + N)) / (math.pi * (1.0 - nu) * opm)
    uz = (2.0 / math.pi) * (np.arctan2(1.0, M) + M * (N * n_s) / (2.0 * (1.0 - nu)))
    return {"x": x * ur_r, "y": y * ur_r, "z": uz}


def _sliding_punch_radial(g):
    """The radial functions of (I18) for the traction 1/sqrt(1 - r^2) along +x (a = 1):
    (I38): Phi, g_z, D Psi and the products z D g_z, D g, z P, each bounded (every 1/S comes with
    M N, M^2 or N^2)."""
    M, N = g["M"], g["N"]
    m_s, n_s = _over_s(g["S"], M, N)
    m2, opm, opn = M * M, 1.0 + M * M, 1.0 + N
    atan = np.arctan2(1.0, M)
    zdgz = 2.0 * math.pi * (M * n_s) * (N - m2 * (2.0 + N)) / (opm * opn) ** 2
    return dict(
        Phi=2.0 * math.pi * atan,
        gz=2.0 * math.pi / (opm * opn),
        DPsi=math.pi * (atan + M / opm),
        zDgz=zdgz,
        Dg=zdgz + 2.0 * math.pi * M * (M * m_s) / (opm * opm),
        zP=-2.0 * math.pi * (M * m_s) * N / opm,
    )


def sliding_punch_displacement_unit(x, y, z, nu, rm1=None) -> dict[str, np.ndarray]:
    """Displacement of the half-space under the tangential traction 1/(pi sqrt(1 - r^2)) along +x
    on the unit disc (the sliding punch of ``interior_hertz.sliding_punch_unit``: the friction
    traction of a flat punch of radius 1 pressed to depth 1, E* = 1, per mu), at coordinates
    divided by the radius: the Cerruti superposition (I18) with the radial functions (I38),
    docs/theory/interior.md (I39).  Under the punch u_x = E*/G* = (2 - nu)/(2(1 - nu)), u_y = 0.
    No division by r; finite and continuous everywhere.  Closed form: relative error at most 1e-12
    of the largest term of each component.  ``rm1``: r - 1 without rounding."""
    x, y, g = _unit_coords(x, y, z, rm1)
    nu = np.asarray(nu, dtype=x.dtype)
    # (1/pi) / (4 pi G) with G = (1 - nu)/2 per E*: the traction is 1/pi times 1/sqrt(1 - r^2)
    return _cerruti(x, y, g["z"], nu, _sliding_punch_radial(g), 1.0 / (2.0 * math.pi ** 2 * (1.0 - nu)))


def hertz_displacement_unit(x, y, z, nu) -> dict[str, np.ndarray]:
    """Displacement of the half-space under the Hertz pressure of a paraboloid with R = a = 1
    pressed to delta = 1 (p = (2/pi) sqrt(1 - r^2) per E*), at coordinates divided by a:
    docs/theory/interior.md (I41).  u_z = 1 - r^2/2 under the contact.  No division by r.
    Closed form: relative error at most 1e-12 of the largest term of each component."""
    x, y, g = _unit_coords(x, y, z, None)
    nu = np.asarray(nu, dtype=x.dtype)
    M, N, W, z = g["M"], g["N"], g["W"], g["z"]
    opm = 1.0 + M * M
    phi = np.arctan2(1.0, M)
    t20 = 0.5 * x_minus_sin(2.0 * phi, 2.0 * M / opm)
    enclosed = 2.0 * (1.0 + N + N * N) / (W * (1.0 + N))       # (1 - N^3)/r^2, (I7a)
    ur_r = -(2.0 * (1.0 - 2.0 * nu) / (3.0 * math.pi * (1.0 - nu))) * enclosed + (2.0 / math.pi) * z * t20
    uz = (2.0 / math.pi) * (phi - 0.5 * g["r2"] * t20 + nu / (1.0 - nu) * z * N * one_minus_m_atan(M))
    return {"x": x * ur_r, "y": y * ur_r, "z": uz}


def _hertz_sliding_radial(g):
    """The radial functions of (I18) for the Hertz traction sqrt(1 - r^2) along +x (a = 1), (I40):
    Phi, g_z, D Psi, z P and, from (I19), z D g_z and D g."""
    M, N, W, z, r2 = g["M"], g["N"], g["W"], g["z"], g["r2"]
    opm = 1.0 + M * M
    phi = np.arctan2(1.0, M)
    t20 = 0.5 * x_minus_sin(2.0 * phi, 2.0 * M / opm)
    t31 = x_minus_sin(4.0 * phi, 4.0 * M * (M * M - 1.0) / (opm * opm)) / 16.0
    zt20 = z * t20
    s = sliding_scalars(g)
    return dict(
        Phi=math.pi * (phi - z * N * one_minus_m_atan(M) - 0.5 * r2 * t20),
        gz=(4.0 * math.pi / 3.0) * (1.0 + N + N * N) / (W * (1.0 + N)) - math.pi * zt20,
        DPsi=math.pi * (phi - 0.5 * opm * t20 - 0.5 * r2 * t20 / opm + 0.5 * r2 * (t20 - t31)),
        zDgz=z * s["Dgz"],
        Dg=s["Dg"],
        zP=-math.pi * zt20,
    )


def _cerruti(x, y, z, nu, s, k):
    """(I18) with the radial functions ``s`` (I38) or (I40), times ``k`` = 1/(4 pi G) per traction
    unit: 4 pi G u_x = 2 Phi - z Lambda_xxz + 2 nu Lambda_xx, Lambda_xx = g + x^2 D g,
    Lambda_xxz = g_z + x^2 D g_z, g = z g_z - D Psi, and u_y, u_z alike (I39)."""
    zgz = z * s["gz"]
    x2 = x * x
    ux = 2.0 * s["Phi"] - (1.0 - 2.0 * nu) * zgz - 2.0 * nu * s["DPsi"] - x2 * s["zDgz"] + 2.0 * nu * x2 * s["Dg"]
    uy = x * y * (2.0 * nu * s["Dg"] - s["zDgz"])
    uz = x * ((1.0 - 2.0 * nu) * s["gz"] - s["zP"])
    return {"x": k * ux, "y": k * uy, "z": k * uz}


def hertz_sliding_displacement_unit(x, y, z, nu) -> dict[str, np.ndarray]:
    """Displacement of the half-space under the Hertz traction sqrt(1 - r^2) along +x on the unit
    disc (q0 = 1, E* = 1; the traction of ``interior_hertz.sliding_unit``), at coordinates divided
    by the contact radius: (I18) with the radial functions (I40), docs/theory/interior.md (I41).
    No division by r; finite and continuous everywhere.  Closed form: relative error at most 1e-12
    of the largest term of each component."""
    x, y, g = _unit_coords(x, y, z, None)
    nu = np.asarray(nu, dtype=x.dtype)
    return _cerruti(x, y, g["z"], nu, _hertz_sliding_radial(g), 1.0 / (2.0 * math.pi * (1.0 - nu)))


# -- the superposition of punches (I42)-(I43) ------------------------------------------------------

def _integrator(unit):
    """sum_j w_j g'(rho_j) u(x / rho_j) over the nodes of a group of points (the displacement of a
    punch of radius rho and unit depth depends on x / rho only, (I42))."""
    def integrate(nd: Nodes, profile) -> dict[str, np.ndarray]:
        live, rho, rm1 = live_nodes(nd)
        w = np.where(live, nd.weights * profile.dg(rho), 0.0)
        with np.errstate(over="ignore", invalid="ignore"):   # M^2 of nodes far below the point: no weight
            u = unit(nd.x[:, None] / rho, nd.y[:, None] / rho, nd.z[:, None] / rho, nd.nu[:, None], rm1=rm1)
        return {k: np.sum(np.where(live, v, 0.0) * w, axis=1) for k, v in u.items()}
    return integrate


_NORMAL_KERNEL = (_integrator(punch_displacement_unit), _KEYS)
_SLIDING_KERNEL = (_integrator(sliding_punch_displacement_unit), _KEYS)


def _geometric_count(r, b, q):
    """The number of geometric panel ends r q^k (k >= 1) that may lie below b, per point."""
    with np.errstate(divide="ignore"):
        return np.where(r > 0.0, np.ceil(np.log(b / np.where(r > 0.0, r, 1.0)) / math.log(q)), 0.0).astype(int)


def _surface_ends(r, b, profile, q, kmax):
    """Panel ends of the surface rule (I44) on [0, b] for points with r <= b at z = 0: b1 (the tip
    panel [0, b1]), r, r q^k (1 <= k <= kmax) below b, b and the knots of a tabulated profile
    (rows, sorted, padded with b)."""
    b1 = np.where(r > 0.0, 0.5 * r, 0.5 * b)
    knots = np.asarray(profile.r, dtype=float) if profile.kind == "tabulated" else np.zeros(0)
    knots = knots[knots > 0.0]
    if knots.size:
        b1 = np.minimum(b1, knots[0])
    cols = [b1, np.where(r > b1, r, b), b]
    cols += [np.where((r > 0.0) & (r * q ** k < b), r * q ** k, b) for k in range(1, kmax + 1)]
    cols += [np.where((kn > b1) & (kn < b), kn, b) for kn in knots]
    return np.sort(np.column_stack(cols), axis=1)


def _surface_sum(x, y, b, nu, profile, rtol, unit):
    """int_0^b g'(rho) u(x / rho) d rho at z = 0 for points with r <= b, (I44): Gauss–Jacobi with
    the tip weight rho^m0 on [0, b1], and on the other panels Gauss–Legendre after
    rho = lo + (hi - lo)(1 - cos(pi t))/2, which makes the one-sided square-root kinks of the
    integrand at rho = r (the punch's edge passing the point) and at the knots of a tabulated g'
    analytic in t."""
    # n + 4 nodes: against the rule (40 nodes, ratio 1.6) for cone, power laws n = 0.5, 1.5 and a
    # 13-knot spline at r/a in [0, 1] (axis, 1 - 1e-12 included) the error per row of
    # interior_orders is at most 0.02 rtol delta; with n nodes it reached 0.6 rtol (n = 0.5, 1e-10)
    n, q = interior_orders(rtol)
    r = np.hypot(x, y)
    count = _geometric_count(r, b, q)
    out = {k: np.empty(r.size) for k in _KEYS}
    # points with equal panel counts together: one point at r = 1e-200 b needs 420 panels, the rest a few
    for kmax, idx in group_by(count):
        ends = _surface_ends(r[idx], b[idx], profile, q, int(kmax))
        for k, v in _surface_rule(x[idx], y[idx], r[idx], ends, nu[idx], profile, n + 4, unit).items():
            out[k][idx] = v
    return out


def _surface_rule(x, y, r, ends, nu, profile, n, unit):
    """The rule (I44) on the panels ``ends`` (rows) with n nodes per panel."""
    m0 = float(profile.tip_exponent)
    tj, wj = gauss_jacobi(n, m0) if m0 != 0.0 else gauss_legendre(n)
    b1 = ends[:, :1]
    rho0 = b1 * tj[None, :]
    w0 = b1 ** (1.0 + m0) * wj[None, :] / np.where(rho0 > 0.0, rho0, 1.0) ** m0
    t, w = gauss_legendre(n)
    lo, hi = ends[:, :-1, None], ends[:, 1:, None]
    rho1 = lo + (hi - lo) * 0.5 * (1.0 - np.cos(math.pi * t))
    w1 = (hi - lo) * 0.5 * math.pi * np.sin(math.pi * t) * w
    rho = np.concatenate([rho0, rho1.reshape(len(r), -1)], axis=1)
    wts = np.concatenate([w0, w1.reshape(len(r), -1)], axis=1)
    live = (wts > 0.0) & (rho > 0.0)
    rho = np.where(live, rho, 1.0)
    wts = np.where(live, wts * profile.dg(rho), 0.0)
    with np.errstate(over="ignore", invalid="ignore"):
        u = unit(x[:, None] / rho, y[:, None] / rho, np.zeros_like(rho), nu[:, None], rm1=r[:, None] / rho - 1.0)
    return {k: np.sum(np.where(live, v, 0.0) * wts, axis=1) for k, v in u.items()}


def _sum(x, y, z, b, nu, profile, rtol, unit, kernel):
    """Sigma(b) = int_0^b g'(rho) u(x / rho) d rho: the stresses' panels (I16)-(I17) where z > 0 or
    r > b, the surface rule (I44) at z = 0, r <= b."""
    out = {k: np.zeros(x.size) for k in _KEYS}
    # below _SURFACE_DEPTH b the surface value: u is continuous and |u(z) - u(0)| <= C z^min(1, 1 + m0)
    # (the stresses grow at most like rho^m0 at a tip, d^(-1/2) next to an edge), 1e-145 delta or less
    # for every tip exponent m0 >= -1/2, while the panels of (I16) lose z to subnormal rounding there
    # (NaN at z = 1e-310 a)
    z = np.where(z < _SURFACE_DEPTH * b, 0.0, z)
    top = (z == 0.0) & (np.hypot(x, y) <= b)
    i = np.flatnonzero(~top)
    if i.size:
        part = superpose(x[i], y[i], z[i], b[i], nu[i], profile, rtol, kernel)
        for k in _KEYS:
            out[k][i] = part[k]
    i = np.flatnonzero(top)
    for lo in range(0, i.size, _CHUNK):
        j = i[lo:lo + _CHUNK]
        part = _surface_sum(x[j], y[j], b[j], nu[j], profile, rtol, unit)
        for k in _KEYS:
            out[k][j] = part[k]
    return out


# -- the entry point ---------------------------------------------------------------------------

@quiet
def displacements(names, profile: Profile, x, y, z, *, a, nu, mu, ux0, c, mu_kernel, method: str = "auto",
                  rtol: float = 1e-10) -> dict[str, np.ndarray]:
    """Displacements u_x, u_y, u_z divided by the indentation depth delta at (x, y, z), z >= 0 the
    depth, under the rigid axisymmetric ``profile`` pressed to the contact radius ``a`` with
    Cattaneo–Mindlin tangential load; docs/theory/interior.md (I36)-(I44).

    ``names``: any of "u_x", "u_y", "u_z".  ``c``, ``mu_kernel``: the stick radius and the
    coefficient of friction the kernels take, as ``loading.stick`` returns them (a sticking flat
    punch: c = 0 and mu_kernel = (G*/E*) u_x0/delta); the traction is mu_kernel [p(r; a) - p(r; c)]
    along +x, none where mu_kernel = 0 or c = a.  ``mu`` and ``ux0`` (u_x0/delta) are those of the
    scenario (the traction is fixed by ``c`` and ``mu_kernel``: in the stick zone the tangential
    part of u_x/delta is ux0).  u_x, u_y are the tangential part plus the radial displacement of
    the normal pressure (the half-space is not held at the surface: the normal and tangential
    parts are superposed, uncoupled as Cattaneo–Mindlin).  x, y, z, a, nu, mu, ux0, c, mu_kernel
    broadcast.

    Routes (``method``: "auto", "closed" or "quadrature", as ``interior_stress``):

    * closed forms, relative error at most 1e-12 of |value| everywhere the value is finite (of the
      largest term where a component passes through zero), far field and next to edges included:
      the flat punch, normal (I37) and tangential (I39) (always); the paraboloid and the power law
      n = 2, normal and Cattaneo–Mindlin (I41) ("auto", "closed").
    * 1-D superposition of punches (I42) and of sliding punches (I43), every other profile (the
      paraboloid too with "quadrature"); on the surface z = 0 inside the range of integration the
      panel rule (I44): |error| <= rtol * max(|value|, delta) (the displacement scale is delta).

    Every value is finite (the displacement is continuous, the edge rings included)."""
    names = tuple(names)
    unknown = [n for n in names if n not in NAMES]
    if unknown:
        raise ValueError(f"unknown displacement {unknown!r}; allowed: {', '.join(NAMES)}")
    shape, (x, y, z, a, nu, c, muk) = flat_arguments("displacement", method, x, y, z, a, nu, c, mu_kernel)
    _validate(z, a, c, nu, muk, profile, rtol)
    normal = _normal(x, y, z, a, nu, profile, method, rtol)
    tangential = _tangential(x, y, z, a, c, nu, muk, profile, method, rtol, _slip(profile, shape, ux0, mu, nu, a, c))
    return {n: (normal[n[-1]] + tangential[n[-1]]).reshape(shape) for n in names}


def tangential_displacements(names, profile: Profile, x, y, z, *, a, c, nu, mu_kernel, ux0=None,
                             method: str = "auto", rtol: float = 1e-10) -> dict[str, np.ndarray]:
    """The tangential part alone of ``displacements`` (the traction mu_kernel [p(r; a) - p(r; c)]
    along +x), divided by delta: one c-term of a load, which a loading history weights and sums
    (docs/theory/interior.md (I43); docs/theory/axisymmetric.md (A69)).  ``ux0``: u_x0/delta of
    this term where known (a monotonic load: the paraboloid then takes its slip ratio, exact as
    c -> a); None: the kernels see c alone.  Routes and accuracy as ``displacements``."""
    names = tuple(names)
    shape, (x, y, z, a, nu, c, muk) = flat_arguments("displacement", method, x, y, z, a, nu, c, mu_kernel)
    _validate(z, a, c, nu, muk, profile, rtol)
    slip = None if ux0 is None else _slip(profile, shape, ux0, mu_kernel, nu, a, c)
    part = _tangential(x, y, z, a, c, nu, muk, profile, method, rtol, slip)
    return {n: part[n[-1]].reshape(shape) for n in names}


def _slip(profile, shape, ux0, mu, nu, a, c):
    """The paraboloid's slip ratio 1 - (c/a)^2 = G* u_x0 / (mu E* delta) (A32) per flat point where
    ``ux0`` is the displacement of the stick radius c (to 1e-13; NaN elsewhere), None for other
    profiles: ``_hertz_mindlin`` takes it where the difference of the rounded radii loses digits."""
    if profile.closed is None or profile.closed[0] != "paraboloid":
        return None
    ux, mu_ = (np.broadcast_to(np.asarray(v, dtype=float), shape).ravel() for v in (ux0, mu))
    with np.errstate(divide="ignore", invalid="ignore"):
        slip = np.where(mu_ > 0.0, 2.0 * (1.0 - nu) / (2.0 - nu) * ux / mu_, 1.0)   # (A32): 1 - (c/a)^2
        # only where u_x0 is the one of this c (the traction is fixed by c and mu_kernel)
        return np.where((slip > 0.0) & (np.abs(1.0 - slip - (c / a) ** 2) <= 1e-13), slip, np.nan)


def _validate(z, a, c, nu, muk, profile, rtol):
    if not (math.isfinite(float(rtol)) and float(rtol) > 0.0):
        raise ValueError(f"rtol must be a positive finite number, got {rtol!r}")
    check_arguments(z, a, nu, profile, c=c, mu=muk, mu_name="mu_kernel (coefficient of friction of the kernels)")


def _family(profile, method):
    """"paraboloid", "flat_punch" or None (the 1-D route), as ``interior._closed_family``."""
    closed = profile.closed
    family = closed[0] if closed is not None and closed[0] in ("paraboloid", "flat_punch") else None
    if profile.kind == "flat_punch":
        return "flat_punch"
    if method == "closed" and family is None:
        raise ValueError(f"method='closed': no displacement closed form for the {profile.kind} profile {profile!r}; "
                         "use method='quadrature'")
    return family if method in ("auto", "closed") else None


def _normal(x, y, z, a, nu, profile, method, rtol):
    family = _family(profile, method)
    if family == "flat_punch":
        return punch_displacement_unit(x / a, y / a, z / a, nu)
    if family == "paraboloid":
        return hertz_displacement_unit(x / a, y / a, z / a, nu)     # delta = a^2/R: u/delta is R-free
    total = _sum(x, y, z, a, nu, profile, rtol, punch_displacement_unit, _NORMAL_KERNEL)
    delta = profile.depth(a)
    return {k: v / delta for k, v in total.items()}


#: Gauss–Legendre nodes of the thin-annulus difference of ``_hertz_mindlin``: at a distance of at least
#: 4 widths from the annulus the integrand's nearest singularity lies beyond the Bernstein ellipse
#: of parameter 16, so 8 nodes leave 16^-16 (5e-20) of the integral
_ANNULUS_NODES, _ANNULUS_REACH = 8, 4.0
#: below this slip ratio rho = 1 - (c/a)^2 the plain difference of (I41) would lose more than 1e-12
#: (1e-16/rho): only there the superposition over [c, a] replaces it
_THIN = 1e-4
#: nearer: panels growing geometrically (ratio 2) from the ring point nearest to the field point, each
#: mapped by t = lo + (hi - lo)(1 - cos(pi s))/2 (the one-sided square-root kink at the ring, z = 0,
#: becomes analytic); every panel's singularity lies at least its own length away, 24 nodes each
_NEAR_NODES, _NEAR_LEVELS = 24, 60


def thin_annulus(x, y, z, a, c, w, nu, unit, power=0):
    """int_{a-w}^a t^power unit(p/t) dt, p = (x, y, z), the superposition of punches over a thin
    annulus [c, a] of width w (given free of the rounding of c), at every point (1-D arrays):
    Gauss–Legendre in t = a - w (1 - s)/2 at least ``_ANNULUS_REACH`` widths from the annulus,
    graded panels (``_annulus_near``) nearer.  ``unit(x, y, z, nu, rm1=None)`` -> dict of arrays."""
    r = np.hypot(x, y)
    gap = np.hypot(np.where(r < c, c - r, np.where(r > a, r - a, 0.0)), z)
    far = np.flatnonzero(gap >= _ANNULUS_REACH * w)
    out: dict[str, np.ndarray] = {}

    def put(i, part):
        for k, v in part.items():
            out.setdefault(k, np.zeros(x.size))[i] = v

    if far.size:
        s, ws = gauss_legendre(_ANNULUS_NODES)                # on [0, 1]
        A, W = a[far, None], w[far, None]
        t = A - W * (1.0 - s[None, :])                        # nodes in (c, a)
        # r/t - 1 without the rounding of t: a point at depth z next to the ring sees it on the scale z
        rm1 = ((r[far] - a[far])[:, None] + W * (1.0 - s[None, :])) / t
        vals = unit(x[far, None] / t, y[far, None] / t, z[far, None] / t, nu[far, None], rm1=rm1)
        put(far, {k: np.sum(W * ws[None, :] * t ** power * v, axis=1) for k, v in vals.items()})
    near = np.flatnonzero(~(gap >= _ANNULUS_REACH * w))
    for lo in range(0, near.size, 256):                   # (points x 121 panels x 24 nodes) blocks
        i = near[lo:lo + 256]
        put(i, _annulus_near(x[i], y[i], z[i], a[i], w[i], nu[i], unit, power))
    return out


def _annulus_near(x, y, z, a, w, nu, unit, power):
    """int_{a-w}^a t^power unit(p/t) dt at points next to the thin annulus, in offsets s = a - t from
    the outer edge, so that the panels' widths, and so the weights, carry w and not a rounded a - w."""
    r = np.hypot(x, y)
    s_star = np.clip(a - r, 0.0, w)                       # offset of the ring point nearest to the point
    d = np.hypot((a - r) - s_star, z)                     # its distance
    # closer than w 2^-59 the point is on the ring for the rule: the cosine map takes the kink
    steps = np.where(d > w * 2.0 ** (1 - _NEAR_LEVELS), d, 0.0)[:, None] * 2.0 ** np.arange(_NEAR_LEVELS)[None, :]
    left, right = np.clip(s_star[:, None] - steps, 0.0, None), np.minimum(s_star[:, None] + steps, w[:, None])
    ends = np.concatenate([np.zeros((r.size, 1)), w[:, None], s_star[:, None], left, right], axis=1)
    ends = np.sort(ends, axis=1)
    q, wq = gauss_legendre(_NEAR_NODES)
    lo, hi = ends[:, :-1, None], ends[:, 1:, None]
    s = lo + (hi - lo) * 0.5 * (1.0 - np.cos(math.pi * q))
    ws = (hi - lo) * 0.5 * math.pi * np.sin(math.pi * q) * wq
    s, ws = s.reshape(r.size, -1), ws.reshape(r.size, -1)
    t = a[:, None] - s
    rm1 = ((r - a)[:, None] + s) / t                      # r/t - 1 without the rounding of t
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        vals = unit(x[:, None] / t, y[:, None] / t, z[:, None] / t, nu[:, None], rm1=rm1)
    return {k: np.sum(np.where(ws > 0.0, ws * t ** power * v, 0.0), axis=1) for k, v in vals.items()}


def _hertz_mindlin(x, y, z, a, c, nu, mu, slip=None):
    """(I41) for partial slip: the traction mu p0 [sqrt(1 - r^2/a^2) - (c/a) sqrt(1 - r^2/c^2)] per
    E*, p0 = 2a/(pi R), delta = a^2/R: u/delta = mu (2/pi) [V(x/a) - (c/a)^2 V(x/c)].

    As fx -> 0 the two terms cancel (c -> a): the difference lost 1e-16/fx of its value (8e-8 at
    fx = 1e-9).  Where ``slip`` = 1 - (c/a)^2 is given (exactly, from u_x0, (A32)) and below
    ``_THIN``, the difference is instead the superposition of sliding punches over [c, a]
    (docs/theory/interior.md (I43), (I45)): t^2 V(p/t) has the derivative pi t U(p/t), U the unit
    sliding punch (I39), so u/delta = (2 mu / a^2) int_c^a t U(p/t) dt, with the annulus width
    w = a slip / (1 + sqrt(1 - slip)) free of the rounding of c: by Gauss–Legendre in
    t = a - w (1 - s)/2 at points at least 4 widths from the annulus, on graded panels
    (``_annulus_near``) nearer."""
    out = {k: v * (2.0 / math.pi) * mu for k, v in hertz_sliding_displacement_unit(x / a, y / a, z / a, nu).items()}
    part = np.flatnonzero(c > 0.0)
    if part.size:
        cp, ap = c[part], a[part]
        stick = hertz_sliding_displacement_unit(x[part] / cp, y[part] / cp, z[part] / cp, nu[part])
        for k in _KEYS:
            out[k][part] -= (2.0 / math.pi) * mu[part] * (cp / ap) ** 2 * stick[k]
    if slip is None:
        return out
    w = a * slip / (1.0 + np.sqrt(np.clip(1.0 - slip, 0.0, 1.0)))
    thin = np.flatnonzero((c > 0.0) & (slip < _THIN))
    if thin.size:
        i = thin
        part = thin_annulus(x[i], y[i], z[i], a[i], c[i], w[i], nu[i], sliding_punch_displacement_unit, power=1)
        for k in _KEYS:
            out[k][i] = 2.0 * mu[i] / a[i] ** 2 * part[k]
    return out


def _tangential(x, y, z, a, c, nu, muk, profile, method, rtol, slip=None):
    out = {k: np.zeros(x.size) for k in _KEYS}
    act = np.flatnonzero((muk > 0.0) & (c < a))
    if not act.size:
        return out
    X, Y, Z, A, C, NU, MU = (v[act] for v in (x, y, z, a, c, nu, muk))
    slip = None if slip is None else slip[act]
    family = _family(profile, method)
    if family == "flat_punch":
        part = {k: MU * v for k, v in sliding_punch_displacement_unit(X / A, Y / A, Z / A, NU).items()}
    elif family == "paraboloid":
        part = _hertz_mindlin(X, Y, Z, A, C, NU, MU, slip)
    else:
        part = _sum(X, Y, Z, A, NU, profile, rtol, sliding_punch_displacement_unit, _SLIDING_KERNEL)
        stick = np.flatnonzero(C > 0.0)
        if stick.size:
            inner = _sum(X[stick], Y[stick], Z[stick], C[stick], NU[stick], profile, rtol,
                         sliding_punch_displacement_unit, _SLIDING_KERNEL)
            for k in _KEYS:
                part[k][stick] -= inner[k]
        delta = profile.depth(A)
        part = {k: MU * v / delta for k, v in part.items()}
    for k in _KEYS:
        out[k][act] = part[k]
    return out

