"""The graded reference points (tests/data/graded_power_law.json), shared by the graded physics
tests."""
from conftest import load_reference

REF = load_reference("graded_power_law")


def nu_of(case) -> float:
    """The case's Poisson ratio; "1/(2+k)" is the Holl ratio."""
    return 1.0 / (2.0 + case["k"]) if case["nu"] == "1/(2+k)" else float(case["nu"])
