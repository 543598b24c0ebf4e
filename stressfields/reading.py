"""Reopen written data labelled: choice dimensions by their names, not their CF flag codes.

In memory (`sf.generate`) a sweep over choices (``control`` of graded_adhesive, ``domain`` of wavy)
is a string-labelled dimension. On disk it is an int8 flag coordinate (``flag_values``/
``flag_meanings``) with the names beside it in ``<name>_name``, because CF coordinate variables must
be numeric (`writers.encode_choices`). `open_dataset` turns it back into the labelled form, so
``open_dataset(p).sel(control="fixed_load")`` works and plots are labelled by name; the same is
`xr.open_dataset(p, engine="stressfields")`.

This module imports only the writer layer (xarray, NumPy): xarray loads every installed backend
when it opens a file.
"""
from __future__ import annotations

import os

import numpy as np
import xarray as xr
from xarray.backends import BackendEntrypoint

from .writers import format_for


def open_dataset(path: str | os.PathLike, **kw) -> xr.Dataset:
    """A NetCDF file or Zarr store written by stressfields (format from `writers.format_for`), lazy,
    with its choice dimensions labelled (`decode_choices`); ``kw`` as for `xr.open_dataset` (e.g.
    ``chunks={}`` for dask arrays in the file's own chunks)."""
    return decode_choices(format_for(path).read(path, **kw))


def decode_choices(ds: xr.Dataset) -> xr.Dataset:
    """Every flag-coded choice dimension (an integer coordinate with ``flag_values`` and
    ``flag_meanings`` and its ``<name>_name`` coordinate) as a string-labelled dimension; the inverse
    of `writers.encode_choices`."""
    for name in [d for d in ds.dims if _flag_coded(ds, d)]:
        var = ds[name]
        meanings = dict(zip(np.ravel(var.attrs["flag_values"]).tolist(), var.attrs["flag_meanings"].split()))
        labels = [meanings[code] for code in np.asarray(var.values).tolist()]
        attrs = {k: v for k, v in var.attrs.items() if k not in ("flag_values", "flag_meanings")}
        ds = ds.drop_vars(f"{name}_name").assign_coords({name: xr.Variable((name,), np.array(labels, dtype=object),
                                                                            attrs)})
    return ds


def _flag_coded(ds: xr.Dataset, dim: str) -> bool:
    if dim not in ds.coords or f"{dim}_name" not in ds.coords or ds[dim].dtype.kind not in "iu":
        return False
    attrs = ds[dim].attrs
    if "flag_values" not in attrs or not isinstance(attrs.get("flag_meanings"), str):
        return False
    codes = np.ravel(attrs["flag_values"]).tolist()
    return len(codes) == len(attrs["flag_meanings"].split()) and set(np.asarray(ds[dim].values).tolist()) <= set(codes)


class StressfieldsBackend(BackendEntrypoint):
    """``xr.open_dataset(path, engine="stressfields")``: `open_dataset` as an xarray backend."""

    description = "stressfields NetCDF files and Zarr stores, choice dimensions labelled by name"
    url = "https://pypi.org/project/stressfields/"
    open_dataset_parameters = ("filename_or_obj", "drop_variables")

    def open_dataset(self, filename_or_obj, *, drop_variables=None, **kw) -> xr.Dataset:
        ds = open_dataset(filename_or_obj, **kw)
        return ds.drop_vars(drop_variables or [], errors="ignore")

    def guess_can_open(self, filename_or_obj) -> bool:
        return False        # only when asked by name: the netcdf4 and zarr engines stay the defaults
