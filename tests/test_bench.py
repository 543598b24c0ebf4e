"""Smoke test of the benchmark machinery on a tiny configuration (no timing assertions)."""
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))   # the harness is not in the package
import harness as bench  # noqa: E402


@pytest.mark.slow          # ~2 s: CI runs it with the slow tests
def test_bench_tiny(tmp_path):
    ds, tp = bench.measure(bench.TINY, peers=False)
    assert tp == {}                                        # no throughput in the tiny run
    assert ds.time_per_point.dims == ("method", "order", "case")
    assert {"closed form", "quadrature", "series", "approximate eq. 18"} <= set(ds.method.values)
    for key in ("cpu_model", "cores", "numpy_version", "date"):
        assert ds.attrs[key]
    assert np.all(ds.time_per_point.fillna(1.0) > 0)

    # the integral route and the series get more accurate as rtol tightens (or stay at rounding:
    # several routes are exact for polynomial profiles at every order)
    for name in ("quadrature", "series"):
        err = ds.max_error.sel({"method": name}).sel(order=list(bench.RTOLS)).dropna("case", how="all")
        loose, tight = err.sel(order=bench.RTOLS[0]), err.sel(order=bench.RTOLS[-1])
        assert np.all(tight <= np.maximum(loose, 1e-14)), name
        assert np.all(loose <= 1e-3) and np.all(tight <= 1e-9)   # sanity, not the contract
    tab = ds.max_error.sel({"method": "quadrature", "case": "axisymmetric tabulated hyperboloid, partial slip: "
                                                             "six surface stresses"})
    assert float(tab.sel(order=1e-4)) > 100 * float(tab.sel(order=1e-12))

    bench.write(ds, tp, tmp_path)
    with xr.open_dataset(tmp_path / "results.nc") as back:
        assert back.sizes == ds.sizes and back.attrs["cpu_model"] == ds.attrs["cpu_model"]
    assert (tmp_path / "accuracy_vs_time.png").stat().st_size > 10_000
    assert "| case | method |" in (tmp_path / "README.md").read_text()


def test_peers_skip_without_contactmechanics(monkeypatch, capsys):
    import builtins

    real_import = builtins.__import__

    def fake_import(name, *args, **kwargs):
        if name.startswith("ContactMechanics"):
            raise ImportError("No module named 'ContactMechanics'")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", fake_import)
    assert bench._peer_solver() is None
    assert "peers skipped" in capsys.readouterr().err


def test_peer_solves_both_problems_and_converges_to_our_closed_forms():
    """ContactMechanics (optional `bench` extra) against our exact pressures: the grid error falls
    about linearly with the spacing, for Hertz and for the cone."""
    pytest.importorskip("ContactMechanics")
    solve = bench._peer_solver()
    for problem in bench.PEER_PROBLEMS:
        errors = []
        for n in (64, 128):
            _, p, exact = solve(n, problem)
            ok = np.isfinite(exact)
            errors.append(np.linalg.norm((p - exact)[ok]) / np.linalg.norm(exact[ok]))
        assert errors[1] < 0.6 * errors[0] and errors[1] < 0.005, (problem, errors)


def test_the_bench_command_loads_the_harness():
    """`stressfields bench` loads benchmarks/harness.py by path: its dataclasses need the module
    registered while it loads."""
    from stressfields.cli import bench_harness

    harness = bench_harness()
    assert harness.QUICK.points < harness.FULL.points and callable(harness.run)


#: made-up figures of a bench run's whole-process section (one 1e7-point pair)
FIGURES = {"process_1e+07_all_pipeline_s": 4.0, "process_1e+07_all_pipeline_cpu_s": 5.0,
           "process_1e+07_all_hand_s": 3.0, "process_1e+07_all_hand_cpu_s": 3.0,
           "process_1e+07_all_ratio_wall": 1.3, "process_1e+07_all_ratio_cpu": 1.6,
           "fixed_describe_s": 0.1, "fixed_import_s": 0.02, "fixed_run_1e4_s": 1.0, "fixed_bare_python_s": 0.02,
           "fixed_dependencies_s": 0.6, "hertz_mindlin_512_first_call_s": 0.8, "hertz_mindlin_512_first_run_s": 1.2,
           "sha256_bytes_per_s": 2.2e9, "disk_bytes_per_s": 1.76e9}


def test_the_whole_process_section_reports_the_floor_and_its_share():
    """The report's arithmetic on made-up figures: floor = kernels + 88 bytes at the disk rate + 88
    bytes through SHA-256, and its share of the CPU per point of the 1e7-point run."""
    text = "\n".join(bench._process_lines({**FIGURES, "kernels_alone_cpu_s_per_point": 200e-9}))
    # 200 + 50 + 40 = 290 ns against 500 ns per point
    assert "the kernels alone 200 ns" in text and "at the disk rate 50 ns, hashing them 40 ns: 290 ns" in text
    assert "1e+07 points 58%" in text


def test_the_first_call_line_says_whether_a_fortieth_of_the_peer_is_reachable():
    """The 40x first-call target against the import of xarray alone, on made-up figures: 9.2 s of
    the peer leave 0.23 s, less than a 0.25 s import; 12 s leave 0.30 s, more."""
    tp = {**FIGURES, "fixed_xarray_s": 0.25}
    short = "\n".join(bench._process_lines({**tp, "peer_512_first_s": 9.2}))
    assert "A fortieth of the peer's solve, 0.23 s, is less than a fresh process takes to import xarray " \
           "alone (0.25 s)" in short
    long = "\n".join(bench._process_lines({**tp, "peer_512_first_s": 12.0}))
    assert "0.30 s, is more than" in long
    assert "fortieth" not in "\n".join(bench._process_lines(tp))
