"""stressfields: reference datasets of contact-mechanics fields.

    import stressfields as sf
    ds = sf.generate("recipes/cone_figures.toml")   # or a dict with the same keys; lazy xr.Dataset
    sf.to_netcdf(ds, "cone.nc")                     # atomic write
    sf.scenarios()                                  # names with one-line descriptions
"""
from __future__ import annotations

__version__ = "0.1.0"

from .api import describe, generate, scenarios  # noqa: E402
from .io import OutputError, to_netcdf  # noqa: E402
from .recipe import RecipeError  # noqa: E402

__all__ = ["generate", "to_netcdf", "scenarios", "describe", "RecipeError", "OutputError", "__version__"]
