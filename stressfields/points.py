"""The [points] table of a recipe: columns of equal length that vary together along the dimension
`POINT` (after the swept ones), given inline, read from a file (`pointfiles`: the read policy and
the readers), or drawn as a seeded sample (`draw_sample`). Each column is checked against its
parameter's declaration, every problem reported at once; `recipe.load` calls `points_table`,
`points_size` (bounded before anything is parsed or drawn) and `parse_points`.
"""
from __future__ import annotations

import difflib
import hashlib
import warnings
from pathlib import Path
from typing import Mapping

import numpy as np

from .errors import show
from .pointfiles import MAX_SWEEP, file_label, read_points_file
from .scenarios.base import ARRAY, Parameter, Scenario
from .units import NOT_PARAMETERS, allowed as allowed_units, canonical, factor as unit_factor, show_unit

#: the dimension along which the [points] columns vary together (last, after the swept ones)
POINT = "point"
SAMPLE_METHODS = ("sobol", "lhs", "uniform")
#: the keys of points.sample that are not parameter ranges
SAMPLE_KEYS = ("n", "method", "seed")


def points_digest(columns: Mapping[str, np.ndarray]) -> str:
    """SHA-256 of the [points] columns (each name, then its values little-endian, names in sorted
    order): what the canonical recipe records of them.  Not the values themselves: 1e7 points would
    make an attribute of hundreds of MB; the file holds them as coordinates along `point`."""
    h = hashlib.sha256()
    for name in sorted(columns):
        values = np.asarray(columns[name])
        h.update(name.encode() + b"\0" + values.astype(values.dtype.newbyteorder("<"), copy=False).tobytes())
    return h.hexdigest()


def name_hint(scen: Scenario, key) -> str:
    """' (renamed: ...)' or ' (did you mean ...?)' for an unknown parameter, else ''."""
    if not isinstance(key, str):
        return ""
    if key in scen.renamed:
        return f" (renamed: it is now {scen.renamed[key]!r})"
    close = difflib.get_close_matches(key, [p.name for p in scen.parameters], n=1, cutoff=0.8)
    return f" (did you mean {close[0]!r}?)" if close else ""


def points_table(data: dict, declared: dict, params: dict, scen: Scenario, base: Path | None,
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
                return _converted(columns, declared, physical, said(problems, source)), source
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


def said(problems: list[str], source: dict):
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
                            f"{name_hint(scen, key)}; give n, method, seed and [low, high] ranges of: "
                            f"{', '.join(columns)}")
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


def points_size(table: dict, problems: list[str]) -> int | None:
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


def parse_points(table: dict, declared: dict, params: dict, scen: Scenario,
                  problems: list[str]) -> dict[str, np.ndarray]:
    """The [points] columns as 1-D arrays, each value checked against its parameter's range.

    Unlike a sweep, a column may repeat values and go both ways: it is not a dimension coordinate.
    """
    columns = {}
    for key, raw in table.items():
        if key not in declared:
            problems.append(f"points: unknown parameter {show(key)} for scenario '{scen.name}'"
                            f"{name_hint(scen, key)}; "
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
