"""The entry points of the graded family: one call per scenario kind, returning the requested fields.

``normal_fields``, ``adhesive_fields`` and ``tangential_fields`` take the field names, an
:class:`~.indenter.Indenter` and plain arrays that broadcast against each other (numpy rules),
choose the route with :func:`~.routes.resolve` (closed forms of the paper, or the quadrature of the
MDR rules, looped over the profiles of a swept geometry) and return ``{name: ndarray}``.  Radii
``a``, ``r`` are absolute lengths; units are any consistent system.  A material argument that a
requested field does not need may be left ``None``.
"""
from __future__ import annotations

from typing import Sequence

import numpy as np

from . import adhesive, normal, tangential
from ._validate import check_mode
from .indenter import Indenter, at_centre
from .material import c_N_star
from .profiles import kappa
from .routes import QUADRATURE, resolve

__all__ = ["NORMAL", "ADHESIVE", "TANGENTIAL", "normal_fields", "adhesive_fields", "tangential_fields"]

NORMAL = ("kappa", "depth", "normal_force", "pressure", "uz")
ADHESIVE = ("depth", "normal_force", "pressure", "critical_radius", "critical_depth", "critical_force")
TANGENTIAL = ("stick_radius", "tangential_displacement", "max_tangential_displacement", "force_ratio",
              "normal_force", "shear_traction")
_MODES = ("fixed_load", "fixed_grips")


def _quadrature(profile: Indenter, method: str, rtol: float, names: Sequence[str], known: tuple) -> bool:
    unknown = [n for n in names if n not in known]
    if unknown:
        raise ValueError(f"unknown field(s) {unknown!r}: use some of {', '.join(known)}")
    return resolve(profile.kind, method, rtol)[0] == QUADRATURE


def _placer(rho):
    """at(x, a) -> the kernels' point arguments {r, a, rho} for a point x that is r/a where ``rho``
    is given (the closures then carry x = rho in place of r), else the absolute r."""
    if rho is None:
        return lambda x, a: dict(r=x, a=a)
    return lambda x, a: dict(r=None, a=a, rho=x)


def normal_fields(names: Sequence[str], profile: Indenter, *, a, r=0.0, k, nu=None, E0=None, c0=None,
                  method: str = "auto", rtol: float = 1e-10, rho=None) -> dict[str, np.ndarray]:
    """Non-adhesive normal contact of a rigid indenter: fields among :data:`NORMAL`.

    kappa = g(a)/f(a) (docs/theory/graded.md (G13)), depth d(a) (G15), normal_force F_N(a) (G16),
    pressure p(r; a) (G17)-(G18; +inf at r = 0 where n + k <= 1) and uz = u_z(r; a) (G20)-(G21).
    ``rho = r/a`` may be given instead of ``r``: the kernels then work in units of a, so the edge
    distance 1 - r/a is exact (forming r = rho a would round it).
    """
    if not names:
        return {}
    mat = dict(k=k, nu=nu, E0=E0, c0=c0)
    at, x = _placer(rho), (r if rho is None else rho)
    if not _quadrature(profile, method, rtol, names, NORMAL):
        n, A_n = profile.power()
        closed = {
            "kappa": lambda: kappa(n, k) + 0.0 * a,
            "depth": lambda: normal.depth(a, k=k, n=n, A_n=A_n),
            "normal_force": lambda: normal.normal_force(a, **mat, n=n, A_n=A_n),
            "pressure": lambda: normal.pressure(r, a, **mat, n=n, A_n=A_n, rho=rho),
            "uz": lambda: normal.surface_displacement(r, a, k=k, n=n, A_n=A_n, rho=rho),
        }
        return {name: closed[name]() for name in names}
    quad = {
        "kappa": lambda prof, a, k, **_: normal.depth_quad(a, prof, k=k, rtol=rtol) / prof.f(a),
        "depth": lambda prof, a, k, **_: normal.depth_quad(a, prof, k=k, rtol=rtol),
        "normal_force": lambda prof, r, a, **m: normal.normal_force_quad(a, prof, **m, rtol=rtol),
        "pressure": lambda prof, r, a, **m: at_centre(
            r, a, prof, m["k"], lambda rr: normal.pressure_quad(profile=prof, **at(rr, a), **m, rtol=rtol), np.inf),
        "uz": lambda prof, r, a, k, **_: normal.surface_displacement_quad(profile=prof, **at(r, a), k=k, rtol=rtol),
    }
    return {name: profile.each(quad[name], r=x, a=a, **mat) for name in names}


def adhesive_fields(names: Sequence[str], profile: Indenter, *, a=None, r=0.0, k, nu, E0, c0, delta_gamma,
                    mode="fixed_load", method: str = "auto", rtol: float = 1e-10, rho=None) -> dict[str, np.ndarray]:
    """Adhesive (JKR-type) contact of a rigid indenter: fields among :data:`ADHESIVE`.

    depth (docs/theory/graded.md (G22)), normal_force (G23), pressure (G24; -inf at r = a) at contact
    radius ``a``; the pull-off point critical_radius, critical_depth, critical_force (G26)-(G29), by
    root finding on the MDR rules on the quadrature route (G42), for each ``mode`` ("fixed_load" or
    "fixed_grips"; an array of them broadcasts).  NaN where no critical point exists.  ``rho = r/a``
    may be given instead of ``r`` (as in :func:`normal_fields`).
    """
    quad = _quadrature(profile, method, rtol, names, ADHESIVE)
    mat = dict(k=k, nu=nu, E0=E0, c0=c0, delta_gamma=delta_gamma)
    at, x = _placer(rho), (r if rho is None else rho)
    out = {}
    if quad:
        fns = {"depth": lambda prof, r, a, **m: adhesive.depth_quad(a, prof, **m, rtol=rtol),
               "normal_force": lambda prof, r, a, **m: adhesive.normal_force_quad(a, prof, **m, rtol=rtol),
               "pressure": lambda prof, r, a, **m: at_centre(
                   r, a, prof, m["k"], lambda rr: adhesive.pressure_quad(profile=prof, **at(rr, a), **m, rtol=rtol),
                   np.inf)}
        out.update({n: profile.each(fns[n], r=x, a=a, **mat) for n in names if n in fns})
    elif set(names) & {"depth", "normal_force", "pressure"}:
        n, A_n = profile.power()
        fns = {"depth": lambda: adhesive.depth(a, **mat, n=n, A_n=A_n),
               "normal_force": lambda: adhesive.normal_force(a, **mat, n=n, A_n=A_n),
               "pressure": lambda: adhesive.pressure(r, a, **mat, n=n, A_n=A_n, rho=rho)}
        out.update({name: fns[name]() for name in names if name in fns})
    crit = ADHESIVE[3:]
    if set(crit) & set(names):
        mode = np.asarray(mode)
        for m in np.unique(mode):
            check_mode(str(m))
        state = None
        for m in _MODES:              # one pass per loading condition present, merged by `mode`
            if not np.any(mode == m):
                continue
            if quad:
                part = profile.each(lambda prof, **kw: adhesive.critical_state_search(prof, mode=m, rtol=rtol, **kw),
                                    **mat)
            else:
                n, A_n = profile.power()
                part = adhesive.critical_state_or_nan(n=n, A_n=A_n, mode=m, **mat)
            state = part if state is None else tuple(np.where(mode == m, s, p) for s, p in zip(part, state))
        out.update({name: v for name, v in zip(crit, state) if name in names})
    return out


def tangential_fields(names: Sequence[str], profile: Indenter, *, a, r=0.0, fx=0.0, delta_x=0.0, mu=None, k,
                      nu=None, E0=None, c0=None, E0_2=None, nu_2=None, require_decoupled: bool = True,
                      method: str = "auto", rtol: float = 1e-10, rho=None) -> dict[str, np.ndarray]:
    """Cattaneo-Mindlin partial slip of two graded bodies: fields among :data:`TANGENTIAL`.

    Body 2 as in :mod:`.tangential` (``E0_2=None`` identical, ``inf`` rigid).  stick_radius c/a
    (docs/theory/graded.md (G33); exactly 0 at ``fx`` = F_x/(mu F_N) = 1), tangential_displacement
    and max_tangential_displacement (G34), force_ratio F_x/(mu F_N) under the imposed ``delta_x``
    (G35), normal_force of the pair (G16), shear_traction (G32): in the stick zone the one integral
    (G45)-(G48) on both routes (finite at r = 0 also where n + k <= 1), +inf only at an unbounded
    centre in gross slip.  ``rho = r/a`` may be given instead of ``r`` (as in :func:`normal_fields`).
    """
    if not names:           # (a block holding only flags may lack the geometry)
        return {}
    if E0_2 is None:        # identical bodies, said explicitly: the quadrature kernels have no such default
        E0_2, nu_2 = E0, nu
    pair = dict(k=k, nu=nu, E0=E0, E0_2=E0_2, nu_2=nu_2)
    pk = dict(pair, require_decoupled=require_decoupled)
    at, x = _placer(rho), (r if rho is None else rho)
    if not _quadrature(profile, method, rtol, names, TANGENTIAL):
        n, A_n = profile.power()

        def dmax():
            return tangential.max_tangential_displacement(a, mu=mu, n=n, A_n=A_n, **pk)

        closed = {
            "stick_radius": lambda: tangential.stick_radius(a, fx, k=k, n=n) / a,
            "tangential_displacement": lambda: tangential.tangential_displacement(a, fx, mu=mu, n=n, A_n=A_n, **pk),
            "max_tangential_displacement": dmax,
            "force_ratio": lambda: tangential.force_ratio_from_displacement(np.minimum(delta_x / dmax(), 1.0),
                                                                            k=k, n=n),
            "normal_force": lambda: tangential.normal_force(a, c0=c0, n=n, A_n=A_n, **pair),
            "shear_traction": lambda: tangential.shear_traction(r, a, fx, mu=mu, c0=c0, n=n, A_n=A_n, rho=rho, **pk),
        }
        return {name: closed[name]() for name in names}

    def stick(prof, a, fx, k):
        # c/a is independent of the elastic constants (nominal ones here); the bisection resolves it
        # only to ~eps^(1/(n+k+1)) near gross slip, so fx = 1 is set to c = 0 exactly
        c = tangential.stick_radius_quad(a, fx, prof, k=k, nu=0.0, E0=1.0, c0=1.0, rtol=rtol)
        return np.where(fx >= 1.0, 0.0, c)

    def shear(prof, r, a, fx, mu, c0, **m):
        mat = dict(m, c0=c0)
        k = np.asarray(m["k"], float)
        sc, D = tangential.slip_width_quad(a, fx, prof, k=k, rtol=rtol)
        rel, e = (r, 1.0 - r) if rho is not None else (r / a, (a - r) / a)
        stick = rel < sc
        # stick zone: the one integral (G45) at r/a, never p(r; a) - p(r; c) (error ~ rtol/F)
        J = tangential.stick_zone_integral_quad(np.where(stick, rel, 0.0), sc, D, a, prof, k=k, rtol=rtol,
                                                one_minus_rho=np.where(stick, e, 1.0))
        tau_stick = mu * c_N_star(**mat) * a ** k / np.pi * J
        # slip annulus and gross slip: mu p(r; a); +inf at an unbounded centre in gross slip (c = 0)
        # (stick points are moved to the edge r = a, where p = 0 costs nothing)
        r_slip = np.where(stick, 1.0 if rho is not None else a, r)
        tau_slip = mu * at_centre(r_slip, a, prof, k, lambda rr: normal.pressure_quad(
            profile=prof, **at(rr, a), **mat, rtol=rtol), np.inf)
        return np.where(stick, tau_stick, tau_slip)

    quad = {
        "stick_radius": lambda prof, a, fx, k, **_: stick(prof, a, fx, k) / a,
        "tangential_displacement": lambda prof, a, fx, mu, k, nu, E0, E0_2, nu_2, **_:
            tangential.tangential_displacement_quad(a, fx, prof, mu=mu, k=k, nu=nu, E0=E0, E0_2=E0_2, nu_2=nu_2,
                                                    require_decoupled=require_decoupled, rtol=rtol),
        "max_tangential_displacement": lambda prof, a, mu, k, nu, E0, E0_2, nu_2, **_:
            tangential.max_tangential_displacement_quad(a, prof, mu=mu, k=k, nu=nu, E0=E0, E0_2=E0_2, nu_2=nu_2,
                                                        require_decoupled=require_decoupled, rtol=rtol),
        "force_ratio": lambda prof, a, delta_x, mu, k, nu, E0, E0_2, nu_2, **_:
            tangential.force_ratio_quad(a, delta_x, prof, mu=mu, k=k, nu=nu, E0=E0, E0_2=E0_2, nu_2=nu_2,
                                        require_decoupled=require_decoupled, rtol=rtol),
        "normal_force": lambda prof, a, c0, k, nu, E0, E0_2, nu_2, **_:
            normal.normal_force_quad(a, prof, c0=c0, k=k, nu=nu, E0=E0, E0_2=E0_2, nu_2=nu_2, rtol=rtol),
        "shear_traction": lambda prof, r, a, fx, mu, c0, delta_x, **m: shear(prof, r, a, fx, mu, c0, **m),
    }
    return {name: profile.each(quad[name], r=x, a=a, fx=fx, delta_x=delta_x, mu=mu, c0=c0, **pair)
            for name in names}
