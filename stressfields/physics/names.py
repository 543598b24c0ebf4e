"""The names the scenario declarations share with the kernels: method lists and field names.

One definition each: the route tables (``<family>/routes.py``) and entry points (``<family>/fields.py``)
take them from here, and so do the declarations in ``stressfields.scenarios``.  This module imports
nothing, so that declaring the scenarios (`stressfields list`, `describe`, `schema`, `validate`)
loads no kernel and no SciPy: importing a family package loads all of its kernels, and SciPy with them
(0.35 s of the 0.6 s `stressfields describe conical` took, measured with ``python -X importtime``).
"""
from __future__ import annotations

#: axisymmetric: every method of the family, the default first (``axisymmetric.routes.METHODS``)
AXISYMMETRIC_METHODS: tuple[str, ...] = ("auto", "closed", "quadrature")
#: axisymmetric: the stress tensor components, in the order of the files (``axisymmetric.fields.STRESS``)
STRESS: tuple[str, ...] = ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "sigma_yz")
#: axisymmetric: the principal stresses, largest first (``axisymmetric.fields.PRINCIPAL``)
PRINCIPAL: tuple[str, ...] = ("sigma_1", "sigma_2", "sigma_3")

#: graded: every method of the family, the default first (``graded.routes.METHODS``)
GRADED_METHODS: tuple[str, ...] = ("auto", "closed", "quadrature")

#: wavy: the exact methods, the default first (``wavy.routes.SERIES_METHODS``)
WAVY_SERIES_METHODS: tuple[str, ...] = ("auto", "series")
#: wavy: the paper's approximate pressures, in the order of ``wavy.routes.APPROXIMATE``
WAVY_APPROXIMATE_METHODS: tuple[str, ...] = ("approximate_eq18", "approximate_eq20")
#: wavy: every method, in the order a recipe lists them (``wavy.routes.METHODS``)
WAVY_METHODS: tuple[str, ...] = WAVY_SERIES_METHODS + WAVY_APPROXIMATE_METHODS
