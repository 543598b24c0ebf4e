"""All CF-1.8 metadata in one place: global attributes, coordinate and variable attributes."""
from __future__ import annotations

import os
import platform
import time

import numpy as np

from . import __version__
from .scenarios.base import Parameter, Variable

CONVENTIONS = "CF-1.8"


def global_attrs(recipe) -> dict[str, str]:
    scen = recipe.scenario
    stamp = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime(_now()))
    mode = "physical units" if recipe.physical else "normalised (dimensionless) units"
    return {
        "Conventions": CONVENTIONS,
        "title": recipe.title,
        "institution": "stressfields",
        "source": f"stressfields {__version__}, scenario '{scen.name}', method '{recipe.method}', "
                  f"rtol {recipe.rtol:g}",
        "history": f"{stamp} stressfields {__version__} generate (scenario {scen.name}, "
                   f"recipe sha256 {recipe.sha256[:16]}) on Python {platform.python_version()}",
        "references": scen.full_references,
        "comment": f"{scen.summary}. Values in {mode}. Signs: {scen.conventions}. See data_schema.md "
                   "of stressfields for every variable.",
        "stressfields_version": __version__,
        "stressfields_scenario": scen.name,
        "stressfields_units_mode": "physical" if recipe.physical else "normalised",
        "stressfields_recipe": recipe.text,
        "stressfields_recipe_canonical": recipe.canonical,
        "stressfields_recipe_sha256": recipe.sha256,
    }


def coord_attrs(par: Parameter, physical: bool) -> dict[str, str]:
    attrs = {"long_name": par.meaning_in(physical)}
    if not par.choices:
        attrs["units"] = par.units_in(physical)
    return attrs


def variable_attrs(var: Variable, physical: bool) -> dict:
    attrs: dict = {"long_name": var.long_name_in(physical)}
    if var.flag_values:
        attrs["flag_values"] = np.array(var.flag_values, dtype=np.int8)
        attrs["flag_meanings"] = " ".join(var.flag_meanings)
    else:
        attrs["units"] = var.units_in(physical)
    if var.scale and not physical:
        attrs["normalisation"] = var.scale
    if var.comment:
        attrs["comment"] = var.comment
    return attrs


def _now() -> float:
    # SOURCE_DATE_EPOCH makes the history stamp reproducible for archived reference runs
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    return float(epoch) if epoch and epoch.isdigit() else time.time()
