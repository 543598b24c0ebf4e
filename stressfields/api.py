"""The public Python API; the command line calls the same functions.

xarray, dask and the recipe checker (which imports the writers) are imported by the functions that
use them, so that `scenarios` and `describe` (and `stressfields list`/`describe`) load only the
scenario declarations.
"""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Mapping

from .scenarios import REGISTRY

if TYPE_CHECKING:
    import xarray as xr


def generate(recipe: str | Path | Mapping, chunks: dict[str, int] | None = None, *, allow_read=()) -> xr.Dataset:
    """The recipe's dataset: lazy (dask-backed), CF-annotated; computed when written or `.compute()`d.

    ``recipe`` is a TOML path or a dict with the same keys; ``chunks`` overrides the recipe's
    chunk sizes per dimension. A ``[points] file`` is read only from inside the recipe's folder (a
    dict's: the working directory), symbolic links resolved, or from inside a folder listed in
    ``allow_read``.
    """
    from .build import build
    from .recipe import load

    return build(load(recipe, allow_read), chunks)


def estimate(recipe: str | Path | Mapping, chunks: dict[str, int] | None = None, *, allow_read=()) -> dict:
    """What running ``recipe`` will produce, before anything large is computed: ``dims``, ``points``,
    ``bytes``, ``chunks`` and ``seconds`` (extrapolated from evaluating a small leading slice);
    ``allow_read`` as for `generate`."""
    from .build import estimate as _estimate
    from .recipe import load

    return _estimate(load(recipe, allow_read), chunks)


def scenarios() -> dict[str, str]:
    """Scenario names with their one-line descriptions."""
    return {name: s.summary for name, s in REGISTRY.items()}


def describe(name: str) -> str:
    """Parameters (units, allowed values, defaults) and variables of scenario ``name``, as text."""
    from .schema import scenario_text

    if name not in REGISTRY:
        raise KeyError(f"unknown scenario {name!r}; one of: {', '.join(REGISTRY)}")
    return scenario_text(REGISTRY[name])

