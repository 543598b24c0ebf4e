"""Reference displacements below a periodic rigid wavy surface in continuous contact (plane strain), written to
wavy_periodic_displacement.json beside this file.  Independent of the package: nothing here imports stressfields.

Route: the pressure of one period, p/p* = sqrt(sin((a - s)/2) sin((a + s)/2)) sum_j B_j cos((j + 1/2) s) with
B_j = sum_{n_i > j} 2 (Delta_i/Delta_1) n_i P_{n_i - 1 - j}(cos a) (mpmath's Legendre functions), lambda_1 = 2 pi;
then tanh-sinh quadrature over the contact (s = a sin f, split at the point above) of the periodic line-load
kernels, the Flamant kernels summed over all periods with the datum of the periodic surface displacement:

    Re Psi_1 = ln|2 sin(y/2)|/pi,  Im Psi_1 = (-(x - s)/2 + arg(1 - e^{iy}))/pi,  G_1 = cot(y/2)/(2 pi),  y = zeta - s,

normal load: 2 mu_s u_x = (1 - 2 nu) Im Psi + z Re G, 2 mu_s u_z = -2 (1 - nu) Re Psi - z Im G;
shear traction q along +x: 2 mu_s u_x = -2 (1 - nu) Re Phi + z Im H, 2 mu_s u_z = -(1 - 2 nu) Im Phi + z Re H
(2 mu_s = E* (1 - nu), p* = E* Delta_1/2, so u/Delta_1 = the right sides over 2 (1 - nu) with p in p*).
Partial slip: q = mu [p(s; a) - p(s; c)], the stick half-width c from P(c) = (1 - fx) P(a), P = int p over the
contact (quadrature) solved by mpmath's findroot.

Run: python make_wavy_periodic_displacement.py  (about two minutes on one core)."""
from __future__ import annotations

import json
import math
from pathlib import Path

import mpmath as mp

DPS = 20
NU = mp.mpf(3) / 10
F1 = ([0.5], [1])
F2 = ([0.5, 0.01], [1, 11])
F11 = ([0.5] + [0.004] * 10, list(range(1, 12)))
PROFILES = {"F1": F1, "F2": F2, "F11": F11}
#: (profile, 2a/lambda_1): 1, 2 and 11 harmonics, 2a/lambda_1 from 1e-3 to 0.999
CASES = [("F1", 1e-3), ("F1", 0.3), ("F2", 0.3), ("F2", 0.6), ("F2", 0.999), ("F11", 0.2), ("F11", 0.6)]
#: depths (kernel units, lambda_1 = 2 pi) from 1e-9 to 5 lambda_1, and x over three periods
DEPTHS = [1e-9, 1e-9, 1e-6, 0.02, 0.15, 0.5, 2.0, 7.0, 10 * math.pi]
SLIP = [("F2", 0.3, 0.3, 0.6), ("F11", 0.6, 0.5, 0.4)]


def pressure(w, profile):
    a = mp.pi * mp.mpf(w)
    amps, wns = profile
    K = max(wns)
    B = [sum(2 * mp.mpf(d) / mp.mpf(amps[0]) * n * mp.legendre(n - 1 - j, mp.cos(a)) for d, n in zip(amps, wns)
             if n > j) for j in range(K)]

    def p(s):
        r = mp.sin((a - s) / 2) * mp.sin((a + s) / 2)
        return mp.sqrt(max(r, 0)) * mp.fsum(B[j] * mp.cos((j + mp.mpf(1) / 2) * s) for j in range(K))
    return p, a


def integrals(x, z, p, a):
    """(Re Psi, Im Psi, G) of the pressure p over its contact [-a, a]."""
    x, z = mp.mpf(x), mp.mpf(z)
    zeta = mp.mpc(x, z)
    xf = x - 2 * mp.pi * mp.nint(x / (2 * mp.pi))
    br = [-mp.pi / 2, mp.asin(xf / a), mp.pi / 2] if abs(xf) < a else [-mp.pi / 2, mp.pi / 2]

    def quad(kernel):
        return mp.quad(lambda f: p(a * mp.sin(f)) * kernel(a * mp.sin(f)) * a * mp.cos(f), br)

    re_psi = mp.re(quad(lambda s: mp.log(abs(2 * mp.sin((zeta - s) / 2))))) / mp.pi
    im_psi = mp.re(quad(lambda s: -(x - s) / 2 + mp.arg(1 - mp.exp(1j * (zeta - s))))) / mp.pi
    G = quad(lambda s: mp.cot((zeta - s) / 2)) / (2 * mp.pi) if z > 0 else mp.mpc(0)
    return re_psi, im_psi, G


def normal(x, z, p, a):
    re_psi, im_psi, G = integrals(x, z, p, a)
    k = 1 / (2 * (1 - NU))
    return k * ((1 - 2 * NU) * im_psi + z * G.real), -re_psi - k * z * G.imag


def stick_width(w, profile, fx):
    """c/a with P(c) = (1 - fx) P(a), P = int p over the contact at half-width c."""
    def load(ww):
        p, a = pressure(ww, profile)
        return mp.quad(lambda f: p(a * mp.sin(f)) * a * mp.cos(f), [-mp.pi / 2, mp.pi / 2])
    target = (1 - mp.mpf(fx)) * load(w)
    root = mp.findroot(lambda r: load(w * r) - target, mp.sqrt(1 - mp.mpf(fx)))
    return root


def points(w):
    a = math.pi * w
    xs = [0.3 * a, 2.0, -0.9 * a, a, -1.2, 0.4 + 2 * math.pi, 2.9, -5.0, 1.0]
    return [(x / a, z / a) for x, z in zip(xs, DEPTHS)]


def main():
    mp.mp.dps = DPS
    out = {"meta": {"route": __doc__.split("\n\n")[1], "dps": DPS, "nu": float(NU), "lambda_1": "2 pi",
                    "units": "x/a, z/a; u_x/Delta_1, u_z/Delta_1 with p* = E* Delta_1/2 (the package's p* = pi E* "
                             "Delta_1/lambda_1 at lambda_1 = 2 pi)"},
           "profiles": {k: {"amplitudes": v[0], "wavenumbers": v[1]} for k, v in PROFILES.items()},
           "normal": [], "slip": []}
    for name, w in CASES:
        p, a = pressure(w, PROFILES[name])
        rows = []
        for t, zt in points(w):
            ux, uz = normal(mp.mpf(t) * a, mp.mpf(zt) * a, p, a)
            rows.append([t, zt, float(ux), float(uz)])
        out["normal"].append({"profile": name, "two_a_over_lambda1": w, "points": rows})
        print(name, w, flush=True)
    for name, w, mu, fx in SLIP:
        prof = PROFILES[name]
        r = stick_width(w, prof, fx)
        pa, a = pressure(w, prof)
        pc, c = pressure(w * r, prof)
        rows = []
        k = 1 / (2 * (1 - NU))
        for t, zt in points(w)[::2]:
            x, z = mp.mpf(t) * a, mp.mpf(zt) * a
            ia, ic = integrals(x, z, pa, a), integrals(x, z, pc, c)
            re_phi, im_phi, H = (mu * (u - v) for u, v in zip(ia, ic))
            rows.append([t, zt, float(-re_phi + k * z * H.imag), float(k * (-(1 - 2 * NU) * im_phi + z * H.real))])
        out["slip"].append({"profile": name, "two_a_over_lambda1": w, "mu": mu, "fx": fx, "stick_over_a": float(r),
                            "points": rows})
        print(name, w, "slip", flush=True)
    Path(__file__).with_name("wavy_periodic_displacement.json").write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
