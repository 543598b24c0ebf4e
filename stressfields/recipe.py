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
    [splits]              # optional: train/valid/test of the ML exports (see splits.py)
    [points]              # optional: columns of equal length that vary together along `point`
    x = [0.1, 0.5, 2.0]
    z = [0.2, 0.0, 0.5]
    # or, as the one key of [points]: file = "nodes.csv" (.csv, .npy, .npz, .nc; relative to the
    # recipe's directory and read only from inside it, see pointfiles.resolve),
    # or sample = { n = 1000, method = "sobol", seed = 1, mu = [0.0, 1.0] }

Every error names the key, the value and what is allowed; all errors are reported at once.
Bounds are checked before any work: the file (a regular file of at most MAX_RECIPE_BYTES, UTF-8,
keys of at most MAX_KEY_PARTS dotted parts, at most MAX_NESTING nested arrays/tables), each sweep
(at most MAX_SWEEP values) and their product (at most MAX_POINTS) from the sweep specifications
and the length of the [points] columns (a points file: at most pointfiles.MAX_POINTS_FILE_BYTES,
checked before it is read; a sample: its n, before it is drawn),
ARRAY parameters (their declared size limit), and the chunk count of output.chunks.
"""
from __future__ import annotations

import difflib
import hashlib
import json
import math
import os
import re
import stat
import sys
import tomllib
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Collection, Mapping

import numpy as np

from .errors import name_problem, show
from .pointfiles import MAX_SWEEP, file_label, read_points_file
from .scenarios import REGISTRY
from .scenarios.base import ARRAY, Parameter, Scenario
from .options import output_option_problems
from .units import NOT_PARAMETERS, allowed as allowed_units, canonical, factor as unit_factor, show_unit

TOP_KEYS = ("scenario", "title", "parameters", "points", "output", "method", "plot", "splits", "compare")
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
#: points of the whole sweep (the product): 1e4 chunks of the default 1e6 points
MAX_POINTS = 10_000_000_000
#: dask chunks of one variable group: each costs ~10 ms of scheduling whatever its size
#: (2e5 points: 0.4 s in one chunk, 6.9 s in 1 000, 104 s and 1.1 GB in 10 000)
MAX_CHUNKS = 10_000
SAMPLE_METHODS = ("sobol", "lhs", "uniform")
#: the keys of points.sample that are not parameter ranges
SAMPLE_KEYS = ("n", "method", "seed")

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
    #: the checked [splits] table in canonical form (splits.py), {} if none: used by the ML exports
    splits: dict = field(default_factory=dict)

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


#: the recipe path that means standard input (`stressfields validate -`, `stressfields run - -o x.nc`)
STDIN = "-"


def load(source: str | Path | Mapping, allow_read=()) -> Recipe:
    """Parse and validate a recipe from a TOML path (``"-"``: standard input, relative paths in it
    then from the working directory) or a dict.

    A points file the recipe names (``[points] file``) is read only from inside the recipe's folder
    (a dict's or standard input's: the working directory), symbolic links resolved, or from inside one
    of the folders ``allow_read`` lists (see `pointfiles.resolve`).
    """
    if isinstance(source, Mapping):
        data, text, label = dict(source), None, "recipe"
    else:
        stdin = str(source) == STDIN
        path = Path.cwd() / "stdin.toml" if stdin else Path(source)
        label = "<stdin>" if stdin else str(path)
        why = None if stdin else name_problem(label)
        if why is not None:         # said with ascii(): the name itself may not print
            raise RecipeError([f"cannot read the recipe file: {why}"], ascii(label))
        text = _decoded(sys.stdin.buffer.read(MAX_RECIPE_BYTES + 1), label) if stdin else _read_text(path, label)
        _check_shape(text, label)
        try:
            data = tomllib.loads(text)
        except ValueError as exc:       # TOMLDecodeError, or an integer of over 4300 digits
            raise RecipeError([f"not valid TOML: {exc}"], label) from None
        except RecursionError:          # _check_shape bounds nesting; kept as a last guard
            raise RecipeError([f"not valid: nested deeper than {MAX_NESTING} levels"], label) from None
    return _validate(data, text, label, None if isinstance(source, Mapping) else path.parent, allow_read)


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
    return _decoded(raw, label)


def _decoded(raw: bytes, label: str) -> str:
    """Recipe bytes as text: at most MAX_RECIPE_BYTES of UTF-8."""
    if len(raw) > MAX_RECIPE_BYTES:
        raise RecipeError([f"the file has more than {MAX_RECIPE_BYTES:,} bytes; a recipe has at most "
                           f"{MAX_RECIPE_BYTES:,}"], label)
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise RecipeError([f"not UTF-8 text (byte {raw[exc.start]:#04x} at offset {exc.start}); TOML "
                           "is UTF-8"], label) from None


#: strings and comments, in TOML's order of precedence, so that brackets and dots inside them are
#: not counted; an unterminated string runs to the end of its line (or file), a trailing backslash
#: included, so that every character is scanned once (possessive quantifiers: no backtracking on
#: hostile text; without the backslash a line of "\"\"\... made every quote a failed start that
#: scanned to the line's end: quadratic, 16 KB took 1.15 s)
_STRINGS = re.compile(r'"""(?:[^"\\]|\\[\s\S]|"(?!""))*+(?:"""|\\?\Z)|\'\'\'[\s\S]*?(?:\'\'\'|\Z)'
                      r'|"(?:[^"\\\n]|\\.)*+(?:"|\\?$)|\'[^\'\n]*+(?:\'|$)|#[^\n]*+', re.M)
_LONG_KEY = re.compile(r'(?<![\w"+-])[\w"+-]++(?:[ \t]*+\.[ \t]*+[\w"+-]++){%d}' % MAX_KEY_PARTS)


def _check_shape(text: str, label: str) -> None:
    """Refuse text whose keys or nesting would make the TOML parser blow up, before parsing."""
    # a comment becomes "" too: a token without a dot cannot lengthen a key, and one replacement
    # text keeps the substitution in C (a Python callback per match: 0.26 s of 1 MB of hostile lines)
    bare = _STRINGS.sub('""', text)
    problems = []
    if _LONG_KEY.search(bare):
        problems.append(f"a key has more than {MAX_KEY_PARTS} dotted parts; recipes nest at most a few")
    codes = np.frombuffer(bare.encode("utf-8", "replace"), dtype=np.uint8)
    step = np.isin(codes, (ord("["), ord("{"))).astype(np.int32) - np.isin(codes, (ord("]"), ord("}")))
    if step.size and int(np.cumsum(step).max()) > MAX_NESTING:
        problems.append(f"arrays or tables are nested more than {MAX_NESTING} levels deep")
    if problems:
        raise RecipeError(problems, label)


def _validate(data: dict, text: str | None, label: str, base: Path | None = None, allow_read=()) -> Recipe:
    """The checked recipe; ``base`` is the directory a relative points.file is found in and must lie
    in (None: the working directory, for a recipe given as a dict), or in a folder of ``allow_read``."""
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
    if "compare" in data:       # used by `compare` alone (the units of a VTU or Exodus file); checked here too
        from .fe.units import compare_table_problem

        problem = compare_table_problem(data["compare"])
        if problem:
            problems.append(problem)

    declared = {p.name: p for p in scen.parameters}
    # a scenario without a switch works in physical units only
    physical = scen.physical_switch is None or scen.physical_switch in params
    mode = "physical" if physical else "normalised"
    values: dict[str, Any] = {}
    points_raw, source = _points_table(data, declared, params, scen, base, problems, physical, allow_read)
    # from the lengths (or the sample's n), before any parsing or drawing
    n_points = source["sample"]["n"] if "sample" in source else _points_size(points_raw, _said(problems, source))
    rejected = _sweep_sizes(params, declared, problems, n_points)   # before any sweep is expanded
    if "sample" in source and POINT not in rejected:
        points_raw = draw_sample(source["sample"])
    columns = {} if n_points is None or POINT in rejected else _parse_points(
        points_raw, declared, params, scen, _said(problems, source))
    # a refused column is already reported: not "missing" as well
    rejected |= {k for k in points_raw if k not in columns and k not in params}
    if "points" in data and not columns:    # a refused file or sample: its columns are not "missing" too
        rejected |= {k for k, par in declared.items() if par.per_point and k not in params}
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
    method, rtol = _method(scen, method_t, problems)
    if scen.check and not problems:
        listed = output.get("variables")
        listed = tuple(v for v in listed if isinstance(v, str)) if isinstance(listed, list) else ()
        marked = CheckValues(values, tuple(k for k in columns if k in values), listed)
        problems += scen.check(marked, physical, {"method": method, "rtol": rtol})

    swept = tuple(p.name for p in scen.parameters
                  if isinstance(values.get(p.name), np.ndarray) and p.name not in columns)
    points = tuple(p.name for p in scen.parameters if p.name in columns and p.name in values)
    dims = swept + ((POINT,) if points else ())
    variables = _variables(scen, output.get("variables"), physical, problems, values)
    chunks = _chunks(output.get("chunks", {}), dims, problems)
    storage = {k: output[k] for k in ("dtype", "compression", "nonfinite") if k in output}
    problems += [f"output.{p}" for p in output_option_problems(**storage)]
    if not problems:
        problems += chunk_problems({d: len(values[points[0] if d == POINT else d]) for d in dims}, chunks,
                                   "output.chunks")
    if method_t and not problems:
        # only a recipe that names its method or rtol can ask for one without a route (every table takes
        # the defaults: tests/test_routes.py), so a plain recipe is checked without loading a kernel
        problems += scen.route_problems(CheckValues(values, points, variables), {"method": method, "rtol": rtol},
                                        variables)
    title = data.get("title", f"stressfields {name}")
    if not isinstance(title, str):
        problems.append(f"title = {show(title)} must be a string")
    split_spec = {}
    if "splits" in data and not problems:
        from .splits import problems as split_problems

        found, split_spec = split_problems(data["splits"], scen, values, variables, physical)
        problems += found
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
    if split_spec:                  # likewise: recipes without [splits] keep their hash
        canonical_dict["splits"] = split_spec
    if points:                      # likewise; with the file (name, SHA-256) or the sample's spec
        canonical_dict["points"] = {"columns": sorted(points), "n": len(values[points[0]]),
                                    "sha256": points_digest({k: values[k] for k in points}), **source}
    canonical = json.dumps(canonical_dict, sort_keys=True, separators=(",", ":"))
    return Recipe(scen, values, swept, physical, variables, chunks, method, rtol, title,
                  text if text is not None else canonical, canonical, dict(plot), storage, points, split_spec)


def points_digest(columns: Mapping[str, np.ndarray]) -> str:
    """SHA-256 of the [points] columns (each name, then its values little-endian, names in sorted
    order): what the canonical recipe records of them.  Not the values themselves: 1e7 points would
    make an attribute of hundreds of MB; the file holds them as coordinates along `point`."""
    h = hashlib.sha256()
    for name in sorted(columns):
        values = np.asarray(columns[name])
        h.update(name.encode() + b"\0" + values.astype(values.dtype.newbyteorder("<"), copy=False).tobytes())
    return h.hexdigest()


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


class CheckValues(dict):
    """The values a scenario's ``check`` receives: the recipe's values, ``points``, the names
    that are [points] columns: 1-D arrays that vary together (one value per point, compared
    element-wise), where a swept array is an axis of its own (every combination is computed), and
    ``variables``, the names the recipe's output.variables lists (empty when it lists none)."""

    def __init__(self, values: Mapping, points: tuple[str, ...] = (), variables: tuple[str, ...] = ()):
        super().__init__(values)
        self.points = tuple(points)
        self.variables = tuple(variables)


def _points_table(data: dict, declared: dict, params: dict, scen: Scenario, base: Path | None,
                  problems: list[str], physical: bool = False, allow_read=()) -> tuple[dict, dict]:
    """The [points] columns as given ({} if none) and their source for the canonical recipe: {} for
    inline columns, {"file", "file_sha256"} for a file, {"sample": spec} for a sample (drawn later,
    once its size has passed the bounds; the columns are then {})."""
    if "points" not in data:
        return {}, {}
    table = data["points"]
    if hasattr(table, "data_vars"):             # an xarray.Dataset (itself a Mapping)
        return _dataset_columns(table, declared, problems), {}
    if hasattr(table, "columns") and hasattr(table, "to_numpy"):   # a pandas.DataFrame, not imported
        return _frame_columns(table, problems), {}
    if not isinstance(table, Mapping):
        problems.append(f"'points' must be a table of columns like {{ x = [0.1, 0.5], z = [0.2, 0.0] }}, "
                        f"got {show(table)}")
        return {}, {}
    if not table:
        problems.append("[points] has no column; give at least one, e.g. x = [0.1, 0.5]")
        return {}, {}
    for key in ("file", "sample"):
        if key in table:
            others = [k for k in table if k != key]
            if others:      # one source per table: a file's or a sample's rows cannot be told apart
                problems.append(f"points.{key}: [points] takes one source of points, inline columns, a file or a "
                                f"sample; it also has {', '.join(map(show, others))}: put every column in one of them")
                return {}, {}
            if key == "file":
                columns, source = read_points_file(table["file"], base, problems, allow_read)
                columns = _parameter_columns(columns, scen)
                return _converted(columns, declared, physical, _said(problems, source)), source
            spec = _sample_spec(table["sample"], declared, params, scen, problems)
            return {}, ({"sample": spec} if spec else {})
    return dict(table), {}


def _parameter_columns(columns, scen) -> list:
    """The columns of a points file that can be parameters, named as the scenario names them: a file
    `compare` reads serves as a points file too (FE header forms such as ``X(mm)`` or ``Node Label``
    read by `units.canonical`), its node ids, quadrature weights, body and value columns left
    out. Any other name stays, for the recipe checker to refuse."""
    from dataclasses import replace

    declared = {p.name for p in scen.parameters}
    fields = {v.name for v in scen.variables}
    kept = []
    for col in columns:
        name = col.name if col.name in declared else canonical(col.name)[0]
        if name in NOT_PARAMETERS or (name in fields and name not in declared):
            continue
        kept.append(replace(col, name=name) if name in declared else col)
    return kept


def _converted(columns, declared: dict, physical: bool, problems) -> dict:
    """A points file's columns by name, each in its parameter's unit for the recipe's mode: a unit
    the file gives (``x[mm]``, a NetCDF ``units`` attribute) is converted by `units.UNITS`, or refused."""
    out = {}
    for col in columns:
        par = declared.get(col.name)
        if par is None or col.unit is None:
            out[col.name] = col.values
            continue
        target = par.units_in(physical)
        f = unit_factor(col.unit, target)
        if f is None:
            problems.append(f"column {col.name!r}: unit {show_unit(col.unit)} cannot be converted to {col.name}'s unit "
                            f"in the recipe's {'physical' if physical else 'normalised'} mode ({target!r}); allowed: "
                            f"{', '.join(allowed_units(target))}")
            continue
        out[col.name] = col.values if f == 1.0 else np.asarray(col.values, dtype=np.float64) * f
    return out


class _Named:
    """A problems list whose messages are prefixed by the points file the columns came from."""

    def __init__(self, problems: list[str], prefix: str):
        self.problems, self.prefix = problems, prefix

    def append(self, message: str) -> None:
        self.problems.append(self.prefix + message)


def _said(problems: list[str], source: dict):
    return _Named(problems, f"points.file = {file_label(source['file'])}: ") if "file" in source else problems


def _frame_columns(frame, problems: list[str]) -> dict:
    """A DataFrame's columns (duck-typed: pandas is not a dependency); its index is not a column."""
    names = list(frame.columns)
    bad = [c for c in names if not isinstance(c, str)]
    twice = [c for c in names if names.count(c) > 1]
    if bad or twice:
        problems.append(f"points: a DataFrame of points needs one column per parameter, named by a string; got "
                        f"{show(bad[0]) + ' (not a string)' if bad else show(twice[0]) + ' twice'}")
        return {}
    if not names:
        problems.append("[points] has no column; the DataFrame has none")
    return {c: np.asarray(frame[c].to_numpy()) for c in names}


def _dataset_columns(ds, declared: dict, problems: list[str]) -> dict:
    """A Dataset's data variables and coordinates along its one dimension (its index coordinate only
    if it names a parameter: otherwise it merely numbers the points)."""
    if len(ds.sizes) != 1:
        problems.append(f"points: a Dataset of points has one dimension (one entry per point); this one has "
                        f"{show(dict(ds.sizes))}")
        return {}
    dim = next(iter(ds.sizes))
    out = {}
    for name, var in {**ds.coords, **ds.data_vars}.items():
        if var.ndim == 0 and name in ds.coords:
            continue                            # a scalar coordinate (left by .sel) locates nothing per point
        if name == dim and name not in declared:
            continue
        out[str(name)] = np.asarray(var.values) if var.ndim == 1 else var.values
    if not out:
        problems.append(f"[points] has no column; the Dataset has no variable along {show(dim)}")
    return out




# -- points.sample -------------------------------------------------------------------------------

def _sample_spec(raw, declared: dict, params: dict, scen: Scenario, problems: list[str]) -> dict | None:
    """The checked sample specification {method, n, seed, ranges}, or None (problems said).

    A key of the table is n, method or seed, or a parameter with its [low, high] range (a list: so the
    graded profile exponent `n` is a range when given as one, the count when an integer)."""
    example = '{ n = 1000, method = "sobol", seed = 1, mu = [0.0, 1.0] }'
    if not isinstance(raw, Mapping):
        problems.append(f"points.sample = {show(raw)} must be a table like {example}")
        return None
    before = len(problems)
    n = raw.get("n")
    if isinstance(n, list):
        n = None
    if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= MAX_SWEEP:
        problems.append(f"points.sample.n = {show(n)} must be an integer in [1, {MAX_SWEEP:,}] (the number of "
                        "points)")
    method = raw.get("method", "sobol")
    if method not in SAMPLE_METHODS:
        problems.append(f"points.sample.method = {show(method)} must be one of "
                        f"{', '.join(map(repr, SAMPLE_METHODS))}")
    seed = raw.get("seed")
    if "seed" not in raw:
        problems.append("points.sample.seed is missing: give an integer >= 0; the seed makes the sample "
                        "reproducible (the same recipe, the same points)")
    elif isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        problems.append(f"points.sample.seed = {show(seed)} must be an integer >= 0")
    ranges = {}
    columns = [p for p in declared if declared[p].per_point and declared[p].kind != "int"]
    for key, value in raw.items():
        if key in SAMPLE_KEYS and not isinstance(value, list):
            continue
        if key not in declared:
            problems.append(f"points.sample: unknown parameter {show(key)} for scenario '{scen.name}'"
                            f"{_hint(scen, key)}; give n, method, seed and [low, high] ranges of: {', '.join(columns)}")
        elif key in params:
            problems.append(f"points.sample.{key}: '{key}' is also given in [parameters]; give it in one place")
        elif key not in columns:
            par = declared[key]
            what = ("a choice" if par.choices else "an array" if par.kind == ARRAY else "an integer"
                    if par.kind == "int" else "a single-value")
            problems.append(f"points.sample.{key}: '{key}' cannot be sampled ({what} parameter); give it in "
                            "[parameters]")
        elif (bounds := _sample_range(declared[key], value, problems)) is not None:
            ranges[key] = bounds
    if len(problems) == before and not ranges:
        problems.append(f"points.sample names no parameter range; give [low, high] of one or more of: "
                        f"{', '.join(columns)}")
    if len(problems) > before:
        return None
    return {"method": method, "n": n, "seed": seed, "ranges": dict(sorted(ranges.items()))}


def _sample_range(par: Parameter, value, problems: list[str]) -> list[float] | None:
    key = par.name
    if not (isinstance(value, list) and len(value) == 2 and all(
            isinstance(v, (int, float)) and not isinstance(v, bool) for v in value) and value[0] <= value[1]):
        problems.append(f"points.sample.{key} = {show(value)} must be [low, high], two numbers, low <= high")
        return None
    for v in value:         # both ends within the parameter's range: every point drawn is then valid
        why = par.check(v)
        if why:
            problems.append(f"points.sample.{key} = {show(value)}: {show(v)} {why}")
            return None
    return [float(v) for v in value]


def draw_sample(spec: dict) -> dict[str, np.ndarray]:
    """The columns of a checked sample specification: bit-identical for the same spec (and NumPy/SciPy).

    Dimensions in alphabetical order of the parameters (the order of the canonical spec), so that
    the order of the keys in the recipe does not change the points.
    """
    names, n, seed = list(spec["ranges"]), spec["n"], spec["seed"]
    rng = np.random.default_rng(seed)
    if spec["method"] == "uniform":
        unit = rng.random((n, len(names)))
    else:
        from scipy.stats import qmc            # scipy.stats takes ~0.3 s to import: only for a sample

        # seed=: the keyword every supported SciPy (>= 1.11) takes; 1.15 added rng= as its new name

        if spec["method"] == "lhs":
            unit = qmc.LatinHypercube(len(names), seed=rng).random(n)
        else:
            # random(n) is the first n points of random_base2(ceil(log2 n)) (tested), without
            # drawing up to twice as many: scipy's warning that n is not a power of 2 (balance
            # properties) is silenced, not the sequence changed
            with warnings.catch_warnings():
                warnings.filterwarnings("ignore", message=".*balance properties.*", category=UserWarning)
                unit = qmc.Sobol(len(names), scramble=True, seed=rng).random(n)
    low = np.array([spec["ranges"][k][0] for k in names])
    high = np.array([spec["ranges"][k][1] for k in names])
    # low + u (high - low) may round one ulp beyond high: clipped, so that every point is in the box
    values = np.clip(low + unit * (high - low), low, high)
    return {k: np.ascontiguousarray(values[:, i]) for i, k in enumerate(names)}


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
                            f"allowed: {', '.join(p for p in declared if declared[p].per_point)}")
        elif key in params:
            problems.append(f"points.{key}: '{key}' is also given in [parameters]; give it in one place")
        elif not declared[key].per_point:
            par = declared[key]
            what = "a choice" if par.choices else "an array" if par.kind == ARRAY else "a single-value"
            problems.append(f"points.{key}: '{key}' cannot be a points column ({what} parameter); "
                            "give it in [parameters]")
        elif (column := _parse_column(declared[key], raw, problems)) is not None:
            columns[key] = column
    return columns



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


def _variables(scen: Scenario, requested, physical: bool, problems: list[str],
               given: Collection[str] = ()) -> tuple[str, ...]:
    # every variable of the mode may be requested, except one named like a parameter of the recipe
    # (``given``: its value is a coordinate); the always-on ones (flags) also join by themselves, so
    # the default list leaves them out (and recipes without output.variables keep their hash)
    available = [v.name for v in scen.available(physical, given)]
    if requested is None:
        return scen.defaults(physical, given)
    if not isinstance(requested, list) or not requested or not all(isinstance(v, str) for v in requested):
        problems.append(f"output.variables = {show(requested)} must be a non-empty list of names; "
                        f"available: {', '.join(available)}")
        return ()
    for v in requested:
        if v in given and v in [w.name for w in scen.variables]:
            problems.append(f"output.variables: {show(v)} is a parameter of this recipe (a coordinate of the "
                            f"dataset), not computed; available: {', '.join(available)}")
        elif v not in available:
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
    kind = plot_kind(plot, swept)
    if kind not in PLOT_KINDS:
        return [f"plot.kind = {show(kind)} must be one of {', '.join(map(repr, PLOT_KINDS))}"]
    plane = map_plane(swept)
    if kind == "map" and plane is None:
        problems.append(f"plot.kind = 'map' needs x and y swept (or x and z); swept: {', '.join(swept)}")
    across = plane[0] if plane else "x"
    x = plot.get("x", across if kind == "map" else swept[-1])
    if kind == "map" and x != across:
        problems.append(f"plot.x = {show(x)}: a map is drawn over {across} and {plane[1] if plane else 'y'}; "
                        "leave plot.x out")
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
    need = set(plane) if kind == "map" else {along}
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


#: the sections below the surface: x-z (a plane through the axis, signed x), rho-z (the radius r/a
#: of an axisymmetric field, the graded scenarios)
SECTIONS = (("x", "z"), ("rho", "z"))


def map_plane(swept) -> tuple[str, str] | None:
    """The plane of a map: x-y where both are swept, else a section (x-z, rho-z) below the surface."""
    for plane in (("x", "y"),) + SECTIONS:
        if set(plane) <= set(swept):
            return plane
    return None


def plot_kind(spec: dict, swept) -> str:
    """plot.kind, else "map" over x and y, or over x and z unless the table asks for a line (an x or
    a hue), else "line"."""
    if "kind" in spec:
        return spec["kind"]
    plane = map_plane(swept)
    if plane == ("x", "y") or (plane in SECTIONS and not {"x", "hue"} & set(spec)):
        return "map"
    return "line"


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
