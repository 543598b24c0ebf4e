"""Compare an FE model's raw output with the reference: its files as the solver wrote them
(``formats``), its frame (``frames``), its units (``units``), judged by the statistics validators use
(``stats``), one table per file, time step or set of element centroids, and a mesh sequence's
convergence when several files are given.

    tables = compare_files("recipe.toml", ["L1.vtu", "L2.vtu"], Options(axisymmetric=True, z_up=True))
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import numpy as np
import xarray as xr

from .. import cf
from ..comparison import Column as RefColumn
from ..comparison import CompareError, _derived_recipe, _recipe, _reference, _scale_spec, _scale_value
from ..errors import name_problem
from ..recipe import POINT
from ..units import written_name
from . import stats as st
from .formats import FormatProblem, Table, read_nodes, user_table
from .frames import BODY2_FLIP, CYLINDRICAL, NEEDS, Frame, FrameProblem, rotate_reference, to_depth_frame
from .units import UnitProblem, compare_table_problem, factor, parse_unit_option, unit_from_option

#: `--scale` choices: user stresses divided by one of these
SCALES = ("p0", "p_m")
#: scenarios whose normal pressure is axisymmetric (body 2's mirror image holds; edges are circles)
AXISYMMETRIC_PRESSURE = ("parabolic", "conical", "axisymmetric", "axisymmetric_history")


@dataclass
class Options:
    """The switches of `stressfields compare` (see its --help)."""
    tolerance: dict[str, float] = field(default_factory=dict)
    variables: tuple[str, ...] | None = None
    step: int | None = None
    units: dict[str, str] = field(default_factory=dict)
    z_up: bool = False
    axisymmetric: bool = False
    body: int = 1
    exclude_edge: float | None = None
    remove_rigid_offset: bool = False
    scale: str | None = None
    h: tuple[float, ...] | None = None


def parse_tolerance(text) -> dict[str, float]:
    """``0.01`` (max) or ``rms=1e-3,max=0.05`` -> {key: limit}; CompareError (one line) if bad."""
    if text is None or text == "":
        return {}
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        items = [("max", text)]
    else:
        items = []
        for part in str(text).split(","):
            key, sep, value = part.partition("=")
            items.append((key.strip(), value.strip()) if sep else ("max", key.strip()))
    out = {}
    for key, value in items:
        if key not in st.TOLERANCE_KEYS:
            raise CompareError(f"--tolerance {key}: one of {', '.join(st.TOLERANCE_KEYS)} (e.g. rms=1e-3,max=0.05)")
        try:
            limit = float(value)
        except ValueError:
            limit = math.nan
        if not (math.isfinite(limit) and limit > 0):
            raise CompareError(f"--tolerance {key}={value}: must be a positive finite number")
        out[key] = limit
    return out


def compare_files(recipe, files, options: Options) -> list[xr.Dataset]:
    """One comparison dataset per table of every file (see the module docstring)."""
    if options.exclude_edge is not None and not (math.isfinite(options.exclude_edge) and options.exclude_edge > 0):
        raise CompareError(f"--exclude-edge {options.exclude_edge}: must be a positive number (a multiple of a)")
    if options.scale is not None and options.scale not in SCALES:
        raise CompareError(f"--scale {options.scale}: one of {', '.join(SCALES)}")
    base, data = _recipe(recipe)
    if not options.units:
        options = replace(options, units=_recipe_units(data, base.label))
    tables = []
    for path in files:
        if isinstance(path, (Mapping, xr.Dataset)):         # sf.compare's data in memory
            try:
                got = [user_table(path)]
            except FormatProblem as exc:
                raise CompareError(f"{'the user dataset' if isinstance(path, xr.Dataset) else 'the user data'}: "
                                   f"{exc}") from None
            if options.step is not None:
                raise CompareError(f"step {options.step}: only an Exodus II file has time steps")
            tables += got
            continue
        why = name_problem(str(path))
        if why is not None:          # said with ascii(): the name itself may not print
            raise CompareError(f"{ascii(str(path))}: cannot read it ({why})")
        try:
            got = read_nodes(path, step=options.step)
        except FormatProblem as exc:
            raise CompareError(f"{path}: {exc}") from None
        tables += got if len(files) == 1 else got[:1]
    frames = []
    for table in tables:
        try:
            frames.append((table, to_depth_frame(table, z_up=options.z_up, axisymmetric=options.axisymmetric,
                                                 body=options.body)))
        except FrameProblem as exc:
            raise CompareError(f"{table.label}: {exc}") from None
    # every table is checked before the first reference is computed
    if options.variables and len(frames) > 1:     # tables that give none of them (nodes or elements) left out
        kept = [(t, f) for t, f in frames if {c.name for c in f.values} & set(options.variables)]
        frames = kept or frames[:1]
    plans = [_plan(base, table, frame, options) for table, frame in frames]
    return [_compare_one(base, data, plan, options) for plan in plans]


def _recipe_units(data: dict, label: str) -> dict[str, str]:
    """The recipe's ``[compare] units = { length = "mm", stress = "MPa" }``: the units of a format that
    carries none when ``--units`` gives none (checked as --units is; `recipe` checks it the same way)."""
    table = data.get("compare")
    if table is None:
        return {}
    problem = compare_table_problem(table)
    if problem:
        raise CompareError(f"{label}: {problem}")
    units = table.get("units") or {}
    return parse_unit_option(",".join(f"{k}={v}" for k, v in units.items()))


@dataclass
class _Plan:
    table: Table
    frame: Frame
    coords: list
    values: list
    factors: dict
    cartesian: list[str]
    units: dict             # the unit each coordinate is given in ("": none), for the worst point's place


def _plan(base, table: Table, frame: Frame, options: Options) -> _Plan:
    scen, physical, source = base.scenario, base.physical, table.label
    params = {p.name: p for p in scen.parameters}
    fields = {v.name: v for v in scen.variables_in(physical) if v.dtype.startswith("float") and not v.flag_values}
    values = []
    for c in frame.values:
        written = written_name(c.label)
        if written in fields and written != c.name and not frame.cylindrical:
            c = replace(c, name=written)        # a scenario's own name as written (the wavy field's uz, not u_z)
        if options.variables and c.name not in options.variables:
            continue            # a column not asked for is not checked (an FE file holds many)
        cart = CYLINDRICAL.get(c.name, c.name) if frame.cylindrical else c.name
        if cart in fields:
            values.append(c)
            continue
        var = next((v for v in scen.variables if v.name == c.name), None)
        what = ("unknown" if var is None else "a flag, not a field" if var.flag_values
                else "not a float field in this mode")
        raise CompareError(f"{source}: column {c.label!r} is {what} for scenario '{scen.name}' "
                           f"({'physical' if physical else 'normalised'} mode); coordinates: "
                           f"{', '.join(p.name for p in scen.parameters if p.per_point)}; fields: {', '.join(fields)}")
    if options.variables:
        given = {c.name: c for c in values}
        unknown = [n for n in options.variables if n not in given]
        if unknown:
            raise CompareError(f"variables {', '.join(map(repr, unknown))}: not value columns of {source} "
                               f"(value columns: {', '.join(given)})")
        values = [given[n] for n in dict.fromkeys(options.variables)]
    coords = [c for c in frame.coords if c.name in params]
    stray = [c.label for c in frame.coords if c.name not in params]
    if stray:
        raise CompareError(f"{source}: coordinate {stray[0]!r} is not a parameter of scenario '{scen.name}'")
    if not coords:
        raise CompareError(f"{source}: no coordinate column (e.g. x, y, z of scenario '{scen.name}')")
    if not values:
        raise CompareError(f"{source}: no value column to compare (e.g. {', '.join(list(fields)[:3])})")
    everything = [*coords, *values] + [c for c in (frame.node, frame.weight) if c is not None]
    for col in everything:
        bad = np.flatnonzero(~np.isfinite(col.values))
        if bad.size:
            raise CompareError(f"{source}, column {col.label!r}: data row {bad[0]} (from 0; {bad.size} such rows) "
                               "is not a finite number")
    if frame.node is not None and not np.all((frame.node.values == np.round(frame.node.values))
                                             & (np.abs(frame.node.values) < 2 ** 31)):
        raise CompareError(f"{source}, column {frame.node.label!r}: node identities must be 32-bit integers")
    if frame.weight is not None and np.any(frame.weight.values < 0):
        raise CompareError(f"{source}, column {frame.weight.label!r}: quadrature weights and volumes are >= 0")
    if ({"wl2", "wrms"} & set(options.tolerance)) and frame.weight is None:
        raise CompareError(f"--tolerance wl2/wrms: {source} gives no quadrature weights or cell volumes (a column "
                           "'weight' or 'volume')")
    if frame.cylindrical or frame.axisymmetric or (frame.body == 2).any() or options.exclude_edge or \
            options.scale == "p0":
        if scen.name not in AXISYMMETRIC_PRESSURE:
            raise CompareError(f"{source}: cylindrical components, a second body, --exclude-edge and --scale p0 "
                               f"need an axisymmetric pressure; scenario '{scen.name}' has none")
    if frame.axisymmetric:
        loaded = [k for k in ("ux0", "fx", "tangential_force") if _nonzero(_recipe_data(base).get(k))]
        if loaded:
            raise CompareError(f"--axisymmetric: the recipe gives a tangential load ({', '.join(loaded)}): its field "
                               "is not axisymmetric; compare a 3-D model")
    factors, shown = {}, {}
    for col in [*coords, *values]:
        name = CYLINDRICAL.get(col.name, col.name) if frame.cylindrical else col.name
        decl = params[name] if name in params else fields[name]
        target = decl.units_in(physical)
        unit = col.unit
        if options.scale and name.startswith("sigma_") and col in values:
            if unit not in (None, "1"):
                raise CompareError(f"{source}, column {col.label!r}: --scale {options.scale} means values divided by "
                                   f"{options.scale}, without a unit; it has {unit!r}")
            factors[col.name] = 1.0         # times the scale, once the reference gives it
            continue
        if unit is None and not table.carries_units:
            unit = unit_from_option(col.name, target, options.units)
            if unit is None and physical and target != "1":
                raise CompareError(f"{source}: the format carries no units and the recipe is in physical units: give "
                                   "--units (e.g. length=mm,stress=MPa,force=N); nothing is guessed")
        try:
            factors[col.name] = factor(unit, target, col.label)
        except UnitProblem as exc:
            mode = "" if physical else (" (the recipe is in normalised mode ('1'): values divided by the scale, "
                                        "without a unit)")
            raise CompareError(f"{source}: {exc}{mode}") from None
        shown[col.name] = "" if (unit or target) == "1" else (unit or target)
    needed = list(dict.fromkeys(n for c in values for n in
                                (NEEDS.get(c.name, (c.name,)) if frame.cylindrical else (c.name,))))
    return _Plan(table, frame, coords, values, factors, needed, shown)


def _recipe_data(base) -> dict:
    import tomllib

    try:
        return dict(tomllib.loads(base.text).get("parameters") or {})
    except (tomllib.TOMLDecodeError, AttributeError):
        import json

        return dict(json.loads(base.text).get("parameters") or {})


def _nonzero(value) -> bool:
    if value is None:
        return False
    if isinstance(value, (list, tuple)):
        return any(_nonzero(v) for v in value)
    return not isinstance(value, (int, float)) or value != 0


def _compare_one(base, data: dict, plan: _Plan, options: Options) -> xr.Dataset:
    scen, physical, source = base.scenario, base.physical, plan.table.label
    frame = plan.frame
    n = frame.body.size
    body2 = frame.body == 2
    # the points the reference is evaluated at: body 2's nodes at their mirror image (frames docstring)
    points = {}
    for c in plan.coords:
        v = c.values * plan.factors[c.name]
        points[c.name] = np.where(body2, -v, v) if c.name in ("x", "y", "z") else v
    extra = options.scale == "p0"
    if extra:           # the centre of the contact: p0 = -sigma_zz(0, 0, 0)
        points = {k: np.append(v, 0.0) for k, v in points.items()}
    available = {v.name for v in scen.variables_in(physical)}
    wanted = list(plan.cartesian)
    if options.exclude_edge:
        wanted += [v for v in ("contact_radius", "stick_radius") if v in available]
    if options.scale:
        wanted += [v for v in ("sigma_zz", "mean_pressure") if v in available]
    cols = [RefColumn(k, k, None, v) for k, v in points.items()]
    vals = [RefColumn(k, k, None, np.empty(0)) for k in dict.fromkeys(wanted)]
    scales = {k: _scale_spec(scen.variable(k), physical) for k in dict.fromkeys(wanted)}
    derived = _derived_recipe(base, data, cols, {k: 1.0 for k in points}, vals, scales, source)
    ref = _reference(derived, base.label, source)
    m = n + (1 if extra else 0)

    def at_nodes(name):
        values = np.broadcast_to(np.asarray(ref[name].values, dtype=float), (m,)).copy()
        if extra and name == "sigma_zz":
            return values[:n], values[n]
        return values[:n], None

    cart = {}
    centre = None
    for name in plan.cartesian:
        values, last = at_nodes(name)
        cart[name] = np.where(body2, -values, values) if name in BODY2_FLIP else values
        centre = last if last is not None else centre
    stress_scale = _user_scale(options.scale, ref, at_nodes, n, physical, source, centre)
    user_xy = {c.name: c.values * plan.factors[c.name] for c in plan.coords}
    out_coords = {c.name: xr.Variable((POINT,), user_xy[c.name], {
        **{k: v for k, v in ref[c.name].attrs.items() if k in ("long_name", "description", "units", "axis",
                                                               "positive", "cartesian_axis")},
        "coverage_content_type": "coordinate", **({"user_units": c.unit} if c.unit else {})}) for c in plan.coords}
    for name, var in ref.coords.items():
        if var.ndim == 0:
            out_coords[name] = var.variable
    if frame.node is not None:
        out_coords["node"] = xr.Variable((POINT,), frame.node.values.astype(np.int32), {
            "long_name": "node", "description": f"node identity given in {source}", "units": "1",
            "coverage_content_type": "referenceInformation"})
    out_coords["body"] = xr.Variable((POINT,), frame.body, {
        "long_name": "body", "units": "1", "coverage_content_type": "referenceInformation",
        "description": "body of the node: 1 the half-space, 2 the second identical body (mirror image)"})
    weights = None if frame.weight is None else frame.weight.values
    mask = np.ones(n, dtype=bool)
    ring = None
    attrs = {}
    if options.exclude_edge:
        ring, text = _edge_ring(base, ref, at_nodes, user_xy, n, options.exclude_edge)
        mask = ~ring
        attrs["compare_edge_ring"] = text
        out_coords["edge_ring"] = xr.Variable((POINT,), ring.astype(np.int8), {
            "long_name": "in the edge ring", "units": "1", "coverage_content_type": "qualityInformation",
            "description": f"1: node within the edge ring ({text}), reported apart"})
    data_vars, refs, diffs, judged = {}, {}, {}, []
    for col in plan.values:
        name = col.name
        if frame.cylindrical and name in CYLINDRICAL:
            reference = rotate_reference(name, cart, user_xy["x"], user_xy["y"])
            declared = scen.variable(CYLINDRICAL[name])
        else:
            reference = cart[name]
            declared = scen.variable(name)
        user = col.values * plan.factors[name]
        if options.scale and name.startswith("sigma_"):
            user = user * stress_scale
        units = declared.units_in(physical)
        offset = None
        if options.remove_rigid_offset and name.startswith("u_"):
            ok = np.isfinite(reference) & mask
            w = np.ones(ok.sum()) if weights is None else weights[ok]
            offset = float(np.sum(w * (user[ok] - reference[ok])) / np.sum(w)) if ok.any() else 0.0
            user = user - offset
        definition, _ = _scale_spec(declared, physical)
        scale = _scale_value(declared, physical, ref.isel({POINT: slice(0, n)}) if POINT in ref.dims else ref,
                             reference)
        diff = user - reference
        given = ref[CYLINDRICAL.get(name, name) if frame.cylindrical else name].attrs
        long = given.get("description", given.get("long_name", name))
        rotated = " (rotated to r, theta, z)" if name in CYLINDRICAL else ""
        # short long_names (plot labels), the sentences in description (cf.py)
        data_vars[f"{name}_reference"] = xr.Variable((POINT,), reference, {
            "long_name": f"{name} (reference)", "description": f"reference: {long}{rotated}", "units": units,
            "coverage_content_type": "modelResult"})
        data_vars[f"{name}_user"] = xr.Variable((POINT,), user, {
            "long_name": f"{name} (user)",
            "description": f"user value from {source}" + (f" (converted from {col.unit})" if col.unit else ""),
            "units": units, "coverage_content_type": "modelResult"})
        data_vars[f"{name}_difference"] = xr.Variable((POINT,), diff, {
            "long_name": f"{name} user - reference", "description": f"user minus reference: {long}",
            "units": units, "coverage_content_type": "qualityInformation"})
        data_vars[f"{name}_scale"] = xr.Variable((POINT,), scale, {
            "long_name": f"scale S of {name}", "description": f"scale S of the comparison of {name}: {definition}",
            "units": units, "coverage_content_type": "referenceInformation"})
        s = st.statistics(diff, reference, scale, weights, mask)
        s["scale_definition"] = definition
        s["label"] = col.label
        if s["worst_point"] >= 0:
            s["worst_coordinates"] = ", ".join(
                f"{c} = {float(user_xy[c][s['worst_point']]) / plan.factors[c]:.6g}"
                + (f" {plan.units[c]}" if plan.units.get(c) else "") for c in user_xy)
            if frame.node is not None:
                s["worst_node"] = int(frame.node.values[s["worst_point"]])
        if ring is not None:
            s.update({f"edge_{k}": v for k, v in st.statistics(diff, reference, scale, weights, ring).items()
                      if k in ("compared_points", "max_abs_difference_over_scale", "rms_difference_over_scale",
                               "p95_abs_difference_over_scale", "worst_point")})
        if offset is not None:
            s["rigid_offset_removed"] = offset
        hint = st.sign_hint(user, reference)
        if hint:
            s["note"] = hint
        refs[name], diffs[name] = reference, diff
        judged.append((name, s))
    if "validity" in ref and ref["validity"].ndim <= 1:
        flag = ref["validity"]
        data_vars["reference_validity"] = xr.Variable((POINT,), np.broadcast_to(flag.values, (m,))[:n].copy(),
                                                      flag.attrs)
    nu = float(ref["nu"].values) if "nu" in ref.coords and ref["nu"].ndim == 0 else 0.3
    energy = st.energy_error(diffs, refs, nu, weights, mask)
    ds = xr.Dataset(data_vars, coords=out_coords, attrs={
        "Conventions": cf.CONVENTIONS, "featureType": "point",
        "title": f"{source} against the stressfields reference of {ref.attrs.get('title', base.title)}",
        "history": cf.history(f"compare ({source} against scenario {scen.name}, "
                              f"recipe sha256 {ref.attrs.get('stressfields_recipe_sha256', '')[:16]})"),
        **cf.discovery_attrs(f"User results from {source} beside the stressfields reference at the same points "
                             "and their differences.", scen.name),
        "source": ref.attrs.get("source", ""), "references": ref.attrs.get("references", ""),
        "stressfields_scenario": scen.name, "stressfields_units_mode": ref.attrs.get("stressfields_units_mode", ""),
        "compare_user_data": source, "compare_recipe": base.text,
        "stressfields_recipe": ref.attrs["stressfields_recipe"],
        "compare_frame": _frame_text(frame, options), **attrs})
    if energy is not None:
        ds.attrs["compare_energy_relative_error"] = energy
    if weights is not None:
        ds.attrs["compare_weights"] = f"column {frame.weight.label!r}: integrals are sums of weight x value"
    ds.attrs["compare_points"] = n
    # the dimension the nodes fill (a line of surface nodes: 1, an (r, z) mesh: 2), for h = N^(-1/d)
    ds.attrs["compare_dimension"] = len({c.name for c in plan.coords if np.ptp(c.values) > 0}) or 1
    return _judge(ds, judged, options.tolerance, energy)


def _user_scale(scale, ref, at_nodes, n, physical, source, centre) -> float:
    """The factor a user stress divided by ``scale`` is multiplied by (in the recipe's units)."""
    if scale is None:
        return 1.0
    pm = float(np.asarray(at_nodes("mean_pressure")[0])[0]) if physical and "mean_pressure" in ref else 1.0
    if scale == "p_m":
        return pm
    p0 = -float(centre) if centre is not None else math.nan
    if not math.isfinite(p0) or p0 <= 0:
        raise CompareError(f"--scale p0: the pressure at the centre of the contact is not finite and positive "
                           f"for this recipe ({source}); use --scale p_m")
    return p0


def _edge_ring(base, ref, at_nodes, xy, n, width) -> tuple[np.ndarray, str]:
    a = float(at_nodes("contact_radius")[0][0]) if "contact_radius" in ref else 1.0
    radii = [a]
    text = f"within {width:g} a of the contact edge r = a"
    if "stick_radius" in ref:
        c = at_nodes("stick_radius")[0][0] * (1.0 if base.physical else a)
        if 0 < c < a * (1 - 1e-12):
            radii.append(float(c))
            text += f", the stick edge r = c = {c / a:.4g} a"
    tip = base.scenario.name == "conical"
    if tip:
        text += ", the cone tip"
    zero = np.zeros(n)
    d = st.edge_distance(xy.get("x", zero), xy.get("y", zero), np.abs(xy.get("z", zero)), radii, tip)
    return d <= width * a, text


def _frame_text(frame: Frame, options: Options) -> str:
    parts = ["z up in the file (negated: z, sigma_xz, sigma_yz, u_z, dpdz)" if options.z_up else "z is depth"]
    if frame.axisymmetric:
        parts.append("axisymmetric (r, z): x = r, y = 0")
    if frame.cylindrical:
        parts.append("cylindrical components: the reference rotated to (r, theta, z)")
    if (frame.body == 2).any():
        parts.append(f"{int((frame.body == 2).sum())} nodes of body 2 (mirror image)")
    return "; ".join(parts)


def _judge(ds: xr.Dataset, judged, tolerance: dict, energy) -> xr.Dataset:
    verdicts = []
    for name, s in judged:
        if tolerance:
            failed = []
            for key, limit in tolerance.items():
                value = energy if key == "energy" else s.get(st.TOLERANCE_KEYS[key])
                if value is None:
                    continue
                if not (math.isfinite(value) and value <= limit):
                    failed.append(f"{key} {value:.3g} > {limit:g}")
            s["result"] = "FAIL: " + "; ".join(failed) if failed else "PASS"
            verdicts.append(not failed)
        else:
            s["result"] = "not judged (no tolerance)"
        ds.attrs.update({f"compare_{name}_{k}": v for k, v in s.items()})
    ds.attrs["compare_variables"] = " ".join(n for n, _ in judged)
    if tolerance:
        ds.attrs["compare_tolerance"] = ",".join(f"{k}={v:g}" for k, v in tolerance.items())
    ds.attrs["compare_result"] = ("not judged (no tolerance)" if not tolerance
                                  else "PASS" if all(verdicts) else "FAIL")
    return ds


def convergence(datasets: list[xr.Dataset], h: tuple[float, ...] | None = None) -> dict:
    """Per variable and statistic the error on each mesh, the observed orders and the Richardson-style
    remainder (stats.observed_orders); the mesh size is N^(-1/d) unless ``h`` gives it."""
    if h is not None and len(h) != len(datasets):
        raise CompareError(f"--h gives {len(h)} sizes for {len(datasets)} meshes")
    sizes = list(h) if h is not None else [float(ds.attrs["compare_points"]) ** (-1.0 / int(ds.attrs[
        "compare_dimension"])) for ds in datasets]
    names = [n for n in datasets[0].attrs["compare_variables"].split()
             if all(n in ds.attrs["compare_variables"].split() for ds in datasets)]
    table = {}
    for name in names:
        row = {}
        for key in st.CONVERGENCE_KEYS:
            if key == "energy":
                continue
            attr = f"compare_{name}_{st.TOLERANCE_KEYS[key]}"
            if all(attr in ds.attrs for ds in datasets):
                row[key] = st.observed_orders(sizes, [float(ds.attrs[attr]) for ds in datasets])
        table[name] = row
    if all("compare_energy_relative_error" in ds.attrs for ds in datasets):
        table["stress (energy norm)"] = {"energy": st.observed_orders(
            sizes, [float(ds.attrs["compare_energy_relative_error"]) for ds in datasets])}
    scen = datasets[0].attrs["stressfields_scenario"]
    edges, expected = st.EDGES.get(scen, ("none stated", "p + 1 in L2 for a smooth field"))
    return {"meshes": [ds.attrs["compare_user_data"] for ds in datasets], "h": sizes,
            "h_definition": "given by --h" if h is not None else "N^(-1/d): N nodes, d the mesh dimension",
            "expected": expected, "edges": edges, "variables": table}


def stats_summary(ds: xr.Dataset) -> dict:
    """Every figure of one comparison dataset (for report.json)."""
    out = {"user_data": ds.attrs["compare_user_data"], "points": int(ds.attrs["compare_points"]),
           "frame": ds.attrs.get("compare_frame", ""), "result": ds.attrs["compare_result"], "variables": {}}
    for key in ("compare_tolerance", "compare_edge_ring", "compare_energy_relative_error", "compare_weights"):
        if key in ds.attrs:
            out[key[len("compare_"):]] = ds.attrs[key]
    for name in ds.attrs["compare_variables"].split():
        prefix = f"compare_{name}_"
        out["variables"][name] = {k[len(prefix):]: _plain(v) for k, v in ds.attrs.items() if k.startswith(prefix)}
    return out


def _plain(v):
    if isinstance(v, (np.integer,)):
        return int(v)
    if isinstance(v, (np.floating, float)):
        return float(v) if math.isfinite(v) else str(v)
    return v

