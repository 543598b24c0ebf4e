import json
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SHARED = ROOT.parent / "shared"


def load_reference(seed: str) -> dict:
    """Reference points of the verified formula sheet ``seed`` (e.g. "seed000")."""
    path = SHARED / "formulas" / seed / "reference_points.json"
    if not path.exists():
        pytest.fail(f"reference points not found at {path}: shared/ must sit beside the project")
    return json.loads(path.read_text())
