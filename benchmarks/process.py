"""Whole-process throughput: `stressfields run` in a fresh interpreter against a hand-written loop
over the same kernels with a plain netCDF4 write, also in a fresh interpreter.

Each pair is run back to back (pipeline, then hand loop) and the ratio is taken per pair, so a
change of load on this shared machine hits both sides of one ratio; the medians of the per-pair
ratios and of the times are reported.  CPU time is the children's user + system time
(``resource.getrusage(RUSAGE_CHILDREN)``), wall time by ``time.perf_counter``.

The case is the issue's: a cone (tan theta = 1) under Cattaneo–Mindlin partial slip (nu = 0.3,
mu = 0.4, u_x0/delta = 0.25) on a square n x n grid |x|, |y| <= 1.5 a, either all eleven float
surface fields (six stresses, von Mises, three principal stresses, dp/dz) or von Mises alone.
"""
from __future__ import annotations

import os
import resource
import statistics
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

ELEVEN = ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "sigma_yz", "von_mises",
          "sigma_1", "sigma_2", "sigma_3", "dpdz")

#: the hand loop: the physics kernels of the package, blocked over ~1e6 points, one netCDF4 file
HAND = textwrap.dedent('''
    import sys
    import numpy as np, netCDF4
    from stressfields.physics import axisymmetric as ax
    from stressfields.physics.invariants import principal_stresses, von_mises
    n, out, names = int(sys.argv[1]), sys.argv[2], sys.argv[3].split(",")
    nu, mu, ux0 = 0.3, 0.4, 0.25
    prof = ax.cone(1.0)
    c = ax.stick_radius(1.0, nu, mu, ux0, prof)
    pm = float(ax.mean_pressure(1.0, prof))
    xs = np.linspace(-1.5, 1.5, n)
    with netCDF4.Dataset(out, "w") as nc:
        nc.createDimension("y", n); nc.createDimension("x", n)
        var = {k: nc.createVariable(k, "f8", ("y", "x")) for k in names}
        rows = max(1, 1_000_000 // n)
        for s in range(0, n, rows):
            X, Y = xs[None, :], xs[s:s + rows, None]
            t = ax.surface_stress(X, Y, 1.0, c, nu, mu, prof)
            comps = [t[k] / pm for k in ("xx", "yy", "zz", "xy", "xz", "yz")]
            got = {}
            if any(k.startswith("sigma_") and len(k) == 8 for k in names):
                got.update(zip(("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "sigma_yz"), comps))
            if "von_mises" in names:
                got["von_mises"] = von_mises(*comps)
            if "sigma_1" in names:
                got.update(zip(("sigma_1", "sigma_2", "sigma_3"), principal_stresses(*comps)))
            if "dpdz" in names:
                got["dpdz"] = ax.surface_dpdz(X, Y, 1.0, c, nu, mu, prof) / pm
            for k in names:
                var[k][s:s + rows] = got[k]
''')


def _recipe(n: int, names) -> str:
    return textwrap.dedent(f'''
        scenario = "conical"
        [parameters]
        nu = 0.3
        mu = 0.4
        ux0 = 0.25
        y = {{ start = -1.5, stop = 1.5, num = {n} }}
        x = {{ start = -1.5, stop = 1.5, num = {n} }}
        [output]
        variables = [{", ".join(f'"{v}"' for v in names)}]
    ''')


def _child(cmd: list[str]) -> tuple[float, float]:
    """(wall, CPU) seconds of one child process, which must succeed."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed: {done.stderr[-2000:]}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def pipeline_vs_hand(n: int, names=ELEVEN, pairs: int = 3) -> dict:
    """Median wall/CPU of `stressfields run` and of the hand loop on n x n points, and the median
    of the per-pair ratios."""
    exe = Path(sys.executable).with_name("stressfields")
    with tempfile.TemporaryDirectory() as tmp:
        recipe = Path(tmp) / "case.toml"
        recipe.write_text(_recipe(n, names))
        hand = Path(tmp) / "hand.py"
        hand.write_text(HAND)
        rows = []
        for i in range(pairs):
            pipe = _child([str(exe), "run", str(recipe), "-o", str(Path(tmp) / f"p{i}.nc"), "--quiet"])
            byhand = _child([sys.executable, str(hand), str(n), str(Path(tmp) / f"h{i}.nc"), ",".join(names)])
            rows.append((pipe, byhand))
            for f in Path(tmp).glob("*.nc"):
                f.unlink()
    med = statistics.median
    return {"points": float(n * n), "fields": len(names),
            "pipeline_s": med(p[0] for p, _ in rows), "pipeline_cpu_s": med(p[1] for p, _ in rows),
            "hand_s": med(h[0] for _, h in rows), "hand_cpu_s": med(h[1] for _, h in rows),
            "ratio_wall": med(p[0] / h[0] for p, h in rows), "ratio_cpu": med(p[1] / h[1] for p, h in rows)}


def fixed_costs(repeats: int = 5) -> dict:
    """Median wall seconds of `stressfields describe conical`, of `import stressfields`, of a
    1e4-point `stressfields run` (the fixed cost of a small job), and of the imports below them."""
    exe = str(Path(sys.executable).with_name("stressfields"))
    with tempfile.TemporaryDirectory() as tmp:
        recipe = Path(tmp) / "small.toml"
        recipe.write_text(_recipe(100, ELEVEN))
        out = {}
        for key, cmd in (("describe_s", [exe, "describe", "conical"]),
                         ("import_s", [sys.executable, "-c", "import stressfields"]),
                         # the floor of any run: the libraries a dataset and its file need
                         ("dependencies_s", [sys.executable, "-c", "import numpy, scipy.special, xarray, dask.array, "
                                                                     "netCDF4"]),
                         # the floor of any Dataset, the API's first call included
                         ("xarray_s", [sys.executable, "-c", "import xarray"]),
                         ("bare_python_s", [sys.executable, "-c", "pass"]),
                         ("run_1e4_s", [exe, "run", str(recipe), "-o", str(Path(tmp) / "s.nc"), "--quiet",
                                        "--overwrite"])):
            out[key] = statistics.median(_child(cmd)[0] for _ in range(repeats))
    return out


def first_call_hertz_mindlin_512() -> float:
    """Wall seconds of a fresh process computing every surface field of a 512 x 512 Hertz–Mindlin
    case through the API (imports and first-call costs included), minus the bare interpreter start."""
    code = textwrap.dedent('''
        import time; t = time.perf_counter()
        import stressfields as sf
        g = {"start": -1.5, "stop": 1.5, "num": 512}
        sf.generate({"scenario": "parabolic", "parameters": {"nu": 0.3, "mu": 0.3, "ux0": 0.25, "y": g, "x": g},
                     "output": {"variables": ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "sigma_yz",
                                              "von_mises", "sigma_1", "sigma_2", "sigma_3", "tau_max", "dpdz"]}
                     }).compute()
        print(time.perf_counter() - t)
    ''')
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return float(done.stdout.split()[-1])


def first_run_hertz_mindlin_512() -> float:
    """Wall seconds of `stressfields run` in a fresh process writing every surface field of the
    512 x 512 Hertz–Mindlin case to NetCDF (imports, the file and its content hash included)."""
    exe = str(Path(sys.executable).with_name("stressfields"))
    recipe = textwrap.dedent('''
        scenario = "parabolic"
        [parameters]
        nu = 0.3
        mu = 0.3
        ux0 = 0.25
        y = { start = -1.5, stop = 1.5, num = 512 }
        x = { start = -1.5, stop = 1.5, num = 512 }
        [output]
        variables = ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "sigma_yz", "von_mises",
                     "sigma_1", "sigma_2", "sigma_3", "tau_max", "dpdz"]
    ''')
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "hm.toml"
        path.write_text(recipe)
        return statistics.median(_child([exe, "run", str(path), "-o", str(Path(tmp) / f"hm{i}.nc"), "-q"])[0]
                                 for i in range(3))


def kernels_alone(n: int = 1000, repeats: int = 5) -> float:
    """CPU seconds per point of the hand loop's kernels without any writing, in this process (one
    thread): the eleven fields of the cone case on an n x n grid, median of ``repeats``."""
    import numpy as np

    from stressfields.physics import axisymmetric as ax
    from stressfields.physics.invariants import principal_stresses, von_mises

    prof = ax.cone(1.0)
    c = ax.stick_radius(1.0, 0.3, 0.4, 0.25, prof)
    pm = float(ax.mean_pressure(1.0, prof))
    xs = np.linspace(-1.5, 1.5, n)
    X, Y = xs[None, :], xs[:, None]

    def once():
        t = ax.surface_stress(X, Y, 1.0, c, 0.3, 0.4, prof)
        comps = [t[k] / pm for k in ("xx", "yy", "zz", "xy", "xz", "yz")]
        von_mises(*comps)
        principal_stresses(*comps)
        ax.surface_dpdz(X, Y, 1.0, c, 0.3, 0.4, prof)
    once()
    times = []
    for _ in range(repeats):
        start = time.process_time()
        once()
        times.append(time.process_time() - start)
    return statistics.median(times) / (n * n)


def machine_limits(megabytes: int = 512) -> dict:
    """This machine's disk write rate (fsync'd) and SHA-256 rate, bytes per second."""
    import hashlib

    import numpy as np

    block = np.random.default_rng(0).random(megabytes * 2 ** 17).tobytes()
    start = time.perf_counter()
    hashlib.sha256(block).hexdigest()
    sha = len(block) / (time.perf_counter() - start)
    with tempfile.NamedTemporaryFile(dir=os.environ.get("TMPDIR")) as fh:
        start = time.perf_counter()
        fh.write(block)
        fh.flush()
        os.fsync(fh.fileno())
        disk = len(block) / (time.perf_counter() - start)
    return {"sha256_bytes_per_s": sha, "disk_bytes_per_s": disk}
