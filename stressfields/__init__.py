"""stressfields: reference datasets of contact-mechanics fields.

    import stressfields as sf
    ds = sf.generate("recipes/cone_figures.toml")   # or a dict with the same keys; lazy xr.Dataset
    sf.write(ds, "cone.nc")                         # atomic write (.nc NetCDF, .zarr Zarr; parts=, resume=;
                                                    # dtype="float32", compression=4, nonfinite="nan")
    sf.open_dataset("cone.nc")                      # reopen lazily, choice dimensions labelled by name
    sf.estimate("recipes/cone_figures.toml")        # dimensions, points, bytes, seconds before running
    sf.scenarios()                                  # names with one-line descriptions
    sf.compare("recipe.toml", "nodes.csv")          # your FE results against the reference at their nodes
    sf.batches("recipe.toml", 4096, seed=0)         # (inputs, targets) NumPy batches at seeded Sobol points

The names are imported on first use: xarray imports this package to list its backend
(``engine="stressfields"``) whenever it opens a file, and that must not load the physics.
"""
from __future__ import annotations

import importlib

__version__ = "0.1.0"

from .errors import OutputError  # noqa: E402

#: public name -> the module that defines it
_LAZY = {"generate": "api", "estimate": "api", "scenarios": "api", "describe": "api", "RecipeError": "recipe",
         "write": "writers", "to_netcdf": "writers", "export": "writers", "output_options": "writers",
         "open_dataset": "reading", "compare": "comparison", "batches": "procedural"}

__all__ = ["generate", "write", "to_netcdf", "export", "open_dataset", "output_options", "estimate", "scenarios",
           "describe", "compare", "batches", "RecipeError", "OutputError", "__version__"]


def __getattr__(name: str):
    if name in _LAZY:
        value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    try:
        return importlib.import_module(f".{name}", __name__)     # sf.writers, sf.cli, ...
    except ModuleNotFoundError as exc:
        if exc.name != f"{__name__}.{name}":
            raise
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None


def __dir__():
    return sorted([*globals(), *_LAZY])
