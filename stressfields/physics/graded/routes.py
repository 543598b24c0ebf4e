"""The route table of the graded family: which evaluation a (profile kind, method) pair takes.

This is the one place that says where a closed form exists and what method ``auto`` means; the
field entry points (:mod:`.fields`) and the scenarios' ``route`` both ask :func:`resolve`.  The
strings are written into every output file (``stressfields_method``, ``stressfields_accuracy``).
"""
from __future__ import annotations

import numpy as np

from ..names import GRADED_METHODS as METHODS  # one definition, read by the scenario declarations

KINDS = ("parabolic", "conical", "power_law", "tabulated")

#: closed forms of the paper for f = A r^n (docs/theory/graded.md (G15)-(G37))
CLOSED = "closed form (Tables 1-3)"
#: tanh-sinh quadrature of the MDR rules for any profile object (docs/theory/graded.md (G42))
QUADRATURE = "quadrature of the MDR rules (eq. 5, 10-15, 27-31, 41-43)"

#: the accuracy contract of the family, as written into the files (docs/theory/graded.md (G43), (G44))
_CLOSED_ACCURACY = ("relative error at most 1e-12 of |value| everywhere the value is finite, far field and next "
                    "to edges included")


def _quadrature_accuracy(rtol: float) -> str:
    return f"relative error at most rtol = {rtol:g} of |value| (graded: rtol is relative to |value|)"


#: the groups of variables the table answers for: the surface quantities (depth, force, pressure,
#: displacement, stick radius, ...) and the stress below the surface with its peaks
GROUPS = ("surface", "stress")


def resolve(profile_kind: str, method: str, rtol: float, *, group: str = "surface", k=None,
            n=None) -> tuple[str, str]:
    """(route, accuracy) for a profile kind, a method and a group of variables (``GROUPS``).

    At the surface ``route`` is :data:`CLOSED` or :data:`QUADRATURE`: every power law (paraboloid,
    cone, A r^n) has the closed forms of the paper, which ``auto`` takes; a tabulated profile has none
    and always takes the quadrature of the MDR rules (docs/theory/graded.md (G14), (G42)), whose
    accuracy is the requested ``rtol``.  The ``stress`` group, with the grading exponents ``k`` of a
    recipe that gives depths (None: the surface only), adds the route below the surface
    (``resolve_interior``).  ValueError for ``closed`` on a tabulated profile and for ``quadrature`` on
    a power law with an exponent ``n`` below 1 (the transform quadrature (eq. 5) does not converge
    for a tip of unbounded slope f' ~ r^(n-1)), in words a recipe check quotes after "method.".
    """
    if profile_kind not in KINDS:
        raise ValueError(f"profile kind {profile_kind!r} is not allowed: use one of {', '.join(map(repr, KINDS))}")
    if method not in METHODS:
        raise ValueError(f"method = {method!r} is not allowed: use one of {', '.join(map(repr, METHODS))}")
    if group not in GROUPS:
        raise ValueError(f"unknown variable group {group!r}; allowed: {', '.join(GROUPS)}")
    if method == "closed" and profile_kind == "tabulated":
        raise ValueError("method = 'closed' has no closed form for profile = 'tabulated'; use 'auto' or 'quadrature'")
    least = None if n is None else float(np.min(n))
    if method == "quadrature" and profile_kind == "power_law" and least is not None and least < 1.0:
        raise ValueError(f"method = 'quadrature' needs n in [1, 50] for profile = 'power_law' (a tip of finite "
                         f"slope), got n = {least!r}; use method 'auto' for n < 1")
    if method == "quadrature" or profile_kind == "tabulated":
        surface = QUADRATURE, _quadrature_accuracy(rtol)
    else:
        surface = CLOSED, _CLOSED_ACCURACY
    if group == "surface" or k is None:
        return surface
    below = resolve_interior(k, rtol, profile_kind)
    return f"{surface[0]}; below the surface: {below[0]}", f"{surface[1]}; below the surface: {below[1]}"


#: below the surface (docs/theory/graded.md (G67)): k = 0 takes the axisymmetric family's interior
#: routes, k > 0 with nu = 1/(2+k) the 2-D quadrature of the radial point-load field
INTERIOR_HOMOGENEOUS = ("k = 0: the homogeneous interior (closed forms: paraboloid, cone; else the 1-D "
                        "superposition of flat punches)")
#: a tabulated profile at k = 0: the axisymmetric spline through the same samples (the same not-a-knot spline)
INTERIOR_TABULATED = ("k = 0: the homogeneous interior of the axisymmetric family's spline through the same samples "
                      "(the 1-D superposition of flat punches)")
INTERIOR_HOLL = ("k > 0, nu = 1/(2+k): 2-D quadrature of the radial point-load field over the contact (Gauss "
                 "rules, orders from rtol)")


def resolve_interior(k, rtol: float, profile_kind: str = "parabolic") -> tuple[str, str]:
    """(route, accuracy) of the stress below the surface for the grading exponents ``k`` of a recipe and its
    profile kind (a tabulated profile has no closed form: the superposition's accuracy alone)."""
    k = [float(v) for v in np.ravel(k)]
    routes, acc = [], []
    if any(v == 0.0 for v in k) and profile_kind == "tabulated":
        routes.append(INTERIOR_TABULATED)
        acc.append(f"k = 0: |error| <= rtol * max(|value|, p_m), rtol = {rtol:g}, p_m the mean contact pressure "
                   "(superposition)")
    elif any(v == 0.0 for v in k):
        routes.append(INTERIOR_HOMOGENEOUS)
        acc.append("k = 0: " + _CLOSED_ACCURACY + " (closed forms) or |error| <= rtol * max(|value|, p_m) "
                   "(superposition)")
    if any(v > 0.0 for v in k):
        routes.append(INTERIOR_HOLL)
        acc.append(f"k > 0: |error| <= rtol * max(|value|, P), rtol = {rtol:g}, P the pressure scale of the contact; "
                   "on z = 0 the closed-form limit")
    return "; ".join(routes), "; ".join(acc)
