"""The scenario registry: the one place that lists the scenarios."""
from __future__ import annotations

from .axisymmetric import AXISYMMETRIC, CONICAL, PARABOLIC
from .base import Scenario

REGISTRY: dict[str, Scenario] = {s.name: s for s in (CONICAL, PARABOLIC, AXISYMMETRIC)}
