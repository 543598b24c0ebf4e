"""Compare a user's nodal values (an FE model's, say) with the reference at exactly the same points.

    ds = sf.compare("recipe.toml", "nodes.csv", tolerance=1e-2)     # `stressfields compare` on the command line

(`sf.compare` is `api.compare`; the module is not named `compare`: a submodule of that name would
replace the function `sf.compare` in the package's namespace when first imported.)

The user data is anything `stressfields compare` reads (`fe.formats`: CSV with the common FE header
forms, NetCDF, Exodus II; VTU/VTK, XDMF, MED, Gmsh with the ``fe`` extra), an ``xr.Dataset`` along
one dimension, or a mapping of header -> values; `sf.compare` (`api.compare`) is a thin front on
`fe.validate.compare_files`, the command's own path, with its switches as keywords. A column named
like one of the scenario's parameters (``x``, ``y``, ``z``, ...) is a coordinate of the nodes, a
column named like a float variable (``sigma_xx``, ...) a value to compare. Units go in brackets
(``x[mm]``, ``sigma_xx[MPa]``); a column without them is in the scenario's declared unit for the
recipe's mode, except in a format that carries no units (VTU, Exodus II), whose units come from
``units=`` (``--units``) or the recipe's ``[compare] units``; nothing is guessed.

This module holds what the comparison needs of the recipe: the reference is the recipe with the
coordinate columns as its ``[points]`` table (the recipe's own values of those parameters and its
``[points]`` are replaced), so it is evaluated at the nodes and nowhere else, within the accuracy
its fields state (``stressfields_accuracy``); the scale S of each variable (its declared ``Scale``:
1 in normalised mode, where values are already divided by it; in physical mode the scale's value,
``Scale.value``, from the reference's variables and the recipe's values, e.g. the mean contact
pressure p_m for stresses, p_m/a for dpdz, p* and Delta_1 for the wavy fields; where the scale
declares none, the largest |reference| over the nodes); and the report folder, checked before
anything is computed and published whole. The statistics are `fe.stats`'.
"""
from __future__ import annotations

import json
import os
import re
import shutil
import stat
import sys
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Mapping

import numpy as np
import xarray as xr

from .errors import OutputError, name_problem
from .pointfiles import MAX_POINTS_FILE_BYTES, Column, FileProblem, file_bytes, nc_columns
from .recipe import MAX_RECIPE_BYTES, POINT, RecipeError, load
from .scenarios import REGISTRY
from .scenarios.base import ARRAY, Scenario
from .units import UNITS  # noqa: F401 (the one table of units: `[points]` files and compare alike)

#: names of the identity column of an FE export: kept as a coordinate, never compared
ID_COLUMNS = ("node", "node_id", "id")


class CompareError(ValueError):
    """Bad user data or a recipe that cannot be compared; the message is one line."""


@dataclass(frozen=True)
class _Base:
    """What the comparison needs of the recipe as given, before its coordinates come from the nodes."""
    scenario: Scenario
    physical: bool
    title: str
    text: str
    label: str


def _recipe(recipe) -> tuple[_Base, dict]:
    """The recipe's tables as given; it is checked whole once the nodes are its [points] (`_reference`),
    so that a recipe need not give the coordinates the nodes give (e.g. the required x)."""
    if isinstance(recipe, Mapping):
        data, text, label = dict(recipe), json.dumps(dict(recipe), default=str, sort_keys=True), "recipe"
    else:
        label = str(recipe)
        why = name_problem(label)
        if why is not None:
            raise CompareError(f"{ascii(label)}: cannot read the recipe ({why})")
        path = Path(recipe)
        try:
            if not stat.S_ISREG(os.stat(path).st_mode) or os.stat(path).st_size > MAX_RECIPE_BYTES:
                raise CompareError(f"{label}: not a regular file of at most {MAX_RECIPE_BYTES:,} bytes")
            text = path.read_text(encoding="utf-8")
            data = tomllib.loads(text)
        except OSError as exc:
            raise CompareError(f"{label}: cannot read the recipe ({exc.strerror})") from None
        except (UnicodeDecodeError, ValueError, RecursionError) as exc:
            try:        # the recipe checker says what is wrong in its own words
                load(path)
            except RecipeError as err:
                raise CompareError(f"{label}: " + "; ".join(err.problems)) from None
            raise CompareError(f"{label}: not a valid recipe ({exc})") from None
    name = data.get("scenario")
    if not isinstance(name, str) or name not in REGISTRY:
        raise CompareError(f"{label}: scenario = {name!r} is unknown; one of: {', '.join(REGISTRY)}")
    scen = REGISTRY[name]
    params = data.get("parameters") or {}
    physical = scen.physical_switch is None or (isinstance(params, Mapping) and scen.physical_switch in params)
    title = data.get("title") if isinstance(data.get("title"), str) else f"stressfields {name}"
    return _Base(scen, physical, title, text, label), data


# --- reading -------------------------------------------------------------------------------------

def read_user_data(user_data) -> tuple[list[Column], str]:
    """The columns of a NetCDF file of nodes (`fe.formats` tells the format) or an xr.Dataset along
    one dimension, and a name for messages."""
    if isinstance(user_data, xr.Dataset):
        return _dataset_columns(user_data, "the user dataset"), "the user dataset"
    path = Path(user_data)
    source = str(path)
    try:
        # resolved first: the reader follows no symbolic link, and the user may name one
        raw = file_bytes(Path(os.path.realpath(path)), source, MAX_POINTS_FILE_BYTES)
        columns = nc_columns(raw, skip_scalars=True, drop_index=True, kept_index=ID_COLUMNS)
    except FileProblem as exc:
        raise CompareError(f"{source}: {exc}") from None
    return [Column(c.name, c.label, c.unit, _numbers(c.values, c.label, source)) for c in columns], source


def _numbers(values, label: str, source: str) -> np.ndarray:
    arr = np.asarray(values)
    if arr.ndim != 1 or arr.dtype.kind not in "iuf":
        raise CompareError(f"{source}, column {label!r}: must be one column of numbers")
    return arr.astype(np.float64)


def _dataset_columns(ds: xr.Dataset, source: str) -> list[Column]:
    dims = sorted({d for v in ds.variables.values() if v.ndim for d in v.dims})
    if len(dims) != 1:
        raise CompareError(f"{source}: the nodes must lie along one dimension (e.g. point); it has "
                           f"{', '.join(dims) or 'none'}")
    dim = dims[0]
    out = []
    for name, var in ds.variables.items():
        if var.ndim == 0 or (name == dim and name not in ID_COLUMNS):
            continue            # scalars (metadata) and the dimension's own index
        out.append(Column(str(name), str(name), var.attrs.get("units"), _numbers(var.values, str(name), source)))
    return out


# --- the reference ---------------------------------------------------------------------------------

FALLBACK_SCALE = "max |reference| over the compared points"


def _scale_spec(var, physical: bool) -> tuple[str, tuple[str, ...]]:
    """(definition, variables of the reference it needs) of S, from the variable's declared Scale: in
    normalised mode a normalised variable's values are already divided by its scale, so S = 1; in
    physical mode the scale's value (``Scale.value``), or the largest |reference| where it declares none."""
    scale = var.scale
    if scale is not None and not physical:
        return "1 (values divided by " + scale.text + ")", ()
    if scale is not None and scale.value is not None:
        return scale.definition, scale.needs
    return FALLBACK_SCALE, ()


def _derived_recipe(base, data: dict, coords, factors, values, scales, source: str) -> dict:
    """The recipe with the coordinate columns as [points]; every other sweep must be a single value."""
    names = {c.name for c in coords}
    params = {k: v for k, v in (data.get("parameters") or {}).items() if k not in names}
    scen = base.scenario
    declared = {p.name: p for p in scen.parameters}
    for key, value in params.items():
        if key in declared and declared[key].kind != ARRAY and isinstance(value, (list, dict)):
            raise CompareError(f"the recipe sweeps {key!r} ({_count(value)} values) but {source} has no "
                               f"{key!r} column: give {key!r} as a column, or one value in the recipe")
    # the nodes replace [points] whole (a file or sample source too); a column they do not give is refused
    left = [k for k in (data.get("points") or {}) if k in declared and k not in names]
    if left:
        raise CompareError(f"the recipe's [points] has {', '.join(map(repr, left))}, which {source} does not "
                           "give: add the column(s), or give one value in [parameters]")
    needed = [c.name for c in values]
    available = {v.name for v in scen.variables_in(base.physical)}
    needed += [n for _, needs in scales.values() for n in needs if n in available and n not in needed]
    out = {"scenario": scen.name, "parameters": params,
           "points": {c.name: c.values * factors[c.name] for c in coords},
           "output": {"variables": list(dict.fromkeys(needed))}}
    # other tables as given, so that the checker still reports their problems (an unknown key, say)
    out.update({k: v for k, v in data.items() if k not in ("points", "output", "plot", "parameters", "compare")})
    return out


def _count(sweep) -> int | str:
    return len(sweep) if isinstance(sweep, list) else sweep.get("num", "?")


def _reference(derived: dict, label: str, source: str) -> xr.Dataset:
    """The recipe's dataset at the nodes as `generate` gives it, computed now (`_evaluate_now`)."""
    from .build import build

    _dask_arrays_once_imported()
    try:
        return build(load(derived), evaluate_group=_evaluate_now)
    except RecipeError as exc:
        raise CompareError(f"{label} with the nodes of {source} as [points] (points.<column>[i] is data row i, "
                           "from 0, in the recipe's units): " + "; ".join(exc.problems)) from None


class _DaskArrays:
    """xarray's record of dask as an array library, with dask.array imported only when needed.

    xarray asks, of every array it wraps, whether it is a dask array, and to know dask's array type
    imports dask.array whenever dask is installed (0.3-0.5 s of a cold `compare`, which has none). No
    object can be a dask array before dask.array is imported, so the type is () until then and
    dask.array's Array after; anything else xarray asks of the record (the module, its version) gets
    the full record, which then replaces this one."""

    @property
    def type(self) -> tuple:
        module = sys.modules.get("dask.array")
        return (module.Array,) if module is not None and hasattr(module, "Array") else ()

    def __getattr__(self, name):
        from xarray.namedarray import pycompat

        full = pycompat.DuckArrayModule("dask")
        pycompat._cached_duck_array_modules["dask"] = full
        return getattr(full, name)


def _dask_arrays_once_imported() -> None:
    """Install `_DaskArrays` unless xarray has looked for dask already (or keeps its record elsewhere:
    then dask.array is imported as before, nothing else changes)."""
    try:
        from xarray.namedarray import pycompat
    except ImportError:
        return
    cache = getattr(pycompat, "_cached_duck_array_modules", None)
    if isinstance(cache, dict) and hasattr(pycompat, "DuckArrayModule") and "dask" not in cache:
        cache["dask"] = _DaskArrays()


def _evaluate_now(recipe, dims, names, fixed, options, chunking) -> list[np.ndarray]:
    """`build`'s evaluation of one group of variables, done now by the kernels (`procedural.evaluate`):
    no dask graph and no import of dask.array (0.3-0.5 s of a cold `compare` of 1e5 nodes here). The
    nodes are cut into the lazy dataset's chunks (`chunking`), each evaluated on its own, on every core
    when there are several: the kernels' temporaries take the memory of a chunk per core, as the lazy
    dataset's do (1e6 nodes: 469 MB peak against 457-470 MB through dask, measured). Every value
    depends on its own point alone, so the values are the lazy dataset's bit for bit. A comparison's
    recipe sweeps only its [points] (`_derived_recipe`)."""
    from concurrent.futures import ThreadPoolExecutor

    from .build import group_columns
    from .procedural import evaluate

    scen = recipe.scenario
    dtypes = [np.dtype(scen.variable(n).dtype) for n in names]
    if not dims:            # per-case values (the contact radius, p_m): scalars, as the lazy dataset has them
        result = evaluate(recipe, names, dict(fixed), options["sweep"])
        return [np.asarray(np.broadcast_to(np.asarray(result[n], dtype=dt), ())) for n, dt in zip(names, dtypes)]
    if dims != (POINT,):
        raise CompareError(f"scenario '{scen.name}' gives {', '.join(names)} along "
                           f"{', '.join(d for d in dims if d != POINT)} as well as the nodes; compare takes fields "
                           "that vary with the nodes alone")
    columns = group_columns(recipe, names)      # the nodes' columns this group depends on, as build's
    size, step = recipe.shape[POINT], chunking[POINT]
    out = [np.empty(size, dt) for dt in dtypes]

    def block(lo: int) -> None:
        hi = min(size, lo + step)
        params = dict(fixed)
        params.update({c: recipe.values[c][lo:hi] for c in columns})
        result = evaluate(recipe, names, params, options["sweep"])
        for arr, name, dt in zip(out, names, dtypes):
            arr[lo:hi] = np.broadcast_to(np.asarray(result[name], dtype=dt), (hi - lo,))

    starts = range(0, size, step)
    if len(starts) == 1:
        block(0)
        return out
    pool = ThreadPoolExecutor(min(len(starts), os.cpu_count() or 1))
    try:
        list(pool.map(block, starts))           # a kernel's exception is raised here
    except BaseException as exc:
        # the chunks not started are dropped; after an interrupt (Ctrl-C, a signal) the running ones
        # are not waited for either
        pool.shutdown(wait=isinstance(exc, Exception), cancel_futures=True)
        raise
    pool.shutdown()
    return out


def _scale_value(var, physical: bool, ref: xr.Dataset, reference: np.ndarray) -> np.ndarray:
    """S at every point (``_scale_spec``): 1, the Scale's value from the reference's variables and the
    recipe's values, or max |reference| (also where a value it reads is a column of the nodes)."""
    definition, needs = _scale_spec(var, physical)
    if definition.startswith("1 "):
        return np.ones_like(reference)
    if definition != FALLBACK_SCALE and all(n in ref for n in needs):
        quantities = {**json.loads(ref.attrs["stressfields_recipe_canonical"])["parameters"],
                      **{n: ref[n] for n in needs}}
        try:
            value = var.scale.value(quantities)
        except KeyError:            # a value it reads is a column of the nodes
            value = None
        if value is not None:
            return np.broadcast_to(np.asarray(value, dtype=float), reference.shape).copy()
    finite = reference[np.isfinite(reference)]
    return np.full_like(reference, np.max(np.abs(finite)) if finite.size else np.nan)


def summary(ds: xr.Dataset) -> dict[str, dict]:
    """The per-variable statistics of a comparison dataset, from its ``compare_<v>_*`` attributes."""
    out = {}
    for name in ds.attrs.get("compare_variables", "").split():
        prefix = f"compare_{name}_"
        out[name] = {k[len(prefix):]: v for k, v in ds.attrs.items() if k.startswith(prefix)}
    return out


#: what a report folder holds (`fe.command`); a folder holding anything else is never replaced
REPORT_FILES = ("comparison.nc", "comparison.png", "report.md", "report.json", "convergence.png")
#: the per-file tables of a mesh sequence or an Exodus history (fe/report.py names them)
REPORT_NUMBERED = re.compile(r"^comparison_\d+\.(nc|png)$")


def check_report_folder(folder: Path, *, overwrite: bool = False) -> Path:
    """The one check of a report folder before anything is computed: it does not exist (its parent
    can take it), is an empty directory, or, with ``overwrite``, a previous report (nothing but
    REPORT_FILES). Raises OutputError naming the problem."""
    from .output.atomic import check_name

    folder = Path(folder)
    parent = folder.parent if str(folder.parent) else Path(".")
    if os.path.islink(folder):
        raise OutputError(f"{folder} is a symbolic link; give the report folder itself")
    if os.path.lexists(folder):
        if not folder.is_dir():
            raise OutputError(f"{folder} exists and is not a directory; a report is a folder")
        entries = os.listdir(folder)
        others = [e for e in entries if e not in REPORT_FILES and not REPORT_NUMBERED.match(e)]
        if others:
            raise OutputError(f"{folder} holds {len(others)} entr{'y' if len(others) == 1 else 'ies'} that "
                              f"{'is' if len(others) == 1 else 'are'} not of a report (e.g. {others[0]!r}); "
                              "refusing to replace it: give a new or empty folder")
        if entries and not overwrite:
            raise OutputError(f"{folder} holds a report; refusing to overwrite it (use --overwrite)")
    elif not parent.is_dir():
        raise OutputError(f"cannot write {folder}: {parent} is not a directory or does not exist")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise OutputError(f"cannot write {folder}: {parent} is not writable (read-only or no permission)")
    check_name(folder, parent)
    return folder


def publish_report(folder: str | os.PathLike, fill, *, overwrite: bool = False) -> Path:
    """Publish a report folder whole: ``fill(tmp)`` writes its files into a temporary folder beside
    ``folder`` (``.NAME.HOST-PID.RANDOM.partial``, `output.atomic.temporary`), which is renamed into place
    when complete. On any error or interrupt (Ctrl-C, SIGTERM, SIGHUP) the temporary folder is removed
    and nothing is left; I/O failures (a full disk) are one OutputError. A folder a killed run left is
    removed by the next (`output.atomic.clean_stale`). The folder replaced by ``overwrite`` is moved aside in
    one rename and removed after, as for a Zarr store."""
    from .output.atomic import clean_stale, output_error, publish_folder, target_lock, temporary, umask

    folder = check_report_folder(Path(folder), overwrite=overwrite)
    parent = folder.parent if str(folder.parent) else Path(".")
    with target_lock(folder):
        clean_stale(folder)
        tmp = temporary(folder, ".partial")
        try:
            fill(tmp)
            os.chmod(tmp, 0o777 & ~umask())         # mkdtemp makes 0700; publish like any new folder
            fd = os.open(tmp, os.O_RDONLY)
            try:
                os.fsync(fd)                        # the names of the files, before the folder's own
            finally:
                os.close(fd)
            # checked again at the last moment: a folder that gained other files meanwhile is kept
            check_report_folder(folder, overwrite=overwrite)
            publish_folder(tmp, folder, overwrite=True)
        except BaseException as exc:
            shutil.rmtree(tmp, ignore_errors=True)
            error = output_error(exc, folder, parent)
            if error is None and isinstance(exc, OutputError):     # the writer's: named after the folder
                text = re.sub(re.escape(str(tmp)) + r"/comparison(_\d+)?\.nc", str(folder), str(exc))
                error = OutputError(text.replace(str(tmp), str(folder)))
            if error is not None:
                raise error from None
            raise
    return folder
