"""The scenario registry: the one place that lists the scenarios."""
from __future__ import annotations

from .axisymmetric import AXISYMMETRIC, CONICAL, PARABOLIC
from .base import Scenario
from .graded import SCENARIOS as GRADED
from .history import SCENARIOS as HISTORY
from .wavy import SCENARIOS as WAVY

REGISTRY: dict[str, Scenario] = {s.name: s for s in (CONICAL, PARABOLIC, AXISYMMETRIC, *HISTORY, *GRADED, *WAVY)}
