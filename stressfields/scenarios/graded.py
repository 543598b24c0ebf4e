"""Power-law graded half-space scenarios (filled in by the graded family)."""
SCENARIOS: tuple = ()
