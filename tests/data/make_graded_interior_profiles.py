"""Write graded_interior_profiles.json: the stress below a power-law graded half-space with Holl's ratio
nu = 1/(2+k) under the pressure shape Phi(rho) of a power-law indenter f = A r^n (cone n = 1, and n = 0.6,
1.5, 3) on the unit disc, by a route independent of the package.

Route: the point-load field sigma_R = -chi P cos^(chi-2)(theta) / (2 pi R^2), chi = 3 + k, summed over the
disc as a double integral in the disc's own polar coordinates (rho, psi) with mpmath's tanh-sinh quadrature
(mp.quad, nested: the azimuth inside, on [0, pi/8, pi]; the radius outside in u = sqrt(1 - rho), split at
rho = r, so that the pressure's edge factor and its tip behaviour rho^(n+k-1) sit at end points), at 12
digits.  The pressure shape is not the package's cosh-form quadrature but the hypergeometric form of the
incomplete beta function of docs/theory/graded.md (G18)-(G19),
    Phi(rho) = rho^(n+k-1)/2 * z^s/s * 2F1(s, (1+n+k)/2; s+1; z),  z = 1 - rho^2,  s = (1+k)/2,
by mpmath.hyp2f1 at 40 digits.  Error estimate: mp.quad's own (error=True) of the outer integral, stored per
point.

Run from the repository root:  python tests/data/make_graded_interior_profiles.py  (or the ranges
"0 32" and "32 64" in two processes, each printing its points as JSON lines to a part file, then
python tests/data/make_graded_interior_profiles.py --join PART1 PART2)
"""
import json
import random
import sys

import mpmath as mp

from make_graded_interior import run      # the parts and their join (this directory)

mp.mp.dps = 12


def phi(rho, n, k):
    """The pressure shape (G18) by the hypergeometric form of the incomplete beta (G19)."""
    with mp.workdps(40):
        rho, n, k = mp.mpf(rho), mp.mpf(n), mp.mpf(k)
        s = (1 + k) / 2
        z = (1 - rho) * (1 + rho)
        v = rho ** (n + k - 1) / 2 * z ** s / s * mp.hyp2f1(s, (1 + n + k) / 2, s + 1, z)
    return +v


def stress(r, z, k, n):
    chi = 3 + k
    r, z, k = (mp.mpf(v) for v in (r, z, k))
    cache = {}

    def ring(u):
        # the four azimuth integrals at rho = 1 - u^2, shared by the four outer integrals
        if u not in cache:
            rho = 1 - u * u

            def part(which):
                def f(psi):
                    dx = r - rho * mp.cos(psi)
                    dy = rho * mp.sin(psi)
                    R2 = dx * dx + dy * dy + z * z
                    num = {"rr": dx * dx, "tt": dy * dy, "zz": z * z, "rz": dx * z}[which]
                    return num * R2 ** (-(chi + 2) / 2)
                return mp.quad(f, [0, mp.pi / 8, mp.pi])
            p = phi(rho, n, k) if 0 < u < 1 else mp.mpf(0)
            cache[u] = {c: p * rho * 2 * u * part(c) for c in ("rr", "tt", "zz", "rz")}
        return cache[u]

    out = {}
    for c in ("rr", "tt", "zz", "rz"):
        pts = [0, mp.sqrt(1 - r), 1] if 0 < r < 1 else [0, 1]
        val, err = mp.quad(lambda u: ring(u)[c], pts, error=True)
        fac = -(chi / mp.pi) * z ** (chi - 2)
        out[c] = (fac * val, abs(fac * err))
    return out


def cases():
    """The 64 points (r, z, k, n), drawn in a fixed order from a seeded generator: 40 anywhere, 20 near the
    axis and the surface, where the pressure's centre behaviour rho^(n+k-1) matters most; and 4 of the
    steep power law n = 50 (its pressure turns within about a/50 of the edge)."""
    rng = random.Random(2929)
    out = []
    for i in range(60):
        k = (0.25, 0.5, 0.75)[i % 3]
        n = (1.0, 0.6, 1.5, 3.0)[i % 4]
        if i < 40:
            r = rng.choice((0.0, rng.uniform(0, 0.95), rng.uniform(0, 2.0), 1.0))
            z = 10 ** rng.uniform(-1.0, 0.3)
        else:
            r = rng.choice((0.0, rng.uniform(0, 0.05)))
            z = 10 ** rng.uniform(-3.0, -1.0)
        out.append((r, z, k, n))
    out += [(1.2, 0.8, 0.25, 50.0), (0.5, 0.3, 0.75, 50.0), (0.98, 0.05, 0.25, 50.0), (0.0, 0.5, 0.75, 50.0)]
    return out


def main(argv):
    run(argv, cases(), stress, ("rho", "z", "k", "n"), write)


def write(rows):
    meta = dict(problem="stress (tension positive, z into the body) at (r, 0, z), r = rho, of the pressure shape "
                        "Phi(rho) of f = A r^n (docs/theory/graded.md (G18)) on the unit disc over the graded "
                        "half-space with nu = 1/(2+k): sigma_ij = -(chi/2 pi) z^(chi-2) int Phi d_i d_j R^-(chi+2) "
                        "dA, chi = 3 + k",
                route="mpmath.quad (tanh-sinh) nested double integral in (u, psi), rho = 1 - u^2, 12 digits; "
                      "Phi by mpmath.hyp2f1 at 40 digits",
                script="tests/data/make_graded_interior_profiles.py")
    with open("tests/data/graded_interior_profiles.json", "w") as fh:
        json.dump(dict(meta=meta, points=rows), fh, indent=1)


if __name__ == "__main__":
    main(sys.argv[1:])
