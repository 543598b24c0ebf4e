"""Axisymmetric rigid indenters on an elastic half-space: surface (z = 0) stress tensor and
normal gradient of the hydrostatic pressure under normal and Cattaneo–Mindlin tangential load, and
both below the surface (z > 0).

E. Willert, F. Forsbach, V. L. Popov, "Stress tensor and gradient of hydrostatic pressure in the
contact plane of axisymmetric bodies under normal and tangential loading", Forschung im
Ingenieurwesen (2020); the equations as implemented, with conventions, stable forms and errata, are
in docs/theory/axisymmetric.md (A1)-(A98), below the surface in docs/theory/interior.md.  Pure
NumPy/SciPy; results divided by E*.

``fields`` (and ``history_fields`` for tangential loading histories) computes every field of a
scenario in one call (``stress_invariants`` forms the stress invariants, from a tensor in any
unit); ``routes`` is the one table of which profiles have closed forms and
what the methods (``auto``, ``closed``, ``quadrature``) mean.
"""
from .fields import (FIELDS, HISTORY_FIELDS, HISTORY_LOADS, INVARIANTS, PRINCIPAL, STRESS, Singular,
                     contact_radius, fields, history_fields, stress_invariants, validity_flag)
from .interior import interior_dpdz, interior_stress
from .interior_tangential import interior_dpdz_tangential, interior_stress_tangential
from .peaks import PEAKS, peaks
from .profiles import (FlatPunch, Cone, Paraboloid, PowerLaw, Profile, Tabulated, cone, flat_punch,
                       paraboloid, power_law, tabulated)
from .routes import (INTERIOR_RTOL, METHODS, TANGENTIAL_TIP_RTOL, Route, has_closed_form,
                     has_interior_closed_form, resolve, resolve_depth, resolve_interior, tangential_floor)
from .surface import COMPONENTS, mean_pressure, min_pressure, stick_radius, surface_dpdz, surface_stress

__all__ = [
    "Profile", "Cone", "Paraboloid", "PowerLaw", "FlatPunch", "Tabulated",
    "cone", "paraboloid", "power_law", "flat_punch", "tabulated",
    "COMPONENTS", "surface_stress", "surface_dpdz", "stick_radius", "mean_pressure", "min_pressure",
    "interior_stress", "interior_dpdz", "interior_stress_tangential", "interior_dpdz_tangential",
    "STRESS", "PRINCIPAL", "INVARIANTS", "FIELDS", "HISTORY_LOADS", "HISTORY_FIELDS",
    "fields", "history_fields", "stress_invariants", "Singular",
    "contact_radius", "validity_flag",
    "METHODS", "INTERIOR_RTOL", "TANGENTIAL_TIP_RTOL", "tangential_floor",
    "Route", "has_closed_form", "has_interior_closed_form", "resolve",
    "resolve_interior", "resolve_depth",
    "PEAKS", "peaks",
]
