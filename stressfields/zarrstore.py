"""Zarr output: on a dask.distributed cluster every worker writes its own chunk-aligned region and
nothing passes through the client. The store is built under ``.NAME.partial`` beside the target
and renamed when complete, with its content hash in the group attributes."""
from __future__ import annotations

import os
import shutil
from pathlib import Path

import xarray as xr

from .errors import OutputError
from .hashing import ATTR, content_hash
from .netcdf import progress_bar


def _zarr():
    try:
        import zarr
    except ImportError:
        raise OutputError("Zarr output needs zarr: pip install 'stressfields[zarr]'") from None
    return zarr


def write(ds: xr.Dataset, target: Path, *, progress: bool = False, scheduler=None) -> Path:
    """Write ``ds`` to the Zarr store ``target`` atomically (the caller has checked the target)."""
    zarr = _zarr()
    target = Path(target)
    parent = target.parent if str(target.parent) else Path(".")
    partial = parent / f".{target.name}.partial"
    shutil.rmtree(partial, ignore_errors=True)
    encoding = {name: {"chunks": tuple(int(c[0]) for c in var.chunks)} for name, var in ds.variables.items()
                if var.chunks and var.ndim}
    try:
        delayed = ds.to_zarr(partial, mode="w", encoding=encoding, compute=False, consolidated=True)
        with progress_bar(progress):
            delayed.compute(scheduler=scheduler)
        with read(partial, raw=True) as written:
            digest = content_hash(written)
        group = zarr.open_group(partial, mode="r+")
        group.attrs[ATTR] = digest
        zarr.consolidate_metadata(partial)
        if target.exists():
            shutil.rmtree(target)
        os.replace(partial, target)
    except OSError as exc:
        shutil.rmtree(partial, ignore_errors=True)
        raise OutputError(f"cannot write {target}: {exc.strerror or exc}") from exc
    except BaseException:
        shutil.rmtree(partial, ignore_errors=True)
        raise
    return target


def read(path, raw: bool = False) -> xr.Dataset:
    """The store as a dataset: decoded, or ``raw`` (stored values and attributes, for hashing)."""
    _zarr()
    if raw:
        return xr.open_zarr(path, decode_cf=False, mask_and_scale=False, consolidated=True)
    return xr.open_zarr(path, consolidated=True)
