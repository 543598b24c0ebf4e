"""Read a recipe (TOML file or dict), check it against its scenario's declaration, normalise it.

A recipe::

    scenario = "conical"
    title = "optional title"
    [parameters]          # each a single value, or a sweep: [..] list, {start, stop, num[, log]}
    nu = 0.3
    mu = [0.0, 0.1, 0.2]
    x = { start = -2.0, stop = 2.0, num = 401 }
    [output]              # optional
    variables = ["sigma_xx", "von_mises"]
    chunks = { x = 1000 }
    [method]              # optional
    method = "auto"
    rtol = 1e-10
    [plot]                # optional: the quick-look PNG (see plot.py)
    [points]              # optional: columns of equal length that vary together along `point`
    x = [0.1, 0.5, 2.0]
    z = [0.2, 0.0, 0.5]

Every error names the key, the value and what is allowed; all errors are reported at once.
Bounds are checked before any work: the file (a regular file of at most MAX_RECIPE_BYTES, UTF-8,
keys of at most MAX_KEY_PARTS dotted parts, at most MAX_NESTING nested arrays/tables), each sweep
(at most MAX_SWEEP values) and their product (at most MAX_POINTS) from the sweep specifications
and the length of the [points] columns,
ARRAY parameters (their declared size limit), and the chunk count of output.chunks.
"""
from __future__ import annotations

import difflib
import hashlib
import json
import math
import os
import re
import reprlib
import stat
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from .scenarios import REGISTRY
from .scenarios.base import ARRAY, Parameter, Scenario
from .writers import output_option_problems

TOP_KEYS = ("scenario", "title", "parameters", "points", "output", "method", "plot")
#: the dimension along which the [points] columns vary together (last, after the swept ones)
POINT = "point"
OUTPUT_KEYS = ("variables", "chunks", "dtype", "compression", "nonfinite")
METHOD_KEYS = ("method", "rtol")
PLOT_KEYS = ("x", "variables", "hue", "kind", "ylim", "marker")
PLOT_KINDS = ("line", "map")
#: matplotlib's one-character markers
PLOT_MARKERS = tuple(".,ov^<>12348spP*hHxXDd|_+")
RTOL_RANGE = (1e-14, 1e-2)
#: recipe files: the largest recipe shipped is ~2 KB; 1 MB holds a 20 000-sample table
MAX_RECIPE_BYTES = 1_000_000
#: tomllib's memory grows with the square of a dotted key's length (5 000 parts: 109 MB,
#: 20 000 parts: 1.5 GB, measured), and it recurses once per nested array or inline table
#: (RecursionError near 1 000 levels): both are bounded before parsing
MAX_KEY_PARTS = 16
MAX_NESTING = 32
#: values of one sweep: its coordinate takes 80 MB and is expanded and checked in ~0.2 s
MAX_SWEEP = 10_000_000
#: points of the whole sweep (the product): 1e4 chunks of the default 1e6 points
MAX_POINTS = 10_000_000_000
#: dask chunks of one variable group: each costs ~10 ms of scheduling whatever its size
#: (2e5 points: 0.4 s in one chunk, 6.9 s in 1 000, 104 s and 1.1 GB in 10 000)
MAX_CHUNKS = 10_000

_SHOW = reprlib.Repr()
_SHOW.maxlevel, _SHOW.maxlist, _SHOW.maxdict, _SHOW.maxstring, _SHOW.maxother = 3, 8, 6, 60, 40


def show(value) -> str:
    """repr for messages, shortened: a recipe value may be a 1 MB list or nested 30 deep."""
    return _SHOW.repr(value)


class RecipeError(ValueError):
    """An invalid recipe; ``problems`` lists every message."""

    def __init__(self, problems: list[str], source: str = "recipe"):
        self.problems = problems
        self.source = source
        super().__init__(f"{source}: " + "; ".join(problems))

    def __str__(self) -> str:
        lines = [f"{self.source} is not valid:"] + [f"  - {p}" for p in self.problems]
        return "\n".join(lines)


@dataclass(frozen=True)
class Recipe:
    scenario: Scenario
    values: dict[str, Any]          # fixed: scalar / tuple (ARRAY); swept: 1-D np.ndarray
    swept: tuple[str, ...]          # swept parameters, in declaration order (= dimension order)
    physical: bool
    variables: tuple[str, ...]
    chunks: dict[str, int]
    method: str
    rtol: float
    title: str
    text: str                       # the recipe as given (TOML text, or canonical JSON of a dict)
    canonical: str                  # canonical JSON of the normalised recipe
    plot: dict
    #: how values are stored ([output] dtype, compression, nonfinite; see writers.OutputOptions)
    storage: dict = field(default_factory=dict)
    #: the [points] columns (declaration order): 1-D arrays of one length in ``values``, varying
    #: together along the dimension POINT, which comes after the swept ones
    points: tuple[str, ...] = ()

    @property
    def dims(self) -> tuple[str, ...]:
        """The dataset's dimensions in order: the swept parameters, then POINT if [points] is given."""
        return self.swept + ((POINT,) if self.points else ())

    @property
    def sha256(self) -> str:
        return hashlib.sha256(self.canonical.encode()).hexdigest()

    @property
    def shape(self) -> dict[str, int]:
        sizes = {name: len(self.values[name]) for name in self.swept}
        if self.points:
            sizes[POINT] = len(self.values[self.points[0]])
        return sizes

    @property
    def size(self) -> int:
        return int(np.prod(list(self.shape.values()), dtype=np.int64)) if self.dims else 1


def load(source: str | Path | Mapping) -> Recipe:
    """Parse and validate a recipe from a TOML path, TOML text or a dict."""
    if isinstance(source, Mapping):
        data, text, label = dict(source), None, "recipe"
    else:
        path = Path(source)
        label = str(path)
        text = _read_text(path, label)
        _check_shape(text, label)
        try:
            data = tomllib.loads(text)
        except ValueError as exc:       # TOMLDecodeError, or an integer of over 4300 digits
            raise RecipeError([f"not valid TOML: {exc}"], label) from None
        except RecursionError:          # _check_shape bounds nesting; kept as a last guard
            raise RecipeError([f"not valid: nested deeper than {MAX_NESTING} levels"], label) from None
    return _validate(data, text, label)


def _read_text(path: Path, label: str) -> str:
    """The file's text: a regular file of at most MAX_RECIPE_BYTES of UTF-8, read without blocking.

    O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer forever; fstat then
    refuses it (and devices such as /dev/zero) before a byte is read.
    """
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError as exc:
        raise RecipeError([f"cannot read the recipe file: {exc.strerror}"], label) from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise RecipeError(["not a regular file (a recipe is a TOML file)"], label)
        if info.st_size > MAX_RECIPE_BYTES:
            raise RecipeError([f"the file has {info.st_size:,} bytes; a recipe has at most "
                               f"{MAX_RECIPE_BYTES:,}"], label)
        with os.fdopen(fd, "rb", closefd=False) as handle:
            raw = handle.read(MAX_RECIPE_BYTES + 1)     # the file may grow after fstat
    except OSError as exc:
        raise RecipeError([f"cannot read the recipe file: {exc.strerror}"], label) from None
    finally:
        os.close(fd)
    if len(raw) > MAX_RECIPE_BYTES:
        raise RecipeError([f"the file has more than {MAX_RECIPE_BYTES:,} bytes; a recipe has at most "
                           f"{MAX_RECIPE_BYTES:,}"], label)
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise RecipeError([f"not UTF-8 text (byte {raw[exc.start]:#04x} at offset {exc.start}); TOML "
                           "is UTF-8"], label) from None


#: strings and comments, in TOML's order of precedence, so that brackets and dots inside them are
#: not counted; an unterminated string runs to the end of its line (or file), so that every
#: character is scanned once (possessive quantifiers: no backtracking on hostile text)
_STRINGS = re.compile(r'"""(?:[^"\\]|\\[\s\S]|"(?!""))*+(?:"""|\Z)|\'\'\'[\s\S]*?(?:\'\'\'|\Z)'
                      r'|"(?:[^"\\\n]|\\.)*+(?:"|$)|\'[^\'\n]*+(?:\'|$)|#[^\n]*+', re.M)
_LONG_KEY = re.compile(r'(?<![\w"+-])[\w"+-]++(?:[ \t]*+\.[ \t]*+[\w"+-]++){%d}' % MAX_KEY_PARTS)


def _check_shape(text: str, label: str) -> None:
    """Refuse text whose keys or nesting would make the TOML parser blow up, before parsing."""
    bare = _STRINGS.sub(lambda m: "" if m.group().startswith("#") else '""', text)
    problems = []
    if _LONG_KEY.search(bare):
        problems.append(f"a key has more than {MAX_KEY_PARTS} dotted parts; recipes nest at most a few")
    codes = np.frombuffer(bare.encode("utf-8", "replace"), dtype=np.uint8)
    step = np.isin(codes, (ord("["), ord("{"))).astype(np.int32) - np.isin(codes, (ord("]"), ord("}")))
    if step.size and int(np.cumsum(step).max()) > MAX_NESTING:
        problems.append(f"arrays or tables are nested more than {MAX_NESTING} levels deep")
    if problems:
        raise RecipeError(problems, label)


def _validate(data: dict, text: str | None, label: str) -> Recipe:
    problems: list[str] = []
    for key in data:
        if key not in TOP_KEYS:
            problems.append(f"unknown key '{key}'; allowed top-level keys: {', '.join(TOP_KEYS)}")
    name = data.get("scenario")
    if name is None:
        raise RecipeError(problems + [f"missing key 'scenario'; one of: {', '.join(REGISTRY)}"], label)
    if not isinstance(name, str) or name not in REGISTRY:
        raise RecipeError(problems + [f"scenario = {show(name)} is unknown; one of: {', '.join(REGISTRY)}"],
                          label)
    scen = REGISTRY[name]
    params = _table(data, "parameters", problems)
    output = _table(data, "output", problems)
    method_t = _table(data, "method", problems)
    plot = _table(data, "plot", problems)
    for table, allowed, tname in ((output, OUTPUT_KEYS, "output"), (method_t, METHOD_KEYS, "method"),
                                  (plot, PLOT_KEYS, "plot")):
        for key in table:
            if key not in allowed:
                problems.append(f"unknown key '{tname}.{key}'; allowed: {', '.join(allowed)}")

    declared = {p.name: p for p in scen.parameters}
    # a scenario without a switch works in physical units only
    physical = scen.physical_switch is None or scen.physical_switch in params
    mode = "physical" if physical else "normalised"
    values: dict[str, Any] = {}
    points_raw = _points_table(data, problems)
    n_points = _points_size(points_raw, problems)          # from the lengths, before any parsing
    rejected = _sweep_sizes(params, declared, problems, n_points)   # before any sweep is expanded
    columns = {} if n_points is None or POINT in rejected else _parse_points(
        points_raw, declared, params, scen, problems)
    # a refused column is already reported: not "missing" as well
    rejected |= {k for k in points_raw if k not in columns and k not in params}
    for key, raw in params.items():
        if key in rejected:
            continue
        if key not in declared:
            problems.append(f"unknown parameter {show(key)} for scenario '{name}'{_hint(scen, key)}; allowed: "
                            f"{', '.join(declared)}")
            if key in scen.renamed:         # said once: its new name is not "missing" as well
                rejected.add(scen.renamed[key])
            continue
        value = _parse_value(declared[key], raw, problems)
        if value is None:
            rejected.add(key)   # already reported: not "missing" as well
        else:
            values[key] = value
    values.update(columns)
    given = set(params) | set(columns)
    # applicability: mode and `when` conditions
    for key in list(values):
        par = declared[key]
        if par.mode and par.mode != mode:
            hint = (f"give '{scen.physical_switch}' to switch to physical units" if par.mode == "physical"
                    else f"it is not used when '{scen.physical_switch}' is given")
            problems.append(f"parameter '{key}' is only used in {par.mode} mode; {hint}")
            del values[key]
    for par in scen.parameters:
        if par.name not in values and par.default is not None and _applies(par, values, declared, mode):
            values[par.name] = par.default
    for key in list(values):
        par = declared[key]
        if not _applies(par, values, declared, mode) and par.when:
            if key in given:
                problems.append(f"parameter '{key}' is only used when {par.condition()}")
            del values[key]
    for par in scen.parameters:
        if par.name not in values and par.name not in rejected and _applies(par, values, declared, mode) and (
                par.required or (par.mode == "physical" and physical)):
            problems.append(f"missing parameter '{par.name}' ({par.meaning}; {par.allowed()}"
                            f"{', in ' + par.units_in(physical) if par.units_in(physical) != '1' else ''})")
    if scen.complete and not problems:
        scen.complete(values)
    if scen.check and not problems:
        problems += scen.check(values, physical, method_t.get("method", "auto"))

    swept = tuple(p.name for p in scen.parameters
                  if isinstance(values.get(p.name), np.ndarray) and p.name not in columns)
    points = tuple(p.name for p in scen.parameters if p.name in columns and p.name in values)
    dims = swept + ((POINT,) if points else ())
    variables = _variables(scen, output.get("variables"), physical, problems)
    chunks = _chunks(output.get("chunks", {}), dims, problems)
    storage = {k: output[k] for k in ("dtype", "compression", "nonfinite") if k in output}
    problems += [f"output.{p}" for p in output_option_problems(**storage)]
    if not problems:
        problems += chunk_problems({d: len(values[points[0] if d == POINT else d]) for d in dims}, chunks,
                                   "output.chunks")
    method, rtol = _method(scen, method_t, problems)
    title = data.get("title", f"stressfields {name}")
    if not isinstance(title, str):
        problems.append(f"title = {show(title)} must be a string")
    if plot and points:
        problems.append("[plot] draws lines and maps over swept parameters; it is not available with [points]")
    elif not problems:
        problems += _plot(scen, plot, swept, variables, physical)
    if problems:
        raise RecipeError(problems, label)

    canonical_dict = {
        "scenario": name,
        "parameters": {k: _jsonable(values[k]) for k in sorted(values) if k not in points},
        "output": {"variables": list(variables), "chunks": dict(sorted(chunks.items()))},
        "method": {"method": method, "rtol": rtol},
    }
    if storage:                     # only when given: recipes without them keep their hash
        canonical_dict["output"].update(sorted(storage.items()))
    if points:                      # likewise
        canonical_dict["points"] = {k: _jsonable(values[k]) for k in sorted(points)}
    canonical = json.dumps(canonical_dict, sort_keys=True, separators=(",", ":"))
    return Recipe(scen, values, swept, physical, variables, chunks, method, rtol, title,
                  text if text is not None else canonical, canonical, dict(plot), storage, points)


def _hint(scen: Scenario, key) -> str:
    """' (renamed: ...)' or ' (did you mean ...?)' for an unknown parameter, else ''."""
    if not isinstance(key, str):
        return ""
    if key in scen.renamed:
        return f" (renamed: it is now {scen.renamed[key]!r})"
    close = difflib.get_close_matches(key, [p.name for p in scen.parameters], n=1, cutoff=0.8)
    return f" (did you mean {close[0]!r}?)" if close else ""


def _table(data: dict, key: str, problems: list[str]) -> dict:
    table = data.get(key, {})
    if not isinstance(table, dict):
        problems.append(f"'{key}' must be a table, got {show(table)}")
        return {}
    return table


def _sweep_size(raw) -> int | None:
    """The number of values a sweep specification asks for, without expanding it (None: no sweep)."""
    if isinstance(raw, list):
        return len(raw)
    if isinstance(raw, dict):
        num = raw.get("num")
        return num if isinstance(num, int) and not isinstance(num, bool) and num >= 1 else None
    return None


def _sweep_sizes(params: dict, declared: dict, problems: list[str], n_points: int | None = None) -> set[str]:
    """Check each sweep's size and their product (with the [points] count) from the specifications;
    the keys refused (POINT among them if the points are)."""
    sizes = {k: n for k, raw in params.items() if k in declared and declared[k].kind != ARRAY
             and (n := _sweep_size(raw)) is not None}
    if n_points is not None:
        sizes[POINT] = n_points
    refused = {k for k, n in sizes.items() if n > MAX_SWEEP}
    for key in refused:
        problems.append(f"{key}: a sweep of {sizes[key]:,} values; at most {MAX_SWEEP:,} per parameter")
    total = math.prod(n for k, n in sizes.items() if k not in refused)
    if total > MAX_POINTS:
        what = " x ".join(f"{k}={n:,}" for k, n in sizes.items() if k not in refused)
        problems.append(f"the sweep {what} has {total:.3g} points; at most {MAX_POINTS:.0e} are allowed")
        refused |= set(sizes)
    return refused


def _points_table(data: dict, problems: list[str]) -> dict:
    """The [points] table (a dict of columns in the Python API), or {} if not given."""
    table = data.get("points", {})
    if not isinstance(table, Mapping):
        problems.append(f"'points' must be a table of columns like {{ x = [0.1, 0.5], z = [0.2, 0.0] }}, "
                        f"got {show(table)}")
        return {}
    if "points" in data and not table:
        problems.append("[points] has no column; give at least one, e.g. x = [0.1, 0.5]")
    return dict(table)


def _points_size(table: dict, problems: list[str]) -> int | None:
    """The number of points, from the columns' lengths only (None: no points, or refused)."""
    lengths = {k: len(v) for k, v in table.items()
               if isinstance(v, (list, tuple)) or (isinstance(v, np.ndarray) and v.ndim == 1)}
    for key, raw in table.items():
        if key not in lengths:
            problems.append(f"points.{show(key)} = {show(raw)} must be a list (or 1-D array) of values")
    if not lengths or len(lengths) < len(table):
        return None
    if len(set(lengths.values())) > 1:
        problems.append("[points] columns must have one length (one value per point): "
                        + ", ".join(f"{k} has {n:,}" for k, n in lengths.items()))
        return None
    n = next(iter(lengths.values()))
    if n == 0:
        problems.append("[points] columns are empty; give at least one point")
        return None
    if n > MAX_SWEEP:
        problems.append(f"[points] has {n:,} points; at most {MAX_SWEEP:,}")
        return None
    return n


def _parse_points(table: dict, declared: dict, params: dict, scen: Scenario,
                  problems: list[str]) -> dict[str, np.ndarray]:
    """The [points] columns as 1-D arrays, each value checked against its parameter's range.

    Unlike a sweep, a column may repeat values and go both ways: it is not a dimension coordinate.
    """
    columns = {}
    for key, raw in table.items():
        if key not in declared:
            problems.append(f"points: unknown parameter {show(key)} for scenario '{scen.name}'{_hint(scen, key)}; "
                            f"allowed: {', '.join(p for p in declared if _is_column(declared[p]))}")
        elif key in params:
            problems.append(f"points.{key}: '{key}' is also given in [parameters]; give it in one place")
        elif not _is_column(declared[key]):
            par = declared[key]
            what = "a choice" if par.choices else "an array" if par.kind == ARRAY else "a single-value"
            problems.append(f"points.{key}: '{key}' cannot be a points column ({what} parameter); "
                            "give it in [parameters]")
        elif (column := _parse_column(declared[key], raw, problems)) is not None:
            columns[key] = column
    return columns


def _is_column(par: Parameter) -> bool:
    return par.sweepable and par.kind != ARRAY and not par.choices


def _parse_column(par: Parameter, raw, problems: list[str]) -> np.ndarray | None:
    """One column: numbers only (type checked one by one for lists), range checked vectorised."""
    key = par.name
    if isinstance(raw, np.ndarray):
        bad_type = None if raw.dtype.kind in "iuf" else 0
    else:
        bad_type = next((i for i, v in enumerate(raw) if isinstance(v, bool) or not isinstance(v, (int, float))),
                        None)
    if bad_type is not None:
        v = raw[bad_type]
        problems.append(f"points.{key}[{bad_type}] = {show(v)} must be {par.allowed()}, got a "
                        f"{type(v).__name__ if not isinstance(raw, np.ndarray) else raw.dtype}")
        return None
    try:
        arr = np.asarray(raw, dtype=np.float64)
    except OverflowError:           # an integer beyond the float range
        arr = np.array([float(v) if abs(v) < 1e308 else np.inf for v in raw])
    first_bad = par.check_many(arr)
    if first_bad:
        value, why = first_bad
        i = int(np.flatnonzero((arr == value) | (np.isnan(arr) & np.isnan(value)))[0])
        problems.append(f"points.{key}[{i}] = {show(raw[i] if not isinstance(raw, np.ndarray) else value)} {why}")
        return None
    return arr.astype(np.int32) if par.kind == "int" else arr    # CF-1.8: no int64


def chunk_problems(sizes: dict[str, int], chunks: dict[str, int], source: str) -> list[str]:
    """Why a chunking would make too many dask tasks (none if fine); checked before a graph is built.

    Chunk sizes of dimensions not given are the largest possible here: the count is a lower
    bound of what build() makes, and build() checks its own chunking again.
    """
    count = math.prod(-(-n // (n if chunks.get(d, -1) == -1 else min(chunks[d], n))) for d, n in sizes.items())
    if count <= MAX_CHUNKS:
        return []
    given = ", ".join(f"{d}={c}" for d, c in chunks.items())
    return [f"{source} {given} makes {count:,} chunks of the sweep {sizes}; at most {MAX_CHUNKS:,} (each "
            "chunk costs ~10 ms of scheduling): give larger chunks"]


def _applies(par: Parameter, values: dict, declared: dict, mode: str) -> bool:
    if par.mode and par.mode != mode:
        return False
    for other, allowed in par.when.items():
        v = values.get(other, declared[other].default)
        if isinstance(v, np.ndarray) or v not in allowed:
            return False
    return True


def _parse_value(par: Parameter, raw, problems: list[str]):
    key = par.name
    if par.kind == ARRAY:
        if not isinstance(raw, list) or len(raw) == 0:
            problems.append(f"{key} = {show(raw)} must be {par.allowed()}")
            return None
        if len(raw) > par.size_limit:
            problems.append(f"{key} has {len(raw):,} values; at most {par.size_limit:,} are allowed")
            return None
        bad = [v for v in raw if par.check(v)]
        if bad:
            problems.append(f"{key} contains {show(bad[0])}; it must be {par.allowed()}")
            return None
        return tuple(float(v) for v in raw)
    if isinstance(raw, (list, dict)):
        if not par.sweepable:
            problems.append(f"{key} = {show(raw)} cannot be swept; give a single value ({par.allowed()})")
            return None
        return _parse_sweep(par, raw, problems)
    why = par.check(raw)
    if why:
        problems.append(f"{key} = {show(raw)} {why}")
        return None
    if par.choices:
        return raw
    return np.int32(raw) if par.kind == "int" else float(raw)


def _parse_sweep(par: Parameter, raw, problems: list[str]):
    """A sweep's values (1-D array), checked at once, strictly monotonic as a CF coordinate must be."""
    key = par.name
    items = _expand_sweep(key, raw, problems)
    if items is None:
        return None
    if par.choices or isinstance(items, list):
        # a list given in the recipe (at most ~1e5 values in a 1 MB file): its types one by one
        for v in items:
            why = par.check(v)
            if why:
                problems.append(f"{key} sweep value {show(v)} {why}")
                return None
        if par.choices:
            if len(set(items)) != len(items):
                problems.append(f"{key} sweep {show(raw)} repeats a value")
                return None
            return np.array(items, dtype=object)
    else:
        first_bad = par.check_many(items)
        if first_bad:
            problems.append(f"{key} sweep value {first_bad[0]!r} {first_bad[1]}")
            return None
    arr = np.asarray(items, dtype=np.int32 if par.kind == "int" else np.float64)  # CF-1.8: no int64
    step = np.diff(arr)
    if np.any(step == 0):
        problems.append(f"{key} sweep {show(raw)} repeats a value; sweep values must be distinct")
        return None
    if not (np.all(step > 0) or np.all(step < 0)):
        i = int(np.argmax(np.sign(step) != np.sign(step[0])))
        problems.append(f"{key} sweep {show(raw)} goes both ways ({arr[i - 1].item()!r}, {arr[i].item()!r}, "
                        f"{arr[i + 1].item()!r}); a coordinate must be strictly increasing or "
                        "decreasing: give the values in order")
        return None
    return arr


def _expand_sweep(key: str, raw, problems: list[str]):
    """A list sweep as given (a list), or a {start, stop, num} table expanded (an array)."""
    if isinstance(raw, list):
        if not raw:
            problems.append(f"{key} = [] is an empty sweep; give at least one value")
            return None
        return list(raw)
    allowed = {"start", "stop", "num", "log"}
    extra = set(raw) - allowed
    missing = {"start", "stop", "num"} - set(raw)
    if extra or missing:
        what = (f"unknown key(s) {sorted(extra)}" if extra else f"missing key(s) {sorted(missing)}")
        problems.append(f"{key} = {show(raw)}: a sweep table needs start, stop, num (and optional log = true); "
                        f"{what}")
        return None
    start, stop, num, log = raw["start"], raw["stop"], raw["num"], raw.get("log", False)
    for k, v in (("start", start), ("stop", stop)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v):
            problems.append(f"{key}.{k} = {show(v)} must be a finite number")
            return None
    if isinstance(num, bool) or not isinstance(num, int) or not 1 <= num <= MAX_SWEEP:
        problems.append(f"{key}.num = {show(num)} must be an integer in [1, {MAX_SWEEP:,}]")
        return None
    if not isinstance(log, bool):
        problems.append(f"{key}.log = {show(log)} must be true or false")
        return None
    if num > 1 and start == stop:
        problems.append(f"{key}: start = stop = {start!r} with num = {num} repeats a value")
        return None
    if log:
        if start <= 0 or stop <= 0:
            problems.append(f"{key}: a log sweep needs start > 0 and stop > 0, got {start!r}, {stop!r}")
            return None
        return np.geomspace(start, stop, num)
    return np.linspace(start, stop, num)


def _variables(scen: Scenario, requested, physical: bool, problems: list[str]) -> tuple[str, ...]:
    # every variable of the mode may be requested; the always-on ones (flags) also join by themselves,
    # so the default list leaves them out (and recipes without output.variables keep their hash)
    available = [v.name for v in scen.variables_in(physical)]
    if requested is None:
        return tuple(scen.default_variables or [v.name for v in scen.variables_in(physical) if not v.always])
    if not isinstance(requested, list) or not requested or not all(isinstance(v, str) for v in requested):
        problems.append(f"output.variables = {show(requested)} must be a non-empty list of names; "
                        f"available: {', '.join(available)}")
        return ()
    for v in requested:
        if v not in available:
            problems.append(f"output.variables: unknown variable {show(v)} for scenario '{scen.name}'"
                            f"{' in this mode' if v in [w.name for w in scen.variables] else ''}; "
                            f"available: {', '.join(available)}")
    return tuple(dict.fromkeys(requested))


def _chunks(raw, swept: tuple[str, ...], problems: list[str]) -> dict[str, int]:
    if not isinstance(raw, dict):
        problems.append(f"output.chunks = {show(raw)} must be a table like {{ x = 1000 }}")
        return {}
    out = {}
    for dim, size in raw.items():
        if dim not in swept:
            problems.append(f"output.chunks.{dim}: '{dim}' is not a swept dimension; "
                            f"swept: {', '.join(swept) or 'none'}")
        elif isinstance(size, bool) or not isinstance(size, int) or (size < 1 and size != -1):
            problems.append(f"output.chunks.{dim} = {show(size)} must be a positive integer (or -1 for whole)")
        else:
            out[dim] = size
    return out


def _method(scen: Scenario, table: dict, problems: list[str]) -> tuple[str, float]:
    method = table.get("method", "auto")
    if method not in scen.methods:
        problems.append(f"method.method = {show(method)} must be one of {', '.join(map(repr, scen.methods))}")
    rtol = table.get("rtol", 1e-10)
    if isinstance(rtol, bool) or not isinstance(rtol, (int, float)) or not (
            RTOL_RANGE[0] <= rtol <= RTOL_RANGE[1]):
        problems.append(f"method.rtol = {show(rtol)} must be a number in [{RTOL_RANGE[0]:g}, {RTOL_RANGE[1]:g}]")
        rtol = 1e-10
    return method, float(rtol)


def _plot(scen: Scenario, plot: dict, swept: tuple[str, ...], variables: tuple[str, ...],
          physical: bool) -> list[str]:
    """Check the [plot] table against what the dataset will hold (plot.py draws every table that passes)."""
    problems: list[str] = []
    if not plot:
        return problems
    if not swept:
        return ["[plot] needs a swept parameter to plot along; none is swept"]
    shown = list(variables) + [v.name for v in scen.variables_in(physical) if v.always]
    dims = {n: tuple(d for d in swept if scen.variable(n).dims is None or d in scen.variable(n).dims)
            for n in shown}
    kind = plot.get("kind", "map" if {"x", "y"} <= set(swept) else "line")
    if kind not in PLOT_KINDS:
        return [f"plot.kind = {show(kind)} must be one of {', '.join(map(repr, PLOT_KINDS))}"]
    if kind == "map" and not {"x", "y"} <= set(swept):
        problems.append(f"plot.kind = 'map' needs x and y swept; swept: {', '.join(swept)}")
    x = plot.get("x", "x" if kind == "map" else swept[-1])
    if kind == "map" and x != "x":
        problems.append(f"plot.x = {show(x)}: a map is drawn over x and y; leave plot.x out")
    elif not isinstance(x, str) or (x not in swept and not dims.get(x)):
        problems.append(f"plot.x = {show(x)} must name a swept parameter ({', '.join(swept)}) or a variable "
                        f"of the output that depends on one ({', '.join(n for n in shown if dims[n])})")
    if problems:
        return problems
    hue = plot.get("hue")
    along = plot_along(x, hue, swept, dims) if kind == "line" else None
    if kind == "line" and along is None:
        return [f"plot.x = {x!r} depends only on plot.hue = {show(hue)}: nothing to draw a line along"]
    if hue is not None and (kind == "map" or not isinstance(hue, str) or hue not in swept or hue in (x, along)):
        problems.append(f"plot.hue = {show(hue)} must name a swept parameter other than the horizontal axis "
                        f"({', '.join(d for d in swept if d not in (x, along)) or 'none'}), in a line plot")
    need = {"x", "y"} if kind == "map" else {along}
    need_text = " and ".join(sorted(need))
    names = plot.get("variables")
    if names is not None and not (isinstance(names, list) and names and all(isinstance(n, str) for n in names)):
        problems.append(f"plot.variables = {show(names)} must be a non-empty list of names of the output")
    elif names is not None:
        for n in names:
            if n not in dims:
                problems.append(f"plot.variables: {show(n)} is not in the output; one of: {', '.join(shown)}")
            elif not need <= set(dims[n]):
                problems.append(f"plot.variables: {n!r} does not depend on {need_text}")
    elif not problems and not any(need <= set(dims[n]) for n in variables):
        problems.append(f"[plot]: no output variable depends on {need_text}; "
                        "name one in plot.variables")
    ylim = plot.get("ylim")
    if ylim is not None and not (isinstance(ylim, list) and len(ylim) == 2 and all(
            isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in ylim)
            and ylim[0] < ylim[1]):
        problems.append(f"plot.ylim = {show(ylim)} must be [low, high], two finite numbers, low < high")
    marker = plot.get("marker")
    if marker is not None and marker not in PLOT_MARKERS:
        problems.append(f"plot.marker = {show(marker)} must be one of {' '.join(PLOT_MARKERS)}")
    return problems


def plot_along(x: str, hue, swept: tuple[str, ...], dims: dict) -> str | None:
    """The dimension a line plot runs along: x itself if swept, else the last dimension of the
    variable x other than hue (None if there is none)."""
    if x in swept:
        return x
    rest = [d for d in dims.get(x, ()) if d != hue]
    return rest[-1] if rest else None


def _jsonable(value):
    if isinstance(value, np.ndarray):
        return [v if isinstance(v, str) else (int(v) if isinstance(v, np.integer) else float(v))
                for v in value.tolist()]
    if isinstance(value, tuple):
        return list(value)
    if isinstance(value, np.generic):
        return value.item()
    return value
