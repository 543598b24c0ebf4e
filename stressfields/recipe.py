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

import hashlib
import json
import math
import os
import re
import stat
import sys
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Collection, Mapping

import numpy as np

from . import plotkeys
from .errors import RecipeError, name_problem, show
from .output.options import output_option_problems
from .pointfiles import MAX_SWEEP
from .points import POINT, draw_sample, name_hint, parse_points, points_digest, points_size, points_table, said
from .scenarios import REGISTRY
from .scenarios.base import ARRAY, Parameter, Scenario

TOP_KEYS = ("scenario", "title", "parameters", "points", "output", "method", "plot", "splits", "compare")
OUTPUT_KEYS = ("variables", "chunks", "dtype", "compression", "nonfinite")
METHOD_KEYS = ("method", "rtol")
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
    #: how values are stored ([output] dtype, compression, nonfinite; see output.options.OutputOptions)
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
                                  (plot, plotkeys.PLOT_KEYS, "plot")):
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
    points_raw, source = points_table(data, declared, params, scen, base, problems, physical, allow_read)
    # from the lengths (or the sample's n), before any parsing or drawing
    n_points = source["sample"]["n"] if "sample" in source else points_size(points_raw, said(problems, source))
    rejected = _sweep_sizes(params, declared, problems, n_points)   # before any sweep is expanded
    if "sample" in source and POINT not in rejected:
        points_raw = draw_sample(source["sample"])
    columns = {} if n_points is None or POINT in rejected else parse_points(
        points_raw, declared, params, scen, said(problems, source))
    # a refused column is already reported: not "missing" as well
    rejected |= {k for k in points_raw if k not in columns and k not in params}
    if "points" in data and not columns:    # a refused file or sample: its columns are not "missing" too
        rejected |= {k for k, par in declared.items() if par.per_point and k not in params}
    for key, raw in params.items():
        if key in rejected:
            continue
        if key not in declared:
            problems.append(f"unknown parameter {show(key)} for scenario '{name}'{name_hint(scen, key)}; allowed: "
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
        problems += plotkeys.check(scen, plot, swept, variables, physical)
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


def _jsonable(value):
    if isinstance(value, np.ndarray):
        return [v if isinstance(v, str) else (int(v) if isinstance(v, np.integer) else float(v))
                for v in value.tolist()]
    if isinstance(value, tuple):
        return list(value)
    if isinstance(value, np.generic):
        return value.item()
    return value
