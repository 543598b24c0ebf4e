"""The [plot] table of a recipe (the quick-look PNG of `stressfields run --plot`): its keys, its
check against what the dataset will hold (`problems`, called by `recipe.load`), and the choices
`plot.py` draws by (`plot_kind`, `map_plane`, `plot_along`). Light: the recipe check imports it
without matplotlib or xarray.
"""
from __future__ import annotations

import math

from .errors import show
from .scenarios.base import Scenario

PLOT_KEYS = ("x", "variables", "hue", "kind", "ylim", "marker")
PLOT_KINDS = ("line", "map")
#: matplotlib's one-character markers
PLOT_MARKERS = tuple(".,ov^<>12348spP*hHxXDd|_+")


def check(scen: Scenario, plot: dict, swept: tuple[str, ...], variables: tuple[str, ...],
          physical: bool) -> list[str]:
    """Check the [plot] table against what the dataset will hold (plot.py draws every table that passes)."""
    problems: list[str] = []
    if not plot:
        return problems
    if not swept:
        return ["[plot] needs a swept parameter to plot along; none is swept"]
    shown = list(variables) + [v.name for v in scen.variables_in(physical) if v.always]
    dims = {n: tuple(d for d in swept if scen.variable(n).dims is None or d in scen.variable(n).dims)
            for n in shown}
    kind = plot_kind(plot, swept)
    if kind not in PLOT_KINDS:
        return [f"plot.kind = {show(kind)} must be one of {', '.join(map(repr, PLOT_KINDS))}"]
    plane = map_plane(swept)
    if kind == "map" and plane is None:
        problems.append(f"plot.kind = 'map' needs x and y swept (or x and z); swept: {', '.join(swept)}")
    across = plane[0] if plane else "x"
    x = plot.get("x", across if kind == "map" else swept[-1])
    if kind == "map" and x != across:
        problems.append(f"plot.x = {show(x)}: a map is drawn over {across} and {plane[1] if plane else 'y'}; "
                        "leave plot.x out")
    elif not isinstance(x, str) or (x not in swept and not dims.get(x)):
        problems.append(f"plot.x = {show(x)} must name a swept parameter ({', '.join(swept)}) or a variable "
                        f"of the output that depends on one ({', '.join(n for n in shown if dims[n])})")
    if problems:
        return problems
    hue = plot.get("hue")
    along = plot_along(x, hue, swept, dims) if kind == "line" else None
    if kind == "line" and along is None:
        return [f"plot.x = {x!r} depends only on plot.hue = {show(hue)}: nothing to draw a line along"]
    if hue is not None and (kind == "map" or not isinstance(hue, str) or hue not in swept or hue in (x, along)):
        problems.append(f"plot.hue = {show(hue)} must name a swept parameter other than the horizontal axis "
                        f"({', '.join(d for d in swept if d not in (x, along)) or 'none'}), in a line plot")
    need = set(plane) if kind == "map" else {along}
    need_text = " and ".join(sorted(need))
    names = plot.get("variables")
    if names is not None and not (isinstance(names, list) and names and all(isinstance(n, str) for n in names)):
        problems.append(f"plot.variables = {show(names)} must be a non-empty list of names of the output")
    elif names is not None:
        for n in names:
            if n not in dims:
                problems.append(f"plot.variables: {show(n)} is not in the output; one of: {', '.join(shown)}")
            elif not need <= set(dims[n]):
                problems.append(f"plot.variables: {n!r} does not depend on {need_text}")
    elif not problems and not any(need <= set(dims[n]) for n in variables):
        problems.append(f"[plot]: no output variable depends on {need_text}; "
                        "name one in plot.variables")
    ylim = plot.get("ylim")
    if ylim is not None and not (isinstance(ylim, list) and len(ylim) == 2 and all(
            isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in ylim)
            and ylim[0] < ylim[1]):
        problems.append(f"plot.ylim = {show(ylim)} must be [low, high], two finite numbers, low < high")
    marker = plot.get("marker")
    if marker is not None and marker not in PLOT_MARKERS:
        problems.append(f"plot.marker = {show(marker)} must be one of {' '.join(PLOT_MARKERS)}")
    return problems


#: the sections below the surface: x-z (a plane through the axis, signed x), rho-z (the radius r/a
#: of an axisymmetric field, the graded scenarios)
SECTIONS = (("x", "z"), ("rho", "z"))


def map_plane(swept) -> tuple[str, str] | None:
    """The plane of a map: x-y where both are swept, else a section (x-z, rho-z) below the surface."""
    for plane in (("x", "y"),) + SECTIONS:
        if set(plane) <= set(swept):
            return plane
    return None


def plot_kind(spec: dict, swept) -> str:
    """plot.kind, else "map" over x and y, or over x and z unless the table asks for a line (an x or
    a hue), else "line"."""
    if "kind" in spec:
        return spec["kind"]
    plane = map_plane(swept)
    if plane == ("x", "y") or (plane in SECTIONS and not {"x", "hue"} & set(spec)):
        return "map"
    return "line"


def plot_along(x: str, hue, swept: tuple[str, ...], dims: dict) -> str | None:
    """The dimension a line plot runs along: x itself if swept, else the last dimension of the
    variable x other than hue (None if there is none)."""
    if x in swept:
        return x
    rest = [d for d in dims.get(x, ()) if d != hue]
    return rest[-1] if rest else None
