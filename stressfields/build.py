"""Expand a recipe's sweep into coordinates and a lazy, dask-chunked, CF-annotated xr.Dataset.

The [points] columns vary together along one dimension, `point`, placed after the swept ones: each
column is a 1-D coordinate along it and reaches the scenario's evaluate as an array along the last
axis of the block, exactly as a swept parameter reaches it along its own axis, so a value at a point
is the value of the grid at the same coordinates.

Each group of variables that shares the same dimensions is evaluated by one task per chunk
(`xr.apply_ufunc(..., dask="parallelized")` with one output per variable), so a chunk's shared
work (e.g. the six stress components behind von Mises and the principal stresses) is done once.
Nothing is computed until the dataset is written or `.compute()`d.
"""
from __future__ import annotations

import os
import warnings

import numpy as np
import xarray as xr

from . import cf
# a sweep of at least PARALLEL_ABOVE points gets at least MIN_TASKS chunks where it can (output/compute.py
# says why; resumable parts are cut by the same two figures)
from .output.compute import MIN_TASKS, PARALLEL_ABOVE
from .recipe import POINT, Recipe, RecipeError, chunk_problems
from .scenarios.base import ARRAY

#: points per chunk (~4 MB a float field): the fastest of 6e4 to 1e6 on a large run; larger chunks pay
#: in system time for the kernels' temporaries, smaller ones in scheduling (docs/bench/tuning.md)
TARGET_CHUNK_POINTS = 500_000


def build(recipe: Recipe, chunks: dict[str, int] | None = None, *, evaluate_group=None) -> xr.Dataset:
    """The recipe's dataset, lazy: one dask task per chunk and group of variables. ``evaluate_group``
    (the signature of `_evaluate_group`) replaces the lazy evaluation of each group: `compare`
    computes its reference at once, in NumPy, without importing dask.array."""
    scen = recipe.scenario
    physical = recipe.physical
    sizes = recipe.shape
    requested = {**recipe.chunks, **(chunks or {})}
    chunking = default_chunks(sizes, requested)
    check_chunks(sizes, requested, chunking)

    coords: dict[str, xr.Variable] = {}
    fixed: dict = {}
    data_vars: dict[str, xr.DataArray] = {}
    for par in scen.parameters:
        if par.name not in recipe.values:
            continue
        value = recipe.values[par.name]
        if par.name in recipe.points:
            coords[par.name] = xr.Variable((POINT,), value, cf.coord_attrs(par, physical))
        elif par.name in recipe.swept and par.choices:
            # labelled by name in memory (.sel(control="fixed_load"), legends); the writers store
            # it as the CF flag coordinate (output.form.encode_choices), sf.open_dataset reads it back
            coords[par.name] = xr.Variable((par.name,), np.asarray(value, dtype=object),
                                           cf.coord_attrs(par, physical))
        elif par.name in recipe.swept:
            coords[par.name] = xr.Variable((par.name,), value, cf.coord_attrs(par, physical))
        elif par.kind == ARRAY:
            fixed[par.name] = np.asarray(value)
            data_vars[par.name] = xr.DataArray(np.asarray(value), dims=(f"{par.name}_index",),
                                               attrs=cf.coord_attrs(par, physical))
        else:
            fixed[par.name] = value
            if not par.choices:
                coords[par.name] = xr.Variable((), value, cf.coord_attrs(par, physical))
    options = {"method": recipe.method, "rtol": recipe.rtol, "physical": physical, "sweep": recipe.values}

    groups = _groups(recipe)
    # each float variable says the route and accuracy of its own group (displacements, peaks and the
    # contact quantities may take other routes than the stresses): the family's route table decides
    routes = scen.routes(recipe.values, recipe.method, recipe.rtol, [n for names in groups.values() for n in names])
    for dims, names in groups.items():
        outputs = (evaluate_group or _evaluate_group)(recipe, dims, names, fixed, options, chunking)
        for name, arr in zip(names, outputs):
            var = scen.variable(name)
            attrs = cf.variable_attrs(var, physical)
            if var.group in routes and not var.flag_values and var.dtype.startswith("float"):
                attrs["stressfields_method"], attrs["stressfields_accuracy"] = routes[var.group]
            (coords if var.coordinate else data_vars)[name] = xr.Variable(dims, arr, attrs)

    ds = xr.Dataset(data_vars, coords=coords, attrs=cf.global_attrs(recipe))
    ds.attrs.update(cf.feature_type(ds.sizes))
    for par in scen.parameters:
        if par.choices and par.name in recipe.values and par.name not in recipe.swept:
            ds.attrs[f"stressfields_{par.name}"] = recipe.values[par.name]
    return ds


def check_chunks(sizes: dict[str, int], requested: dict[str, int], chunking: dict[str, int]) -> None:
    """Refuse, before any graph is built, a requested chunking of more than MAX_CHUNKS chunks.

    The default chunking (`default_chunks`) is never refused: it is the least a sweep needs.
    """
    if not requested or chunk_problems(sizes, chunking, "") == [] or chunking == default_chunks(sizes, {}):
        return
    raise RecipeError(chunk_problems(sizes, chunking, "chunks"), "the chunking")


def default_chunks(sizes: dict[str, int], requested: dict[str, int]) -> dict[str, int]:
    """Chunk sizes per dimension: the requested ones, the rest filled towards TARGET_CHUNK_POINTS a
    chunk. Trailing (spatial) dimensions are kept whole first, so each line along x is
    one chunk.

    A sweep of PARALLEL_ABOVE points or more that this leaves with fewer than MIN_TASKS chunks (up to
    ~2e6 points) has its trailing dimensions cut further (`_spread`): a 1e6-point grid is four tasks of
    2.5e5 points, not one that leaves the second core idle. Only the spatial dimensions are cut there,
    where fields are evaluated point by point; the sweep dimensions keep the blocks they had, so the
    per-case quantities over them (stick radii, series tables, peaks) are computed from the same blocks
    as before. Every value depends on its own point alone (tests/test_write_path.py,
    tests/physics/test_wavy_chunk_invariance.py), so the content hash does not depend on the chunking.
    """
    out = _filled(sizes, requested)
    total = int(np.prod(list(sizes.values()), dtype=np.int64)) if sizes else 1
    if total >= PARALLEL_ABOVE and _count(sizes, out) < MIN_TASKS:
        out = _spread(sizes, requested, out)
    return out


def _filled(sizes: dict[str, int], requested: dict[str, int]) -> dict[str, int]:
    out: dict[str, int] = {}
    budget = TARGET_CHUNK_POINTS
    for dim in sizes:
        if dim in requested:
            size = sizes[dim] if requested[dim] == -1 else min(requested[dim], sizes[dim])
            out[dim] = size
            budget = max(1, budget // size)
    for dim in reversed(list(sizes)):
        if dim in out:
            continue
        out[dim] = max(1, min(sizes[dim], budget))
        budget = max(1, budget // out[dim])
    return {dim: out[dim] for dim in sizes}


def _count(sizes: dict[str, int], chunking: dict[str, int]) -> int:
    return int(np.prod([-(-sizes[d] // chunking[d]) for d in sizes], dtype=np.int64))


def _spread(sizes: dict[str, int], requested: dict[str, int], chunking: dict[str, int]) -> dict[str, int]:
    """Cut the trailing dimensions not requested, last first, into pieces of equal size until there
    are MIN_TASKS chunks (or nothing is left to cut)."""
    out = dict(chunking)
    for dim in reversed(list(sizes)):
        count = _count(sizes, out)
        if count >= MIN_TASKS:
            break
        if dim in requested:
            continue
        pieces = -(-sizes[dim] // out[dim])
        others = count // pieces                       # chunks of the other dimensions
        wanted = min(sizes[dim], max(pieces, -(-MIN_TASKS // others)))
        out[dim] = -(-sizes[dim] // wanted)
    return out


def _groups(recipe: Recipe) -> dict[tuple[str, ...], list[str]]:
    """Requested variables grouped by their dimensions (in declaration order)."""
    scen = recipe.scenario
    names = list(recipe.variables)
    # an always-on variable (a validity flag) joins whenever a requested variable spans its dims, or,
    # if it names the variables it describes, whenever one of those is requested
    requested_dims = [set(scen.variable(n).dims or ()) for n in names]
    names += [v.name for v in scen.variables_in(recipe.physical)
              if v.always and v.name not in names
              and (set(v.always) & set(names) if isinstance(v.always, tuple)
                   else any(set(v.dims or ()) <= d for d in requested_dims))]
    groups: dict[tuple[str, ...], list[str]] = {}
    for name in names:
        deps = scen.variable(name).dims
        dims = tuple(d for d in recipe.swept if deps is None or d in deps)
        if any(deps is None or c in deps for c in recipe.points):
            dims += (POINT,)
        groups.setdefault(dims, []).append(name)
    return groups


def group_columns(recipe, names) -> list[str]:
    """The [points] columns a group of variables depends on (all of them for a variable that depends
    on every parameter)."""
    deps = [recipe.scenario.variable(n).dims for n in names]
    return [col for col in recipe.points if any(d is None or col in d for d in deps)]


def _inputs(recipe, dims, names, chunking) -> dict[str, xr.DataArray]:
    """The arrays a group varies with, by parameter: a swept one along its dimension; the [points]
    columns the group depends on along POINT, chunked alike so that blocks pair up point by point."""
    out = {}
    for dim in dims:
        if dim != POINT:
            out[dim] = xr.DataArray(recipe.values[dim], dims=(dim,)).chunk({dim: chunking[dim]})
            continue
        for col in group_columns(recipe, names):
            out[col] = xr.DataArray(recipe.values[col], dims=(POINT,)).chunk({POINT: chunking[POINT]})
    return out


def _evaluate_group(recipe, dims, names, fixed, options, chunking):
    from dask.array import PerformanceWarning

    scen = recipe.scenario
    dtypes = [np.dtype(scen.variable(n).dtype) for n in names]
    inputs = _inputs(recipe, dims, names, chunking) if dims else {}
    # parameters this group depends on that are swept but not dimensions of the group are
    # impossible by construction (dims = swept dependencies); scalars pass as keywords
    def kernel(*blocks):
        params = dict(fixed)
        params.update(zip(inputs, blocks))
        shape = np.broadcast_shapes(*(np.shape(b) for b in blocks)) if blocks else ()
        # singular points give inf/NaN on purpose; the scenario flags them in the data
        with np.errstate(all="ignore"):
            result = scen.evaluate(names, params, options)
        out = tuple(np.broadcast_to(np.asarray(result[n], dtype=dt), shape) for n, dt in zip(names, dtypes))
        return out if len(out) > 1 or not blocks else out[0]

    if not dims:
        return [np.asarray(v) for v in kernel()]
    with warnings.catch_warnings():
        # dask notes that broadcasting 1-D coordinates multiplies chunks: that is the point
        warnings.simplefilter("ignore", category=PerformanceWarning)
        out = xr.apply_ufunc(
            kernel, *inputs.values(),
            output_core_dims=[[] for _ in names],
            dask="parallelized",
            output_dtypes=dtypes,
        )
    out = out if isinstance(out, tuple) else (out,)
    return [o.transpose(*dims).data for o in out]


def estimate(recipe: Recipe, chunks: dict[str, int] | None = None, sample_points: int = 200_000) -> dict:
    """What a run will produce before anything large is computed: dimensions, points, bytes, and a
    time extrapolated from evaluating a small leading slice of the sweep."""
    import dataclasses
    import time

    ds = build(recipe, chunks)
    nbytes = int(sum(v.size * v.dtype.itemsize for v in ds.data_vars.values()))
    # a recipe cut down to about n points (leading dimensions shrink first): slicing the lazy
    # dataset instead would still compute whole chunks
    def timed(n: int) -> tuple[float, int]:
        values, points = dict(recipe.values), recipe.size
        for dim, size in recipe.shape.items():
            if points <= n:
                break
            keep = max(1, size * n // points)
            points = points // size * keep
            for name in recipe.points if dim == POINT else (dim,):
                values[name] = values[name][:keep]
        sample = build(dataclasses.replace(recipe, values=values))
        start = time.perf_counter()
        sample.compute(scheduler="synchronous")
        return time.perf_counter() - start, points

    # the fastest of a few samples, up to a second of them: first-call costs are not per point (the
    # first touch of memory among them), and this machine's noise is not either (the giga.toml sweep,
    # which runs in 98 s, was estimated at 611 s after a warm-up of 1e4 points, and at 140-400 s from
    # single samples of 2e5 points on one core). A slow sample is taken once: an overestimate. The
    # sample runs on one core; the run spreads its tasks over the cores.
    t2, n2 = timed(sample_points)
    spent, repeats = t2, 1
    while spent < 1.0 and repeats < 5:
        t, _ = timed(sample_points)
        t2, spent, repeats = min(t2, t), spent + t, repeats + 1
    tasks = int(np.prod([len(c) for c in ds.chunks.values()])) if ds.chunks else 1
    seconds = t2 / max(1, n2) * recipe.size / max(1, min(os.cpu_count() or 1, tasks))
    return {"dims": dict(recipe.shape), "points": recipe.size, "bytes": nbytes,
            "chunks": {d: c[0] for d, c in ds.chunks.items()} if ds.chunks else {},
            "seconds": seconds, "sample_points": n2}
