"""stressfields: reference datasets of contact-mechanics fields.

    import stressfields as sf
    ds = sf.generate("recipes/cone_fig2_sigma_xx.toml")   # or a dict with the same keys; lazy xr.Dataset
    sf.write(ds, "cone.nc")                         # atomic write (.nc NetCDF, .zarr Zarr; parts=, resume=;
                                                    # dtype="float32", compression=4, nonfinite="nan"; by
                                                    # default the recipe's [output] options)
    sf.run("recipe.toml", "cone.nc")                # `stressfields run recipe.toml -o cone.nc`: checked first
    sf.open_dataset("cone.nc")                      # reopen lazily, choice dimensions labelled by name
    sf.estimate("recipes/cone_fig2_sigma_xx.toml")        # dimensions, points, bytes, seconds before running
    sf.scenarios()                                  # names with one-line descriptions
    sf.compare("recipe.toml", "nodes.csv")          # your FE results against the reference at their nodes
    sf.batches("recipe.toml", 4096, seed=0)         # (inputs, targets) NumPy batches at seeded Sobol points
    sf.open_mfdataset("sweep_*.nc", concat_dim="mu")  # a sweep split over files, every source recipe kept
    sf.examples(); sf.open_example("hertz_subsurface")  # the recipes shipped with the package

The names are imported on first use: xarray imports this package to list its backend
(``engine="stressfields"``) whenever it opens a file, and that must not load the physics.
"""
from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from .errors import OutputError  # noqa: E402
from .version import __version__  # noqa: E402 (the one source: version.py)

#: public name -> the module that defines it
_LAZY = {"generate": "api", "estimate": "api", "scenarios": "api", "describe": "api", "RecipeError": "errors",
         "examples": "api", "example": "api", "open_example": "api", "open_mfdataset": "reading",
         "write": "output.formats", "to_netcdf": "output.formats", "export": "output.formats",
         "output_options": "output.options", "run": "api",
         "open_dataset": "reading", "compare": "api", "batches": "procedural"}

__all__ = ["generate", "run", "write", "to_netcdf", "export", "open_dataset", "open_mfdataset", "output_options",
           "estimate", "scenarios", "describe", "compare", "batches", "examples", "example", "open_example",
           "RecipeError", "OutputError", "__version__"]

if TYPE_CHECKING:       # what the lazy names are, for type checkers and IDEs
    from .api import compare, describe, estimate, example, examples, generate, open_example, run, scenarios
    from .procedural import batches
    from .reading import open_dataset, open_mfdataset
    from .errors import RecipeError
    from .output.formats import export, to_netcdf, write
    from .output.options import output_options


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    try:
        return importlib.import_module(f".{name}", __name__)     # sf.output, sf.cli, ...
    except ModuleNotFoundError as exc:
        if exc.name != f"{__name__}.{name}":
            raise
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None


def __dir__() -> list[str]:
    return sorted([*globals(), *_LAZY])
