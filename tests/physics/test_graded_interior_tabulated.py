"""A tabulated profile below the graded surface at k = 0 (docs/theory/graded.md section 10): the graded spline is
the axisymmetric family's, so the interior is that family's 1-D superposition for the same samples.  Held against
the closed-form paraboloid of the graded family (a not-a-knot cubic spline reproduces a quadratic), against the
graded family's own surface pressure (G17) as z -> 0 for non-polynomial tables (another route: the MDR
quadrature of the spline, not the superposition of punches), and the refusals at k > 0 and for a clamped tip."""
from __future__ import annotations

import math

import numpy as np
import pytest

from stressfields.physics import axisymmetric as ax
from stressfields.physics import graded as gp
from stressfields.physics.graded.interior import interior_fields, tangential_interior_fields

R, A0, E0, C0, NU = 0.02, 1e-3, 2e9, 1e-2, 0.3
STRESS = ("sigma_rr", "sigma_tt", "sigma_zz", "sigma_rz")
R_TAB = np.linspace(0.0, 2e-3, 13)
#: non-polynomial tables: r^1.5 (a tip of infinite curvature) and a cone blunted by a hyperbola of radius 0.3 mm
TABLES = {"r^1.5": R * (R_TAB / R) ** 1.5, "blunted cone": 0.3 * (np.hypot(R_TAB, 3e-4) - 3e-4)}
# a dozen points, z from 1e-3 a to 3a, inside and outside the contact
RHO = np.array([0.0, 0.3, 0.7, 0.95, 1.05, 1.5, 2.0, 0.5, 0.2, 1.2, 0.9, 0.0])
Z = np.array([1e-3, 0.01, 0.1, 0.3, 0.5, 1.0, 3.0, 2.0, 0.05, 1e-3, 0.002, 3.0])


def _mean_pressure(profile, k=0.0):
    force = gp.normal_fields(["normal_force"], profile, a=A0, k=k, nu=NU, E0=E0, c0=C0)["normal_force"]
    return float(force) / (math.pi * A0 ** 2)


@pytest.mark.parametrize("name", sorted(TABLES))
def test_the_graded_spline_is_the_axisymmetric_one(name):
    """Same samples, same not-a-knot spline of f - f[0]: the piece coefficients (about each lower knot) agree,
    and so do the surface pressures of the two families at k = 0 (graded (G17) times c_N* = E*)."""
    f = TABLES[name]
    graded = gp.Indenter.tabulated(R_TAB, f)
    axi = ax.tabulated(R_TAB, f)
    # the axisymmetric spline's coefficients (f', f''/2, f'''/6 at each lower knot), the graded one's (c3, c2, c1)
    np.testing.assert_allclose(axi._local, graded.table._s.c[2::-1], rtol=1e-15, atol=0.0)
    rho = np.linspace(0.05, 0.95, 7)
    p_graded = gp.normal_fields(["pressure"], graded, a=A0, rho=rho, k=0.0, nu=NU, E0=E0, c0=C0,
                                rtol=1e-12)["pressure"]
    e_star = E0 / (1.0 - NU * NU)
    p_axi = -e_star * ax.surface_stress(rho * A0, 0.0, A0, A0, NU, 0.0, axi, components=("zz",),
                                        method="quadrature", rtol=1e-12)["zz"]
    np.testing.assert_allclose(p_graded, p_axi, rtol=1e-11)


@pytest.mark.parametrize("dg", [None, 0.8])
def test_sampled_paraboloid_equals_the_closed_form_paraboloid(dg):
    """A table of f = r^2/(2R) is the paraboloid exactly: the interior of the tabulated route (1-D superposition)
    equals the graded family's closed form at k = 0 (Hertz times c_N*, minus the adhesive punch) within the
    stated accuracy |error| <= rtol max(|value|, p_m), normal and adhesive load."""
    rtol = 1e-8
    tab = gp.Indenter.tabulated(R_TAB, R_TAB ** 2 / (2 * R))
    got = interior_fields(STRESS, tab, a=A0, rho=RHO, z=Z, k=0.0, nu=NU, E0=E0, c0=C0, delta_gamma=dg, rtol=rtol)
    ref = interior_fields(STRESS, gp.Indenter.parabolic(R), a=A0, rho=RHO, z=Z, k=0.0, nu=NU, E0=E0, c0=C0,
                          delta_gamma=dg)
    pm = _mean_pressure(gp.Indenter.parabolic(R))
    for n in STRESS:
        assert np.all(np.abs(got[n] - ref[n]) <= rtol * np.maximum(np.abs(ref[n]), pm)), n


@pytest.mark.parametrize("name", sorted(TABLES))
@pytest.mark.parametrize("dg", [None, 0.5])
def test_traction_tends_to_the_graded_surface_pressure(name, dg):
    """sigma_zz(r, z) -> -p(r) as z -> 0 inside the contact and -> 0 outside, p the graded family's own pressure
    of the spline ((G17), adhesive (G24)); the difference falls as z^2 (measured: 4e-6 p_m at z = 1e-3 a,
    4e-12 p_m at z = 1e-6 a), so a pressure of another spline or a missing term would stand out."""
    tab = gp.Indenter.tabulated(R_TAB, TABLES[name])
    rho = np.array([0.2, 0.5, 0.8, 1.3])
    entry = gp.normal_fields if dg is None else gp.adhesive_fields
    p = entry(["pressure"], tab, a=A0, rho=rho, k=0.0, nu=NU, E0=E0, c0=C0, rtol=1e-12,
              **({} if dg is None else {"delta_gamma": dg}))["pressure"]
    assert p[-1] == 0.0 and np.all(np.abs(p[:-1]) > 0.0)
    pm = _mean_pressure(tab)
    for z, tol in ((1e-3, 1e-5), (1e-6, 1e-10)):
        s = interior_fields(["sigma_zz"], tab, a=A0, rho=rho, z=z, k=0.0, nu=NU, E0=E0, c0=C0, delta_gamma=dg,
                            rtol=1e-10)["sigma_zz"]
        np.testing.assert_array_less(np.abs(s + p), tol * pm)


def test_sampled_paraboloid_under_tangential_load_equals_the_closed_form():
    """Cattaneo-Mindlin at k = 0 (G69): the stick radius of the table (bisection on F_N) and its sliding-punch
    superposition equal the paraboloid's closed forms within rtol max(|value|, p_m)."""
    rtol = 1e-8
    names = ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz", "validity")
    x = np.where(np.arange(RHO.size) % 2, -RHO, RHO)
    kw = dict(a=A0, x=x, z=Z, fx=0.4, mu=0.3, k=0.0, nu=NU, E0=E0, c0=C0, rtol=rtol)
    got = tangential_interior_fields(names, gp.Indenter.tabulated(R_TAB, R_TAB ** 2 / (2 * R)), **kw)
    ref = tangential_interior_fields(names, gp.Indenter.parabolic(R), **kw)
    pm = _mean_pressure(gp.Indenter.parabolic(R))
    for n in names[:-1]:
        assert np.all(np.abs(got[n] - ref[n]) <= rtol * np.maximum(np.abs(ref[n]), pm)), n
    assert np.all(got["validity"] == 0)


def test_k_above_zero_and_a_clamped_tip_are_refused_in_one_line():
    tab = gp.Indenter.tabulated(R_TAB, R_TAB ** 2 / (2 * R))
    with pytest.raises(ValueError, match=r"^profile = 'tabulated' is solved below the surface at k = 0 only: at "
                                         r"k > 0 .*pressure at every radial node.*; here k = 0\.25$"):
        interior_fields(STRESS, tab, a=A0, rho=0.5, z=[0.0, 0.5], k=[0.0, 0.25], nu=0.4, E0=E0, c0=C0)
    clamped = gp.Indenter("tabulated", (), gp.Tabulated(R_TAB, R_TAB ** 2 / (2 * R), slope_at_0=0.0))
    for call in (lambda: interior_fields(STRESS, clamped, a=A0, rho=0.5, z=0.5, k=0.0, nu=NU, E0=E0, c0=C0),
                 lambda: tangential_interior_fields(("sigma_zz",), clamped, a=A0, x=0.5, z=0.5, fx=0.4, mu=0.3, k=0.0,
                                                    nu=NU, E0=E0, c0=C0)):
        with pytest.raises(ValueError, match=r"slope_at_0 set is not solved below the surface: its spline's end "
                                             r"condition .*\(slope_at_0 = 0\.0\)$"):
            call()


@pytest.mark.slow          # ~2 s: CI runs it with the slow tests
def test_peak_of_a_sampled_paraboloid_is_the_closed_form_peak():
    """The peak search on the tabulated field finds the paraboloid's tau_max peak (on the axis at 0.48 a,
    found on its closed form) to the superposition's rtol in value and the search's 1e-7 a in position."""
    from stressfields.physics.graded.interior import peaks

    kw = dict(a=A0, k=0.0, nu=NU, E0=E0, c0=C0, rtol=1e-10)
    got = peaks(gp.Indenter.tabulated(R_TAB, R_TAB ** 2 / (2 * R)), **kw)
    ref = peaks(gp.Indenter.parabolic(R), **kw)
    assert float(got["tau_max_peak"]) == pytest.approx(float(ref["tau_max_peak"]), rel=1e-9)
    assert float(got["tau_max_peak_depth"]) == pytest.approx(float(ref["tau_max_peak_depth"]), abs=1e-7)
    assert float(got["tau_max_peak_rho"]) == float(ref["tau_max_peak_rho"]) == 0.0
    assert int(got["peak_validity"]) == int(ref["peak_validity"]) == 0
