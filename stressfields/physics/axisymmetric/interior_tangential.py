"""The tangential (Cattaneo–Mindlin) part of the stress tensor below the surface (z >= 0) of a
half-space indented by a rigid axisymmetric profile: the entry point ``interior_stress_tangential``.

The surface traction is the one of the surface kernels (docs/theory/axisymmetric.md (A34)):
along +x on the half-space, sigma_xz(z = 0) = -q with q = mu [p(r; a) - p(r; c)], c the stick
radius (c = 0 gross slip, c = a no tangential load).  The full field is the normal part
(``interior.interior_stress``) plus the part returned here.

Route (docs/theory/interior.md (I18)-(I23)):

* ``closed``: the paraboloid, mu p0 [T(x/a) - (c/a) T(x/c)] with T the Hertz sliding field per q0
  (Hamilton & Goodman 1966; Hamilton 1983; Cattaneo 1938; Mindlin 1949), ``sliding_unit``.
  Accuracy: closed form, relative error at most 1e-12 of |value| everywhere the value is finite,
  far field and next to edges included.

Other profiles (cone, power law n != 2, tabulated, flat punch) need the sliding-punch kernel
superposed as in (I15); it is not available yet and those profiles are refused.

Units as ``interior_stress``: lengths in the profile's unit, stresses divided by E*.  Components
"xx", "yy", "zz", "xy", "xz", "yz"; tension positive, z into the body.  Pure NumPy.
"""
from __future__ import annotations

import math

import numpy as np

from .interior_hertz import COMPONENTS, sliding_unit
from .profiles import Profile

__all__ = ["COMPONENTS", "interior_stress_tangential"]

METHODS = ("auto", "closed")


def interior_stress_tangential(x, y, z, a, c, nu, mu, profile: Profile, *, method: str = "auto",
                               rtol: float = 1e-10) -> dict[str, np.ndarray]:
    """Tangential part of the stress tensor / E* at (x, y, z), z >= 0 the depth, for the contact
    radius ``a``, stick radius ``c`` (0 <= c <= a; c = 0 gross slip) and coefficient of friction
    ``mu`` >= 0 (Cattaneo–Mindlin, traction along +x on the half-space); docs/theory/interior.md
    (I23).  x, y, z, a, c, nu, mu broadcast; returns {"xx", "yy", "zz", "xy", "xz", "yz": ndarray}.

    ``method``: "auto" or "closed" (paraboloid and power law n = 2: the closed form (I23),
    relative error at most 1e-12 of |value| everywhere the value is finite).  Every other profile
    raises ValueError (its route, the superposition of sliding punches, is not available).
    ``rtol`` is accepted for the signature shared with ``interior_stress`` and checked; the closed
    form does not use it.  The field is finite and continuous everywhere in z >= 0, the edge
    rings r = a and r = c at z = 0 included."""
    if method not in METHODS:
        raise ValueError(f"unknown tangential interior method {method!r}; allowed: {', '.join(METHODS)}")
    if not (math.isfinite(float(rtol)) and float(rtol) > 0.0):
        raise ValueError(f"rtol must be a positive finite number, got {rtol!r}")
    R = _paraboloid_radius(profile)
    arrays = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (x, y, z, a, c, nu, mu)))
    shape = arrays[0].shape
    x, y, z, a, c, nu, mu = (np.ascontiguousarray(v).ravel() for v in arrays)
    _validate(z, a, c, nu, mu)
    k = mu * 2.0 * a / (math.pi * R)                     # mu p0 per E*, (I1)
    slide = sliding_unit(x / a, y / a, z / a, nu)
    out = {key: k * v for key, v in slide.items()}
    part = np.flatnonzero(c > 0.0)
    if part.size:
        cp = c[part]
        stick = sliding_unit(x[part] / cp, y[part] / cp, z[part] / cp, nu[part])
        for key in COMPONENTS:
            out[key][part] -= k[part] * (cp / a[part]) * stick[key]
    return {key: out[key].reshape(shape) for key in COMPONENTS}


def _paraboloid_radius(profile):
    closed = profile.closed
    if closed is None or closed[0] != "paraboloid":
        raise ValueError(f"the tangential interior field is available for the paraboloid only; "
                         f"no route for the {profile.kind} profile {profile!r}")
    return float(closed[1])


def _validate(z, a, c, nu, mu):
    if np.any(~(z >= 0.0)):
        raise ValueError("z (depth below the surface) must be >= 0 and not NaN")
    if np.any(~(a > 0.0)) or not np.all(np.isfinite(a)):
        raise ValueError("a (contact radius) must be positive and finite (a > 0)")
    if np.any(~((c >= 0.0) & (c <= a))):
        raise ValueError("c (stick radius) must be in [0, a]")
    if np.any(~((nu >= 0.0) & (nu <= 0.5))):
        raise ValueError("nu (Poisson's ratio) must be in [0, 0.5]")
    if np.any(~(mu >= 0.0)) or not np.all(np.isfinite(mu)):
        raise ValueError("mu (coefficient of friction) must be finite and >= 0")
