"""The readers of a recipe's `[points] file = ...` and of `compare`'s node files: CSV, .npy, .npz and
NetCDF columns, each read whole after its size, and the size its columns decode to, are checked;
every problem one message (the caller names the file) that quotes no content of the file beyond
column names of the allowed form (`units.LABEL`): a file that is not what it should be (a
symbolic link to a system file, say) is described by line and column numbers, never echoed.

Read policy: a points file named by a recipe is read only from inside the recipe's folder (for a
recipe given as a dict: the working directory), after resolving `..` and symbolic links, or from
inside a folder the caller allows explicitly (``allow_read``; the command line's ``--allow-read``).
"""
from __future__ import annotations

import hashlib
import io
import os
import re
import stat
import zipfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .errors import name_problem, show
from .units import LABEL_RULE, parse_label, show_unit

#: values of one sweep: its coordinate takes 80 MB and is expanded and checked in ~0.2 s
MAX_SWEEP = 10_000_000
#: a [points] file is read whole (its SHA-256 is of the bytes parsed): 1 GB holds the MAX_SWEEP
#: rows of a CSV of a few columns at full precision (~25 bytes a value)
MAX_POINTS_FILE_BYTES = 1_000_000_000
#: the columns read, as float64, take at most this much memory, checked from the file's headers (or
#: for a CSV its line count) before anything is decoded: MAX_SWEEP rows of 12 columns. A small file
#: may declare far more (a 40 KB NetCDF file of 64 variables along 1e7 rows decodes to 5 GB)
MAX_DECODED_BYTES = 1_000_000_000
#: a points file names at most this many columns (a scenario declares fewer than 30 parameters), in a
#: CSV header line of at most MAX_HEADER_CHARS
MAX_FILE_COLUMNS = 64
MAX_HEADER_CHARS = 10_000
POINTS_FILE_TYPES = (".csv", ".npy", ".npz", ".nc")


def file_label(name: str) -> str:
    """The file name as given, whole (a path is rarely long; show() would cut it at 60 characters)."""
    return repr(name) if len(name) <= 4096 else show(name)


@dataclass(frozen=True)
class Column:
    """A column of a points or node file: its name and unit from the label (``name[unit]``) or the
    ``units`` attribute; ``label`` as given (of the form `units.LABEL`, so safe to quote)."""
    name: str
    label: str
    unit: str | None
    values: np.ndarray


# -- points.file ---------------------------------------------------------------------------------

class FileProblem(Exception):
    """Why a points file cannot be read (one message; the caller names the file)."""


def read_points_file(name, base: Path | None, problems: list[str],
                     allow_read=()) -> tuple[list[Column], dict]:
    """The file's columns, and its name and SHA-256 (of the bytes parsed); ([], {}) with one problem
    naming the file if it cannot be read. ``base`` is the recipe's folder (None: the working
    directory); the file must lie inside it, or inside a folder of ``allow_read`` (`resolve`)."""
    if not isinstance(name, str) or not name.strip():
        problems.append(f"points.file = {show(name)} must be a file name (a string), e.g. \"nodes.csv\"")
        return [], {}
    try:
        path = resolve(name, base, allow_read)
        suffix = Path(name).suffix.lower()      # the name's, not its link target's
        if suffix not in _READERS:
            raise FileProblem(f"unknown file type {show(Path(name).suffix or '(no suffix)')}; one of "
                              f"{', '.join(POINTS_FILE_TYPES)}")
        raw = file_bytes(path, name)
        columns = _READERS[suffix](raw)
    except FileProblem as exc:
        problems.append(f"points.file = {file_label(name)}: {exc}")
        return [], {}
    return columns, {"file": name, "file_sha256": hashlib.sha256(raw).hexdigest()}


def resolve(name: str, base: Path | None, allow_read=()) -> Path:
    """The real path of the points file ``name`` (relative to ``base``, the recipe's folder; None:
    the working directory), ``..`` and every symbolic link resolved; FileProblem unless it lies
    inside ``base`` or one of the folders ``allow_read`` names (each resolved likewise)."""
    why = name_problem(name)
    if why is not None:
        raise FileProblem(why)
    folder = Path(os.path.realpath(base if base is not None and str(base) else "."))
    path = Path(name)
    real = Path(os.path.realpath(path if path.is_absolute() else folder / path))
    allowed = [folder]
    for extra in allow_read or ():
        extra = os.fspath(extra)
        if name_problem(extra) is None:
            allowed.append(Path(os.path.realpath(extra)))
    if not any(real == d or d in real.parents for d in allowed):
        more = "" if len(allowed) == 1 else f" or a folder it is allowed to read ({', '.join(map(str, allowed[1:]))})"
        raise FileProblem(f"it lies outside the recipe's folder {str(folder)!r}{more} (an absolute path, '..' or "
                          "a symbolic link leading out of it); points files are read only from inside that folder "
                          "unless another is allowed: --allow-read DIR on the command line, allow_read=[DIR] from "
                          "Python")
    return real


def file_bytes(path: Path, name: str | None = None, limit: int = MAX_POINTS_FILE_BYTES) -> bytes:
    """The whole file: a regular file of at most ``limit`` bytes, sized before a byte is read
    (O_NONBLOCK: a FIFO is refused by fstat instead of waiting for a writer; O_NOFOLLOW: a symbolic
    link put in place of the resolved path after `resolve` is not followed). ``name``: the name
    messages give (default: the path)."""
    shown = repr(name if name is not None else str(path))
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOFOLLOW", 0))
    except OSError as exc:
        raise FileProblem(f"cannot read {shown}: {exc.strerror}") from None
    try:
        info = os.fstat(fd)
        if stat.S_ISDIR(info.st_mode):
            raise FileProblem(f"{shown} is a directory; give a file")
        if not stat.S_ISREG(info.st_mode):
            raise FileProblem(f"{shown} is not a regular file")
        if info.st_size > limit:
            raise FileProblem(f"the file has {info.st_size:,} bytes; at most {limit:,}")
        with os.fdopen(fd, "rb", closefd=False) as handle:
            raw = handle.read(limit + 1)     # the file may grow after fstat
    except OSError as exc:
        raise FileProblem(f"cannot read {shown}: {exc.strerror}") from None
    finally:
        os.close(fd)
    if len(raw) > limit:
        raise FileProblem(f"the file has more than {limit:,} bytes; at most {limit:,}")
    if not raw:
        raise FileProblem("the file is empty")
    return raw


def _check_rows(n: int) -> None:
    if n > MAX_SWEEP:
        raise FileProblem(f"it has {n:,} rows; [points] has at most {MAX_SWEEP:,}")


def _check_decoded(rows: int, columns: int) -> None:
    """The columns as float64 fit MAX_DECODED_BYTES (checked before any is decoded)."""
    size = 8 * rows * columns
    if size > MAX_DECODED_BYTES:
        raise FileProblem(f"its {columns} columns of {rows:,} rows decode to {size:,} bytes; at most "
                          f"{MAX_DECODED_BYTES:,}")


def _labels(labels: list, what: str) -> list[tuple[str, str | None]]:
    """(name, unit) of every label, checked for their number, form and repetition; a label not of
    the form `units.LABEL` is named by its position only."""
    if len(labels) > MAX_FILE_COLUMNS:
        raise FileProblem(f"it has {len(labels):,} {what}s; at most {MAX_FILE_COLUMNS} (one per parameter)")
    if not labels:
        raise FileProblem(f"it has no {what}")
    parsed = []
    for i, label in enumerate(labels, start=1):
        item = parse_label(label)
        if item is None:
            raise FileProblem(f"{what} {i} is not named as a column: its name must be {LABEL_RULE}")
        parsed.append(item)
    names = [n for n, _ in parsed]
    twice = next((n for n in names if names.count(n) > 1), None)
    if twice is not None:
        raise FileProblem(f"the column {twice!r} appears twice")
    return parsed


def csv_columns(raw: bytes) -> list[Column]:
    """A CSV: `#` comment lines, a header naming the columns (``name`` or ``name[unit]``), then rows
    of numbers, comma-separated, UTF-8. FileProblem says what is wrong by line and column."""
    fields, line_no, start = csv_header(raw)
    labels = _labels(fields, "column")
    data = csv_values(raw, start, [n for n, _ in labels], line_no)
    return [Column(n, f, u, np.ascontiguousarray(data[:, i])) for i, ((n, u), f) in enumerate(zip(labels, fields))]


def csv_header(raw: bytes) -> tuple[list[str], int, int]:
    """The header of a CSV (its first line neither blank nor a `#` comment; a byte-order mark skipped):
    its fields as written (spaces, quotes and a trailing comment taken off), its line number (from 1)
    and the offset of the rows after it. FileProblem if there is none, or it holds numbers or an
    empty name; the fields' form is the caller's to check."""
    start = 3 if raw.startswith(b"\xef\xbb\xbf") else 0    # a spreadsheet's byte-order mark
    line_no = 0
    while True:                                 # the header: the first line neither blank nor a comment
        end = raw.find(b"\n", start)
        end = len(raw) if end < 0 else end
        line_no += 1
        if end - start > MAX_HEADER_CHARS:
            raise FileProblem(f"line {line_no} has {end - start:,} characters; a header has at most "
                               f"{MAX_HEADER_CHARS:,}")
        line = _text(raw[start:end], start).strip()
        if line and not line.startswith("#"):
            break
        if end >= len(raw):
            raise FileProblem("it has no header line naming the columns (e.g. x,y,z)")
        start = end + 1
    fields = [n.strip().strip('"').strip() for n in line.split("#")[0].split(",")]
    if any(_is_number(n) for n in fields):
        raise FileProblem(f"line {line_no} holds numbers; the first line must name the columns (a header "
                           "like x,y,z)")
    empty = next((i for i, n in enumerate(fields, start=1) if not n), None)
    if empty is not None:
        raise FileProblem(f"the header (line {line_no}) has an empty column name (column {empty})")
    return fields, line_no, end + 1


def csv_values(raw: bytes, start: int, names: list[str], header_line: int, *, by_row: bool = False) -> np.ndarray:
    """The rows of numbers of a CSV from byte ``start`` on (after its header, `csv_header`), one row
    per data line and one column per name, in one parse (`_csv_values`), the size they decode to
    checked first. A fault is named by its line and column (``by_row``: by its data row, from 0,
    then the line); a field written "nan" is read as NaN, for the caller to refuse."""
    # a data row of k numbers takes at least 2k bytes (digits, commas, its newline): the body's size
    # bounds the decoded size to 4 bytes per byte, and the lines are counted only where that is not enough
    if 4 * (len(raw) - start + 1) > MAX_DECODED_BYTES:
        rows = raw.count(b"\n", start) + 1     # at least the data rows (comment and blank lines too)
        _check_decoded(min(rows, MAX_SWEEP + 1), len(names))
    data = _csv_values(raw, start, names, header_line, by_row)
    if data.shape[0] == 0:
        raise FileProblem("it has a header but no rows of values")
    if data.shape[0] > MAX_SWEEP:               # read one row past the limit, no further
        raise FileProblem(f"it has more than {MAX_SWEEP:,} rows; [points] has at most {MAX_SWEEP:,}")
    return data


def _text(raw: bytes, offset: int) -> str:
    """``raw`` (found at ``offset`` in the file) as UTF-8 text, or FileProblem naming the first bad byte."""
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise FileProblem(f"not UTF-8 text (byte {raw[exc.start]:#04x} at offset {offset + exc.start}); a CSV "
                          "is text") from None


def _csv_values(raw: bytes, start: int, names: list[str], header_line: int, by_row: bool = False) -> np.ndarray:
    """The rows of numbers from byte ``start`` on (after the header), parsed by pandas' C reader from
    the bytes (correctly rounded; a 1e6-row CSV of three columns in 0.57-0.76 s here against 2.5-2.6 s
    for np.loadtxt, medians of 3 at a load of 11-13 on 2 cores, pandas already imported, as xarray
    does). The fast pass takes numbers only: no missing-value filter, and comments only if the body
    has a ``#``. A missing value, a row of the wrong length, a
    field that is not a number or a byte that is not UTF-8 is then located by `_csv_where` (one Python
    step per line, on that error path only); if it finds none, the fields written "nan" are what
    failed, and a second pass reads them as NaN (refused with its row by the range checks)."""
    import csv

    import pandas as pd                         # installed with xarray

    columns = len(names)
    if _BLANK.fullmatch(raw, start):
        return np.empty((0, columns))
    options = dict(header=None, names=list(range(columns)), dtype=np.float64, engine="c", encoding="utf-8",
                   quoting=csv.QUOTE_NONE, skip_blank_lines=True, nrows=MAX_SWEEP + 1, index_col=False,
                   comment="#" if raw.find(b"#", start) >= 0 else None)
    try:
        frame = pd.read_csv(_from(raw, start), na_filter=False, **options)
    except (ValueError, pd.errors.ParserError) as exc:     # no message of pandas': it quotes the cell
        where = _csv_where(_text(raw[start:], start), names, header_line, by_row)
        if where is not None:
            raise FileProblem(where) from None
        try:
            frame = pd.read_csv(_from(raw, start), keep_default_na=False, na_values=["nan", "NaN", "-nan"],
                                **options)
        except (ValueError, pd.errors.ParserError):
            raise FileProblem(f"not a table of numbers ({type(exc).__name__})") from None
    return frame.to_numpy(dtype=np.float64)


def _from(raw: bytes, start: int) -> io.BytesIO:
    """``raw`` from byte ``start`` on as a file, without a copy (a slice of a 1e6-row file copies 90 MB)."""
    handle = io.BytesIO(raw)        # shares the bytes while nothing writes to it
    handle.seek(start)
    return handle


#: a body of blank lines only (no rows)
_BLANK = re.compile(rb"\s*")


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _csv_where(body: str, names: list[str], header_line: int, by_row: bool = False) -> str | None:
    """Where a CSV the fast reader refused goes wrong: the line (``by_row``: the data row, from 0, and
    the line) and the column (by its name, checked to be of the form `units.LABEL`; the text of the
    field is not quoted)."""
    row = -1
    for offset, line in enumerate(body.split("\n"), start=header_line + 1):
        line = line.split("#")[0].strip(" \t\r")
        if not line:
            continue
        row += 1
        at = f"data row {row} (from 0, line {offset})" if by_row else f"line {offset}"
        fields = line.split(",")
        if len(fields) != len(names):
            return (f"{at} has {len(fields)} values but the header names {len(names)} columns "
                    f"({', '.join(names)})")
        for name, value in zip(names, fields):
            value = value.strip(" \t\r")
            # ASCII only, as pandas' reader takes: Python's float() also strips Unicode blanks and
            # reads Unicode digits and 1_000
            if not value.isascii() or not _is_number(value) or "_" in value:
                return f"{at}, column {name!r}: not a number"
    return None


def _npy_header(handle, size: int) -> tuple[tuple, np.dtype]:
    """The shape and dtype of a .npy stream of ``size`` bytes, read from its header alone (nothing else
    is read), checked to hold numbers only and to declare no more values than the stream holds."""
    try:
        version = np.lib.format.read_magic(handle)
        read = np.lib.format.read_array_header_1_0 if version == (1, 0) else np.lib.format.read_array_header_2_0
        shape, _, dtype = read(handle)
    except (ValueError, OSError, EOFError, SyntaxError, TypeError, RecursionError):   # numpy's quote the header
        raise FileProblem("not a readable .npy array (its header cannot be read)") from None
    if dtype.hasobject:
        raise FileProblem("it holds Python objects; a points file holds numbers only")
    count = int(np.prod(shape, dtype=object))
    if count * dtype.itemsize > size - handle.tell():
        raise FileProblem(f"its header declares {count:,} entries of {dtype.itemsize:,} bytes, more than the "
                          f"{max(0, size - handle.tell()):,} bytes of data it holds")
    return shape, dtype


def _numeric(dtype: np.dtype) -> bool:
    return dtype.kind in "iuf" and not dtype.shape


def _npy_columns(raw: bytes) -> list[Column]:
    """A .npy file: a 1-D structured array, one named field per column."""
    handle = io.BytesIO(raw)
    shape, dtype = _npy_header(handle, len(raw))
    if dtype.names is None:
        raise FileProblem("it holds a plain array; a points .npy is a 1-D structured array with one named "
                          "field per column (e.g. np.rec.fromarrays([x, y], names='x,y'))")
    labels = _labels(list(dtype.names), "field")
    if len(shape) != 1:
        raise FileProblem(f"its array has shape {shape}; a points .npy is 1-D (one entry per point)")
    _check_rows(shape[0])
    bad = next((i for i, f in enumerate(dtype.names) if not _numeric(dtype[f])), None)
    if bad is not None:
        raise FileProblem(f"the field {dtype.names[bad]!r} is not a single number per point")
    _check_decoded(shape[0], len(labels))
    handle.seek(0)
    try:
        arr = np.lib.format.read_array(handle, allow_pickle=False)
    except (ValueError, OSError, EOFError):
        raise FileProblem("not a readable .npy array (its data cannot be read)") from None
    return [Column(n, f, u, np.ascontiguousarray(arr[f])) for f, (n, u) in zip(dtype.names, labels)]


def _npz_columns(raw: bytes) -> list[Column]:
    """A .npz file: one 1-D array per column, named by the column; the members' sizes are checked from
    the zip directory and their .npy headers before any is decompressed."""
    try:
        archive = zipfile.ZipFile(io.BytesIO(raw))
    except (zipfile.BadZipFile, OSError, ValueError):
        raise FileProblem("not a readable .npz archive") from None
    with archive:
        members = archive.infolist()
        labels = _labels([m.filename[:-4] if m.filename.endswith(".npy") else m.filename for m in members],
                         "array")
        if sum(m.file_size for m in members) > MAX_POINTS_FILE_BYTES:
            raise FileProblem(f"its arrays take {sum(m.file_size for m in members):,} bytes uncompressed; at "
                               f"most {MAX_POINTS_FILE_BYTES:,}")
        rows = []
        for i, member in enumerate(members):
            try:
                with archive.open(member) as handle:
                    shape, dtype = _npy_header(handle, member.file_size)
            except (zipfile.BadZipFile, OSError, ValueError, EOFError):
                raise FileProblem(f"the array {labels[i][0]!r} cannot be read") from None
            if len(shape) != 1 or not _numeric(dtype) or dtype.names is not None:
                raise FileProblem(f"the array {labels[i][0]!r} has shape {shape} and is not a 1-D array of numbers; "
                                  "a points .npz holds one per column")
            _check_rows(shape[0])
            rows.append(shape[0])
        _check_decoded(max(rows), len(rows))
        out = []
        for (name, unit), member in zip(labels, members):
            try:
                with archive.open(member) as handle:
                    values = np.lib.format.read_array(handle, allow_pickle=False)
            except (zipfile.BadZipFile, OSError, ValueError, EOFError):
                raise FileProblem(f"the array {name!r} cannot be read") from None
            out.append(Column(name, member.filename[:-4] if member.filename.endswith(".npy") else member.filename,
                              unit, values))
    return out


def nc_columns(raw: bytes, *, skip_scalars: bool = False, drop_index: bool = False, kept_index=()) -> list[Column]:
    """A NetCDF file (classic or NetCDF4): the variables of the root group are columns, 1-D along one
    dimension, with the unit of their ``units`` attribute; fill values become NaN (refused as not
    finite, with their row). ``skip_scalars``: leave 0-D variables (metadata) out instead of refusing
    them; ``drop_index``: leave the dimension's own coordinate variable out unless it is named in
    ``kept_index``. The size the columns decode to is checked before a value is read."""
    import netCDF4                              # the writer's dependency: only needed here

    try:
        ds = netCDF4.Dataset("points", mode="r", memory=raw)
    except (OSError, ValueError, RuntimeError):
        raise FileProblem("not a readable NetCDF file") from None
    with ds:
        variables = {k: v for k, v in ds.variables.items() if not (skip_scalars and not v.dimensions)}
        parsed = _labels(list(variables), "variable")
        for (name, _), var in zip(parsed, variables.values()):
            if len(var.dimensions) != 1:
                raise FileProblem(f"the variable {name!r} has {len(var.dimensions)} dimensions; a points file "
                                  "has 1-D variables along one dimension (one entry per point)")
            # a primitive type only: strings, variable-length, compound and enum types are not numbers
            if not isinstance(var.datatype, np.dtype) or not _numeric(var.datatype):
                raise FileProblem(f"the variable {name!r} does not hold numbers")
        dims = {v.dimensions[0] for v in variables.values()}
        if len(dims) > 1:
            raise FileProblem(f"its variables lie along {len(dims)} dimensions; a points file has one")
        dim = dims.pop()
        rows = len(ds.dimensions[dim])
        _check_rows(rows)
        kept = [(label, item, var) for label, item, var in zip(variables, parsed, variables.values())
                if not (drop_index and label == dim and label not in kept_index)]
        _check_decoded(rows, len(kept))
        out = []
        for label, (name, bracket), var in kept:
            unit = var.getncattr("units") if "units" in var.ncattrs() else None
            if unit is not None and not isinstance(unit, str):
                raise FileProblem(f"the variable {name!r} has a units attribute that is not text")
            if unit is not None and bracket is not None and unit.strip() != bracket:
                raise FileProblem(f"the variable {name!r} gives two units, [{bracket}] in its name and "
                                  f"{show_unit(unit)} as its units attribute")
            try:
                values = var[:]
            except (OSError, ValueError, RuntimeError, TypeError, IndexError):
                raise FileProblem(f"the variable {name!r} cannot be read") from None
            if np.ma.is_masked(values):
                values = np.ma.filled(values.astype(np.float64), np.nan)
            out.append(Column(name, label, bracket if unit is None else unit.strip(), np.asarray(values)))
    return out


_READERS = {".csv": csv_columns, ".npy": _npy_columns, ".npz": _npz_columns, ".nc": nc_columns}
