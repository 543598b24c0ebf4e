"""Output formats behind one seam: a table keyed by format, one target check, one `write`.

The command line, the Python API, resumable parts, `export` and `hash` all go through here. A
format is a module with two functions:

    write(ds, target, *, progress, scheduler, overwrite) -> Path
        # atomic: nothing at `target` until complete, the content hash stored inside; without
        # `overwrite` a target that appeared meanwhile is never replaced
    read(path, raw=False) -> xr.Dataset                 # decoded for export, raw (undecoded) for hashing

Adding a format is one such module and one row in `FORMATS`.
"""
from __future__ import annotations

import os
import stat
import time
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Protocol

import xarray as xr

from . import netcdf, zarrstore
from .errors import OutputError


class Writer(Protocol):
    def __call__(self, ds: xr.Dataset, target: Path, *, progress: bool = False, scheduler=None,
                 overwrite: bool = False) -> Path: ...


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


def check_target(target: str | os.PathLike, *, overwrite: bool = False, resume: bool = False,
                 parts: bool = False) -> Path:
    """The one check before anything is computed: the target may be written, and nothing (an
    interrupted run, a device, a directory that is not a store) would be silently replaced.
    Raises OutputError naming the problem and the way out."""
    target = Path(target)
    fmt = format_for(target)
    if (parts or resume) and not fmt.resumable:
        raise OutputError(f"{target}: {fmt.name} output is not written in parts; drop --parts/--resume")
    parent = target.parent if str(target.parent) else Path(".")
    if not parent.is_dir():
        what = "is not a directory" if os.path.lexists(parent) else "does not exist"
        raise OutputError(f"cannot write {target}: {parent} {what}")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise OutputError(f"cannot write {target}: {parent} is not writable (read-only or no permission)")
    check_name(target, parent)
    if os.path.lexists(target):
        _check_existing(target, fmt, overwrite)
    if os.path.lexists(parts_dir(target)) and not resume:
        raise OutputError(f"{parts_dir(target)} holds parts of an interrupted run; use --resume to "
                          "finish it, or remove the folder")
    return target


def check_name(target: Path, folder: Path) -> None:
    """The target's name leaves room for its temporaries (`netcdf.TEMP_OVERHEAD` bytes more)."""
    try:
        limit = os.pathconf(folder, "PC_NAME_MAX")
    except (OSError, ValueError):
        limit = 255
    size = len(os.fsencode(target.name))
    if size + netcdf.TEMP_OVERHEAD > limit:
        raise OutputError(f"cannot write {target}: its name is {size} bytes; at most "
                          f"{limit - netcdf.TEMP_OVERHEAD} here (file names are limited to {limit} bytes and "
                          f"the temporary written first adds {netcdf.TEMP_OVERHEAD})")


def _check_existing(target: Path, fmt: Format, overwrite: bool) -> None:
    """An existing name (a dangling symbolic link counts) is replaced only with ``overwrite``, and only
    if it is a regular file, or a directory that is a Zarr store (or empty) for a Zarr target."""
    try:
        mode = os.stat(target).st_mode
    except OSError:
        mode = None           # dangling symbolic link
    if mode is not None and not (stat.S_ISREG(mode) or stat.S_ISDIR(mode)):
        raise OutputError(f"{target} is not a regular file (a device, FIFO or socket); refusing to replace it")
    if not overwrite:
        raise OutputError(f"{target} exists; refusing to overwrite it (use --overwrite)")
    if mode is not None and stat.S_ISDIR(mode):
        if fmt.name != "zarr":
            raise OutputError(f"{target} is a directory")
        if not _is_store(target) and any(target.iterdir()):
            raise OutputError(f"{target} is a directory that is not a Zarr store; refusing to replace it")


def _is_store(path: Path) -> bool:
    return any((path / name).is_file() for name in ("zarr.json", ".zgroup", ".zattrs"))


@contextmanager
def target_lock(target: Path):
    """Hold ``.NAME.lock`` beside ``target`` for a whole run: a second run onto the same target stops
    before computing anything. The lock names its owner (`netcdf.OWNER`); a lock whose process is gone
    (a killed run) is taken over."""
    lock = target.with_name(f".{target.name}.lock")
    for _ in range(3):
        try:
            fd = os.open(lock, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644)
        except FileExistsError:
            owner = _read_lock(lock)
            if owner == "":
                continue
            if owner is None or netcdf.owner_alive(owner):
                raise OutputError(f"{target} is being written by another run (process {owner or '?'}; "
                                  f"lock {lock}); wait for it, or remove the lock if that run is gone") from None
            _unlink(lock)
            continue
        except OSError as exc:
            raise OutputError(f"cannot write {target}: {exc.strerror or exc}") from None
        with os.fdopen(fd, "w") as fh:
            fh.write(netcdf.OWNER)
        break
    else:
        raise OutputError(f"{target}: cannot take the lock {lock}")
    try:
        yield
    finally:
        _unlink(lock)


def _read_lock(lock: Path) -> str | None:
    for _ in range(20):            # a new lock is empty until its owner writes its name (microseconds)
        try:
            owner = lock.read_text().strip()
        except FileNotFoundError:
            return ""              # released meanwhile: take it
        except OSError:
            return None
        if owner:
            return owner
        time.sleep(0.005)
    return None


def _unlink(path: Path) -> None:
    try:
        os.unlink(path)
    except FileNotFoundError:
        pass


def write(ds: xr.Dataset, path: str | os.PathLike, *, overwrite: bool = False, parts: bool = False,
          resume: bool = False, progress: bool = False, scheduler=None) -> Path:
    """Compute ``ds`` chunk by chunk and write it to ``path`` in the format its suffix names
    (``.nc``: NetCDF, ``.zarr``: Zarr), atomically, with its content hash.

    ``parts=True`` writes in resumable parts along the first dimension; ``resume=True`` finishes an
    interrupted parts run from its verified parts. ``scheduler`` is passed to dask (None: threads).
    One run at a time writes a target (`target_lock`); of two runs onto one new name exactly one
    publishes, the other raises OutputError.
    """
    fmt = format_for(path)
    target = check_target(path, overwrite=overwrite, resume=resume, parts=parts)
    with target_lock(target):
        if parts or resume:
            from .parts import write_in_parts

            return write_in_parts(ds, target, fmt, progress=progress, scheduler=scheduler, overwrite=overwrite)
        return fmt.write(ds, target, progress=progress, scheduler=scheduler, overwrite=overwrite)


def export(source: str | os.PathLike, target: str | os.PathLike, *, overwrite: bool = False) -> Path:
    """Copy a written dataset into another format (e.g. a cluster's Zarr store to NetCDF),
    atomically; the source's content hash is verified first (damaged or unfinished input is refused)
    and the copy gets its own content hash."""
    from .hashing import ATTR, verify

    source = Path(source)
    if not source.exists():
        raise OutputError(f"{source}: no such file or store")
    target = check_target(target, overwrite=overwrite)
    verify(source)
    with target_lock(target), format_for(source).read(source) as ds:
        ds.attrs.pop(ATTR, None)
        for name in ds.variables:      # one format's encodings (compressors, chunk keys) mean nothing to another
            ds[name].encoding = {}
        return format_for(target).write(ds, target, overwrite=overwrite)


def to_netcdf(ds: xr.Dataset, path: str | os.PathLike, *, overwrite: bool = False, progress: bool = False,
              scheduler=None) -> Path:
    """`write` to NetCDF whatever the suffix (kept for the API's first users)."""
    target = check_target(path, overwrite=overwrite)
    with target_lock(target):
        return FORMATS["netcdf"].write(ds, target, progress=progress, scheduler=scheduler, overwrite=overwrite)


__all__ = ["FORMATS", "Format", "Writer", "OutputError", "check_target", "export", "format_for", "parts_dir",
           "target_lock", "to_netcdf", "write"]
