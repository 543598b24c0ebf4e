"""The route table of the axisymmetric family: which profiles have closed forms, what ``auto``
means, and the (route, accuracy) strings written into every field's attributes.

The one place that decides "a closed form exists" (docs/theory/axisymmetric.md (A5)-(A8)):

* cone, paraboloid and flat punch always; a power law for n = 1 (the cone, tan(theta) = A) and
  n = 2 (the paraboloid, R = 1/(2A)); a tabulated profile never.
* ``auto`` takes the closed forms where they exist (normal load (A12)-(A13), (A18)-(A21),
  (A28)-(A30); tangential load (A35)-(A37), (A42)-(A52), (A56)-(A59)) and otherwise the
  one-dimensional integrals (A14)-(A16), (A24)-(A27), (A34), (A38)-(A41), (A53)-(A54) by Gauss
  quadrature, whose order comes from a table verified against rtol.
* ``closed`` and ``quadrature`` force a route; the kernels refuse ``closed`` where no closed form
  exists, and a flat punch always uses its closed forms (its g' is a Dirac delta).

Below the surface (z > 0, normal load; docs/theory/interior.md) ``resolve_interior`` decides:

* the paraboloid (and the power law n = 2), the cone (and the power law n = 1) and the flat punch
  have closed forms (I5)-(I14), (I24)-(I27), (I46)-(I52); the flat punch always uses them;
* every other profile (power law n != 1, 2, tabulated) is the one-dimensional superposition of
  flat-punch fields (I15)-(I17), (I28) by Gauss quadrature, as is the paraboloid under
  ``quadrature``; ``closed`` is refused where no interior closed form exists.

Under tangential load (Cattaneo–Mindlin, ``tangential=True``) the tangential part has the closed
forms (I23), (I33), (I34)-(I35) of the paraboloid and the flat punch, else the superposition of
sliding punches (I33), (I45), (I28) with (I35): for the cone ``auto`` is the closed form for the
normal part and the superposition for the tangential part (``Route.kernel`` "auto"), and
``closed`` is refused; its accuracy is relative to mu p_m
(the traction's scale), so the 1-D route states max(|value|, S max(1, mu)).  The partial-slip
superposition is one integral over [c, a] (I45), so every profile, power laws with n < 1 (a tip
g' ~ rho^m0, m0 < 0) included, reaches the normal route's rtol = 1e-12 there.

``resolve_depth`` joins the two for a set of depths (z = 0 takes the surface route).

``resolve(..., group=...)`` answers for every group of variables (``GROUPS``), each with its own
route and accuracy, written into the attributes of that group's variables:

* ``stress`` and ``dpdz`` -- the fields above, on the surface and below it (``resolve_depth``);
  a rtol below the superposition's floor (``tangential_floor``) below the surface is refused;
* ``displacement`` -- closed forms for the flat punch and the paraboloid (and the power law n = 2),
  docs/theory/interior.md (I37)-(I41); every other profile, and the paraboloid under
  ``quadrature``, the 1-D superposition of punches (I42)-(I44) within rtol * max(|value|, delta),
  also under ``closed`` (the stresses of the cone have closed forms, its displacements do not: the
  route says so);
* ``peaks`` -- the converged search of ``peaks`` over the field on and below the surface;
* ``contact`` -- the normal contact, the stick radius and the tangential load (contact radius,
  mean pressure, forces): the profile's closed forms, else its quadrature (the surface route).

The strings of ``resolve`` are written into files; they state the accuracy contract, proved by
tests/physics/test_axisymmetric_contract.py, tests/physics/test_axisymmetric_tabulated.py,
tests/physics/test_interior_superposition.py and tests/test_scenario_interior.py.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..names import AXISYMMETRIC_METHODS

__all__ = ["GROUPS", "has_displacement_closed_form", "METHODS", "CLOSED_KINDS", "POWER_LAW_CLOSED",
           "INTERIOR_CLOSED_KINDS", "INTERIOR_RTOL", "Route",
           "power_law_family", "has_closed_form", "has_interior_closed_form", "resolve", "resolve_interior",
           "INTERIOR_TANGENTIAL_CLOSED_KINDS", "has_interior_tangential_closed_form",
           "TANGENTIAL_TIP_RTOL", "resolve_depth", "tangential_floor"]

#: every method the family offers, the default first (defined in ``physics.names``, which the scenario
#: declarations read without importing the kernels)
METHODS: tuple[str, ...] = AXISYMMETRIC_METHODS
#: profile kinds whose every member has closed forms
CLOSED_KINDS: tuple[str, ...] = ("cone", "paraboloid", "flat_punch")
#: power-law exponents n with closed forms, and the closed-form family each one is
POWER_LAW_CLOSED: dict[float, str] = {1.0: "cone", 2.0: "paraboloid"}

_CLOSED = ("closed form", "relative error at most 1e-12 of |value| everywhere the value is finite, far field and "
                           "next to edges included")
_QUADRATURE = "one-dimensional Gauss quadrature of the MDR integrals"
_SUPERPOSITION = ("1-D superposition of flat-punch fields below the surface (Gauss quadrature, "
                  "docs/theory/interior.md (I15)-(I17), (I28))")
#: profile kinds with closed forms below the surface under normal load (power laws n = 1, 2 too)
INTERIOR_CLOSED_KINDS: tuple[str, ...] = ("paraboloid", "flat_punch", "cone")
#: profile kinds whose tangential part below the surface has closed forms (a power law n = 2 too)
INTERIOR_TANGENTIAL_CLOSED_KINDS: tuple[str, ...] = ("paraboloid", "flat_punch")
#: the smallest rtol the superposition below the surface reaches (its rounding floor, about 1e-13)
INTERIOR_RTOL = 1e-12
#: the smallest rtol of the tangential superposition below the surface for a tip g' ~ rho^m0 with
#: m0 < 0 (power laws n < 1).  It was 1e-11 while partial slip was Sigma_T(a) - Sigma_T(c) (which
#: lost eps |Sigma_T(a)|, 2e-11 mu p_m for n = 0.5 at z = 7.6e-10 a on the axis); the direct
#: integral over [c, a] (I45) measured 3e-15 mu p_m there, so it is the normal route's floor
TANGENTIAL_TIP_RTOL = INTERIOR_RTOL
_CLOSED_TANGENTIAL = " (normal and tangential parts)"
_CLOSED_NORMAL_ONLY = " (normal part)"
_SUPERPOSITION_TANGENTIAL = ("; tangential part: 1-D superposition of sliding punches (Gauss quadrature, "
                             "docs/theory/interior.md (I33), (I45), (I28) with (I35))")


class Route(NamedTuple):
    """(route, accuracy) as written into every field's attributes (``stressfields_method``,
    ``stressfields_accuracy``)."""

    route: str
    accuracy: str

    @property
    def kernel(self) -> str:
        """The ``method`` argument of the kernels: "closed", "quadrature", or "auto" where below the
        surface the normal part has a closed form and the tangential part does not (the cone)."""
        head = self.route.split(";")[0]
        if head.endswith(_CLOSED_NORMAL_ONLY):
            return "auto"
        head = head.removesuffix(_CLOSED_TANGENTIAL)
        return "closed" if head in (_CLOSED[0], f"{_CLOSED[0]} below the surface") else "quadrature"


def power_law_family(n) -> str | None:
    """The closed-form family ("cone", "paraboloid") of the power law f = A r^n, or None."""
    if n is None or isinstance(n, (str, bytes)) or np.ndim(n) != 0:
        return None
    return POWER_LAW_CLOSED.get(float(n))


def has_closed_form(kind: str, n=None) -> bool:
    """Whether a profile of this kind (``Profile.kind``; ``n`` the exponent of a power law) has
    closed forms, docs/theory/axisymmetric.md (A5)-(A8)."""
    return kind in CLOSED_KINDS or (kind == "power_law" and power_law_family(n) is not None)


#: the groups of variables the table answers for (``resolve(..., group=...)``)
GROUPS: tuple[str, ...] = ("stress", "dpdz", "displacement", "peaks", "contact")

_DISPLACEMENT_SUPERPOSITION = ("1-D superposition of punches and sliding punches (Gauss quadrature, "
                               "docs/theory/interior.md (I42)-(I44))")
_NO_DISPLACEMENT_CLOSED = " (the displacements of this profile have no closed form)"
_SEARCH = "converged search (physics.axisymmetric.peaks) of the field on and below the surface: "


def resolve(profile, method: str, rtol: float, n=None, *, group: str = "stress", z=None,
            tangential: bool = False) -> Route:
    """The route ``method`` takes for a profile and a group of variables, and how accurate it is.

    ``profile`` is a profile kind ("cone", "paraboloid", "power_law", "flat_punch", "tabulated"),
    with ``n`` the exponent of a power law, or a ``Profile`` (its kind and exponent are used).
    ``auto`` is the closed form where one exists (``has_closed_form``), else the quadrature.
    ``group`` is one of ``GROUPS``; ``z`` the depths of the recipe (None: the surface) and
    ``tangential`` whether a Cattaneo–Mindlin load acts, for the fields below the surface
    (``resolve_depth``).  A method the profile has no route for raises ValueError (``closed``
    without a closed form; rtol below ``tangential_floor`` for the superposition below the surface),
    in words a recipe check can quote after "method.".
    """
    if not isinstance(profile, str):
        profile, n = profile.kind, getattr(profile, "n", None)
    if method not in METHODS:
        raise ValueError(f"unknown axisymmetric method {method!r}; allowed: {', '.join(METHODS)}")
    if group not in GROUPS:
        raise ValueError(f"unknown variable group {group!r}; allowed: {', '.join(GROUPS)}")
    if method == "closed" and not has_closed_form(profile, n):
        raise ValueError(f"method = 'closed' has no closed form for profile = {profile!r}; use 'auto' or "
                         "'quadrature'")
    if group == "contact" or (group in ("stress", "dpdz") and z is None):
        return _surface(profile, method, rtol, n)
    if group == "displacement":
        if profile == "flat_punch" or (method != "quadrature" and has_displacement_closed_form(profile, n)):
            return Route(*_CLOSED)
        return Route(_DISPLACEMENT_SUPERPOSITION + (_NO_DISPLACEMENT_CLOSED if method == "closed" else ""),
                     f"|error| <= rtol = {rtol:g} times max(|value|, delta), delta the indentation depth")
    if group == "peaks":
        field = _depths(profile, method, rtol, n, (0.0, 1.0), tangential)
        return Route(_SEARCH + field.route, f"{field.accuracy}; positions within about 1e-7 a")
    return _depths(profile, method, rtol, n, z, tangential)


def _surface(profile: str, method: str, rtol: float, n) -> Route:
    if method == "closed" or (method == "auto" and has_closed_form(profile, n)):
        return Route(*_CLOSED)
    return Route(_QUADRATURE, _quadrature_accuracy(rtol))


def has_displacement_closed_form(profile, n=None) -> bool:
    """Whether the displacements of a profile (a kind with ``n``, or a ``Profile``) have a closed form:
    the flat punch, the paraboloid and the power law n = 2 (docs/theory/interior.md (I37)-(I41));
    every other profile takes the 1-D superposition."""
    if not isinstance(profile, str):
        profile, n = profile.kind, getattr(profile, "n", None)
    return profile in ("flat_punch", "paraboloid") or (profile == "power_law" and power_law_family(n) == "paraboloid")


def _quadrature_accuracy(rtol: float, tangential: bool = False) -> str:
    if tangential:
        return (f"|error| <= rtol = {rtol:g} times max(|value|, S max(1, mu)), S the variable's normalisation "
                "scale: p_m for stresses, p_m/a for dpdz; mu the coefficient of friction")
    return (f"|error| <= rtol = {rtol:g} times max(|value|, the variable's normalisation scale: p_m for stresses, "
            "p_m/a for dpdz)")


def has_interior_closed_form(kind: str, n=None, tangential: bool = False) -> bool:
    """Whether the field below the surface of a profile of this kind has closed forms: under normal
    load (docs/theory/interior.md (I5)-(I14), (I24)-(I27), (I46)-(I52)) the paraboloid, the cone,
    the power laws n = 1 and 2 and the flat punch; with ``tangential`` (a Cattaneo–Mindlin load
    acts too) only those whose tangential part has them as well
    (``has_interior_tangential_closed_form``: not the cone)."""
    normal = kind in INTERIOR_CLOSED_KINDS or (kind == "power_law" and power_law_family(n) is not None)
    return normal and (not tangential or has_interior_tangential_closed_form(kind, n))


def has_interior_tangential_closed_form(kind: str, n=None) -> bool:
    """Whether the tangential (Cattaneo–Mindlin) part below the surface has closed forms
    (docs/theory/interior.md (I23), (I33)-(I35)): paraboloid, power law n = 2, flat punch."""
    return kind in INTERIOR_TANGENTIAL_CLOSED_KINDS or (kind == "power_law" and power_law_family(n) == "paraboloid")


def resolve_interior(profile, method: str, rtol: float, n=None, tangential: bool = False) -> Route:
    """The route below the surface (z > 0) and its accuracy; arguments as ``resolve``, with
    ``tangential`` whether a tangential (Cattaneo–Mindlin) load acts too.  ``closed`` where no
    interior closed form exists raises ValueError, and so does rtol below ``tangential_floor``."""
    if not isinstance(profile, str):
        profile, n = profile.kind, getattr(profile, "n", None)
    if method not in METHODS:
        raise ValueError(f"unknown axisymmetric method {method!r}; allowed: {', '.join(METHODS)}")
    closed = has_interior_closed_form(profile, n)
    if method == "closed" and not closed:
        raise ValueError(f"method = 'closed' has no closed form below the surface (z > 0) for profile = "
                         f"{profile!r}; use 'auto' or 'quadrature', or z = 0")
    both = closed and (not tangential or has_interior_tangential_closed_form(profile, n))
    if method == "closed" and not both:
        raise ValueError(f"method = 'closed' has no closed form below the surface (z > 0) under tangential load "
                         f"for profile = {profile!r} (its normal part has one); use 'auto' or 'quadrature', or "
                         "z = 0")
    if profile == "flat_punch" or (both and method != "quadrature"):
        return Route(f"{_CLOSED[0]} below the surface" + (_CLOSED_TANGENTIAL if tangential else ""), _CLOSED[1])
    if not tangential:
        return Route(_SUPERPOSITION, _quadrature_accuracy(rtol))
    floor = tangential_floor(profile, n)
    if rtol < floor:
        raise ValueError(f"rtol = {rtol:g} is below {floor:g}, the smallest the tangential superposition below "
                         f"the surface reaches; use rtol >= {floor:g}")
    if closed and method == "auto":
        return Route(f"{_CLOSED[0]} below the surface{_CLOSED_NORMAL_ONLY}{_SUPERPOSITION_TANGENTIAL}",
                     _quadrature_accuracy(rtol, tangential=True))
    return Route(_SUPERPOSITION + _SUPERPOSITION_TANGENTIAL, _quadrature_accuracy(rtol, tangential=True))


def tangential_floor(kind: str, n=None) -> float:
    """The smallest rtol of the tangential superposition below the surface: ``TANGENTIAL_TIP_RTOL``
    for a power law with n < 1 (its g' ~ rho^(n-1) tip), else ``INTERIOR_RTOL``; both 1e-12 since
    partial slip is integrated over [c, a] directly (docs/theory/interior.md (I45))."""
    tip = kind == "power_law" and n is not None and np.ndim(n) == 0 and float(n) < 1.0
    return TANGENTIAL_TIP_RTOL if tip else INTERIOR_RTOL


def resolve_depth(profile, method: str, rtol: float, n=None, z=None, tangential: bool = False) -> Route:
    """The route for the depths ``z`` (None: the surface only): ``resolve`` where every z is 0,
    ``resolve_interior`` where every z > 0, both ("z = 0: ...; z > 0: ...") for a mix;
    ``tangential`` as ``resolve_interior``."""
    if not isinstance(profile, str):
        profile, n = profile.kind, getattr(profile, "n", None)
    return _depths(profile, method, rtol, n, z, tangential)


def _depths(profile: str, method: str, rtol: float, n, z, tangential: bool) -> Route:
    surface = _surface(profile, method, rtol, n)
    depth = np.asarray(0.0 if z is None else z, dtype=float)
    if not np.any(depth > 0.0):
        return surface
    floor = tangential_floor(profile, n) if tangential else INTERIOR_RTOL
    if rtol < floor and resolve_interior(profile, method, floor, n, tangential=tangential).kernel != "closed":
        load = " under tangential load" if floor > INTERIOR_RTOL else ""
        raise ValueError(f"rtol = {rtol:g} is below {floor:g}, the smallest the superposition below the surface "
                         f"(z > 0) reaches{load} for {profile!r}; use rtol >= {floor:g}, or z = 0")
    interior = resolve_interior(profile, method, rtol, n, tangential)
    if np.all(depth > 0.0):
        return interior
    accuracy = (surface.accuracy if surface.accuracy == interior.accuracy
                else f"z = 0: {surface.accuracy}; z > 0: {interior.accuracy}")
    return Route(f"z = 0: {surface.route}; z > 0: {interior.route}", accuracy)
