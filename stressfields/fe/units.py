"""Units of an FE engineer's columns: any unit pint can convert to the column's declared dimension
(``N/mm^2``, ``N/mm2``, ``N/mm²``, ``psi``, ``ksi``, ``µm``, ``in``, ...), the explicit table
``comparison.UNITS`` when pint is not installed. A unit that does not convert is refused in one line
naming the column, the unit and the dimension expected; nothing is guessed.
"""
from __future__ import annotations

import functools
import re

#: unit -> (the SI unit it converts to, exact factor): the conversions made without pint (and first)
UNITS = {"Pa": ("Pa", 1.0), "kPa": ("Pa", 1e3), "MPa": ("Pa", 1e6), "GPa": ("Pa", 1e9),
         "m": ("m", 1.0), "mm": ("m", 1e-3), "um": ("m", 1e-6), "N": ("N", 1.0), "1": ("1", 1.0)}
#: the declared units of the scenarios (SI, or "1") -> the dimension a message names
DIMENSIONS = {"Pa": "stress (e.g. Pa, MPa, N/mm^2, psi)", "m": "length (e.g. m, mm, um, in)",
              "N": "force (e.g. N, kN, lbf)", "Pa/m": "stress per length (e.g. Pa/m, MPa/mm)",
              "1": "a pure number (1)"}
#: keys of `--units`: which declared unit each one stands for ("displacement" is a length too)
UNIT_KEYS = {"length": "m", "displacement": "m", "stress": "Pa", "force": "N"}
_SUPERSCRIPT = str.maketrans({"²": "^2", "³": "^3", "¹": "", "µ": "u", "μ": "u", "·": "*", "−": "-"})
_BARE_POWER = re.compile(r"(?<=[A-Za-z])([23])\b")       # N/mm2 -> N/mm^2 (never 1e2: a letter before)


class UnitProblem(ValueError):
    """A unit that cannot be converted to the expected one (the message is one line)."""


def _normal(unit: str) -> str:
    text = unit.strip().translate(_SUPERSCRIPT)
    return _BARE_POWER.sub(r"^\1", text)


@functools.lru_cache(maxsize=None)
def _registry():
    try:
        import pint
    except ImportError:          # optional: the table below serves the common units
        return None
    return pint.UnitRegistry()


def factor(unit: str | None, target: str, label: str) -> float:
    """The factor from ``unit`` to the declared ``target`` unit (SI or "1"); None or "" is the target.

    ``label`` names the column in the message of UnitProblem."""
    if unit is None or not unit.strip() or unit.strip() == target:
        return 1.0
    return _factor(_normal(unit), target, label, unit)


@functools.lru_cache(maxsize=256)
def _factor(unit: str, target: str, label: str, given: str) -> float:
    expected = DIMENSIONS.get(target, repr(target))
    known = UNITS.get(unit)
    if known is not None and known[0] == target:
        return known[1]         # the table's exact factors: no pint registry built (~2 s) for them
    ureg = _registry()
    if ureg is None:
        allowed = ", ".join([target] + [u for u, (base, _) in UNITS.items() if base == target and u != target])
        raise UnitProblem(f"column {label!r}: unit {given!r} is not {expected} in the table of known units "
                          f"({allowed}; install pint for any other)")
    import pint

    try:
        quantity = ureg.Quantity(1.0, unit)
        if quantity.unitless and unit not in ("1", ""):
            raise pint.errors.UndefinedUnitError(unit)
        value = quantity.to(ureg.Quantity(1.0, "dimensionless" if target == "1" else target).units).magnitude
    except pint.errors.DimensionalityError:
        raise UnitProblem(f"column {label!r}: unit {given!r} is not {expected}") from None
    except (pint.errors.PintError, AttributeError, TypeError, ValueError, AssertionError, SyntaxError):
        raise UnitProblem(f"column {label!r}: unit {given!r} is not a unit pint knows; expected {expected}") from None
    return float(value)


def parse_unit_option(text: str | None) -> dict[str, str]:
    """``length=mm,stress=MPa,force=N`` -> {key: the user's unit}, each checked against its dimension
    (UnitProblem if bad): the units of a format that carries none (VTU, Exodus II, ...)."""
    out: dict[str, str] = {}
    if not text:
        return out
    for item in text.split(","):
        key, sep, value = item.partition("=")
        key, value = key.strip(), value.strip()
        if not sep or key not in UNIT_KEYS or not value:
            raise UnitProblem(f"--units {item.strip()!r}: give key=unit with a key among "
                              f"{', '.join(UNIT_KEYS)}, e.g. length=mm,stress=MPa")
        try:                    # checked now: refused before any work
            factor(value, UNIT_KEYS[key], key)
        except UnitProblem as exc:
            raise UnitProblem(f"--units {key}={value}: " + str(exc).split(": ", 1)[1]) from None
        out[key] = value
    return out


def unit_from_option(name: str, target: str, units: dict[str, str]) -> str | None:
    """The unit `--units` gives a column of declared unit ``target`` (None: it gives none)."""
    if target == "m":
        return units.get("displacement" if name.startswith("u_") else "length", units.get("length"))
    if target == "Pa":
        return units.get("stress")
    if target == "N":
        return units.get("force")
    if target == "Pa/m" and "stress" in units and "length" in units:
        return f"({units['stress']})/({units['length']})"
    return None
