"""The route table of the wavy family: what each method means, and the paper's approximations.

The one place that says which computation a method name selects (docs/theory/wavy.md (W25)):

* ``series`` -- the exact series of the domain, (W9) with the coefficients of (W7) (periodic) or
  (W8) (non-periodic), its length chosen from rtol, (W22)-(W24);
* ``auto`` -- the same, except that the pressure of a narrow periodic contact is taken from the
  cheaper non-periodic series where the periodic correction (W26) plus that series' error stays
  within rtol (validity nonperiodic_series_within_rtol);
* ``approximate_eq18`` / ``approximate_eq20`` -- the pressure only by the paper's approximate
  formulas (W29), non-periodic only, inaccurate (validity approximate_formula).

Below the surface (``resolve(..., below=True)``), for every exact method:

* ``potential`` -- the plane-strain field from the complex potential of the surface tractions
  (W36)-(W41): periodic, the closed finite form (W37) near the surface and the Taylor series of S(w)
  at depth, switched per contact where their bounds meet (W39); single indenter, the series in omega
  (W38) of the surface series' length (tail bounds unchanged); partial slip by the same potential
  at the stick width (W41), (W43).

``resolve`` gives the route and accuracy strings written into every file's attributes; they must
not change (the surface ones: recipes without z keep their strings) but for the validity code they name.
"""
from __future__ import annotations

from typing import Callable

import numpy as np

from ..flags import Validity
from ..names import WAVY_APPROXIMATE_METHODS, WAVY_METHODS, WAVY_SERIES_METHODS
from .contact import approximate_pressure_eq18, approximate_pressure_eq20

#: the paper's approximate pressures (non-periodic, docs/theory/wavy.md (W29)): method name -> kernel
#: kernel(x_over_a, two_a_over_lambda1, amplitudes, wavenumbers, *, n_harmonics) -> p/p*
#: (the method names are defined in ``physics.names``, which the scenario declarations read without
#: importing the kernels)
APPROXIMATE: dict[str, Callable[..., np.ndarray]] = dict(
    zip(WAVY_APPROXIMATE_METHODS, (approximate_pressure_eq18, approximate_pressure_eq20), strict=True))
#: the exact methods: the default first
SERIES_METHODS: tuple[str, ...] = WAVY_SERIES_METHODS
#: every method the family offers, in the order a recipe lists them
METHODS: tuple[str, ...] = WAVY_METHODS

_SERIES_ROUTE = ("closed Legendre-cosine form (periodic, docs/theory/wavy.md (W30)) or Bessel series "
                 "(non-periodic, eq. 14), length from rtol")
_AUTO_ROUTE = ("; auto: pressure of a narrow periodic contact by the non-periodic series where the periodic "
               f"correction is below rtol (validity = {int(Validity.nonperiodic_series_within_rtol)})")


_BELOW_ROUTE = ("; below the surface: complex potential of the surface tractions (docs/theory/wavy.md (W36)-(W41)), "
                "periodic closed finite form near the surface and Taylor series in w at depth, switched a priori by "
                "their bounds (W39); single indenter, the series in omega (W38)")
_BELOW_ACCURACY = ("; stresses below the surface: |error| <= error_estimate <= rtol * p* under normal load "
                   "(closed-form "
                   "rounding and series truncation bounds, (W38), (W39)), (1 + 4 mu) of it under partial slip; dpdz "
                   "not bounded")


def approximation(method: str) -> Callable[..., np.ndarray] | None:
    """The approximate-pressure kernel a method selects, or None for the exact series methods."""
    return APPROXIMATE.get(_known(method))


def substitutes(method: str) -> bool:
    """Whether the method takes a narrow periodic contact's pressure from the non-periodic series
    where that is within rtol, docs/theory/wavy.md (W26) (method ``auto`` only)."""
    return _known(method) == "auto"


def resolve(method: str, rtol: float, *, below: bool = False) -> tuple[str, str]:
    """(route, accuracy) of a method at tolerance rtol, as written into every field's attributes;
    ``below``: the recipe asks for the field below the surface (exact methods only, (W36)-(W44))."""
    if below:
        route, accuracy = resolve(method, rtol)
        if approximation(method) is not None:
            raise ValueError(f"method {method!r} replaces the pressure only; below the surface use "
                             f"{', '.join(SERIES_METHODS)}")
        return route + _BELOW_ROUTE, accuracy + _BELOW_ACCURACY
    if approximation(method) is not None:
        return (f"the paper's approximate {method.removeprefix('approximate_')} (inaccurate; for comparison only)",
                "not controlled: see the exact series")
    return (_SERIES_ROUTE + (_AUTO_ROUTE if substitutes(method) else ""),
            f"quadrature and series: |error| <= rtol * max(|value|, S), rtol = {rtol:g}, S = p* for pressures "
            "(Delta_1 for u_z); periodic: rounding bound of the closed form (W31), non-periodic: truncated "
            "tail plus rounding of the Bessel series (W22), (W23); error_estimate is an upper bound of |error|, "
            "converged = 1 if and only if error_estimate <= rtol * S")


def _known(method: str) -> str:
    if method not in METHODS:
        raise ValueError(f"unknown wavy method {method!r}; allowed: {', '.join(METHODS)}")
    return method
