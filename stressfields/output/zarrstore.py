"""Zarr output: on a dask.distributed cluster every worker writes its own chunk-aligned region and
nothing passes through the client. The store is built beside the target under a name of its own
(``.NAME.HOST-PID.RANDOM.partial``, see `atomic.temporary`) and renamed when complete, with its
content hash in the group attributes.

Zarr keeps attributes as JSON, which has no integer widths and no order of arrays, so the store
also records the order of the variables (``stressfields_variables``), and `read` gives the
CF attributes that must share their variable's type (``flag_values``, ...) that type again: an
export to NetCDF is then the file a direct NetCDF run writes.
"""
from __future__ import annotations

import shutil
import warnings
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import xarray as xr

from ..errors import OutputError
from .atomic import clean_stale, publish_folder, temporary
from .compute import compute
from .hashing import ATTR, content_hash
from .options import FILL_VALUES, OutputOptions


def _zarr():
    try:
        import zarr
    except ImportError:
        raise OutputError("Zarr output needs zarr: pip install 'stressfields[zarr]'") from None
    return zarr


def write(ds: xr.Dataset, target: Path, *, progress: bool = False, scheduler=None, overwrite: bool = False) -> Path:
    """Write ``ds`` to the Zarr store ``target`` atomically (the caller has checked the target and holds
    its run lock, `atomic.target_lock`); without ``overwrite`` an existing target is never replaced."""
    zarr = _zarr()
    target = Path(target)
    clean_stale(target)
    partial = temporary(target, ".partial")
    ds = ds.assign_attrs({ORDER_ATTR: [str(name) for name in ds.variables]})
    try:
        encoding = _encoding(ds)
        with quiet():
            delayed = ds.to_zarr(
                partial, mode="w", encoding=encoding, compute=False, consolidated=True)
            compute(delayed, progress=progress, scheduler=scheduler)
            with read(partial, raw=True) as written:
                digest = content_hash(written)
            group = zarr.open_group(partial, mode="r+")
            group.attrs[ATTR] = digest
            group.attrs["id"] = digest
            zarr.consolidate_metadata(partial)
        publish_folder(partial, target, overwrite)
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


#: the group attribute listing the variables in the dataset's order
ORDER_ATTR = "stressfields_variables"
#: CF attributes that have the type of their variable (CF 1.8, 2.5.1 and 3.5)
TYPED_ATTRS = ("flag_values", "flag_masks", "valid_min", "valid_max", "valid_range", "actual_range",
               "missing_value")


def _encoding(ds: xr.Dataset) -> dict:
    """Chunks as dask's (each worker writes whole chunks of its own); the compressor from the
    output options (`options.OutputOptions`): zarr's default (zstd) unless a level is given, none
    at 0, Blosc/zstd with byte shuffling at 1-9; `_FillValue` for the ``fill`` option."""
    from zarr.codecs import BloscCodec, BloscShuffle

    options = OutputOptions.from_attrs(ds.attrs)
    encoding = {}
    for name, var in ds.variables.items():
        e: dict = {}
        if var.chunks and var.ndim:
            e["chunks"] = tuple(int(c[0]) for c in var.chunks)
        if options.compression == 0:
            e["compressors"] = None
        elif options.compression is not None and var.dtype != object:
            e["compressors"] = (BloscCodec(cname="zstd", clevel=options.compression, shuffle=BloscShuffle.shuffle),)
        if options.nonfinite == "fill" and var.dtype.kind == "f" and name not in ds.coords:
            e["_FillValue"] = var.dtype.type(FILL_VALUES[var.dtype.itemsize])
        encoding[name] = e
    return encoding


@contextmanager
def quiet():
    """Without zarr's note that consolidated metadata is not (yet) in the Zarr 3 specification: the
    package writes and reads it on purpose (one read of the metadata instead of one per array), and
    the note would show on every command."""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="Consolidated metadata", category=UserWarning)
        yield


def _ordered(ds: xr.Dataset, order: list[str]) -> xr.Dataset:
    """``ds`` with its variables in ``order`` (a dataset keeps the order in which they were added)."""
    out = xr.Dataset(attrs=ds.attrs)
    for name in order:
        item = {name: ds.variables[name]}
        out = out.assign_coords(item) if name in ds.coords else out.assign(item)
    return out


def read(path, raw: bool = False, **kw) -> xr.Dataset:
    """The store as a dataset: decoded (``kw`` as for `xr.open_zarr`; the variables in their written
    order, typed CF attributes of their variable's type), or ``raw`` (stored values and attributes,
    for hashing)."""
    _zarr()
    with quiet():
        if raw:
            return xr.open_zarr(path, decode_cf=False, mask_and_scale=False, consolidated=True)
        ds = xr.open_zarr(path, **{"consolidated": True, **kw})
    order = ds.attrs.pop(ORDER_ATTR, None)
    if isinstance(order, list) and set(order) == set(map(str, ds.variables)):
        ds = _ordered(ds, order)
    for var in ds.variables.values():
        for key in TYPED_ATTRS:
            if key in var.attrs and var.dtype.kind in "iuf":
                var.attrs[key] = np.asarray(var.attrs[key], dtype=var.dtype)
    return ds
