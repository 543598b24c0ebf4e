"""Resumable writes: a sweep is written in parts along its first dimension, with a manifest.

    OUT.nc.parts/manifest.json     recipe hash, the part boundaries, content hash per finished part
    OUT.nc.parts/part-00000.nc     each part published atomically (temporary name, then rename)

A kill at any moment leaves no file at OUT.nc and no half-written part; `resume=True` checks the
finished parts against their hashes (a part that cannot be read or does not verify is computed
again), computes only the missing ones, then joins the parts into OUT.nc (atomically) and removes
the folder. The part names come from the plan (the recipe's chunk boundaries), never from the
manifest, so nothing outside the folder is ever read. The joined file's content hash equals that of
an uninterrupted run: the values are the same bits and the metadata is the same.
"""
from __future__ import annotations

import json
import os
import shutil
import sys
from pathlib import Path

import numpy as np
import xarray as xr

from .errors import OutputError
from .hashing import content_hash, file_hash, slabs, stored_hash
from .netcdf import read as netcdf_read
from .writers import Format, parts_dir

MANIFEST = "manifest.json"


def write_in_parts(ds: xr.Dataset, target: Path, fmt: Format, *, progress: bool = False, scheduler=None,
                   overwrite: bool = False) -> Path:
    """Write ``ds`` to ``target`` (checked by `writers.check_target`, its run lock held) in parts of
    format ``fmt``."""
    dim = next(iter(ds.dims), None)
    if dim is None or ds.chunks.get(dim) is None:
        return fmt.write(ds, target, progress=progress, scheduler=scheduler, overwrite=overwrite)
    edges = part_edges(ds, dim)
    plan = {"recipe_sha256": ds.attrs.get("stressfields_recipe_sha256"), "dim": dim, "edges": edges}
    folder = parts_dir(target)
    manifest = _start(folder, plan)
    names = part_names(edges)
    for i, (name, lo, hi) in enumerate(zip(names, edges[:-1], edges[1:])):
        path = folder / name
        if _intact(path, manifest["parts"].get(name)):
            continue
        manifest["parts"].pop(name, None)
        if progress:
            print(f"  part {i + 1}/{len(names)}: {dim}[{lo}:{hi}]", file=sys.stderr)
        fmt.write(ds.isel({dim: slice(lo, hi)}), path, progress=progress, scheduler=scheduler, overwrite=True)
        # the hash the write just computed from memory and stored: hashing the part again would
        # read it back for nothing (it is read back and verified on resume, `_intact`)
        manifest["parts"][name] = stored_hash(path)
        _dump(folder, manifest)
    _join(folder, names, dim, edges, ds, target, fmt, overwrite)
    shutil.rmtree(folder)
    return target


def part_edges(ds: xr.Dataset, dim: str) -> list[int]:
    """Part boundaries along ``dim``: at chunk boundaries, one row of chunks a part, or, where a row is
    large (PARALLEL_ABOVE points or more), as many rows as give a part MIN_TASKS chunks: a part's
    chunks are its tasks, and a part of one task would leave every other core idle while it is
    computed (a 1e8-point grid of 1e6-point rows: 25 parts of four tasks, not 100 of one)."""
    from .build import MIN_TASKS, PARALLEL_ABOVE

    rows = [int(n) for n in ds.chunks[dim]]
    others = [d for d in ds.chunks if d != dim]
    per_row = int(np.prod([len(ds.chunks[d]) for d in others]))
    row_points = max(rows) * int(np.prod([ds.sizes[d] for d in others]))
    group = 1 if row_points < PARALLEL_ABOVE else max(1, -(-MIN_TASKS // per_row))
    ends = np.cumsum(rows)
    cuts = ends[group - 1::group].tolist()
    if not cuts or cuts[-1] != ends[-1]:
        cuts.append(int(ends[-1]))
    return [0] + [int(c) for c in cuts]


def part_names(edges: list[int]) -> list[str]:
    """The file of each part, from the plan alone."""
    return [f"part-{i:05d}.nc" for i in range(len(edges) - 1)]


def _intact(path: Path, digest) -> bool:
    """A finished part: listed with its hash, readable, and its content, stored hash and listed hash
    agree. Anything else (missing, truncated, a flipped byte, emptied) is computed again."""
    if not isinstance(digest, str) or not path.is_file():
        return False
    try:
        return file_hash(path) == (digest, digest)
    except Exception:       # whatever a damaged file makes the HDF5 layer raise: recompute the part
        return False


def _start(folder: Path, plan: dict) -> dict:
    """The manifest of the parts folder: the existing one (a resume, allowed by
    `writers.check_target`) after checking it belongs to this run, or a new one."""
    if folder.exists():
        if not folder.is_dir():
            raise OutputError(f"{folder} is not a folder of parts; remove it and rerun")
        try:
            manifest = json.loads((folder / MANIFEST).read_text())
        except (OSError, ValueError):
            raise OutputError(f"{folder}/{MANIFEST} is missing or unreadable; remove {folder} and rerun") from None
        if not isinstance(manifest, dict) or not isinstance(manifest.get("parts"), dict):
            raise OutputError(f"{folder}/{MANIFEST} is not a manifest of parts (expected an object with "
                              "'parts'); remove the folder and rerun")
        if {k: manifest.get(k) for k in plan} != plan:
            raise OutputError(f"{folder} belongs to another recipe or chunking (recipe hash or part "
                              "boundaries differ); remove it or run the original recipe")
        return manifest
    folder.mkdir()
    manifest = {**plan, "parts": {}}
    _dump(folder, manifest)
    return manifest


def _dump(folder: Path, manifest: dict) -> None:
    tmp = folder / f".{MANIFEST}.tmp"
    tmp.write_text(json.dumps(manifest, indent=1, sort_keys=True))
    os.replace(tmp, folder / MANIFEST)


def _join(folder: Path, names: list[str], dim: str, edges: list[int], template: xr.Dataset, target: Path,
          fmt: Format, overwrite: bool) -> None:
    """Copy the parts into one file, a slab at a time, so memory stays at the size of a slab. The
    variables that start with the parts' dimension (the fields) are copied variable by variable, in the
    order of the content hash, and hashed as they pass: the joined file is not read back. The parts
    were verified before (`_intact`) or hashed as written."""
    import netCDF4

    def fill(path: str) -> str | None:
        streamed = _streamed(template, dim)
        if not streamed or any(var.nbytes > _HELD_BYTES for name, var in template.variables.items()
                               if name not in streamed):
            streamed = []       # a large variable the stream does not cover: copy all, read back to hash
        with netCDF4.Dataset(path, "a") as out:
            for i, name in enumerate(names):
                with netCDF4.Dataset(folder / name) as part:
                    for var, values in part.variables.items():
                        if var in streamed:
                            continue
                        if dim in values.dimensions:
                            offset = [0] * values.ndim
                            offset[values.dimensions.index(dim)] = edges[i]
                            _copy(values, out[var], offset)
                        elif i == 0:
                            _copy(values, out[var], [0] * values.ndim)
        if not streamed:
            return None
        with netcdf_read(path, raw=True) as raw:
            # heads of every variable, values of the small ones: in memory before the file is reopened
            # for writing (HDF5 opens a file once per process)
            held = raw.drop_vars(streamed).load()
            heads = {name: raw.variables[name] for name in streamed}
            attrs = dict(raw.attrs)
        hashed = xr.Dataset(attrs=attrs)
        hashed = hashed.assign_coords(held.variables).assign(heads)
        with netCDF4.Dataset(path, "a") as out:
            out.set_auto_maskandscale(False)
            values = {var: (lambda var=var: _stream_copy(folder, names, edges, var, out[var]))
                      for var in streamed}
            return content_hash(hashed, values=values)

    fmt.write(template, target, fill=fill, overwrite=overwrite)


#: the largest variable the join holds in memory to hash it (the others start with the parts' dimension)
_HELD_BYTES = 64 * 2 ** 20


def _streamed(template: xr.Dataset, dim: str) -> list[str]:
    """The numeric data variables whose first dimension is ``dim``: their values in C order are the
    parts' values one part after the other."""
    return [str(name) for name, var in template.data_vars.items()
            if var.dims and var.dims[0] == dim and var.dtype.kind in "biuf"]


def _stream_copy(folder: Path, names: list[str], edges: list[int], var: str, dst, limit: int = 16 * 2 ** 20):
    """Copy ``var`` from every part into ``dst`` (its rows edges[i]:edges[i+1]), yielding each slab as
    stored (no masking), in C order."""
    import netCDF4

    for name, lo in zip(names, edges[:-1]):
        with netCDF4.Dataset(folder / name) as part:
            src = part[var]
            src.set_auto_maskandscale(False)
            for index in slabs(src.shape, src.dtype.itemsize, limit):
                # integer indices as length-1 slices: the slab keeps its rank, so it lands unchanged
                index = tuple(i if isinstance(i, slice) else slice(i, i + 1) for i in index)
                values = np.asarray(src[index])
                dst[(slice(lo + index[0].start, lo + index[0].stop),) + index[1:]] = values
                yield values


def _copy(src, dst, offset: list[int], limit: int = 64 * 2 ** 20) -> None:
    """dst[offset + index] = src[index], one slab of at most ~`limit` bytes at a time."""
    if not src.shape:
        dst[...] = src[...]
        return
    # variable-length strings (a swept choice parameter) have no item size: count a generous 256
    # bytes per item; such coordinates are short
    itemsize = src.dtype.itemsize if isinstance(src.dtype, np.dtype) else 256
    for index in slabs(src.shape, itemsize, limit):
        target = tuple(slice(o + (i.start or 0), o + (i.stop if i.stop is not None else n)) if isinstance(i, slice)
                       else o + i for i, o, n in zip(index, offset, src.shape))
        dst[target] = src[index]
