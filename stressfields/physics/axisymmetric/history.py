"""Arbitrary tangential loading histories at constant normal load (fretting): MDR spring memory,
surface stresses, dp/dz, tangential force and frictional dissipation.

E. Willert, F. Forsbach, V. L. Popov, "Stress tensor and gradient of hydrostatic pressure in the
contact plane of axisymmetric bodies under normal and tangential loading", eq. (27)-(28)
(docs/theory/axisymmetric.md (A65)-(A77); R. D. Mindlin, H. Deresiewicz, J. Appl. Mech. 20 (1953)
327-344).  In the method of dimensionality reduction every 1-D spring at |x| <= a
carries the history: the indenter drags the spring tops by u_x0(t); a spring sticks while
|u_x,1D(x)| < L(x) and slips (Coulomb) at |u_x,1D| = L(x), with

    L(x) = mu (E*/G*) [g(a) - g(|x|)],      G*/E* = 2(1 - nu)/(2 - nu).

Each spring is a stop operator of threshold L(x).  Written with lambda = L(x) (in units of the
indentation depth delta = g(a)), the displacement u_x,1D = s(lambda) of all springs after any
history is a piecewise linear function of lambda with slopes +-1 that ends with slope 0:

    s(lambda) = sum_k w_k min(lambda, lambda_k),

a short list of "c-terms" (lambda_k, w_k).  One term min(lambda, lambda_k) is exactly the spring
state of monotonic Cattaneo–Mindlin loading to u_x0 = lambda_k, whose stick radius c_k follows from
G* lambda_k delta = mu E* [g(a) - g(c_k)] (eq. 38; ``stick_radius``), and whose surface fields are
the verified monotonic kernels (eq. 24-26).  Eq. (27)-(28) are linear in u_x,1D, so every field of
the history is sum_k w_k (tangential part with stick radius c_k) plus the normal part: for one
reversal after loading to c_1 and reversing with radius c_r this is Mindlin–Deresiewicz,
q = mu [(p_a - p_c1) - 2 (p_a - p_cr)]; nested reversals add further terms of weight +-2.

The terms follow from the turning points of u_x0 alone (Masing's rules, Mindlin & Deresiewicz
1953): the memory is the list of dominant turning points e_1, e_2, ... (a loop closes, and is
forgotten, when u_x0 returns to the turning point that opened it; passing -e_1 restores a virgin
curve), and

    skeleton        (|e_1|,              sgn e_1)          [no turning point yet: (|u|, sgn u)]
    closed branches (|e_j+1 - e_j| / 2,  2 sgn(e_j+1 - e_j))
    current branch  (|u - e_k| / 2,      2 sgn(u - e_k)).

Because the memory holds input values (not computed radii), returning to an earlier state gives
that state exactly, bit for bit.  Terms with lambda_k beyond gross slip (lambda_k >= mu/(G*/E*))
all have c_k = 0: gross slip wipes the springs' memory, whatever the stored turning points say.

Everything here is per unit E* (stresses dimensionless, dp/dz in 1/length), as in ``surface``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..quadrature import segment_rule
from .surface import stick_radius, surface_dpdz, surface_stress

__all__ = ["State", "states", "closed_cycles", "timeline", "cycle_closures", "cycle_energy", "stick_radii",
           "current_stick_radius", "slip_zones",
           "history_stress", "history_dpdz", "tangential_force", "dissipated_energy", "spring_state"]

_INPLANE = ("xx", "yy", "xy")


@dataclass(frozen=True)
class State:
    """Memory of the MDR springs after a history: dominant turning points and the current u_x0
    (both in units of the indentation depth delta).  Equal states are equal spring fields."""

    turning: tuple[float, ...] = ()
    u: float = 0.0

    @property
    def direction(self) -> int:
        """Direction of the current branch (+1, -1; 0 in the unloaded start state)."""
        ref = self.turning[-1] if self.turning else 0.0
        return int(np.sign(self.u - ref))

    def terms(self, scale: float = 1.0) -> tuple[tuple[float, float], ...]:
        """The c-terms (lambda_k, w_k) of s(lambda) = sum w_k min(lambda, lambda_k), lambda_k in
        units of delta times ``scale`` (>= 0: the same history at another amplitude), ordered from
        the largest lambda (smallest stick radius) to the smallest (the current branch).  The first
        term always has weight +-1 and the weights sum to the current direction (+-1)."""
        e, u = self.turning, self.u
        if not e:
            return ((abs(u) * scale, float(np.sign(u))),) if u != 0.0 else ()
        out = [(abs(e[0]) * scale, float(np.sign(e[0])))]
        out += [(0.5 * abs(e[j + 1] - e[j]) * scale, 2.0 * np.sign(e[j + 1] - e[j])) for j in range(len(e) - 1)]
        out.append((0.5 * abs(u - e[-1]) * scale, 2.0 * np.sign(u - e[-1])))
        return tuple((lam, float(w)) for lam, w in out if lam > 0.0)

    def move(self, u_new: float) -> "State":
        """The state after moving u_x0 monotonically from ``self.u`` to ``u_new`` (Masing rules
        with wiping-out)."""
        u_new = float(u_new)
        if u_new == self.u:
            return self
        e = list(self.turning)
        d = 1 if u_new > self.u else -1
        if self.direction not in (0, d):
            e.append(self.u)                       # a reversal: the old position is a turning point
        while e:
            if len(e) == 1:
                if abs(u_new - e[0]) >= 2.0 * abs(e[0]):   # past -e_1: the virgin curve again
                    e = []
                break
            if abs(u_new - e[-1]) >= abs(e[-1] - e[-2]):   # the loop e_k-1 -> e_k closes
                del e[-2:]
            else:
                break
        return State(tuple(e), u_new)


def states(history) -> list[State]:
    """The spring memory after each value of the history u_x0/delta (the start is unloaded, u = 0;
    step k is reached from step k-1 by monotonic motion)."""
    h = np.asarray(history, dtype=float).ravel()
    if not np.all(np.isfinite(h)):
        raise ValueError("the history u_x0/delta must be finite")
    out, s = [], State()
    for u in h:
        s = s.move(u)
        out.append(s)
    return out


def closed_cycles(sts: list[State]) -> list[int | None]:
    """For each step j, the latest earlier step i whose state equals the state at j with a different
    state in between (a closed hysteresis cycle i -> j), else None."""
    out: list[int | None] = []
    for j, s in enumerate(sts):
        found = None
        changed = False
        for i in range(j - 1, -1, -1):
            if sts[i + 1] != s:
                changed = True
            if changed and sts[i] == s:
                found = i
                break
        out.append(found)
    return out


def _wipes(s: State, u_new: float) -> list[tuple[float, State]]:
    """The points strictly inside the monotonic move s.u -> u_new where the memory is wiped
    (a loop closes on reaching the turning point that opened it, or -e_1 restores the virgin
    curve), in the order passed, each with its state ``s.move(u)``."""
    d = 1 if u_new > s.u else -1
    e = list(s.turning)
    if s.direction not in (0, d):
        e.append(s.u)
    out = []
    while e:
        # a loop e_k-1 -> e_k closes at u = e_k-1; the last turning point is wiped at -e_1
        point = -e[0] if len(e) == 1 else e[-2]
        if not (d * (point - s.u) > 0.0 and d * (u_new - point) > 0.0):
            break
        out.append((point, s.move(point)))
        del e[-2:]
    return out


def timeline(history) -> list[tuple[int, float, State]]:
    """Every point of the path where the memory can return to an earlier state: (step, u, state)
    for each wipe inside the move into a step (``_wipes``) and for each step's end, in order."""
    out, prev = [], State()
    for j, s in enumerate(states(history)):
        if s.u != prev.u:
            out += [(j, u, mid) for u, mid in _wipes(prev, s.u)]
        out.append((j, s.u, s))
        prev = s
    return out


def cycle_closures(history) -> list[tuple[int, int] | None]:
    """For each step j the outermost hysteresis cycle that closes during the move into it (at its
    end or on the way): (k, i), indices into ``timeline``, k the last point of step j whose state
    equals that of an earlier point i (the latest such, with a different state in between), else
    None.  The cycles closing within one monotonic move are nested, so the last one encloses the
    others (docs/theory/axisymmetric.md (A95))."""
    line = timeline(history)
    out: list[tuple[int, int] | None] = [None] * len({j for j, _, _ in line})
    for k, (j, _, s) in enumerate(line):
        changed = False
        for i in range(k - 1, -1, -1):
            if line[i + 1][2] != s:
                changed = True
            if changed and line[i][2] == s:
                out[j] = (k, i)
                break
    return out


def _broadcast(*args):
    return np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in args))


def stick_radii(terms, a, nu, mu, profile) -> list[np.ndarray]:
    """Stick radius c_k of every term: G* lambda_k delta = mu E* [g(a) - g(c_k)] (eq. 38); 0 for
    lambda_k at or beyond gross slip."""
    return [np.asarray(stick_radius(a, nu, mu, lam, profile), dtype=float) for lam, _ in terms]


def current_stick_radius(terms, a, nu, mu, profile) -> np.ndarray:
    """Radius of the zone that does not slip at this step: the stick radius of the current branch
    (a when nothing has been loaded).  Equals the Cattaneo–Mindlin c under monotonic loading."""
    if not terms:
        return np.broadcast_to(np.asarray(a, dtype=float), np.broadcast_shapes(*(np.shape(v) for v in (a, nu, mu))))
    return stick_radii(terms[-1:], a, nu, mu, profile)[0]


def slip_zones(terms, a, nu, mu, profile) -> list[tuple[float, float, int, bool]]:
    """Annuli (inner, outer, direction, slipping_now) of the spring field for scalar a, nu, mu:
    in each annulus u'_x,1D = direction * (-mu E*/G* g'), i.e. the springs carry the limiting
    friction of that sign (slipping now) or a locked-in slip from an earlier branch; inside the
    innermost radius the springs have never slipped since the last wipe."""
    cs = [float(c) for c in stick_radii(terms, a, nu, mu, profile)]
    zones = []
    outer = float(a)
    slope = sum(w for _, w in terms)               # slope of s(lambda) next to lambda = 0 (r = a)
    for k in range(len(terms) - 1, -1, -1):
        inner = cs[k]
        if inner < outer:
            zones.append((inner, outer, int(round(slope)), k == len(terms) - 1))
        slope -= terms[k][1]
        outer = min(outer, inner)
    return zones


def spring_state(x, terms, a, nu, mu, profile) -> np.ndarray:
    """u_x,1D(x) / delta of the MDR springs, s(L(x)) = sum w_k min(L(x), lambda_k), |x| <= a."""
    gstar = 2.0 * (1.0 - np.asarray(nu, dtype=float)) / (2.0 - np.asarray(nu, dtype=float))
    lam = np.asarray(mu, dtype=float) / gstar * (1.0 - profile.g(x) / profile.g(a))
    return sum((w * np.minimum(lam, lk) for lk, w in terms), np.zeros(np.shape(lam)))


# -- surface fields ------------------------------------------------------------------------------

def _flip(sign, x):
    return np.where(np.asarray(sign) < 0, -np.asarray(x, dtype=float), x)


def history_stress(x, y, a, nu, mu, profile, terms, *, components=("xx", "yy", "zz", "xy", "xz", "yz"),
                   method="closed", rtol=1e-10, radii=None, width=None) -> dict[str, np.ndarray]:
    """Surface stress tensor / E* after a loading history with c-terms ``terms`` (``State.terms``),
    eq. (27)-(28) written as sum_k w_k (monotonic tangential field with stick radius c_k, eq. 24-25)
    plus the normal part (eq. 9).

    The smallest-c term is evaluated together with the normal part in one ``surface_stress`` call
    with the net direction sigma_0 = sum w_k (+-1; for -1 by the mirror x -> -x, under which the
    normal part is even and the tangential part odd, sigma_xy the other way round); every other
    term adds w_k [S(c_k) - S(c_min)], the field of the annulus c_min < r < c_k, which is exactly 0
    where r <= c_min (both in their stick zones).  sigma_xz is purely tangential and summed
    directly.  So a single term is exactly the monotonic result, and the unbounded or
    direction-dependent values at a conical tip r = 0 are those of ``surface_stress``.
    Arguments as in ``surface_stress`` (a, nu, mu, x, y broadcast); ``radii``: the stick radii c_k
    of the terms where known otherwise (a monotonic load given as a force, a sticking flat punch:
    ``loading.stick``; None: ``stick_radii``); ``width``: a - c of the first term from its slip
    ratio (``profiles.annulus_width``), handed to ``surface_stress`` (None: a - c)."""
    comps = tuple(components)
    if not terms:
        return surface_stress(x, y, a, a, nu, mu, profile, components=comps, method=method, rtol=rtol)
    if radii is not None and len(terms) == 1 and terms[0][1] == 1.0:
        # a monotonic load: the one call the construction below makes, without its copies
        return surface_stress(x, y, a, radii[0], nu, mu, profile, components=comps, method=method, rtol=rtol,
                              width=width)
    x, y, a, nu, mu = _broadcast(x, y, a, nu, mu)
    cs = stick_radii(terms, a, nu, mu, profile) if radii is None else radii
    weights = [w for _, w in terms]
    sigma0 = sum(weights)
    need = tuple(dict.fromkeys(comps + ("xz",)))
    kw = dict(method=method, rtol=rtol)
    base = surface_stress(_flip(sigma0, x), y, a, cs[0], nu, mu, profile, components=need, width=width, **kw)
    out = {k: base[k].copy() for k in comps if k != "xz"}
    if "xy" in out and sigma0 < 0:
        out["xy"] = -out["xy"]
    inplane = tuple(k for k in _INPLANE if k in comps)
    r = np.hypot(x, y)
    if len(terms) > 1:
        ref = base if sigma0 > 0 else surface_stress(x, y, a, cs[0], nu, mu, profile, components=need, **kw)
        xz_n = ref["xz"]
        group = np.zeros(x.shape)                   # net weight of the terms sharing c_min
        xz = np.zeros(x.shape)
        for ck, wk in zip(cs, weights):
            same = ck == cs[0]
            group += np.where(same, wk, 0.0)
            if np.all(same):
                continue
            sk = surface_stress(x, y, a, ck, nu, mu, profile, components=need, **kw)
            with np.errstate(invalid="ignore"):
                for k in inplane:
                    out[k] += wk * np.where((r <= cs[0]) | same, 0.0, sk[k] - ref[k])
            xz += np.where(same, 0.0, wk * sk["xz"])
        if "xz" in comps:
            with np.errstate(invalid="ignore"):
                out["xz"] = xz + np.where(group != 0.0, group * xz_n, 0.0)
    elif "xz" in comps:
        out["xz"] = sigma0 * base["xz"]
    return {k: out[k] for k in comps}


def history_dpdz(x, y, a, nu, mu, profile, terms, *, method="closed", rtol=1e-10, radii=None,
                 width=None) -> np.ndarray:
    """d p_h/dz at z = 0+ / E* after a loading history: normal part eq. (11) plus
    sum_k w_k (tangential part of eq. 26 with stick radius c_k), the tangential part being
    (2(1+nu)/3) dq/dx (local).  Built like ``history_stress``: the annulus term w_k [D(c_k) -
    D(c_min)] vanishes exactly where r > c_k (both slip there, q = mu p locally).  Unbounded on
    r = a (-inf sgn(x) sigma_0, contact side) and on every stick edge r = c_k > 0 (+inf sgn(x)
    times the net weight of the terms with that radius); 0 there on x = 0.  ``radii``, ``width`` as
    for ``history_stress``."""
    if not terms:
        return surface_dpdz(x, y, a, a, nu, mu, profile, method=method, rtol=rtol)
    if radii is not None and len(terms) == 1 and terms[0][1] == 1.0:
        return surface_dpdz(x, y, a, radii[0], nu, mu, profile, method=method, rtol=rtol, width=width)
    x, y, a, nu, mu = _broadcast(x, y, a, nu, mu)
    cs = stick_radii(terms, a, nu, mu, profile) if radii is None else radii
    weights = [w for _, w in terms]
    sigma0 = sum(weights)
    kw = dict(method=method, rtol=rtol)
    out = surface_dpdz(_flip(sigma0, x), y, a, cs[0], nu, mu, profile, width=width, **kw)
    if len(terms) == 1:
        return out
    r = np.hypot(x, y)
    ref = out if sigma0 > 0 else surface_dpdz(x, y, a, cs[0], nu, mu, profile, **kw)
    edges = []
    for ck, wk in zip(cs[1:], weights[1:]):
        skip = (r > ck) | (r == 0.0) | (ck == cs[0])
        if np.all(skip):
            continue
        dk = surface_dpdz(x, y, a, ck, nu, mu, profile, **kw)
        with np.errstate(invalid="ignore"):
            out = out + wk * np.where(skip, 0.0, dk - ref)
        edges.append(ck)
    # on a stick edge r = c the infinities of two terms meet: the sign is that of the net weight
    for ck in [cs[0]] + edges:
        on = (r == ck) & (ck > 0.0) & (ck < a)
        if np.any(on):
            net = sum(np.where(cj == ck, wj, 0.0) for cj, wj in zip(cs, weights))
            with np.errstate(invalid="ignore"):
                out = np.where(on, np.where(x == 0.0, 0.0, np.sign(x) * net * math.inf), out)
    return out


# -- loads and energy ----------------------------------------------------------------------------

def tangential_force(terms, a, nu, mu, profile) -> np.ndarray:
    """F_x / (mu F_N) = sum_k w_k [F_N(a) - F_N(c_k)] / F_N(a): each c-term carries the
    Cattaneo–Mindlin force mu [F_N(a) - F_N(c_k)] (eq. 10 at radius c_k); for the paraboloid one
    term is Mindlin's mu F_N (1 - (c/a)^3).  At mu = 0 the limit mu -> 0+ (+-1, gross slip)."""
    a_ = np.asarray(a, dtype=float)
    fa = profile.normal_force(a_)
    total = np.zeros(np.broadcast_shapes(*(np.shape(v) for v in (a, nu, mu))))
    for (_lam, w), c in zip(terms, stick_radii(terms, a, nu, mu, profile)):
        total = total + w * (1.0 - profile.normal_force(c) / fa)
    return total


def _s(terms, lam):
    return sum((w * np.minimum(lam, lk) for lk, w in terms), np.zeros(np.shape(lam)))


def _step_dissipation(before, after, du, a, nu, mu, profile, nodes) -> float:
    """Energy dissipated by the springs while u_x0 moves monotonically by du (units of delta),
    divided by mu F_N delta: each spring of width dx slips by |du| - |s' - s| against the friction
    force G* L(x) dx, so W = 2 int_0^a G* L (|du| - |s'(L) - s(L)|) dx; with L = (mu/k) delta
    (1 - g/g(a)), k = G*/E*, and F_N = 2 E* int_0^a (g(a) - g) dx (eq. 10) the friction
    coefficient cancels except in L.  The integrand is smooth between the stick radii of the
    terms (and the knots of a tabulated profile), where the rule is split."""
    gstar = 2.0 * (1.0 - nu) / (2.0 - nu)
    delta = float(profile.depth(a))
    lams = sorted({lk for lk, _ in before} | {lk for lk, _ in after})
    cuts = [float(stick_radius(a, nu, mu, lam, profile)) for lam in lams] if mu > 0.0 else []
    cuts += [float(r) for r in getattr(profile, "r", ()) if 0.0 < r < a]
    pts = np.array(sorted({0.0, float(a), *[c for c in cuts if 0.0 < c < a]}))
    xs, ws = segment_rule(pts[None, :], nodes)
    xs, ws = xs[0], ws[0]
    ghat = 1.0 - profile.g(xs) / delta              # (g(a) - g) / delta
    lam = mu / gstar * ghat
    slip = np.maximum(abs(du) - np.abs(_s(after, lam) - _s(before, lam)), 0.0)
    return float(2.0 * delta * np.sum(ws * ghat * slip) / profile.normal_force(a))


def cycle_energy(history, a, nu, mu, profile, *, scale: float = 1.0, nodes: int = 24) -> np.ndarray:
    """Energy dissipated in the hysteresis cycle that closes during the move into each step (the
    outermost one, ``cycle_closures``; 0 where none closes), divided by mu F_N delta; scalar a, nu,
    mu.  W(closing point) - W(opening point), the dissipation (A76) summed up to each point of the
    ``timeline``: a cycle closing inside a step is counted at that step (docs/theory/axisymmetric.md
    (A95))."""
    a, nu, mu = float(a), float(nu), float(mu)
    line = timeline(history)
    energy, total, prev = [], 0.0, State()
    for _, u, s in line:
        if u != prev.u:
            total += _step_dissipation(prev.terms(scale), s.terms(scale), (u - prev.u) * scale, a, nu, mu,
                                       profile, nodes)
        energy.append(total)
        # a wipe point lies on the move into its step: the next sub-move continues from it
        prev = s
    return np.array([0.0 if c is None else energy[c[0]] - energy[c[1]] for c in cycle_closures(history)])


def dissipated_energy(history, a, nu, mu, profile, *, scale: float = 1.0, nodes: int = 24) -> np.ndarray:
    """Cumulative frictional energy dissipated from the unloaded start up to each step of the
    history (u_x0/delta values times ``scale``), divided by mu F_N delta; scalar a, nu, mu.

    Over a closed cycle i -> j (``closed_cycles``) the elastic energy returns to its value, so
    W[j] - W[i] is the area of the F_x-u_x0 hysteresis loop.  At mu = 0 the limit mu -> 0+
    (W = sum |du|, pure sliding).  Exact (to rounding) for cone and paraboloid, whose integrands
    are polynomials in x; Gauss–Legendre with the t = w^2 grading of ``segment_rule`` otherwise."""
    a, nu, mu = float(a), float(nu), float(mu)
    sts = states(history)
    out, total = [], 0.0
    prev = State()
    for s in sts:
        if s.u != prev.u:
            total += _step_dissipation(prev.terms(scale), s.terms(scale), (s.u - prev.u) * scale, a, nu, mu,
                                       profile, nodes)
        out.append(total)
        prev = s
    return np.array(out)
