"""Train/valid/test splits declared in a recipe's ``[splits]`` table, checked with it and hashed with it.

::

    [splits]
    seed = 1                                        # required when a split draws a fraction
    valid = { fraction = 0.1 }                      # random: a seeded draw of the points left
    test = { parameter = { nu = [0.4, 0.5] } }      # parameter extrapolation: low <= nu <= high
    # or test = { region = "contact_edge", width = 0.1 }   # a band around the contact edge ring
    #    (region: "contact_edge", "stick_edge" or "tip"; width in the unit of x)

``train`` is every point in no other split. The held-out splits (parameter, region) are taken first,
then the random fractions are drawn from what is left (a fraction of all points, by a permutation
seeded by ``seed``), so the three never share a point. A region is the set of points within
``width`` of the contact edge ring (r = a, z = 0), of the stick edge ring (r = c), or of the tip
(r = 0, z = 0): the distance sqrt((r - edge)^2 + z^2), r = sqrt(x^2 + y^2).

This module checks specifications (`problems`, called by recipe.py for every recipe) and assigns
points (`assign`, called by the ML exports on the values of a written file); it imports NumPy only.
"""
from __future__ import annotations

from typing import Any, Mapping

import numpy as np

NAMES = ("valid", "test")
KINDS = ("fraction", "parameter", "region")
REGIONS = ("contact_edge", "stick_edge", "tip")
#: the codes of the split of each point, in the order train, valid, test
CODES = {"train": 0, "valid": 1, "test": 2}
#: a region needs the variable that places its edge (in normalised mode the contact edge is r = 1)
EDGE_VARIABLE = {"contact_edge": "contact_radius", "stick_edge": "stick_radius"}


def problems(raw, scenario, values: Mapping[str, Any], variables, physical: bool) -> tuple[list[str], dict]:
    """Why the ``[splits]`` table ``raw`` is refused (one message per problem, naming the key, the value
    and what is allowed), and its canonical form ({} when refused)."""
    found: list[str] = []
    if not isinstance(raw, Mapping):
        return [f"'splits' must be a table like {{ seed = 1, valid = {{ fraction = 0.1 }} }}, got {raw!r}"], {}
    declared = {p.name: p for p in scenario.parameters}
    canonical: dict[str, Any] = {}
    for key in raw:
        if key not in (*NAMES, "seed"):
            found.append(f"unknown key 'splits.{key}'; allowed: seed, {', '.join(NAMES)} (train is every point "
                         "in no other split)")
    seed = raw.get("seed")
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int) or seed < 0):
        found.append(f"splits.seed = {seed!r} must be an integer >= 0")
    fractions = 0.0
    for name in NAMES:
        if name not in raw:
            continue
        spec = raw[name]
        where = f"splits.{name}"
        kinds = [k for k in KINDS if isinstance(spec, Mapping) and k in spec]
        if not isinstance(spec, Mapping) or len(kinds) != 1:
            found.append(f"{where} = {spec!r} must be a table with one of {', '.join(KINDS)}, e.g. "
                         "{ fraction = 0.1 } or { parameter = { nu = [0.4, 0.5] } }")
            continue
        kind = kinds[0]
        extra = set(spec) - {kind} - ({"width"} if kind == "region" else set())
        if extra:
            found.append(f"{where}: unknown key(s) {', '.join(sorted(extra))} beside {kind!r}")
            continue
        if kind == "fraction":
            f = spec["fraction"]
            if isinstance(f, bool) or not isinstance(f, (int, float)) or not 0 < f < 1:
                found.append(f"{where}.fraction = {f!r} must be a number in (0, 1)")
                continue
            fractions += f
            if seed is None:
                found.append(f"{where}.fraction needs splits.seed (an integer >= 0): the same recipe must draw "
                             "the same split")
            canonical[name] = {"fraction": float(f)}
        elif kind == "parameter":
            table = spec["parameter"]
            parsed = _parameter_ranges(where, table, declared, values, found)
            if parsed:
                canonical[name] = {"parameter": parsed}
        else:
            region, width = spec["region"], spec.get("width")
            if region not in REGIONS:
                found.append(f"{where}.region = {region!r} must be one of {', '.join(map(repr, REGIONS))}")
            elif not {"x", "y"} <= set(declared):
                found.append(f"{where}.region: scenario '{scenario.name}' has no surface coordinates x, y to place "
                             "a region by")
            elif isinstance(width, bool) or not isinstance(width, (int, float)) or not 0 < width < float("inf"):
                found.append(f"{where}.width = {width!r} must be a positive number (in the unit of x)")
            elif region in EDGE_VARIABLE and (physical or region == "stick_edge") and \
                    EDGE_VARIABLE[region] not in variables:
                found.append(f"{where}.region = {region!r} needs {EDGE_VARIABLE[region]!r} in output.variables "
                             "(it places the edge)")
            else:
                canonical[name] = {"region": region, "width": float(width)}
    if fractions >= 1:
        found.append(f"splits: the fractions add up to {fractions:g}; the train split would be empty (they must "
                     "add up to less than 1)")
    held = {n: s["parameter"] for n, s in canonical.items() if "parameter" in s}
    if len(held) == 2:
        for par in set(held["valid"]) & set(held["test"]):
            (l1, h1), (l2, h2) = held["valid"][par], held["test"][par]
            if max(l1, l2) <= min(h1, h2):
                found.append(f"splits.valid and splits.test overlap: both hold out {par} in "
                             f"[{max(l1, l2)!r}, {min(h1, h2)!r}]; a point belongs to one split")
    if not found:
        found += _empty_train(canonical, values)
    if found:
        return found, {}
    if seed is not None:
        canonical["seed"] = seed
    return [], canonical


def _parameter_ranges(where, table, declared, values, found) -> dict:
    if not isinstance(table, Mapping) or not table:
        found.append(f"{where}.parameter = {table!r} must be a table of [low, high] ranges, e.g. "
                     "{ nu = [0.4, 0.5] }")
        return {}
    out = {}
    for par, bounds in table.items():
        if par not in declared:
            found.append(f"{where}.parameter: unknown parameter {par!r}; one of: {', '.join(declared)}")
        elif not (isinstance(bounds, list) and len(bounds) == 2 and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) and np.isfinite(v) for v in bounds)
                and bounds[0] <= bounds[1]):
            found.append(f"{where}.parameter.{par} = {bounds!r} must be [low, high], two finite numbers, low <= high")
        elif par not in values or (values[par] is not None and np.asarray(values[par]).dtype.kind not in "iuf"):
            found.append(f"{where}.parameter.{par}: {par!r} is not a number of this recipe (give it in "
                         "[parameters] or [points])")
        else:
            out[par] = [float(bounds[0]), float(bounds[1])]
    return out


def _empty_train(canonical: dict, values: Mapping) -> list[str]:
    """A parameter hold-out that takes every value of its parameter (a fixed one inside the range, or
    every value of a sweep or column) leaves no train point."""
    for name, spec in canonical.items():
        for par, (low, high) in spec.get("parameter", {}).items():
            v = np.asarray(values[par], dtype=float)
            inside = (v >= low) & (v <= high)
            if inside.all():
                return [f"splits.{name}.parameter.{par} = [{low!r}, {high!r}] holds out every value of {par} "
                        f"({_few(v)}); the train split would be empty"]
    return []


def _few(v: np.ndarray) -> str:
    v = np.atleast_1d(v)
    return ", ".join(f"{x:g}" for x in v[:5]) + (", ..." if v.size > 5 else "")


def assign(spec: Mapping, columns: Mapping[str, np.ndarray], n: int) -> np.ndarray:
    """The split code (CODES) of each of ``n`` points, given the spec's canonical form and the
    points' ``columns`` (1-D arrays of length n: coordinates, parameters, and the edge variables
    ``contact_radius``/``stick_radius`` where a region needs them; fixed values broadcast).
    Raises ValueError (one line) when a split comes out empty of train points or two overlap."""
    code = np.zeros(n, dtype=np.int8)
    held = np.zeros(n, dtype=bool)
    for name in NAMES:
        s = spec.get(name, {})
        if "fraction" in s:
            continue
        mask = _parameter_mask(s["parameter"], columns, n) if "parameter" in s else \
            _region_mask(s, columns, n) if "region" in s else None
        if mask is None:
            continue
        if (mask & held).any():
            raise ValueError(f"splits.valid and splits.test overlap at {int((mask & held).sum()):,} points; "
                             "a point belongs to one split")
        code[mask] = CODES[name]
        held |= mask
    free = np.flatnonzero(~held)
    randoms = [(name, spec[name]["fraction"]) for name in NAMES if "fraction" in spec.get(name, {})]
    if randoms:
        order = free[np.random.default_rng(spec["seed"]).permutation(free.size)]
        start = 0
        for name, fraction in randoms:
            count = int(round(fraction * n))
            code[order[start:start + count]] = CODES[name]
            start += count
    if not (code == 0).any():
        raise ValueError("splits: no point is left for train; hold out less")
    return code


def _parameter_mask(ranges: Mapping, columns: Mapping, n: int) -> np.ndarray:
    mask = np.ones(n, dtype=bool)
    for par, (low, high) in ranges.items():
        v = np.broadcast_to(np.asarray(columns[par], dtype=float), (n,))
        mask &= (v >= low) & (v <= high)
    return mask


def _region_mask(spec: Mapping, columns: Mapping, n: int) -> np.ndarray:
    def col(name, default=0.0):
        return np.broadcast_to(np.asarray(columns.get(name, default), dtype=float), (n,))
    r = np.hypot(col("x"), col("y"))
    z = col("z")
    region = spec["region"]
    edge = 0.0 if region == "tip" else col(EDGE_VARIABLE[region], 1.0)
    return np.hypot(r - edge, z) <= spec["width"]
