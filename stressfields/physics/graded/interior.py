"""Below the surface of the power-law graded half-space: the stress tensor under the normal and the
adhesive (JKR-type) MDR contact, docs/theory/graded.md section 10 ((G57)-(G70)).

Two cases are solved, every other (k, nu) is refused (``check_supported``):

* k = 0, any nu: the homogeneous half-space.  The pressure of the graded family at k = 0 is the one of
  the axisymmetric family (c_N* = E* for a rigid indenter), so the interior is its interior field
  (``axisymmetric.interior_stress``: closed forms for the paraboloid and the cone, the 1-D superposition
  of flat punches otherwise) times c_N*; with adhesion minus the flat-punch field of the depth
  Delta l_max (``axisymmetric.interior_hertz.punch_unit``), (G57)-(G58).
* k > 0 with nu = 1/(2+k) (Holl): the area integral of the radial point-load field over the contact
  (``holl.disc_stress``, (G60)-(G65)) for every power law (paraboloid, cone, A r^n): the paraboloid's
  pressure is a sum of (1 - rho^2)^e terms, any other power law's is (1 - rho^2)^((1+k)/2) times its
  shape S(rho) (``holl.PressureShape``, (G70)), with the adhesive term of the paraboloid.

On the surface z = 0 the values are the limits z -> 0+: sigma_zz = -p with p the family's pressure
(the same call, so bit for bit the ``pressure`` variable), and the other components from the
axisymmetric surface kernels (k = 0) or (G66) (Holl).  Components on the plane y = 0 through the axis
at x = r: "rr", "tt" (hoop), "zz", "rz"; tension positive, z into the body, stresses in the units of E0.
"""
from __future__ import annotations

import functools
import math
from typing import Sequence

import numpy as np

from ..flags import Validity
from ..invariants import principal_stresses, singular_limits, von_mises
from ..names import PRINCIPAL
from . import adhesive, holl
from .fields import adhesive_fields, normal_fields
from .indenter import Indenter
from .material import c_N_star
from .normal import pressure_shape
from .profiles import kappa

__all__ = ["INTERIOR", "STRESS", "supported", "check_supported", "interior_fields", "UNRESOLVED", "peaks",
           "tangential_interior_fields", "tangential_peaks"]

#: the stress components, in the order of the files
STRESS = ("sigma_rr", "sigma_tt", "sigma_zz", "sigma_rz")
#: everything ``interior_fields`` computes
INTERIOR = STRESS + ("von_mises",) + PRINCIPAL + ("tau_max",)
#: validity code of a point below the surface that the routes do not resolve (as the axisymmetric family)
UNRESOLVED = Validity.not_resolved_below_the_surface
#: nu is Holl's ratio 1/(2+k) to this relative tolerance (as ``material.tangential_decoupled``)
_HOLL_RTOL = 1e-9
SUPPORTED = ("below the surface the graded family solves k = 0 (any nu; every profile) and k > 0 with "
             "nu = 1/(2+k) (poisson = 'holl_ratio'; the parabolic, conical and power-law profiles)")
#: why a tabulated profile is refused below the surface at k > 0 (docs/theory/graded.md section 10, Limits)
_TABULATED = ("profile = 'tabulated' is solved below the surface at k = 0 only: at k > 0 the area integral of "
              "the point-load field needs the pressure at every radial node of its rule, which a spline has only "
              "by the quadrature of (G17) (no shape S(rho) to interpolate)")
#: why a spline with a clamped slope at the tip is refused below the surface
_CLAMPED = ("a tabulated profile with slope_at_0 set is not solved below the surface: its spline's end condition "
            "at r = 0 differs from the not-a-knot spline of the axisymmetric family, whose interior serves k = 0")


def supported(k, nu):
    """Boolean array: is the interior of (k, nu) solved? k = 0, or nu = 1/(2+k) to 1e-9 relative."""
    k, nu = np.broadcast_arrays(np.asarray(k, dtype=float), np.asarray(nu, dtype=float))
    return (k == 0.0) | np.isclose(nu, 1.0 / (2.0 + k), rtol=_HOLL_RTOL, atol=0.0)


def check_supported(k, nu, kind: str, slope_at_0=None) -> None:
    """ValueError (one line, naming the first unsupported value and the supported cases) unless every
    (k, nu) is solved for the profile ``kind``: a power law at k = 0 or nu = 1/(2+k), a tabulated profile
    at k = 0 and without a clamped tip slope (``slope_at_0`` of :class:`~.profiles.Tabulated`)."""
    k, nu = np.broadcast_arrays(np.asarray(k, dtype=float), np.asarray(nu, dtype=float))
    if kind == "tabulated":
        if slope_at_0 is not None:
            raise ValueError(f"{_CLAMPED} (slope_at_0 = {slope_at_0!r})")
        if np.any(k != 0.0):
            raise ValueError(f"{_TABULATED}; here k = {float(k[k != 0.0].flat[0])!r}")
    ok = supported(k, nu)
    if not np.all(ok):
        kb, nb = float(k[~ok].flat[0]), float(nu[~ok].flat[0])
        raise ValueError(f"nu = {nb!r} with k = {kb!r} is not solved below the surface: {SUPPORTED}; "
                         f"here 1/(2+k) = {1.0 / (2.0 + kb):.12g}")


def _axisymmetric_profile(profile: Indenter, geometry):
    """The axisymmetric family's profile of the same shape.  A tabulated profile maps to the axisymmetric
    spline through the same samples: both are the not-a-knot cubic spline of f - f[0] (a clamped tip slope
    is refused by ``check_supported``), so at k = 0 the pressures agree (G57)."""
    from .. import axisymmetric as ax

    if profile.kind == "tabulated":
        return ax.tabulated(*profile.table.samples)
    if profile.kind == "parabolic":
        return ax.paraboloid(geometry[0])
    if profile.kind == "conical":
        return ax.cone(geometry[0])
    return ax.power_law(geometry[0], geometry[1])


def interior_fields(names: Sequence[str], profile: Indenter, *, a, rho, z, k, nu, E0, c0, delta_gamma=None,
                    method: str = "auto", rtol: float = 1e-10) -> dict[str, np.ndarray]:
    """The stress below a graded contact: fields among :data:`INTERIOR` at r = rho a, depth z a.

    Normal contact (``delta_gamma`` None) or adhesive (JKR-type, work of adhesion ``delta_gamma``) of a
    rigid indenter at contact radius ``a``; ``rho``, ``z`` in units of a; E0, c0, k, nu as the surface
    entry points.  Every argument broadcasts (the geometry arrays of ``profile`` too).  Routes and
    accuracy: docs/theory/graded.md (G67), (G70); singular points (conical tip at k = 0, the centre of a
    power law with n + k <= 1 at k > 0, adhesive edge r = a) only at z = 0, with +-inf or NaN as the
    surface fields (G68).
    """
    names = _known(names, INTERIOR)
    if not names:
        return {}
    shape, (A, RHO, Z, K, NU, E, C0, DG, *G) = _flat(profile, z, a, rho, z, k, nu, E0, c0,
                                                     0.0 if delta_gamma is None else delta_gamma)
    check_supported(K, NU, profile.kind, _slope_at_0(profile))
    flat = Indenter(profile.kind, tuple(G), profile.table)
    mat = dict(k=K, nu=NU, E0=E, c0=C0)
    if delta_gamma is None:
        p_surf = normal_fields(["pressure"], flat, a=A, rho=RHO, **mat, method=method, rtol=rtol)["pressure"]
    else:
        p_surf = adhesive_fields(["pressure"], flat, a=A, rho=RHO, **mat, delta_gamma=DG, method=method,
                                 rtol=rtol)["pressure"]
    T = {c: np.zeros(A.size) for c in holl.COMPONENTS}
    surf = Z == 0.0
    homo = K == 0.0
    cN = c_N_star(**mat)
    dl = np.zeros(A.size) if delta_gamma is None else adhesive.delta_l_max(A, **mat, delta_gamma=DG)
    if np.any(homo):
        _homogeneous(T, np.flatnonzero(homo), flat, A, RHO, Z, NU, cN, dl, method, rtol)
    if np.any(~homo):
        _holl(T, np.flatnonzero(~homo & ~surf), flat, A, RHO, Z, K, cN, dl, rtol)
        on = np.flatnonzero(~homo & surf)
        lim = holl.surface_limit(p_surf[on], K[on])
        for c in holl.COMPONENTS:
            T[c][on] = lim[c]
    T["zz"][surf] = -p_surf[surf]
    deep = ~surf
    for c in holl.COMPONENTS:     # below the surface every exact value is finite: a non-finite one is unresolved
        T[c][deep] = np.where(np.isfinite(T[c][deep]), T[c][deep], np.nan)
    out = _invariants(names, T, flat, A, RHO, Z, K, NU, DG)
    return {n: v.reshape(shape) for n, v in out.items()}


def _slope_at_0(profile: Indenter):
    """The clamped tip slope of a tabulated profile's spline (None: not-a-knot, or a power law)."""
    return None if profile.table is None else profile.table.slope_at_0


def _known(names, allowed) -> list[str]:
    names = list(names)
    unknown = [n for n in names if n not in allowed]
    if unknown:
        raise ValueError(f"unknown field(s) {unknown!r}: use some of {', '.join(allowed)}")
    return names


def _flat(profile: Indenter, z, *values):
    """(shape, flat arrays): ``values`` and the profile's geometry arrays broadcast and flattened (the
    geometry last), after refusing a depth z < 0 or NaN in one line."""
    arrays = [np.asarray(v, dtype=float) for v in values] + list(profile.geometry)
    shape = np.broadcast_shapes(*(v.shape for v in arrays))
    z = np.asarray(z, dtype=float)
    if np.any(~(z >= 0.0)):
        raise ValueError(f"z = {float(z[~(z >= 0.0)].flat[0])!r} is outside the allowed range z >= 0 (depth below "
                         "the surface / contact radius)")
    return shape, [np.ascontiguousarray(np.broadcast_to(v, shape)).ravel() for v in arrays]


def _homogeneous(T, idx, flat, A, RHO, Z, NU, cN, dl, method, rtol):
    """k = 0: c_N* times the axisymmetric interior (G57), minus the punch of depth Delta l_max (G58)."""
    from ..axisymmetric import interior_stress
    from ..axisymmetric.interior_hertz import punch_unit

    keys = np.stack([g[idx] for g in flat.geometry], axis=-1) if flat.geometry else np.zeros((idx.size, 0))
    groups = np.unique(keys, axis=0) if keys.shape[1] else np.zeros((1, 0))
    for g in groups:
        sel = idx[np.all(keys == g, axis=1)] if keys.shape[1] else idx
        prof = _axisymmetric_profile(flat, [float(v) for v in g])
        a = A[sel]
        s = interior_stress(RHO[sel] * a, 0.0, Z[sel] * a, a, NU[sel], prof, method=method, rtol=rtol)
        for c, src in (("rr", "xx"), ("tt", "yy"), ("zz", "zz"), ("rz", "xz")):
            T[c][sel] = cN[sel] * s[src]
        adh = dl[sel] > 0.0
        if np.any(adh):
            i = sel[adh]
            with np.errstate(invalid="ignore"):
                pu = punch_unit(RHO[i], 0.0, Z[i], NU[i])
            for c, src in (("rr", "xx"), ("tt", "yy"), ("zz", "zz"), ("rz", "xz")):
                with np.errstate(invalid="ignore"):
                    T[c][i] = T[c][i] - cN[i] * (dl[i] / A[i]) * pu[src]


def _holl(T, idx, flat, A, RHO, Z, K, cN, dl, rtol):
    """k > 0, nu = 1/(2+k): p = P Phi(rho) - Q (1-rho^2)^(-(1-k)/2) (G18), (G24), each term by
    ``holl.disc_stress`` (G62); Phi = (1-rho^2)^((1+k)/2)/(1+k) for the paraboloid, else its shape (G70)."""
    if idx.size == 0:
        return
    n, A_n = flat.power()
    n = np.broadcast_to(np.asarray(n, dtype=float), A.shape)[idx]
    A_n = np.broadcast_to(np.asarray(A_n, dtype=float), A.shape)[idx]
    k, a = K[idx], A[idx]
    P = cN[idx] * n * kappa(n, k) * A_n * a ** (n + k - 1.0)       # over pi: the amplitude of Phi (G18)
    para = n == 2.0
    if np.any(para):
        i = idx[para]
        part = holl.disc_stress(RHO[i], Z[i], K[i], 0.5 * (1.0 + K[i]), rtol)
        for c in holl.COMPONENTS:
            T[c][i] = P[para] / (math.pi * (1.0 + K[i])) * part[c]
    for nk in np.unique(np.stack([n[~para], k[~para]], axis=-1), axis=0):
        sel = np.flatnonzero(~para & (n == nk[0]) & (k == nk[1]))
        i = idx[sel]
        part = holl.disc_stress(RHO[i], Z[i], K[i], 0.5 * (1.0 + K[i]), rtol, shape=_shape(*map(float, nk)))
        for c in holl.COMPONENTS:
            T[c][i] = P[sel] / math.pi * part[c]
    adh = dl[idx] > 0.0
    if np.any(adh):
        i = idx[adh]
        Q = cN[i] * dl[i] * A[i] ** (K[i] - 1.0) / math.pi
        part = holl.disc_stress(RHO[i], Z[i], K[i], -0.5 * (1.0 - K[i]), rtol)
        for c in holl.COMPONENTS:
            T[c][i] = T[c][i] - Q * part[c]


@functools.lru_cache(maxsize=32)
def _shape(n: float, k: float) -> holl.PressureShape:
    """The interpolated shape S = Phi / (1 - rho^2)^((1+k)/2) of f = A r^n (G70), once per (n, k); for n > 4
    with its edge layer of width 1/n and max(20, n) Chebyshev points per panel (measured: 1e-13 at n = 50)."""
    return holl.PressureShape(lambda rho: pressure_shape(rho, k=k, n=n), 0.5 * (1.0 + k), n + k - 1.0,
                              max(20, math.ceil(n)), 1.0 / n if n > 4.0 else None)


def _invariants(names, T, flat, A, RHO, Z, K, NU, DG):
    """The requested components and invariants; at the singular points of the surface (a component
    +-inf) the invariants are the limits of ``singular_limits`` with the leading tensor (G68)."""
    out = {f"sigma_{c}": T[c] for c in holl.COMPONENTS if f"sigma_{c}" in names}
    inv = [n for n in INTERIOR[4:] if n in names]
    if not inv:
        return out
    zero = np.zeros(A.size)
    comps = (T["rr"], T["tt"], T["zz"], zero, T["rz"], zero)
    vals = {"von_mises": von_mises(*comps)}
    s1, s2, s3 = principal_stresses(*comps)
    vals.update(sigma_1=s1, sigma_2=s2, sigma_3=s3, tau_max=0.5 * (s1 - s3))
    bad = np.flatnonzero(~np.all([np.isfinite(T[c]) for c in ("rr", "tt", "zz")], axis=0) & (Z == 0.0))
    if bad.size:
        lead = np.full((bad.size, 3, 3), np.nan)
        k, nu, r = K[bad], NU[bad], RHO[bad]
        edge = (r == 1.0) & (DG[bad] > 0.0)            # adhesive edge: p -> -inf, tension
        side = np.where(k > 0.0, 1.0 / (1.0 + k), 2.0 * nu)  # (G66) at k > 0; punch edge ~ (1, 2nu, 1)
        lead[edge] = 0.0
        lead[edge, 0, 0] = np.where(k[edge] > 0.0, side[edge], 1.0)
        lead[edge, 1, 1] = side[edge]
        lead[edge, 2, 2] = 1.0
        tip = (r == 0.0) & ~edge & (k == 0.0)           # conical tip at k = 0: p -> +inf, compression
        if np.any(tip):
            m = _tip_exponent(flat, bad[tip])
            q = 1.0 - 2.0 * nu[tip]
            lead[tip] = 0.0
            lead[tip, 0, 0] = -(1.0 - q / (m + 2.0))
            lead[tip, 1, 1] = -(2.0 * nu[tip] + q / (m + 2.0))
            lead[tip, 2, 2] = -1.0
        tip = (r == 0.0) & ~edge & (k > 0.0)            # tip of f = A r^n, n + k <= 1, at k > 0: (G66)
        lead[tip] = 0.0
        lead[tip, 0, 0] = lead[tip, 1, 1] = -side[tip]
        lead[tip, 2, 2] = -1.0
        # the shear of a punch edge depends on the direction of approach (NaN): only the leading normal
        # stresses are known, so the remainder is unknown and a zero eigenvalue gives NaN
        rest = np.full((bad.size, 3, 3), np.nan)
        vm, pr = singular_limits(lead, rest)
        tau = np.where(np.isinf(vm), np.inf, np.nan)
        for n, v in zip(INTERIOR[4:], (vm,) + pr + (tau,)):
            vals[n] = np.array(vals[n])
            vals[n][bad] = v
    out.update((n, vals[n]) for n in inv)
    return out


def _tip_exponent(flat: Indenter, idx):
    """m0 of g' ~ u^m0 at the tip: n - 1 for f = A r^n (0 for the cone; the geometry arrays are flat)."""
    if flat.kind == "tabulated":
        return np.zeros(idx.size)
    n, _ = flat.power()
    return np.broadcast_to(np.asarray(n, dtype=float), (flat.geometry[0].size,))[idx] - 1.0


#: the keys of ``peaks`` (positions in units of the contact radius)
PEAKS = ("tau_max_peak", "tau_max_peak_rho", "tau_max_peak_depth",
         "von_mises_peak", "von_mises_peak_rho", "von_mises_peak_depth", "peak_validity")


def peaks(profile: Indenter, *, a, k, nu, E0, c0, delta_gamma=None, method: str = "auto",
          rtol: float = 1e-10) -> dict[str, np.ndarray]:
    """The largest tau_max and von Mises in the half-space z >= 0 and where they sit (rho = r/a, depth z/a),
    for every case of the broadcast arguments (a loop), and ``peak_validity`` (the codes of
    ``axisymmetric.peaks``: 0 within accuracy, 1 unbounded at a surface singular point, 2 undefined there,
    4 not converged).  The search of ``axisymmetric.peaks`` (its module docstring) on the field of
    :func:`interior_fields`: the surface singular points r = 0 and r = a probed first, a grid over
    rho in [0, 2] and 41 depths to 3, a bounded Nelder-Mead refinement of the best local maxima."""
    from ..axisymmetric.peaks import FINITE, search

    args = [np.asarray(v, dtype=float) for v in (a, k, nu, E0, c0, 0.0 if delta_gamma is None else delta_gamma)]
    shape = np.broadcast_shapes(*(v.shape for v in args), *(g.shape for g in profile.geometry))
    args = [np.broadcast_to(v, shape) for v in args]
    geo = [np.broadcast_to(g, shape) for g in profile.geometry]
    out = {n: np.empty(shape, dtype=np.int8 if n == "peak_validity" else float) for n in PEAKS}
    for idx in np.ndindex(shape):
        one = Indenter(profile.kind, tuple(np.asarray(g[idx]) for g in geo), profile.table)
        ai, ki, nui, ei, ci, dgi = (float(v[idx]) for v in args)
        flag = FINITE
        for name in ("tau_max", "von_mises"):
            def field(u, w, name=name):
                return interior_fields([name], one, a=ai, rho=u, z=w, k=ki, nu=nui, E0=ei, c0=ci,
                                       delta_gamma=None if delta_gamma is None else dgi, method=method,
                                       rtol=rtol)[name]
            value, x, z, code = search(field, np.array([0.0, 1.0]), False)
            out[f"{name}_peak"][idx], out[f"{name}_peak_rho"][idx], out[f"{name}_peak_depth"][idx] = value, x, z
            flag = max(flag, code)
        out["peak_validity"][idx] = flag
    return out


#: the fields of ``tangential_interior_fields``: the Cartesian set on the plane y = 0 along the load
TANGENTIAL_STRESS = ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz")
TANGENTIAL_INTERIOR = TANGENTIAL_STRESS + ("von_mises",) + PRINCIPAL + ("tau_max", "validity")


def tangential_interior_fields(names: Sequence[str], profile: Indenter, *, a, x, z, fx, mu, k, nu, E0, c0,
                               E0_2=None, nu_2=None, method: str = "auto",
                               rtol: float = 1e-10) -> dict[str, np.ndarray]:
    """The stress in the lower body of a Cattaneo-Mindlin contact of graded bodies at k = 0 (G69): fields among
    :data:`TANGENTIAL_INTERIOR` at (x a, 0, z a), x signed along the tangential load, z >= 0 the depth.

    At k = 0 the traction of the pair is the axisymmetric family's (pressure (G17) with c_N* of the pair,
    shear mu [p(r; a) - p(r; c)] with the stick radius c = a (1 - fx)^(1/(n+1)) (G33)), so the stress is
    the axisymmetric family's entry point (``axisymmetric.fields``: normal plus tangential interior, the
    surface kernels at z = 0, the invariants' limits at singular points, the validity codes 0-3) with the
    tangential displacement that gives that stick radius, scaled by c_N* instead of E*.  Body 2 as
    :func:`~.fields.tangential_fields` (None: identical; inf: rigid).  ``validity`` is the family's flag.
    """
    from .. import axisymmetric as ax
    from ..axisymmetric.profiles import displacement_ratio, slip_ratio

    names = _known(names, TANGENTIAL_INTERIOR)
    if not names:
        return {}
    if E0_2 is None:
        E0_2, nu_2 = E0, nu
    shape, (A, X, Z, FX, MU, K, NU, E, C0, E2, NU2, *G) = _flat(profile, z, a, x, z, fx, mu, k, nu, E0, c0, E0_2,
                                                                nu if nu_2 is None else nu_2)
    _check_tangential(K, profile)
    cN = c_N_star(K, NU, E, C0, E2, NU2)
    flat = Indenter(profile.kind, tuple(G), profile.table)
    out = {n: np.empty(A.size, dtype=np.int8 if n == "validity" else float) for n in names}
    for sel, prof in _profile_groups(flat, G, A.size):
        a_s = A[sel]
        ux0 = displacement_ratio(slip_ratio(prof, a_s, FX[sel]), NU[sel], MU[sel])
        vals, _ = ax.fields(names, prof, X[sel] * a_s, 0.0, Z[sel] * a_s, a=a_s, nu=NU[sel], mu=MU[sel], ux0=ux0,
                            method=method, rtol=rtol)
        for n in names:
            # the family's values are per unit E*: the pair's c_N* takes its place
            out[n][sel] = vals[n] if n == "validity" else vals[n] * cN[sel]
    return {n: v.reshape(shape) for n, v in out.items()}


def _check_tangential(K, profile: Indenter) -> None:
    """One line unless every k is 0 and a tabulated profile's spline is not-a-knot (the cases solved under
    tangential load: every profile at k = 0, a spline as the axisymmetric family's, ``_axisymmetric_profile``)."""
    K = np.asarray(K, dtype=float)
    if np.any(K != 0.0):
        raise ValueError(f"k = {float(K[K != 0.0][0])!r} is not solved below the surface under tangential load: "
                         "the graded family solves k = 0 there")
    if _slope_at_0(profile) is not None:
        raise ValueError(f"{_CLAMPED} (slope_at_0 = {_slope_at_0(profile)!r})")


def _profile_groups(flat: Indenter, G, size: int):
    """(indices, axisymmetric profile) per distinct geometry of the flat geometry arrays ``G``."""
    keys = np.stack(G, axis=-1) if G else np.zeros((size, 0))
    groups = np.unique(keys, axis=0) if keys.shape[1] else np.zeros((1, 0))
    for g in groups:
        sel = np.flatnonzero(np.all(keys == g, axis=1)) if keys.shape[1] else np.arange(size)
        yield sel, _axisymmetric_profile(flat, [float(v) for v in g])


#: the keys of ``tangential_peaks`` (positions in units of the contact radius, x signed along the load)
TANGENTIAL_PEAKS = ("tau_max_peak", "tau_max_peak_x", "tau_max_peak_depth",
                    "von_mises_peak", "von_mises_peak_x", "von_mises_peak_depth", "peak_validity")


def tangential_peaks(profile: Indenter, *, a, fx, mu, k, nu, E0, c0, E0_2=None, nu_2=None, method: str = "auto",
                     rtol: float = 1e-10) -> dict[str, np.ndarray]:
    """The largest tau_max and von Mises in the lower body of the Cattaneo-Mindlin contact at k = 0 (G69) and
    where they sit (x/a signed along the load, depth z/a), per case of the broadcast arguments, with
    ``peak_validity`` (the codes of ``axisymmetric.peaks``).

    The field is c_N* of the pair times the axisymmetric family's at the tangential displacement that gives
    the stick radius of (G33) (:func:`tangential_interior_fields`), and c_N* > 0 is a constant of the case, so
    the peaks are c_N* times the axisymmetric family's peaks of that field, found by its search
    (``axisymmetric.peaks``: the surface singular points first, a grid over x in [-2a, 2a] and 41 depths to
    3a, a bounded Nelder-Mead refinement); the positions do not depend on c_N*.  Body 2 as
    :func:`tangential_interior_fields`.
    """
    from ..axisymmetric.peaks import peaks as ax_peaks
    from ..axisymmetric.profiles import displacement_ratio, slip_ratio

    if E0_2 is None:
        E0_2, nu_2 = E0, nu
    args = [np.asarray(v, dtype=float) for v in (a, fx, mu, k, nu, E0, c0, E0_2, nu if nu_2 is None else nu_2)]
    shape = np.broadcast_shapes(*(v.shape for v in args), *(g.shape for g in profile.geometry))
    A, FX, MU, K, NU, E, C0, E2, NU2 = (np.broadcast_to(v, shape).ravel() for v in args)
    G = [np.broadcast_to(g, shape).ravel() for g in profile.geometry]
    _check_tangential(K, profile)
    cN = c_N_star(K, NU, E, C0, E2, NU2)
    flat = Indenter(profile.kind, tuple(G), profile.table)
    out = {n: np.empty(A.size, dtype=np.int8 if n == "peak_validity" else float) for n in TANGENTIAL_PEAKS}
    for sel, prof in _profile_groups(flat, G, A.size):
        ux0 = displacement_ratio(slip_ratio(prof, A[sel], FX[sel]), NU[sel], MU[sel])
        found = ax_peaks(prof, a=A[sel], nu=NU[sel], mu=MU[sel], ux0=ux0, method=method, rtol=rtol)
        for name in ("tau_max", "von_mises"):
            out[f"{name}_peak"][sel] = cN[sel] * found[f"{name}_peak"]
            out[f"{name}_peak_x"][sel] = found[f"{name}_peak_r"] / A[sel]
            out[f"{name}_peak_depth"][sel] = found[f"{name}_peak_depth"] / A[sel]
        out["peak_validity"][sel] = found["peak_validity"]
    return {n: v.reshape(shape) for n, v in out.items()}
