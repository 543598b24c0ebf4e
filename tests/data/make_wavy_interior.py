"""Reference stresses below the wavy contact, by quadrature of the defining integrals with mpmath.

Writes tests/data/wavy_interior.json.  Independent of the package's interior route (no potential
in closed form, no Taylor series): for each case the surface pressure p(s)/p* is evaluated in
mpmath from its own series of docs/theory/wavy.md ((W30), periodic, with mpmath's Legendre
functions; (W8), non-periodic, with mpmath's Bessel functions, summed until the terms fall below
1e-30), and at each point (x, z) (lambda_1 = 2 pi units, z depth) the stresses are integrals over the
contact, in s = a sin(phi) (no edge singularity), split at the point's abscissa:

* non-periodic: the Flamant line-load superposition itself (real kernels),
  sigma_xx = -(2/pi) int p (x-s)^2 z / rho^4, sigma_zz = -(2/pi) int p z^3 / rho^4,
  sigma_xz = -(2/pi) int p (x-s) z^2 / rho^4, rho^2 = (x-s)^2 + z^2;
* periodic: the image sum of those kernels over all periods, which is the cot kernel:
  G = (1/2 pi) int p(s) cot((zeta - s)/2) ds, G' = -(1/4 pi) int p(s) csc^2((zeta - s)/2) ds, and
  sigma_xx = Im G + z Re G', sigma_zz = Im G - z Re G', sigma_xz = -z Im G' (the mean pressure's
  k = 0 mode included as the limit of the image sum).

Run from the repository root:  python tests/data/make_wavy_interior.py  (about a minute per case).
"""
from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import mpmath as mp
import numpy as np

mp.mp.dps = 20

PROFILES = {
    "one": ([1.0], [1]),
    "two": ([1.0, 0.02], [1, 11]),
    "eleven": ([1.0] + [0.1 / i ** 2 for i in range(2, 12)], list(range(1, 12))),
}
WIDTHS = (1e-3, 0.3, 0.6, 0.999)


def periodic_pressure(amps, wns, a):
    """p/p* = R(s) sum_j B_j cos((j + 1/2) s), B_j = sum_{n_i > j} 2 (Delta_i/Delta_1) n_i P_{n_i-1-j}(cos a)."""
    top = max(wns)
    B = [mp.mpf(0)] * top
    ca = mp.cos(a)
    for d, n in zip(amps, wns):
        for j in range(n):
            B[j] += 2 * mp.mpf(d) / amps[0] * n * mp.legendre(n - 1 - j, ca)

    def p(s):
        R = mp.sqrt(mp.sin((a - s) / 2) * mp.sin((a + s) / 2))
        return R * mp.fsum(B[j] * mp.cos((j + mp.mpf(1) / 2) * s) for j in range(top))
    return p


def nonperiodic_pressure(amps, wns, a):
    """p/p* = sum_m D_m sin((2m + 1) theta), cos theta = s/a,
    D_m = sum_i 2 (Delta_i/Delta_1) n_i (-1)^m J_{2m+1}(a n_i)."""
    D = []
    m = 0
    while True:
        d = mp.fsum(2 * mp.mpf(di) / amps[0] * n * (-1) ** m * mp.besselj(2 * m + 1, a * n)
                    for di, n in zip(amps, wns))
        D.append(d)
        if m > a * max(wns) and abs(d) < mp.mpf("1e-30"):
            break
        m += 1

    def p(s):
        th = mp.acos(s / a)
        return mp.fsum(D[k] * mp.sin((2 * k + 1) * th) for k in range(len(D)))
    return p


def stresses(p, a, x, z, periodic):
    x, z = mp.mpf(x), mp.mpf(z)
    if periodic:
        x = x - 2 * mp.pi * mp.nint(x / (2 * mp.pi))
    breaks = [-mp.pi / 2, mp.pi / 2]
    if abs(x) < a:
        breaks = [-mp.pi / 2, mp.asin(x / a), mp.pi / 2]
    if periodic:
        zeta = mp.mpc(x, z)
        G = mp.quad(lambda f: p(a * mp.sin(f)) * mp.cot((zeta - a * mp.sin(f)) / 2) * a * mp.cos(f),
                    breaks) / (2 * mp.pi)
        Gp = -mp.quad(lambda f: p(a * mp.sin(f)) / mp.sin((zeta - a * mp.sin(f)) / 2) ** 2 * a * mp.cos(f),
                      breaks) / (4 * mp.pi)
        return (G.imag + z * Gp.real, G.imag - z * Gp.real, -z * Gp.imag)

    def k(f, which):
        s = a * mp.sin(f)
        u = x - s
        rho4 = (u * u + z * z) ** 2
        num = {0: u * u * z, 1: z ** 3, 2: u * z * z}[which]
        return p(s) * num / rho4 * a * mp.cos(f)
    return tuple(-2 / mp.pi * mp.quad(lambda f, w=w: k(f, w), breaks) for w in range(3))


def points(a, rng, count):
    """(x, z) in lambda_1 = 2 pi units: depths log-spaced from 1e-9 to 5 lambda_1, x over two periods
    each side, plus points just inside and outside the contact edge and on the centre line."""
    z = np.exp(rng.uniform(math.log(1e-9), math.log(10 * math.pi), count))
    x = rng.uniform(-4 * math.pi, 4 * math.pi, count)
    near = count // 4                      # a quarter close to the contact, where the field varies most
    x[:near] = a * rng.uniform(-1.5, 1.5, near)
    z[:near] = a * np.exp(rng.uniform(math.log(1e-9), math.log(3.0), near))
    x[near:near + 2] = [a * (1 - 1e-6), -a * (1 + 1e-6)]
    z[near:near + 2] = [1e-4 * a, 1e-4 * a]
    x[near + 2] = 0.0
    x[near + 3], z[near + 3] = math.pi / 3, 10 * math.pi          # the deepest: 5 lambda_1
    return x, z


def main(out):
    rng = np.random.default_rng(20261128)
    cases = []
    for name, (amps, wns) in PROFILES.items():
        for width in WIDTHS:
            for periodic in (True, False):
                a = mp.pi * mp.mpf(width)
                p = periodic_pressure(amps, wns, a) if periodic else nonperiodic_pressure(amps, wns, a)
                x, z = points(float(a), rng, 22)
                rows = []
                for xi, zi in zip(x, z):
                    s = stresses(p, a, xi, zi, periodic)
                    rows.append([float(xi / float(a)), float(zi / float(a))] + [float(v) for v in s])
                cases.append({"profile": name, "amplitudes": amps, "wavenumbers": wns, "two_a_over_lambda1": width,
                              "domain": "periodic" if periodic else "nonperiodic", "points": rows})
                print(name, width, periodic, file=sys.stderr, flush=True)
    meta = {"problem": "plane-strain stresses below a rigid wavy surface in continuous contact (Tsukanov 2018 "
                       "pressure), normal load, lambda_1 = 2 pi, p* units, tension positive, z depth",
            "columns": ["x_over_a", "z_over_a", "sigma_xx", "sigma_zz", "sigma_xz"],
            "method": __doc__.strip().splitlines()[0], "mpmath_dps": mp.mp.dps,
            "script": "tests/data/make_wavy_interior.py", "seed": 20261128}
    Path(out).write_text(json.dumps({"meta": meta, "cases": cases}, indent=1) + "\n")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).with_name("wavy_interior.json"))
