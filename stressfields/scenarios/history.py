"""Tangential loading histories (fretting) on axisymmetric indenters (filled in by the history family)."""
SCENARIOS: tuple = ()
