"""Output formats behind one seam: a table keyed by format, one target check, one `write`.

The command line, the Python API, resumable parts, `export` and `hash` all go through here. A
format is a module with two functions:

    write(ds, target, *, progress, scheduler, overwrite) -> Path
        # atomic: nothing at `target` until complete, the content hash stored inside; without
        # `overwrite` a target that appeared meanwhile is never replaced
    read(path, raw=False) -> xr.Dataset                 # decoded for export, raw (undecoded) for hashing

Adding a format is one such module and one row in `FORMATS`.

Before any format sees a dataset, `prepare` puts it in its on-disk form, the same for every format:
string-labelled choice dimensions become CF flag coordinates (`encode_choices`), and the output
options (`output_options`: dtype, compression, non-finite values) are applied and recorded in the
global attribute `stressfields_output`, from which each format derives its own encoding.
"""
from __future__ import annotations

import os
import stat
import time
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Protocol

import numpy as np
import xarray as xr

from . import netcdf, zarrstore
from .errors import OutputError
from .options import DTYPES, NONFINITE, output_option_problems  # noqa: F401 (re-exported)


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


#: the global attribute recording the output options a file was written with
OPTIONS_ATTR = "stressfields_output"
#: what float32 storage adds to every stated accuracy (float32 has a 24-bit significand)
FLOAT32_NOTE = ("Stored as float32: add a rounding error of at most 6e-8 (2^-24) of |value| "
                "(at most 1.4e-45 absolute below |value| = 1.2e-38).")


@dataclass(frozen=True)
class OutputOptions:
    """How values are stored. ``dtype``: float data variables as float64 (exact) or float32
    (coordinates and the recipe's array inputs stay float64); ``compression``: None for the format's
    default (NetCDF: none; Zarr: zarr's default compressor), 0 for none, 1-9 for zlib (NetCDF) or
    Blosc/zstd (Zarr) at that level; ``nonfinite``: ``keep`` +-inf and NaN, turn +-inf into NaN
    (``nan``), or store +-inf and NaN as the variable's ``_FillValue`` (``fill``). Validity flags are
    always kept: they say why a value is not finite."""
    dtype: str = "float64"
    compression: int | None = None
    nonfinite: str = "keep"

    def text(self) -> str:
        level = "default" if self.compression is None else str(self.compression)
        return f"dtype={self.dtype}; compression={level}; nonfinite={self.nonfinite}"

    @classmethod
    def from_attrs(cls, attrs) -> OutputOptions:
        """The options recorded in a dataset's global attributes (defaults if none are)."""
        text = attrs.get(OPTIONS_ATTR)
        if not isinstance(text, str):
            return cls()
        items = dict(item.strip().partition("=")[::2] for item in text.split(";") if "=" in item)
        level = items.get("compression", "default")
        return output_options(dtype=items.get("dtype", "float64"),
                              compression=None if level == "default" else int(level),
                              nonfinite=items.get("nonfinite", "keep"))


def output_options(dtype: str = "float64", compression: int | None = None, nonfinite: str = "keep") -> OutputOptions:
    """Checked `OutputOptions`; raises OutputError naming every problem at once."""
    problems = output_option_problems(dtype, compression, nonfinite)
    if problems:
        raise OutputError("output options: " + "; ".join(problems))
    return OutputOptions(dtype, None if compression is None else int(compression), nonfinite)


def encode_choices(ds: xr.Dataset) -> xr.Dataset:
    """The CF form of string-labelled dimensions (a sweep over choices): CF coordinate variables
    must be numeric, so the labels become int8 codes with ``flag_values``/``flag_meanings``, and the
    names stand beside them as the auxiliary string coordinate ``<name>_name``. Datasets already in
    that form are returned unchanged (`reading.decode_choices` is the inverse)."""
    labelled = [d for d in ds.dims if d in ds.coords and ds[d].dims == (d,) and ds[d].dtype.kind in "OUT"]
    if not labelled:
        return ds
    coords, data_vars = {}, {}
    for name, var in ds.variables.items():
        if name not in labelled:
            (coords if name in ds.coords else data_vars)[name] = var
            continue
        labels = [str(v) for v in var.values]
        bad = [label for label in labels if not label or any(c.isspace() for c in label)]
        if bad or len(set(labels)) != len(labels) or len(labels) > 127:
            raise OutputError(f"dimension {name!r}: its labels must be at most 127 distinct words without "
                              f"blanks (CF flag_meanings); got {labels[:10]}")
        codes = np.arange(len(labels), dtype=np.int8)
        attrs = {**var.attrs, "flag_values": codes, "flag_meanings": " ".join(labels)}
        coords[name] = xr.Variable((name,), codes, attrs)
        coords[f"{name}_name"] = xr.Variable((name,), np.array(labels, dtype=object),
                                             {"long_name": f"{var.attrs.get('long_name', name)} (name)"})
    return xr.Dataset(data_vars, coords=coords, attrs=ds.attrs)


def prepare(ds: xr.Dataset, options: OutputOptions | None = None) -> xr.Dataset:
    """``ds`` in its on-disk form for ``options`` (default `OutputOptions()`): choices as CF flags,
    float32 and non-finite values applied lazily, the options recorded in ``stressfields_output``."""
    options = options or OutputOptions()
    ds = encode_choices(ds)
    changed = {}
    for name, var in ds.data_vars.items():
        out = _stored(name, var, options)
        if out is not var:
            changed[name] = out
    if changed:
        ds = ds.assign(changed)
    else:
        ds = ds.copy(deep=False)        # the caller's dataset keeps its attributes
    ds.attrs = {**ds.attrs, OPTIONS_ATTR: options.text()}
    return ds


def _stored(name: str, var: xr.DataArray, options: OutputOptions) -> xr.DataArray:
    """One data variable as stored: float32 (an error bound rounded upwards, so it stays a bound)
    and +-inf -> NaN for ``nan``/``fill``. The recipe's array inputs (dims ``<name>_index``) are kept."""
    if var.dtype.kind != "f" or var.dims == (f"{name}_index",):
        return var
    single = options.dtype == "float32"
    if not single and options.nonfinite == "keep":
        return var
    convert = _converter(name, single, upward="error_estimate" in name, no_inf=options.nonfinite != "keep")
    dtype = np.float32 if single else var.dtype
    if hasattr(var.data, "map_blocks"):
        data = var.data.map_blocks(convert, dtype=dtype)
    else:
        data = convert(np.asarray(var.values))
    out = var.copy(data=data)
    if single and "stressfields_accuracy" in out.attrs:
        out.attrs["stressfields_accuracy"] = f"{out.attrs['stressfields_accuracy'].rstrip()} {FLOAT32_NOTE}"
    return out


def _converter(name: str, single: bool, upward: bool, no_inf: bool):
    def convert(block: np.ndarray) -> np.ndarray:
        out = block
        if single:
            with np.errstate(over="ignore"):     # an overflow is refused just below
                out = block.astype(np.float32)
            overflow = np.isinf(out) & np.isfinite(block)
            if overflow.any():    # a finite value must never read as unbounded
                raise OutputError(f"{name}: the finite value {block[overflow].flat[0]:.6g} exceeds the float32 "
                                  "range (3.4e38); write it as float64")
            if upward:
                low = out.astype(block.dtype) < block
                out[low] = np.nextafter(out[low], np.float32(np.inf))
        if no_inf:
            out = np.where(np.isinf(out), out.dtype.type(np.nan), out)
        return out
    return convert


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
          resume: bool = False, progress: bool = False, scheduler=None, dtype: str = "float64",
          compression: int | None = None, nonfinite: str = "keep") -> Path:
    """Compute ``ds`` chunk by chunk and write it to ``path`` in the format its suffix names
    (``.nc``: NetCDF, ``.zarr``: Zarr), atomically, with its content hash.

    ``parts=True`` writes in resumable parts along the first dimension; ``resume=True`` finishes an
    interrupted parts run from its verified parts. ``scheduler`` is passed to dask (None: threads).
    ``dtype``, ``compression`` and ``nonfinite`` are the output options (see `OutputOptions`).
    One run at a time writes a target (`target_lock`); of two runs onto one new name exactly one
    publishes, the other raises OutputError.
    """
    options = output_options(dtype, compression, nonfinite)
    fmt = format_for(path)
    target = check_target(path, overwrite=overwrite, resume=resume, parts=parts)
    ds = prepare(ds, options)
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
        # the stored dtypes and values are copied as they are; the recorded options (compression)
        # give the new format's encoding
        ds.attrs.setdefault(OPTIONS_ATTR, OutputOptions().text())
        return format_for(target).write(encode_choices(ds), target, overwrite=overwrite)


def to_netcdf(ds: xr.Dataset, path: str | os.PathLike, *, overwrite: bool = False, progress: bool = False,
              scheduler=None, **options) -> Path:
    """`write` to NetCDF whatever the suffix (kept for the API's first users); ``options`` as for `write`."""
    options = output_options(**options)
    target = check_target(path, overwrite=overwrite)
    ds = prepare(ds, options)
    with target_lock(target):
        return FORMATS["netcdf"].write(ds, target, progress=progress, scheduler=scheduler, overwrite=overwrite)


__all__ = ["FORMATS", "Format", "OPTIONS_ATTR", "OutputError", "OutputOptions", "Writer", "check_target",
           "encode_choices", "export", "format_for", "output_option_problems", "output_options", "parts_dir",
           "prepare", "target_lock", "to_netcdf", "write"]
