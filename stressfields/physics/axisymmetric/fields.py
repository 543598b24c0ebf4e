"""The entry points of the axisymmetric family: every field of a scenario in one call.

``fields`` (monotonic Cattaneo–Mindlin loading) and ``history_fields`` (a tangential displacement
history at constant normal load, docs/theory/axisymmetric.md (A65)-(A77)) take the field names, a
``Profile`` and plain arrays that broadcast against each other, choose the route with
``routes.resolve`` and return ``({name: ndarray}, Route)``.  Both are one pipeline, because a
monotonic load is a history of one term (``loading``):

1. load terms: the points grouped by the c-terms they share (``loading.Monotonic``: one term of
   weight 1, the stick radius (A32)-(A33), the sticking flat punch; ``loading.History``: per step
   its memory terms, Mindlin–Deresiewicz) and the loads that do not depend on the point (stick
   radius; a history's force and energies);
2. surface (z = 0) or interior (z > 0): on the surface the normal part and the terms in one
   kernel call per group (``history.history_stress``, ``history.history_dpdz``, which for one term
   of weight 1 are ``surface.surface_stress`` and ``surface.surface_dpdz``); below it the normal
   interior field (``interior``) plus each term's tangential interior field
   (``interior_tangential``, docs/theory/interior.md (I23), (I33)-(I35));
3. the stress tensor (and where a component is infinite, a ``Singular``), dp/dz, the
   contact-region flag and the displacements (``displacement``: the normal part plus the terms,
   (I36)-(I44));
4. one merge of the surface and interior values, and one validity flag;
5. the invariants (A60)-(A61) of the tensor, with the limits of ``singular_limits`` at the
   singular points: ``stress_invariants``, the one place they are formed.  With
   ``invariants=False`` the entry points stop before it and the caller forms them from the tensor
   in its own units (the scenarios: after ``apply_scales``, so they are the invariants of the
   scaled tensor to the last bit).

Units (as the kernels): lengths (x, y, z, a, the stick radius) in the profile's length unit;
stresses, von Mises and principal stresses divided by E*, dp/dz divided by E*/length,
displacements divided by the indentation depth delta: the family's natural units.  A caller
that wants pascals multiplies by E*, one that wants units of the mean pressure p_m by E*/p_m (and
dp/dz by a E*/p_m for units of p_m/a).  Pure NumPy/SciPy.
"""
from __future__ import annotations

import math
from typing import Callable, Iterable, NamedTuple

import numpy as np

from ..flags import quiet
from ..flags import Validity, validity_flag
from ..invariants import principal_stresses, singular_limits, von_mises
# the stress components and principal stresses are defined in ``physics.names``: the scenario
# declarations read them without importing the kernels
from ..names import PRINCIPAL, STRESS
from . import history as hist
from .displacement import NAMES as DISPLACEMENTS
from .displacement import displacements, tangential_displacements
from .interior import interior_dpdz, interior_stress
from .interior_tangential import interior_dpdz_tangential, interior_stress_tangential
from .loading import History, Monotonic
from .profiles import Profile
from .routes import Route, resolve, resolve_depth, resolve_interior

__all__ = ["STRESS", "PRINCIPAL", "INVARIANTS", "FIELDS", "HISTORY_LOADS", "HISTORY_FIELDS", "fields", "history_fields",
           "stress_invariants", "Singular", "contact_radius", "validity_flag"]

#: validity code of a point below the surface that the 1-D routes do not resolve
UNRESOLVED = Validity.not_resolved_below_the_surface
#: the invariants of the stress tensor: von Mises (A60), principal stresses, tau_max = (sigma_1 - sigma_3)/2
INVARIANTS = ("von_mises",) + PRINCIPAL + ("tau_max",)
#: fields of a point (they need x and y, and z below the surface)
SPATIAL = STRESS + INVARIANTS + ("dpdz", "region", "validity")
#: everything ``fields`` computes
FIELDS = SPATIAL + DISPLACEMENTS + Monotonic.LOADS
#: the loads of a history step (no x, y): stick radius, F_x / (mu F_N), energies / (mu F_N delta)
HISTORY_LOADS = History.LOADS
#: everything ``history_fields`` computes
HISTORY_FIELDS = SPATIAL + DISPLACEMENTS + HISTORY_LOADS
#: the fields the validity flag looks at
_VALUED = STRESS + INVARIANTS + ("dpdz",)

# region flag values (flag_meanings of the scenarios' `region`)
OUTSIDE, STICK, SLIP, NO_TRACTION = 0, 1, 2, 3


@quiet
def fields(names: Iterable[str], profile: Profile, x=None, y=None, z=None, *, a, nu, mu, ux0, stick=None,
           method: str = "auto", rtol: float = 1e-10, invariants: bool = True) -> tuple[dict[str, np.ndarray], Route]:
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
    invariants : True: the invariants asked for are formed here, per unit E*.  False: they are
        not; instead the six stress components, "singular" (a ``Singular``: what their limits
        need where a component is infinite) and a validity flag of the other values are
        returned, for ``stress_invariants`` to form the invariants (and complete the flag) from
        the tensor in the caller's units: the invariants of the scaled tensor, not the scaled
        invariants, to the last bit.

    A flat punch sticks whole or slides; sticking (c = a with u_x0 > 0 and mu > 0) its traction is
    the sliding one with mu E* delta replaced by G* u_x0 (paper eq. 20; docs/theory/axisymmetric.md
    (A37), (A42)-(A44), (A59)), which the kernels take as c = 0 and mu = (G*/E*) u_x0/delta.  The
    stick radius and the region flag keep c = a.
    """
    return _pipeline(_known(names, FIELDS), profile, x, y, z, Monotonic(profile, ux0, stick), a=a, nu=nu, mu=mu,
                     method=method, rtol=rtol, invariants=invariants)


@quiet
def history_fields(names: Iterable[str], profile: Profile, x=None, y=None, z=None, *, a, nu, mu, amplitude,
                   history, step, method: str = "auto", rtol: float = 1e-10,
                   invariants: bool = True) -> tuple[dict[str, np.ndarray], Route]:
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
    indices into it.  a, nu, mu, amplitude, step, x, y and z broadcast (x, y may be None when
    no surface field is requested).  Units, ``method``, ``rtol`` and ``invariants`` as for ``fields``.  The
    outputs have the broadcast shape of all arguments.

    ``z``: depth below the surface (z >= 0; None: 0).  Where z > 0 the fields are the normal
    interior part plus the same superposition (A69) of the c-terms as on the surface, each term
    w_k times the Cattaneo–Mindlin interior field with stick radius c_k (docs/theory/interior.md
    (I23), (I33); dp/dz (I34)-(I35)), all finite; the route and its accuracy are those of
    ``fields`` below the surface (closed forms: relative error at most 1e-12 of |value|
    everywhere the value is finite, far field and next to edges included).  z = 0 is the surface
    computation, bit for bit; "region" and the loads do not depend on z.
    """
    names = _known(names, HISTORY_FIELDS)
    if profile.kind == "flat_punch":
        # a sticking punch carries a traction the c-terms do not describe (A37); the surface route
        # has no history for it either
        if _below(names, z):
            raise ValueError("history_fields below the surface: the flat punch has no history route")
        if any(n in DISPLACEMENTS for n in names):
            raise ValueError("history_fields: the flat punch has no history route")
    return _pipeline(names, profile, x, y, z, History(profile, amplitude, history, step), a=a, nu=nu, mu=mu,
                     method=method, rtol=rtol, invariants=invariants)


def contact_radius(profile: Profile, delta) -> np.ndarray:
    """Contact radius a at the indentation depth ``delta`` (eq. 7, delta = g(a),
    docs/theory/axisymmetric.md (A3)), element by element."""
    return np.vectorize(profile.contact_radius, otypes=[float])(delta)


# -- the pipeline --------------------------------------------------------------------------------

def _known(names: Iterable[str], allowed: tuple[str, ...]) -> list[str]:
    names = list(names)
    unknown = [n for n in names if n not in allowed]
    if unknown:
        raise ValueError(f"unknown field(s) {unknown!r}: use some of {', '.join(allowed)}")
    return names


def _below(names, z) -> bool:
    """Whether some point field is asked for below the surface (z > 0)."""
    return z is not None and any(n in SPATIAL for n in names) and bool(np.any(np.asarray(z, dtype=float) > 0.0))


def _pipeline(names: list[str], profile: Profile, x, y, z, load, *, a, nu, mu, method: str,
              rtol: float, invariants: bool) -> tuple[dict[str, np.ndarray], Route]:
    """The fields ``names`` of the load ``load`` (``loading.Monotonic`` or ``loading.History``) and
    the route: the surface values where z = 0 (or z is None), the interior ones where z > 0, one
    merge, one validity flag, then the displacements (surface and interior alike).  Asked for
    invariants, the pipeline computes the whole tensor and its singular points ("singular") and
    forms them at the end (``stress_invariants``), unless ``invariants`` is False."""
    case = {"a": a, "nu": nu, "mu": mu, **load.arrays}
    inv = [n for n in INVARIANTS if n in names]
    asked = names
    # the validity flag of the other valued fields asked for; ``stress_invariants`` adds the invariants'
    flagged = [n for n in names if n in _VALUED and n not in INVARIANTS]
    if inv:
        names = [n for n in names if n not in INVARIANTS] + [s for s in STRESS if s not in names] + ["singular"]
    rest = [n for n in names if n not in DISPLACEMENTS]
    if _below(rest, z):
        out, route = _with_depth(rest, profile, x, y, z, case, load, method, rtol, flagged)
    else:
        out, route = _on_surface(rest, profile, x, y, case, load, method, rtol, flagged)
    moved = [n for n in names if n in DISPLACEMENTS]
    if moved:
        out.update(_displacements(moved, profile, x, y, z, case, load,
                                   resolve(profile, method, rtol, group="displacement").kernel, rtol))
    if inv and invariants:
        singular = out.pop("singular")
        out.update(stress_invariants(inv, out, singular, validity=out.get("validity")))
        out = {n: out[n] for n in asked}
    return out, route


def _flat(arrays: dict) -> tuple[tuple[int, ...], dict[str, np.ndarray]]:
    """The broadcast shape of ``arrays`` and each of them broadcast to it and flattened."""
    full = np.broadcast_arrays(*(np.asarray(v, dtype=np.int64 if k == "step" else float) for k, v in arrays.items()))
    return full[0].shape, {k: v.ravel() for k, v in zip(arrays, full)}


def _on_surface(names, profile, x, y, case, load, method, rtol, flagged=()):
    """The surface (z = 0) fields and the loads, group by group of the load's terms, on the
    broadcast of the case arrays (and x, y where a point field is asked for)."""
    route = resolve(profile, method, rtol)
    spatial = [n for n in names if n in SPATIAL and n != "validity"] + [n for n in names if n == "singular"]
    shape, P = _flat({**case, **({"x": x, "y": y} if spatial else {})})
    size = int(np.prod(shape, dtype=np.int64))
    results = {n: np.empty(size, dtype=np.int8 if n == "region" else float) for n in names
               if n not in ("validity", "singular")}
    singular = []
    kw = dict(method=route.kernel, rtol=rtol)
    for group in load.groups(P):
        G = {k: v[group.index] for k, v in P.items()}
        part = load.loads(names, group, P)
        if spatial:
            x_, y_, a_, nu_, mu_ = G["x"], G["y"], G["a"], G["nu"], group.mu
            on = dict(terms=group.terms, radii=group.radii, width=group.width, **kw)
            part.update(_point_fields(
                spatial,
                stress=lambda comps: hist.history_stress(x_, y_, a_, nu_, mu_, profile, components=comps, **on),
                dpdz=lambda: hist.history_dpdz(x_, y_, a_, nu_, mu_, profile, **on),
                region=lambda: _region(np.hypot(x_, y_), a_, group.stick, group.free),
                singular=lambda i: Singular.at(profile, i, len(x_), x=x_, y=y_, a=a_, nu=nu_, mu_kernel=mu_,
                                               mu_lead=group.gross_weight() * mu_)))
            if part.get("singular") is not None:
                singular.append(part["singular"].moved(group.index, shape))
            part.pop("singular", None)
        for n, v in part.items():
            results[n][group.index] = v
    out = {n: v.reshape(shape) for n, v in results.items()}
    if "singular" in names:
        out["singular"] = Singular.join(singular, shape)
    if "validity" in names:
        out["validity"] = validity_flag(*(out[n] for n in flagged))
    return out, route


def _with_depth(names, profile, x, y, z, case, load, method, rtol, flagged):
    """The fields where some z > 0: the surface computation (without z, so bit for bit the values
    of z = 0) where z = 0 and for the region and the loads, which do not depend on z; the normal
    interior field plus the terms' tangential ones where z > 0; one merge, one validity flag."""
    shape, P = _flat({"x": x, "y": y, "z": z, **case})
    if np.any(~(P["z"] >= 0.0)):
        raise ValueError("z (depth below the surface) must be >= 0 and not NaN")
    deep = P["z"].reshape(shape) > 0.0
    valued = [n for n in names if n in _VALUED]
    top = [n for n in names if n != "validity" and (n not in _VALUED + ("singular",) or not np.all(deep))]
    out: dict = {}
    if top:
        out, _ = _on_surface(top, profile, x, y, case, load, method, rtol)
        out = {n: v if n in _VALUED else (None if v is None else v.broadcast(shape, ~deep)) if n == "singular"
               else np.array(np.broadcast_to(v, shape)) for n, v in out.items()}
    if "singular" in names and "singular" not in out:
        out["singular"] = None
    D = {k: v[deep.ravel()] for k, v in P.items()}
    terms = _terms(load, D)
    expo, tangential = getattr(profile, "n", None), bool(terms)
    route = resolve_depth(profile, method, rtol, expo, z, tangential=tangential)
    kw = dict(method=resolve_interior(profile, method, rtol, expo, tangential=tangential).kernel, rtol=rtol)
    at = (D["x"], D["y"], D["z"], D["a"])

    def part(kernel):
        """The tangential field of one term at its points ``on``: stick radius c, coefficient mu."""
        return lambda on, c, mu, width: kernel(*(v[on] for v in at), c, D["nu"][on], mu, profile, width=width, **kw)

    below = _point_fields(
        valued,
        stress=lambda comps: _add_terms(interior_stress(*at, D["nu"], profile, **kw), comps, terms,
                                        part(interior_stress_tangential)),
        dpdz=lambda: _add_terms({"dpdz": interior_dpdz(*at, D["nu"], profile, **kw)}, ("dpdz",), terms,
                                lambda *t: {"dpdz": part(interior_dpdz_tangential)(*t)})["dpdz"],
        region=lambda: None)
    return _merge_depth(out, below, names, valued, flagged, deep, shape), route


def _terms(load, P: dict) -> list[tuple]:
    """The terms of the flat points ``P`` that carry a traction (``loading.Term``) with ``on`` the
    indices into P of their points."""
    return [term._replace(on=group.index[term.on]) for group in load.groups(P)
            for term in group.live_terms(P["a"][group.index])]


def _add_terms(normal: dict, keys, terms, tangential: Callable) -> dict:
    """The normal part's ``keys`` plus sum_k w_k times the tangential part of term k at its points
    (``tangential(on, c, mu, width)``): (A69) with docs/theory/interior.md (I23), (I33).  One term
    of weight 1 adds the kernel's values unchanged."""
    out = {k: np.array(normal[k], dtype=float) for k in keys}
    for term in terms:
        part = tangential(term.on, term.c, term.mu, term.width)
        for k in keys:
            out[k][term.on] += term.w * part[k]
    return out


def _merge_depth(out: dict, below: dict, names, valued, flagged, deep: np.ndarray, shape) -> dict:
    """The surface values ``out`` where z = 0 and the interior ones ``below`` where z > 0, with one
    validity flag. Below the surface every exact value is finite, so a non-finite one there is a
    point the routes do not resolve (r or z below ~1e-100 a, docs/theory/interior.md section 6):
    NaN, flagged UNRESOLVED, never an infinity (which the contract keeps for unbounded limits)."""
    whole = bool(np.all(deep))
    for n in valued:
        resolved = np.where(np.isfinite(below[n]), below[n], np.nan)
        if whole:
            out[n] = resolved.reshape(shape)
            continue
        full = np.empty(shape)
        if n in out:
            full[~deep] = np.broadcast_to(out[n], shape)[~deep]
        full[deep] = resolved
        out[n] = full
    if "validity" in names:
        flag = validity_flag(*(out[n] for n in flagged))
        unresolved = deep & np.any([~np.isfinite(out[n]) for n in valued], axis=0) if valued else deep & False
        out["validity"] = np.where(unresolved, np.int8(UNRESOLVED), flag).astype(np.int8)
    return out


def _displacements(names, profile, x, y, z, case, load, method, rtol) -> dict[str, np.ndarray]:
    """Displacements / delta on the surface and below it: the normal part plus the terms, each w_k
    times the Cattaneo–Mindlin displacement with stick radius c_k (docs/theory/interior.md
    (I42)-(I43), docs/theory/axisymmetric.md (A69)); a term that knows its u_x0 (a monotonic load)
    hands it to the kernel, whose paraboloid keeps its accuracy as c -> a through the slip ratio."""
    shape, P = _flat({"x": 0.0 if x is None else x, "y": 0.0 if y is None else y, "z": 0.0 if z is None else z,
                      **case})
    xyz = (P["x"], P["y"], P["z"])
    out = displacements(names, profile, *xyz, a=P["a"], nu=P["nu"], mu=0.0, ux0=0.0, c=P["a"], mu_kernel=0.0,
                        method=method, rtol=rtol)
    out = {n: np.array(v, dtype=float) for n, v in out.items()}
    for term in _terms(load, P):
        i = term.on
        part = tangential_displacements(names, profile, *(v[i] for v in xyz), a=P["a"][i], c=term.c, nu=P["nu"][i],
                                        mu_kernel=term.mu, ux0=term.ux0, method=method, rtol=rtol)
        for n in names:
            out[n][i] += term.w * part[n]
    return {n: v.reshape(shape) for n, v in out.items()}


# -- the point fields ------------------------------------------------------------------------------

def _point_fields(names: list[str], *, stress: Callable[[tuple[str, ...]], dict], dpdz: Callable[[], np.ndarray],
                  region: Callable[[], np.ndarray], singular: Callable | None = None) -> dict:
    """The stress tensor, dp/dz and the region flag, each computed only if requested;
    ``stress(components)`` gives the tensor / E*, ``dpdz()`` dp/dz / (E*/length).  "singular":
    ``singular(flat indices)`` -> the ``Singular`` of the points where a component is infinite."""
    out: dict = {}
    want = [n for n in names if n in STRESS]
    if want:
        tensor = {f"sigma_{k}": v for k, v in stress(tuple(n.removeprefix("sigma_") for n in want)).items()}
        out.update((n, tensor[n]) for n in names if n in STRESS)
        if "singular" in names and singular is not None:
            shape = np.broadcast_shapes(*(np.shape(tensor[s]) for s in STRESS))
            infinite = np.zeros(shape, dtype=bool)
            for s in STRESS:
                infinite |= np.isinf(tensor[s])
            idx = np.flatnonzero(infinite)
            out["singular"] = singular(idx) if idx.size else None
    if "dpdz" in names:
        out["dpdz"] = dpdz()
    if "region" in names:
        out["region"] = region()
    return out


class Singular(NamedTuple):
    """The points of a result's shape ``shape`` where a stress component is infinite (``index``,
    flat) and, at each, what the limits of the invariants there need (``_singular``): the point
    (x, y), a, nu, the kernels' mu and the coefficient of sigma_xz's growth in gross slip."""

    profile: Profile
    shape: tuple
    index: np.ndarray
    x: np.ndarray
    y: np.ndarray
    a: np.ndarray
    nu: np.ndarray
    mu_kernel: np.ndarray
    mu_lead: np.ndarray

    @classmethod
    def at(cls, profile: Profile, idx, size: int, **arrays) -> "Singular":
        """The points ``idx`` of a flat result of ``size`` points, the ``arrays`` broadcasting to it."""
        return cls(profile, (size,), idx, *(np.broadcast_to(np.asarray(arrays[k], dtype=float), (size,))[idx]
                                            for k in cls._fields[3:]))

    @staticmethod
    def join(parts: list, shape) -> "Singular | None":
        """The points of ``parts`` (each of ``shape``, disjoint) together; None if there are none."""
        if not parts:
            return None
        return parts[0]._replace(shape=tuple(shape), **{k: np.concatenate([getattr(p, k) for p in parts])
                                                        for k in Singular._fields[2:]})

    def moved(self, index: np.ndarray, shape) -> "Singular":
        """The points of a flat group whose point i is the flat point ``index[i]`` of ``shape``."""
        return self._replace(shape=tuple(shape), index=index[self.index])

    def broadcast(self, shape, keep=None) -> "Singular":
        """The points of the result broadcast to ``shape`` (where ``keep``, a boolean of ``shape``)."""
        shape = tuple(shape)
        if shape == self.shape and keep is None:
            return self
        row = np.full(int(np.prod(self.shape, dtype=np.int64)), -1)
        row[self.index] = np.arange(self.index.size)
        src = np.broadcast_to(row.reshape(self.shape), shape).ravel()
        hit = (src >= 0) if keep is None else (src >= 0) & np.broadcast_to(keep, shape).ravel()
        rows = src[hit]
        return type(self)(self.profile, shape, np.flatnonzero(hit), *(getattr(self, k)[rows] for k in self._fields[3:]))


def stress_invariants(names: Iterable[str], tensor: dict, singular: Singular | None = None, scale=1.0,
                      validity=None) -> dict[str, np.ndarray]:
    """The invariants ``names`` (of ``INVARIANTS``: von Mises (A60), principal stresses, tau_max =
    (sigma_1 - sigma_3)/2) of the stress tensor ``tensor`` ({"sigma_xx": ..., ...}, broadcasting),
    the one place they are formed.  Where a component is infinite they are the limits of
    ``singular_limits`` at the points of ``singular`` (docs/theory/axisymmetric.md (A97)).

    ``scale``: the factor (broadcasting) the tensor has been multiplied by since ``fields`` returned
    it, whose bounded remainder at a singular point (``_singular``) is scaled alike; the invariants
    of the scaled tensor are formed, not scaled invariants, so their last bits are the tensor's.
    ``validity``: a flag of the other values (``fields`` with ``invariants=False``); returned under
    "validity" with the singular points whose invariants' limits are unknown (NaN) flagged so."""
    out: dict[str, np.ndarray] = {}
    comps = [tensor[s] for s in STRESS]
    if "von_mises" in names:
        out["von_mises"] = von_mises(*comps)
    if any(n in names for n in PRINCIPAL + ("tau_max",)):
        s1, s2, s3 = principal_stresses(*comps)
        out.update((n, v) for n, v in zip(PRINCIPAL, (s1, s2, s3)) if n in names)
        if "tau_max" in names:
            out["tau_max"] = 0.5 * (s1 - s3)
    shape = np.broadcast_shapes(*(np.shape(c) for c in comps), np.shape(scale))
    if singular is not None and singular.index.size:
        at = singular.broadcast(shape)
        xz = np.broadcast_to(tensor["sigma_xz"], shape).ravel()[at.index]
        lead, rest = _singular(at, xz, np.broadcast_to(np.asarray(scale, dtype=float), shape).ravel()[at.index])
        vm, pr = singular_limits(lead, rest)
        for n, v in zip(INVARIANTS, (vm,) + pr + (_tau_limit(vm, rest),)):
            if n in out:
                out[n] = np.array(np.broadcast_to(out[n], shape))
                out[n].flat[at.index] = v
    if validity is not None:
        # the flag of all the values: the other values' flag as a value of its own (0, +-inf or NaN)
        # with the invariants; a code of its own (a point below the surface that the routes do not
        # resolve, where the tensor and so the invariants are NaN) stays
        flag = np.broadcast_to(validity, np.broadcast_shapes(shape, np.shape(validity)))
        unbounded, undefined = Validity.unbounded_at_singular_point, Validity.undefined_direction_dependent_limit
        proxy = np.where(flag == unbounded, np.inf, np.where(flag == undefined, np.nan, 0.0))
        general = (flag == Validity.within_stated_accuracy) | (flag == unbounded) | (flag == undefined)
        out["validity"] = np.where(general, validity_flag(proxy, *out.values()), flag).astype(np.int8)
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


def _singular(at: Singular, XZ, SC):
    """(lead, rest) of the stress tensor lam * lead + rest + o(1), lam -> +inf, at the points of
    ``at`` where a component is infinite, with ``XZ`` the tensor's sigma_xz there and ``SC`` the
    factor it has been scaled by (``stress_invariants``); NaN where the limit is not known
    (docs/theory/axisymmetric.md (A97)).

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
    profile = at.profile
    X, Y, A, NU, MU, ML = at.x, at.y, at.a, at.nu, at.mu_kernel, at.mu_lead
    r = np.hypot(X, Y)
    n = at.index.size
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


def _region(r, a, c, free) -> np.ndarray:
    """Contact region flag: OUTSIDE r > a, STICK r < c, SLIP c <= r <= a; NO_TRACTION r <= a where
    ``free`` (no tangential traction)."""
    region = np.where(r > a, OUTSIDE, np.where(r < c, STICK, SLIP)).astype(np.int8)
    return np.where(np.asarray(free) & (r <= a), np.int8(NO_TRACTION), region)
