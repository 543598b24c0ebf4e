"""Von Mises (eq. 30, sqrt(3 J2)) and principal stresses: against the reference points, the
closed form at y = 0 (docs/theory/axisymmetric.md (A61)) and basic algebra."""
import math

import numpy as np
import pytest
from conftest import load_reference

from stressfields.physics import axisymmetric as ax
from stressfields.physics.invariants import principal_stresses, von_mises

KEYS = ("xx", "yy", "zz", "xy", "xz", "yz")


@pytest.fixture(scope="module")
def points():
    return load_reference("axisymmetric_surface")["points"]


def test_against_reference_points(points):
    """The invariants of the reference tensors equal the reference invariants (an independent
    3-D route computed both)."""
    sig = {k: np.array([p["sigma"][k] for p in points]) for k in KEYS}
    vm = von_mises(*(sig[k] for k in KEYS))
    s1, s2, s3 = principal_stresses(*(sig[k] for k in KEYS))
    ref_vm = np.array([p["von_mises"] for p in points])
    ref_pr = np.array([p["principal"] for p in points])
    scale = np.maximum(1.0, np.abs(ref_pr))
    np.testing.assert_array_less(np.abs(vm - ref_vm) / np.maximum(1, np.abs(ref_vm)), 1e-13)
    np.testing.assert_array_less(np.abs(np.stack([s1, s2, s3], axis=1) - ref_pr) / scale, 1e-13)


def test_closed_form_on_y0():
    """At y = 0 sigma_xy = sigma_yz = 0: sigma_yy is principal and the other two are
    (sxx+szz)/2 +- sqrt((sxx-szz)^2/4 + sxz^2) (docs/theory/axisymmetric.md (A61)).  Cone and
    paraboloid in partial slip."""
    x = np.linspace(-2.5, 2.5, 501)
    for prof in (ax.cone(0.7), ax.paraboloid(2.0)):
        s = ax.surface_stress(x, 0.0, 1.0, 0.45, 0.3, 0.4, prof)
        fin = x != 0.0          # the cone's tip r = 0 is singular (documented)
        assert np.all(s["xy"][fin] == 0.0) and np.all(s["yz"] == 0.0)
        with np.errstate(invalid="ignore"):   # -inf - -inf at the tip
            m = 0.5 * (s["xx"] + s["zz"])
            rad = np.sqrt(0.25 * (s["xx"] - s["zz"]) ** 2 + s["xz"] ** 2)
        expected = np.sort(np.stack([m + rad, m - rad, s["yy"]], axis=1), axis=1)[:, ::-1]
        got = np.stack(principal_stresses(*(s[k] for k in KEYS)), axis=1)
        scale = np.max(np.abs(expected), axis=1, keepdims=True)
        assert np.max(np.abs(got - expected)[fin] / scale[fin]) < 1e-14
        # von Mises from the principal values: sqrt(((s1-s2)^2 + (s2-s3)^2 + (s3-s1)^2)/2)
        e1, e2, e3 = expected.T
        vm_p = np.sqrt(0.5 * ((e1 - e2) ** 2 + (e2 - e3) ** 2 + (e3 - e1) ** 2))
        vm = von_mises(*(s[k] for k in KEYS))
        assert np.max(np.abs(vm - vm_p)[fin] / scale[fin, 0]) < 1e-14


def test_known_tensors_and_broadcasting():
    # uniaxial tension: vm = |s|; pure shear tau: vm = sqrt(3) tau, principal (tau, 0, -tau)
    assert von_mises(2.0, 0, 0, 0, 0, 0) == pytest.approx(2.0, rel=1e-15)
    assert von_mises(0, 0, 0, 0, 0, 1.5) == pytest.approx(math.sqrt(3) * 1.5, rel=1e-15)
    s1, s2, s3 = principal_stresses(0, 0, 0, 1.5, 0, 0)
    assert (float(s1), float(s2), float(s3)) == pytest.approx((1.5, 0.0, -1.5), abs=1e-15)
    # hydrostatic: vm = 0
    assert von_mises(-3.0, -3.0, -3.0, 0, 0, 0) == 0.0
    # broadcasting (2,1) against (3,) and a scalar
    sxx = np.array([[1.0], [2.0]])
    syy = np.array([0.0, 1.0, 2.0])
    out = principal_stresses(sxx, syy, 0.5, 0.1, 0.0, 0.0)
    assert all(o.shape == (2, 3) for o in out)
    assert von_mises(sxx, syy, 0.5, 0.1, 0.0, 0.0).shape == (2, 3)
    s1, s2, s3 = out
    assert np.all(s1 >= s2) and np.all(s2 >= s3)
    # trace is invariant
    np.testing.assert_allclose(s1 + s2 + s3, sxx + syy + 0.5, rtol=1e-14)


def test_nonfinite_inputs_give_nan_without_raising():
    sxx = np.array([np.nan, -np.inf, 1.0, 1.0])
    sxy = np.array([0.0, 0.0, np.inf, 0.2])
    vm = von_mises(sxx, 0.0, 0.0, sxy, 0.0, 0.0)
    s1, s2, s3 = principal_stresses(sxx, 0.0, 0.0, sxy, 0.0, 0.0)
    assert np.all(np.isnan(vm[:3])) and np.isfinite(vm[3])
    for s in (s1, s2, s3):
        assert np.all(np.isnan(s[:3])) and np.isfinite(s[3])
