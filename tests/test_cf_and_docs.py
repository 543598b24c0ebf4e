"""Every recipe's output is CF-1.8 clean; data_schema.md and the README's quick start stay true."""
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest
import xarray as xr

import stressfields as sf
from stressfields import cli
from stressfields.schema import document

ROOT = Path(__file__).resolve().parents[1]
RECIPES = sorted((ROOT / "recipes").glob("*.toml"))


@pytest.fixture(scope="module")
def outputs(tmp_path_factory):
    out = tmp_path_factory.mktemp("out")
    assert cli.main(["run", *map(str, RECIPES), "--out-dir", str(out), "-q"]) == 0
    return out


def cf_failures(path: Path) -> list:
    from compliance_checker.runner import CheckSuite, ComplianceChecker

    CheckSuite.load_all_available_checkers()
    report = path.with_suffix(".cf.json")
    _, checker_errors = ComplianceChecker.run_checker(str(path), ["cf:1.8"], 0, "lenient",
                                                      output_filename=str(report), output_format="json")
    result = json.loads(report.read_text())["cf:1.8"]
    failures = [("checker", "exceptions while checking", [])] if checker_errors else []
    for level in ("high_priorities", "medium_priorities", "low_priorities"):
        for item in result.get(level, []):
            if item["value"][0] < item["value"][1]:
                failures.append((level, item["name"], item["msgs"]))
    return failures


@pytest.mark.parametrize("recipe", RECIPES, ids=lambda p: p.stem)
def test_recipe_output_is_cf_clean(outputs, recipe):
    path = outputs / f"{recipe.stem}.nc"
    assert cf_failures(path) == []
    with xr.open_dataset(path) as ds:
        for name, var in ds.variables.items():
            assert "long_name" in var.attrs, name
            assert "units" in var.attrs or "flag_values" in var.attrs or var.dtype.kind in "OSU", name


def test_schema_file_is_in_sync():
    assert (ROOT / "data_schema.md").read_text() == document(), \
        "data_schema.md is stale: run `stressfields schema > data_schema.md`"


def quick_start() -> list[str]:
    text = (ROOT / "README.md").read_text()
    section = re.search(r"^## Quick start\n(.*?)(?=^## )", text, re.S | re.M).group(1)
    block = re.search(r"```(?:\w+)?\n(.*?)```", section, re.S).group(1)
    return [line for line in block.splitlines() if line.strip()]


def test_readme_quick_start_is_two_commands_and_ci_runs_the_second():
    commands = quick_start()
    assert len(commands) == 2
    assert "pytest" in commands[1] and "stressfields run" in commands[0]
    ci = (ROOT / ".ci" / "run").read_text()
    assert "Quick start" in ci  # .ci/run reads the test command from the README itself


def test_module_entry_point():
    done = subprocess.run([sys.executable, "-m", "stressfields", "list"], capture_output=True, text=True)
    assert done.returncode == 0 and "conical" in done.stdout


def test_accuracy_contract_is_written_once_and_quoted():
    """The contract lives in cf.ACCURACY_CONTRACT; the README and the schema quote it verbatim and
    every file carries it."""
    from stressfields.cf import ACCURACY_CONTRACT
    from stressfields.schema import document

    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert ACCURACY_CONTRACT in readme
    assert ACCURACY_CONTRACT in document()
    ds = sf.generate({"scenario": "conical", "parameters": {"x": [0.5]}})
    assert ds.attrs["stressfields_accuracy_contract"] == ACCURACY_CONTRACT
