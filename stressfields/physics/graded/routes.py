"""The route table of the graded family: which evaluation a (profile kind, method) pair takes.

This is the one place that says where a closed form exists and what method ``auto`` means; the
field entry points (:mod:`.fields`) and the scenarios' ``route`` both ask :func:`resolve`.  The
strings are written into every output file (``stressfields_method``, ``stressfields_accuracy``).
"""
from __future__ import annotations

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


def resolve(profile_kind: str, method: str, rtol: float) -> tuple[str, str]:
    """(route, accuracy) for a profile kind and a method: ``route`` is :data:`CLOSED` or :data:`QUADRATURE`.

    Every power law (paraboloid, cone, A r^n) has the closed forms of the paper, which ``auto``
    takes; a tabulated profile has none and always takes the quadrature of the MDR rules
    (docs/theory/graded.md (G14), (G42)), whose accuracy is the requested ``rtol``.
    """
    if profile_kind not in KINDS:
        raise ValueError(f"profile kind {profile_kind!r} is not allowed: use one of {', '.join(map(repr, KINDS))}")
    if method not in METHODS:
        raise ValueError(f"method = {method!r} is not allowed: use one of {', '.join(map(repr, METHODS))}")
    if method == "closed" and profile_kind == "tabulated":
        raise ValueError("method = 'closed' has no closed form for a tabulated profile; use 'auto' or 'quadrature'")
    if method == "quadrature" or profile_kind == "tabulated":
        return QUADRATURE, _quadrature_accuracy(rtol)
    return CLOSED, _CLOSED_ACCURACY
