"""The non-periodic series in place of the periodic one for narrow contacts (method auto).

Independent route: Westergaard's closed form for one harmonic on a periodic surface,
p/p* = 2 cos(h s) sqrt(sin^2 h - sin^2(h s)), h = pi a/lambda_1, s = x/a. The non-periodic
series stands in only where the periodic correction plus its own error is below the tolerance.
"""
import numpy as np
import pytest

from stressfields.physics import wavy
from stressfields.physics.wavy import contact

F1 = {"amplitudes": [1.0], "wavenumbers": [1]}
F3 = {"amplitudes": [0.5, 0.01, 0.00075], "wavenumbers": [1, 11, 40]}
X = np.linspace(-1.0, 1.0, 4001)
WIDTHS = np.array([1e-5, 1e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3])


def westergaard(x, w):
    h = 0.5 * np.pi * w
    return 2.0 * np.cos(h * x) * np.sqrt(np.clip(np.sin(h) ** 2 - np.sin(h * x) ** 2, 0.0, None))


def single_indenter(x, w, table):
    return wavy.pressure(x, w, **table, periodic=False, rtol=1e-14)[0]


@pytest.mark.parametrize("w", WIDTHS)
def test_correction_bounds_the_difference_from_westergaard(w):
    bound, _ = wavy.periodic_correction(w, **F1, rtol=1e-12)
    true = np.max(np.abs(westergaard(X, w) - single_indenter(X, w, F1)))
    assert true <= bound <= 1.1 * true + 1e-14     # a bound, and a tight one


def test_correction_bounds_the_difference_for_three_harmonics():
    bound, _ = wavy.periodic_correction(WIDTHS, **F3, rtol=1e-12)
    for w, b in zip(WIDTHS, bound):
        periodic = wavy.pressure(X, w, **F3, periodic=True, rtol=1e-14)[0]
        true = np.max(np.abs(periodic - single_indenter(X, w, F3)))
        assert true <= b and (b <= 1.1 * true + 1e-14 or b == np.inf)
    assert np.all(np.isfinite(bound[WIDTHS <= 0.03]))


def test_correction_grows_as_the_square_of_the_contact_width():
    bound, info = wavy.periodic_correction(WIDTHS[:5], **F1, rtol=1e-12)
    # 0.41 (2a/lambda_1)^2 of the series scale, measured over five decades
    np.testing.assert_allclose(bound / (WIDTHS[:5] ** 2 * info["scale"]), 0.411, rtol=0.01)


@pytest.fixture
def any_size(monkeypatch):
    """Substitute on every contact, however few points (the default needs 1e5 to pay off)."""
    monkeypatch.setattr(contact, "SUBSTITUTE_MIN_POINTS", 0)


@pytest.mark.parametrize("rtol", [1e-4, 1e-6, 1e-8, 1e-12])
def test_substituted_pressure_meets_the_periodic_tolerance(rtol, any_size):
    p, info = wavy.pressure(X[:, None], WIDTHS[None, :], **F1, periodic=True, rtol=rtol, substitute=True)
    _, exact_info = wavy.pressure(0.0, WIDTHS, **F1, periodic=True, rtol=rtol)
    scale = wavy.periodic_correction(WIDTHS, **F1, rtol=rtol)[1]["scale"]
    err = np.max(np.abs(p - westergaard(X[:, None], WIDTHS[None, :])), axis=0)
    sub = info["substituted"][0]
    assert np.all(err <= info["error_estimate"][0] + 1e-15)
    assert np.all(info["error_estimate"][0] <= rtol * scale)
    # it stands in exactly where the correction allows: narrow contacts, fewer as rtol tightens
    expected = 0.411 * WIDTHS ** 2 < 0.5 * rtol
    assert np.all(sub[expected]) and not np.any(sub[0.411 * WIDTHS ** 2 > rtol])
    # where it does not stand in, the values are the periodic series' own
    np.testing.assert_array_equal(p[:, ~sub], wavy.pressure(X[:, None], WIDTHS[None, ~sub], **F1, periodic=True,
                                                             rtol=rtol)[0])
    assert np.all(exact_info["converged"])


def test_substituted_pressure_is_the_single_indenters(any_size):
    p, info = wavy.pressure(X, 1e-3, **F3, periodic=True, rtol=1e-6, substitute=True)
    assert info["substituted"].all()
    np.testing.assert_array_equal(p, wavy.pressure(X, 1e-3, **F3, periodic=False, rtol=1e-6)[0])


def test_no_substitution_unless_asked_or_for_a_single_indenter():
    _, info = wavy.pressure(X, 1e-4, **F1, periodic=True, rtol=1e-4)
    assert "substituted" not in info
    p, info = wavy.pressure(X, 1e-4, **F1, periodic=False, rtol=1e-4, substitute=True)
    assert "substituted" not in info


def test_substitution_only_where_it_pays():
    """The test costs ~2 ms per contact: fewer points than SUBSTITUTE_MIN_POINTS keep the periodic series."""
    few = np.linspace(-1.0, 1.0, contact.SUBSTITUTE_MIN_POINTS - 1)
    many = np.linspace(-1.0, 1.0, contact.SUBSTITUTE_MIN_POINTS)
    assert not wavy.pressure(few, 1e-4, **F1, periodic=True, rtol=1e-6, substitute=True)[1]["substituted"].any()
    p, info = wavy.pressure(many, 1e-4, **F1, periodic=True, rtol=1e-6, substitute=True)
    assert info["substituted"].all()
    assert np.max(np.abs(p - westergaard(many, 1e-4))) <= info["error_estimate"][0]
    # counted per contact: outside points do not count
    wide = np.concatenate([few, np.linspace(1.5, 2.0, contact.SUBSTITUTE_MIN_POINTS)])
    assert not wavy.pressure(wide, 1e-4, **F1, periodic=True, rtol=1e-6, substitute=True)[1]["substituted"].any()
