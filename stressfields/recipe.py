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

Every error names the key, the value and what is allowed; all errors are reported at once.
"""
from __future__ import annotations

import hashlib
import json
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from .scenarios import REGISTRY
from .scenarios.base import ARRAY, Parameter, Scenario

TOP_KEYS = ("scenario", "title", "parameters", "output", "method", "plot")
OUTPUT_KEYS = ("variables", "chunks")
METHOD_KEYS = ("method", "rtol")
PLOT_KEYS = ("x", "variables", "hue", "kind", "ylim", "marker")
RTOL_RANGE = (1e-14, 1e-2)
MAX_SWEEP = 100_000_000


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

    @property
    def sha256(self) -> str:
        return hashlib.sha256(self.canonical.encode()).hexdigest()

    @property
    def shape(self) -> dict[str, int]:
        return {name: len(self.values[name]) for name in self.swept}

    @property
    def size(self) -> int:
        return int(np.prod(list(self.shape.values()), dtype=np.int64)) if self.swept else 1


def load(source: str | Path | Mapping) -> Recipe:
    """Parse and validate a recipe from a TOML path, TOML text or a dict."""
    if isinstance(source, Mapping):
        data, text, label = dict(source), None, "recipe"
    else:
        path = Path(source)
        label = str(path)
        try:
            text = path.read_text()
        except OSError as exc:
            raise RecipeError([f"cannot read the recipe file: {exc.strerror}"], label) from None
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise RecipeError([f"not valid TOML: {exc}"], label) from None
    return _validate(data, text, label)


def _validate(data: dict, text: str | None, label: str) -> Recipe:
    problems: list[str] = []
    for key in data:
        if key not in TOP_KEYS:
            problems.append(f"unknown key '{key}'; allowed top-level keys: {', '.join(TOP_KEYS)}")
    name = data.get("scenario")
    if name is None:
        raise RecipeError(problems + [f"missing key 'scenario'; one of: {', '.join(REGISTRY)}"], label)
    if name not in REGISTRY:
        raise RecipeError(problems + [f"scenario = {name!r} is unknown; one of: {', '.join(REGISTRY)}"], label)
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
    rejected: set[str] = set()
    for key, raw in params.items():
        if key not in declared:
            problems.append(f"unknown parameter '{key}' for scenario '{name}'; allowed: {', '.join(declared)}")
            continue
        value = _parse_value(declared[key], raw, problems)
        if value is None:
            rejected.add(key)   # already reported: not "missing" as well
        else:
            values[key] = value
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
            if key in params:
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

    swept = tuple(p.name for p in scen.parameters if isinstance(values.get(p.name), np.ndarray))
    variables = _variables(scen, output.get("variables"), physical, problems)
    chunks = _chunks(output.get("chunks", {}), swept, problems)
    method, rtol = _method(scen, method_t, problems)
    title = data.get("title", f"stressfields {name}")
    if not isinstance(title, str):
        problems.append(f"title = {title!r} must be a string")
    size = int(np.prod([len(values[s]) for s in swept], dtype=np.int64)) if swept else 1
    if size > MAX_SWEEP * 100:
        problems.append(f"the sweep has {size:.3g} points; at most {MAX_SWEEP * 100:.0e} are allowed")
    if problems:
        raise RecipeError(problems, label)

    canonical_dict = {
        "scenario": name,
        "parameters": {k: _jsonable(values[k]) for k in sorted(values)},
        "output": {"variables": list(variables), "chunks": dict(sorted(chunks.items()))},
        "method": {"method": method, "rtol": rtol},
    }
    canonical = json.dumps(canonical_dict, sort_keys=True, separators=(",", ":"))
    return Recipe(scen, values, swept, physical, variables, chunks, method, rtol, title,
                  text if text is not None else canonical, canonical, dict(plot))


def _table(data: dict, key: str, problems: list[str]) -> dict:
    table = data.get(key, {})
    if not isinstance(table, dict):
        problems.append(f"'{key}' must be a table, got {table!r}")
        return {}
    return table


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
            problems.append(f"{key} = {raw!r} must be {par.allowed()}")
            return None
        bad = [v for v in raw if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v)]
        if bad:
            problems.append(f"{key} contains {bad[0]!r}; it must be {par.allowed()}")
            return None
        return tuple(float(v) for v in raw)
    if isinstance(raw, (list, dict)):
        if not par.sweepable:
            problems.append(f"{key} = {raw!r} cannot be swept; give a single value ({par.allowed()})")
            return None
        items = _expand_sweep(key, raw, problems)
        if items is None:
            return None
        for v in items:
            why = par.check(v)
            if why:
                problems.append(f"{key} sweep value {v!r} {why}")
                return None
        if par.choices:
            if len(set(items)) != len(items):
                problems.append(f"{key} sweep {raw!r} repeats a value")
                return None
            return np.array(items, dtype=object)
        arr = np.asarray(items, dtype=np.int32 if par.kind == "int" else np.float64)  # CF-1.8: no int64
        if len(np.unique(arr)) != len(arr):
            problems.append(f"{key} sweep {raw!r} repeats a value; sweep values must be distinct")
            return None
        return arr
    why = par.check(raw)
    if why:
        problems.append(f"{key} = {raw!r} {why}")
        return None
    if par.choices:
        return raw
    return np.int32(raw) if par.kind == "int" else float(raw)


def _expand_sweep(key: str, raw, problems: list[str]):
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
        problems.append(f"{key} = {raw!r}: a sweep table needs start, stop, num (and optional log = true); {what}")
        return None
    start, stop, num, log = raw["start"], raw["stop"], raw["num"], raw.get("log", False)
    for k, v in (("start", start), ("stop", stop)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v):
            problems.append(f"{key}.{k} = {v!r} must be a finite number")
            return None
    if isinstance(num, bool) or not isinstance(num, int) or not 1 <= num <= MAX_SWEEP:
        problems.append(f"{key}.num = {num!r} must be an integer in [1, {MAX_SWEEP}]")
        return None
    if not isinstance(log, bool):
        problems.append(f"{key}.log = {log!r} must be true or false")
        return None
    if num > 1 and start == stop:
        problems.append(f"{key}: start = stop = {start!r} with num = {num} repeats a value")
        return None
    if log:
        if start <= 0 or stop <= 0:
            problems.append(f"{key}: a log sweep needs start > 0 and stop > 0, got {start!r}, {stop!r}")
            return None
        return list(np.geomspace(start, stop, num))
    return list(np.linspace(start, stop, num))


def _variables(scen: Scenario, requested, physical: bool, problems: list[str]) -> tuple[str, ...]:
    available = [v.name for v in scen.variables_in(physical) if not v.always]
    if requested is None:
        return tuple(scen.default_variables or available)
    if not isinstance(requested, list) or not requested or not all(isinstance(v, str) for v in requested):
        problems.append(f"output.variables = {requested!r} must be a non-empty list of names; "
                        f"available: {', '.join(available)}")
        return ()
    for v in requested:
        if v not in available:
            problems.append(f"output.variables: unknown variable {v!r} for scenario '{scen.name}'"
                            f"{' in this mode' if v in [w.name for w in scen.variables] else ''}; "
                            f"available: {', '.join(available)}")
    return tuple(dict.fromkeys(requested))


def _chunks(raw, swept: tuple[str, ...], problems: list[str]) -> dict[str, int]:
    if not isinstance(raw, dict):
        problems.append(f"output.chunks = {raw!r} must be a table like {{ x = 1000 }}")
        return {}
    out = {}
    for dim, size in raw.items():
        if dim not in swept:
            problems.append(f"output.chunks.{dim}: '{dim}' is not a swept dimension; "
                            f"swept: {', '.join(swept) or 'none'}")
        elif isinstance(size, bool) or not isinstance(size, int) or (size < 1 and size != -1):
            problems.append(f"output.chunks.{dim} = {size!r} must be a positive integer (or -1 for whole)")
        else:
            out[dim] = size
    return out


def _method(scen: Scenario, table: dict, problems: list[str]) -> tuple[str, float]:
    method = table.get("method", "auto")
    if method not in scen.methods:
        problems.append(f"method.method = {method!r} must be one of {', '.join(map(repr, scen.methods))}")
    rtol = table.get("rtol", 1e-10)
    if isinstance(rtol, bool) or not isinstance(rtol, (int, float)) or not (
            RTOL_RANGE[0] <= rtol <= RTOL_RANGE[1]):
        problems.append(f"method.rtol = {rtol!r} must be a number in [{RTOL_RANGE[0]:g}, {RTOL_RANGE[1]:g}]")
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
