"""The one table of unit conversions and the one parser of column labels, shared by `[points]` files
and `compare`: a column is named ``name`` or ``name[unit]`` (a CSV header, a .npy field, a .npz
member), or carries a ``units`` attribute (NetCDF); a unit is converted to the unit the recipe
expects by the explicit table `UNITS`, or refused. Nothing is guessed."""
from __future__ import annotations

import re

#: unit -> (the SI unit it converts to, factor): the only conversions made
UNITS = {"Pa": ("Pa", 1.0), "kPa": ("Pa", 1e3), "MPa": ("Pa", 1e6), "GPa": ("Pa", 1e9),
         "m": ("m", 1.0), "mm": ("m", 1e-3), "um": ("m", 1e-6), "N": ("N", 1.0), "1": ("1", 1.0)}

#: a column label: a name (as parameters and variables are named) and an optional unit in brackets;
#: a label of any other form is refused by its position, never quoted (it may be anything a file
#: holds, e.g. the first line of a file that is not a table of points)
LABEL = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_]{0,63})\s*(?:\[\s*([A-Za-z0-9_./*^ -]{1,32}?)\s*\])?\s*$")
LABEL_RULE = ("a name of letters, digits and _ (at most 64, not starting with a digit), optionally with a "
              "unit in brackets such as x[mm]")
#: a unit as written in a ``units`` attribute that may be quoted in a message
_QUOTABLE_UNIT = re.compile(r"^[A-Za-z0-9_./*^ -]{1,32}$")


def parse_label(label: str) -> tuple[str, str | None] | None:
    """(name, unit or None) of a column label, or None if it is not of the form LABEL."""
    match = LABEL.match(label) if isinstance(label, str) else None
    return None if match is None else (match.group(1), match.group(2))


def show_unit(unit) -> str:
    """A unit for a message: quoted if it looks like a unit, else only said to be unreadable."""
    return repr(unit) if isinstance(unit, str) and _QUOTABLE_UNIT.match(unit) else "(not a unit)"


def factor(unit: str | None, target: str) -> float | None:
    """The factor from ``unit`` to ``target`` (None: the column has no unit, so it is in ``target``);
    None if the table has no such conversion."""
    if unit is None or unit == target:
        return 1.0
    known = UNITS.get(unit)
    if known is not None and known[0] == target:
        return known[1]
    return None


def allowed(target: str) -> list[str]:
    """The units convertible to ``target``, ``target`` first."""
    return [target] + [u for u, (base, _) in UNITS.items() if base == target and u != target]
