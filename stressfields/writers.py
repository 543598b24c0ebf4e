"""Output formats behind one seam: a table keyed by format, one target check, one `write`.

The command line, the Python API, resumable parts, `export` and `hash` all go through here. A
format is a module with two functions:

    write(ds, target, *, progress, scheduler) -> Path   # atomic: nothing at `target` until complete,
                                                        # the content hash stored inside
    read(path, raw=False) -> xr.Dataset                 # decoded for export, raw (undecoded) for hashing

Adding a format is one such module and one row in `FORMATS`.
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Protocol

import xarray as xr

from . import netcdf, zarrstore
from .errors import OutputError


class Writer(Protocol):
    def __call__(self, ds: xr.Dataset, target: Path, *, progress: bool = False, scheduler=None) -> Path: ...


@dataclass(frozen=True)
class Format:
    name: str
    suffixes: tuple[str, ...]
    write: Writer
    read: Callable[..., xr.Dataset]
    #: can be written in resumable parts along the first dimension (see `parts`)
    resumable: bool = False


FORMATS: dict[str, Format] = {
    "netcdf": Format("netcdf", (".nc", ".nc4", ".netcdf"), netcdf.write, netcdf.read, resumable=True),
    "zarr": Format("zarr", (".zarr",), zarrstore.write, zarrstore.read),
}
DEFAULT = "netcdf"


def format_for(path: str | os.PathLike) -> Format:
    """The format of a target, from its suffix; an unknown suffix is NetCDF, or Zarr for an existing
    directory (a store named without `.zarr`)."""
    suffix = Path(path).suffix.lower()
    known = next((f for f in FORMATS.values() if suffix in f.suffixes), None)
    if known is None:
        return FORMATS["zarr"] if Path(path).is_dir() else FORMATS[DEFAULT]
    return known


def parts_dir(target: Path) -> Path:
    """Where the finished parts of an interrupted run wait (see `parts`)."""
    return target.with_name(target.name + ".parts")


def check_target(target: str | os.PathLike, *, overwrite: bool = False, resume: bool = False) -> Path:
    """The one check before anything is computed: the target may be written, and no interrupted run
    would be silently discarded. Raises OutputError naming the problem and the way out."""
    target = Path(target)
    if target.exists() and not overwrite:
        raise OutputError(f"{target} exists; refusing to overwrite it (use --overwrite)")
    if target.is_dir() and format_for(target).name != "zarr":
        raise OutputError(f"{target} is a directory")
    parent = target.parent if str(target.parent) else Path(".")
    if not parent.is_dir():
        raise OutputError(f"cannot write {target}: directory {parent} does not exist")
    if parts_dir(target).exists() and not resume:
        raise OutputError(f"{parts_dir(target)} holds parts of an interrupted run; use --resume to "
                          "finish it, or remove the folder")
    return target


def write(ds: xr.Dataset, path: str | os.PathLike, *, overwrite: bool = False, parts: bool = False,
          resume: bool = False, progress: bool = False, scheduler=None) -> Path:
    """Compute ``ds`` chunk by chunk and write it to ``path`` in the format its suffix names
    (``.nc``: NetCDF, ``.zarr``: Zarr), atomically, with its content hash.

    ``parts=True`` writes in resumable parts along the first dimension; ``resume=True`` finishes an
    interrupted parts run from its verified parts. ``scheduler`` is passed to dask (None: threads).
    """
    fmt = format_for(path)
    target = check_target(path, overwrite=overwrite, resume=resume)
    if parts or resume:
        if not fmt.resumable:
            raise OutputError(f"{target}: {fmt.name} output is not written in parts; drop --parts/--resume")
        from .parts import write_in_parts

        return write_in_parts(ds, target, fmt, progress=progress, scheduler=scheduler)
    return fmt.write(ds, target, progress=progress, scheduler=scheduler)


def export(source: str | os.PathLike, target: str | os.PathLike, *, overwrite: bool = False) -> Path:
    """Copy a written dataset into another format (e.g. a cluster's Zarr store to NetCDF),
    atomically; the copy gets its own content hash."""
    from .hashing import ATTR

    source = Path(source)
    if not source.exists():
        raise OutputError(f"{source}: no such file or store")
    check_target(target, overwrite=overwrite)
    with format_for(source).read(source) as ds:
        ds.attrs.pop(ATTR, None)
        for name in ds.variables:      # one format's encodings (compressors, chunk keys) mean nothing to another
            ds[name].encoding = {}
        return format_for(target).write(ds, Path(target))


def to_netcdf(ds: xr.Dataset, path: str | os.PathLike, *, overwrite: bool = False, progress: bool = False,
              scheduler=None) -> Path:
    """`write` to NetCDF whatever the suffix (kept for the API's first users)."""
    target = check_target(path, overwrite=overwrite)
    return FORMATS["netcdf"].write(ds, target, progress=progress, scheduler=scheduler)


__all__ = ["FORMATS", "Format", "Writer", "OutputError", "check_target", "export", "format_for", "parts_dir",
           "to_netcdf", "write"]
