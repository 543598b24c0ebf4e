"""The public Python API, and the one front door of a run; the command line calls the same functions.

`run` (and `plan` + `check_space` + `Run.write`, for several recipes checked before any is
computed) owns everything before the computation: the recipe check, the chunking's task count,
the target check, the free space, the parts policy (`PARTS_ABOVE`), and the output options (the
recipe's ``[output]`` dtype, compression and nonfinite, under the caller's overrides). A dataset of
`generate` carries its recipe's output options, so ``sf.write(sf.generate(recipe), path)`` stores
what the recipe asks, as ``stressfields run recipe -o path`` does.

Everything is imported by the functions that use it: `scenarios` and `describe` (and `stressfields
list`/`describe`) load only the scenario declarations, and `--help` (which quotes `PARTS_ABOVE`)
not even those.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Mapping, Sequence

if TYPE_CHECKING:
    import xarray as xr

    from .output.options import OutputOptions
    from .recipe import Recipe

#: sweeps of more points than this are written in resumable parts where the format allows (NetCDF):
#: a killed run of that size is resumed, not computed again
PARTS_ABOVE = 50_000_000


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
    from .output.options import OPTIONS_ATTR

    recipe = _loaded(recipe, allow_read)
    ds = build(recipe, chunks)
    # the recipe's [output] options travel with the dataset: `write` applies them unless told otherwise
    ds.encoding[OPTIONS_ATTR] = dict(recipe.storage)
    return ds


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

    return _estimate(_loaded(recipe, allow_read), chunks)


def scenarios() -> dict[str, str]:
    """The scenarios.

    Returns
    -------
    dict of str to str
        Scenario names with their one-line descriptions.
    """
    from .scenarios import summaries

    return summaries()


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
    from .scenarios import REGISTRY
    from .schema import scenario_text

    if name not in REGISTRY:
        raise KeyError(f"unknown scenario {name!r}; one of: {', '.join(REGISTRY)}")
    return scenario_text(REGISTRY[name])


@dataclass(frozen=True)
class Run:
    """A run checked before anything is computed (`plan`): its recipe, target, lazy dataset, output
    options and whether it is written in resumable parts."""
    recipe: Recipe
    target: Path
    dataset: xr.Dataset
    options: OutputOptions
    parts: bool
    resume: bool = False
    overwrite: bool = False
    chunks: dict | None = None

    @property
    def format(self) -> str:
        """The target's format (``netcdf``, ``zarr``), from its suffix."""
        from .output.formats import format_for

        return format_for(self.target).name

    def space_needed(self) -> int:
        """Bytes the output needs on its file system (uncompressed; less what a resumed run holds)."""
        from .output.formats import space_needed

        return space_needed(self.dataset, self.target, self.options, self.resume)

    def estimate(self) -> dict[str, Any]:
        """`estimate` of this run's recipe and chunks."""
        return estimate(self.recipe, self.chunks)

    def write(self, *, progress: bool = False, scheduler: Any = None, space_check: bool = True) -> Path:
        """Compute and write the dataset (`output.formats.write`: the target and, with
        ``space_check``, the free space checked again first; atomic; content hash stored)."""
        from .output.formats import write

        o = self.options
        return write(self.dataset, self.target, overwrite=self.overwrite, parts=self.parts, resume=self.resume,
                     progress=progress, scheduler=scheduler, space_check=space_check, dtype=o.dtype,
                     compression=o.compression, nonfinite=o.nonfinite)


def plan(recipe: str | Path | Mapping | Recipe, target: str | Path, *, chunks: dict[str, int] | None = None,
         overwrite: bool = False, parts: bool = False, resume: bool = False, dtype: str | None = None,
         compression: int | None = None, nonfinite: str | None = None, allow_read: Sequence[str | Path] = (),
         check_target: bool = True, folder_made_later: bool = False) -> Run:
    """Check a run without computing anything: the recipe, the chunking (unknown dimensions, the
    task count), the target, and the output options; decide the parts.

    Parameters
    ----------
    recipe : str, Path, Mapping or Recipe
        As for `generate` (or a recipe already loaded).
    target : str or Path
        The output: ``.nc`` NetCDF, ``.zarr`` a Zarr store.
    chunks : dict of str to int, optional
        Chunk sizes per dimension, over the recipe's ``[output] chunks``.
    overwrite, resume : bool
        As for `write`.
    parts : bool
        Write in resumable parts; also chosen for a resumable format above `PARTS_ABOVE` points.
    dtype, compression, nonfinite : optional
        Output options over the recipe's ``[output]`` ones (None: the recipe's, else the defaults).
    allow_read : sequence of path, optional
        As for `generate`.
    check_target : bool
        Check the target now (False: a dry run, which writes nothing).
    folder_made_later : bool
        The target's folder does not exist yet and the caller makes it before writing: only the
        target's name is checked, against the nearest existing folder.

    Returns
    -------
    Run

    Raises
    ------
    RecipeError
        For the recipe or the chunking, naming every problem.
    OutputError
        For the target or the output options.
    """
    import os

    from .build import check_chunks, default_chunks
    from .errors import RecipeError
    from .output.atomic import check_name
    from .output.formats import check_target as check, format_for
    from .output.options import resolved

    loaded = _loaded(recipe, allow_read)
    chunks = dict(chunks or {})
    bad = set(chunks) - set(loaded.dims)
    if bad:
        raise RecipeError([f"{', '.join(sorted(bad))} is not a swept dimension of {_label(recipe)} (swept: "
                           f"{', '.join(loaded.dims) or 'none'})"], "the chunking")
    wanted = {**loaded.chunks, **chunks}
    check_chunks(loaded.shape, wanted, default_chunks(loaded.shape, wanted))     # task count, before any work
    target = Path(target)
    if folder_made_later:
        folder = Path(os.path.abspath(target.parent))
        while not os.path.lexists(folder) and folder != folder.parent:
            folder = folder.parent
        check_name(target, folder)
    elif check_target:
        check(target, overwrite=overwrite, resume=resume, parts=parts)
    options = resolved(loaded.storage, dtype=dtype, compression=compression, nonfinite=nonfinite)
    parts = parts or (loaded.size > PARTS_ABOVE and format_for(target).resumable)
    return Run(loaded, target, generate(loaded, chunks), options, bool(parts), resume, overwrite, chunks)


def check_space(runs: Sequence[Run]) -> None:
    """Refuse runs whose file systems have less free space than they need together
    (`output.formats.check_space`), before any of them is computed."""
    from .output.formats import check_space as check

    check([(r.target, r.space_needed()) for r in runs])


def run(recipe: str | Path | Mapping | Recipe, target: str | Path, *, progress: bool = False, scheduler: Any = None,
        space_check: bool = True, **overrides: Any) -> Path:
    """The recipe's dataset, computed and written to ``target``: `stressfields run recipe -o target`.

    Everything is checked before anything is computed (`plan`: the recipe, the chunking, the target,
    the output options; then the free space); the recipe's ``[output]`` options apply unless
    ``overrides`` give others; above `PARTS_ABOVE` points a NetCDF target is written in resumable parts.

    Parameters
    ----------
    recipe : str, Path, Mapping or Recipe
        As for `generate`.
    target : str or Path
        The output: ``.nc`` NetCDF, ``.zarr`` a Zarr store.
    progress : bool
        dask's progress bar, on stderr.
    scheduler : optional
        Passed to dask (None: the local threads; a dask.distributed ``Client`` for a cluster).
    space_check : bool
        Refuse to start when the output's estimated size exceeds the free space.
    **overrides
        ``chunks``, ``overwrite``, ``parts``, ``resume``, ``dtype``, ``compression``, ``nonfinite``,
        ``allow_read``, as for `plan`.

    Returns
    -------
    pathlib.Path
        The written target.

    Raises
    ------
    RecipeError, OutputError
        Before anything is computed, naming the problem; an OutputError after (a full disk) leaves
        nothing behind.
    """
    checked = plan(recipe, target, **overrides)
    if space_check:
        check_space([checked])
    return checked.write(progress=progress, scheduler=scheduler, space_check=False)


def compare(recipe: str | Path | Mapping, user_data: str | Path | xr.Dataset | Mapping, *,
            tolerance: float | str | Mapping | None = None, variables: list[str] | tuple[str, ...] | None = None,
            step: int | None = None, units: str | Mapping[str, str] | None = None, z_up: bool = False,
            axisymmetric: bool = False, body: int = 1, exclude_edge: float | None = None,
            remove_rigid_offset: bool = False, scale: str | None = None) -> xr.Dataset | list[xr.Dataset]:
    """The user's values against the reference at the user's points: `stressfields compare` without
    the report folder (`fe.validate.compare_files` does the work; the options are its switches).

    Parameters
    ----------
    recipe : str, Path or Mapping
        The recipe of the reference; the coordinates the user's data give replace its sweep.
    user_data : str, Path, xarray.Dataset or Mapping
        A file of nodes (CSV, NetCDF, Exodus II; VTU/VTK, XDMF, MED, Gmsh with the ``fe`` extra), a
        dataset along one dimension, or a mapping of header (``sigma_xx[MPa]``) -> values.
    tolerance : float, str or Mapping, optional
        The largest max |difference| / S a variable may have to pass (a float), or limits on any
        statistic (``"rms=1e-3,max=0.05"`` or ``{"rms": 1e-3}``); None: report only.
    variables : list of str, optional
        Compare only these value columns (default: every one).
    step : int, optional
        The time step (from 1) of an Exodus II file; None: every step.
    units : str or Mapping, optional
        The units of a format that carries none (VTU, Exodus II): ``"length=mm,stress=MPa"`` or
        ``{"length": "mm", "stress": "MPa"}``. None: the recipe's ``[compare] units``, if any.
    z_up, axisymmetric : bool
        The model's body lies at z <= 0 (z up); a 2-D (r, z) mesh or cylindrical components.
    body : int
        1 (the half-space) or 2 (the second identical body, its mirror image).
    exclude_edge : float, optional
        Nodes within this many a of an edge of the contact are reported apart.
    remove_rigid_offset : bool
        Remove the mean difference of displacements (a finite model's rigid offset).
    scale : {"p0", "p_m"}, optional
        The user's stresses are divided by this scale.

    Returns
    -------
    xarray.Dataset or list of xarray.Dataset
        ``<v>_reference``, ``<v>_user``, ``<v>_difference`` and ``<v>_scale`` at every point; the
        statistics and the verdict (``compare_result``) in its attributes. A file of several tables
        (an Exodus II history without ``step``, nodes and element centroids) gives one per table.

    Raises
    ------
    CompareError
        In one line, for input that cannot be compared.
    """
    from .comparison import CompareError
    from .fe.units import UnitProblem, parse_unit_option
    from .fe.validate import Options, compare_files, parse_tolerance

    if isinstance(tolerance, Mapping):
        tolerance = ",".join(f"{k}={v}" for k, v in tolerance.items())
    if isinstance(units, Mapping):
        units = ",".join(f"{k}={v}" for k, v in units.items())
    try:
        unit_option = None if units is None else parse_unit_option(units)
    except UnitProblem as exc:
        raise CompareError(str(exc)) from None
    if isinstance(variables, str):
        variables = [variables]
    options = Options(tolerance=parse_tolerance(tolerance), variables=tuple(variables or ()) or None, step=step,
                      units=unit_option, z_up=bool(z_up), axisymmetric=bool(axisymmetric), body=body,
                      exclude_edge=exclude_edge, remove_rigid_offset=bool(remove_rigid_offset), scale=scale)
    tables = compare_files(recipe, [user_data], options)
    return tables[0] if len(tables) == 1 else tables


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


def _loaded(recipe, allow_read=()) -> Recipe:
    """A checked recipe: ``recipe`` itself if it is one already, else `recipe.load`."""
    from .recipe import Recipe, load

    return recipe if isinstance(recipe, Recipe) else load(recipe, allow_read)


def _label(recipe) -> str:
    return "the recipe" if isinstance(recipe, Mapping) or not isinstance(recipe, (str, Path)) else str(recipe)


def _shipped():
    from importlib.resources import files

    return files(__package__)
