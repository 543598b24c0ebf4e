"""Resumable writes: a large sweep is written in parts along its first dimension, into one file.

    OUT.nc.parts/manifest.json   recipe hash, part boundaries, and per finished part the CRC-32 of
                                 every block it stored
    OUT.nc.parts/data.nc         the output: laid out once (dimensions, attributes, coordinates), its
                                 values filled part by part in place, then hashed and published as OUT.nc

Nothing is copied: each value is written once, where it belongs (the earlier design wrote each
part to a file of its own and copied them all into the output: at 1.6e7 points x eleven fields
that copy took 4.4 of 14 s, and half the run's system time).

A part enters the manifest only after its values are in data.nc (HDF5's buffers flushed), so a kill
at any moment leaves no file at OUT.nc and a manifest listing only parts whose values are in data.nc
(after a crash of the machine, values that had not reached the disk fail their CRCs).
``resume=True`` reads every listed part back and checks each block against its CRC (a part that
does not verify is computed again; a data.nc that was not completely laid out or cannot be opened is
laid out anew and every part computed again), computes only the missing parts, then hashes the file
(read back, `netcdf.stamp`) and publishes it. The block list comes from the plan (the recipe's
chunks), never from the manifest, and the manifest must match the plan (recipe hash, part
boundaries) before anything is used. The published file's content hash equals that of an
uninterrupted run: the values are the same bits and the metadata is the same.
"""
from __future__ import annotations

import json
import os
import shutil
import sys
from pathlib import Path

import numpy as np
import xarray as xr

from ..errors import OutputError
from . import netcdf
from .atomic import output_error, parts_dir
from .compute import MIN_TASKS, PARALLEL_ABOVE

MANIFEST = "manifest.json"
DATA = "data.nc"


def write(ds: xr.Dataset, target: Path, *, progress: bool = False, scheduler=None, overwrite: bool = False) -> Path:
    """Write ``ds`` to ``target`` (checked by `formats.check_target`, its run lock held) in parts of
    NetCDF (the one resumable format); a dataset without a chunked first dimension is written whole."""
    dim = next(iter(ds.dims), None)
    if dim is None or ds.chunks.get(dim) is None:
        return netcdf.write(ds, target, progress=progress, scheduler=scheduler, overwrite=overwrite)
    edges = part_edges(ds, dim)
    plan = {"recipe_sha256": ds.attrs.get("stressfields_recipe_sha256"), "dim": dim, "edges": edges}
    folder = parts_dir(target)
    manifest = _start(folder, plan)
    data = folder / DATA
    try:
        if not manifest.get("laid_out") or not _opens(data):
            _lay_out(ds, folder, manifest)
        encoding = netcdf.encodings(ds)
        with netcdf.open_values(data) as nc:
            for i, (lo, hi) in enumerate(zip(edges[:-1], edges[1:])):
                sources = netcdf.sources(ds, encoding, dim, lo, hi, first=i == 0)
                if _intact(nc, sources, manifest["parts"].get(str(i))):
                    continue
                manifest["parts"].pop(str(i), None)
                if progress:
                    print(f"  part {i + 1}/{len(edges) - 1}: {dim}[{lo}:{hi}]", file=sys.stderr)
                crcs = _store(nc, sources, scheduler, progress)
                # HDF5's buffers to the file: a killed process loses nothing listed. Not fsync'd: a
                # part that a crash of the machine kept from the disk fails its CRCs on resume and is
                # computed again, while an fsync per part cost 1.7 s of a 15 s run (3.6e7 points)
                nc.sync()
                manifest["parts"][str(i)] = crcs
                _dump(folder, manifest)
        if progress:
            print(f"  hashing {data.stat().st_size / 1e9:.2f} GB", file=sys.stderr)
        netcdf.finish(data, target, overwrite)
    except (OSError, RuntimeError) as exc:      # the folder stays: a resume takes it up
        error = output_error(exc, target, folder)
        if error is None:
            raise
        raise error from exc
    shutil.rmtree(folder)
    return target


#: points a part holds at least where rows are large: each part costs its own graph, flush and
#: manifest entry, which 4e6-point parts make small (docs/bench/tuning.md)
PART_POINTS = 4_000_000


def part_edges(ds: xr.Dataset, dim: str) -> list[int]:
    """Part boundaries along ``dim``: at chunk boundaries, one row of chunks a part, or, where a row is
    large (PARALLEL_ABOVE points or more), as many rows as give a part MIN_TASKS chunks and
    PART_POINTS points: a part's chunks are its tasks, and a part of one task would leave every other
    core idle while it is computed (a 1e8-point grid of 5e5-point rows: 25 parts of eight tasks, not
    200 of one)."""
    rows = [int(n) for n in ds.chunks[dim]]
    others = [d for d in ds.chunks if d != dim]
    per_row = int(np.prod([len(ds.chunks[d]) for d in others]))
    row_points = max(rows) * int(np.prod([ds.sizes[d] for d in others]))
    group = 1 if row_points < PARALLEL_ABOVE else max(1, -(-MIN_TASKS // per_row), -(-PART_POINTS // row_points))
    ends = np.cumsum(rows)
    cuts = ends[group - 1::group].tolist()
    if not cuts or cuts[-1] != ends[-1]:
        cuts.append(int(ends[-1]))
    return [0] + [int(c) for c in cuts]


def _lay_out(ds: xr.Dataset, folder: Path, manifest: dict) -> None:
    """A new data.nc; the manifest says so only once it is complete (a kill while laying it out
    leaves a manifest without ``laid_out``: the next resume starts it again)."""
    manifest.pop("laid_out", None)
    manifest["parts"] = {}
    _dump(folder, manifest)
    data = folder / DATA
    if os.path.lexists(data):
        os.unlink(data)
    netcdf.layout(ds, data)
    manifest["laid_out"] = True
    _dump(folder, manifest)


def _store(nc, sources: list, scheduler, progress: bool) -> list[int]:
    """Compute and write a part's blocks; their CRC-32s in the order of `netcdf.blocks`."""
    return netcdf.store(nc, sources, scheduler, progress, crcs=True)


def _intact(nc, sources: list, record) -> bool:
    """A finished part: listed with one CRC per block of the plan, and every block read back from
    the file matches its CRC. Anything else (missing, a list of the wrong length, a changed value,
    an unreadable region) is computed again."""
    blocks = list(netcdf.blocks(sources))
    if not isinstance(record, list) or len(record) != len(blocks):
        return False
    try:
        for (name, index), expected in zip(blocks, record):
            if netcdf.crc(nc[name][index]) != expected:
                return False
    except Exception:       # whatever a damaged file makes the HDF5 layer raise: recompute the part
        return False
    return True


def _opens(data: Path) -> bool:
    """Whether data.nc exists and HDF5 can open it for writing (a kill may have damaged it)."""
    if not data.is_file():
        return False
    try:
        netcdf.open_values(data).close()
    except Exception:       # any failure of the HDF5 layer on a damaged file: lay it out again
        return False
    return True


def _start(folder: Path, plan: dict) -> dict:
    """The manifest of the parts folder: the existing one (a resume, allowed by
    `formats.check_target`) after checking it belongs to this run, or a new one."""
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
