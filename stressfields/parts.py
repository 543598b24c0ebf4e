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
from .hashing import file_hash, slabs
from .writers import Format, parts_dir

MANIFEST = "manifest.json"


def write_in_parts(ds: xr.Dataset, target: Path, fmt: Format, *, progress: bool = False, scheduler=None,
                   overwrite: bool = False) -> Path:
    """Write ``ds`` to ``target`` (checked by `writers.check_target`, its run lock held) in parts of
    format ``fmt``."""
    dim = next(iter(ds.dims), None)
    if dim is None or ds.chunks.get(dim) is None:
        return fmt.write(ds, target, progress=progress, scheduler=scheduler, overwrite=overwrite)
    edges = np.concatenate([[0], np.cumsum(ds.chunks[dim])]).astype(int).tolist()
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
        manifest["parts"][name] = file_hash(path)[1]
        _dump(folder, manifest)
    _join(folder, names, dim, edges, ds, target, fmt, overwrite)
    shutil.rmtree(folder)
    return target


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
    """Copy the parts into one file, one part at a time, so memory stays at the size of a part."""
    import netCDF4

    def fill(path: str) -> None:
        with netCDF4.Dataset(path, "a") as out:
            for i, name in enumerate(names):
                with netCDF4.Dataset(folder / name) as part:
                    for var, values in part.variables.items():
                        if dim in values.dimensions:
                            offset = [0] * values.ndim
                            offset[values.dimensions.index(dim)] = edges[i]
                            _copy(values, out[var], offset)
                        elif i == 0:
                            _copy(values, out[var], [0] * values.ndim)

    fmt.write(template, target, fill=fill, overwrite=overwrite)


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
