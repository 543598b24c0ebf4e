"""The readers of a recipe's `[points] file = ...`: CSV, .npy, .npz and NetCDF columns, each read
whole after its size is checked, every problem one message (the recipe names the file)."""
from __future__ import annotations

import hashlib
import io
import os
import stat
import warnings
import zipfile
from pathlib import Path

import numpy as np

from .errors import show

#: values of one sweep: its coordinate takes 80 MB and is expanded and checked in ~0.2 s
MAX_SWEEP = 10_000_000
#: a [points] file is read whole (its SHA-256 is of the bytes parsed): 1 GB holds the MAX_SWEEP
#: rows of a CSV of a few columns at full precision (~25 bytes a value)
MAX_POINTS_FILE_BYTES = 1_000_000_000
#: a points file names at most this many columns (a scenario declares fewer than 30 parameters), in a
#: CSV header line of at most MAX_HEADER_CHARS
MAX_FILE_COLUMNS = 64
MAX_HEADER_CHARS = 10_000
POINTS_FILE_TYPES = (".csv", ".npy", ".npz", ".nc")


def file_label(name: str) -> str:
    """The file name as given, whole (a path is rarely long; show() would cut it at 60 characters)."""
    return repr(name) if len(name) <= 4096 else show(name)


# -- points.file ---------------------------------------------------------------------------------

class FileProblem(Exception):
    """Why a points file cannot be read (one message; the caller names the file)."""


def read_points_file(name, base: Path | None, problems: list[str]) -> tuple[dict, dict]:
    """The file's columns, and its name and SHA-256 (of the bytes parsed); ({}, {}) with one problem
    naming the file if it cannot be read."""
    if not isinstance(name, str) or not name.strip():
        problems.append(f"points.file = {show(name)} must be a file name (a string), e.g. \"nodes.csv\"")
        return {}, {}
    path = Path(name)
    if base is not None and not path.is_absolute():
        path = base / path
    suffix = path.suffix.lower()
    try:
        if suffix not in _READERS:
            raise FileProblem(f"unknown file type {show(path.suffix or '(no suffix)')}; one of "
                               f"{', '.join(POINTS_FILE_TYPES)}")
        raw = _file_bytes(path)
        columns = _READERS[suffix](raw)
    except FileProblem as exc:
        problems.append(f"points.file = {file_label(name)}: {exc}")
        return {}, {}
    return columns, {"file": name, "file_sha256": hashlib.sha256(raw).hexdigest()}


def _file_bytes(path: Path) -> bytes:
    """The whole file: a regular file of at most MAX_POINTS_FILE_BYTES, sized before a byte is read
    (O_NONBLOCK: a FIFO is refused by fstat instead of waiting for a writer)."""
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError as exc:
        raise FileProblem(f"cannot read {str(path)!r}: {exc.strerror}") from None
    try:
        info = os.fstat(fd)
        if stat.S_ISDIR(info.st_mode):
            raise FileProblem(f"{str(path)!r} is a directory; give a file")
        if not stat.S_ISREG(info.st_mode):
            raise FileProblem(f"{str(path)!r} is not a regular file")
        if info.st_size > MAX_POINTS_FILE_BYTES:
            raise FileProblem(f"the file has {info.st_size:,} bytes; a points file has at most "
                               f"{MAX_POINTS_FILE_BYTES:,}")
        with os.fdopen(fd, "rb", closefd=False) as handle:
            raw = handle.read(MAX_POINTS_FILE_BYTES + 1)     # the file may grow after fstat
    except OSError as exc:
        raise FileProblem(f"cannot read {str(path)!r}: {exc.strerror}") from None
    finally:
        os.close(fd)
    if len(raw) > MAX_POINTS_FILE_BYTES:
        raise FileProblem(f"the file has more than {MAX_POINTS_FILE_BYTES:,} bytes; a points file has at most "
                           f"{MAX_POINTS_FILE_BYTES:,}")
    if not raw:
        raise FileProblem("the file is empty")
    return raw


def _check_rows(n: int) -> None:
    if n > MAX_SWEEP:
        raise FileProblem(f"it has {n:,} rows; [points] has at most {MAX_SWEEP:,}")


def _check_names(names: list[str]) -> None:
    if len(names) > MAX_FILE_COLUMNS:
        raise FileProblem(f"it has {len(names):,} columns; at most {MAX_FILE_COLUMNS} (one per parameter)")
    if not names:
        raise FileProblem("it has no column")
    twice = next((n for n in names if names.count(n) > 1), None)
    if twice is not None:
        raise FileProblem(f"the column {twice!r} appears twice")


def csv_columns(raw: bytes) -> dict[str, np.ndarray]:
    """A CSV: `#` comment lines, a header naming the columns, then rows of numbers, comma-separated.
    The columns by their header fields as written (`compare` reads units in brackets from them);
    FileProblem says what is wrong, the line and the column included."""
    try:
        text = raw.decode("utf-8-sig")          # a spreadsheet's byte-order mark is not part of the header
    except UnicodeDecodeError as exc:
        raise FileProblem(f"not UTF-8 text (byte {raw[exc.start]:#04x} at offset {exc.start}); a CSV "
                          "is text") from None
    start, line_no = 0, 0
    while True:                                 # the header: the first line neither blank nor a comment
        end = text.find("\n", start)
        end = len(text) if end < 0 else end
        line_no += 1
        if end - start > MAX_HEADER_CHARS:
            raise FileProblem(f"line {line_no} has {end - start:,} characters; a header has at most "
                               f"{MAX_HEADER_CHARS:,}")
        line = text[start:end].strip()
        if line and not line.startswith("#"):
            break
        if end >= len(text):
            raise FileProblem("it has no header line naming the columns (e.g. x,y,z)")
        start = end + 1
    names = [n.strip().strip('"').strip() for n in line.split("#")[0].split(",")]
    _check_names(names)
    if any(not n for n in names):
        raise FileProblem(f"the header {line[:80]!r} has an empty column name")
    if any(_is_number(n) for n in names):
        raise FileProblem(f"the first line {line[:80]!r} holds numbers; it must name the columns (a header "
                           "like x,y,z)")
    body = text[end + 1:]
    try:
        with warnings.catch_warnings():     # "input contained no data": said below as a problem
            warnings.simplefilter("ignore", UserWarning)
            data = np.loadtxt(io.StringIO(body), delimiter=",", comments="#", dtype=np.float64, ndmin=2,
                              max_rows=MAX_SWEEP + 1)
    except ValueError as exc:
        raise FileProblem(_csv_where(body, names, line_no) or f"not numbers: {exc}") from None
    if data.shape[0] == 0:
        raise FileProblem("it has a header but no rows of values")
    if data.shape[0] > MAX_SWEEP:               # read one row past the limit, no further
        raise FileProblem(f"it has more than {MAX_SWEEP:,} rows; [points] has at most {MAX_SWEEP:,}")
    if data.shape[1] != len(names):
        raise FileProblem(f"its rows have {data.shape[1]} values but the header names {len(names)} columns "
                           f"({', '.join(names)})")
    return {n: np.ascontiguousarray(data[:, i]) for i, n in enumerate(names)}


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _csv_where(body: str, names: list[str], header_line: int) -> str | None:
    """Where a CSV the fast reader refused goes wrong: the line, the column and the value (only on
    that error path: one Python step per line)."""
    for offset, line in enumerate(body.splitlines(), start=header_line + 1):
        line = line.split("#")[0].strip()
        if not line:
            continue
        fields = line.split(",")
        if len(fields) != len(names):
            return (f"line {offset} has {len(fields)} values but the header names {len(names)} columns "
                    f"({', '.join(names)})")
        for name, value in zip(names, fields):
            if not _is_number(value.strip()) or "_" in value:
                return f"line {offset}, column {name!r}: {show(value.strip())} is not a number"
    return None


def _npy_header(handle) -> tuple[tuple, np.dtype]:
    """The shape and dtype of a .npy stream, read from its header alone (nothing else is read)."""
    try:
        version = np.lib.format.read_magic(handle)
        read = np.lib.format.read_array_header_1_0 if version == (1, 0) else np.lib.format.read_array_header_2_0
        shape, _, dtype = read(handle)
    except (ValueError, OSError, EOFError) as exc:
        raise FileProblem(f"not a readable .npy array: {exc}") from None
    if dtype.hasobject:
        raise FileProblem("it holds Python objects; a points file holds numbers only")
    return shape, dtype


def _npy_columns(raw: bytes) -> dict[str, np.ndarray]:
    """A .npy file: a 1-D structured array, one named field per column."""
    handle = io.BytesIO(raw)
    shape, dtype = _npy_header(handle)
    if dtype.names is None:
        raise FileProblem(f"it holds a plain array of {dtype} with shape {shape}; a points .npy is a 1-D "
                           "structured array with one named field per column (e.g. np.rec.fromarrays([x, y], "
                           "names='x,y'))")
    _check_names(list(dtype.names))
    if len(shape) != 1:
        raise FileProblem(f"its array has shape {shape}; a points .npy is 1-D (one entry per point)")
    _check_rows(shape[0])
    nested = next((f for f in dtype.names if dtype[f].shape or dtype[f].names), None)
    if nested is not None:
        raise FileProblem(f"the field {nested!r} is not a single number per point ({dtype[nested]})")
    handle.seek(0)
    try:
        arr = np.lib.format.read_array(handle, allow_pickle=False)
    except (ValueError, OSError, EOFError) as exc:
        raise FileProblem(f"not a readable .npy array: {exc}") from None
    return {f: np.ascontiguousarray(arr[f]) for f in dtype.names}


def _npz_columns(raw: bytes) -> dict[str, np.ndarray]:
    """A .npz file: one 1-D array per column, named by the column; the members' sizes are checked from
    the zip directory and their .npy headers before any is decompressed."""
    try:
        archive = zipfile.ZipFile(io.BytesIO(raw))
    except (zipfile.BadZipFile, OSError, ValueError) as exc:
        raise FileProblem(f"not a readable .npz archive: {exc}") from None
    with archive:
        members = archive.infolist()
        names = [m.filename[:-4] if m.filename.endswith(".npy") else m.filename for m in members]
        _check_names(names)
        if sum(m.file_size for m in members) > MAX_POINTS_FILE_BYTES:
            raise FileProblem(f"its arrays take {sum(m.file_size for m in members):,} bytes uncompressed; at "
                               f"most {MAX_POINTS_FILE_BYTES:,}")
        out = {}
        for name, member in zip(names, members):
            try:
                with archive.open(member) as handle:
                    shape, dtype = _npy_header(handle)
                    if len(shape) != 1 or dtype.names is not None:
                        raise FileProblem(f"the array {name!r} has shape {shape} and dtype {dtype}; a points "
                                           ".npz holds one 1-D array of numbers per column")
                    _check_rows(shape[0])
                with archive.open(member) as handle:
                    out[name] = np.lib.format.read_array(handle, allow_pickle=False)
            except (zipfile.BadZipFile, OSError, ValueError, EOFError) as exc:
                raise FileProblem(f"the array {name!r} cannot be read: {exc}") from None
    return out


def _nc_columns(raw: bytes) -> dict[str, np.ndarray]:
    """A NetCDF file (classic or NetCDF4): every variable of the root group is a column, 1-D along one
    dimension; fill values become NaN (and are refused as not finite, with their row)."""
    import netCDF4                              # the writer's dependency: only needed here

    try:
        ds = netCDF4.Dataset("points", mode="r", memory=raw)
    except (OSError, ValueError, RuntimeError) as exc:
        raise FileProblem(f"not a readable NetCDF file: {exc}") from None
    with ds:
        variables = dict(ds.variables)
        _check_names(list(variables))
        bad = next((n for n, v in variables.items() if len(v.dimensions) != 1), None)
        if bad is not None:
            raise FileProblem(f"the variable {bad!r} has dimensions {variables[bad].dimensions}; a points file "
                               "has 1-D variables along one dimension (one entry per point)")
        dims = {v.dimensions[0] for v in variables.values()}
        if len(dims) > 1:
            raise FileProblem(f"its variables lie along {len(dims)} dimensions ({', '.join(sorted(dims))}); a "
                               "points file has one")
        _check_rows(len(ds.dimensions[dims.pop()]))
        out = {}
        for name, var in variables.items():
            try:
                values = var[:]
            except (OSError, ValueError, RuntimeError, TypeError) as exc:
                raise FileProblem(f"the variable {name!r} cannot be read: {exc}") from None
            if np.ma.is_masked(values):
                values = np.ma.filled(values.astype(np.float64), np.nan)
            out[name] = np.asarray(values)
    return out


_READERS = {".csv": csv_columns, ".npy": _npy_columns, ".npz": _npz_columns, ".nc": _nc_columns}
