"""Compare a user's nodal values (an FE model's, say) with the reference at exactly the same points.

    ds = sf.compare("recipe.toml", "nodes.csv", tolerance=1e-2)     # `stressfields compare` on the command line

(The module is not named `compare`: a submodule of that name would replace the function `sf.compare`
in the package's namespace when first imported.)

The user data is a CSV file whose header names the columns, a NetCDF file (one dimension; units
from the ``units`` attributes), an ``xr.Dataset`` of the same form, or a mapping of header -> values.
A column named like one of the scenario's parameters (``x``, ``y``, ``z``, ...) is a coordinate of
the nodes, a column named like a float variable (``sigma_xx``, ...) a value to compare. Units go in
brackets (``x[mm]``, ``sigma_xx[MPa]``); a column without them is in the scenario's declared unit
for the recipe's mode. Units are converted to the recipe's ("1" in normalised mode, SI in physical
mode) by the explicit table ``units.UNITS``, the one `[points]` files use; nothing is guessed. Files
are read by the readers of `[points]` files (`pointfiles`): their size, and the size their columns
decode to, are checked before anything is decoded, and no message quotes their content.

The reference is the recipe with the coordinate columns as its ``[points]`` table (the recipe's own
values of those parameters and its ``[points]`` are replaced), so it is evaluated at the nodes and
nowhere else, within the accuracy its fields state (``stressfields_accuracy``).

Each compared variable ``v`` gives ``v_reference``, ``v_user`` and ``v_difference`` (user -
reference) along ``point``, and global attributes ``compare_<v>_*``: the scale S (the variable's
normalisation scale: 1 in normalised mode, where values are already divided by it; in physical mode
the mean contact pressure p_m for stresses, p_m/a for dpdz, p* and Delta_1 for the wavy fields, read
from the reference; else the largest |reference| over the nodes), max |difference| / S and where it
is, the RMS difference and the relative L2 difference. Nodes where the reference is not finite
(a singular point: its ``validity`` says why) are left out of the statistics and counted.
"""
from __future__ import annotations

import json
import math
import os
import re
import shutil
import stat
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Mapping

import numpy as np
import xarray as xr

from . import cf
from .errors import OutputError, name_problem
from .pointfiles import MAX_POINTS_FILE_BYTES, Column, FileProblem, csv_columns, file_bytes, nc_columns
from .recipe import MAX_RECIPE_BYTES, POINT, RecipeError, load
from .scenarios import REGISTRY
from .scenarios.base import ARRAY, Scenario
from .units import LABEL_RULE, UNITS, allowed as allowed_units, factor as unit_factor, parse_label, show_unit

#: CSV files read: 200 MB holds ~1e7 nodes of a few columns (the most a recipe's [points] takes)
MAX_CSV_BYTES = 200_000_000
#: names of the identity column of an FE export: kept as a coordinate, never compared
ID_COLUMNS = ("node", "node_id", "id")


class CompareError(ValueError):
    """Bad user data or a recipe that cannot be compared; the message is one line."""


def compare(recipe: str | Path | Mapping, user_data: str | Path | xr.Dataset | Mapping, *,
            tolerance: float | None = None, variables: list[str] | tuple[str, ...] | None = None) -> xr.Dataset:
    """The user's values against the reference at the user's points (see the module docstring).

    Parameters
    ----------
    recipe : str, Path or Mapping
        The recipe of the reference; the coordinates the user's data give replace its sweep.
    user_data : str, Path, xarray.Dataset or Mapping
        A CSV or NetCDF file, a dataset along one dimension, or a mapping of header -> values.
    tolerance : float, optional
        The largest max |difference| / S a variable may have to pass (None: report only).
    variables : list of str, optional
        Compare only these value columns (default: every one).

    Returns
    -------
    xarray.Dataset
        ``<v>_reference``, ``<v>_user``, ``<v>_difference`` and ``<v>_scale`` at every point; the
        statistics and the verdict (``compare_result``) in its attributes.

    Raises
    ------
    CompareError
        In one line, for input that cannot be compared.
    """
    tolerance = _check_tolerance(tolerance)
    base, data = _recipe(recipe)
    columns, source = read_user_data(user_data)
    coords, values, ids = _classify(base.scenario, columns, base.physical, source)
    values = _select(values, variables, source)
    factors = {c.name: _factor(base.scenario, c, base.physical, source) for c in [*coords, *values]}
    scales = {c.name: _scale_spec(base.scenario.variable(c.name), base.physical) for c in values}
    derived = _derived_recipe(base, data, coords, factors, values, scales, source)
    ref = _reference(derived, base.label, source)
    ds = _assemble(base, ref, coords, values, factors, ids, scales, source)
    return _judge(ds, [c.name for c in values], tolerance)


def _check_tolerance(tolerance):
    if tolerance is None:
        return None
    if isinstance(tolerance, bool) or not isinstance(tolerance, (int, float)) or not (
            math.isfinite(tolerance) and tolerance > 0):
        raise CompareError(f"tolerance = {tolerance!r} must be a positive finite number (max |difference| / scale)")
    return float(tolerance)


@dataclass(frozen=True)
class _Base:
    """What the comparison needs of the recipe as given, before its coordinates come from the nodes."""
    scenario: Scenario
    physical: bool
    title: str
    text: str
    label: str


def _recipe(recipe) -> tuple[_Base, dict]:
    """The recipe's tables as given; it is checked whole once the nodes are its [points] (`_reference`),
    so that a recipe need not give the coordinates the nodes give (e.g. the required x)."""
    if isinstance(recipe, Mapping):
        data, text, label = dict(recipe), json.dumps(dict(recipe), default=str, sort_keys=True), "recipe"
    else:
        label = str(recipe)
        why = name_problem(label)
        if why is not None:
            raise CompareError(f"{ascii(label)}: cannot read the recipe ({why})")
        path = Path(recipe)
        try:
            if not stat.S_ISREG(os.stat(path).st_mode) or os.stat(path).st_size > MAX_RECIPE_BYTES:
                raise CompareError(f"{label}: not a regular file of at most {MAX_RECIPE_BYTES:,} bytes")
            text = path.read_text(encoding="utf-8")
            data = tomllib.loads(text)
        except OSError as exc:
            raise CompareError(f"{label}: cannot read the recipe ({exc.strerror})") from None
        except (UnicodeDecodeError, ValueError, RecursionError) as exc:
            try:        # the recipe checker says what is wrong in its own words
                load(path)
            except RecipeError as err:
                raise CompareError(f"{label}: " + "; ".join(err.problems)) from None
            raise CompareError(f"{label}: not a valid recipe ({exc})") from None
    name = data.get("scenario")
    if not isinstance(name, str) or name not in REGISTRY:
        raise CompareError(f"{label}: scenario = {name!r} is unknown; one of: {', '.join(REGISTRY)}")
    scen = REGISTRY[name]
    params = data.get("parameters") or {}
    physical = scen.physical_switch is None or (isinstance(params, Mapping) and scen.physical_switch in params)
    title = data.get("title") if isinstance(data.get("title"), str) else f"stressfields {name}"
    return _Base(scen, physical, title, text, label), data


# --- reading -------------------------------------------------------------------------------------

def read_user_data(user_data) -> tuple[list[Column], str]:
    """The columns of a CSV or NetCDF file, an xr.Dataset or a mapping, and a name for messages."""
    if isinstance(user_data, xr.Dataset):
        return _dataset_columns(user_data, "the user dataset"), "the user dataset"
    if isinstance(user_data, Mapping):
        return [_header_column(str(k), np.asarray(v), "the user data") for k, v in user_data.items()], "the user data"
    path = Path(user_data)
    source = str(path)
    why = name_problem(source)
    if why is not None:
        raise CompareError(f"{ascii(source)}: cannot read it ({why})")
    try:
        # a NetCDF file (classic or HDF5) by its first bytes; anything else is read as a CSV
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
        try:
            if not stat.S_ISREG(os.fstat(fd).st_mode):
                raise CompareError(f"{source}: not a regular file (give a CSV or NetCDF file)")
            netcdf = os.read(fd, 4).startswith((b"CDF", b"\x89HDF"))
        finally:
            os.close(fd)
    except OSError as exc:
        raise CompareError(f"{source}: cannot read it ({exc.strerror})") from None
    try:
        # resolved first: the reader follows no symbolic link, and the user may name one
        raw = file_bytes(Path(os.path.realpath(path)), source, MAX_POINTS_FILE_BYTES if netcdf else MAX_CSV_BYTES)
        columns = (nc_columns(raw, skip_scalars=True, drop_index=True, kept_index=ID_COLUMNS) if netcdf
                   else csv_columns(raw))
    except FileProblem as exc:
        raise CompareError(f"{source}: {exc}") from None
    return [Column(c.name, c.label, c.unit, _numbers(c.values, c.label, source)) for c in columns], source


def _header_column(header: str, values: np.ndarray, source: str) -> Column:
    parsed = parse_label(header)
    if parsed is None:
        raise CompareError(f"{source}: a column header is not {LABEL_RULE}, e.g. sigma_xx[MPa]")
    return Column(parsed[0], header.strip(), parsed[1], _numbers(values, header.strip(), source))


def _numbers(values, label: str, source: str) -> np.ndarray:
    arr = np.asarray(values)
    if arr.ndim != 1 or arr.dtype.kind not in "iuf":
        raise CompareError(f"{source}, column {label!r}: must be one column of numbers")
    return arr.astype(np.float64)


def _dataset_columns(ds: xr.Dataset, source: str) -> list[Column]:
    dims = sorted({d for v in ds.variables.values() if v.ndim for d in v.dims})
    if len(dims) != 1:
        raise CompareError(f"{source}: the nodes must lie along one dimension (e.g. point); it has "
                           f"{', '.join(dims) or 'none'}")
    dim = dims[0]
    out = []
    for name, var in ds.variables.items():
        if var.ndim == 0 or (name == dim and name not in ID_COLUMNS):
            continue            # scalars (metadata) and the dimension's own index
        out.append(Column(str(name), str(name), var.attrs.get("units"), _numbers(var.values, str(name), source)))
    return out


# --- what the columns are ------------------------------------------------------------------------

def _classify(scen: Scenario, columns: list[Column], physical: bool, source: str):
    """Coordinates (parameters), values (float variables of the mode) and the optional id column."""
    params = {p.name for p in scen.parameters}
    fields = {v.name: v for v in scen.variables_in(physical) if v.dtype.startswith("float") and not v.flag_values}
    seen: dict[str, str] = {}
    coords, values, ids = [], [], None
    for col in columns:
        if col.name in seen:
            raise CompareError(f"{source}: columns {seen[col.name]!r} and {col.label!r} name the same {col.name!r}")
        seen[col.name] = col.label
        if col.name in ID_COLUMNS:
            ids = col
        elif col.name in params:
            coords.append(col)
        elif col.name in fields:
            values.append(col)
        else:
            var = next((v for v in scen.variables if v.name == col.name), None)
            what = ("unknown" if var is None else "a flag, not a field" if var.flag_values
                    else "not a float field in this mode")
            raise CompareError(f"{source}: column {col.label!r} is {what} for scenario '{scen.name}' "
                               f"({'physical' if physical else 'normalised'} mode); coordinates: "
                               f"{', '.join(p.name for p in scen.parameters if p.per_point)}; fields: "
                               f"{', '.join(fields)}")
    if not coords:
        raise CompareError(f"{source}: no coordinate column (e.g. x, y, z of scenario '{scen.name}')")
    if not values:
        raise CompareError(f"{source}: no value column to compare (e.g. {', '.join(list(fields)[:3])})")
    everything = [*coords, *values] + ([ids] if ids else [])
    lengths = {c.label: c.values.size for c in everything}
    if len(set(lengths.values())) != 1 or not everything[0].values.size:
        raise CompareError(f"{source}: the columns must have one length of at least 1; "
                           + ", ".join(f"{k} has {n}" for k, n in lengths.items()))
    for col in everything:
        bad = np.flatnonzero(~np.isfinite(col.values))
        if bad.size:
            raise CompareError(f"{source}, column {col.label!r}: {col.values[bad[0]]} at data row {bad[0]} "
                               f"(from 0; {bad.size} such rows); every value must be a finite number")
    if ids is not None and not np.all((ids.values == np.round(ids.values)) & (np.abs(ids.values) < 2 ** 31)):
        raise CompareError(f"{source}, column {ids.label!r}: node identities must be 32-bit integers")
    return coords, values, ids



def _select(values: list[Column], names, source: str) -> list[Column]:
    if not names:
        return values
    given = {c.name: c for c in values}
    unknown = [n for n in names if n not in given]
    if unknown:
        raise CompareError(f"variables {', '.join(map(repr, unknown))}: not value columns of {source} "
                           f"(value columns: {', '.join(given)})")
    return [given[n] for n in dict.fromkeys(names)]


def _factor(scen: Scenario, col: Column, physical: bool, source: str) -> float:
    """The factor from the column's unit to the recipe's unit for it (UNITS; refused otherwise)."""
    decl = scen.parameter(col.name) if col.name in {p.name for p in scen.parameters} else scen.variable(col.name)
    target = decl.units_in(physical)
    f = unit_factor(col.unit, target)
    if f is not None:
        return f
    mode = "physical" if physical else "normalised"
    raise CompareError(f"{source}, column {col.label!r}: unit {show_unit(col.unit)} cannot be converted to "
                       f"{col.name}'s unit in the recipe's {mode} mode ({target!r}); allowed: "
                       f"{', '.join(allowed_units(target))}")


# --- the reference ---------------------------------------------------------------------------------

#: normalisation scale (the start of a Variable.scale text) -> how its value is had in physical mode:
#: variables of the reference to divide, or a function of the recipe values
_SCALES = (
    ("the mean contact pressure p_m", ("mean_pressure",), "mean_pressure"),
    ("p_m/a", ("mean_pressure", "contact_radius"), "mean_pressure / contact_radius"),
    ("the contact radius a", ("contact_radius",), "contact_radius"),
    ("p* =", (), "p* = pi E/(1-nu^2) Delta_1/lambda_1"),
    ("the amplitude Delta_1", (), "Delta_1"),
    ("the contact half-width a", (), "a lambda_1/2"),
)
FALLBACK_SCALE = "max |reference| over the compared points"


def _scale_spec(var, physical: bool) -> tuple[str, tuple[str, ...]]:
    """(definition, variables of the reference it needs); in normalised mode a normalised variable's
    values are already divided by its scale, so S = 1."""
    if var.scale and not physical:
        return "1 (values divided by " + var.scale + ")", ()
    for start, needs, text in _SCALES:
        if var.scale and var.scale.startswith(start):
            return text, needs
    return FALLBACK_SCALE, ()


def _derived_recipe(base, data: dict, coords, factors, values, scales, source: str) -> dict:
    """The recipe with the coordinate columns as [points]; every other sweep must be a single value."""
    names = {c.name for c in coords}
    params = {k: v for k, v in (data.get("parameters") or {}).items() if k not in names}
    scen = base.scenario
    declared = {p.name: p for p in scen.parameters}
    for key, value in params.items():
        if key in declared and declared[key].kind != ARRAY and isinstance(value, (list, dict)):
            raise CompareError(f"the recipe sweeps {key!r} ({_count(value)} values) but {source} has no "
                               f"{key!r} column: give {key!r} as a column, or one value in the recipe")
    # the nodes replace [points] whole (a file or sample source too); a column they do not give is refused
    left = [k for k in (data.get("points") or {}) if k in declared and k not in names]
    if left:
        raise CompareError(f"the recipe's [points] has {', '.join(map(repr, left))}, which {source} does not "
                           "give: add the column(s), or give one value in [parameters]")
    needed = [c.name for c in values]
    available = {v.name for v in scen.variables_in(base.physical)}
    needed += [n for _, needs in scales.values() for n in needs if n in available and n not in needed]
    out = {"scenario": scen.name, "parameters": params,
           "points": {c.name: c.values * factors[c.name] for c in coords},
           "output": {"variables": list(dict.fromkeys(needed))}}
    # other tables as given, so that the checker still reports their problems (an unknown key, say)
    out.update({k: v for k, v in data.items() if k not in ("points", "output", "plot", "parameters")})
    return out


def _count(sweep) -> int | str:
    return len(sweep) if isinstance(sweep, list) else sweep.get("num", "?")


def _reference(derived: dict, label: str, source: str) -> xr.Dataset:
    from .api import generate

    try:
        return generate(derived).compute()
    except RecipeError as exc:
        raise CompareError(f"{label} with the nodes of {source} as [points] (points.<column>[i] is data row i, "
                           "from 0, in the recipe's units): " + "; ".join(exc.problems)) from None


def _scale_value(definition: str, needs, ref: xr.Dataset, reference: np.ndarray) -> np.ndarray:
    """S at every point: 1, the reference's own scale variables, the recipe's values, or max |reference|."""
    if definition.startswith("1 "):
        return np.ones_like(reference)
    if definition == FALLBACK_SCALE or (needs and not all(n in ref for n in needs)):
        finite = reference[np.isfinite(reference)]
        return np.full_like(reference, np.max(np.abs(finite)) if finite.size else np.nan)
    if needs:
        s = ref[needs[0]] / ref[needs[1]] if len(needs) == 2 else ref[needs[0]]
        return np.broadcast_to(np.asarray(s.values, dtype=float), reference.shape).copy()
    p = json.loads(ref.attrs["stressfields_recipe_canonical"])["parameters"]
    if not {"amplitudes", "a", "lambda_1", "E", "nu"} <= set(p):     # one of them is a column of nodes
        return _scale_value(FALLBACK_SCALE, (), ref, reference)
    amps = p["amplitudes"]
    s = {"Delta_1": amps[0], "a lambda_1/2": p["a"] * p["lambda_1"] / 2.0,
         "p* = pi E/(1-nu^2) Delta_1/lambda_1": math.pi * p["E"] / (1.0 - p["nu"] ** 2) * amps[0] / p["lambda_1"]}
    return np.full_like(reference, s[definition])


# --- the comparison dataset ---------------------------------------------------------------------

def _assemble(base, ref: xr.Dataset, coords, values, factors, ids, scales, source: str) -> xr.Dataset:
    n = len(coords[0].values)
    out_coords = {}
    for col in coords:
        attrs = dict(ref[col.name].attrs)
        if col.unit is not None:
            attrs["user_units"] = col.unit
        out_coords[col.name] = xr.Variable((POINT,), ref[col.name].values, attrs)
    for name, var in ref.coords.items():
        if var.ndim == 0:
            out_coords[name] = var.variable
    if ids is not None:
        out_coords[ids.name] = xr.Variable((POINT,), ids.values.astype(np.int64).astype(np.int32),
                                           {"long_name": "node identity", "units": "1",
                                            "description": f"node identity given in {source}",
                                            "coverage_content_type": "coordinate"})
    data = {}
    for col in values:
        rv = ref[col.name]
        reference = np.broadcast_to(np.asarray(rv.values, dtype=float), (n,)).copy()
        user = col.values * factors[col.name]
        units = rv.attrs.get("units", "1")
        long = rv.attrs.get("description", rv.attrs.get("long_name", col.name))
        data[f"{col.name}_reference"] = xr.Variable((POINT,), reference, {
            k: v for k, v in rv.attrs.items() if k not in ("coordinates",)})
        # short long_names (plot labels), the sentences in description (cf.py)
        data[f"{col.name}_user"] = xr.Variable((POINT,), user, {
            "long_name": f"{col.name} (user)",
            "description": f"{long}: user value from {source}"
                           + (f" (converted from {col.unit})" if col.unit not in (None, units) else ""),
            "units": units, "coverage_content_type": "modelResult"})
        data[f"{col.name}_difference"] = xr.Variable((POINT,), user - reference, {
            "long_name": f"{col.name} user - reference", "description": f"user minus reference: {long}",
            "units": units, "coverage_content_type": "qualityInformation"})
        definition, needs = scales[col.name]
        data[f"{col.name}_scale"] = xr.Variable((POINT,), _scale_value(definition, needs, ref, reference), {
            "long_name": f"scale S of {col.name}",
            "description": f"scale S of the comparison of {col.name}: {definition}", "units": units,
            "coverage_content_type": "referenceInformation"})
    if "validity" in ref and ref["validity"].ndim <= 1:
        flag = ref["validity"]
        data["reference_validity"] = xr.Variable((POINT,), np.broadcast_to(flag.values, (n,)).copy(), flag.attrs)
    attrs = {
        "Conventions": cf.CONVENTIONS, "featureType": "point",
        "title": f"{source} against the stressfields reference of {ref.attrs.get('title', base.title)}",
        "history": cf.history(f"compare ({source} against scenario {base.scenario.name}, "
                              f"recipe sha256 {ref.attrs.get('stressfields_recipe_sha256', '')[:16]})"),
        **cf.discovery_attrs(f"User results from {source} beside the stressfields reference at the same points "
                             "and their differences.", base.scenario.name),
        "source": ref.attrs.get("source", ""), "comment": ref.attrs.get("comment", ""),
        "references": ref.attrs.get("references", ""),
        "stressfields_scenario": base.scenario.name,
        "stressfields_units_mode": ref.attrs.get("stressfields_units_mode", ""),
        "compare_user_data": source,
        "compare_recipe": base.text,
        "stressfields_recipe": ref.attrs["stressfields_recipe"],
        "stressfields_recipe_sha256": ref.attrs.get("stressfields_recipe_sha256", ""),
    }
    return xr.Dataset(data, coords=out_coords, attrs=attrs)


def _judge(ds: xr.Dataset, names: list[str], tolerance: float | None) -> xr.Dataset:
    """Statistics per variable in the global attributes, and PASS/FAIL against the tolerance."""
    coords = [c for c in ds.coords if ds[c].dims == (POINT,) and c not in ID_COLUMNS]
    verdicts = []
    for name in names:
        stats = _statistics(ds, name, coords)
        if tolerance is not None:
            ok = bool(np.isfinite(stats["max_abs_difference_over_scale"])
                      and stats["max_abs_difference_over_scale"] <= tolerance)
            stats["result"] = "PASS" if ok else "FAIL"
            verdicts.append(ok)
        else:
            stats["result"] = "not judged (no tolerance)"
        ds.attrs.update({f"compare_{name}_{k}": v for k, v in stats.items()})
    ds.attrs["compare_variables"] = " ".join(names)
    if tolerance is not None:
        ds.attrs["compare_tolerance"] = tolerance
    ds.attrs["compare_result"] = ("not judged (no tolerance)" if tolerance is None
                                  else "PASS" if all(verdicts) else "FAIL")
    return ds


def _statistics(ds: xr.Dataset, name: str, coords: list[str]) -> dict:
    ref = ds[f"{name}_reference"].values
    diff = ds[f"{name}_difference"].values
    scale = ds[f"{name}_scale"].values
    ok = np.isfinite(ref)
    stats = {"compared_points": int(ok.sum()), "excluded_points": int((~ok).sum()),
             "scale_definition": ds[f"{name}_scale"].attrs["description"].split(": ", 1)[1]}
    if not ok.any():
        return {**stats, "max_abs_difference_over_scale": math.nan, "rms_difference": math.nan,
                "rms_difference_over_scale": math.nan, "relative_l2": math.nan, "worst_point": -1,
                "worst_coordinates": "none"}
    ratio = np.where(ok, np.abs(diff) / scale, -np.inf)
    worst = int(np.argmax(ratio))
    d, r = diff[ok], ref[ok]
    norm = float(np.linalg.norm(r))
    return {**stats, "scale": float(scale[worst]), "max_abs_difference_over_scale": float(ratio[worst]),
            "max_abs_difference": float(abs(diff[worst])),
            "rms_difference": float(np.sqrt(np.mean(d * d))),
            "rms_difference_over_scale": float(np.sqrt(np.mean((d / scale[ok]) ** 2))),
            "relative_l2": float(np.linalg.norm(d) / norm) if norm > 0 else (0.0 if not d.any() else math.inf),
            "worst_point": worst, "worst_coordinates": _where(ds, worst, coords),
            **{f"worst_{c}": int(ds[c].values[worst]) for c in ID_COLUMNS if c in ds.coords}}


def _where(ds: xr.Dataset, i: int, coords: list[str]) -> str:
    """The coordinates of point i, in the user's units where the user gave some."""
    parts = []
    for c in coords:
        values, unit = _user_coordinate(ds, c)
        parts.append(f"{c} = {float(values[i]):.6g}" + ("" if unit == "1" else f" {unit}"))
    return ", ".join(parts)


def _user_coordinate(ds: xr.Dataset, c: str) -> tuple[np.ndarray, str]:
    """A coordinate's values in the unit the user gave it in."""
    target = ds[c].attrs.get("units", "1")
    unit = ds[c].attrs.get("user_units", target)
    return ds[c].values / (1.0 if unit == target else UNITS[unit][1]), unit


def summary(ds: xr.Dataset) -> dict[str, dict]:
    """The per-variable statistics of a comparison dataset, from its ``compare_<v>_*`` attributes."""
    out = {}
    for name in ds.attrs.get("compare_variables", "").split():
        prefix = f"compare_{name}_"
        out[name] = {k[len(prefix):]: v for k, v in ds.attrs.items() if k.startswith(prefix)}
    return out


# --- the report -------------------------------------------------------------------------------------

def report_markdown(ds: xr.Dataset, recipe_label: str, png_note: str) -> str:
    """A short Markdown report: the case, one table row per variable, PASS/FAIL against the tolerance."""
    stats = summary(ds)
    tol = ds.attrs.get("compare_tolerance")
    verdict = (f"tolerance {tol:g} of the scale: **{ds.attrs['compare_result']}**" if tol is not None
               else "no tolerance given: not judged")
    lines = [f"# {ds.attrs['compare_user_data']} against the stressfields reference", "",
             f"- recipe: `{recipe_label}` (scenario `{ds.attrs['stressfields_scenario']}`, "
             f"{ds.attrs['stressfields_units_mode']} units)",
             f"- points: {ds.sizes[POINT]}; {verdict}",
             "- S: the variable's normalisation scale (p_m for stresses), as the reference gives it; "
             "Δ = user - reference", "",
             "| variable | S | max abs Δ / S | RMS Δ / S | relative L2 | worst point | at | result |",
             "|---|---|---|---|---|---|---|---|"]
    for name, s in stats.items():
        units = ds[f"{name}_reference"].attrs.get("units", "1")
        scale = f"{s['scale']:.6g} {units} ({s['scale_definition']})" if "scale" in s else s["scale_definition"]
        node = "".join(f" ({c} {s[f'worst_{c}']})" for c in ID_COLUMNS if f"worst_{c}" in s)
        lines.append(f"| `{name}` | {scale} | {s['max_abs_difference_over_scale']:.3e} | "
                     f"{s['rms_difference_over_scale']:.3e} | {s['relative_l2']:.3e} | {s['worst_point']}{node} | "
                     f"{s['worst_coordinates']} | {s['result']} |")
    excluded = {n: s["excluded_points"] for n, s in stats.items() if s["excluded_points"]}
    lines += ["", "Worst point: the index along `point` (data rows from 0)."]
    if excluded:
        lines.append("Left out where the reference is not finite (a singular point, see `reference_validity`): "
                     + ", ".join(f"{n} {k}" for n, k in excluded.items()) + " points.")
    lines += ["", f"Every value: `comparison.nc`. {png_note}", ""]
    return "\n".join(lines)


#: what a report folder holds (`write_report`); a folder holding anything else is never replaced
REPORT_FILES = ("comparison.nc", "comparison.png", "report.md", "report.json", "convergence.png")
#: the per-file tables of a mesh sequence or an Exodus history (fe/report.py names them)
REPORT_NUMBERED = re.compile(r"^comparison_\d+\.(nc|png)$")


def check_report_folder(folder: Path, *, overwrite: bool = False) -> Path:
    """The one check of a report folder before anything is computed: it does not exist (its parent
    can take it), is an empty directory, or, with ``overwrite``, a previous report (nothing but
    REPORT_FILES). Raises OutputError naming the problem."""
    from .writers import check_name

    folder = Path(folder)
    parent = folder.parent if str(folder.parent) else Path(".")
    if os.path.islink(folder):
        raise OutputError(f"{folder} is a symbolic link; give the report folder itself")
    if os.path.lexists(folder):
        if not folder.is_dir():
            raise OutputError(f"{folder} exists and is not a directory; a report is a folder")
        entries = os.listdir(folder)
        others = [e for e in entries if e not in REPORT_FILES and not REPORT_NUMBERED.match(e)]
        if others:
            raise OutputError(f"{folder} holds {len(others)} entr{'y' if len(others) == 1 else 'ies'} that "
                              f"{'is' if len(others) == 1 else 'are'} not of a report (e.g. {others[0]!r}); "
                              "refusing to replace it: give a new or empty folder")
        if entries and not overwrite:
            raise OutputError(f"{folder} holds a report; refusing to overwrite it (use --overwrite)")
    elif not parent.is_dir():
        raise OutputError(f"cannot write {folder}: {parent} is not a directory or does not exist")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise OutputError(f"cannot write {folder}: {parent} is not writable (read-only or no permission)")
    check_name(folder, parent)
    return folder


def write_report(ds: xr.Dataset, folder: str | os.PathLike, recipe_label: str, *, overwrite: bool = False,
                 plot: bool = True) -> Path:
    """Publish the comparison ``ds`` as the folder ``folder`` (`publish_report`): comparison.nc,
    report.md and (with ``plot``) comparison.png."""
    from .textfiles import write_text
    from .writers import write

    note = ("Quick look: `comparison.png`." if plot else
            "No comparison.png: matplotlib is not installed (pip install 'stressfields[plot]').")

    def fill(tmp: Path) -> None:
        write(ds, tmp / "comparison.nc")
        if plot:
            plot_comparison(ds, tmp / "comparison.png")
        write_text(tmp / "report.md", report_markdown(ds, recipe_label, note))

    return publish_report(folder, fill, overwrite=overwrite)


def publish_report(folder: str | os.PathLike, fill, *, overwrite: bool = False) -> Path:
    """Publish a report folder whole: ``fill(tmp)`` writes its files into a temporary folder beside
    ``folder`` (``.NAME.HOST-PID.RANDOM.partial``, `netcdf.temporary`), which is renamed into place
    when complete. On any error or interrupt (Ctrl-C, SIGTERM, SIGHUP) the temporary folder is removed
    and nothing is left; I/O failures (a full disk) are one OutputError. A folder a killed run left is
    removed by the next (`netcdf.clean_stale`). The folder replaced by ``overwrite`` is moved aside in
    one rename and removed after, as for a Zarr store."""
    from .netcdf import _umask, clean_stale, output_error, temporary
    from .writers import target_lock
    from .zarrstore import publish_folder

    folder = check_report_folder(Path(folder), overwrite=overwrite)
    parent = folder.parent if str(folder.parent) else Path(".")
    with target_lock(folder):
        clean_stale(folder)
        tmp = temporary(folder, ".partial")
        try:
            fill(tmp)
            os.chmod(tmp, 0o777 & ~_umask())         # mkdtemp makes 0700; publish like any new folder
            fd = os.open(tmp, os.O_RDONLY)
            try:
                os.fsync(fd)                        # the names of the files, before the folder's own
            finally:
                os.close(fd)
            # checked again at the last moment: a folder that gained other files meanwhile is kept
            check_report_folder(folder, overwrite=overwrite)
            publish_folder(tmp, folder, overwrite=True)
        except BaseException as exc:
            shutil.rmtree(tmp, ignore_errors=True)
            error = output_error(exc, folder, parent)
            if error is None and isinstance(exc, OutputError):     # the writer's: named after the folder
                text = re.sub(re.escape(str(tmp)) + r"/comparison(_\d+)?\.nc", str(folder), str(exc))
                error = OutputError(text.replace(str(tmp), str(folder)))
            if error is not None:
                raise error from None
            raise
    return folder


def plot_comparison(ds: xr.Dataset, path: Path) -> Path:
    """comparison.png: per variable the difference / S along the one coordinate that varies (points
    on a line), or a map over two varying coordinates coloured by |difference| / S; the worst point ringed."""
    from .plot import plain, require_matplotlib, save_figure

    plt = require_matplotlib()
    names = ds.attrs["compare_variables"].split()
    coords = [c for c in ds.coords if ds[c].dims == (POINT,) and c not in ID_COLUMNS]
    varying = sorted((c for c in coords if np.ptp(ds[c].values) > 0),
                     key=lambda c: ("x", "y", "z").index(c) if c in ("x", "y", "z") else 3)
    cols = min(len(names), 2)
    rows = -(-len(names) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(5.0 * cols, 3.8 * rows), squeeze=False)
    for ax, name in zip(axes.flat, names):
        _panel(ax, ds, name, varying)
    for ax in list(axes.flat)[len(names):]:
        ax.set_visible(False)
    # the title holds the file names and the recipe's title as given: plain text, never mathtext
    fig.suptitle(plain(ds.attrs["title"]), fontsize=8, wrap=True)
    fig.tight_layout()
    return save_figure(fig, plt, path)       # into the report's temporary folder (`write_report`)


def _panel(ax, ds: xr.Dataset, name: str, varying: list[str]) -> None:
    ratio = ds[f"{name}_difference"].values / ds[f"{name}_scale"].values
    worst = int(ds.attrs[f"compare_{name}_worst_point"])

    def label(c):
        units = _user_coordinate(ds, c)[1]
        return c if units == "1" else f"{c} [{units}]"

    if len(varying) >= 2:
        h, v = _user_coordinate(ds, varying[0])[0], _user_coordinate(ds, varying[1])[0]
        art = ax.scatter(h, v, c=np.abs(ratio), s=14, cmap="viridis")
        ax.figure.colorbar(art, ax=ax, label="|Δ| / S")
        ax.set(xlabel=label(varying[0]), ylabel=label(varying[1]))
        at = (h[worst], v[worst]) if worst >= 0 else None
    else:
        h = _user_coordinate(ds, varying[0])[0] if varying else np.arange(ratio.size)
        order = np.argsort(h, kind="stable")
        ax.plot(h[order], ratio[order], ".-", ms=4, lw=0.8)
        ax.set(xlabel=label(varying[0]) if varying else "point", ylabel="Δ / S")
        at = (h[worst], ratio[worst]) if worst >= 0 else None
    if at is not None:
        ax.plot(*at, "o", mfc="none", mec="red", ms=12, mew=1.5)
    stat_ = ds.attrs[f"compare_{name}_max_abs_difference_over_scale"]
    ax.set_title(f"{name}: max |Δ|/S = {stat_:.3g} at point {worst}", fontsize=9)
