"""The commands that compute nothing load no heavy library: `--help`, `list`, `describe`, `schema`
and `validate` import neither xarray nor dask (nor dask.distributed), and neither does
`import stressfields`."""
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("xarray", "dask", "distributed")

PROBE = """
import contextlib, io, sys
from stressfields.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    try:
        main({argv!r})
    except SystemExit:
        pass
print(sorted({{m.split('.')[0] for m in sys.modules if m.split('.')[0] in {heavy!r}}}))
"""


def heavy_modules(argv: list[str]) -> str:
    done = subprocess.run([sys.executable, "-c", PROBE.format(argv=argv, heavy=HEAVY)], cwd=ROOT,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout.strip()


@pytest.mark.parametrize("argv", [["--help"], ["list"], ["describe", "conical"], ["schema"]],
                         ids=lambda a: a[0])
def test_light_commands_import_no_heavy_library(argv):
    assert heavy_modules(argv) == "[]"


def test_validate_imports_no_heavy_library():
    assert heavy_modules(["validate", "recipes/cone_fig2_sigma_xx.toml"]) == "[]"


def test_import_stays_light():
    code = f"import sys, stressfields; print(any(m.split('.')[0] in {HEAVY!r} for m in sys.modules))"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.stdout.strip() == "False", done.stderr


def test_api_names_still_work():
    """In a fresh interpreter: `stressfields.scenarios` is also a subpackage, and once it is imported
    before `sf.scenarios` is first reached, the subpackage shadows the function."""
    code = ("import stressfields as sf; print('conical' in sf.scenarios() and '`conical`' in sf.describe('conical') "
            "and sf.generate({'scenario': 'conical', 'parameters': {'x': [0.5]}}).sigma_xx.shape == (1,) "
            "and 'conical' in sf.scenarios())")       # after the subpackage was imported too
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.stdout.strip() == "True", done.stderr
