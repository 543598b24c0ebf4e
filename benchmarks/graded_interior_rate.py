"""Points per CPU second of the graded 2-D route below the surface (physics.graded.holl.disc_stress):
a rho-z map (41 x 25 points, r/a in [0, 2], z/a in [0.02, 2]) and shallow points (z/a from 1e-6 to 1),
k = 0.5, medians of 5 runs per rtol; the paraboloid's pressure (1 - rho^2)^((1+k)/2), and (``--profiles``)
the cone's and f = A r^0.4's shape (docs/theory/graded.md (G70)).  Part of the benchmark tools, not of the
package:  python benchmarks/graded_interior_rate.py [--profiles]  (from a clone)."""
from __future__ import annotations

import statistics
import sys
import time

import numpy as np

from stressfields.physics.graded import holl
from stressfields.physics.graded.interior import _shape


def rate(r, z, rtol, shape=None, repeats=5) -> float:
    holl.disc_stress(r[:8], z[:8], 0.5, 0.75, rtol, shape=shape)          # the rules' caches
    times = []
    for _ in range(repeats):
        start = time.process_time()
        holl.disc_stress(r, z, 0.5, 0.75, rtol, shape=shape)
        times.append(time.process_time() - start)
    return r.size / statistics.median(times)


def main(argv) -> None:
    R, Z = np.meshgrid(np.linspace(0.0, 2.0, 41), np.linspace(0.02, 2.0, 25))
    rng = np.random.default_rng(1)
    r_s, z_s = 2.0 * rng.random(1000), 10.0 ** rng.uniform(-6.0, 0.0, 1000)
    cases = [("paraboloid", None)]
    if "--profiles" in argv:
        cases += [("cone", _shape(1.0, 0.5)), ("A r^0.4", _shape(0.4, 0.5))]
    for label, shape in cases:
        print(f"{label}\nrtol      map points/CPU s   shallow points/CPU s")
        for rtol in (1e-4, 1e-6, 1e-8, 1e-10, 1e-12):
            print(f"{rtol:<8g}  {rate(R.ravel(), Z.ravel(), rtol, shape):>16,.0f}   "
                  f"{rate(r_s, z_s, rtol, shape):>20,.0f}")


if __name__ == "__main__":
    main(sys.argv[1:])
