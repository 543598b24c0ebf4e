"""The wavy validity codes forced one by one, each against an independent statement of its cause, and
the values at a flagged point: NaN, or within the accuracy the cause states, never a finite wrong value
flagged 0 (docs/theory/wavy.md (W25), (W42), (W43); the codes of physics/flags.py).

Codes forced elsewhere: series_not_converged (test_scenario_wavy.py, rtol below rounding),
undefined_direction_dependent_limit (test_scenario_wavy_depth.py, dpdz on a contact edge)."""
from __future__ import annotations

import numpy as np
import pytest

import stressfields as sf
from stressfields.physics.flags import Validity
from stressfields.physics.wavy import contact

#: a single indenter whose load P(c) = lambda_1 p_inf(c) falls and rises again with the contact width
#: (a strong third harmonic): at 2a/lambda_1 = 0.5 the stick zone of fx = 0.7 is not admissible, at 0.1
#: it is (P rises monotonically over [c, a] there)
PROFILE = {"domain": "nonperiodic", "amplitudes": [1.0, 0.2], "wavenumbers": [1, 3]}
LOAD = {"mu": 0.5, "fx": 0.7}
FIELDS = ["pressure", "uz", "sigma_xx", "sigma_xz", "tau_max", "dpdz", "shear_traction", "u_x", "u_z",
          "stick_half_width"]


def _run(parameters, variables, method=None):
    recipe = {"scenario": "wavy", "parameters": parameters, "output": {"variables": variables}}
    if method:
        recipe["method"] = method
    return sf.generate(recipe).compute()


def _load(widths):
    """P/(lambda_1 p*) at the contact widths 2a/lambda_1 = ``widths``: the scenario's mean pressure,
    the closed form (W12), evaluated on its own (not through the stick-width search)."""
    return _run({**PROFILE, "a": list(map(float, widths))}, ["mean_pressure"]).mean_pressure.values


def test_stick_zone_not_admissible_is_flagged_and_its_values_are_nan():
    params = {**PROFILE, **LOAD, "a": [0.1, 0.5], "z": [0.0, 0.5], "x": [-0.5, 0.0, 0.5]}
    ds = _run(params, FIELDS)
    c_over_a = ds.stick_half_width.values
    for w, ratio, admissible in zip((0.1, 0.5), c_over_a, (True, False)):
        # the cause, independently: P over [c, a] (a grid 4x finer than the search's)
        P = _load(w * np.linspace(ratio, 1.0, 65))
        assert bool(np.all(np.diff(P) > 0.0)) is admissible
        # and the stick width is the root of P(c) = (1 - fx) P(a) (W43)
        Pc, Pa = _load([w * ratio, w])
        assert Pc == pytest.approx((1.0 - LOAD["fx"]) * Pa, rel=1e-9)
    good, bad = ds.sel(a=0.1), ds.sel(a=0.5)
    assert (good.validity == Validity.within_stated_accuracy).all()
    assert (bad.validity == Validity.stick_zone_not_admissible).all()
    for name in ("sigma_xx", "sigma_xz", "tau_max", "dpdz", "shear_traction", "u_x", "u_z"):
        assert np.isfinite(good[name]).all(), name
        assert np.isnan(bad[name]).all(), name          # no value of this loading is known there
    # pressure and uz do not depend on the tangential load (uncoupled): those of the normal load alone,
    # which is within its stated accuracy (validity 0 without the load)
    normal = _run({**params, "mu": 0.0, "fx": 0.0}, ["pressure", "uz"])
    assert (normal.validity == Validity.within_stated_accuracy).all()
    for name in ("pressure", "uz"):
        np.testing.assert_array_equal(bad[name], normal[name].sel(a=0.5))
        assert np.isfinite(bad[name]).all()


def test_stick_zone_not_admissible_in_the_peaks_and_beside_the_stick_width_alone():
    params = {**PROFILE, **LOAD, "a": 0.5, "x": [0.0]}
    peaks = _run({**params, "a": [0.1, 0.5]}, ["tau_max_peak", "tau_max_peak_x", "von_mises_peak_depth"])
    assert peaks.peak_validity.values.tolist() == [Validity.within_stated_accuracy, Validity.stick_zone_not_admissible]
    for name in ("tau_max_peak", "tau_max_peak_x", "von_mises_peak_depth"):
        assert np.isfinite(float(peaks[name].sel(a=0.1))), name     # searched beside the case that is not
        assert np.isnan(float(peaks[name].sel(a=0.5))), name
    # the peak under partial slip: at least the surface's tau_max at the centre, which the search visits
    centre = _run({**params, "a": 0.1, "z": 0.0}, ["tau_max"])
    assert float(peaks.tau_max_peak.sel(a=0.1)) >= float(centre.tau_max.max())
    # the stick width requested without any field below the surface still flags the case
    alone = _run(params, ["pressure", "stick_half_width"])
    assert np.isfinite(float(alone.stick_half_width))
    assert (alone.validity == Validity.stick_zone_not_admissible).all()
    assert (_run({**params, "a": 0.1}, ["pressure", "stick_half_width"]).validity == 0).all()


def test_nonperiodic_series_within_rtol_is_the_periodic_pressure_to_rtol(monkeypatch):
    """Where auto takes a narrow periodic contact's pressure from the single-indenter series, the value is
    within rtol p* of the periodic series' own (normalised: p* = 1)."""
    monkeypatch.setattr(contact, "SUBSTITUTE_MIN_POINTS", 0)       # stand in however few the points
    rtol = 1e-10
    params = {"domain": "periodic", "amplitudes": [1.0, 0.1], "wavenumbers": [1, 3], "a": [1e-6, 0.3],
              "x": list(np.linspace(-1.0, 1.0, 9))}
    auto = _run(params, ["pressure"], {"method": "auto", "rtol": rtol})
    exact = _run(params, ["pressure"], {"method": "series", "rtol": rtol})
    assert (auto.validity.sel(a=1e-6) == Validity.nonperiodic_series_within_rtol).all()
    assert (auto.validity.sel(a=0.3) == Validity.within_stated_accuracy).all()      # too wide to stand in
    assert (exact.validity == Validity.within_stated_accuracy).all()
    assert float(np.max(np.abs(auto.pressure - exact.pressure))) <= rtol
    np.testing.assert_array_equal(auto.pressure.sel(a=0.3), exact.pressure.sel(a=0.3))


def test_approximate_formula_is_flagged_where_it_misses_the_stated_accuracy():
    """The paper's eq. (20) is flagged at every point, and it is flagged for a reason: it misses the
    exact series by far more than rtol."""
    params = {"domain": "nonperiodic", "amplitudes": [1.0, 0.1], "wavenumbers": [1, 3], "a": 0.4,
              "x": list(np.linspace(-0.9, 0.9, 7))}
    approx = _run(params, ["pressure"], {"method": "approximate_eq20"})
    exact = _run(params, ["pressure"], {"method": "series"})
    assert (approx.validity == Validity.approximate_formula).all()
    assert (exact.validity == Validity.within_stated_accuracy).all()
    assert float(np.max(np.abs(approx.pressure - exact.pressure))) > 1e3 * 1e-10
