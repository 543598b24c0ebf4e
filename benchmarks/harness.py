"""The benchmark harness: accuracy against run time for every method, peers, and pipeline
throughput. Run from a clone as `stressfields bench` or `python benchmarks/run.py`.

Not part of the tests. Every time is the median of repeated runs after a warm-up call (caches,
first-call costs); numpy runs the kernels on one core. Errors are against the best reference
available: the closed form (whose own error is quoted against the integral route at
rtol = 1e-14), or else the same route converged at rtol = 1e-14. An error is
``max |value - reference| / max(scale, |reference|)``, the library's own accuracy contract
(``|error| <= rtol * max(1, |value|)`` in units of the field's scale), so that fields which are
unbounded near a contact edge are judged relatively there and absolutely elsewhere.

Writes ``results.nc`` (method x order x case), ``accuracy_vs_time.png`` and ``README.md`` into
``out_dir``. ContactMechanics (the peer FFT solver, ``pip install 'stressfields[bench]'``) is
imported only inside :func:`_peers`, and only with ``--peers``.
"""
from __future__ import annotations

import os
import platform
import statistics
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr

from stressfields import __version__

RTOLS = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)
REF_RTOL = 1e-14
CLOSED, QUAD, SERIES = "closed form", "quadrature", "series"
AUTO_WAVY = "auto: non-periodic series where the periodic correction < rtol"
PEER = "ContactMechanics (FFT half-space, CCG)"


@dataclass(frozen=True)
class Config:
    points: int            # field points per accuracy case (the graded integral route gets 1/20)
    repeats: int           # timed runs per measurement (the median is kept)
    peer_grids: tuple      # n of the n x n ContactMechanics grids
    pipeline_n: int        # the pipeline-throughput grid is pipeline_n x pipeline_n
    throughput: bool = True
    #: n of the n x n whole-process runs against the hand loop (1e6, 1e7 points; with the
    #: environment variable STRESSFIELDS_BENCH_BIG=1 also 1e8, which takes ~10 minutes)
    process_n: tuple = (1000, 3163)


FULL = Config(points=20_000, repeats=7, peer_grids=(128, 256, 512, 1024), pipeline_n=2000)
QUICK = Config(points=4_000, repeats=3, peer_grids=(64, 128, 256), pipeline_n=1000, process_n=(1000,))
TINY = Config(points=300, repeats=1, peer_grids=(32,), pipeline_n=100, throughput=False)   # smoke test


def _median_time(fn, repeats: int) -> float:
    fn()                                   # warm-up: caches, first-call costs
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def _wall_cpu(fn, repeats: int) -> tuple[float, float]:
    """Median wall and CPU (this process, all threads) seconds of ``fn``, after a warm-up."""
    fn()
    walls, cpus = [], []
    for _ in range(repeats):
        w, c = time.perf_counter(), time.process_time()
        fn()
        walls.append(time.perf_counter() - w)
        cpus.append(time.process_time() - c)
    return statistics.median(walls), statistics.median(cpus)


def _error(value, ref, scale) -> float:
    value, ref = np.asarray(value, dtype=float), np.asarray(ref, dtype=float)
    ok = np.isfinite(ref)       # +-inf/NaN at singular points are exact limits, not compared
    return float(np.max(np.abs(value - ref)[ok] / np.maximum(scale, np.abs(ref[ok]))))


def _rows(ref, scale, variants, points, repeats, independent=None) -> dict:
    """{(method, order): (seconds per point, error)} for variants [(method, order, fn)].

    A closed form is the reference itself; its error is quoted against ``independent`` (the
    integral route converged at rtol 1e-14), which bounds the rounding of both."""
    return {(m, o): (_median_time(fn, repeats) / points,
                     _error(fn(), independent if m == CLOSED and independent is not None else ref, scale))
            for m, o, fn in variants}


# -- the cases: each returns {case: {(method, order): (seconds per point, error)}} ----------------

def _disk_points(points: int, radius: float, seed: int):
    """Uniform random points in a disk: contact, slip annulus and outside, never on a circle."""
    rng = np.random.default_rng(seed)
    r, phi = radius * np.sqrt(rng.random(points)), 2 * np.pi * rng.random(points)
    return r * np.cos(phi), r * np.sin(phi)


def _axisymmetric(cfg: Config) -> dict:
    from stressfields.physics import axisymmetric as ax

    pts = _disk_points(cfg.points, 1.5, 1)
    nu, mu, ux0 = 0.3, 0.4, 0.25          # partial slip: stick radius c/a between 0.6 and 0.9
    # a spline through 25 samples of a blunted cone (recipes/tabulated_hyperboloid.toml): no
    # polynomial structure for the Gauss rules to be exact on, so rtol really trades accuracy
    rs = np.linspace(0.0, 1.2, 25)
    hyperboloid = ax.tabulated(rs, np.sqrt(rs ** 2 + 0.04) - 0.2)
    out = {}
    for label, profile in (("cone", ax.cone(1.0)), ("paraboloid", ax.paraboloid(1.0)),
                           ("power law n = 3", ax.power_law(1.0, 3.0)), ("tabulated hyperboloid", hyperboloid)):
        c = ax.stick_radius(1.0, nu, mu, ux0, profile)
        pm = float(ax.mean_pressure(1.0, profile))     # a = 1: dp/dz scale p_m / a = p_m
        # the spline route costs ~2e-5 s per point with 25 samples (its rules split at every knot): fewer points
        x, y = (v[: max(20, cfg.points // 20)] for v in pts) if profile.kind == "tabulated" else pts

        def stress(method, rtol, profile=profile, c=c, x=x, y=y):
            s = ax.surface_stress(x, y, 1.0, c, nu, mu, profile, method=method, rtol=rtol)
            return np.stack([s[k] for k in ax.COMPONENTS])

        def dpdz(method, rtol, profile=profile, c=c, x=x, y=y):
            return ax.surface_dpdz(x, y, 1.0, c, nu, mu, profile, method=method, rtol=rtol)

        for field, fn in (("six surface stresses", stress), ("dp/dz", dpdz)):
            closed = profile.has_closed_form
            ref = fn("closed", REF_RTOL) if closed else fn("quadrature", REF_RTOL)
            variants = [(CLOSED, 0.0, lambda fn=fn: fn("closed", REF_RTOL))] if closed else []
            variants += [(QUAD, rtol, lambda fn=fn, rtol=rtol: fn("quadrature", rtol)) for rtol in RTOLS]
            indep = fn("quadrature", REF_RTOL) if closed else None
            out[f"axisymmetric {label}, partial slip: {field}"] = _rows(ref, pm, variants, x.size, cfg.repeats, indep)
    return out


#: the finest rtol of the 1-D routes below the surface (their reference)
INTERIOR_REF_RTOL = 1e-12


def _interior(cfg: Config) -> dict:
    """Below the surface: the six stresses at random points r <= 2a, 1e-3 a <= z <= 3a, every
    route; reference the closed form (its own error against the 1-D route at rtol 1e-12), else
    the 1-D route at rtol 1e-12."""
    from stressfields.physics import axisymmetric as ax

    m = max(20, cfg.points // 4)          # the 1-D route runs at ~1e4-1e5 points per second
    x, y = _disk_points(m, 2.0, 5)
    z = np.geomspace(1e-3, 3.0, m)[np.random.default_rng(6).permutation(m)]
    nu, mu, ux0 = 0.3, 0.4, 0.25
    out = {}
    for label, profile in (("paraboloid", ax.paraboloid(1.0)), ("cone", ax.cone(1.0)),
                           ("power law n = 3", ax.power_law(1.0, 3.0))):
        c = float(ax.stick_radius(1.0, nu, mu, ux0, profile))
        pm = float(ax.mean_pressure(1.0, profile))
        for load in ("normal", "partial slip"):
            def stress(method, rtol, profile=profile, c=c, load=load):
                s = ax.interior_stress(x, y, z, 1.0, nu, profile, method=method, rtol=rtol)
                if load != "normal":
                    t = ax.interior_stress_tangential(x, y, z, 1.0, c, nu, mu, profile, method=method, rtol=rtol)
                    s = {k: s[k] + t[k] for k in s}
                return np.stack([s[k] for k in ax.COMPONENTS])

            closed = ax.has_interior_closed_form(profile.kind, getattr(profile, "n", None),
                                                 tangential=load != "normal")
            quad = stress("quadrature", INTERIOR_REF_RTOL)
            ref = stress("closed", INTERIOR_REF_RTOL) if closed else quad
            variants = [(CLOSED, 0.0, lambda fn=stress: fn("closed", INTERIOR_REF_RTOL))] if closed else []
            variants += [(QUAD, rt, lambda fn=stress, rt=rt: fn("quadrature", rt)) for rt in RTOLS
                         if rt >= INTERIOR_REF_RTOL]
            out[f"below the surface, {label}, {load}: six stresses"] = _rows(
                ref, pm, variants, m, cfg.repeats, quad if closed else None)
    return out


#: the two problems set beside the peer, on the square |x|, |y| <= 1.5 a it solves on (a = E* = 1):
#: name -> (profile, surface height of the indenter, normal force, exact pressure p(r), mean pressure)
PEER_PROBLEMS = {
    "Hertz pressure (paraboloid, square of side 3a)": (
        "paraboloid", lambda r: -r ** 2 / 2.0, 4.0 / 3.0,
        lambda r: 2.0 / np.pi * np.sqrt(np.clip(1.0 - r ** 2, 0.0, None)), 4.0 / (3.0 * np.pi)),
    "cone pressure (square of side 3a)": (       # tan(theta) = 1: p = (1/2) arccosh(a/r), log-singular tip
        "cone", lambda r: -r, np.pi / 2.0,
        lambda r: 0.5 * np.arccosh(np.clip(1.0 / r, 1.0, None)), 0.5),        # +inf on the axis
}
HERTZ = next(iter(PEER_PROBLEMS))


def _pressure_ours(cfg: Config) -> dict:
    """Our pressure p = -sigma_zz on the peer's square, closed form and integral route."""
    from stressfields.physics import axisymmetric as ax

    rng = np.random.default_rng(3)
    x, y = rng.uniform(-1.5, 1.5, cfg.points), rng.uniform(-1.5, 1.5, cfg.points)
    out = {}
    for name, (kind, *_rest) in PEER_PROBLEMS.items():
        prof = getattr(ax, kind)(1.0)
        scale = float(ax.mean_pressure(1.0, prof))

        def p(method, rtol, prof=prof):
            return ax.surface_stress(x, y, 1.0, 1.0, 0.3, 0.0, prof, components=("zz",), method=method,
                                     rtol=rtol)["zz"]

        variants = [(CLOSED, 0.0, lambda p=p: p("closed", REF_RTOL))]
        variants += [(QUAD, rtol, lambda rtol=rtol, p=p: p("quadrature", rtol)) for rtol in RTOLS]
        out[name] = _rows(p("closed", REF_RTOL), scale, variants, x.size, cfg.repeats, p("quadrature", REF_RTOL))
    return out


def _graded(cfg: Config) -> dict:
    from stressfields.physics.graded import normal as N
    from stressfields.physics.graded import profiles as P
    from stressfields.physics.graded import tangential as T

    m = max(20, cfg.points // 20)          # the integral route costs ~1e-4 s per point
    k, nu, E0, c0, a = 0.5, 0.3, 1e9, 1e-3, 1e-3
    kw = dict(k=k, nu=nu, E0=E0, c0=c0)
    n, A = P.parabolic(0.01)
    prof = P.PowerLaw(A=A, n=n)
    r_in, r_all = np.linspace(0.0, 0.999, m) * a, np.linspace(0.01, 3.0, m) * a
    radii = np.linspace(0.1, 2.0, m) * a
    loads = np.linspace(0.01, 0.99, max(5, m // 10))   # one bisection (~2 ms) per load on the integral route
    tang = dict(k=k, nu=nu, mu=0.3, E0=E0)
    cases = {   # name: (points, closed, quadrature(rtol), scale of the field)
        "pressure": (m, lambda: N.pressure(r_in, a, n=n, A_n=A, **kw),
                     lambda rt: N.pressure_quad(r_in, a, prof, rtol=rt, **kw), None),
        "surface displacement": (m, lambda: N.surface_displacement(r_all, a, k=k, n=n, A_n=A),
                                 lambda rt: N.surface_displacement_quad(r_all, a, prof, k=k, rtol=rt), None),
        "normal force F(a)": (m, lambda: N.normal_force(radii, n=n, A_n=A, **kw),
                              lambda rt: N.normal_force_quad(radii, prof, rtol=rt, **kw), 0.0),
        "tangential displacement (partial slip)": (
            loads.size, lambda: T.tangential_displacement(a, loads, n=n, A_n=A, **tang),
            lambda rt: T.tangential_displacement_quad(a, loads, prof, c0=c0, rtol=rt, **tang), 0.0),
    }
    out = {}
    for name, (pts, closed, quad, scale) in cases.items():
        ref = closed()
        # fields: scale = their maximum; global relations (scale 0): relative error per point
        scale = float(np.max(np.abs(ref))) if scale is None else scale
        variants = [(CLOSED, 0.0, closed)] + [(QUAD, rt, lambda rt=rt, q=quad: q(rt)) for rt in RTOLS]
        out[f"graded k = 0.5 paraboloid: {name}"] = _rows(ref, scale, variants, pts, cfg.repeats, quad(REF_RTOL))
    out.update(_graded_interior(cfg))
    return out


def _graded_interior(cfg: Config) -> dict:
    """The 2-D quadrature of the Holl point-load field below the surface (physics.graded.holl) at k = 0,
    where its kernel is Boussinesq's at nu = 1/2: held against the closed-form Hertz field at nu = 1/2
    (an independent route), stresses per unit p0, points r/a in [0, 2], z/a in [0.01, 2]."""
    from stressfields.physics.axisymmetric.interior_hertz import hertz_unit
    from stressfields.physics.graded import holl

    m = max(40, cfg.points // 10)
    rng = np.random.default_rng(29)
    r, z = 2.0 * rng.random(m), 10.0 ** rng.uniform(-2.0, np.log10(2.0), m)
    h = hertz_unit(r, 0.0 * r, z, 0.5)
    ref = np.concatenate([h["xx"], h["yy"], h["zz"], h["xz"]])

    def run(rt):
        s = holl.disc_stress(r, z, 0.0, 0.5, rt)
        return np.concatenate([s["rr"], s["tt"], s["zz"], s["rz"]])

    variants = [(QUAD, rt, lambda rt=rt: run(rt)) for rt in RTOLS]
    return {"graded below the surface (Holl 2-D route, k = 0 vs Hertz nu = 1/2): four stresses":
            _rows(ref, 1.0, variants, m, cfg.repeats)}


def _wavy(cfg: Config) -> dict:
    from stressfields.physics import wavy

    x = np.linspace(-1.0, 1.0, cfg.points)
    f3 = ((0.5, 0.01, 0.00075), (1, 11, 40))      # Tsukanov's f3: three harmonics
    out = {}
    # periodic, one harmonic: Westergaard's closed form p/p* = 2 cos(h s) sqrt(sin^2 h - sin^2(h s)),
    # h = pi a / lambda, is the independent reference
    h = 0.5 * np.pi * 0.5
    west = 2 * np.cos(h * x) * np.sqrt(np.clip(np.sin(h) ** 2 - np.sin(h * x) ** 2, 0.0, None))
    for name, periodic, table, two_a, ref in (
            ("wavy periodic, one harmonic (Westergaard), 2a/lambda = 0.5: pressure", True, ((0.5,), (1,)), 0.5, west),
            ("wavy periodic f3, 2a/lambda = 0.5: pressure", True, f3, 0.5, None),
            ("wavy f3 single indenter, 2a/lambda = 0.3: pressure", False, f3, 0.3, None)):
        def run(rtol, periodic=periodic, table=table, two_a=two_a):
            return wavy.pressure(x, two_a, *table, periodic=periodic, rtol=rtol)[0]

        ref = run(REF_RTOL) if ref is None else ref
        variants = [(SERIES, rt, lambda rt=rt, run=run: run(rt)) for rt in RTOLS]
        if not periodic:     # the paper's approximations exist for the single indenter only
            variants += [(f"approximate eq. {eq}", 0.0, lambda fn=fn, table=table, two_a=two_a: fn(x, two_a, *table))
                         for eq, fn in ((18, wavy.approximate_pressure_eq18), (20, wavy.approximate_pressure_eq20))]
        out[name] = _rows(ref, float(np.max(np.abs(ref))), variants, x.size, cfg.repeats)
    # a narrow periodic contact: method auto takes the cheaper non-periodic series wherever the
    # periodic correction (~0.41 (2a/lambda)^2 of the pressure) is below rtol and the contact has
    # enough points to pay for the test; Westergaard is the reference
    x = np.linspace(-1.0, 1.0, max(cfg.points, wavy.contact.SUBSTITUTE_MIN_POINTS))
    h = 0.5 * np.pi * 1e-3
    west = 2 * np.cos(h * x) * np.sqrt(np.clip(np.sin(h) ** 2 - np.sin(h * x) ** 2, 0.0, None))
    variants = [(m, rt, lambda rt=rt, sub=sub: wavy.pressure(x, 1e-3, (0.5,), (1,), periodic=True, rtol=rt,
                                                             substitute=sub)[0])
                for m, sub in ((SERIES, False), (AUTO_WAVY, True)) for rt in RTOLS]
    out["wavy periodic, one harmonic (Westergaard), 2a/lambda = 0.001: pressure"] = _rows(
        west, float(np.max(west)), variants, x.size, cfg.repeats)
    out.update(_wavy_interior(cfg))
    return out


def _wavy_interior(cfg: Config) -> dict:
    """sigma_zz below the surface, 11 harmonics, x over two contact widths and z from 0 to 3a (the
    target: >= 1e6 points per CPU second; the periodic series at depth shortens as rtol loosens)."""
    from stressfields.physics import wavy

    rng = np.random.default_rng(11)
    x, z = rng.uniform(-2.0, 2.0, cfg.points), rng.uniform(0.0, 3.0, cfg.points)
    table = ([1.0] + [0.1 / i ** 2 for i in range(2, 12)], list(range(1, 12)))
    out = {}
    for name, periodic in (("periodic", True), ("single indenter", False)):
        def run(rtol, periodic=periodic):
            values = wavy.contact.subsurface(("sigma_zz",), x, z, 0.6, *table, periodic=periodic, rtol=rtol)[0]
            return values["sigma_zz"]

        ref = run(REF_RTOL)
        variants = [(SERIES, rt, lambda rt=rt, run=run: run(rt)) for rt in RTOLS]
        out[f"wavy {name}, 11 harmonics, 2a/lambda = 0.6: sigma_zz below the surface"] = _rows(
            ref, float(np.max(np.abs(ref))), variants, x.size, cfg.repeats)
    return out


# -- the peer: a numerical half-space solver on the same Hertz problem ---------------------------

def _peer_solver():
    """ContactMechanics' solve of a PEER_PROBLEMS entry on an n x n grid, or None when it is not installed."""
    try:
        import warnings

        warnings.filterwarnings("ignore", module="ContactMechanics|SurfaceTopography|NuMPI|muGrid|muFFT")
        from ContactMechanics import FreeFFTElasticHalfSpace, make_system
        from SurfaceTopography import Topography
    except ImportError as exc:
        print(f"bench: peers skipped, ContactMechanics is not installed ({exc}); "
              "pip install 'stressfields[bench]'", file=sys.stderr)
        return None

    def solve(n: int, problem: str = HERTZ, side: float = 3.0):
        """Free (non-periodic) boundaries on a square of side 3a, nodes on the axis (the peer's own
        documented set-up for an isolated indenter), E* = a = 1. Returns (seconds, p, p_exact)."""
        _kind, height, force, exact, _pm = PEER_PROBLEMS[problem]
        dx = side / n
        xs = (np.arange(n) - n // 2) * dx
        X, Y = np.meshgrid(xs, xs, indexing="ij")
        R = np.hypot(X, Y)
        start = time.perf_counter()
        system = make_system(substrate=FreeFFTElasticHalfSpace((n, n), 1.0, (side, side)),
                             surface=Topography(height(R), (side, side)))
        result = system.minimize_proxy(external_force=force, pentol=1e-10)
        seconds = time.perf_counter() - start
        if not result.success:
            raise RuntimeError(f"ContactMechanics did not converge on {n}^2 ({problem}): {result.message}")
        with np.errstate(divide="ignore"):
            return seconds, result.jac / dx ** 2, np.where(R < 1.0, exact(R), 0.0)

    return solve


def _peers(cfg: Config, solve) -> tuple[dict, dict]:
    solve(32)                              # warm-up: FFT plans, lazy imports
    cases, l2 = {}, {}
    for problem, (*_rest, pm) in PEER_PROBLEMS.items():
        rows = cases.setdefault(problem, {})
        for n in cfg.peer_grids:
            seconds, p, exact = solve(n, problem)
            if n <= 256:                   # one 1024^2 solve takes a minute: repeat only cheap grids
                seconds = statistics.median([solve(n, problem)[0] for _ in range(cfg.repeats)])
            rows[(PEER, float(n))] = (seconds / n ** 2, _error(p, exact, pm))
            ok = np.isfinite(exact)        # the cone tip node: p_exact = +inf
            l2[(problem, n)] = float(np.linalg.norm((p - exact)[ok]) / np.linalg.norm(exact[ok]))
            print(f"bench: ContactMechanics {problem}, {n}^2: {seconds:.2f} s, max error "
                  f"{rows[(PEER, float(n))][1]:.2g}, L2 {l2[(problem, n)]:.2g}", file=sys.stderr)
    return cases, l2


# -- throughput -------------------------------------------------------------------------------

STRESS = ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "sigma_yz")


def _pipeline_vs_hand(n: int, repeats: int) -> dict:
    """recipe -> generate -> to_netcdf against a hand-written blocked loop over the same kernels
    plus a plain netCDF4 write, for the six Hertz-Mindlin stresses and von Mises on n x n points."""
    import netCDF4

    import stressfields as sf
    from stressfields.physics import axisymmetric as ax
    from stressfields.physics.invariants import von_mises

    nu, mu, ux0 = 0.3, 0.3, 0.25
    grid = {"start": -1.5, "stop": 1.5, "num": n}
    recipe = {"scenario": "parabolic", "parameters": {"nu": nu, "mu": mu, "ux0": ux0, "y": grid, "x": grid},
              "output": {"variables": list(STRESS) + ["von_mises"]}}
    with tempfile.TemporaryDirectory() as tmp:
        def pipeline():
            sf.to_netcdf(sf.generate(recipe), Path(tmp) / "p.nc", overwrite=True)

        def by_hand():
            xs = np.linspace(-1.5, 1.5, n)
            prof = ax.paraboloid(1.0)
            c = ax.stick_radius(1.0, nu, mu, ux0, prof)
            pm = ax.mean_pressure(1.0, prof)
            with netCDF4.Dataset(Path(tmp) / "h.nc", "w") as nc:
                nc.createDimension("y", n)
                nc.createDimension("x", n)
                out = {k: nc.createVariable(k, "f8", ("y", "x")) for k in STRESS + ("von_mises",)}
                rows = max(1, 1_000_000 // n)          # ~1e6-point blocks, like the pipeline's chunks
                for start in range(0, n, rows):
                    s = ax.surface_stress(xs[None, :], xs[start:start + rows, None], 1.0, c, nu, mu, prof)
                    s = [s[k[-2:]] / pm for k in STRESS]
                    for k, v in zip(STRESS, s):
                        out[k][start:start + rows] = v
                    out["von_mises"][start:start + rows] = von_mises(*s)

        t_pipe, c_pipe = _wall_cpu(pipeline, repeats)
        t_hand, c_hand = _wall_cpu(by_hand, repeats)
    return {"pipeline_points": float(n * n), "pipeline_s": t_pipe, "pipeline_cpu_s": c_pipe,
            "hand_s": t_hand, "hand_cpu_s": c_hand, "pipeline_over_hand": t_pipe / t_hand,
            "pipeline_over_hand_cpu": c_pipe / c_hand}


def _quadrature_rate(repeats: int) -> dict:
    """Points per CPU second of the integral route at rtol 1e-10 (six stress components)."""
    from stressfields.physics import axisymmetric as ax

    pts = 200_000
    x, y = _disk_points(pts, 1.5, 2)
    out = {}
    for label, prof in (("paraboloid", ax.paraboloid(1.0)), ("power_law_n3", ax.power_law(1.0, 3.0))):
        c = ax.stick_radius(1.0, 0.3, 0.4, 0.25, prof)
        wall, cpu = _wall_cpu(lambda: ax.surface_stress(x, y, 1.0, c, 0.3, 0.4, prof, method="quadrature",
                                                        rtol=1e-10), repeats)
        out[f"quadrature_{label}_points_per_s"] = pts / wall
        out[f"quadrature_{label}_points_per_cpu_s"] = pts / cpu
    out["quadrature_points_per_cpu_s"] = min(v for k, v in out.items() if k.endswith("per_cpu_s"))
    return out


def batches_rate(repeats: int, n: int = 1_048_576, batch_size: int = 65_536) -> dict:
    """Samples per second of `sf.batches` for Hertz below the surface (six stresses and the validity
    flag at scrambled Sobol points of x, y in [-2a, 2a], z in [0, 3a]; one thread: the kernels are
    NumPy, called in the caller's thread): medians of ``repeats`` passes over ``n`` samples, per wall
    and per CPU second (a loaded machine shares its cores: the CPU figure is the one core's rate)."""
    import stressfields as sf

    box = {"n": n, "method": "sobol", "x": [-2.0, 2.0], "y": [-2.0, 2.0], "z": [0.0, 3.0]}
    recipe = {"scenario": "parabolic", "parameters": {"nu": 0.3}, "points": {"sample": box},
              "output": {"variables": list(STRESS)}}
    stream = sf.batches(recipe, batch_size, seed=0)
    wall, cpu = _wall_cpu(lambda: sum(len(inputs) for inputs, _ in stream), repeats)
    return {"batches_hertz_interior_samples_per_s": n / wall, "batches_hertz_interior_samples_per_cpu_s": n / cpu}


def _hertz_mindlin_512(repeats: int) -> dict:
    """All surface fields of a 512^2 Hertz-Mindlin partial-slip case, through the API, at rtol 1e-10,
    on the closed-form route (the default) and forced onto the integral route."""
    import stressfields as sf
    from stressfields.physics import invariants

    grid = {"start": -1.5, "stop": 1.5, "num": 512}
    out = {}
    for method in ("closed", "quadrature"):
        recipe = {"scenario": "parabolic", "method": {"method": method, "rtol": 1e-10},
                  "parameters": {"nu": 0.3, "mu": 0.3, "ux0": 0.25, "y": grid, "x": grid},
                  "output": {"variables": list(STRESS) + ["von_mises", "sigma_1", "sigma_2", "sigma_3", "dpdz"]}}
        out[f"hertz_mindlin_512_{method}_s"] = _median_time(lambda: sf.generate(recipe).compute(), repeats)
    # where the time goes: the principal stresses alone on the same 512^2 points
    rng = np.random.default_rng(4)
    comps = [rng.standard_normal(512 * 512) for _ in range(6)]
    out["principal_stresses_512_s"] = _median_time(lambda: invariants.principal_stresses(*comps), repeats)
    return out


#: sample counts and tolerances of the graded tabulated profile timed
GRADED_SAMPLES = (25, 200, 1000)
GRADED_RTOLS = (1e-6, 1e-10, 1e-12)


def _tabulated_rates(repeats: int) -> dict:
    """Points per CPU second of the tabulated routes at rtol 1e-10: the axisymmetric surface stresses
    (partial slip) for a 1000-sample profile, the graded pressure and surface displacement for
    GRADED_SAMPLES samples."""
    from stressfields.physics import axisymmetric as ax
    from stressfields.physics.graded import normal as N
    from stressfields.physics.graded import profiles as P

    rs = np.linspace(0.0, 1.2, 1000)
    hyper = ax.tabulated(rs, np.sqrt(rs ** 2 + 0.04) - 0.2)
    c = float(ax.stick_radius(1.0, 0.3, 0.4, 0.25, hyper))
    x, y = _disk_points(2000, 1.5, 7)
    _, cpu = _wall_cpu(lambda: ax.surface_stress(x, y, 1.0, c, 0.3, 0.4, hyper, method="quadrature", rtol=1e-10),
                       repeats)
    out = {"tabulated_axisymmetric_points_per_cpu_s": x.size / cpu}
    a = 1e-3
    kw = dict(k=0.5, nu=0.3, E0=1e9, c0=1e-3)
    # points through the contact, its centre and edge included, and outside it up to 3a
    inside, outside = np.linspace(0.0, 0.999, 200) * a, np.linspace(1.001, 3.0, 200) * a
    for samples in GRADED_SAMPLES:
        rs = np.linspace(0.0, 1.2, samples)
        for rtol in GRADED_RTOLS:
            prof = P.Tabulated(rs * a, (np.sqrt(rs ** 2 + 0.04) - 0.2) * a)      # a new contact: no tables yet
            start = time.process_time()
            N.pressure_quad(inside[1:2], a, prof, rtol=rtol, **kw)
            N.surface_displacement_quad(outside[:1], a, prof, k=0.5, rtol=rtol)
            out[f"tabulated_graded_setup_{samples}_{rtol:g}_cpu_s"] = time.process_time() - start
            _, cpu = _wall_cpu(lambda: N.pressure_quad(inside, a, prof, rtol=rtol, **kw), repeats)
            out[f"tabulated_graded_pressure_{samples}_{rtol:g}_points_per_cpu_s"] = inside.size / cpu
            _, cpu = _wall_cpu(lambda: N.surface_displacement_quad(outside, a, prof, k=0.5, rtol=rtol), repeats)
            out[f"tabulated_graded_uz_{samples}_{rtol:g}_points_per_cpu_s"] = outside.size / cpu
    return out


#: sample counts of the tabulated set-up rows
SETUP_SAMPLES = (1000, 10000)


def _tabulated_setup(repeats: int) -> dict:
    """The set-up of a tabulated profile as a user pays it: ``sf.generate(recipe).compute()`` of 2
    surface points (axisymmetric, rtol 1e-10) in a warm process, wall and CPU medians over
    ``repeats`` new profiles of SETUP_SAMPLES samples (each a different hyperboloid: nothing cached),
    then the same profile again (its set-up cached); and the graded tangential stick radius of one
    fx (1000 samples, k = 0.5) per new profile at rtol 1e-4 and 1e-10."""
    import stressfields as sf

    def recipe(samples, shift):
        r = np.linspace(0.0, 1.2, samples)
        f = np.sqrt(r ** 2 + 0.04) - 0.2 + shift * r
        return {"scenario": "axisymmetric", "parameters": {"profile": "tabulated", "profile_r": r.tolist(),
                "profile_f": f.tolist(), "nu": 0.3, "y": 0.0, "x": [0.3, 0.7]}, "method": {"rtol": 1e-10}}

    def graded(shift, rtol):
        r = np.linspace(0.0, 1.5, 1000)
        f = np.sqrt(r ** 2 + 0.04) - 0.2 + shift * r
        return {"scenario": "graded_tangential", "parameters": {
            "profile": "tabulated", "profile_r": r.tolist(), "profile_f": f.tolist(), "E0": 1e9,
            "contact_radius": 1.0, "fx": 0.5}, "output": {"variables": ["stick_radius"]}, "method": {"rtol": rtol}}

    def timed(make):
        """Medians of (wall, CPU) of ``make(i)`` computed for i = 1..repeats, and of the same again."""
        first, again = [], []
        for i in range(1, repeats + 1):
            rec = make(i)
            for out in (first, again):
                w, c = time.perf_counter(), time.process_time()
                sf.generate(rec).compute()
                out.append((time.perf_counter() - w, time.process_time() - c))
        return [float(np.median([v[j] for v in rows])) for rows in (first, again) for j in (0, 1)]

    sf.generate(recipe(20, 0.0)).compute()            # imports and a first small profile
    out = {}
    for samples in SETUP_SAMPLES:
        vals = timed(lambda i: recipe(samples, 1e-3 * i))
        for name, v in zip(("s", "cpu_s", "again_s", "again_cpu_s"), vals):
            out[f"tabulated_setup_{samples}_{name}"] = v
    for rtol in (1e-4, 1e-10):
        vals = timed(lambda i: graded(1e-3 * i, rtol))
        for name, v in zip(("s", "cpu_s", "again_s", "again_cpu_s"), vals):
            out[f"graded_stick_radius_{rtol:g}_{name}"] = v
    return out


def _setup_lines(tp: dict) -> list[str]:
    """The tabulated set-up rows of ``_tabulated_setup``."""
    lines = ["", "Tabulated set-up (a new profile per call, warm process; medians; then the same profile "
             "again, its set-up cached):", "",
             "| case | new profile [s] | CPU [s] | same profile again [s] | CPU [s] |", "|---|---|---|---|---|"]
    rows = [(f"axisymmetric, {n} samples, 2 points, rtol 1e-10", f"tabulated_setup_{n}") for n in SETUP_SAMPLES]
    rows += [(f"graded stick radius, 1000 samples, one fx, rtol {r:g}", f"graded_stick_radius_{r:g}")
             for r in (1e-4, 1e-10)]
    for label, key in rows:
        lines.append(f"| {label} | {tp[key + '_s']:.3f} | {tp[key + '_cpu_s']:.3f} | {tp[key + '_again_s']:.3f} | "
                     f"{tp[key + '_again_cpu_s']:.3f} |")
    return lines + [""]


def _sibling(name: str):
    """A module of this directory (the harness is loaded by path from `stressfields bench`)."""
    import importlib

    if str(Path(__file__).parent) not in sys.path:
        sys.path.insert(0, str(Path(__file__).parent))
    return importlib.import_module(name)


def _whole_process(cfg: Config) -> dict:
    """Fresh-process runs against the hand loop (benchmarks/process.py), fixed costs, the first
    call of a 512^2 Hertz-Mindlin case, and this machine's disk and SHA-256 rates."""
    process = _sibling("process")

    sizes = cfg.process_n + ((10_000,) if os.environ.get("STRESSFIELDS_BENCH_BIG") == "1" else ())
    out = {}
    for n in sizes:
        for label, names in (("all", process.ELEVEN), ("von_mises", ("von_mises",))):
            r = process.pipeline_vs_hand(n, names, pairs=3 if n < 10_000 else 1)
            out.update({f"process_{n * n:.0e}_{label}_{k}": v for k, v in r.items()})
    out.update({f"fixed_{k}": v for k, v in process.fixed_costs().items()})
    out["hertz_mindlin_512_first_call_s"] = process.first_call_hertz_mindlin_512()
    out["hertz_mindlin_512_first_run_s"] = process.first_run_hertz_mindlin_512()
    out.update(process.machine_limits())
    out["kernels_alone_cpu_s_per_point"] = process.kernels_alone()
    return out


# -- the run ----------------------------------------------------------------------------------

def measure(cfg: Config, peers: bool = False) -> tuple[xr.Dataset, dict]:
    """Every accuracy case (and, with ``cfg.throughput``, the throughput numbers): (dataset, throughput)."""
    load_before = os.getloadavg()[0]
    cases: dict = {}
    cases.update(_axisymmetric(cfg))
    cases.update(_pressure_ours(cfg))
    cases.update(_interior(cfg))
    cases.update(_graded(cfg))
    cases.update(_wavy(cfg))
    tp: dict = {}
    solve = _peer_solver() if peers else None
    peer_l2 = {}
    if solve is not None:
        peer_rows, peer_l2 = _peers(cfg, solve)
        for problem, rows in peer_rows.items():
            cases[problem].update(rows)
    if peers:       # below the surface: tamaas' FFT volume operators, ContactMechanics' Hertz forms
        for case, rows in _sibling("peers_interior").peer_interior_rows(cfg).items():
            cases.setdefault(case, {}).update(rows)
    if cfg.throughput:
        tp.update(_pipeline_vs_hand(cfg.pipeline_n, min(cfg.repeats, 3)))
        tp.update(_quadrature_rate(cfg.repeats))
        tp.update(_hertz_mindlin_512(cfg.repeats))
        tp.update(batches_rate(cfg.repeats))
        tp.update(_tabulated_rates(cfg.repeats))
        tp.update(_tabulated_setup(max(3, min(cfg.repeats, 5))))
        tp.update(_whole_process(cfg))
        if solve is not None:
            tp["peer_512_s"] = solve(512)[0] if 512 not in cfg.peer_grids else \
                cases[HERTZ][(PEER, 512.0)][0] * 512 ** 2
            tp["peer_512_first_s"] = tp["peer_512_s"]       # its solve in this process, imports done
    ds = _dataset(cases)
    ds.attrs["load_average_1min"] = f"{load_before:.2f} at start, {os.getloadavg()[0]:.2f} at end"
    ds.attrs.update({f"throughput_{k}": v for k, v in tp.items()})
    if peer_l2:     # the grid solvers' usual measure, ||p - p_exact|| / ||p_exact|| over all nodes
        ds.attrs["peer_pressure_l2_error"] = "; ".join(f"{problem.split(' (')[0]} {n}^2: {e:.2e}"
                                                       for (problem, n), e in peer_l2.items())
    return ds, tp


def run(out_dir: Path, quick: bool = False, peers: bool = False) -> int:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    ds, tp = measure(QUICK if quick else FULL, peers)
    ds.attrs["bench_wall_s"] = round(time.perf_counter() - start, 1)
    write(ds, tp, out_dir, command=f"stressfields bench{' --quick' if quick else ''}{' --peers' if peers else ''}")
    print(f"wrote {out_dir}/results.nc, accuracy_vs_time.png, README.md", file=sys.stderr)
    return 0


def write(ds: xr.Dataset, tp: dict, out_dir: Path, command: str = "stressfields bench") -> None:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    ds.attrs["command"] = command
    tmp = out_dir / ".results.nc.tmp"
    ds.to_netcdf(tmp)
    os.replace(tmp, out_dir / "results.nc")
    _chart(ds, out_dir / "accuracy_vs_time.png")
    (out_dir / "README.md").write_text(_report(ds, tp))


def _cpu_model() -> str:
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


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
        {"time_per_point": (("method", "order", "case"), t,
                            {"units": "s", "long_name": "median wall time per point (one core for stressfields)"}),
         "max_error": (("method", "order", "case"), e,
                       {"units": "1", "long_name": "max |value - reference| / max(scale, |reference|)"})},
        coords={"method": ("method", np.array(methods, dtype=object), {"long_name": "method (route)",
                           "comment": "select with ds.sel({'method': ...}): sel(method=...) is xarray's own keyword"}),
                "order": ("order", np.array(orders), {"units": "1", "long_name":
                          "requested rtol (quadrature, series) or grid size n of an n x n grid (peer); "
                          "0: no parameter (closed form, fixed approximation)"}),
                "case": ("case", np.array(names, dtype=object), {"long_name": "benchmark case"})},
        attrs={"title": "stressfields: accuracy against run time", "source": f"stressfields {__version__}",
               "cpu_model": _cpu_model(), "cores": os.cpu_count() or 0, "numpy_version": np.__version__,
               "python_version": platform.python_version(), "platform": platform.platform(),
               "date": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
               "reference": "closed form (its own error: against the integral route at rtol 1e-14), else the same "
                            "route at rtol = 1e-14; peer: the closed form"})


def _chart(ds: xr.Dataset, path: Path) -> None:
    """One log-log chart of error against time per point: colour = method, marker = case."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    # tall enough for both legends beside the axes (one line per method and per case)
    fig, axp = plt.subplots(figsize=(12, max(6.5, 0.19 * (ds.sizes["method"] + ds.sizes["case"]) + 1.5)))
    markers = "osD^v<>phH*Xd8P1234"
    floor = 1e-16                          # exact to rounding: drawn at 1e-16
    for j, m in enumerate(ds.method.values):
        for i, case in enumerate(ds.case.values):
            sub = ds.sel({"method": m, "case": case})     # dict form: sel(method=...) is sel's own keyword
            t, e = sub.time_per_point.values, np.maximum(sub.max_error.values, floor)
            ok = np.isfinite(t)
            if ok.any():
                axp.loglog(t[ok], e[ok], marker=markers[i % len(markers)], ms=5, lw=1, color=f"C{j}", alpha=0.85)
    methods = [Line2D([], [], color=f"C{j}", lw=2, label=m) for j, m in enumerate(ds.method.values)]
    cases = [Line2D([], [], color="0.3", ls="", marker=markers[i % len(markers)], label=c)
             for i, c in enumerate(ds.case.values)]
    first = axp.legend(handles=methods, title="method (colour)", fontsize=7, loc="upper left",
                       bbox_to_anchor=(1.01, 1.0))
    axp.add_artist(first)
    axp.legend(handles=cases, title="case (marker)", fontsize=6.5, loc="lower left", bbox_to_anchor=(1.01, 0.0))
    axp.set_xlabel("time per point [s] (median)")
    axp.set_ylabel("max error / max(scale, |reference|)")
    axp.set_title(f"stressfields {__version__}: accuracy against run time; {ds.attrs['cpu_model']}, "
                  f"{ds.attrs['date'][:10]}", fontsize=9)
    axp.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def _report(ds: xr.Dataset, tp: dict) -> str:
    a = ds.attrs
    lines = ["# Benchmark: accuracy against run time", "",
             f"Generated by `{a.get('command', 'stressfields bench')}` on {a['date']}: {a['cpu_model']}, "
             f"{a['cores']} cores, Python {a['python_version']}, numpy {a['numpy_version']}; load average "
             f"{a['load_average_1min']}; {a.get('bench_wall_s', '?')} s in all. Medians of repeated runs; "
             "this machine is shared, so read ratios. Errors: max |value - reference| / max(scale, |reference|) "
             "against the closed form (closed forms themselves: against the integral route at rtol = 1e-14), "
             "else the same route at rtol = 1e-14.", "",
             "![accuracy vs time](accuracy_vs_time.png)", "",
             "| case | method | rtol / grid | time per point [s] | max error |", "|---|---|---|---|---|"]
    for case in ds.case.values:
        for m in ds.method.values:
            for o in ds.order.values:
                sub = ds.sel({"method": m, "case": case, "order": o})
                t, e = float(sub.time_per_point), float(sub.max_error)
                if np.isfinite(t):
                    label = "-" if o == 0 else (f"{o:.0f}^2" if m == PEER else f"{o:.0f}^2 x 16 layers"
                                                if m.startswith("tamaas") else f"{o:g}")
                    lines.append(f"| {case} | {m} | {label} | {t:.3g} | {e:.2g} |")
    if "peer_pressure_l2_error" in a:
        lines += ["", f"The peer's max error sits at the contact edge, where a grid resolves the square-root "
                      f"fall of the pressure only to first order (and for the cone beside the log-singular tip); "
                      f"its L2 error (all nodes but the cone's tip) is {a['peer_pressure_l2_error']}."]
    if not tp:
        return "\n".join(lines) + "\n"
    ratio = tp["pipeline_over_hand"]
    hm = tp["hertz_mindlin_512_closed_s"]
    lines += ["", "## Throughput", "",
              f"- Full pipeline (recipe dict -> `generate` -> `to_netcdf`, threaded dask on {a['cores']} cores) "
              f"for the six Hertz–Mindlin surface stresses and von Mises on {tp['pipeline_points']:.0f} points: "
              f"{tp['pipeline_s']:.2f} s wall ({tp['pipeline_cpu_s']:.2f} s CPU), against {tp['hand_s']:.2f} s wall "
              f"({tp['hand_cpu_s']:.2f} s CPU) for a hand-written blocked NumPy loop over the same kernels plus a "
              f"plain netCDF4 write: ratio {ratio:.2f} wall, {tp['pipeline_over_hand_cpu']:.2f} CPU.",
              f"- Integral route at rtol 1e-10 (six stress components, partial slip): "
              f"{tp['quadrature_paraboloid_points_per_cpu_s']:.3g} points per CPU second for the paraboloid, "
              f"{tp['quadrature_power_law_n3_points_per_cpu_s']:.3g} for a power law n = 3.",
              f"- All surface fields (six components, von Mises, principal stresses, dp/dz) of a 512 x 512 "
              f"Hertz–Mindlin partial-slip case through `generate(...).compute()` at rtol 1e-10: {hm:.2f} s on "
              f"the closed-form route, {tp['hertz_mindlin_512_quadrature_s']:.2f} s forced onto the integral "
              f"route (the principal stresses alone: {tp['principal_stresses_512_s']:.2f} s)."]
    if "batches_hertz_interior_samples_per_cpu_s" in tp:
        lines += [f"- `sf.batches` (procedural training data, no file), Hertz below the surface, six stresses: "
                  f"{tp['batches_hertz_interior_samples_per_cpu_s']:.3g} samples per CPU second "
                  f"({tp['batches_hertz_interior_samples_per_s']:.3g} per wall second; target 1e6 on one core)."]
    lines += [f"- Tabulated profiles (1000 samples) at rtol 1e-10: axisymmetric surface stresses "
              f"{tp['tabulated_axisymmetric_points_per_cpu_s']:.3g} points per CPU second."]
    lines += _graded_table(tp)
    lines += _setup_lines(tp)
    lines += _process_lines(tp)
    if "peer_512_s" in tp:
        peer = tp["peer_512_s"]
        lines[-1] += (f" ContactMechanics needs {peer:.1f} s to solve the pressure alone on 512 x 512 (this run): "
                      f"ratio 1/{peer / hm:.0f} closed, 1/{peer / tp['hertz_mindlin_512_quadrature_s']:.0f} integral "
                      f"route.")
    else:
        lines[-1] += " (Run with --peers and ContactMechanics installed for the peer's 512 x 512 time.)"
    return "\n".join(lines) + "\n"


def _graded_table(tp: dict) -> list[str]:
    """Graded tabulated profiles (k = 0.5, hyperboloid): the per-contact setup, then points per CPU
    second of the pressure at 200 points r/a in [0, 0.999] and of u_z at 200 points r/a in (1, 3]."""
    lines = ["", "Graded tabulated profiles (k = 0.5, a sampled hyperboloid; a new contact per row: the setup "
             "builds its tables, then 200 points through the contact, centre and edge included, and 200 "
             "outside it up to 3a):", "",
             "| samples | rtol | setup [CPU s] | pressure [points/CPU s] | u_z [points/CPU s] |",
             "|---|---|---|---|---|"]
    for n in GRADED_SAMPLES:
        for rtol in GRADED_RTOLS:
            key = f"{n}_{rtol:g}"
            lines.append(f"| {n} | {rtol:g} | {tp[f'tabulated_graded_setup_{key}_cpu_s']:.2f} | "
                         f"{tp[f'tabulated_graded_pressure_{key}_points_per_cpu_s']:.3g} | "
                         f"{tp[f'tabulated_graded_uz_{key}_points_per_cpu_s']:.3g} |")
    return lines + [""]


def _fortieth(tp: dict) -> str:
    """Whether a first call 40x faster than the peer's 512 x 512 solve is within reach at all: any
    Dataset needs xarray, whose import alone (a fresh process) is measured."""
    budget, floor = tp["peer_512_first_s"] / 40.0, tp.get("fixed_xarray_s")
    if floor is None:
        return ""
    verdict = "less than" if budget < floor else "more than"
    return (f" A fortieth of the peer's solve, {budget:.2f} s, is {verdict} a fresh process takes to import "
            f"xarray alone ({floor:.2f} s), which any Dataset needs.")


def _process_lines(tp: dict) -> list[str]:
    """The whole-process section of the report: per size and field set, the medians and ratios."""
    runs = sorted({k.split("_")[1] for k in tp if k.startswith("process_")}, key=float)
    if not runs:
        return []
    lines = ["", "### Whole process against the hand loop", "",
             "Fresh processes, back to back per pair (`stressfields run RECIPE -o FILE` against a hand-written "
             "blocked NumPy loop over the same kernels and a plain netCDF4 write: benchmarks/process.py); cone under "
             "partial slip on an n x n grid; medians of the pairs and median of the per-pair ratios.", "",
             "| points | fields | stressfields wall [s] | CPU [s] | hand loop wall [s] | CPU [s] | ratio wall "
             "| ratio CPU |",
             "|---|---|---|---|---|---|---|---|"]
    for size in runs:
        for label in ("all", "von_mises"):
            k = f"process_{size}_{label}_"
            if k + "ratio_wall" in tp:
                lines.append(f"| {float(size):.0e} | {'eleven' if label == 'all' else 'von Mises'} | "
                             f"{tp[k + 'pipeline_s']:.2f} | {tp[k + 'pipeline_cpu_s']:.2f} | {tp[k + 'hand_s']:.2f} | "
                             f"{tp[k + 'hand_cpu_s']:.2f} | {tp[k + 'ratio_wall']:.2f} | {tp[k + 'ratio_cpu']:.2f} |")
    per_point = [f"{float(size):.0e} points {1e9 * tp[f'process_{size}_all_pipeline_cpu_s'] / float(size):.0f} ns "
                 f"(hand loop {1e9 * tp[f'process_{size}_all_hand_cpu_s'] / float(size):.0f})"
                 for size in runs if f"process_{size}_all_pipeline_cpu_s" in tp]
    lines += ["", "- CPU time per point of the whole process, eleven fields: " + ", ".join(per_point) + ".",
              f"- Fixed costs (medians of 5 fresh processes): `stressfields describe conical` "
              f"{tp['fixed_describe_s']:.2f} s, `import stressfields` {tp['fixed_import_s']:.2f} s, a 1e4-point "
              f"`stressfields run` {tp['fixed_run_1e4_s']:.2f} s; the interpreter alone "
              f"{tp['fixed_bare_python_s']:.2f} s, and importing the libraries any run needs (NumPy, "
              f"scipy.special, xarray, dask.array, netCDF4) {tp['fixed_dependencies_s']:.2f} s.",
              f"- First call in a fresh process, every surface field of a 512 x 512 Hertz–Mindlin case (imports "
              f"included): {tp['hertz_mindlin_512_first_call_s']:.2f} s through the API (`generate(...).compute()`), "
              f"{tp['hertz_mindlin_512_first_run_s']:.2f} s as a `stressfields run` writing the NetCDF file."
              + (f" ContactMechanics' 512 x 512 pressure solve in this run: {tp['peer_512_first_s']:.1f} s, "
                 f"{tp['peer_512_first_s'] / tp['hertz_mindlin_512_first_call_s']:.0f}x and "
                 f"{tp['peer_512_first_s'] / tp['hertz_mindlin_512_first_run_s']:.0f}x longer."
                 + _fortieth(tp) if "peer_512_first_s" in tp else ""),
              f"- This machine: SHA-256 {tp['sha256_bytes_per_s'] / 1e9:.2f} GB/s, disk write (fsync'd) "
              f"{tp['disk_bytes_per_s'] / 1e9:.2f} GB/s."]
    if "kernels_alone_cpu_s_per_point" in tp:
        # the per-core cost a point cannot go below with these kernels: computing its eleven values,
        # writing their 88 bytes at the disk rate and hashing them at the SHA-256 rate
        kernel = 1e9 * tp["kernels_alone_cpu_s_per_point"]
        write, sha = 88e9 / tp["disk_bytes_per_s"], 88e9 / tp["sha256_bytes_per_s"]
        floor = kernel + write + sha
        big = [size for size in runs if float(size) >= 1e7 and f"process_{size}_all_pipeline_cpu_s" in tp]
        per_point = {size: 1e9 * tp[f"process_{size}_all_pipeline_cpu_s"] / float(size) for size in big}
        shares = ", ".join(f"{float(size):.0e} points {floor / cpu:.0%}" for size, cpu in per_point.items())
        lines.append(f"- Per core and point, eleven fields: the kernels alone {kernel:.0f} ns (one thread, nothing "
                     f"written), writing 88 bytes at the disk rate {write:.0f} ns, hashing them {sha:.0f} ns: "
                     f"{floor:.0f} ns, the floor of a whole run with these kernels; the share of it a whole run "
                     f"reaches (floor / CPU per point): {shares or 'no run of 1e7 points or more'}.")
    return lines
