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
from typing import Any, Callable, Protocol

import numpy as np
import xarray as xr

from . import netcdf, zarrstore
from .errors import OutputError, name_problem
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
    """The checked output options of `write`.

    Parameters
    ----------
    dtype : {"float64", "float32"}
        Storage of the float fields.
    compression : int, optional
        0-9: lossless compression level (None: the format's default).
    nonfinite : {"keep", "nan", "fill"}
        What becomes of +-inf and NaN at singular points.

    Returns
    -------
    OutputOptions

    Raises
    ------
    OutputError
        Naming every problem at once.
    """
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
                                             {"long_name": f"{var.attrs.get('long_name', name)} (name)",
                                              "coverage_content_type": "coordinate"})
    return xr.Dataset(data_vars, coords=coords, attrs=ds.attrs)


def check_provenance(ds: xr.Dataset) -> None:
    """Refuse a dataset whose coordinates go beyond the recipe it carries: merged from files of
    other recipes by a reader that kept the first file's attributes (``xr.open_mfdataset``'s default).
    Written as it is, the file would claim a recipe that did not make it. A selection of a recipe's
    points (``ds.sel(mu=0.3)``) stays within it and passes; `reading.open_mfdataset` records every
    source recipe instead of one (``stressfields_source_recipe_sha256``) and passes too."""
    import json

    from .reading import SOURCES_ATTR

    canonical = ds.attrs.get("stressfields_recipe_canonical")
    if not canonical or SOURCES_ATTR in ds.attrs:
        return
    try:
        params = json.loads(canonical).get("parameters", {})
    except (ValueError, AttributeError):
        return
    for dim in ds.dims:
        swept = params.get(dim)
        if dim not in ds.coords or not isinstance(swept, list) or ds[dim].ndim != 1:
            continue
        values = np.asarray(ds[dim].values)
        if "flag_meanings" in ds[dim].attrs:        # a choice in its stored form: codes -> names
            codes = np.ravel(ds[dim].attrs["flag_values"]).tolist()
            names = dict(zip(codes, str(ds[dim].attrs["flag_meanings"]).split()))
            values = np.array([names.get(v, v) for v in values.tolist()], dtype=object)
        kind = object if values.dtype.kind in "OUT" or any(isinstance(v, str) for v in swept) else float
        values = values.astype(kind)
        beyond = ~np.isin(values, np.asarray(swept, dtype=kind))
        if beyond.any():
            recipe, first = str(ds.attrs.get("stressfields_recipe_sha256", ""))[:16], _plain(values[beyond][0])
            raise OutputError(f"{dim} = {first!r} is not a value of the recipe this dataset carries "
                              f"(stressfields_recipe_sha256 {recipe}): merged from files of other recipes? open them "
                              "with sf.open_mfdataset, which records every source recipe")


def _plain(value):
    return value.item() if isinstance(value, np.generic) else value


def prepare(ds: xr.Dataset, options: OutputOptions | None = None) -> xr.Dataset:
    """``ds`` in its on-disk form for ``options`` (default `OutputOptions()`): choices as CF flags,
    float32 and non-finite values applied lazily, the options recorded in ``stressfields_output``.
    A dataset whose coordinates go beyond its own recipe is refused (`check_provenance`)."""
    options = options or OutputOptions()
    check_provenance(ds)
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
    """The target's name is UTF-8 text without NUL (`errors.name_problem`: the NetCDF library takes
    UTF-8 names) and leaves room for its temporaries (`netcdf.TEMP_OVERHEAD` bytes more)."""
    why = name_problem(str(target))
    if why is not None:
        raise OutputError(f"cannot write {ascii(str(target))}: {why}")
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


def stored_bytes(ds: xr.Dataset, options: OutputOptions | None = None) -> int:
    """The bytes the values of ``ds`` take when stored with ``options`` (`prepare`; uncompressed, so
    an upper bound for compressed output): what a run must find free before it starts. From the
    shapes and dtypes alone, nothing computed."""
    prepared = prepare(ds, options)
    return int(sum(v.size * v.dtype.itemsize for v in prepared.variables.values()))


def check_space(needs: list[tuple[Path, int]]) -> None:
    """Refuse, before anything is written, targets whose file system has less free space than they
    need together: ``needs`` is (target, bytes) per output (`stored_bytes`), summed per file system
    (of the nearest existing folder of each target). A target replaced with overwrite still needs
    its full size: the old file stays until the new one is complete. Raises OutputError naming the
    bytes needed and free."""
    groups: dict[int, list] = {}
    for target, need in needs:
        folder = Path(target).parent if str(Path(target).parent) else Path(".")
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
          resume: bool = False, progress: bool = False, scheduler: Any = None, dtype: str = "float64",
          compression: int | None = None, nonfinite: str = "keep", space_check: bool = True) -> Path:
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
        The output options (`output_options`).

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
    options = output_options(dtype, compression, nonfinite)
    fmt = format_for(path)
    target = check_target(path, overwrite=overwrite, resume=resume, parts=parts)
    if space_check:
        check_space([(target, space_needed(ds, target, options, resume))])
    ds = prepare(ds, options)
    with target_lock(target):
        if parts or resume:
            from .parts import write_in_parts

            return write_in_parts(ds, target, fmt, progress=progress, scheduler=scheduler, overwrite=overwrite)
        return fmt.write(ds, target, progress=progress, scheduler=scheduler, overwrite=overwrite)


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
    from .hashing import ATTR, verify

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
        ``dtype``, ``compression``, ``nonfinite`` as for `write`.

    Returns
    -------
    pathlib.Path
        The written file.
    """
    options = output_options(**options)
    target = check_target(path, overwrite=overwrite)
    ds = prepare(ds, options)
    with target_lock(target):
        return FORMATS["netcdf"].write(ds, target, progress=progress, scheduler=scheduler, overwrite=overwrite)


__all__ = ["FORMATS", "Format", "OPTIONS_ATTR", "OutputError", "OutputOptions", "Writer", "check_space",
           "check_target", "encode_choices", "export", "format_for", "output_option_problems", "output_options",
           "parts_dir", "prepare", "space_needed", "stored_bytes", "target_lock", "to_netcdf", "write"]
