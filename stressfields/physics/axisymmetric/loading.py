"""The tangential load of the axisymmetric family as c-terms: what the one pipeline of ``fields``
evaluates, for a monotonic load and for a loading history alike.

At constant normal load every field is the normal part plus a weighted sum of Cattaneo–Mindlin
tangential parts, sum_k w_k T(c_k), T the tangential field with stick radius c_k
(docs/theory/axisymmetric.md (A69); below the surface docs/theory/interior.md (I23), (I33),
(I43)).  A monotonic load to u_x0 is one term: lambda = u_x0/delta, w = 1 and c its stick radius
(A32)-(A33), or the radius of a given force; a loading history at one of its steps is the list of
its memory terms (``history.State.terms``, Mindlin–Deresiewicz), the same for every point of that
step.  ``Monotonic`` and ``History`` split a set of points into the groups that share their terms
(``Group``) and give the loads of a step that do not depend on the point (stick radius; for a
history the tangential force and the dissipated energies).  Everything per unit E*.
"""
from __future__ import annotations

import functools
from typing import NamedTuple

import numpy as np

from . import history as hist
from .profiles import Profile, annulus_width
from .surface import stick_radius

__all__ = ["Group", "Term", "Monotonic", "History", "stick"]


class Group(NamedTuple):
    """The points ``index`` (flat indices into the points handed to ``groups``) that share their
    c-terms, with per-point arrays over the group: ``terms`` ((lambda_k, w_k), lambda_k = u_x0/delta
    of the term), their stick radii ``radii`` (c_k, the kernels' radius), ``mu`` the coefficient of
    friction the kernels take, ``width`` the slip annulus' width a - c_1 of the first term from its
    slip ratio (``profiles.annulus_width``; None: a - c_1), ``stick`` the radius of the zone that
    does not slip now and ``free`` the points in contact without tangential traction (the region
    flag's), and the arguments of the step's loads (``loads``)."""

    index: np.ndarray
    terms: tuple
    radii: list
    mu: np.ndarray
    width: np.ndarray | None
    stick: np.ndarray
    free: np.ndarray
    step: int | None = None

    def gross_weight(self) -> np.ndarray:
        """Net weight of the terms in gross slip (stick radius 0): at a conical tip sigma_xz grows
        like -mu times it times the pressure."""
        out = np.zeros(np.shape(self.mu))
        for c, (_, w) in zip(self.radii, self.terms):
            out = out + np.where(c == 0.0, w, 0.0)
        return out

    def live_terms(self, a) -> list["Term"]:
        """The terms that carry a traction at some point (``Term``), ``a`` the contact radius over
        the group.  Consecutive terms with the same radii (every term beyond gross slip has c = 0)
        are merged into one of their net weight, so each distinct field is computed once; one term
        of weight 1 adds the kernel's values unchanged."""
        merged: list[list] = []
        for k, ((lam, w), c) in enumerate(zip(self.terms, self.radii)):
            if merged and np.array_equal(merged[-1][0], c):
                merged[-1][1] += w
                merged[-1][2] = None          # a merged term has no one slip ratio
            else:
                merged.append([c, w, k == 0 and self.width is not None, lam])
        out = []
        for c, w, exact, lam in merged:
            live = (self.mu > 0.0) & (c < a)
            if w != 0.0 and np.any(live):
                on = np.flatnonzero(live)
                out.append(Term(c[on], float(w), on, self.mu[on], self.width[on] if exact else None,
                                lam[on] if exact else None))
        return out


class Term(NamedTuple):
    """One c-term of a group at the points ``on`` (indices into the group) where it carries a
    traction: stick radius ``c``, weight ``w``, the kernels' coefficient of friction ``mu`` and,
    where the term's own u_x0 is known to the kernels (a monotonic load), its annulus width a - c
    from the slip ratio and ``ux0`` = u_x0/delta (None: the kernels take a - c of the radii)."""

    c: np.ndarray
    w: float
    on: np.ndarray
    mu: np.ndarray
    width: np.ndarray | None
    ux0: np.ndarray | None


def stick(a, nu, mu, ux0, profile: Profile, radius=None):
    """(c, c_kernel, mu_kernel): the stick radius (A32)-(A33) of the displacement ``ux0`` =
    u_x0/delta (``radius`` where given, broadcast with the rest: the radius of a given force) and
    what the kernels take for it.  A sticking flat punch (c = a with u_x0 > 0 and mu > 0) carries the
    sliding traction with mu E* delta replaced by G* u_x0 (A37), (A59): the kernels take c = 0,
    mu = (G*/E*) u_x0/delta."""
    c = stick_radius(a, nu, mu, ux0, profile)
    if radius is not None:
        c = np.where(ux0 == 0.0, c, np.broadcast_arrays(np.asarray(radius, dtype=float), c)[0])
    if profile.kind != "flat_punch":
        return c, c, mu
    stuck = (c == a) & (ux0 > 0) & (mu > 0)
    return c, np.where(stuck, 0.0, c), np.where(stuck, 2.0 * (1.0 - nu) / (2.0 - nu) * ux0, mu)


class Monotonic:
    """Cattaneo–Mindlin loading to the tangential displacement ``ux0`` = u_x0/delta: one term of
    weight 1, for every point at once.  ``radius``: the stick radius where the load is given as a
    force (``profiles.stick_radius_of_force``: exact as fx -> 1, where c from ux0 loses digits)."""

    #: the loads of ``loads`` (no x, y)
    LOADS = ("stick_radius",)

    def __init__(self, profile: Profile, ux0, radius=None):
        self.profile = profile
        self.arrays = {"ux0": np.asarray(ux0, dtype=float)}
        if radius is not None:
            self.arrays["radius"] = np.asarray(radius, dtype=float)

    def groups(self, P: dict) -> list[Group]:
        """One group: every point of the flat arrays ``P`` (a, nu, mu and ``arrays``)."""
        a, nu, mu, ux0 = P["a"], P["nu"], P["mu"], P["ux0"]
        c, c_kernel, mu_kernel = stick(a, nu, mu, ux0, self.profile, P.get("radius"))
        # a - c from the slip ratio: the tangential part keeps its relative accuracy as fx -> 0 (A109)
        width = annulus_width(self.profile, a, c_kernel, ux0, nu, mu_kernel)
        return [Group(np.arange(a.size), ((ux0, 1.0),), [c_kernel], mu_kernel, width, c, (mu == 0) | (ux0 == 0))]

    def loads(self, names, group: Group, P: dict) -> dict[str, np.ndarray]:
        return {"stick_radius": group.stick} if "stick_radius" in names else {}


class History:
    """The tangential displacement history u_x0/delta = ``amplitude`` * ``history`` at constant
    normal load (docs/theory/axisymmetric.md (A65)-(A77)), at the steps ``step`` (integer indices
    into it): per step its memory terms, lambda_k times the amplitude."""

    #: the loads of ``loads`` (no x, y): stick radius, F_x / (mu F_N), energies / (mu F_N delta)
    LOADS = ("stick_radius", "tangential_force", "dissipated_energy", "cycle_energy")

    def __init__(self, profile: Profile, amplitude, history, step):
        self.profile = profile
        self.history = tuple(float(v) for v in np.asarray(history, dtype=float).ravel())
        self.arrays = {"amplitude": np.asarray(amplitude, dtype=float), "step": np.asarray(step, dtype=np.int64)}

    def groups(self, P: dict) -> list[Group]:
        """One group per step of the flat arrays ``P`` (a, nu, mu and ``arrays``)."""
        out = []
        sts = _memory(self.history)
        for s in np.unique(P["step"]):
            idx = np.flatnonzero(P["step"] == s)
            A, NU, MU, AMP = (P[k][idx] for k in ("a", "nu", "mu", "amplitude"))
            # no displacement at all is the unloaded state (no terms)
            terms = tuple((lam * AMP, w) for lam, w in sts[int(s)].terms()) if np.any(AMP > 0) else ()
            radii = hist.stick_radii(terms, A, NU, MU, self.profile)
            now = hist.current_stick_radius(terms, A, NU, MU, self.profile)
            free = (MU == 0) | (AMP == 0) | (not terms)
            out.append(Group(idx, terms, radii, MU, None, now, free, int(s)))
        return out

    def loads(self, names, group: Group, P: dict) -> dict[str, np.ndarray]:
        """Stick radius, F_x / (mu F_N) and the energies / (mu F_N delta) of the group's step, the
        energies once per distinct (a, nu, mu, amplitude)."""
        a, nu, mu, amplitude = (P[k][group.index] for k in ("a", "nu", "mu", "amplitude"))
        terms = group.terms
        out = {}
        if "stick_radius" in names:
            out["stick_radius"] = group.stick
        if "tangential_force" in names:
            out["tangential_force"] = hist.tangential_force(terms, a, nu, mu, self.profile)
        want = [n for n in ("dissipated_energy", "cycle_energy") if n in names]
        if want:
            combos = np.stack([a, nu, mu, amplitude], axis=-1)
            uniq, inverse = np.unique(combos, axis=0, return_inverse=True)
            found = {n: np.zeros(len(uniq)) for n in want}
            for i, (ai, nui, mui, ampi) in enumerate(uniq):
                args = (self.history, float(ai), float(nui), float(mui), self.profile, float(ampi))
                for n in want:
                    found[n][i] = _ENERGY[n](*args)[group.step]
            out.update((n, found[n][inverse.ravel()]) for n in want)
        return out


@functools.lru_cache(maxsize=32)
def _memory(history: tuple) -> list:
    """Spring memory of every step of a history (``history.states``)."""
    return hist.states(history)


@functools.lru_cache(maxsize=256)
def _energy(history: tuple, a: float, nu: float, mu: float, profile: Profile, amplitude: float) -> np.ndarray:
    return hist.dissipated_energy(history, a, nu, mu, profile, scale=amplitude)


@functools.lru_cache(maxsize=256)
def _cycle(history: tuple, a: float, nu: float, mu: float, profile: Profile, amplitude: float) -> np.ndarray:
    return hist.cycle_energy(history, a, nu, mu, profile, scale=amplitude)


_ENERGY = {"dissipated_energy": _energy, "cycle_energy": _cycle}
