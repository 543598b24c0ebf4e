"""Multisinusoidal wavy contact scenario (filled in by the wavy family)."""
SCENARIOS: tuple = ()
