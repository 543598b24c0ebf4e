"""Power-law graded elastic half-space, E(z) = E0 (z/c0)^k: MDR kernels.

M. Hess, V. L. Popov, "Method of dimensionality reduction in contact mechanics and friction:
a user's handbook. II. Power-law graded materials", Facta Universitatis Mech. Eng. 14(3), 2016,
251-268, doi:10.22190/FUME1603251H.  The equations, their stable forms and the departures from
the printed paper are given in docs/theory/graded.md (G1) onwards.

Modules: ``material`` (paper eqs. 1-4, 14, 53-56; docs/theory/graded.md (G1)-(G10)), ``profiles``
(eqs. 5-9; (G11)-(G14)), ``normal`` (eqs. 10-26, Table 2; (G15)-(G21)), ``adhesive`` (eqs. 27-38,
Table 3; (G22)-(G29)), ``tangential`` (eqs. 39-52; (G30)-(G37)).  Pure NumPy/SciPy:
arrays in, arrays out with broadcasting over every argument; errors for inputs outside the
model's domain (``ValueError`` naming parameter, value and allowed range).  Closed forms have a
``*_quad`` twin (quadrature of the MDR rules, any profile object, docs/theory/graded.md (G42))
used as an independent check and for tabulated profiles.

Entry points (one per scenario kind): ``normal_fields``, ``adhesive_fields``, ``tangential_fields``
(module ``fields``), which take an ``Indenter`` (kind + geometry arrays, module ``indenter``) and
pick the route with ``resolve`` (module ``routes``, the family's one route table).
"""
from ..quadrature import QuadratureError
from . import adhesive, fields, indenter, material, normal, profiles, routes, tangential
from .fields import adhesive_fields, normal_fields, tangential_fields
from .indenter import Indenter
from .material import C_gs, beta, c_N_star, c_T_star, h_N, h_T, holl_ratio, tangential_decoupled
from .profiles import PowerLaw, Tabulated, conical, kappa, parabolic
from .routes import resolve

__all__ = ["adhesive", "fields", "indenter", "material", "normal", "profiles", "routes", "tangential",
           "QuadratureError", "normal_fields", "adhesive_fields", "tangential_fields", "Indenter", "resolve",
           "C_gs", "beta", "c_N_star", "c_T_star", "h_N", "h_T", "holl_ratio",
           "tangential_decoupled", "PowerLaw", "Tabulated", "conical", "kappa", "parabolic"]
