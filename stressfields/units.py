"""The one table of unit conversions and the one parser of column labels, shared by `[points]` files
and `compare`: a column is named ``name`` or ``name[unit]`` (a CSV header, a .npy field, a .npz
member), or carries a ``units`` attribute (NetCDF); a unit is converted to the unit the recipe
expects by the explicit table `UNITS` (exact factors), else by pint where it is installed (``N/mm^2``,
``psi``, ``µm``, ``in``: any unit of the expected dimension), or refused. Nothing is guessed."""
from __future__ import annotations

import functools
import re

#: unit -> (the SI unit it converts to, factor): the only conversions made
UNITS = {"Pa": ("Pa", 1.0), "kPa": ("Pa", 1e3), "MPa": ("Pa", 1e6), "GPa": ("Pa", 1e9),
         "m": ("m", 1.0), "mm": ("m", 1e-3), "um": ("m", 1e-6), "N": ("N", 1.0), "1": ("1", 1.0)}

#: a column label: a name and an optional unit in brackets or parentheses, as FE exports write them
#: (``x[mm]``, ``X(mm)``, ``S-S11 (N/mm^2)``; words apart only in an id column's name, ``Node Label``).
#: A label of any other form is refused by its position, never quoted (it may be anything a file
#: holds, e.g. the first line of a file that is not a table of points): the characters allowed make
#: a label safe to quote.
LABEL = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_.-]{0,63}(?: (?:Label|label|ID|Id|id|Number|number))?)\s*"
                   r"(?:\[\s*([A-Za-z0-9_./*^ µ²³-]{1,32}?)\s*\]|\(\s*([A-Za-z0-9_./*^ µ²³-]{1,32}?)\s*\))?\s*$")
LABEL_RULE = ("a name of letters, digits, _, - and . (at most 64, starting with a letter or _; an id column "
              "may be written 'Node Label' or 'Node ID'), optionally with a unit in brackets or parentheses "
              "such as x[mm] or X(mm)")
#: a unit as written in a ``units`` attribute that may be quoted in a message
_QUOTABLE_UNIT = re.compile(r"^[A-Za-z0-9_./*^ µ²³-]{1,32}$")


def parse_label(label: str) -> tuple[str, str | None] | None:
    """(name, unit or None) of a column label, or None if it is not of the form LABEL."""
    match = LABEL.match(label) if isinstance(label, str) else None
    return None if match is None else (match.group(1), match.group(2) or match.group(3))


def show_unit(unit) -> str:
    """A unit for a message: quoted if it looks like a unit, else only said to be unreadable."""
    return repr(unit) if isinstance(unit, str) and _QUOTABLE_UNIT.match(unit) else "(not a unit)"


_SUPERSCRIPT = str.maketrans({"²": "^2", "³": "^3", "¹": "", "µ": "u", "μ": "u", "·": "*", "−": "-"})
_BARE_POWER = re.compile(r"(?<=[A-Za-z])([23])\b")       # N/mm2 -> N/mm^2 (never 1e2: a letter before)


def normal_form(unit: str) -> str:
    """A unit as FE exports write it, in the form the table and pint read (N/mm² -> N/mm^2, µm -> um)."""
    return _BARE_POWER.sub(r"^\1", unit.strip().translate(_SUPERSCRIPT))


@functools.lru_cache(maxsize=None)
def registry():
    """pint's unit registry (built once, ~2 s), or None where pint is not installed."""
    try:
        import pint
    except ImportError:          # optional: the table serves the common units
        return None
    return pint.UnitRegistry()


def factor(unit: str | None, target: str) -> float | None:
    """The factor from ``unit`` to ``target`` (None: the column has no unit, so it is in ``target``);
    None if neither the table nor pint converts it (`convert` says why)."""
    if unit is None or unit == target:
        return 1.0
    unit = normal_form(unit)
    known = UNITS.get(unit)
    if known is not None and known[0] == target:
        return known[1]
    if known is not None or registry() is None:
        return None
    try:
        return convert(unit, target, "")
    except UnitProblem:
        return None


def allowed(target: str) -> list[str]:
    """The units convertible to ``target``, ``target`` first."""
    return [target] + [u for u, (base, _) in UNITS.items() if base == target and u != target]


#: the declared units of the scenarios (SI, or "1") -> the dimension a message names
DIMENSIONS = {"Pa": "stress (e.g. Pa, MPa, N/mm^2, psi)", "m": "length (e.g. m, mm, um, in)",
              "N": "force (e.g. N, kN, lbf)", "Pa/m": "stress per length (e.g. Pa/m, MPa/mm)",
              "1": "a pure number (1)"}


class UnitProblem(ValueError):
    """A unit that cannot be converted to the expected one (the message is one line)."""


def convert(unit: str | None, target: str, label: str) -> float:
    """The factor from ``unit`` to the declared ``target`` unit (SI or "1"); None or "" is the target.
    The table's exact factors first (no pint registry built for them), then pint; UnitProblem (one
    line naming the column ``label``, the unit and the dimension expected) if neither converts it."""
    if unit is None or not unit.strip() or unit.strip() == target:
        return 1.0
    return _convert(normal_form(unit), target, label, unit)


@functools.lru_cache(maxsize=256)
def _convert(unit: str, target: str, label: str, given: str) -> float:
    expected = DIMENSIONS.get(target, repr(target))
    known = UNITS.get(unit)
    if known is not None and known[0] == target:
        return known[1]         # the table's exact factors: no pint registry built (~2 s) for them
    ureg = registry()
    if ureg is None:
        allowed = ", ".join([target] + [u for u, (base, _) in UNITS.items() if base == target and u != target])
        raise UnitProblem(f"column {label!r}: unit {show_unit(given)} is not {expected} in the table of known units "
                          f"({allowed}; install pint for any other)")
    import pint

    try:
        quantity = ureg.Quantity(1.0, unit)
        if quantity.unitless and unit not in ("1", ""):
            raise pint.errors.UndefinedUnitError(unit)
        value = quantity.to(ureg.Quantity(1.0, "dimensionless" if target == "1" else target).units).magnitude
    except pint.errors.DimensionalityError:
        raise UnitProblem(f"column {label!r}: unit {show_unit(given)} is not {expected}") from None
    except (pint.errors.PintError, AttributeError, TypeError, ValueError, AssertionError, SyntaxError):
        raise UnitProblem(f"column {label!r}: unit {show_unit(given)} is not a unit pint knows; "
                          f"expected {expected}") from None
    return float(value)


# -- the header forms FE exports write (node files of `compare` and `[points]` files alike) --------

#: header names (lower case, spaces and hyphens as _) -> canonical column names
ALIASES = {
    **dict.fromkeys(("node", "node_label", "nodelabel", "nodeid", "node_id", "id", "node_number", "nid"), "node"),
    **dict.fromkeys(("weight", "weights", "quadrature_weight", "volume", "cell_volume", "ivol", "w"), "weight"),
    "coord_coor1": "x", "coord_coor2": "y", "coord_coor3": "z", "coor1": "x", "coor2": "y", "coor3": "z",
    "radius": "r",
    **{f"{p}{i}{j}": f"sigma_{'xyz'[int(i) - 1]}{'xyz'[int(j) - 1]}" for p in ("s_s", "s") for i, j in
       (("1", "1"), ("2", "2"), ("3", "3"), ("1", "2"), ("1", "3"), ("2", "3"))},
    **{f"{p}{i}": f"u_{'xyz'[int(i) - 1]}" for p in ("u_u", "u") for i in "123"},
    "s_mises": "von_mises", "mises": "von_mises", "tresca": None,
}
#: cylindrical index spellings -> one letter (t for theta)
_INDEX = {"theta": "t", "th": "t", "t": "t", "r": "r", "z": "z", "x": "x", "y": "y"}
_COMPONENT = re.compile(r"^(sigma|s|u|tau)_?((?:theta|th|[rtxyz]))((?:theta|th|[rtxyz]))?$")
_HEADER = re.compile(r"^\s*\"?\s*(?P<name>[^\[\]()\"]*?)\s*(?:[\[(]\s*(?P<unit>[^\])]*?)\s*[\])])?\s*\"?\s*$")

def canonical(header: str) -> tuple[str, str | None]:
    """(canonical name, unit or None) of a header: ``X[mm]``, ``x(mm)``, ``Node Label``, ``S-S11``,
    ``sigma_thetatheta [MPa]``, ``sigma_zr``."""
    match = _HEADER.match(header)
    unit = match.group("unit") if match else None
    written = written_name(header)
    name = written.lower()
    if name in ALIASES and ALIASES[name]:
        return ALIASES[name], unit or None
    if name in ("x", "y", "z", "r"):
        return name, unit or None
    comp = _COMPONENT.match(name)
    if comp and (comp.group(1) == "u") == (comp.group(3) is None):
        i = _INDEX[comp.group(2)]
        if comp.group(1) == "u":
            return f"u_{i}", unit or None
        j = _INDEX[comp.group(3)]
        if "rt".find(i) >= 0 or "rt".find(j) >= 0 or {i, j} == {"z"}:
            order = "rtz"
        else:
            order = "xyz"
        if i in order and j in order and order.index(i) > order.index(j):
            i, j = j, i
        return f"sigma_{i}{j}", unit or None
    return written, unit or None            # as written: a parameter such as R or E keeps its case


def written_name(header: str) -> str:
    """A header's name as written, without its unit (spaces, hyphens, dots as _): ``uz[um]`` -> ``uz``,
    the name a scenario may declare where `canonical` says ``u_z``."""
    match = _HEADER.match(header)
    raw = match.group("name") if match else header
    return re.sub(r"[\s\-.:/]+", "_", raw.strip()).strip("_")


#: columns of an FE export that are not parameters: a [points] file may carry them, unused
NOT_PARAMETERS = ("node", "weight", "body")
