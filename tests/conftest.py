import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

DATA = Path(__file__).resolve().parent / "data"


def load_reference(name: str) -> dict:
    """Reference values of tests/data/<name>.json (provenance in tests/data/README.md):
    "axisymmetric_surface", "graded_power_law", "graded_interior" or "wavy_tsukanov"."""
    return json.loads((DATA / f"{name}.json").read_text())


def kill_after_two_parts(recipe: Path, target: Path, timeout: float) -> dict:
    """Start `stressfields run RECIPE -o TARGET --parts` in a process, SIGKILL it once its manifest
    lists two finished parts, and return the manifest (the run must still have been going)."""
    proc = subprocess.Popen([sys.executable, "-m", "stressfields", "run", str(recipe), "-o", str(target), "-q",
                             "--parts"], stderr=subprocess.PIPE)
    manifest = target.parent / f"{target.name}.parts" / "manifest.json"
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and proc.poll() is None:
        if manifest.exists() and len(json.loads(manifest.read_text())["parts"]) >= 2:
            break
        time.sleep(0.01)
    assert proc.poll() is None, "the run finished before it could be killed; make the recipe larger"
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    return json.loads(manifest.read_text())


@pytest.fixture(scope="session")
def recipe_outputs(tmp_path_factory):
    """Every recipe of recipes/ run once per test process into NetCDF (about 9 s): the CF, ParaView and
    client tests read these files and never change them."""
    from stressfields import cli

    out = tmp_path_factory.mktemp("recipes")
    recipes = sorted((DATA.parents[1] / "recipes").glob("*.toml"))
    assert cli.main(["run", *map(str, recipes), "--out-dir", str(out), "-q"]) == 0
    return out


@pytest.fixture(autouse=True)
def _mpmath_precision_restored():
    """mpmath's working precision is global: a test that lowers it for a quick reference must not
    leave it lowered for the next test in the same process (references computed at 50 digits
    silently fell to 15)."""
    try:
        import mpmath
    except ImportError:
        yield
        return
    dps = mpmath.mp.dps
    yield
    mpmath.mp.dps = dps
