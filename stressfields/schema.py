"""data_schema.md and `stressfields describe`, both derived from the scenario declarations."""
from __future__ import annotations

import numpy as np

from .cf import ACCURACY_CONTRACT
from .scenarios import REGISTRY
from .scenarios.base import LABEL_CHARS, Parameter, Scenario, Variable

HEADER = """# stressfields data schema

Generated from the scenario declarations by `stressfields schema > data_schema.md`; a test keeps
this file in sync. Every dataset is CF-1.8: each variable and coordinate carries `units` (UDUNITS,
`"1"` for dimensionless), a short `long_name` (at most LABEL_CHARS characters, the declaration's
label: plots label their axes with it) and the full sentence in `description`; normalised variables
also carry `normalisation`, the reference scale they are divided by (said by its symbol in
`long_name`, e.g. `stress sigma_xx / p_m`); every computed field also says how it was computed
(`stressfields_method`: closed form, quadrature, series) and to what accuracy
(`stressfields_accuracy`). Flags carry `flag_values` and `flag_meanings`.

Dimensions are the swept parameters, in the order listed per scenario (spatial `x`, `y` last);
a parameter given as a single value becomes a scalar coordinate; a parameter of choice (e.g.
`profile`) given once is stored as the global attribute `stressfields_<name>`. The columns of a
recipe's `[points]` table (the user's own points, of one length) vary together along one dimension
`point`, after the swept ones; each column is a coordinate along `point`, and a dataset whose only
dimension is `point` carries `featureType = "point"` (CF discrete sampling geometry). Global attributes:
`Conventions` (`CF-1.8, ACDD-1.3`), `title`, `institution`, `source`, `history`, `references`, `comment`,
`stressfields_version`, `stressfields_scenario`, `stressfields_units_mode` (normalised | physical),
`stressfields_recipe` (the recipe text), `stressfields_recipe_canonical` and
`stressfields_recipe_sha256` (SHA-256 of the canonical JSON of the normalised recipe),
`stressfields_accuracy_contract` (below), and the ACDD-1.3 discovery attributes below.

Sign conventions are stated per scenario below and in each file's `comment` attribute.

## Readers and catalogues

- **Axes.** `x` and `y` carry `cartesian_axis = "X"` / `"Y"`, the depth `z` carries `axis = "Z"`
  and `positive = "down"` (it grows into the body): cf_xarray finds all three (`ds.cf["Z"]`).
  `x` and `y` carry no `axis` attribute on purpose: ParaView's NetCDF CF reader reads `axis = "X"`
  / `"Y"` as longitude / latitude and draws the data on a sphere; with these attributes it draws
  them planar, depth downwards. The price: compliance-checker's recommendation of CF §2.4 (the
  dimension order T, Z, Y, X) cannot tell `x` and `y` are horizontal, and warns on files that
  sweep `z` together with `x` or `y`; the order is z, y, x as recommended.
- **Text** (the names of a choice sweep, `<name>_name`) is stored as a char array with
  `_Encoding = "utf-8"` (xarray reads it back as text), not as a netCDF-4 string: ParaView's CF
  reader crashes on those.
- **ACDD-1.3**: `summary`, `keywords`, `license`, `creator_name`, `creator_type`,
  `creator_institution`, `date_created` (the time of writing; `SOURCE_DATE_EPOCH` when set),
  `product_version`, `processing_level`, `id` (the content hash, `stressfields_content_sha256`) and
  `coverage_content_type` on every variable (`modelResult`, `qualityInformation` for flags,
  `coordinate`, `referenceInformation` for array inputs). `history`, `date_created` and `id` are
  not part of the content hash. Two groups of ACDD items do not apply: `standard_name`, because no
  CF standard name exists for contact stresses, displacements or their normalised forms (a made-up
  name fails the CF check; the names and units here say what each variable is), and the geospatial
  and time extents (`geospatial_*`, `time_coverage_*`), because the coordinates are positions in
  and on an elastic body, not on the Earth, and the data are not a time series.
- **Merged files** (`sf.open_mfdataset`) list every source recipe hash in
  `stressfields_source_recipe_sha256`.

## Accuracy contract

Every float variable promises the following (each file also carries it as the global attribute
`stressfields_accuracy_contract`):

"""


def document() -> str:
    parts = [HEADER.replace("LABEL_CHARS", str(LABEL_CHARS)) + ACCURACY_CONTRACT]
    for scen in REGISTRY.values():
        parts.append(scenario_text(scen, level=2))
    return "\n".join(parts)


def scenario_text(scen: Scenario, level: int = 1) -> str:
    h = "#" * level
    lines = [f"{h} `{scen.name}`", "", scen.summary + ".", "", f"References: {scen.full_references}.", ""]
    lines += [f"Signs: {scen.conventions}.", ""]
    if scen.physical_switch:
        lines += [f"Units: normalised by default; giving `{scen.physical_switch}` switches to physical "
                  "units (column 'physical').", ""]
    lines += [f"Methods (`[method] method`): {', '.join(scen.methods)}; `rtol` in [1e-14, 1e-2], default 1e-10.",
              "", f"{h}# Parameters", "",
              "| name | long_name | meaning (description) | units | physical units | allowed | default | sweep |",
              "|---|---|---|---|---|---|---|---|"]
    lines += [_parameter_row(p) for p in scen.parameters]
    lines += ["", f"{h}# Variables", "",
              "| name | long_name | description | units | physical units | divided by (normalised) | depends on |",
              "|---|---|---|---|---|---|---|"]
    lines += [_variable_row(v, scen) for v in scen.variables]
    flags = [v for v in scen.variables if v.flag_values]
    if flags:
        lines += ["", "Flags:", ""]
        for v in flags:
            pairs = ", ".join(f"{val} = {m}" for val, m in zip(v.flag_values, v.flag_meanings))
            lines.append(f"- `{v.name}`: {pairs}." + (f" {v.comment}" if v.comment else ""))
    lines.append("")
    return "\n".join(lines)


def scenario_record(scen: Scenario) -> dict:
    """The declaration of ``scen`` as plain JSON values (`stressfields describe NAME --json`): what
    the text of `scenario_text` says, one key per column."""
    def default(p: Parameter):
        value = p.default.tolist() if isinstance(p.default, np.ndarray) else p.default
        return value if isinstance(value, (str, int, float, list, type(None))) else repr(value)

    parameters = [{"name": p.name, "long_name": p.label_in(p.mode == "physical"), "meaning": p.meaning,
                   "units": None if p.choices else p.units, "units_physical": None if p.choices else p.units_in(True),
                   "kind": p.kind, "allowed": p.allowed(), "low": p.low, "high": p.high, "choices": list(p.choices),
                   "default": default(p), "required": p.required, "sweepable": p.sweepable, "mode": p.mode,
                   "when": p.condition() or None} for p in scen.parameters]
    variables = [{"name": v.name, "long_name": v.label_in(v.mode == "physical"), "description": v.long_name,
                  "units": None if v.flag_values else v.units, "units_physical": None if v.flag_values
                  else v.units_in(True), "normalisation": v.scale.text if v.scale else None, "dtype": v.dtype,
                  "mode": v.mode,
                  "flag_values": list(v.flag_values), "flag_meanings": list(v.flag_meanings),
                  "depends_on": None if v.dims is None else [d for d in v.dims
                                                             if d in {p.name for p in scen.parameters}]}
                 for v in scen.variables]
    return {"name": scen.name, "summary": scen.summary, "references": scen.full_references,
            "conventions": scen.conventions, "physical_switch": scen.physical_switch, "methods": list(scen.methods),
            "parameters": parameters, "variables": variables}


def _parameter_row(p: Parameter) -> str:
    if isinstance(p.default, np.ndarray):
        default = "sweep over " + ", ".join(repr(v) for v in p.default.tolist())
    else:
        default = "required" if p.required else ("-" if p.default is None else repr(p.default))
    if p.mode == "physical":
        default = "required in physical mode" if not p.when else "required in physical mode, when applicable"
    if p.when:
        default += f" (only when {p.condition()})"
    units = "-" if p.mode == "physical" else ("-" if p.choices else p.units)
    phys = "-" if p.choices else p.units_in(True)
    label = p.label_in(p.mode == "physical")
    return (f"| `{p.name}` | {label} | {p.meaning} | {units} | {phys} | {p.allowed()} | {default} | "
            f"{'yes' if p.sweepable else 'no'} |")


def _variable_row(v: Variable, scen: Scenario) -> str:
    dims = "all parameters" if v.dims is None else ", ".join(f"`{d}`" for d in v.dims
                                                               if d in {p.name for p in scen.parameters})
    units = "-" if v.mode == "physical" else ("flag" if v.flag_values else v.units)
    phys = "-" if v.mode == "normalised" else ("flag" if v.flag_values else v.units_in(True))
    label = v.label_in(v.mode == "physical")
    return f"| `{v.name}` | {label} | {v.long_name} | {units} | {phys} | {v.scale.text if v.scale else '-'} | {dims} |"
