"""Power-law graded elastic half-space, E(z) = E0 (z/c0)^k: MDR kernels.

M. Hess, V. L. Popov, "Method of dimensionality reduction in contact mechanics and friction:
a user's handbook. II. Power-law graded materials", Facta Universitatis Mech. Eng. 14(3), 2016,
251-268, as corrected by the verified formula sheet shared/formulas/seed001/formulas.md.

Modules: ``material`` (eqs. 1-4, 14, 53-56), ``profiles`` (eqs. 5-9), ``normal`` (eqs. 10-26,
Table 2), ``adhesive`` (eqs. 27-38, Table 3), ``tangential`` (eqs. 39-52).  Pure NumPy/SciPy:
arrays in, arrays out with broadcasting over every argument; errors for inputs outside the
model's domain (``ValueError`` naming parameter, value and allowed range).  Closed forms have a
``*_quad`` twin (quadrature of the MDR rules, any profile object) used as an independent check
and for tabulated profiles.
"""
from . import adhesive, material, normal, profiles, tangential
from ._quad import QuadratureError
from .material import C_gs, beta, c_N_star, c_T_star, h_N, h_T, holl_ratio, tangential_decoupled
from .profiles import PowerLaw, Tabulated, conical, kappa, parabolic

__all__ = ["adhesive", "material", "normal", "profiles", "tangential", "QuadratureError",
           "C_gs", "beta", "c_N_star", "c_T_star", "h_N", "h_T", "holl_ratio",
           "tangential_decoupled", "PowerLaw", "Tabulated", "conical", "kappa", "parabolic"]
