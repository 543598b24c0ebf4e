"""Optional cross-check below the surface against ContactMechanics' Hertz reference solutions
(Hamilton 1983's Cartesian forms, normal and sliding): an implementation written independently of
ours.  Skipped unless the `bench` extra is installed (pip install 'stressfields[bench]').

Off the axis only: the peer's Cartesian forms cancel as r -> 0 (measured: sigma_xx ~ 1e15 p0 at
r = 1e-16 a; a few per cent at r = 1e-5 a under tangential load), which our axial expansions avoid
(tests/physics/test_interior*.py check the axis against Johnson's formulas instead).
"""
import numpy as np
import pytest

hertz = pytest.importorskip("ContactMechanics.ReferenceSolutions.Hertz")

from stressfields.physics import axisymmetric as ax  # noqa: E402

#: the peer's order of components
PEER_ORDER = ("xx", "yy", "zz", "yz", "xz", "xy")
#: |ours - peer| / p0 off the axis: measured 1.0e-13 (normal) and 1.9e-12 (sliding, where the
#: peer's forms lose a few digits to cancellation at r ~ 0.1 a); 1e-11 leaves room for neither
#: a wrong term (an O(1) difference) nor a wrong sign
TOLERANCE = 1e-11


@pytest.fixture(scope="module")
def points():
    rng = np.random.default_rng(11)
    n = 3000
    r, phi, z = rng.uniform(0.1, 3.0, n), rng.uniform(0.0, 2 * np.pi, n), rng.uniform(0.02, 3.0, n)
    return r * np.cos(phi), r * np.sin(phi), z


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.5])
def test_hertz_normal_below_the_surface_matches_hamilton(points, nu):
    x, y, z = points
    p0 = 2.0 / np.pi            # a = R = E* = 1
    ours = ax.interior_stress(x, y, z, 1.0, nu, ax.paraboloid(1.0))
    for k, theirs in zip(PEER_ORDER, hertz.stress_Cartesian(x, y, z, poisson=nu)):
        assert np.max(np.abs(ours[k] / p0 - theirs)) < TOLERANCE, k


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.5])
def test_hertz_sliding_below_the_surface_matches_hamilton(points, nu):
    """Full sliding (c = 0) with mu = 1: the traction mu p along +x."""
    x, y, z = points
    p0 = 2.0 / np.pi
    ours = ax.interior_stress_tangential(x, y, z, 1.0, 0.0, nu, 1.0, ax.paraboloid(1.0))
    for k, theirs in zip(PEER_ORDER, hertz.stress_for_tangential_loading(x, y, z, poisson=nu)):
        assert np.max(np.abs(ours[k] / p0 - theirs)) < TOLERANCE, k
