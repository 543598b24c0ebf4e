"""stressfields: reference datasets of contact-mechanics fields.

    import stressfields as sf
    ds = sf.generate("recipes/cone_figures.toml")   # or a dict with the same keys; lazy xr.Dataset
    sf.write(ds, "cone.nc")                         # atomic write (.nc NetCDF, .zarr Zarr; parts=, resume=)
    sf.estimate("recipes/cone_figures.toml")        # dimensions, points, bytes, seconds before running
    sf.scenarios()                                  # names with one-line descriptions
"""
from __future__ import annotations

__version__ = "0.1.0"

from .api import describe, estimate, generate, scenarios  # noqa: E402
from .errors import OutputError  # noqa: E402
from .recipe import RecipeError  # noqa: E402
from .writers import export, to_netcdf, write  # noqa: E402

__all__ = ["generate", "write", "to_netcdf", "export", "estimate", "scenarios", "describe", "RecipeError",
           "OutputError", "__version__"]
