"""Smoke test of the benchmark machinery (no timing assertions)."""
from stressfields import bench


def test_bench_rows_and_dataset():
    cases = bench._axisymmetric(300, 1)
    rows = cases["axisymmetric power_law_n3: six surface stresses"]
    errors = [rows[("quadrature", rtol)][1] for rtol in bench.RTOLS]
    assert errors[0] > errors[-1]                      # a tighter rtol is more accurate
    assert all(err <= 10 * rtol for err, rtol in zip(errors, bench.RTOLS))
    cases.update(bench._peers())
    ds = bench._dataset(cases)
    assert ds.time_per_point.dims == ("route", "order", "case")
    assert "closed form" in ds.route.values and (ds.time_per_point > 0).sum() > 10
