"""An indenter described by its kind and geometry arrays, for the field entry points (:mod:`.fields`).

The closed forms take a power law as the two numbers (n, A_n), which broadcast like any other
argument; the quadrature kernels take one profile *object* (:class:`~.profiles.PowerLaw`,
:class:`~.profiles.Tabulated`).  :class:`Indenter` serves both: :meth:`Indenter.power` gives the
arrays, :meth:`Indenter.each` runs a quadrature kernel once per distinct geometry of a sweep.
Also here: where the pressure is unbounded at the centre (:func:`tip_singular`, :func:`at_centre`).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from .profiles import PowerLaw, Tabulated, conical, parabolic
from .routes import KINDS

__all__ = ["Indenter", "tip_singular", "at_centre"]


@dataclass(frozen=True, eq=False)
class Indenter:
    """Axisymmetric indenter profiles of one ``kind`` whose geometry may vary over the points.

    ``geometry`` holds the arrays of the kind, in the order of its constructor: parabolic (R,),
    conical (tan_theta,), power_law (A, n), tabulated () with the spline in ``table``.  Each array
    broadcasts against the field points (numpy rules, aligned from the right).
    """

    kind: str
    geometry: tuple[np.ndarray, ...] = ()
    table: Tabulated | None = None

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"profile kind {self.kind!r} is not allowed: use one of {', '.join(map(repr, KINDS))}")

    @classmethod
    def parabolic(cls, R) -> Indenter:
        """f = r^2/(2R), the power law (n, A_n) = (2, 1/(2R)) (docs/theory/graded.md (G15))."""
        return cls("parabolic", (np.asarray(R, dtype=float),))

    @classmethod
    def conical(cls, tan_theta) -> Indenter:
        """f = r tan(theta), the power law (n, A_n) = (1, tan(theta))."""
        return cls("conical", (np.asarray(tan_theta, dtype=float),))

    @classmethod
    def power_law(cls, A, n) -> Indenter:
        """f = A r^n (n > 0), docs/theory/graded.md (G13)."""
        return cls("power_law", (np.asarray(A, dtype=float), np.asarray(n, dtype=float)))

    @classmethod
    def tabulated(cls, r, f) -> Indenter:
        """Cubic spline through f(r_i), r_0 = 0 (docs/theory/graded.md (G14)); one profile, no sweep.
        Equal samples give the same profile object (the set-up cache, keyed by their bytes), so its
        set-up (block trees, panel values of g') serves every call and dask chunk."""
        from ..setup_cache import SETUP, content_key

        r, f = np.asarray(r, dtype=float), np.asarray(f, dtype=float)
        return cls("tabulated", (), SETUP.get(("graded tabulated",) + content_key(r, f), lambda: Tabulated(r, f)))

    def power(self) -> tuple[Any, Any]:
        """(n, A_n) of the closed forms f = A_n r^n (paper eqs. 7, 16, 25); arrays for a sweep."""
        if self.kind == "parabolic":
            return parabolic(self.geometry[0])
        if self.kind == "conical":
            return conical(self.geometry[0])
        if self.kind == "power_law":
            A, n = self.geometry
            return n, A
        raise ValueError("a tabulated profile has no closed form: (n, A_n) do not exist")

    def profile(self, *geometry: float) -> PowerLaw | Tabulated:
        """The profile object for one value of each geometry array."""
        if self.kind == "tabulated":
            return self.table
        if self.kind == "parabolic":
            return PowerLaw.parabolic(*geometry)
        if self.kind == "conical":
            return PowerLaw.conical(*geometry)
        A, n = geometry
        return PowerLaw(A=A, n=n)

    def each(self, fn: Callable[..., Any], **arrays) -> Any:
        """``fn(profile, **arrays)`` for each distinct profile of a swept geometry, assembled.

        The quadrature kernels take one profile object, so a swept geometry (R, n, ...) is looped
        over; each call sees the arrays sliced to its geometry value, so no point is computed twice.
        ``fn`` returns an array or a tuple of arrays (then so does ``each``).
        """
        geo = self.geometry
        if all(g.ndim == 0 for g in geo):
            return fn(self.profile(*map(float, geo)), **arrays)
        gshape = np.broadcast_shapes(*(g.shape for g in geo))
        geo = [np.broadcast_to(g, gshape) for g in geo]
        results = []
        for idx in np.ndindex(gshape):
            sl = tuple(slice(i, i + 1) if s > 1 else slice(None) for i, s in zip(idx, gshape))
            res = fn(self.profile(*(float(g[idx]) for g in geo)), **{k: _part(v, sl) for k, v in arrays.items()})
            many = isinstance(res, tuple)
            results.append((sl, tuple(map(np.asarray, res)) if many else (np.asarray(res),)))
        outs = []
        for j in range(len(results[0][1])):
            shape = np.broadcast_shapes(gshape, *(r[j].shape for _, r in results))
            out = np.empty(shape, dtype=np.result_type(*(r[j] for _, r in results)))
            for sl, res in results:
                out[(Ellipsis,) + sl] = res[j]
            outs.append(out)
        return tuple(outs) if many else outs[0]


def _part(v, sl):
    """``v`` sliced like the geometry: along the axes (aligned from the right) where both vary."""
    if not isinstance(v, np.ndarray) or v.ndim == 0:
        return v
    m = min(v.ndim, len(sl))
    keep = (slice(None),) * (v.ndim - m)
    return v[keep + tuple(s if size > 1 else slice(None) for s, size in zip(sl[len(sl) - m:], v.shape[v.ndim - m:]))]


def tip_singular(profile: PowerLaw | Tabulated, k):
    """Is the pressure unbounded at r = 0? For f = A r^n when n + k <= 1 (Phi(0) of
    docs/theory/graded.md (G18)); for a spline tip (finite slope f'(0)) when k = 0 and f'(0) != 0,
    as for the cone."""
    if isinstance(profile, PowerLaw):
        return profile.n + k <= 1.0
    # a spline through a smooth tip keeps a rounding-level slope at 0: that is no cone
    slope = abs(float(profile.df(0.0))) * profile.r_max / float(profile.f(profile.r_max))
    return (k == 0.0) & (slope > 1e-8)


def at_centre(r, a, profile: PowerLaw | Tabulated, k, compute: Callable[[Any], Any], fill):
    """compute(r) with the points r = 0 of an unbounded centre pressure set to ``fill``.

    The quadrature kernels do not converge there (the integral diverges); the closed forms return +inf.
    """
    sing = (r == 0.0) & tip_singular(profile, k)
    if not np.any(sing):
        return compute(r)
    return np.where(sing, fill, compute(np.where(sing, 0.5 * a, r)))
