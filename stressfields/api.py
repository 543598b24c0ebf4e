"""The public Python API; the command line calls the same functions.

xarray, dask and the recipe checker (which imports the writers) are imported by the functions that
use them, so that `scenarios` and `describe` (and `stressfields list`/`describe`) load only the
scenario declarations.
"""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, Mapping, Sequence

from .scenarios import REGISTRY

if TYPE_CHECKING:
    import xarray as xr


def generate(recipe: str | Path | Mapping, chunks: dict[str, int] | None = None, *,
             allow_read: Sequence[str | Path] = ()) -> xr.Dataset:
    """The recipe's dataset: lazy (dask-backed), CF-annotated; computed when written or `.compute()`d.

    Parameters
    ----------
    recipe : str, Path or Mapping
        A TOML recipe file (``"-"``: standard input) or a dict with the same keys.
    chunks : dict of str to int, optional
        Chunk sizes per dimension, overriding the recipe's ``[output] chunks``.
    allow_read : sequence of path, optional
        Folders a ``[points] file`` may also be read from; by default it must lie inside the
        recipe's folder (a dict's: the working directory), symbolic links resolved.

    Returns
    -------
    xarray.Dataset
        One variable per requested field, one dimension per swept parameter.

    Raises
    ------
    RecipeError
        Naming every problem of the recipe at once; nothing is computed.
    """
    from .build import build
    from .recipe import load

    return build(load(recipe, allow_read), chunks)


def estimate(recipe: str | Path | Mapping, chunks: dict[str, int] | None = None, *,
             allow_read: Sequence[str | Path] = ()) -> dict[str, Any]:
    """What running ``recipe`` will produce, before anything large is computed.

    Parameters
    ----------
    recipe : str, Path or Mapping
        As for `generate`.
    chunks : dict of str to int, optional
        As for `generate`.
    allow_read : sequence of path, optional
        As for `generate`.

    Returns
    -------
    dict
        ``dims``, ``points``, ``bytes``, ``chunks`` and ``seconds`` (extrapolated from evaluating a
        small leading slice), ``sample_points``.
    """
    from .build import estimate as _estimate
    from .recipe import load

    return _estimate(load(recipe, allow_read), chunks)


def scenarios() -> dict[str, str]:
    """The scenarios.

    Returns
    -------
    dict of str to str
        Scenario names with their one-line descriptions.
    """
    return {name: s.summary for name, s in REGISTRY.items()}


def describe(name: str) -> str:
    """Parameters (units, allowed values, defaults) and variables of a scenario.

    Parameters
    ----------
    name : str
        A scenario name (`scenarios`).

    Returns
    -------
    str
        The scenario's section of data_schema.md, as Markdown text.

    Raises
    ------
    KeyError
        For an unknown name, listing the known ones.
    """
    from .schema import scenario_text

    if name not in REGISTRY:
        raise KeyError(f"unknown scenario {name!r}; one of: {', '.join(REGISTRY)}")
    return scenario_text(REGISTRY[name])



def examples() -> list[str]:
    """The recipes shipped with the package (the repository's ``recipes/`` and ``examples/``).

    Returns
    -------
    list of str
        Names for `example` and `open_example`: a recipe's file name without ``.toml``
        (``"hertz_subsurface"``), or ``folder/name`` for the examples (``"large_sweep/giga"``).
    """
    root = _shipped()
    names = sorted(p.name[:-5] for p in (root / "recipes").iterdir() if p.name.endswith(".toml"))
    folders = sorted(p for p in (root / "examples").iterdir() if p.is_dir())
    return names + [f"{d.name}/{p.name[:-5]}" for d in folders for p in sorted(d.iterdir()) if p.name.endswith(".toml")]


def example(name: str) -> Path:
    """The path of a shipped recipe.

    Parameters
    ----------
    name : str
        One of `examples` (``"cone_fig2_sigma_xx"``, ``"fe_hertz_mindlin/recipe"``).

    Returns
    -------
    pathlib.Path
        The recipe file inside the installed package; recipes that name other files (points) find them
        beside it.

    Raises
    ------
    KeyError
        For an unknown name, listing the known ones.
    """
    if name not in examples():
        raise KeyError(f"unknown example {name!r}; one of: {', '.join(examples())}")
    root = _shipped()
    folder, _, stem = name.rpartition("/")
    return Path(str(root / ("examples/" + folder if folder else "recipes") / f"{stem}.toml"))


def open_example(name: str, chunks: dict[str, int] | None = None) -> xr.Dataset:
    """The lazy dataset of a shipped recipe: ``generate(example(name), chunks)``.

    Parameters
    ----------
    name : str
        One of `examples`.
    chunks : dict of str to int, optional
        As for `generate`.

    Returns
    -------
    xarray.Dataset
        As `generate` gives it; nothing is computed yet.
    """
    return generate(example(name), chunks)


def _shipped():
    from importlib.resources import files

    return files(__package__)
