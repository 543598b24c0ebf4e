"""Multisinusoidal wavy surface pressed on an elastic half-plane (plane strain, frictionless).

Tsukanov, I. Yu. (2018) "Partial contact of a rigid multisinusoidal wavy surface with an elastic
half-plane", Advances in Tribology 2018, 8431467, doi:10.1155/2018/8431467; equations, stable
forms and errata in docs/theory/wavy.md (W1)-(W44).  Pure NumPy/SciPy: arrays in,
arrays out, no state.  See ``contact`` for the common arguments and normalisation
(p* = pi E* Delta_1/lambda_1, E* = E/(1 - nu^2); lengths in Delta_1; x in units of a).
``fields`` computes every quantity of the scenario in one call; ``routes`` is the one table of
what the methods (``auto``, ``series``, the paper's approximations) mean.
"""

from .contact import (
    DEFAULT_MAX_TERMS,
    DEFAULT_RTOL,
    approach,
    approximate_pressure_eq18,
    approximate_pressure_eq20,
    contact_validity,
    continuous_contact,
    displacement,
    initial_gap,
    johnson_parameter,
    max_pressure,
    mean_pressure,
    peak_pressure,
    periodic_correction,
    pressure,
    pressure_shape,
    separation,
)
from .fields import FIELDS, fields
from .routes import APPROXIMATE, METHODS, approximation, resolve, substitutes

__all__ = [
    "APPROXIMATE", "FIELDS", "METHODS", "approximation", "fields", "resolve", "substitutes",
    "DEFAULT_MAX_TERMS", "DEFAULT_RTOL", "approach", "approximate_pressure_eq18",
    "approximate_pressure_eq20", "contact_validity", "continuous_contact", "displacement",
    "initial_gap", "johnson_parameter", "max_pressure", "mean_pressure", "peak_pressure",
    "periodic_correction", "pressure", "pressure_shape", "separation",
]
