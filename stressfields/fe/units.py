"""Units of an FE engineer's columns: any unit pint can convert to the column's declared dimension
(``N/mm^2``, ``N/mm2``, ``N/mm²``, ``psi``, ``ksi``, ``µm``, ``in``, ...), the explicit table
``units.UNITS`` when pint is not installed. A unit that does not convert is refused in one line
naming the column, the unit and the dimension expected; nothing is guessed.
"""
from __future__ import annotations

from ..units import DIMENSIONS, UNITS, UnitProblem, convert as factor  # noqa: F401 (this module's names)

#: keys of `--units`: which declared unit each one stands for ("displacement" is a length too)
UNIT_KEYS = {"length": "m", "displacement": "m", "stress": "Pa", "force": "N"}


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


#: keys of a recipe's ``[compare]`` table
COMPARE_KEYS = ("units",)


def compare_table_problem(table) -> str | None:
    """What is wrong with a recipe's ``[compare]`` table (None: nothing): ``units`` is a table of
    `UNIT_KEYS` -> a unit of that dimension, as `--units` takes them."""
    if not isinstance(table, dict):
        return "[compare] must be a table, e.g. [compare] units = { length = \"mm\", stress = \"MPa\" }"
    for key in table:
        if key not in COMPARE_KEYS:
            return f"unknown key 'compare.{key}'; allowed: {', '.join(COMPARE_KEYS)}"
    units = table.get("units", {})
    if not isinstance(units, dict) or not all(isinstance(k, str) and isinstance(v, str) for k, v in units.items()):
        return "compare.units must be a table of unit names, e.g. { length = \"mm\", stress = \"MPa\" }"
    for key, value in units.items():
        if key not in UNIT_KEYS:
            return f"unknown key 'compare.units.{key}'; allowed: {', '.join(UNIT_KEYS)}"
        try:
            factor(value, UNIT_KEYS[key], key)
        except UnitProblem as exc:
            return f"compare.units.{key} = {value!r}: " + str(exc).split(": ", 1)[1]
    return None
