"""The graded sheet's reference points (seed001), shared by the graded physics tests."""
import json
from pathlib import Path

import pytest

REF_PATH = Path(__file__).resolve().parents[2].parent / "shared" / "formulas" / "seed001" / "reference_points.json"


def load_ref() -> dict:
    if not REF_PATH.exists():
        pytest.fail(f"reference points not found at {REF_PATH}")
    return json.loads(REF_PATH.read_text())


REF = load_ref()


def nu_of(case) -> float:
    """The case's Poisson ratio; "1/(2+k)" is the Holl ratio."""
    return 1.0 / (2.0 + case["k"]) if case["nu"] == "1/(2+k)" else float(case["nu"])
