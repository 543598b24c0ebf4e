"""The series length follows rtol, and every rtol keeps the contract.

Non-periodic (Bessel series, docs/theory/wavy.md (W22)-(W24)): at each rtol the pressure, the shape
p/sqrt(1 - (x/a)^2) and the displacement are within rtol * max(|value|, S) of the rtol = 1e-14
series and of the independent Nystroem reference points (tests/data/wavy_tsukanov.json, good to
4e-13), within the reported error_estimate, and the number of terms (counted, not timed) falls as
rtol loosens.  Periodic: the closed form (W30) has no truncation; its value does not depend on rtol
and converged says whether its rounding bound (W31) meets rtol.
"""
import numpy as np
import pytest
from conftest import load_reference

from stressfields.physics import wavy

F3 = {"amplitudes": [0.5, 0.01, 0.00075], "wavenumbers": [1, 11, 40]}
PROFILES = {"f1": ([0.5], [1]), "f2": ([0.5, 0.01], [1, 11]), "f3": ([0.5, 0.01, 0.00075], [1, 11, 40])}
WIDTHS = np.array([1e-4, 1e-2, 0.05, 0.2, 0.5, 0.8, 0.95])
X = np.concatenate([np.linspace(-1.0, 1.0, 401), 1.0 - np.geomspace(1e-12, 1e-2, 30)])
RTOLS = [1e-4, 1e-6, 1e-8, 1e-10, 1e-12]
REFERENCE_ERROR = 4e-13      # the reference data's own error bound (tests/data/README.md)


@pytest.fixture(scope="module")
def exact():
    return wavy.pressure(X[:, None], WIDTHS[None, :], **F3, periodic=False, rtol=1e-14)


@pytest.mark.parametrize("rtol", RTOLS)
def test_nonperiodic_pressure_meets_rtol_against_the_tightest_series(rtol, exact):
    p, info = wavy.pressure(X[:, None], WIDTHS[None, :], **F3, periodic=False, rtol=rtol)
    err = np.abs(p - exact[0])
    assert info["converged"].all()
    assert np.all(err <= rtol * np.maximum(np.abs(p), 1.0))                   # p* = 1
    assert np.all(err <= info["error_estimate"] + exact[1]["error_estimate"])
    assert np.all(info["error_estimate"] <= rtol)                            # converged <=> <= rtol p*


@pytest.mark.parametrize("rtol", RTOLS)
def test_nonperiodic_shape_and_displacement_meet_rtol(rtol):
    t = np.abs(X)
    phi, info = wavy.pressure_shape(t[:, None], WIDTHS[None, :], **F3, periodic=False, rtol=rtol)
    ref, ref_info = wavy.pressure_shape(t[:, None], WIDTHS[None, :], **F3, periodic=False, rtol=1e-14)
    assert np.all(np.abs(phi - ref) <= info["error_estimate"] + ref_info["error_estimate"])
    x_out = np.array([1.0, 1.5, 3.0, 10.0])
    uz, uinfo = wavy.displacement(x_out[:, None], WIDTHS[None, :], **F3, periodic=False, rtol=rtol)
    uref, _ = wavy.displacement(x_out[:, None], WIDTHS[None, :], **F3, periodic=False, rtol=1e-14)
    # u_z outside: the slope series' tail bound integrated over |x| - a, (W18); S = Delta_1 = 1
    assert np.all(np.abs(uz - uref) <= uinfo["error_estimate"] + 1e-13)


@pytest.mark.parametrize("rtol", RTOLS)
def test_nonperiodic_against_the_reference_points(rtol):
    for c in load_reference("wavy_tsukanov")["cases"]:
        if c["problem"] == "periodic":
            continue
        amp, wn = PROFILES[c["profile"]]
        p, info = wavy.pressure(c["x_over_a"], c["two_a_over_lambda1"], amplitudes=amp, wavenumbers=wn,
                                periodic=False, rtol=rtol)
        err = np.abs(p - np.asarray(c["p_over_pstar"]))
        assert np.all(err <= rtol * np.maximum(np.abs(p), 1.0) + REFERENCE_ERROR)
        assert np.all(err <= info["error_estimate"] + REFERENCE_ERROR)


def test_terms_fall_as_rtol_loosens():
    K = np.array([wavy.peak_pressure(WIDTHS, **F3, periodic=False, rtol=r)[1]["n_terms"] for r in RTOLS])
    assert np.all(np.diff(K, axis=0) >= 0)                  # never more terms for a looser rtol
    # narrow contacts: the tail decides, and the length follows ln(1/rtol) (W24)
    assert np.all(K[0, :3] < K[-1, :3])
    assert K[:, :3].sum(axis=1)[0] <= 0.6 * K[:, :3].sum(axis=1)[-1]


def test_periodic_closed_form_does_not_depend_on_rtol():
    values = [wavy.pressure(X[:, None], WIDTHS[None, :], **F3, periodic=True, rtol=r) for r in RTOLS]
    for p, info in values[1:]:
        np.testing.assert_array_equal(p, values[0][0])
        np.testing.assert_array_equal(info["n_terms"], values[0][1]["n_terms"])
    for r, (_, info) in zip(RTOLS, values):
        np.testing.assert_array_equal(info["converged"], info["error_estimate"] <= r)
