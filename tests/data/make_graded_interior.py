"""Write graded_interior.json: the stress below a power-law graded half-space with Holl's ratio
nu = 1/(2+k) under the pressure p = (1 - rho^2)^e on the unit disc, by an independent route.

Route: the point-load field sigma_R = -chi P cos^(chi-2)(theta) / (2 pi R^2), chi = 3 + k, summed over the
disc as a plain double integral in the disc's own polar coordinates (rho, psi) with mpmath's tanh-sinh
quadrature (mp.quad, the radial interval split at rho = r), at 12 digits; not the package's rule (which
works in sinh-mapped azimuth and geometric radial panels).  Error estimate: the difference to the same
integral at quadrature degree + 1 (mp.quad's own estimate, error=True), stored per value.

Run from the repository root:  python tests/data/make_graded_interior.py  (about an hour on one core)
"""
import json
import random

import mpmath as mp

mp.mp.dps = 12


def stress(r, z, k, e):
    chi = 3 + k
    r, z, k, e = (mp.mpf(v) for v in (r, z, k, e))

    def comp(which):
        def f(rho, psi):
            dx = r - rho * mp.cos(psi)
            dy = rho * mp.sin(psi)
            R2 = dx * dx + dy * dy + z * z
            num = {"rr": dx * dx, "tt": dy * dy, "zz": z * z, "rz": dx * z}[which]
            return (1 - rho * rho) ** e * rho * num * R2 ** (-(chi + 2) / 2)
        pts = [0, r, 1] if 0 < r < 1 else [0, 1]
        val, err = mp.quad(f, pts, [0, mp.pi / 8, mp.pi], error=True)
        fac = -(chi / mp.pi) * z ** (chi - 2)
        return fac * val, abs(fac * err)

    return {c: comp(c) for c in ("rr", "tt", "zz", "rz")}


def main():
    rng = random.Random(29)
    rows = []
    for i in range(200):
        k = (0.25, 0.5, 0.75)[i % 3]
        adhesive = i % 4 == 3
        e = -(1 - k) / 2 if adhesive else (1 + k) / 2
        r = rng.choice((0.0, rng.uniform(0, 0.95), rng.uniform(0, 2.0), 1.0))
        z = 10 ** rng.uniform(-1.0, 0.3)
        s = stress(r, z, k, e)
        rows.append(dict(rho=r, z=z, k=k, e=e, **{f"sigma_{c}": float(v) for c, (v, _) in s.items()},
                         err=float(max(er for _, er in s.values()))))
        print(i, rows[-1], flush=True)
    meta = dict(problem="stress (tension positive, z into the body) at (r, 0, z), r = rho, of the pressure "
                        "p = (1 - rho^2)^e on the unit disc over the graded half-space with nu = 1/(2+k): "
                        "sigma_ij = -(chi/2 pi) z^(chi-2) int p d_i d_j R^-(chi+2) dA, chi = 3 + k",
                route="mpmath.quad (tanh-sinh) double integral in (rho, psi), 12 digits",
                script="tests/data/make_graded_interior.py")
    with open("tests/data/graded_interior.json", "w") as fh:
        json.dump(dict(meta=meta, points=rows), fh, indent=1)


if __name__ == "__main__":
    main()
