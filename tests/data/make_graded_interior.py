"""Write graded_interior.json: the stress below a power-law graded half-space with Holl's ratio
nu = 1/(2+k) under the pressure p = (1 - rho^2)^e on the unit disc, by an independent route.

Route: the point-load field sigma_R = -chi P cos^(chi-2)(theta) / (2 pi R^2), chi = 3 + k, summed over the
disc as a plain double integral in the disc's own polar coordinates (rho, psi) with mpmath's tanh-sinh
quadrature (mp.quad in u = sqrt(1 - rho), the radial interval split at rho = r), at 12 digits; not the
package's rule (which works in sinh-mapped azimuth and geometric radial panels).  Error estimate: the
difference to the same integral at quadrature degree + 1 (mp.quad's own estimate, error=True), stored
per value.

Run from the repository root:  python tests/data/make_graded_interior.py  (about an hour on one core; or
the ranges "0 100" and "100 200" in two processes, each printing its points as JSON lines to a part
file, then  python tests/data/make_graded_interior.py --join PART1 PART2)
"""
import json
import random
import sys

import mpmath as mp

mp.mp.dps = 12


def stress(r, z, k, e):
    chi = 3 + k
    r, z, k, e = (mp.mpf(v) for v in (r, z, k, e))

    def comp(which):
        # rho = 1 - u^2: 1 - rho = u^2 exactly, so the edge factor (1 - rho^2)^e = u^(2e) (2 - u^2)^e is not
        # formed by cancellation at nodes rounded next to rho = 1 (at 12 digits that cost ~1e-10 for e < 0)
        def f(u, psi):
            rho = 1 - u * u
            dx = r - rho * mp.cos(psi)
            dy = rho * mp.sin(psi)
            R2 = dx * dx + dy * dy + z * z
            num = {"rr": dx * dx, "tt": dy * dy, "zz": z * z, "rz": dx * z}[which]
            return (u * u * (2 - u * u)) ** e * rho * num * R2 ** (-(chi + 2) / 2) * 2 * u
        pts = [0, mp.sqrt(1 - r), 1] if 0 < r < 1 else [0, 1]
        val, err = mp.quad(f, pts, [0, mp.pi / 8, mp.pi], error=True)
        fac = -(chi / mp.pi) * z ** (chi - 2)
        return fac * val, abs(fac * err)

    return {c: comp(c) for c in ("rr", "tt", "zz", "rz")}


def cases():
    """The 200 points (r, z, k, e), drawn in a fixed order from a seeded generator."""
    rng = random.Random(29)
    out = []
    for i in range(200):
        k = (0.25, 0.5, 0.75)[i % 3]
        adhesive = i % 4 == 3
        e = -(1 - k) / 2 if adhesive else (1 + k) / 2
        r = rng.choice((0.0, rng.uniform(0, 0.95), rng.uniform(0, 2.0), 1.0))
        z = 10 ** rng.uniform(-1.0, 0.3)
        out.append((r, z, k, e))
    return out


def main(argv):
    run(argv, cases(), stress, ("rho", "z", "k", "e"), write)


def run(argv, points, stress, keys, write):
    """All points; or ``FIRST LAST``: the points FIRST..LAST-1 as lines of a part (one process per core),
    joined by ``--join PART...`` into the JSON file (``write``).  ``stress(*point)`` gives (value, error) per
    component; ``keys`` name the point's entries in a row."""
    if argv and argv[0] == "--join":
        rows = {}
        for part in argv[1:]:
            with open(part) as fh:
                rows.update((int(i), row) for i, row in (json.loads(line) for line in fh))
        write([rows[i] for i in range(len(points))])
        return
    todo = range(int(argv[0]), int(argv[1])) if argv else range(len(points))
    rows = []
    for i in todo:
        s = stress(*points[i])
        row = dict(zip(keys, points[i]), **{f"sigma_{c}": float(v) for c, (v, _) in s.items()},
                   err=float(max(er for _, er in s.values())))
        rows.append(row)
        print(json.dumps([i, row]), flush=True)
    if not argv:
        write(rows)


def write(rows):
    meta = dict(problem="stress (tension positive, z into the body) at (r, 0, z), r = rho, of the pressure "
                        "p = (1 - rho^2)^e on the unit disc over the graded half-space with nu = 1/(2+k): "
                        "sigma_ij = -(chi/2 pi) z^(chi-2) int p d_i d_j R^-(chi+2) dA, chi = 3 + k",
                route="mpmath.quad (tanh-sinh) double integral in (u, psi), rho = 1 - u^2, 12 digits",
                script="tests/data/make_graded_interior.py")
    with open("tests/data/graded_interior.json", "w") as fh:
        json.dump(dict(meta=meta, points=rows), fh, indent=1)


if __name__ == "__main__":
    main(sys.argv[1:])
