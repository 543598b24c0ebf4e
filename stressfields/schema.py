"""data_schema.md and `stressfields describe`, both derived from the scenario declarations."""
from __future__ import annotations

import numpy as np

from .cf import ACCURACY_CONTRACT
from .scenarios import REGISTRY
from .scenarios.base import Parameter, Scenario, Variable

HEADER = """# stressfields data schema

Generated from the scenario declarations by `stressfields schema > data_schema.md`; a test keeps
this file in sync. Every dataset is CF-1.8: each variable and coordinate carries `units` (UDUNITS,
`"1"` for dimensionless) and `long_name`; normalised variables also carry `normalisation`, the
reference scale they are divided by; every computed field also says how it was computed
(`stressfields_method`: closed form, quadrature, series) and to what accuracy
(`stressfields_accuracy`). Flags carry `flag_values` and `flag_meanings`.

Dimensions are the swept parameters, in the order listed per scenario (spatial `x`, `y` last);
a parameter given as a single value becomes a scalar coordinate; a parameter of choice (e.g.
`profile`) given once is stored as the global attribute `stressfields_<name>`. The columns of a
recipe's `[points]` table (the user's own points, of one length) vary together along one dimension
`point`, after the swept ones; each column is a coordinate along `point`, and a dataset whose only
dimension is `point` carries `featureType = "point"` (CF discrete sampling geometry). Global attributes:
`Conventions`, `title`, `institution`, `source`, `history`, `references`, `comment`,
`stressfields_version`, `stressfields_scenario`, `stressfields_units_mode` (normalised | physical),
`stressfields_recipe` (the recipe text), `stressfields_recipe_canonical` and
`stressfields_recipe_sha256` (SHA-256 of the canonical JSON of the normalised recipe),
`stressfields_accuracy_contract` (below).

Sign conventions are stated per scenario below and in each file's `comment` attribute.

## Accuracy contract

Every float variable promises the following (each file also carries it as the global attribute
`stressfields_accuracy_contract`):

"""


def document() -> str:
    parts = [HEADER + ACCURACY_CONTRACT]
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
              "| name | meaning | units | physical units | allowed | default | sweep |",
              "|---|---|---|---|---|---|---|"]
    lines += [_parameter_row(p) for p in scen.parameters]
    lines += ["", f"{h}# Variables", "",
              "| name | long_name | units | physical units | divided by (normalised) | depends on |",
              "|---|---|---|---|---|---|"]
    lines += [_variable_row(v, scen) for v in scen.variables]
    flags = [v for v in scen.variables if v.flag_values]
    if flags:
        lines += ["", "Flags:", ""]
        for v in flags:
            pairs = ", ".join(f"{val} = {m}" for val, m in zip(v.flag_values, v.flag_meanings))
            lines.append(f"- `{v.name}`: {pairs}." + (f" {v.comment}" if v.comment else ""))
    lines.append("")
    return "\n".join(lines)


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
    return (f"| `{p.name}` | {p.meaning} | {units} | {phys} | {p.allowed()} | {default} | "
            f"{'yes' if p.sweepable else 'no'} |")


def _variable_row(v: Variable, scen: Scenario) -> str:
    dims = "all parameters" if v.dims is None else ", ".join(f"`{d}`" for d in v.dims
                                                               if d in {p.name for p in scen.parameters})
    units = "-" if v.mode == "physical" else ("flag" if v.flag_values else v.units)
    phys = "-" if v.mode == "normalised" else ("flag" if v.flag_values else v.units_in(True))
    return f"| `{v.name}` | {v.long_name} | {units} | {phys} | {v.scale or '-'} | {dims} |"
