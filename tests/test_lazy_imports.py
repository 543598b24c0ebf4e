"""The commands that compute nothing load no heavy library: `--help`, `list`, `describe`, `schema`
and `validate` (of a recipe whose check needs no kernel) import neither xarray nor dask (nor
dask.distributed) nor SciPy nor any physics kernel (the declarations read ``physics.names`` and the validity table
of ``physics.flags``), and
neither does `import stressfields`."""
import importlib
import statistics
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("xarray", "dask", "distributed", "scipy")
#: the physics modules a command that computes nothing may load: the shared names and the one table of
#: validity codes (the declarations build their flag attributes from it), nothing of a family
LIGHT_PHYSICS = ("stressfields.physics", "stressfields.physics.names", "stressfields.physics.flags")

PROBE = """
import contextlib, io, sys
from stressfields.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    try:
        main({argv!r})
    except SystemExit:
        pass
print(sorted({{m.split('.')[0] for m in sys.modules if m.split('.')[0] in {heavy!r}}}
             | {{m for m in sys.modules if m.startswith('stressfields.physics') and m not in {light!r}}}))
"""


def heavy_modules(argv: list[str]) -> str:
    done = subprocess.run([sys.executable, "-c", PROBE.format(argv=argv, heavy=HEAVY, light=LIGHT_PHYSICS)], cwd=ROOT,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout.strip()


@pytest.mark.parametrize("argv", [["--help"], ["list"], ["describe", "conical"], ["schema"]],
                         ids=lambda a: a[0])
def test_light_commands_import_no_heavy_library(argv):
    assert heavy_modules(argv) == "[]"


def test_validate_imports_no_heavy_library():
    assert heavy_modules(["validate", "recipes/cone_fig2_sigma_xx.toml"]) == "[]"


def test_validate_with_a_kernel_check_still_works():
    """A check that needs the kernels (a tabulated profile, method 'closed') imports them when it runs."""
    code = ("import sys; from stressfields.recipe import load; "
            "r = load({'scenario': 'axisymmetric', 'parameters': {'profile': 'tabulated', 'x': [0.5], "
            "'profile_r': [0.0, 0.5, 1.0, 1.5], 'profile_f': [0.0, 0.25, 1.0, 2.25]}, 'method': {'method': 'closed'}})"
            "\nprint('stressfields.physics.axisymmetric.profiles' in sys.modules)")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert "no closed form for profile = 'tabulated'" in done.stderr, done.stderr
    code = ("import sys; from stressfields.recipe import load; "
            "r = load({'scenario': 'axisymmetric', 'parameters': {'profile': 'tabulated', 'x': [0.5], "
            "'profile_r': [0.0, 0.5, 1.0, 1.5], 'profile_f': [0.0, 0.25, 1.0, 2.25]}}); "
            "print(r.scenario.name, 'stressfields.physics.axisymmetric.profiles' in sys.modules)")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert done.stdout.strip() == "axisymmetric True", done.stderr


def test_methods_and_names_are_the_route_tables():
    """The declarations read ``physics.names``; the route tables and entry points hold the same objects
    (one definition), so `scenario.methods` is each family's route table."""
    from stressfields.physics import names
    from stressfields.physics.axisymmetric import routes as ax_routes
    from stressfields.physics.graded import routes as gr_routes
    from stressfields.physics.wavy import routes as wv_routes
    from stressfields.scenarios import REGISTRY

    # the module: the package's `fields` is the entry-point function
    ax_fields = importlib.import_module("stressfields.physics.axisymmetric.fields")
    family = {"conical": ax_routes, "parabolic": ax_routes, "axisymmetric": ax_routes,
              "axisymmetric_history": ax_routes, "graded_normal": gr_routes, "graded_adhesive": gr_routes,
              "graded_tangential": gr_routes, "wavy": wv_routes}
    assert set(family) == set(REGISTRY)
    for name, routes in family.items():
        assert REGISTRY[name].methods is routes.METHODS, name
    assert ax_fields.STRESS is names.STRESS and ax_fields.PRINCIPAL is names.PRINCIPAL
    assert tuple(wv_routes.APPROXIMATE) == names.WAVY_APPROXIMATE_METHODS
    assert wv_routes.SERIES_METHODS is names.WAVY_SERIES_METHODS
    for name in ("conical", "axisymmetric_history"):
        defaults = REGISTRY[name].default_variables
        assert set(ax_fields.STRESS + ax_fields.PRINCIPAL) <= set(defaults)
        assert set(defaults) <= {v.name for v in REGISTRY[name].variables}


def test_describe_time_is_printed():
    """The wall time of `stressfields describe conical` (median of 5), printed, not asserted: the
    machine's load decides it (0.3 s on a loaded 2-core machine; 0.6 s when it imported the kernels)."""
    runs = []
    for _ in range(5):
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "stressfields", "describe", "conical"], cwd=ROOT,
                       capture_output=True, timeout=120, check=True)
        runs.append(time.perf_counter() - start)
    print(f"stressfields describe conical: {statistics.median(runs):.3f} s (median of 5)")


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


@pytest.mark.parametrize("scheduler", ["threads", "synchronous"])
def test_a_local_run_does_not_import_dask_distributed(tmp_path, scheduler):
    """Only `--scheduler ADDRESS` loads dask.distributed (when it is installed, dask and xarray would
    otherwise import it to look for a client); the run's file is the same, and the process is left
    as it was (an in-process run must not hide dask.distributed from what comes after)."""
    pytest.importorskip("distributed")
    recipe = tmp_path / "r.toml"
    recipe.write_text('scenario = "conical"\n[parameters]\nmu = 0.3\nux0 = 0.25\n'
                      'x = { start = -1.5, stop = 1.5, num = 101 }\ny = { start = -1.5, stop = 1.5, num = 99 }\n')
    code = ("import sys; from stressfields.cli import main\n"
            f"code = main(['run', {str(recipe)!r}, '-o', {str(tmp_path / 'o.nc')!r}, '-q', '--scheduler', "
            f"{scheduler!r}])\n"
            "print(code, 'distributed' in sys.modules, 'dask.distributed' in sys.modules)\n"
            "import dask.distributed\nprint('importable')")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert done.stdout.split("\n")[:2] == ["0 False False", "importable"], done.stderr
    from stressfields.output.formats import file_hash

    digest, stored = file_hash(tmp_path / "o.nc")
    assert digest == stored


def test_a_closed_form_run_loads_no_spline_or_optimizer(tmp_path):
    """scipy.interpolate (and the scipy.optimize it imports) serve tabulated profiles and peak
    searches only: a cone's surface fields load neither (their import is ~0.1 s of every run)."""
    recipe = tmp_path / "r.toml"
    recipe.write_text('scenario = "conical"\n[parameters]\nmu = 0.3\nux0 = 0.25\n'
                      'x = { start = -1.5, stop = 1.5, num = 11 }\ny = { start = -1.5, stop = 1.5, num = 9 }\n'
                      '[output]\nvariables = ["sigma_xx", "von_mises", "sigma_1", "dpdz"]\n')
    code = ("import sys; from stressfields.cli import main\n"
            f"code = main(['run', {str(recipe)!r}, '-o', {str(tmp_path / 'o.nc')!r}, '-q'])\n"
            "print(code, sorted(m for m in ('scipy.interpolate', 'scipy.optimize') if m in sys.modules))")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert done.stdout.strip() == "0 []", done.stderr
