"""Quick-look PNGs of a written dataset, driven by the recipe's optional [plot] table.

    [plot]
    kind = "line"            # "line": curves along `x`, one per value of `hue`; "map": x-y maps
    x = "x"                  # the horizontal dimension, or a variable to plot against
    marker = "o"             # optional marker (e.g. for the turning points of a history)
    hue = "mu"               # one curve per value (line plots)
    variables = ["sigma_xx", "dpdz"]   # one panel each
    ylim = [-20.0, 20.0]     # optional vertical range of line plots
Other dimensions are held at their first value.
"""
from __future__ import annotations

import textwrap
from pathlib import Path

import xarray as xr


def quicklook(path: str | Path, recipe) -> Path:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise ImportError("quick-look PNGs need matplotlib: pip install 'stressfields[plot]'") from None
    spec = recipe.plot
    path = Path(path)
    with xr.open_dataset(path) as ds:
        names = [v for v in spec.get("variables", recipe.variables) if v in ds and ds[v].ndim][:6]
        kind = spec.get("kind", "map" if {"x", "y"} <= set(recipe.swept) else "line")
        xdim = spec.get("x", recipe.swept[-1] if recipe.swept else None)
        hue = spec.get("hue")
        marker = spec.get("marker")
        ncol = min(3, max(1, len(names)))
        nrow = -(-len(names) // ncol)
        fig, axes = plt.subplots(nrow, ncol, figsize=(4.6 * ncol + 1.0, 3.8 * nrow + 0.4), squeeze=False)
        for ax, name in zip(axes.flat, names):
            da = ds[name]
            if kind == "line" and xdim in ds.data_vars:
                # x may be another variable (e.g. force against displacement): plot one against the other
                da = da.assign_coords({xdim: ds[xdim]})
            keep = set(ds[xdim].dims) | {hue} if kind == "line" else {"x", "y"}
            da = da.isel({d: 0 for d in da.dims if d not in keep})
            label = _label(da)
            if kind == "map":
                da.transpose("y", "x").plot(ax=ax, robust=True, cbar_kwargs={"label": label})
                ax.set_aspect("equal")
                ax.set_ylabel(_label(ds["y"]))
            elif hue in da.dims:
                names_ = ds[f"{hue}_name"].values if f"{hue}_name" in ds else None
                for i, value in enumerate(da[hue].values):
                    text = names_[i] if names_ is not None else f"{hue} = {value:g}"
                    da.isel({hue: i}).plot.line(ax=ax, x=xdim, label=text, lw=1, marker=marker)
                ax.legend(fontsize=7)
                ax.set_ylabel(label)
            else:
                da.plot.line(ax=ax, x=xdim, lw=1, marker=marker)
                ax.set_ylabel(label)
            ax.set_xlabel(_label(ds[xdim if kind == "line" else "x"]))
            ax.set_title(textwrap.fill(da.attrs.get("long_name", name), 60), fontsize=7)
            if "ylim" in spec and kind == "line":
                ax.set_ylim(*spec["ylim"])
        for ax in list(axes.flat)[len(names):]:
            ax.set_visible(False)
        fig.suptitle(recipe.title, fontsize=9, wrap=True)
        fig.tight_layout()
        png = path.with_suffix(".png")
        fig.savefig(png, dpi=90)
        plt.close(fig)
    return png


def _label(da) -> str:
    units = da.attrs.get("units")
    return f"{da.name} [{units}]" if units else str(da.name)
