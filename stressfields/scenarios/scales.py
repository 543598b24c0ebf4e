"""Normalisation scales: declared once per family, applied in one place.

The physics of a family returns its values in the family's natural unit (stresses per unit of the
effective modulus E*, displacements per indentation depth delta, lengths in the profile's unit,
wavy pressures per p*).  A variable's declaration names its ``Scale``; the scale says, for the
values of one case, the factor that takes the physics' values to the variable's units in either
mode (normalised: divided by the scale; physical: SI units), the text and symbol its attributes
carry, and how ``compare`` finds the scale's value in SI units.  ``apply_scales`` is the one place
the factors multiply values: the scenarios' ``evaluate`` calls it, so ``build`` (the dataset),
``sf.batches`` and ``compare`` (both through ``procedural.evaluate``) all get the same numbers.

E* = E/(1-nu^2) is formed by ``effective_modulus`` and nowhere else.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Iterator, Mapping

import numpy as np

__all__ = ["Scale", "Case", "apply_scales", "effective_modulus"]


def effective_modulus(E, nu, times=1.0):
    """The plane-strain (effective) modulus E* = E/(1 - nu^2) of a rigid indenter on an elastic
    half-space, times ``times``.

    ``times`` multiplies E before the division, ``times * E / (1 - nu^2)``: the wavy family's
    p* = pi E* Delta_1/lambda_1 is defined as pi E/(1-nu^2) Delta_1/lambda_1 and keeps that rounding.
    With ``times = 1`` the product is exact, so the value is E/(1 - nu^2) to the last bit.
    """
    return times * E / (1.0 - nu ** 2)


@dataclass(frozen=True)
class Scale:
    """The normalisation of a family's variables.

    Parameters
    ----------
    symbol : str
        How a normalised variable's label says it ("stress sigma_xx / p_m").
    text : str
        The sentence of the ``normalisation`` attribute and of the description ("... divided by <text>").
    factor : callable
        ``factor(case, physical)`` -> the factor (broadcasting with the block) that takes the physics'
        values to the variable's units: in normalised mode the values divided by the scale, in
        physical mode SI units.  ``case`` is the family's ``Case`` of the block.
    value : callable, optional
        ``value(quantities)`` -> the scale in SI units, from a mapping of the recipe's parameters and
        of the reference's variables by name (``compare``'s S in physical mode); None: no value is
        declared and ``compare`` uses the largest |reference|.
    needs : tuple of str
        The reference variables ``value`` reads (``compare`` asks the reference for them).
    definition : str
        How ``compare`` states S (its ``scale_definition``).
    """

    symbol: str
    text: str
    factor: Callable[[Mapping[str, Any], bool], Any]
    value: Callable[[Mapping[str, Any]], Any] | None = None
    needs: tuple[str, ...] = ()
    definition: str = ""

    def __str__(self) -> str:
        return self.text


class Case(Mapping):
    """The quantities of one block that the scales' factors read, each computed on first use.

    ``Case(a=a, pm=lambda: mean_pressure(a, profile))``: a callable value is called once, when a
    factor first asks for it, so a block whose variables need no p_m never computes it.
    """

    def __init__(self, **quantities: Any) -> None:
        self._lazy = quantities
        self._known: dict[str, Any] = {}

    def __getitem__(self, key: str) -> Any:
        if key not in self._known:
            made = self._lazy[key]
            self._known[key] = made() if callable(made) else made
        return self._known[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._lazy)

    def __len__(self) -> int:
        return len(self._lazy)


def apply_scales(values: Mapping[str, Any], variables: Mapping[str, Any], case: Mapping[str, Any],
                 physical: bool) -> dict[str, Any]:
    """The values in their variables' units: each one whose declaration (``variables[name]``, a
    ``Variable``) names a Scale times that scale's factor for the case and mode; the others as given.

    Parameters
    ----------
    values : Mapping
        name -> the physics' value (per unit of the family's natural scale).
    variables : Mapping
        name -> the Variable declaring it (a scenario's ``{v.name: v}``).
    case : Mapping
        The block's quantities the factors read (a ``Case``).
    physical : bool
        Physical units (else normalised).
    """
    out = dict(values)
    factors: dict[int, Any] = {}
    for name, value in values.items():
        var = variables.get(name)
        scale = getattr(var, "scale", None)
        if scale is None:
            continue
        key = id(scale)
        if key not in factors:
            factors[key] = scale.factor(case, physical)
        out[name] = np.asarray(value) * factors[key]
    return out
