"""All CF-1.8 metadata in one place: global attributes, coordinate and variable attributes."""
from __future__ import annotations

import os
import platform
import time

import numpy as np

from . import __version__
from .scenarios.base import Parameter, Variable

CONVENTIONS = "CF-1.8"

#: the accuracy every float variable promises: written once, here; the README and data_schema.md
#: quote it (tests/test_cf_and_docs.py keeps them in sync) and every file carries it
ACCURACY_CONTRACT = """\
- **Closed forms**: relative error at most 1e-12 of |value| wherever the value is finite, far
  field and next to contact and stick edges included.
- **Quadrature and series** (the recipe's `[method] rtol`): |error| ≤ rtol · max(|value|, S),
  where S is the variable's normalisation scale (its `normalisation` attribute): the mean contact
  pressure p_m for axisymmetric stresses, p_m/a for `dpdz`, p* for wavy pressures, Δ1 for wavy
  displacements; for the graded family rtol is relative to |value|.
- **`error_estimate`** (where a scenario offers it) is an upper bound of |error|, and
  **`converged`** is 1 exactly when `error_estimate` ≤ rtol · S.
- **`validity`** is 0 where every value of the point meets the above. Any other code names the
  true cause, as its `flag_meanings` say: ±inf only where the exact limit is infinite, NaN only
  where the exact limit depends on the direction of approach, and family-specific causes such as a
  series that did not converge or an approximate formula. A finite value with validity 0 is never
  knowingly wrong.
- **Known limits**, stated rather than hidden: a value within a few units of rounding of an edge
  moves with that rounding (the field's own sensitivity, about eps·a/|r − a|: the graded shear
  traction within 1e-15 of the stick edge c/a, interior fields next to the edge ring); in-plane
  components of the tangential field below the surface that pass through zero meet 1e-12 of the
  largest component rather than of their own value; wavy `error_estimate` bounds the pressures,
  not `uz`.
"""


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
        "stressfields_accuracy_contract": ACCURACY_CONTRACT,
        "stressfields_version": __version__,
        "stressfields_scenario": scen.name,
        "stressfields_units_mode": "physical" if recipe.physical else "normalised",
        "stressfields_recipe": recipe.text,
        "stressfields_recipe_canonical": recipe.canonical,
        "stressfields_recipe_sha256": recipe.sha256,
    }


def feature_type(sizes) -> dict[str, str]:
    """CF-1.8 discrete sampling geometry: ``featureType = "point"`` when the user's points are the
    dataset's only dimension (with swept dimensions beside them the data is a grid, not a DSG)."""
    return {"featureType": "point"} if set(sizes) == {"point"} else {}


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
