"""Quick-look PNGs of a written dataset, driven by the recipe's optional [plot] table.

    [plot]
    kind = "line"            # "line": curves along `x`, one per value of `hue`; "map": x-y maps
    x = "x"                  # the horizontal dimension
    hue = "mu"               # one curve per value (line plots)
    variables = ["sigma_xx", "dpdz"]   # one panel each
Other dimensions are held at their first value.
"""
from __future__ import annotations

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
        ncol = min(3, max(1, len(names)))
        nrow = -(-len(names) // ncol)
        fig, axes = plt.subplots(nrow, ncol, figsize=(4.2 * ncol, 3.4 * nrow), squeeze=False)
        for ax, name in zip(axes.flat, names):
            da = ds[name]
            keep = {xdim, hue} if kind == "line" else {"x", "y"}
            da = da.isel({d: 0 for d in da.dims if d not in keep})
            if kind == "map":
                da.transpose("y", "x").plot(ax=ax, robust=True)
                ax.set_aspect("equal")
            elif hue in da.dims:
                for value in da[hue].values:
                    da.sel({hue: value}).plot(ax=ax, x=xdim, label=f"{hue} = {value}", lw=1)
                ax.legend(fontsize=7)
            else:
                da.plot(ax=ax, x=xdim, lw=1)
            ax.set_title(name, fontsize=9)
        for ax in list(axes.flat)[len(names):]:
            ax.set_visible(False)
        fig.suptitle(recipe.title, fontsize=10)
        fig.tight_layout()
        png = path.with_suffix(".png")
        fig.savefig(png, dpi=90)
        plt.close(fig)
    return png
