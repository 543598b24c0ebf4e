"""The public Python API; the command line calls the same functions."""
from __future__ import annotations

from pathlib import Path
from typing import Mapping

import xarray as xr

from . import recipe as _recipe
from .build import build
from .scenarios import REGISTRY


def generate(recipe: str | Path | Mapping, chunks: dict[str, int] | None = None) -> xr.Dataset:
    """The recipe's dataset: lazy (dask-backed), CF-annotated; computed when written or `.compute()`d.

    ``recipe`` is a TOML path or a dict with the same keys; ``chunks`` overrides the recipe's
    chunk sizes per dimension.
    """
    return build(_recipe.load(recipe), chunks)


def estimate(recipe: str | Path | Mapping, chunks: dict[str, int] | None = None) -> dict:
    """What running ``recipe`` will produce, before anything large is computed: ``dims``, ``points``,
    ``bytes``, ``chunks`` and ``seconds`` (extrapolated from evaluating a small leading slice)."""
    from .build import estimate as _estimate

    return _estimate(_recipe.load(recipe), chunks)


def scenarios() -> dict[str, str]:
    """Scenario names with their one-line descriptions."""
    return {name: s.summary for name, s in REGISTRY.items()}


def describe(name: str) -> str:
    """Parameters (units, allowed values, defaults) and variables of scenario ``name``, as text."""
    from .schema import scenario_text

    if name not in REGISTRY:
        raise KeyError(f"unknown scenario {name!r}; one of: {', '.join(REGISTRY)}")
    return scenario_text(REGISTRY[name])
