import json
from pathlib import Path

DATA = Path(__file__).resolve().parent / "data"


def load_reference(name: str) -> dict:
    """Reference values of tests/data/<name>.json (provenance in tests/data/README.md):
    "axisymmetric_surface", "graded_power_law" or "wavy_tsukanov"."""
    return json.loads((DATA / f"{name}.json").read_text())
