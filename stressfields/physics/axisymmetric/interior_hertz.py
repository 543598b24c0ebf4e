"""Closed forms below the surface: the Hertz field under normal load and the flat-punch kernel.

Coordinates are divided by the contact radius a (x along the later tangential load, z >= 0 the
depth into the body); stresses are tension-positive.  ``hertz_unit`` returns the Hertz field
divided by the maximum pressure p0 (Huber 1904; Hamilton 1983; Johnson, Contact Mechanics 1985,
sec. 3.4), written in the stable forms of docs/theory/interior.md (I3)-(I9): there is no 1/r^2
term left, so points on or next to the axis (r = 0, 1e-16, 1e-8) and far away (r, z ~ 1e4) are
evaluated without cancellation.  ``punch_unit`` is the flat punch of radius 1 pressed to depth 1
into a half-space with E* = 1 (Sneddon 1946), obtained as the a-derivative of the Hertz field,
docs/theory/interior.md (I10)-(I14), with the analytic scaling derivative.

Accuracy contract: closed forms, relative error at most 1e-12 of |value| everywhere the value is
finite, far field and next to edges included (limited only by the conditioning of the field with
respect to the coordinates, e.g. next to the edge ring r = a, z = 0).  Pure NumPy.
"""
from __future__ import annotations

import math

import numpy as np

from ..flags import quiet
from .hertz_geometry import coords, geometry, one_minus_m_atan, x_minus_sin

__all__ = ["COMPONENTS", "hertz_unit", "punch_unit", "sliding_unit", "sliding_punch_unit", "sliding_scalars",
           "sliding_punch_scalars", "mns", "punch_radial"]

COMPONENTS = ("xx", "yy", "zz", "xy", "xz", "yz")

def _scalars(g, nu):
    """Sigma = sigma_rr + sigma_tt, E = (sigma_rr - sigma_tt)/r^2, sigma_tt, sigma_zz and
    T = sigma_rz / r of the Hertz field / p0 (a = 1), docs/theory/interior.md (I5)-(I8), with E
    and sigma_tt in the forms (I56), (I58) that hold the factor 1 - 2 nu apart."""
    N, M, W, R = g["N"], g["M"], g["W"], g["R"]
    F = one_minus_m_atan(M)
    NR = N * R                                     # N^3 / S
    sigma = NR - 2.0 * (1.0 + nu) * N * F
    ea = 4.0 * (2.0 + N) / (3.0 * W * W * (1.0 + N) ** 2)
    eb = -4.0 * N * _m2_over_s(g) / (W * W)
    G = (1.0 + N + N * N) / (W * (1.0 + N))        # (1 - N^3) / (2 r^2), (I7a)
    H = _three_f_minus(M)
    tt = (1.0 - 2.0 * nu) * (N / W + 0.5 * N * F - 2.0 / 3.0 * G) - 0.5 * N * H      # (I58)
    return dict(F=F, NR=NR, Sigma=sigma, E=(1.0 - 2.0 * nu) * ea + eb, ea=ea, eb=eb, zz=-NR,
                T=-2.0 * M * R / W, G=G, H=H, tt=tt)


def _m2_over_s(g):
    """M^2 / S (<= 1), 0 on the edge ring (S = 0), where it multiplies N = 0."""
    M, S = g["M"], g["S"]
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(S > 0.0, M * (M / np.where(S > 0.0, S, 1.0)), 0.0)


def _cartesian(x, y, tt, E, zz, T):
    """(I8) with sigma_rr = sigma_tt + E r^2: sigma_xx = sigma_tt + E x^2, sigma_yy = sigma_tt + E y^2
    (I58).  Not Sigma/2 +- E (x^2 - y^2)/2: at nu = 1/2 sigma_tt is O((a/R)^2) of Sigma and E r^2
    in the far field next to the surface (sigma_yy at y = 0 was off by 4e4 of itself at R = 1e6 a)."""
    return {"xx": tt + E * x * x, "yy": tt + E * y * y, "zz": zz, "xy": E * x * y, "xz": x * T, "yz": y * T}


@quiet
def hertz_unit(x, y, z, nu) -> dict[str, np.ndarray]:
    """Hertz (paraboloid) stress tensor below the surface, divided by p0, at coordinates divided by
    the contact radius; docs/theory/interior.md (I5)-(I9) (Huber 1904, Hamilton 1983, Johnson 1985
    sec. 3.4, in the stable forms (I56), (I58)).  Finite everywhere in z >= 0; on the edge ring
    r = 1, z = 0 the exact limits sigma_rr = -sigma_tt = (1 - 2 nu)/3, sigma_zz = sigma_rz = 0.
    Closed form: relative error at most 1e-12 of |value| wherever the value is finite."""
    x, y, z = coords(x, y, z)
    nu = np.asarray(nu, dtype=float)
    s = _scalars(geometry(x, y, z), nu)
    return _cartesian(x, y, s["tt"], s["E"], s["zz"], s["T"])


def _derivatives(g, s, nu):
    """Scaling derivatives D f = (r d/dr + z d/dz) f of the scalars of ``_scalars``,
    docs/theory/interior.md (I11)-(I13), (I56), (I58).  They carry 1/S: infinite on the edge ring."""
    N, M, S, W, Q, R = g["N"], g["M"], g["S"], g["W"], g["Q"], g["R"]
    with np.errstate(invalid="ignore", divide="ignore"):
        dS = (M * M * W - 2.0 * N * N * Q) / S
        dNR = -N * R * (3.0 * Q + dS) / S
        dsigma = dNR - 2.0 * (1.0 + nu) * (N * s["F"] - N / S)
        dea = s["ea"] / S * (N * Q * (3.0 + N) / ((2.0 + N) * (1.0 + N)) - 4.0 * M * M)
        deb = s["eb"] / S * (1.0 + N * N - 2.0 * M * M - dS)            # D ln e_b = (2 - Q - 2M^2 - D S)/S
        dT = s["T"] / S * (2.0 * N * N - 1.0 - M * M - dS)
        tt = _tt_minus_dtt(g, s, nu)
    return dict(Sigma=dsigma, E=(1.0 - 2.0 * nu) * dea + deb, zz=-dNR, T=dT, tt_fp=tt)


def _tt_minus_dtt(g, s, nu):
    """sigma_tt - D sigma_tt of (I58), the punch's hoop stress (times pi), with D of (I11)-(I13):
    D(N F) = N F - N/S (F cancels), D(N/W) = -(N/W)(Q + 2M^2)/S, G - D G from (I13) and
    D(N H) = -N Q H/S + N H'(M) M (1 + M^2)/S.  Each part has one sign in the far field."""
    N, M, S, W, Q, G, H = g["N"], g["M"], g["S"], g["W"], g["Q"], s["G"], s["H"]
    m2, n2 = M * M, N * N
    g_dg = G * (1.0 + (n2 * Q * (2.0 + N) / ((1.0 + N + n2) * (1.0 + N)) + 2.0 * m2) / S)
    a = (N / W) * (1.0 + (Q + 2.0 * m2) / S) + 0.5 * N / S - 2.0 / 3.0 * g_dg
    nh = N * H * (1.0 + Q / S) - N * _three_f_minus_prime(M) * M * (1.0 + m2) / S
    return (1.0 - 2.0 * nu) * a - 0.5 * nh


@quiet
def punch_unit(x, y, z, nu, rm1=None) -> dict[str, np.ndarray]:
    """Flat punch of radius 1 pressed to depth 1 into a half-space with E* = 1: the stress tensor
    at coordinates divided by the punch radius, (1/pi)[S - (x d/dx + y d/dy + z d/dz) S] with S
    the Hertz field of ``hertz_unit``, docs/theory/interior.md (I10)-(I14).  On the edge ring
    r = 1, z = 0 the normal stresses are -inf and the shears NaN (their sign depends on the
    direction of approach; zero where the component vanishes by symmetry).  Closed form: relative
    error at most 1e-12 of |value| wherever the value is finite.  ``rm1``: r - 1 without rounding,
    optional (see ``geometry``)."""
    x, y, z = coords(x, y, z)
    nu = np.asarray(nu, dtype=float)
    g = geometry(x, y, z, rm1)
    s = _scalars(g, nu)
    d = _derivatives(g, s, nu)
    with np.errstate(invalid="ignore"):
        k = _cartesian(x, y, d["tt_fp"], -(s["E"] + d["E"]), s["zz"] - d["zz"], -d["T"])
    out = {c: v / math.pi for c, v in k.items()}
    _edge_ring(out, x, y, g["S"] == 0.0)
    return out


def _edge_ring(out, x, y, ring):
    """Values on the punch's edge ring (S = 0): docs/theory/interior.md (I14)."""
    if not np.any(ring):
        return
    for c in ("xx", "yy", "zz"):
        out[c] = np.where(ring, -math.inf, out[c])
    for c, factor in (("xy", x * y), ("xz", x), ("yz", y)):
        out[c] = np.where(ring, np.where(factor == 0.0, 0.0, math.nan), out[c])


# -- sliding (Hamilton & Goodman 1966): traction q0 sqrt(1 - r^2) along +x ----------------------

# T20 - T31 = 2 int_0^phi sin^4 t dt = sum_{k>=2} (-1)^k (4^(2k+1) - 2^(2k+4)) phi^(2k+1) / (16 (2k+1)!)
# (the k = 0, 1 terms cancel); 24 terms reach 16^25/51! < 1e-35 at phi = 1
_SIN4 = [(-1.0) ** k * (4.0 ** (2 * k + 1) - 2.0 ** (2 * k + 4)) / (16.0 * math.factorial(2 * k + 1))
         for k in range(2, 26)]


def _t20_minus_t31(phi, t20, t31):
    """T20 - T31 = 2 int_0^phi sin^4 t dt >= 0, docs/theory/interior.md (I57): the two agree to
    O(phi^3) ~ (2/3)/M^3 while the difference is (2/5) phi^5 (the far field, phi ~ 1/R), so the
    series below phi = 1 (at R = 7.9e3 a the difference lost 8 digits: sigma_yy of the sliding
    field at y = 0 next to the surface off by 3.5e-8 of itself), the difference above (at most a
    factor 3 lost, at phi = 1)."""
    small = phi < 1.0
    p2 = phi * phi
    series = np.zeros_like(phi)
    for c in _SIN4[::-1]:
        series = series * p2 + c
    return np.where(small, series * p2 * p2 * phi, t20 - t31)


# 3 F(M) - 1/(1 + M^2) = sum_k (-1)^(k+1) (2 - 2k)/(2k + 1) t^(2k), t = 1/M (the k = 1 term is 0)
_H_SERIES = [(-1.0) ** (k + 1) * (2.0 - 2.0 * k) / (2 * k + 1) for k in range(1, 30)]


def _three_f_minus(M):
    """H(M) = 3 F(M) - 1/(1 + M^2) >= 0, docs/theory/interior.md (I21): the two terms agree to
    O(1/M^2) and H ~ (2/5) / M^4 in the far field, where the difference would lose all digits
    (the axial shear of the sliding field is -N H / 2 there); series in t = 1/M for M >= 2, the
    direct difference below (at most one digit lost, at M = 2)."""
    far = M >= 2.0
    t2 = 1.0 / np.where(far, M, 1.0) ** 2
    series = np.zeros_like(t2)
    for c in _H_SERIES[::-1]:
        series = series * t2 + c
    direct = 3.0 * one_minus_m_atan(M) - 1.0 / (1.0 + M * M)
    return np.where(far, series * t2, direct)


def _three_f_minus_prime(M):
    """H'(M) = 3 F'(M) + 2M/(1 + M^2)^2 of ``_three_f_minus`` (I58): its terms agree to O(1/M^3)
    and H' ~ -(8/5)/M^5 in the far field, so the derivative of the series for M >= 2; below,
    F' = -arctan(1/M) + M/(1 + M^2) (M <= 1) or (F (1 + M^2) - 1)/(M (1 + M^2)) (as (I25))."""
    far = M >= 2.0
    t = 1.0 / np.where(far, M, 1.0)
    t2 = t * t
    series = np.zeros_like(t2)
    for k, c in list(enumerate(_H_SERIES, start=1))[::-1]:
        series = series * t2 - 2.0 * k * c
    opm = 1.0 + M * M
    F = one_minus_m_atan(M)
    with np.errstate(invalid="ignore", divide="ignore"):
        fp = np.where(M <= 1.0, -(0.5 * math.pi - np.arctan(np.minimum(M, 1.0))) + M / opm,
                      (F * opm - 1.0) / np.where(M > 1.0, M * opm, 1.0))
    return np.where(far, series * t2 * t, 3.0 * fp + 2.0 * M / (opm * opm))


def sliding_scalars(g):
    """The radial functions of the sliding field, docs/theory/interior.md (I19)-(I21), with a = 1,
    q0 = 1: D = (1/r) d/dr, Lambda the harmonic potential of (I18) and Phi = Lambda_zz.  Every
    1/S is taken with the factor (M^2, N^2 or M N, each <= S) that makes it bounded; on the edge
    ring (S = 0) those products multiply a vanishing factor and are set to 0 (I22)."""
    M, N, S = g["M"], g["N"], g["S"]
    # M/S and N/S (<= S^(-1/2)), not 1/S: next to the edge ring at a subnormal depth (z = 5e-324 a)
    # 1/S overflowed and the bounded products became -inf
    with np.errstate(invalid="ignore", divide="ignore"):
        safe = np.where(S > 0.0, S, 1.0)
        m_s, n_s = np.where(S > 0.0, M / safe, 0.0), np.where(S > 0.0, N / safe, 0.0)
    m2, mn, n2 = M * m_s, M * n_s, N * n_s
    opm = 1.0 + M * M
    opn = 1.0 + N
    phi = np.arctan2(1.0, M)
    t20 = 0.5 * x_minus_sin(2.0 * phi, 2.0 * M / opm)                 # int_u^inf ds / (sqrt(s)(1+s)^2)
    t31 = x_minus_sin(4.0 * phi, 4.0 * M * (M * M - 1.0) / (opm * opm)) / 16.0   # int sqrt(s)/(1+s)^3
    dgz = -(2.0 * math.pi / 3.0) * (2.0 + N) / (opm * opm * opn * opn)
    bracket = 4.0 * M * M * (2.0 + N) / (opm * opn * opn) - N * (3.0 + N) / opn ** 3
    zd2gz = (2.0 * math.pi / 3.0) * mn * bracket / (opm * opm)           # z D^2 g_z
    return dict(
        P=-math.pi * t20,                                               # D Phi = g_zz
        H=_three_f_minus(M),                                            # (Phi_z - z D Phi) = -pi N H
        Dg=g["z"] * dgz + math.pi * t31,
        J=_t20_minus_t31(phi, t20, t31),                               # (z D g_z - D g - D Phi)/pi (I57)
        D2g=zd2gz - 2.0 * math.pi * M * m2 / opm ** 3,                  # D^2 g = z D^2 g_z - D^2 g_Psi
        Dgz=dgz,
        zD2gz=zd2gz,
        zDgzz=2.0 * math.pi * N * m2 / (opm * opm),                     # z D^2 Phi
        zgzzz=2.0 * math.pi * M * n2 / opm,                             # z D Phi_z
    )


def sliding_unit(x, y, z, nu) -> dict[str, np.ndarray]:
    """Hertz sliding field (Hamilton & Goodman 1966; Hamilton 1983): the stress tensor below the
    surface under the tangential traction q = q0 sqrt(1 - r^2) along +x (sigma_xz = -q at z = 0),
    divided by q0, at coordinates divided by the contact radius; docs/theory/interior.md
    (I18)-(I22), written with the radial functions of the harmonic potential of the Cerruti
    superposition, none of which is divided by r (the axis r = 0, 1e-16, 1e-8 needs no branch).
    Finite and continuous everywhere in z >= 0, the edge ring r = 1, z = 0 included.  Closed form:
    relative error at most 1e-12 of |value| everywhere the value is finite, far field and next to
    edges included (where a component passes through zero: of the largest component)."""
    x, y, z = coords(x, y, z)
    nu = np.asarray(nu, dtype=float)
    g = geometry(x, y, z)
    return _sliding_cartesian(x, y, z, nu, sliding_scalars(g), g["N"])


def _sliding_cartesian(x, y, z, nu, s, N=None):
    """(I21): the Cartesian components from the radial functions; the shear sigma_xz as the sum of
    two terms of one sign ((Phi_z - z D Phi)/(2 pi), which is -N H / 2 for the sliding field or
    s["X"] if given, and -x^2 z D^2 Phi / (2 pi)), so that the far-field cancellation of Phi_z
    against z D Phi (exact for a point load) never happens in rounding."""
    x2, y2 = x * x, y * y
    xz0 = s["X"] if "X" in s else -0.5 * N * s["H"]
    # D g = z D g_z - P - pi J (I57): D g, -P and z D g_z agree to O(1/R^2) relative in the far
    # field, so the sums of (I21) that hold them are formed from P, z D g_z and J
    P, J, zdgz = s["P"], s["J"], z * s["Dgz"]
    k = 1.0 / (4.0 * math.pi)
    p2, q2, j2 = (2.0 - 4.0 * nu) * P, (1.0 - 2.0 * nu) * zdgz, 2.0 * math.pi * nu * J
    xx = 2.0 * x * (p2 - 3.0 * (q2 + j2) - x2 * s["zD2gz"] + 2.0 * nu * x2 * s["D2g"])
    yy = 2.0 * x * (-(q2 + j2) - y2 * s["zD2gz"] + 2.0 * nu * y2 * s["D2g"])
    xy = y * (p2 - 2.0 * (q2 + j2) - 2.0 * x2 * s["zD2gz"] + 4.0 * nu * x2 * s["D2g"])
    return {"xx": k * xx, "yy": k * yy, "zz": -2.0 * k * x * s["zgzzz"], "xy": k * xy,
            "xz": xz0 - 2.0 * k * x2 * s["zDgzz"], "yz": -2.0 * k * x * y * s["zDgzz"]}


# -- the sliding punch: traction (1/pi)/sqrt(1 - r^2) along +x, the rho-derivative of rho T(x/rho) --

def sliding_punch_scalars(g):
    """The radial functions of (I19) for the traction 1/sqrt(1 - r^2) (a = 1), whose harmonic
    potential is Phi = 2 pi arctan(1/M): docs/theory/interior.md (I30)-(I31).  Each is f = k f_s -
    (r d/dr + z d/dz) f_s of the sliding one f_s of degree k, in closed form; every 1/S comes with
    powers of M and N that keep the product of order S^(-1/2) (the edge-ring singularity)."""
    M, N, S = g["M"], g["N"], g["S"]
    z = g["z"]
    with np.errstate(invalid="ignore", divide="ignore"):
        inv_s = np.where(S > 0.0, 1.0 / np.where(S > 0.0, S, 1.0), 0.0)
    m2, n2 = M * M, N * N
    opm, opn = 1.0 + m2, 1.0 + N
    num = N - m2 * (2.0 + N)
    bracket = 2.0 * (m2 - n2) * inv_s + 4.0 * m2 / opm - 2.0 * N / opn
    zd2gz = 2.0 * math.pi * (M * N * inv_s) * ((-N - 4.0 * m2 - m2 * N) - num * bracket) * inv_s / (opm * opn) ** 2
    dgz = 2.0 * math.pi * num * inv_s / (opm * opn) ** 2
    m3s = M * (m2 * inv_s)
    return dict(
        P=-2.0 * math.pi * M * inv_s / opm,                                      # D Phi
        X=-N * inv_s / opm,                                                      # (Phi_z - z D Phi)/(2 pi)
        Dg=z * dgz + 2.0 * math.pi * m3s / (opm * opm),
        J=2.0 * M * inv_s / (opm * opm),                                       # (z D g_z - D g - D Phi)/pi (I57)
        D2g=zd2gz + 2.0 * math.pi * m3s * ((m2 + 5.0 * n2 + m2 * (n2 - 3.0 * m2)) * inv_s) * inv_s / opm ** 3,
        Dgz=dgz,
        zD2gz=zd2gz,
        zDgzz=-2.0 * math.pi * (m2 * inv_s) * (N * inv_s) * ((3.0 * n2 - m2 + m2 * (n2 - 3.0 * m2)) * inv_s)
        / (opm * opm),                                                           # z D^2 Phi
        zgzzz=2.0 * math.pi * (M * inv_s) * (n2 * inv_s) * ((3.0 * m2 - n2) * inv_s),   # z D Phi_z
    )


@quiet
def sliding_punch_unit(x, y, z, nu, rm1=None) -> dict[str, np.ndarray]:
    """The sliding flat punch: stress tensor below the surface under the tangential traction
    q = 1/(pi sqrt(1 - r^2)) along +x (sigma_xz = -q at z = 0; the friction traction mu p of a
    flat punch of radius 1 pressed to depth 1 into a half-space with E* = 1, per mu), at
    coordinates divided by the punch radius; equal to (1/pi)[T - (x d/dx + y d/dy + z d/dz) T]
    with T = ``sliding_unit``, docs/theory/interior.md (I30)-(I32).  No division by r.  On the
    edge ring r = 1, z = 0 the values of (I32).  Closed form: relative error at most 1e-12 of
    |value| everywhere the value is finite.  ``rm1``: r - 1 without rounding, optional (see
    ``geometry``)."""
    x, y, z = coords(x, y, z)
    nu = np.asarray(nu, dtype=float)
    g = geometry(x, y, z, rm1)
    with np.errstate(invalid="ignore"):
        k = _sliding_cartesian(x, y, z, nu, sliding_punch_scalars(g))
    out = {c: v / math.pi for c, v in k.items()}
    _sliding_edge_ring(out, x, y, nu, g["S"] == 0.0)
    return out


def _sliding_edge_ring(out, x, y, nu, ring):
    """Values on the sliding punch's edge ring (S = 0), docs/theory/interior.md (I32): 0 where the
    component vanishes by symmetry (odd in x: xx, yy, zz, yz; odd in y: xy, yz), else the sign of
    the leading d^(-1/2) term over the directions omega into the body (s = d cos omega, z =
    d sin omega, 0 < omega < pi, probed at d = 1e-10 on 181 directions): one sign everywhere with
    a leading term above 1e-3 of the largest one gives +-inf, anything else NaN (the limit depends
    on the direction).  sigma_xz is -inf and sigma_xx -inf sgn x on the whole ring; the others
    depend on the position on the ring and on nu."""
    idx = np.flatnonzero(np.broadcast_to(ring, out["xx"].shape))
    if not idx.size:
        return
    xs, ys = (np.broadcast_to(v, out["xx"].shape).ravel()[idx] for v in (x, y))
    nus = np.broadcast_to(nu, out["xx"].shape).ravel()[idx]
    d = 1e-10
    om = np.linspace(0.0, math.pi, 183)[1:-1]
    rr = 1.0 + d * np.cos(om)
    g = geometry(xs[:, None] * rr, ys[:, None] * rr, np.broadcast_to(d * np.sin(om), (idx.size, om.size)),
                  np.broadcast_to(d * np.cos(om), (idx.size, om.size)))
    probe = _sliding_cartesian(xs[:, None] * rr, ys[:, None] * rr, g["z"], nus[:, None], sliding_punch_scalars(g))
    big = np.max([np.max(np.abs(v), axis=1) for v in probe.values()], axis=0)
    zero = {"xx": xs == 0.0, "yy": xs == 0.0, "zz": xs == 0.0, "xy": ys == 0.0, "xz": np.zeros(idx.size, bool),
            "yz": (xs == 0.0) | (ys == 0.0)}
    for c in COMPONENTS:
        v = probe[c]
        tol = 1e-3 * big[:, None]
        sign = np.where(np.all(v < -tol, axis=1), -1.0, np.where(np.all(v > tol, axis=1), 1.0, math.nan))
        flat = out[c].reshape(-1).copy() if out[c].shape else out[c].reshape(1).copy()
        flat[idx] = np.where(zero[c], 0.0, sign * math.inf)
        out[c] = flat.reshape(out[c].shape)



# -- the punch's radial functions at once (the nodes of the superposition (I15)) ----------------

def mns(rm1, zs, z2):
    """S, M, N of ``geometry`` (I2)-(I3) for z > 0 from r - 1 and z (and z^2), without its guards
    (S >= 2 z > 0 there, so M N = z divides by a positive root)."""
    A = rm1 + 2.0
    A *= rm1
    A += z2
    S = A * A
    S += 4.0 * z2
    np.sqrt(S, out=S)
    if not (np.min(S) > 1e-150 and np.max(S) < 1e150):    # A^2 and z^2 under- or overflow: hypot (7x slower)
        S = np.hypot(A, 2.0 * zs)
    root = np.abs(A)
    root += S
    root *= 0.5
    np.sqrt(root, out=root)
    other = zs / root
    big = A >= 0.0
    return S, np.where(big, root, other), np.where(big, other, root)


@quiet
def punch_radial(rs, zs, rm1, nu):
    """The flat punch of radius 1 (depth 1, E* = 1) as its four radial functions, times pi:
    Sigma = sigma_rr + sigma_tt, sigma_zz, E = (sigma_rr - sigma_tt)/r^2 and T = sigma_rz/r at
    (r, z) = (rs, zs), z > 0, with ``rm1`` = r - 1 without rounding; docs/theory/interior.md
    (I53): (I10)-(I13) with the F(M) terms cancelled analytically (no arctan), E + D E as the two
    terms of one sign of (I56) (no switch at the axis) and each subexpression formed once, in
    place where it can be (a fresh temporary per operation cost 3x the time: the allocator
    returns and re-faults the pages).  The Cartesian components are (I8) of these; they equal
    those of ``punch_unit`` to 4e-15 of the largest component (2e5 points, r in [0, 1e4], r - 1
    down to +-1e-12, z in [1e-12, 1e4]; both against extended precision),
    and the decimal reference of (I10) within 1e-12 of |value| out to R = 1e8 (every polar angle,
    nu = 0.3), which is the accuracy the superposition needs.  Finite for z > 0."""
    r2 = rs * rs
    z2 = zs * zs
    S, M, N = mns(rm1, zs, z2)
    m2, n2 = M * M, N * N
    W = r2 + z2
    W += 1.0
    W += S
    inv_s = np.reciprocal(S, out=S)
    Q = 2.0 * r2
    Q /= W
    onepn = N + 1.0
    twopn = N + 2.0
    NR = n2 * N
    NR *= inv_s                                        # N^3 / S
    dS = m2 * W                                        # D S (I11)
    tmp = n2 * Q
    tmp *= 2.0
    dS -= tmp
    dS *= inv_s
    nr_1 = 3.0 * Q                                     # NR - D(NR) (I11)
    nr_1 += dS
    nr_1 *= inv_s
    nr_1 += 1.0
    nr_1 *= NR
    sigma = N * inv_s                                  # Sigma - D Sigma: the N F terms cancel (I53)
    sigma *= -2.0 * (1.0 + nu)
    sigma += nr_1
    t_p = 2.0 * n2                                     # -D T = (T/S)(1 + M^2 + D S - 2 N^2) (I11)
    t_p -= 1.0
    t_p -= m2
    t_p -= dS
    t_p *= M
    t_p *= n2
    t_p *= inv_s
    t_p *= inv_s
    t_p *= 2.0
    t_p /= W                                           # with T = -2 M N^2 / (S W) (I8)
    # E + D E by (I56): (1 - 2 nu)(e_a + D e_a) + e_b + D e_b, each part of one sign where the sum
    # of (I7) cancelled (next to the axis, in the far field, next to the surface at nu = 1/2)
    e1 = W * onepn                                     # e_a + D e_a (I12)
    e1 *= e1
    np.divide(twopn, e1, out=e1)
    e1 *= 4.0 * (1.0 - 2.0 * nu) / 3.0
    f = N + 3.0
    f *= N
    f *= Q
    f /= twopn
    f /= onepn
    tmp = 4.0 * m2
    f -= tmp
    f *= inv_s
    f += 1.0
    e1 *= f
    e2 = n2 + 1.0                                      # e_b + D e_b = e_b (1 + (1 + N^2 - 2M^2 - D S)/S)
    e2 -= 2.0 * m2
    e2 -= dS
    e2 *= inv_s
    e2 += 1.0
    e2 *= N
    e2 *= m2
    e2 *= inv_s
    e2 /= W
    e2 /= W
    e2 *= -4.0
    e1 += e2
    e1 *= -1.0
    nr_1 *= -1.0
    return sigma, nr_1, e1, t_p
