"""Quick-look PNGs of a written dataset, driven by the recipe's optional [plot] table.

    [plot]
    kind = "line"            # "line": curves along `x`, one per value of `hue`; "map": x-y maps
    x = "x"                  # the horizontal dimension, or a variable to plot against
    marker = "o"             # optional marker (e.g. for the turning points of a history)
    hue = "mu"               # one curve per value (line plots)
    variables = ["sigma_xx", "dpdz"]   # one panel each
    ylim = [-20.0, 20.0]     # optional vertical range of line plots
Other dimensions are held at their first value. recipe.py checks the table; every table it
accepts is drawn, and so is a recipe without one (a recipe with nothing swept gets its values as
text).
"""
from __future__ import annotations

import textwrap
from pathlib import Path

import numpy as np
import xarray as xr

from .reading import open_dataset
from .recipe import plot_along

#: at most this many panels (3 columns)
MAX_PANELS = 6
#: characters of a panel title (the variable's long_name, shortened): one line at 7 pt on a 4.6 in panel
TITLE_CHARS = 70


def require_matplotlib():
    """matplotlib.pyplot on the Agg backend, or an ImportError saying how to install it.

    Call it before any work when a plot is asked for, so a missing library costs nothing.
    """
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise ImportError("quick-look PNGs need matplotlib: pip install 'stressfields[plot]'") from None
    return plt


def quicklook(path: str | Path, recipe) -> Path:
    plt = require_matplotlib()
    path = Path(path)
    with open_dataset(path) as ds:          # choice dimensions labelled by name, for the legends
        fig = _figure(plt, ds, recipe)
        fig.suptitle(recipe.title, fontsize=9, wrap=True)
        fig.tight_layout()
        png = path.with_suffix(".png")
        fig.savefig(png, dpi=90)
        plt.close(fig)
    return png


def _figure(plt, ds: xr.Dataset, recipe):
    spec, swept = recipe.plot, recipe.swept
    kind = spec.get("kind", "map" if {"x", "y"} <= set(swept) else "line")
    xname = spec.get("x", "x" if kind == "map" else (swept[-1] if swept else None))
    hue = spec.get("hue")
    dims = {n: v.dims for n, v in ds.variables.items()}      # coordinates too: plot.x may be one (ux0)
    along = plot_along(xname, hue, swept, dims) if kind == "line" and xname else None
    need = {"x", "y"} if kind == "map" else {along}
    names = [n for n in spec.get("variables", recipe.variables)
             if n in ds.data_vars and need <= set(ds[n].dims)][:MAX_PANELS]
    if not names:
        return _text_figure(plt, ds, recipe)
    ncol = min(3, len(names))
    nrow = -(-len(names) // ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.6 * ncol + 1.0, 3.8 * nrow + 0.4), squeeze=False)
    for ax, name in zip(axes.flat, names):
        if kind == "map":
            _map(ax, ds, name)
        else:
            _lines(ax, ds, name, xname, along, hue, spec.get("marker"))
            if "ylim" in spec:
                ax.set_ylim(*spec["ylim"])
        ax.set_title(textwrap.shorten(ds[name].attrs.get("long_name", name), TITLE_CHARS, placeholder=" ..."),
                     fontsize=7)
    for ax in list(axes.flat)[len(names):]:
        ax.set_visible(False)
    return fig


def _map(ax, ds, name):
    da = ds[name]
    da = da.isel({d: 0 for d in da.dims if d not in ("x", "y")})
    da.transpose("y", "x").plot(ax=ax, robust=True, cbar_kwargs={"label": _label(da)})
    ax.set_aspect("equal")
    ax.set_xlabel(_label(ds["x"]))
    ax.set_ylabel(_label(ds["y"]))


def _lines(ax, ds, name, xname, along, hue, marker):
    """One curve of `name` against `xname` along `along` per value of `hue`; other dims at index 0."""
    y, x = xr.broadcast(ds[name], ds[xname])
    hold = {d: 0 for d in y.dims if d not in (along, hue)}
    y, x = y.isel(hold), x.isel(hold)
    if hue in y.dims:
        for i, text in enumerate(_legend(ds[hue])):
            ax.plot(x.isel({hue: i}).values, y.isel({hue: i}).values, lw=1, marker=marker, label=text)
        ax.legend(fontsize=7)
    else:
        ax.plot(x.values, y.values, lw=1, marker=marker)
    ax.set_xlabel(_label(ds[xname]))
    ax.set_ylabel(_label(ds[name]))


def _text_figure(plt, ds, recipe):
    """Nothing varies along a line: the values as text."""
    fig, ax = plt.subplots(figsize=(6.0, 4.0))
    ax.axis("off")
    lines = [f"{n} = {ds[n].values.ravel()[0]!r}" + (" ..." if ds[n].size > 1 else "")
             for n in list(ds.data_vars)[:20]]
    ax.text(0.0, 1.0, "\n".join(lines) or "no variables", va="top", family="monospace", fontsize=7,
            transform=ax.transAxes)
    return fig


def _legend(coord) -> list[str]:
    """One entry per value of a hue dimension: the name of a choice, else ``name = value``."""
    values = np.asarray(coord.values)
    if values.dtype.kind in "OUST":
        return [str(v) for v in values]
    return [f"{coord.name} = {v:g}" for v in values.tolist()]


def _label(da) -> str:
    """An axis label of one short line: the variable's name and its units (the long_name would wrap
    onto 4-8 lines; it is the panel's title)."""
    units = da.attrs.get("units")
    return f"{da.name} [{units}]" if units and units != "1" else str(da.name)
