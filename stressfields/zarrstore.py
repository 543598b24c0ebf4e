"""Zarr output: on a dask.distributed cluster every worker writes its own chunk-aligned region and
nothing passes through the client. The store is built beside the target under a name of its own
(``.NAME.HOST-PID.RANDOM.partial``, see `netcdf.temporary`) and renamed when complete, with its
content hash in the group attributes."""
from __future__ import annotations

import os
import shutil
from pathlib import Path

import xarray as xr

from .errors import OutputError
from .hashing import ATTR, content_hash
from .netcdf import clean_stale, compute, temporary


def _zarr():
    try:
        import zarr
    except ImportError:
        raise OutputError("Zarr output needs zarr: pip install 'stressfields[zarr]'") from None
    return zarr


def write(ds: xr.Dataset, target: Path, *, progress: bool = False, scheduler=None, overwrite: bool = False) -> Path:
    """Write ``ds`` to the Zarr store ``target`` atomically (the caller has checked the target and holds
    its run lock, `writers.target_lock`); without ``overwrite`` an existing target is never replaced."""
    zarr = _zarr()
    target = Path(target)
    clean_stale(target)
    partial = temporary(target, ".partial")
    encoding = {name: {"chunks": tuple(int(c[0]) for c in var.chunks)} for name, var in ds.variables.items()
                if var.chunks and var.ndim}
    try:
        delayed = ds.to_zarr(partial, mode="w", encoding=encoding, compute=False, consolidated=True)
        compute(delayed, progress=progress, scheduler=scheduler)
        with read(partial, raw=True) as written:
            digest = content_hash(written)
        group = zarr.open_group(partial, mode="r+")
        group.attrs[ATTR] = digest
        zarr.consolidate_metadata(partial)
        _publish(partial, target, overwrite)
    except OutputError:
        shutil.rmtree(partial, ignore_errors=True)
        raise
    except OSError as exc:
        shutil.rmtree(partial, ignore_errors=True)
        raise OutputError(f"cannot write {target}: {exc.strerror or exc}") from exc
    except BaseException:
        shutil.rmtree(partial, ignore_errors=True)
        raise
    return target


def _publish(partial: Path, target: Path, overwrite: bool) -> None:
    """Rename the complete store onto ``target``. A rename replaces an empty directory, so the name is
    checked first, under the run lock. The store replaced by ``overwrite`` is moved aside in one rename
    and removed after: the target is always either the old store or the new one."""
    if not os.path.lexists(target):
        os.rename(partial, target)
        return
    if not overwrite:
        raise OutputError(f"{target} was created by another run while this one was writing; refusing to "
                          "overwrite it (use --overwrite)")
    old = temporary(target, ".partial")
    os.rename(target, old) if target.is_dir() and not target.is_symlink() else os.replace(target, old / "old")
    os.rename(partial, target)
    shutil.rmtree(old, ignore_errors=True)


def read(path, raw: bool = False) -> xr.Dataset:
    """The store as a dataset: decoded, or ``raw`` (stored values and attributes, for hashing)."""
    _zarr()
    if raw:
        return xr.open_zarr(path, decode_cf=False, mask_and_scale=False, consolidated=True)
    return xr.open_zarr(path, consolidated=True)
