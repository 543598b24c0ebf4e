"""Axisymmetric rigid indenters on an elastic half-space: surface (z = 0) stress tensor and
normal gradient of the hydrostatic pressure under normal and Cattaneo–Mindlin tangential load.

E. Willert, F. Forsbach, V. L. Popov, "Stress tensor and gradient of hydrostatic pressure in the
contact plane of axisymmetric bodies under normal and tangential loading", Forschung im
Ingenieurwesen (2020); the equations as implemented, with conventions, stable forms and errata, are
in docs/theory/axisymmetric.md (A1)-(A94).  Pure NumPy/SciPy; results divided by E*.
"""
from .profiles import (FlatPunch, Cone, Paraboloid, PowerLaw, Profile, Tabulated, cone, flat_punch,
                       paraboloid, power_law, tabulated)
from .surface import COMPONENTS, mean_pressure, stick_radius, surface_dpdz, surface_stress

__all__ = [
    "Profile", "Cone", "Paraboloid", "PowerLaw", "FlatPunch", "Tabulated",
    "cone", "paraboloid", "power_law", "flat_punch", "tabulated",
    "COMPONENTS", "surface_stress", "surface_dpdz", "stick_radius", "mean_pressure",
]
