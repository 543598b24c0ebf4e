"""The 2-D quadrature of the Holl point-load field (physics.graded.holl, docs/theory/graded.md (G62)-(G65))
against an independent mpmath double integral of the same kernel in the disc's own coordinates
(tests/data/graded_interior.json, written by tests/data/make_graded_interior.py; provenance in
tests/data/README.md)."""
from __future__ import annotations

import numpy as np
import pytest

from stressfields.physics.graded import holl

from conftest import load_reference


@pytest.mark.parametrize("rtol", [1e-6, 1e-10])
def test_against_the_mpmath_double_integral_of_the_point_load_kernel(rtol):
    """|error| <= rtol times the pressure amplitude (1 here) at every stored point and component."""
    ref = load_reference("graded_interior")["points"]
    assert len(ref) >= 200 and max(p["err"] for p in ref) < 1e-13     # (values: 12 significant digits)
    rho, z, k, e = (np.array([p[key] for p in ref]) for key in ("rho", "z", "k", "e"))
    got = holl.disc_stress(rho, z, k, e, rtol)
    for c in holl.COMPONENTS:
        want = np.array([p[f"sigma_{c}"] for p in ref])
        worst = np.max(np.abs(got[c] - want))
        assert worst < rtol, (c, worst)
