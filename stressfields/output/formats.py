"""The table of output formats, the one target check, and `write`, `export`, `file_hash`, `verify`.

The command line, the Python API, `export` and `hash` all go through here. A format is a module
(`netcdf`, `zarrstore`) with two functions:

    write(ds, target, *, progress, scheduler, overwrite) -> Path
        # atomic: nothing at `target` until complete, the content hash stored inside; without
        # `overwrite` a target that appeared meanwhile is never replaced
    read(path, raw=False) -> xr.Dataset                 # decoded for export, raw (undecoded) for hashing

and, where it can be written in resumable parts, a third (`parts.write`, NetCDF). Adding a format is
one such module, built on the shared machinery (`atomic`, `compute`, `options`, `hashing`), and one
row in `FORMATS`; a format module imports neither this table nor another format's private names.

Before any format sees a dataset, `form.prepare` puts it in its on-disk form, the same for every
format, with the output options (`options`) recorded in the global attribute ``stressfields_output``,
from which each format derives its own encoding. The options of a write are those given to it, over
those the dataset carries from its recipe's ``[output]`` table (`options.carried`), over the defaults.
"""
from __future__ import annotations

import os
import stat
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Protocol

import xarray as xr

from ..errors import OutputError
from . import netcdf, parts, zarrstore
from .atomic import check_name, folder_of, parts_dir, target_lock
from .form import encode_choices, prepare, stored_bytes
from .hashing import ATTR, stored_hash
from .options import OPTIONS_ATTR, OutputOptions, carried, resolved


class Writer(Protocol):
    def __call__(self, ds: xr.Dataset, target: Path, *, progress: bool = False, scheduler=None,
                 overwrite: bool = False) -> Path: ...


@dataclass(frozen=True)
class Format:
    name: str
    suffixes: tuple[str, ...]
    write: Writer
    read: Callable[..., xr.Dataset]
    #: the writer in resumable parts along the first dimension (`parts`), None if the format has none
    write_parts: Writer | None = None

    @property
    def resumable(self) -> bool:
        return self.write_parts is not None


FORMATS: dict[str, Format] = {
    "netcdf": Format("netcdf", (".nc", ".nc4", ".netcdf"), netcdf.write, netcdf.read, parts.write),
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


def check_target(target: str | os.PathLike, *, overwrite: bool = False, resume: bool = False,
                 parts: bool = False) -> Path:
    """The one check before anything is computed: the target may be written, and nothing (an
    interrupted run, a device, a directory that is not a store) would be silently replaced.
    Raises OutputError naming the problem and the way out."""
    target = Path(target)
    fmt = format_for(target)
    if (parts or resume) and not fmt.resumable:
        raise OutputError(f"{target}: {fmt.name} output is not written in parts; drop --parts/--resume")
    parent = folder_of(target)
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


def check_space(needs: list[tuple[Path, int]]) -> None:
    """Refuse, before anything is written, targets whose file system has less free space than they
    need together: ``needs`` is (target, bytes) per output (`stored_bytes`), summed per file system
    (of the nearest existing folder of each target). A target replaced with overwrite still needs
    its full size: the old file stays until the new one is complete. Raises OutputError naming the
    bytes needed and free."""
    groups: dict[int, list] = {}
    for target, need in needs:
        folder = folder_of(Path(target))
        folder = Path(os.path.abspath(folder))
        while not folder.is_dir() and folder != folder.parent:
            folder = folder.parent
        try:
            device = os.stat(folder).st_dev
        except OSError:
            continue            # said by the target checks
        group = groups.setdefault(device, [folder, 0, []])
        group[1] += need
        group[2].append(str(target))
    for folder, need, targets in groups.values():
        try:
            st = os.statvfs(folder)
        except OSError:
            continue            # no figure to check against: the write itself reports a full disk
        free = st.f_bavail * st.f_frsize
        if need > free:
            raise OutputError(f"{', '.join(targets)}: needs about {need:,} bytes ({need / 1e9:,.3g} GB, uncompressed) "
                              f"but {folder} has {free:,} bytes ({free / 1e9:,.3g} GB) free; free some space or write "
                              "elsewhere (--no-space-check, space_check=False: start anyway)")


def space_needed(ds: xr.Dataset, target: Path, options: OutputOptions | None = None, resume: bool = False) -> int:
    """`stored_bytes`, less what the parts of an interrupted run already hold on disk when resuming."""
    held = 0
    if resume:
        try:
            held = os.stat(parts_dir(Path(target)) / "data.nc").st_blocks * 512
        except (OSError, AttributeError):
            pass
    return max(0, stored_bytes(ds, options) - held)


def write(ds: xr.Dataset, path: str | os.PathLike, *, overwrite: bool = False, parts: bool = False,
          resume: bool = False, progress: bool = False, scheduler: Any = None, dtype: str | None = None,
          compression: int | None = None, nonfinite: str | None = None, space_check: bool = True) -> Path:
    """Compute ``ds`` chunk by chunk and write it atomically, with its content hash.

    One run at a time writes a target (`target_lock`); of two runs onto one new name exactly one
    publishes, the other raises OutputError.

    Parameters
    ----------
    ds : xarray.Dataset
        A dataset of `generate` (or `open_dataset`, `open_mfdataset`; a selection of one).
    path : str or path
        The target: ``.nc`` NetCDF, ``.zarr`` a Zarr store.
    overwrite : bool
        Replace an existing target (never a device, FIFO or socket).
    parts : bool
        Write in resumable parts along the first dimension.
    resume : bool
        Finish an interrupted parts run from its verified parts.
    progress : bool
        dask's progress bar, on stderr.
    scheduler : optional
        Passed to dask (None: the local threads; a dask.distributed ``Client`` for a cluster).
    dtype, compression, nonfinite
        The output options (`output_options`); None: as the dataset carries them from its recipe's
        ``[output]`` table (``sf.write(sf.generate(recipe), path)`` stores what the recipe asks),
        else the defaults (float64, the format's default compression, non-finite values kept).

    Returns
    -------
    pathlib.Path
        The written target.

    Raises
    ------
    OutputError
        For a target that exists (without ``overwrite``), a full disk, or a dataset whose
        coordinates go beyond the recipe it carries (`check_provenance`); nothing is left behind.
    """
    options = resolved(carried(ds), dtype=dtype, compression=compression, nonfinite=nonfinite)
    target = check_target(path, overwrite=overwrite, resume=resume, parts=parts)
    if space_check:
        check_space([(target, space_needed(ds, target, options, resume))])
    fmt = format_for(target)
    ds = prepare(ds, options)
    with target_lock(target):
        writer = fmt.write_parts if parts or resume else fmt.write
        return writer(ds, target, progress=progress, scheduler=scheduler, overwrite=overwrite)


def export(source: str | os.PathLike, target: str | os.PathLike, *, overwrite: bool = False) -> Path:
    """Copy a written dataset into another format (e.g. a cluster's Zarr store to NetCDF), atomically.

    Parameters
    ----------
    source : str or path
        A NetCDF file or Zarr store written by stressfields; its content hash is verified first
        (damaged or unfinished input is refused).
    target : str or path
        The copy (format from its suffix); it gets its own content hash.
    overwrite : bool
        Replace an existing target.

    Returns
    -------
    pathlib.Path
        The written target.
    """
    source = Path(source)
    if not source.exists():
        raise OutputError(f"{source}: no such file or store")
    target = check_target(target, overwrite=overwrite)
    verify(source)
    with target_lock(target), format_for(source).read(source) as ds:
        ds.attrs.pop(ATTR, None)
        ds.attrs.pop("id", None)
        for name in ds.variables:      # one format's encodings (compressors, chunk keys) mean nothing to another
            ds[name].encoding = {}
        # the stored dtypes and values are copied as they are; the recorded options (compression)
        # give the new format's encoding
        ds.attrs.setdefault(OPTIONS_ATTR, OutputOptions().text())
        return format_for(target).write(encode_choices(ds), target, overwrite=overwrite)


def to_netcdf(ds: xr.Dataset, path: str | os.PathLike, *, overwrite: bool = False, progress: bool = False,
              scheduler: Any = None, **options: Any) -> Path:
    """`write` to NetCDF whatever the suffix (kept for the API's first users).

    Parameters
    ----------
    ds, path, overwrite, progress, scheduler
        As for `write`.
    **options
        ``dtype``, ``compression``, ``nonfinite`` as for `write` (None or absent: as the dataset
        carries them).

    Returns
    -------
    pathlib.Path
        The written file.
    """
    options = resolved(carried(ds), **options)
    target = check_target(path, overwrite=overwrite)
    ds = prepare(ds, options)
    with target_lock(target):
        return FORMATS["netcdf"].write(ds, target, progress=progress, scheduler=scheduler, overwrite=overwrite)


def file_hash(path: str | os.PathLike) -> tuple[str, str | None]:
    """(recomputed hash, hash stored in the file or None), for any format of `FORMATS`. A file whose
    stored hash is of an earlier form (`hashing.FORMS`) and matches it gives that one."""
    with format_for(path).read(path, raw=True) as ds:
        return stored_hash(ds)


def verify(path: str | os.PathLike) -> str:
    """The content hash of a written file or store after checking it against the stored one. Raises
    OutputError naming the problem when the input cannot be read, carries no hash (a run that did not
    finish, or a file not written here), or its content changed (a flipped bit, a lost chunk)."""
    try:
        digest, stored = file_hash(path)
    except Exception as exc:       # any reader's failure on damaged input: HDF5, zarr, codecs
        raise OutputError(f"{path}: not a readable NetCDF file or Zarr store "
                          f"({type(exc).__name__}: {str(exc)[:200]})") from None
    if stored is None:
        raise OutputError(f"{path}: no stored content hash (unfinished, or not written by stressfields); "
                          "refusing to use it")
    if stored != digest:
        raise OutputError(f"{path}: damaged: its content hash {digest} differs from the stored {stored}")
    return digest


__all__ = ["FORMATS", "Format", "Writer", "check_space", "check_target", "export", "file_hash", "format_for",
           "space_needed", "to_netcdf", "verify", "write"]
