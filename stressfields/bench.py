"""`stressfields bench`: accuracy against run time for every method, and pipeline throughput.

Not part of the tests. Times are medians of repeated runs on one core (numpy is single-threaded
here), taken after a warm-up call; errors are against the best reference available: the closed
form, or the same route converged at rtol = 1e-14. Writes results.nc (route x order x case),
accuracy_vs_time.png and README.md into ``out_dir``.
"""
from __future__ import annotations

import os
import platform
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import xarray as xr

from . import __version__

RTOLS = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)


def _median_time(fn, repeats: int) -> float:
    fn()                                   # warm-up: caches, first-call costs
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


# -- the cases: each returns {method: {order: (seconds per point, max error)}} -----------------

def _axisymmetric(points: int, repeats: int) -> dict:
    from .physics import axisymmetric as ax

    rng = np.random.default_rng(1)
    r, phi = 2.0 * np.sqrt(rng.random(points)), 2 * np.pi * rng.random(points)
    x, y = r * np.cos(phi), r * np.sin(phi)
    out = {}
    for label, profile in (("cone", ax.cone(1.0)), ("paraboloid", ax.paraboloid(1.0)),
                           ("power_law_n3", ax.power_law(1.0, 3.0))):
        c = ax.stick_radius(1.0, 0.3, 0.4, 0.25, profile)
        pm = float(ax.mean_pressure(1.0, profile))

        def run(method, rtol):
            s = ax.surface_stress(x, y, 1.0, c, 0.3, 0.4, profile, method=method, rtol=rtol)
            return np.stack([s[k] for k in sorted(s)])

        ref = run("closed", 1e-14) if profile.has_closed_form else run("quadrature", 1e-14)
        finite = np.isfinite(ref)
        rows = {}
        if profile.has_closed_form:
            rows[("closed form", 0.0)] = (_median_time(lambda: run("closed", 1e-10), repeats) / points, 0.0)
        for rtol in RTOLS:
            err = np.max(np.abs(run("quadrature", rtol) - ref)[finite]) / pm
            rows[("quadrature", rtol)] = (_median_time(lambda: run("quadrature", rtol), repeats) / points, err)
        out[f"axisymmetric {label}: six surface stresses"] = rows
    return out


def _graded(points: int, repeats: int) -> dict:
    from .physics.graded import normal as N
    from .physics.graded import profiles as P

    r = np.linspace(0.0, 0.999, points) * 1e-3
    kw = dict(k=0.5, nu=0.3, E0=1e9, c0=1e-3)
    n, A = P.parabolic(0.01)
    ref = N.pressure(r, 1e-3, n=n, A_n=A, **kw)
    scale = np.max(np.abs(ref))
    profile = P.PowerLaw(n, A)
    rows = {("closed form", 0.0): (_median_time(lambda: N.pressure(r, 1e-3, n=n, A_n=A, **kw), repeats) / points,
                                   0.0)}
    for rtol in RTOLS:
        def run():
            return N.pressure_quad(r, 1e-3, profile, rtol=rtol, **kw)
        rows[("quadrature", rtol)] = (_median_time(run, repeats) / points, np.max(np.abs(run() - ref)) / scale)
    return {"graded k = 0.5 paraboloid: pressure": rows}


def _wavy(points: int, repeats: int) -> dict:
    from .physics import wavy

    x = np.linspace(-1.0, 1.0, points)
    table = ((0.5, 0.01, 0.00075), (1, 11, 40))
    rows = {}
    ref, _ = wavy.pressure(x, 0.3, *table, periodic=False, rtol=1e-14)
    scale = np.max(np.abs(ref))
    for rtol in RTOLS:
        def run():
            return wavy.pressure(x, 0.3, *table, periodic=False, rtol=rtol)[0]
        rows[("series", rtol)] = (_median_time(run, repeats) / points, np.max(np.abs(run() - ref)) / scale)
    for name, fn in (("approximate eq. 18", wavy.approximate_pressure_eq18),
                     ("approximate eq. 20", wavy.approximate_pressure_eq20)):
        def run():
            return fn(x, 0.3, *table)
        rows[(name, 0.0)] = (_median_time(run, repeats) / points, np.max(np.abs(run() - ref)) / scale)
    return {"wavy f3 single indenter, 2a/lambda = 0.3: pressure": rows}


#: ContactMechanics 1.8.3 (CCG, FreeFFT, L = 3a), Hertz pressure, this kind of machine: grid n,
#: wall seconds for one solve, L2 pressure error. From shared/notes/peers.md §3.1, NOT measured by
#: this run: installing the peer's 40 packages is left to `pip install contactmechanics` by hand.
PEER_HERTZ = ((128, 0.648, 2.96e-3), (256, 3.55, 1.24e-3), (512, 27.3, 5.22e-4), (1024, 236.0, 3.32e-4))


def _peers() -> dict:
    rows = {("ContactMechanics FFT solver (published timings)", float(n)): (t / n ** 2, err)
            for n, t, err in PEER_HERTZ}
    return {"peer: Hertz pressure on an n x n grid": rows}


# -- throughput -----------------------------------------------------------------------------

def _throughput(quick: bool) -> dict[str, float]:
    import stressfields as sf
    from .physics import axisymmetric as ax
    from .physics.invariants import von_mises

    n = 1000 if quick else 2000
    recipe = {"scenario": "parabolic", "parameters": {
        "nu": 0.3, "mu": 0.3, "ux0": 0.25, "y": {"start": -1.5, "stop": 1.5, "num": n},
        "x": {"start": -1.5, "stop": 1.5, "num": n}},
        "output": {"variables": ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "sigma_yz",
                                 "von_mises"]}}
    with tempfile.TemporaryDirectory() as tmp:
        def pipeline():
            sf.to_netcdf(sf.generate(recipe), Path(tmp) / "p.nc", overwrite=True)

        def by_hand():
            import netCDF4

            xs = np.linspace(-1.5, 1.5, n)
            profile = ax.paraboloid(1.0)
            c = ax.stick_radius(1.0, 0.3, 0.3, 0.25, profile)
            pm = ax.mean_pressure(1.0, profile)
            with netCDF4.Dataset(Path(tmp) / "h.nc", "w") as nc:
                nc.createDimension("y", n)
                nc.createDimension("x", n)
                names = ["xx", "yy", "zz", "xy", "xz", "yz"]
                out = {k: nc.createVariable(k, "f8", ("y", "x")) for k in names + ["vm"]}
                rows = max(1, 1_000_000 // n)
                for start in range(0, n, rows):
                    yy = xs[start:start + rows, None]
                    s = ax.surface_stress(xs[None, :], yy, 1.0, c, 0.3, 0.3, profile)
                    for k in names:
                        out[k][start:start + rows] = s[k] / pm
                    out["vm"][start:start + rows] = von_mises(*(s[k] / pm for k in names))

        t_pipe = _median_time(pipeline, 3)
        t_hand = _median_time(by_hand, 3)

    from .physics import axisymmetric as ax2

    pts = 200_000
    rng = np.random.default_rng(2)
    x, y = rng.uniform(-1.2, 1.2, pts), rng.uniform(-1.2, 1.2, pts)
    prof = ax2.power_law(1.0, 3.0)
    c = ax2.stick_radius(1.0, 0.3, 0.4, 0.25, prof)
    t_quad = _median_time(lambda: ax2.surface_stress(x, y, 1.0, c, 0.3, 0.4, prof, method="quadrature",
                                                     rtol=1e-10), 3)
    hm = {"scenario": "parabolic", "parameters": {
        "nu": 0.3, "mu": 0.3, "ux0": 0.25, "y": {"start": -1.5, "stop": 1.5, "num": 512},
        "x": {"start": -1.5, "stop": 1.5, "num": 512}}}
    t_hm = _median_time(lambda: sf.generate(hm).compute(), 3)
    return {"points": float(n * n), "pipeline_s": t_pipe, "hand_s": t_hand, "pipeline_over_hand": t_pipe / t_hand,
            "quadrature_points_per_s": pts / t_quad, "hertz_mindlin_512_all_fields_s": t_hm}


# -- output ---------------------------------------------------------------------------------

def run(out_dir: Path, quick: bool = False, peers: bool = False) -> int:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    points, repeats = (2000, 3) if quick else (20000, 7)
    cases: dict = {}
    cases.update(_axisymmetric(points, repeats))
    cases.update(_graded(points // 10, repeats))
    cases.update(_wavy(points, repeats))
    if peers:
        cases.update(_peers())
    ds = _dataset(cases)
    throughput = _throughput(quick)
    ds.attrs.update({f"throughput_{k}": v for k, v in throughput.items()})
    ds.to_netcdf(out_dir / "results.nc")
    _chart(ds, out_dir / "accuracy_vs_time.png")
    (out_dir / "README.md").write_text(_report(ds, throughput, quick))
    print(f"wrote {out_dir}/results.nc, accuracy_vs_time.png, README.md", file=sys.stderr)
    return 0


def _dataset(cases: dict) -> xr.Dataset:
    methods = sorted({m for rows in cases.values() for m, _ in rows})
    orders = sorted({o for rows in cases.values() for _, o in rows})
    names = list(cases)
    t = np.full((len(methods), len(orders), len(names)), np.nan)
    e = np.full_like(t, np.nan)
    for k, name in enumerate(names):
        for (m, o), (sec, err) in cases[name].items():
            t[methods.index(m), orders.index(o), k] = sec
            e[methods.index(m), orders.index(o), k] = err
    return xr.Dataset(
        {"time_per_point": (("route", "order", "case"), t,
                            {"units": "s", "long_name": "median wall time per point, one core"}),
         "error": (("route", "order", "case"), e,
                   {"units": "1", "long_name": "max error relative to the field's scale, against the best reference"})},
        coords={"route": ("route", np.array(methods, dtype=object), {"long_name": "method (route)"}),
                "order": ("order", np.array(orders), {"units": "1", "long_name":
                          "requested rtol (quadrature, series) or grid size n (peer solver); 0: none"}),
                "case": ("case", np.array(names, dtype=object), {"long_name": "benchmark case"})},
        attrs={"title": "stressfields accuracy against run time", "source": f"stressfields {__version__}",
               "machine": f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
                          f"Python {platform.python_version()}, numpy {np.__version__}",
               "date": time.strftime("%Y-%m-%d")})


def _chart(ds: xr.Dataset, path: Path) -> None:
    """One log-log chart: error against time per point, a curve per route and case, peers included."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axp = plt.subplots(figsize=(10, 6.5))
    markers = "osD^v<>ph*"
    for i, case in enumerate(ds.case.values):
        sub = ds.sel(case=case)
        for j, m in enumerate(ds.route.values):
            t = sub.time_per_point.sel(route=m).values
            e = np.maximum(sub.error.sel(route=m).values, 1e-16)   # exact to rounding: drawn at 1e-16
            ok = np.isfinite(t)
            if ok.any():
                axp.loglog(t[ok], e[ok], marker=markers[j % len(markers)], ms=5, lw=1,
                           color=f"C{i}", label=f"{case} — {m}")
    axp.set_xlabel("time per point [s] (median, one core)")
    axp.set_ylabel("max error relative to the field's scale")
    axp.set_title("stressfields: accuracy against run time (colour: case; marker: route)", fontsize=10)
    axp.grid(True, which="both", alpha=0.3)
    axp.legend(fontsize=6.5, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def _report(ds: xr.Dataset, tp: dict, quick: bool) -> str:
    lines = ["# Benchmark: accuracy against run time", "",
             f"Generated by `stressfields bench{' --quick' if quick else ''}` on {ds.attrs['date']}, "
             f"{ds.attrs['machine']}. Medians of repeated runs; this machine is shared, so read ratios.",
             "", "![accuracy vs time](accuracy_vs_time.png)", "",
             "| case | method | rtol / grid | time per point [s] | max relative error |", "|---|---|---|---|---|"]
    for case in ds.case.values:
        for m in ds.route.values:
            for o in ds.order.values:
                t = float(ds.time_per_point.sel(case=case, route=m, order=o))
                if np.isfinite(t):
                    e = float(ds.error.sel(case=case, route=m, order=o))
                    lines.append(f"| {case} | {m} | {o:g} | {t:.3g} | {e:.2g} |")
    lines += ["", "## Throughput", "",
              f"- Full pipeline (recipe -> dask -> NetCDF) for the six Hertz–Mindlin surface stresses and von "
              f"Mises on {tp['points']:.0f} points: {tp['pipeline_s']:.2f} s, against {tp['hand_s']:.2f} s for a "
              f"hand-written blocked NumPy loop calling the same kernels plus a plain netCDF4 write: ratio "
              f"{tp['pipeline_over_hand']:.2f} (target <= 1.3).",
              f"- Quadrature route at rtol 1e-10 (power law n = 3, six components, one call): "
              f"{tp['quadrature_points_per_s']:.3g} points per second (target >= 1e6 per core).",
              f"- All surface fields (six components, von Mises, principal stresses, dp/dz, stick radius, region) "
              f"of a 512 x 512 Hertz–Mindlin partial-slip case: {tp['hertz_mindlin_512_all_fields_s']:.2f} s, "
              f"against {PEER_HERTZ[2][1]:g} s for ContactMechanics to solve the pressure alone on 512 x 512 to "
              f"{PEER_HERTZ[2][2]:.1e} (published timing, not this run): ratio "
              f"1/{PEER_HERTZ[2][1] / tp['hertz_mindlin_512_all_fields_s']:.0f} (target <= 1/30).", ""]
    return "\n".join(lines)
