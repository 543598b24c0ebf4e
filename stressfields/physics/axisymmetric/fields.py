"""The entry points of the axisymmetric family: every field of a scenario in one call.

``fields`` (monotonic Cattaneo–Mindlin loading) and ``history_fields`` (a tangential displacement
history at constant normal load, docs/theory/axisymmetric.md (A65)-(A77)) take the field names, a
``Profile`` and plain arrays that broadcast against each other, choose the route with
``routes.resolve`` and return ``({name: ndarray}, Route)``.  They own what lies between the kernels
and a scenario: the stick radius (A32)-(A33), the sticking flat punch, the invariants (A60)-(A61)
of the stress tensor, dp/dz, the contact-region flag and the validity flag.  Below the surface
(``fields`` with z > 0) they call ``interior.interior_stress`` and ``interior.interior_dpdz`` and,
under tangential load, add ``interior_tangential.interior_stress_tangential`` and
``interior_dpdz_tangential`` with the same stick radius (docs/theory/interior.md); z = 0 takes the
surface kernels.

Units (as the kernels): lengths (x, y, a, the stick radius) in the profile's length unit; stresses,
von Mises and principal stresses divided by E* and multiplied by ``scale``; dp/dz divided by
E*/length and multiplied by ``dpdz_scale`` (default ``scale``).  With the default ``scale = 1`` the
values are per unit E*; a caller that wants pascals passes E*, one that wants units of the mean
pressure p_m passes E*/p_m (and a E*/p_m for dp/dz in units of p_m/a).  The invariants are formed
from the scaled tensor.  Pure NumPy/SciPy.
"""
from __future__ import annotations

import functools
import math
from typing import Callable, Iterable

import numpy as np

from ..flags import quiet
from ..flags import Validity, validity_flag
from ..invariants import principal_stresses, singular_limits, von_mises
# the stress components and principal stresses are defined in ``physics.names``: the scenario
# declarations read them without importing the kernels
from ..names import PRINCIPAL, STRESS
from . import history as hist
from .displacement import NAMES as DISPLACEMENTS
from .displacement import displacements, has_displacement_closed_form, tangential_displacements
from .interior import interior_dpdz, interior_stress
from .interior_tangential import interior_dpdz_tangential, interior_stress_tangential
from .profiles import Profile, annulus_width
from .routes import Route, resolve, resolve_depth, resolve_interior
from .surface import stick_radius, surface_dpdz, surface_stress

__all__ = ["STRESS", "PRINCIPAL", "INVARIANTS", "FIELDS", "HISTORY_LOADS", "HISTORY_FIELDS", "fields", "history_fields",
           "contact_radius", "validity_flag"]

#: validity code of a point below the surface that the 1-D routes do not resolve
UNRESOLVED = Validity.not_resolved_below_the_surface
#: the invariants of the stress tensor: von Mises (A60), principal stresses, tau_max = (sigma_1 - sigma_3)/2
INVARIANTS = ("von_mises",) + PRINCIPAL + ("tau_max",)
#: fields of a point (they need x and y, and z below the surface)
SPATIAL = STRESS + INVARIANTS + ("dpdz", "region", "validity")
#: everything ``fields`` computes
FIELDS = SPATIAL + DISPLACEMENTS + ("stick_radius",)
#: the loads of a history step (no x, y): stick radius, F_x / (mu F_N), energies / (mu F_N delta)
HISTORY_LOADS = ("stick_radius", "tangential_force", "dissipated_energy", "cycle_energy")
#: everything ``history_fields`` computes
HISTORY_FIELDS = SPATIAL + DISPLACEMENTS + HISTORY_LOADS
#: the fields the validity flag looks at
_VALUED = STRESS + INVARIANTS + ("dpdz",)

# region flag values (flag_meanings of the scenarios' `region`)
OUTSIDE, STICK, SLIP, NO_TRACTION = 0, 1, 2, 3


@quiet
def fields(names: Iterable[str], profile: Profile, x=None, y=None, z=None, *, a, nu, mu, ux0, stick=None,
           method: str = "auto", rtol: float = 1e-10, scale=1.0,
           dpdz_scale=None) -> tuple[dict[str, np.ndarray], Route]:
    """The requested fields on the surface (z = 0) and below it (z > 0) under normal load and
    monotonic Cattaneo–Mindlin tangential load, and the route taken (``routes.resolve_depth``).

    Parameters
    ----------
    names : any of ``FIELDS``: "sigma_xx" ... "sigma_yz" (stresses, eq. 9 + 24-25,
        docs/theory/axisymmetric.md (A14)-(A16), (A34), (A38)-(A41)), "von_mises" (A60),
        "sigma_1" ... "sigma_3" (principal stresses, eigenvalues of the tensor), "tau_max"
        (sigma_1 - sigma_3)/2, "dpdz" (d p_h/dz at z = 0+, (A24)-(A26) + (A53)-(A54)),
        "stick_radius" (A32)-(A33), "region" (int8: 0 outside the contact r > a, 1 stick r < c,
        2 slip, 3 contact without tangential traction, mu = 0 or ux0 = 0; of the surface point
        (x, y), whatever z) and "validity" (int8: 0 every requested value finite, 1 some value
        +-inf, 2 some value NaN; 0 when no valued field is requested).  Below the surface the
        stresses are docs/theory/interior.md (I5)-(I17) plus, under tangential load, (I23), (I33),
        and dpdz (I24)-(I28) plus (I34)-(I35).
    profile : a ``Profile`` (``cone``, ``paraboloid``, ``power_law``, ``flat_punch``, ``tabulated``).
    x, y : surface coordinates (x along the tangential load), length unit of the profile; may be
        None when only "stick_radius" is requested.
    z : depth below the surface (z >= 0, same unit; None: 0).  Where z > 0 every value is finite
        (the edge rings r = a and r = c are singular at z = 0 only).  Under tangential load the 1-D
        route refuses rtol below ``routes.tangential_floor`` (1e-11 for power laws n < 1).
    a : contact radius; nu : Poisson's ratio; mu : coefficient of friction; ux0 : tangential
        rigid-body displacement u_x0 divided by the indentation depth delta.  All broadcast.
    stick : the stick radius c where the load is given as a force (length units, broadcasting;
        ``profiles.stick_radius_of_force``: exact as fx -> 1, where c from ux0 loses digits); None:
        c of ux0 (A32)-(A33).
    method : "auto", "closed" or "quadrature" (``routes.resolve``); rtol : accuracy of the
        quadrature route.
    scale, dpdz_scale : see the module docstring (default: per unit E*).

    A flat punch sticks whole or slides; sticking (c = a with u_x0 > 0 and mu > 0) its traction is
    the sliding one with mu E* delta replaced by G* u_x0 (paper eq. 20; docs/theory/axisymmetric.md
    (A37), (A42)-(A44), (A59)), which the kernels take as c = 0 and mu = (G*/E*) u_x0/delta.  The
    stick radius and the region flag keep c = a.
    """
    names = _known(names, FIELDS)
    if any(n in DISPLACEMENTS for n in names):
        rest = [n for n in names if n not in DISPLACEMENTS]
        out, route = fields(rest, profile, x, y, z, a=a, nu=nu, mu=mu, ux0=ux0, stick=stick, method=method,
                            rtol=rtol, scale=scale, dpdz_scale=dpdz_scale)
        _, c, mu_k = _stick(*(np.asarray(v, dtype=float) for v in (a, nu, mu, ux0)), profile, stick)
        out.update(displacements([n for n in names if n in DISPLACEMENTS], profile, x, y, 0.0 if z is None else z,
                                 a=a, nu=nu, mu=mu, ux0=ux0, c=c, mu_kernel=mu_k, method=_dmethod(profile, method),
                                 rtol=rtol))
        return out, route
    spatial = [n for n in names if n in SPATIAL]
    if z is not None and spatial and np.any(np.asarray(z, dtype=float) > 0.0):
        return _with_depth(names, profile, x, y, z, a=a, nu=nu, mu=mu, ux0=ux0, stick=stick, method=method,
                           rtol=rtol, scale=scale, dpdz_scale=dpdz_scale)
    route = resolve(profile, method, rtol)
    nu, mu, ux0 = (np.asarray(v, dtype=float) for v in (nu, mu, ux0))
    c, c_kernel, mu_kernel = _stick(a, nu, mu, ux0, profile, stick)
    out: dict[str, np.ndarray] = {}
    if "stick_radius" in names:
        out["stick_radius"] = c
    if not spatial:
        return out, route
    # a - c from the slip ratio: the tangential part keeps its relative accuracy as fx -> 0 (A109)
    kw = dict(method=route.kernel, rtol=rtol, width=annulus_width(profile, a, c_kernel, ux0, nu, mu_kernel))
    out.update(_surface(
        spatial, scale, dpdz_scale,
        stress=lambda comps: surface_stress(x, y, a, c_kernel, nu, mu_kernel, profile, components=comps, **kw),
        dpdz=lambda: surface_dpdz(x, y, a, c_kernel, nu, mu_kernel, profile, **kw),
        region=lambda: _region(np.hypot(x, y), a, c, (mu == 0) | (ux0 == 0)),
        singular=lambda tensor, idx: _singular(profile, tensor, idx, x, y, a, nu, mu_kernel,
                                               np.where((mu_kernel > 0) & (c_kernel == 0), mu_kernel, 0.0), scale)))
    if "validity" in names:
        out["validity"] = validity_flag(*(out[n] for n in out if n in _VALUED))
    return out, route


def _dmethod(profile: Profile, method: str) -> str:
    """The displacements' method: "closed" where they have no closed form (cone, power laws other
    than n = 2, tabulated profiles, whose stresses may have one) takes their 1-D route."""
    return "auto" if method == "closed" and not has_displacement_closed_form(profile) else method


def _stick(a, nu, mu, ux0, profile, stick=None):
    """(c, c_kernel, mu_kernel): the stick radius (A32)-(A33) (``stick`` where given, broadcast with
    the rest) and what the kernels take for it.  A sticking flat punch (c = a with u_x0 > 0 and
    mu > 0) carries the sliding traction with mu E* delta replaced by G* u_x0 (A37), (A59): the
    kernels take c = 0, mu = (G*/E*) u_x0/delta."""
    c = stick_radius(a, nu, mu, ux0, profile)
    if stick is not None:
        c = np.where(ux0 == 0.0, c, np.broadcast_arrays(np.asarray(stick, dtype=float), c)[0])
    if profile.kind != "flat_punch":
        return c, c, mu
    stuck = (c == a) & (ux0 > 0) & (mu > 0)
    return c, np.where(stuck, 0.0, c), np.where(stuck, 2.0 * (1.0 - nu) / (2.0 - nu) * ux0, mu)


def _with_depth(names, profile, x, y, z, *, a, nu, mu, ux0, stick, method, rtol, scale, dpdz_scale):
    """``fields`` where some z > 0: the surface fields where z = 0 (the same call as without z, so
    bit for bit the same values), the interior kernels where z > 0; one validity flag."""
    dpdz_scale = scale if dpdz_scale is None else dpdz_scale
    arrays = [np.asarray(v, dtype=float) for v in (x, y, z, a, nu, mu, ux0, scale, dpdz_scale)]
    shape = np.broadcast_shapes(*(v.shape for v in arrays))
    X, Y, Z, A, NU, MU, UX0, SC, DSC = (np.broadcast_to(v, shape) for v in arrays)
    deep = Z > 0.0
    if np.any(~(Z >= 0.0)):
        raise ValueError("z (depth below the surface) must be >= 0 and not NaN")
    _, C, MU_K = (np.broadcast_to(v, shape) for v in _stick(A, NU, MU, UX0, profile, stick))
    loaded = deep & (MU_K > 0.0) & (C < A)
    expo, tangential = getattr(profile, "n", None), bool(np.any(loaded))
    route = resolve_depth(profile, method, rtol, expo, z, tangential=tangential)
    interior_route = resolve_interior(profile, method, rtol, expo, tangential=tangential)
    valued = [n for n in names if n in _VALUED]
    out: dict[str, np.ndarray] = {}
    if not np.all(deep) or any(n in names for n in ("stick_radius", "region")):
        top = [n for n in names if n != "validity" and (n not in _VALUED or not np.all(deep))]
        out, _ = fields(top, profile, x, y, a=a, nu=nu, mu=mu, ux0=ux0, stick=stick, method=method, rtol=rtol,
                        scale=scale, dpdz_scale=dpdz_scale)
    kw = dict(method=interior_route.kernel, rtol=rtol)
    P = [v[deep] for v in (X, Y, Z, A, NU)]
    T = [v[deep] for v in (X, Y, Z, A, C, NU, MU_K)]   # the arguments of the tangential kernels
    # a - c from the slip ratio, as on the surface (A109)
    W = np.broadcast_to(annulus_width(profile, A, C, UX0, NU, MU_K), shape)[deep]
    on = np.flatnonzero(loaded[deep])         # the deep points under tangential load
    below = _surface(valued, SC[deep], DSC[deep],
                     stress=lambda comps: _add(interior_stress(*P, profile, **kw), on, comps,
                                               lambda: interior_stress_tangential(*(v[on] for v in T), profile,
                                                                                  width=W[on], **kw)),
                     dpdz=lambda: _add({"dpdz": interior_dpdz(*P, profile, **kw)}, on, ("dpdz",),
                                       lambda: {"dpdz": interior_dpdz_tangential(*(v[on] for v in T), profile,
                                                                                 width=W[on], **kw)})["dpdz"],
                     region=lambda: None)
    return _merge_depth(out, below, names, valued, deep, shape), route


def _merge_depth(out: dict, below: dict, names, valued, deep: np.ndarray, shape) -> dict:
    """The surface values ``out`` where z = 0 and the interior ones ``below`` where z > 0, with one
    validity flag. Below the surface every exact value is finite, so a non-finite one there is a
    point the routes do not resolve (r or z below ~1e-100 a, docs/theory/interior.md section 6):
    NaN, flagged UNRESOLVED, never an infinity (which the contract keeps for unbounded limits)."""
    for n in valued:
        full = np.empty(shape)
        if n in out:
            full[~deep] = np.broadcast_to(out[n], shape)[~deep]
        full[deep] = np.where(np.isfinite(below[n]), below[n], np.nan)
        out[n] = full
    if "validity" in names:
        flag = validity_flag(*(out[n] for n in valued))
        unresolved = deep & np.any([~np.isfinite(out[n]) for n in valued], axis=0) if valued else deep & False
        out["validity"] = np.where(unresolved, np.int8(UNRESOLVED), flag).astype(np.int8)
    return out


def _add(normal: dict, on: np.ndarray, keys, tangential: Callable[[], dict]) -> dict:
    """The normal part's ``keys`` plus the tangential part at the indices ``on`` (computed only
    if any): the superposition of docs/theory/interior.md (I23), (I33)."""
    out = {k: np.array(normal[k], dtype=float) for k in keys}
    if on.size:
        part = tangential()
        for k in keys:
            out[k][on] += part[k]
    return out


@quiet
def history_fields(names: Iterable[str], profile: Profile, x=None, y=None, z=None, *, a, nu, mu, amplitude,
                   history, step, method: str = "auto", rtol: float = 1e-10, scale=1.0,
                   dpdz_scale=None) -> tuple[dict[str, np.ndarray], Route]:
    """The requested fields after step ``step`` of the tangential displacement history
    u_x0/delta = ``amplitude`` * ``history``, at constant normal load (MDR springs with memory,
    Mindlin–Deresiewicz; docs/theory/axisymmetric.md (A65)-(A77), ``history``), and the route.

    ``names``: any of ``HISTORY_FIELDS``: the surface fields of ``fields`` (the stress tensor
    (A69), its invariants, dp/dz, the region flag with "stick" the zone that does not slip during
    the move into this step and "contact without tangential traction" for mu = 0, amplitude 0 or
    no displacement yet, the validity flag) and the loads "stick_radius" (the current branch's, in
    length units; a before any displacement), "tangential_force" F_x / (mu F_N) (A75),
    "dissipated_energy" (from the start) and "cycle_energy" (of the outermost hysteresis cycle
    closing during the move into this step, at its end or on the way, (A95); 0 where none
    closes), both divided by mu F_N delta (A76).  At mu = 0 the loads are
    the limits mu -> 0+.

    ``history``: the values u_x0/delta, in order, from the unloaded start; ``step``: integer
    indices into it.  a, nu, mu, amplitude, step, x, y, z, scale and dpdz_scale broadcast (x, y may
    be None when no surface field is requested).  Units, ``method``, ``rtol``, ``scale`` and
    ``dpdz_scale`` as for ``fields``.  The outputs have the broadcast shape of all arguments.

    ``z``: depth below the surface (z >= 0; None: 0).  Where z > 0 the fields are the normal
    interior part plus the same superposition (A69) of the c-terms as on the surface, each term
    w_k times the Cattaneo–Mindlin interior field with stick radius c_k (docs/theory/interior.md
    (I23), (I33); dp/dz (I34)-(I35)), all finite; the route and its accuracy are those of
    ``fields`` below the surface (closed forms: relative error at most 1e-12 of |value|
    everywhere the value is finite, far field and next to edges included).  z = 0 is the surface
    computation, bit for bit; "region" and the loads do not depend on z.
    """
    names = _known(names, HISTORY_FIELDS)
    if any(n in DISPLACEMENTS for n in names):
        rest = [n for n in names if n not in DISPLACEMENTS]
        out, route = history_fields(rest, profile, x, y, z, a=a, nu=nu, mu=mu, amplitude=amplitude, history=history,
                                    step=step, method=method, rtol=rtol, scale=scale, dpdz_scale=dpdz_scale)
        out.update(_history_displacements([n for n in names if n in DISPLACEMENTS], profile, x, y, z, a=a, nu=nu,
                                          mu=mu, amplitude=amplitude, history=history, step=step,
                                          method=_dmethod(profile, method), rtol=rtol))
        return out, route
    if z is not None and any(n in SPATIAL for n in names) and np.any(np.asarray(z, dtype=float) > 0.0):
        return _history_with_depth(names, profile, x, y, z, a=a, nu=nu, mu=mu, amplitude=amplitude,
                                   history=history, step=step, method=method, rtol=rtol, scale=scale,
                                   dpdz_scale=dpdz_scale)
    route = resolve(profile, method, rtol)
    history = tuple(float(v) for v in np.asarray(history, dtype=float).ravel())
    sts = _memory(history)
    spatial = [n for n in names if n in SPATIAL]
    arrays = {k: np.asarray(v, dtype=float) for k, v in (("nu", nu), ("mu", mu), ("amplitude", amplitude))}
    if spatial:
        arrays.update(x=np.asarray(x, dtype=float), y=np.asarray(y, dtype=float))
    arrays["a"] = np.asarray(a, dtype=float)
    arrays["step"] = np.asarray(step, dtype=np.int64)
    arrays["scale"] = np.asarray(scale, dtype=float)
    arrays["dpdz_scale"] = arrays["scale"] if dpdz_scale is None else np.asarray(dpdz_scale, dtype=float)
    shape = np.broadcast_shapes(*(np.shape(v) for v in arrays.values()))
    flat = {k: np.broadcast_to(v, shape).ravel() for k, v in arrays.items()}
    size = int(np.prod(shape, dtype=np.int64))
    results = {n: np.empty(size, dtype=np.int8 if n == "region" else float) for n in names if n != "validity"}
    valued = [n for n in spatial if n != "validity"]
    kw = dict(method=route.kernel, rtol=rtol)
    for s in np.unique(flat["step"]):
        idx = np.flatnonzero(flat["step"] == s)
        P = {k: v[idx] for k, v in flat.items()}
        A, NU, MU = P["a"], P["nu"], P["mu"]
        terms = [(lam * P["amplitude"], w) for lam, w in sts[int(s)].terms()]
        terms = terms if np.any(P["amplitude"] > 0) else []
        part = _history_loads(names, A, NU, MU, P["amplitude"], profile, terms, history, int(s))
        if valued:
            part.update(_surface(
                valued, P["scale"], P["dpdz_scale"],
                stress=lambda comps: hist.history_stress(P["x"], P["y"], A, NU, MU, profile, terms,
                                                         components=comps, **kw),
                dpdz=lambda: hist.history_dpdz(P["x"], P["y"], A, NU, MU, profile, terms, **kw),
                region=lambda: _region(np.hypot(P["x"], P["y"]), A,
                                       hist.current_stick_radius(terms, A, NU, MU, profile),
                                       (MU == 0) | (P["amplitude"] == 0) | (not terms)),
                singular=lambda tensor, i: _singular(profile, tensor, i, P["x"], P["y"], A, NU, MU,
                                                     _gross_weight(terms, A, NU, MU, profile) * MU, P["scale"])))
        for n, v in part.items():
            results[n][idx] = v
    out = {n: v.reshape(shape) for n, v in results.items()}
    if "validity" in names:
        out["validity"] = validity_flag(*(out[n] for n in out if n in _VALUED))
    return out, route


def _history_with_depth(names, profile, x, y, z, *, a, nu, mu, amplitude, history, step, method, rtol, scale,
                        dpdz_scale):
    """``history_fields`` where some z > 0: the surface call (without z) where z = 0 and for the
    region and the loads, the interior superposition where z > 0; one validity flag (as
    ``_with_depth``: a non-finite value below the surface is ``UNRESOLVED``)."""
    if profile.kind == "flat_punch":
        # a sticking punch carries a traction the c-terms do not describe (A37); the surface route
        # has no history for it either
        raise ValueError("history_fields below the surface: the flat punch has no history route")
    dpdz_scale = scale if dpdz_scale is None else dpdz_scale
    keys = ("x", "y", "z", "a", "nu", "mu", "amplitude", "scale", "dpdz_scale")
    arrays = dict(zip(keys, (np.asarray(v, dtype=float) for v in (x, y, z, a, nu, mu, amplitude, scale,
                                                                   dpdz_scale))))
    arrays["step"] = np.asarray(step, dtype=np.int64)
    shape = np.broadcast_shapes(*(v.shape for v in arrays.values()))
    full = {k: np.broadcast_to(v, shape) for k, v in arrays.items()}
    if np.any(~(full["z"] >= 0.0)):
        raise ValueError("z (depth below the surface) must be >= 0 and not NaN")
    deep = full["z"] > 0.0
    valued = [n for n in names if n in _VALUED]
    top = [n for n in names if n != "validity" and (n not in _VALUED or not np.all(deep))]
    out: dict[str, np.ndarray] = {}
    if top:
        out, _ = history_fields(top, profile, x, y, a=a, nu=nu, mu=mu, amplitude=amplitude, history=history,
                                step=step, method=method, rtol=rtol, scale=scale, dpdz_scale=dpdz_scale)
        out = {n: v if n in _VALUED else np.array(np.broadcast_to(v, shape)) for n, v in out.items()}
    P = {k: v[deep] for k, v in full.items()}
    terms = _deep_terms(P, profile, _memory(tuple(float(v) for v in np.asarray(history, dtype=float).ravel())))
    tangential = any(w != 0.0 for _, w, on in terms if on.size)
    route = resolve_depth(profile, method, rtol, getattr(profile, "n", None), z, tangential=tangential)
    kw = dict(method=resolve_interior(profile, method, rtol, getattr(profile, "n", None),
                                      tangential=tangential).kernel, rtol=rtol)
    at = (P["x"], P["y"], P["z"], P["a"])

    def stress(comps):
        return _add_terms(interior_stress(*at, P["nu"], profile, **kw), comps, terms, lambda on, c: (
            interior_stress_tangential(*(v[on] for v in at), c, P["nu"][on], P["mu"][on], profile, **kw)))

    def dpdz():
        return _add_terms({"dpdz": interior_dpdz(*at, P["nu"], profile, **kw)}, ("dpdz",), terms, lambda on, c: {
            "dpdz": interior_dpdz_tangential(*(v[on] for v in at), c, P["nu"][on], P["mu"][on], profile, **kw)})
    below = _surface(valued, P["scale"], P["dpdz_scale"], stress=stress, dpdz=lambda: dpdz()["dpdz"],
                     region=lambda: None)
    return _merge_depth(out, below, names, valued, deep, shape), route


def _history_displacements(names, profile, x, y, z, *, a, nu, mu, amplitude, history, step, method, rtol):
    """Displacements / delta after step ``step`` of the history: the normal part plus the same
    weighted sum (A69) of Cattaneo–Mindlin terms as the stresses (``_deep_terms``), on the surface
    and below it (docs/theory/interior.md (I42)-(I43))."""
    if profile.kind == "flat_punch":
        raise ValueError("history_fields: the flat punch has no history route")
    keys = ("x", "y", "z", "a", "nu", "mu", "amplitude")
    arrays = dict(zip(keys, (np.asarray(0.0 if v is None else v, dtype=float)
                             for v in (x, y, z, a, nu, mu, amplitude))))
    arrays["step"] = np.asarray(step, dtype=np.int64)
    shape = np.broadcast_shapes(*(v.shape for v in arrays.values()))
    P = {k: np.broadcast_to(v, shape).ravel() for k, v in arrays.items()}
    at = dict(a=P["a"], nu=P["nu"], method=method, rtol=rtol)
    out = displacements(names, profile, P["x"], P["y"], P["z"], mu=0.0, ux0=0.0, c=P["a"], mu_kernel=0.0, **at)
    out = {n: np.array(v, dtype=float) for n, v in out.items()}
    sts = _memory(tuple(float(v) for v in np.asarray(history, dtype=float).ravel()))
    for c, w, on in _deep_terms(P, profile, sts):
        part = tangential_displacements(names, profile, P["x"][on], P["y"][on], P["z"][on], a=P["a"][on], c=c,
                                        nu=P["nu"][on], mu_kernel=P["mu"][on], method=method, rtol=rtol)
        for n in names:
            out[n][on] += w * part[n]
    return {n: v.reshape(shape) for n, v in out.items()}


def _deep_terms(P: dict, profile: Profile, sts: list) -> list[tuple[np.ndarray, float, np.ndarray]]:
    """The c-terms of the points ``P`` (flat arrays, each point its own step): (c, w, on) with the
    stick radii c of the points ``on`` (indices into P) that carry the term under tangential load
    (mu > 0, c < a).  Consecutive terms with the same radii (every term beyond gross slip has
    c = 0) are merged into one of their net weight, so each distinct field is computed once."""
    out = []
    for s in np.unique(P["step"]):
        idx = np.flatnonzero(P["step"] == s)
        A, NU, MU = (P[k][idx] for k in ("a", "nu", "mu"))
        terms = [(lam * P["amplitude"][idx], w) for lam, w in sts[int(s)].terms()]
        merged: list[list] = []
        for (_, w), c in zip(terms, hist.stick_radii(terms, A, NU, MU, profile)):
            if merged and np.array_equal(merged[-1][0], c):
                merged[-1][1] += w
            else:
                merged.append([c, w])
        for c, w in merged:
            live = (MU > 0.0) & (c < A)
            if w != 0.0 and np.any(live):
                out.append((c[live], float(w), idx[live]))
    return out


def _add_terms(normal: dict, keys, terms, tangential: Callable) -> dict:
    """The normal part's ``keys`` plus sum_k w_k times the tangential part with stick radius c_k
    at its points (``_deep_terms``; ``tangential(on, c)``): (A69) with docs/theory/interior.md
    (I23), (I33).  One term of weight 1 adds the kernel's values unchanged, exactly as ``_add``."""
    out = {k: np.array(normal[k], dtype=float) for k in keys}
    for c, w, on in terms:
        part = tangential(on, c)
        for k in keys:
            out[k][on] += w * part[k]
    return out


def contact_radius(profile: Profile, delta) -> np.ndarray:
    """Contact radius a at the indentation depth ``delta`` (eq. 7, delta = g(a),
    docs/theory/axisymmetric.md (A3)), element by element."""
    return np.vectorize(profile.contact_radius, otypes=[float])(delta)


# -- shared pieces -------------------------------------------------------------------------------

def _known(names: Iterable[str], allowed: tuple[str, ...]) -> list[str]:
    names = list(names)
    unknown = [n for n in names if n not in allowed]
    if unknown:
        raise ValueError(f"unknown field(s) {unknown!r}: use some of {', '.join(allowed)}")
    return names


def _surface(names: list[str], scale, dpdz_scale, *, stress: Callable[[tuple[str, ...]], dict],
             dpdz: Callable[[], np.ndarray], region: Callable[[], np.ndarray],
             singular: Callable | None = None) -> dict[str, np.ndarray]:
    """The stress block (the tensor times ``scale``, von Mises (A60), principal stresses, tau_max), dp/dz
    times ``dpdz_scale`` (default ``scale``) and the region flag, each computed only if requested;
    ``stress(components)`` gives the tensor / E*, ``dpdz()`` dp/dz / (E*/length).  Where a
    component is infinite the invariants are the limits of ``singular(tensor, flat indices)`` ->
    (lead, rest), see ``_singular`` (A97)."""
    out: dict[str, np.ndarray] = {}
    want = [n for n in names if n in STRESS]
    inv = [n for n in INVARIANTS if n in names]
    if inv:
        want = list(STRESS)
    if want:
        sig = stress(tuple(n.removeprefix("sigma_") for n in want))
        tensor = {f"sigma_{k}": v * scale for k, v in sig.items()}
        out.update((n, tensor[n]) for n in names if n in STRESS)
        if "von_mises" in names:
            out["von_mises"] = von_mises(*(tensor[s] for s in STRESS))
        if any(n in names for n in PRINCIPAL + ("tau_max",)):
            s1, s2, s3 = principal_stresses(*(tensor[s] for s in STRESS))
            out.update((n, v) for n, v in zip(PRINCIPAL, (s1, s2, s3)) if n in names)
            if "tau_max" in names:
                out["tau_max"] = 0.5 * (s1 - s3)
        if inv and singular is not None:
            shape = np.broadcast_shapes(*(np.shape(tensor[s]) for s in STRESS))
            infinite = np.zeros(shape, dtype=bool)
            for s in STRESS:
                infinite |= np.isinf(tensor[s])
            idx = np.flatnonzero(infinite)
            if idx.size:
                lead, rest = singular(tensor, idx)
                vm, pr = singular_limits(lead, rest)
                for n, v in zip(INVARIANTS, (vm,) + pr + (_tau_limit(vm, rest),)):
                    if n in inv:
                        out[n] = np.array(np.broadcast_to(out[n], shape))
                        out[n].flat[idx] = v
    if "dpdz" in names:
        out["dpdz"] = dpdz() * (scale if dpdz_scale is None else dpdz_scale)
    if "region" in names:
        out["region"] = region()
    return out


def _tau_limit(vm, rest) -> np.ndarray:
    """tau_max at a singular point from the limit ``vm`` of von Mises (``singular_limits``) and the
    bounded remainder ``rest``: +inf where the leading tensor has a deviatoric part (vm = +inf: its
    largest and smallest eigenvalues differ), half the eigenvalue spread of ``rest`` where it is
    isotropic (vm finite), NaN where the limit is unknown (vm NaN)."""
    tau = np.where(np.isinf(vm), np.inf, np.nan)
    known = np.flatnonzero(np.isfinite(vm))
    if known.size:
        ev = np.linalg.eigvalsh(rest[known])
        tau[known] = 0.5 * (ev[:, -1] - ev[:, 0])
    return tau


def _singular(profile: Profile, tensor, idx, x, y, a, nu, mu_kernel, mu_lead, scale):
    """(lead, rest) of the stress tensor lam * lead + rest + o(1), lam -> +inf, at the points
    ``idx`` (flat indices into the tensor's shape) where a component is infinite; NaN where the
    limit is not known (docs/theory/axisymmetric.md (A97)).

    * Conical or sharper tip r = 0 (g' ~ B u^m, m <= 0): the pressure p ~ lam grows, and
      sigma_rr, sigma_phiphi, sigma_zz -> -p (rho_r, rho_phi, 1) with rho_r = 1 - (1-2nu)/(m+2),
      rho_phi = 2 nu + (1-2nu)/(m+2) (the surface relation sigma_rr = -p + (1-2nu)/r^2 int_0^r p s
      ds with p ~ r^m, or ln r for m = 0); in gross slip sigma_xz -> -mu_lead p.  For m < 0 in
      gross slip the in-plane block is not isotropic and the limit depends on the direction
      (unknown).  At nu = 1/2 the normal part is exactly hydrostatic and the remainder is the
      tangential part, sigma_xz alone (the stick zone carries no in-plane tangential stress).
    * Flat-punch edge r = a (from inside, at the point's own angle): p ~ 1/sqrt(a^2 - r^2) and
      (rr, phiphi, zz) -> -p (1, 2 nu, 1), sigma_xz -> -mu p; remainder (P q/a)(1, -1, 0), P the
      depth/pi, q = 1 - 2 nu (A12), (A29)."""
    shape = np.broadcast_shapes(*(np.shape(tensor[s]) for s in STRESS))
    X, Y, A, NU, MU, ML, SC = (np.broadcast_to(np.asarray(v, dtype=float), shape).ravel()[idx]
                               for v in (x, y, a, nu, mu_kernel, mu_lead, scale))
    XZ = np.broadcast_to(tensor["sigma_xz"], shape).ravel()[idx]
    r = np.hypot(X, Y)
    n = idx.size
    lead = np.full((n, 3, 3), np.nan)
    rest = np.full((n, 3, 3), np.nan)
    q = 1.0 - 2.0 * NU
    if profile.kind == "flat_punch":
        edge = r == A
        c, s = np.where(edge, X / np.where(edge, A, 1.0), 0.0), np.where(edge, Y / np.where(edge, A, 1.0), 0.0)
        block = np.zeros((n, 3, 3))
        block[:, 0, 0], block[:, 1, 1], block[:, 2, 2] = c * c + 2 * NU * s * s, s * s + 2 * NU * c * c, 1.0
        block[:, 0, 1] = block[:, 1, 0] = q * c * s
        block[:, 0, 2] = block[:, 2, 0] = np.where(MU > 0, MU, 0.0)
        k = SC * q * profile.closed[2] / (math.pi * A)
        tail = np.zeros((n, 3, 3))
        tail[:, 0, 0], tail[:, 1, 1] = k * (c * c - s * s), k * (s * s - c * c)
        tail[:, 0, 1] = tail[:, 1, 0] = 2.0 * k * c * s
        lead[edge], rest[edge] = -block[edge], tail[edge]
        return lead, rest
    m = getattr(profile, "tip_exponent", 1.0)
    tip = (r == 0.0) & (m <= 0.0) & ((m == 0.0) | (ML == 0.0))
    rho_r, rho_f = 1.0 - q / (m + 2.0), 2.0 * NU + q / (m + 2.0)
    block = np.zeros((n, 3, 3))
    block[:, 0, 0], block[:, 1, 1], block[:, 2, 2] = rho_r, rho_f, 1.0
    block[:, 0, 2] = block[:, 2, 0] = ML
    lead[tip] = -math.copysign(1.0, profile.tip_coefficient) * block[tip]
    known = tip & (NU == 0.5) & (ML == 0.0) & np.isfinite(XZ)
    tail = np.zeros((n, 3, 3))
    tail[:, 0, 2] = tail[:, 2, 0] = XZ
    rest[known] = tail[known]
    return lead, rest


def _gross_weight(terms, a, nu, mu, profile) -> np.ndarray:
    """Net weight of the history's c-terms in gross slip (stick radius 0): sigma_xz at a conical
    tip grows like -mu times it times the pressure."""
    shape = np.broadcast_shapes(*(np.shape(v) for v in (a, nu, mu)))
    out = np.zeros(shape)
    for (_, w), c in zip(terms, hist.stick_radii(terms, a, nu, mu, profile)):
        out = out + np.where(c == 0.0, w, 0.0)
    return out


def _region(r, a, c, free) -> np.ndarray:
    """Contact region flag: OUTSIDE r > a, STICK r < c, SLIP c <= r <= a; NO_TRACTION r <= a where
    ``free`` (no tangential traction)."""
    region = np.where(r > a, OUTSIDE, np.where(r < c, STICK, SLIP)).astype(np.int8)
    return np.where(np.asarray(free) & (r <= a), np.int8(NO_TRACTION), region)


@functools.lru_cache(maxsize=32)
def _memory(history: tuple) -> list:
    """Spring memory of every step of a history (``history.states``)."""
    return hist.states(history)


@functools.lru_cache(maxsize=256)
def _energy(history: tuple, a: float, nu: float, mu: float, profile: Profile, amplitude: float) -> np.ndarray:
    return hist.dissipated_energy(history, a, nu, mu, profile, scale=amplitude)


@functools.lru_cache(maxsize=256)
def _cycle(history: tuple, a: float, nu: float, mu: float, profile: Profile, amplitude: float) -> np.ndarray:
    return hist.cycle_energy(history, a, nu, mu, profile, scale=amplitude)


def _history_loads(names, a, nu, mu, amplitude, profile, terms, history, step) -> dict[str, np.ndarray]:
    """The loads of one step on 1-D arrays a, nu, mu, amplitude: stick radius, F_x / (mu F_N) and
    the energies / (mu F_N delta), the energy once per distinct (a, nu, mu, amplitude)."""
    out = {}
    if "stick_radius" in names:
        out["stick_radius"] = hist.current_stick_radius(terms, a, nu, mu, profile)
    if "tangential_force" in names:
        out["tangential_force"] = hist.tangential_force(terms, a, nu, mu, profile)
    want = [n for n in ("dissipated_energy", "cycle_energy") if n in names]
    if want:
        combos = np.stack([a, nu, mu, amplitude], axis=-1)
        uniq, inverse = np.unique(combos, axis=0, return_inverse=True)
        total = np.empty(len(uniq))
        cycle = np.zeros(len(uniq))
        for i, (ai, nui, mui, ampi) in enumerate(uniq):
            args = (history, float(ai), float(nui), float(mui), profile, float(ampi))
            if "dissipated_energy" in names:
                total[i] = _energy(*args)[step]
            if "cycle_energy" in names:
                cycle[i] = _cycle(*args)[step]
        inverse = inverse.ravel()
        if "dissipated_energy" in names:
            out["dissipated_energy"] = total[inverse]
        if "cycle_energy" in names:
            out["cycle_energy"] = cycle[inverse]
    return out
