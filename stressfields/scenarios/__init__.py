"""The scenario registry: the one place that lists the scenarios."""
from __future__ import annotations

import sys
import types

from .axisymmetric import AXISYMMETRIC, CONICAL, PARABOLIC
from .base import Scenario
from .graded import SCENARIOS as GRADED
from .history import SCENARIOS as HISTORY
from .wavy import SCENARIOS as WAVY

REGISTRY: dict[str, Scenario] = {s.name: s for s in (CONICAL, PARABOLIC, AXISYMMETRIC, *HISTORY, *GRADED, *WAVY)}


def summaries() -> dict[str, str]:
    """Scenario names with their one-line descriptions (`sf.scenarios()`)."""
    return {name: s.summary for name, s in REGISTRY.items()}


class _Package(types.ModuleType):
    """Importing this subpackage sets the attribute `stressfields.scenarios` to it, over the API
    function `sf.scenarios()` of the same name: calling the subpackage gives what that function
    gives (`summaries`)."""

    def __call__(self) -> dict[str, str]:
        return summaries()


sys.modules[__name__].__class__ = _Package
