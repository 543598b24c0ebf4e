"""Reopen written data labelled: choice dimensions by their names, not their CF flag codes.

In memory (`sf.generate`) a sweep over choices (``control`` of graded_adhesive, ``domain`` of wavy)
is a string-labelled dimension. On disk it is an int8 flag coordinate (``flag_values``/
``flag_meanings``) with the names beside it in ``<name>_name``, because CF coordinate variables must
be numeric (`output.form.encode_choices`). `open_dataset` turns it back into the labelled form, so
``open_dataset(p).sel(control="fixed_load")`` works and plots are labelled by name; the same is
`xr.open_dataset(p, engine="stressfields")`.

This module imports only the writer layer (xarray, NumPy): xarray loads every installed backend
when it opens a file.
"""
from __future__ import annotations

import os
from typing import Any

import numpy as np
import xarray as xr
from xarray.backends import BackendEntrypoint

from .output.form import SOURCES_ATTR
from .output.formats import format_for


def open_dataset(path: str | os.PathLike, **kw: Any) -> xr.Dataset:
    """A NetCDF file or Zarr store written by stressfields, lazy, choice dimensions labelled by name.

    Parameters
    ----------
    path : str or path
        The file or store (format from its suffix, `output.formats.format_for`).
    **kw
        As for `xarray.open_dataset` (e.g. ``chunks={}`` for dask arrays in the file's own chunks).

    Returns
    -------
    xarray.Dataset
        With its choice dimensions labelled (`decode_choices`).
    """
    return decode_choices(format_for(path).read(path, **kw))


def decode_choices(ds: xr.Dataset) -> xr.Dataset:
    """Every flag-coded choice dimension (an integer coordinate with ``flag_values`` and
    ``flag_meanings`` and its ``<name>_name`` coordinate) as a string-labelled dimension; the inverse
    of `output.form.encode_choices`."""
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


#: the global attribute listing the recipe hashes of every file a merged dataset came from
#: attributes of one file that a merged dataset does not share: its hash and its ACDD id
_OWN = ("stressfields_content_sha256", "id")


def open_mfdataset(paths: str | os.PathLike | list, **kw: Any) -> xr.Dataset:
    """A sweep split over files, as one lazy dataset with the provenance of every file.

    Parameters
    ----------
    paths : str, path or list
        A glob pattern (``"sweep_*.nc"``) or the files, in order.
    **kw
        As for `xarray.open_mfdataset` (e.g. ``combine="nested", concat_dim="mu"``). Global attributes
        are combined with ``combine_attrs="drop_conflicts"`` unless given: what the files share is
        kept, what differs (title, recipe, hashes) is dropped rather than taken from the first file.

    Returns
    -------
    xarray.Dataset
        Choice dimensions labelled by name (`decode_choices`, per file). ``stressfields_source_recipe_sha256``
        lists the recipe hash of every file (each once, in file order), ``history`` every file's history
        and this merge; `sf.write` of it keeps them.
    """
    import glob

    files = sorted(glob.glob(os.fspath(paths))) if isinstance(paths, (str, os.PathLike)) else [os.fspath(p) for p in
                                                                                              paths]
    if not files:
        raise FileNotFoundError(f"no files match {paths!r}")
    heads = []
    for path in files:
        with xr.open_dataset(path) as one:
            heads.append(dict(one.attrs))
    own = kw.pop("preprocess", None)
    kw.setdefault("combine_attrs", "drop_conflicts")
    ds = xr.open_mfdataset(files, preprocess=lambda d: decode_choices(own(d) if own else d), **kw)
    sources = [h.get(SOURCES_ATTR, h.get("stressfields_recipe_sha256", "")).split() for h in heads]
    from . import cf

    histories = list(dict.fromkeys(line for h in heads for line in str(h.get("history", "")).splitlines() if line))
    ds.attrs = {k: v for k, v in ds.attrs.items() if k not in _OWN}
    ds.attrs[SOURCES_ATTR] = " ".join(dict.fromkeys(s for hashes in sources for s in hashes))
    # what the files did not share, said of the merge (catalogues need a title and a summary)
    ds.attrs.setdefault("title", f"{len(files)} stressfields files merged")
    ds.attrs.setdefault("summary", "A sweep split over files, merged: " + "; ".join(
        dict.fromkeys(str(h.get("title", "")) for h in heads)))
    ds.attrs["date_created"] = cf.stamp()
    ds.attrs["history"] = "\n".join(histories + [cf.history(f"open_mfdataset of {len(files)} files")])
    return ds


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
