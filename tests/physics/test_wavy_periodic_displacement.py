"""Displacements below the periodic wavy surface (docs/theory/wavy.md (W46)-(W48)), proven by independent
routes: mpmath quadrature of the periodic line-load displacement kernels (the Flamant kernels summed over all
periods, datum of the periodic surface displacement) over the pressure (W30) evaluated in mpmath (stored,
tests/data/wavy_periodic_displacement.json, and a few live points); the surface
displacement (W15) at z = 0; plane-strain Hooke's law against the product's own stresses by central
differences (residual falling as h^2); the mean pressure's uniform strain across a period; the closed
primitive against the series where both hold."""
from __future__ import annotations

import importlib.util
import json
import math
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest

from stressfields.physics.wavy import contact, interior

DATA = Path(__file__).resolve().parents[1] / "data" / "wavy_periodic_displacement.json"
F1 = ([0.5], [1])
F2 = ([0.5, 0.01], [1, 11])
F11 = ([0.5] + [0.004] * 10, list(range(1, 12)))
NU = 0.3


def disp(x, z, w, profile=F2, nu=NU, **kw):
    ux, uz, info = contact.subsurface_displacement(np.asarray(x, float), np.asarray(z, float), w, *profile,
                                               periodic=True, nu=nu, **kw)
    return ux, uz, info


def _generator():
    """The script that wrote the stored reference (tests/data), for its mpmath routes: the pressure (W30) with
    mpmath's Legendre values and the quadrature of the periodic line-load kernels (it imports no stressfields)."""
    spec = importlib.util.spec_from_file_location("make_wavy_periodic_displacement",
                                                  DATA.with_name("make_wavy_periodic_displacement.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _reference():
    return json.loads(DATA.read_text())


def _profile(ref, name):
    p = ref["profiles"][name]
    return p["amplitudes"], p["wavenumbers"]


def test_reference_covers_the_brief():
    ref = _reference()
    cases = ref["normal"]
    assert sum(len(c["points"]) for c in cases) >= 40
    assert {len(_profile(ref, c["profile"])[1]) for c in cases} == {1, 2, 11}
    widths = sorted(c["two_a_over_lambda1"] for c in cases)
    assert widths[0] <= 1e-3 and widths[-1] >= 0.999
    depths = [np.array(c["points"])[:, 1] * math.pi * c["two_a_over_lambda1"] for c in cases]
    assert min(d.min() for d in depths) <= 1e-9 * 1.0001 and max(d.max() for d in depths) >= 10 * math.pi * 0.9999
    assert ref["meta"]["nu"] == NU


@pytest.mark.parametrize("case", _reference()["normal"], ids=lambda c: f"{c['profile']}-{c['two_a_over_lambda1']}")
def test_against_stored_quadrature(case):
    """Nine points per case (1, 2 and 11 harmonics, 2a/lambda_1 = 1e-3 .. 0.999): depths 1e-9 to 5 lambda_1,
    near the surface (closed primitive) and deep (series), inside, at and outside the contact and beyond one
    period; each within its error_estimate (<= 1e-12 Delta_1) plus the reference's 1e-14."""
    P = np.array(case["points"])
    prof = _profile(_reference(), case["profile"])
    ux, uz, info = disp(P[:, 0], P[:, 1], case["two_a_over_lambda1"], prof)
    err = info["error_estimate"]
    assert info["converged"].all() and (err <= 1e-12).all(), err.max()
    tol = err + 1e-14 * (1.0 + np.abs(P[:, 2]) + np.abs(P[:, 3]))
    assert (np.abs(ux - P[:, 2]) <= tol).all(), np.abs(ux - P[:, 2]).max()
    assert (np.abs(uz - P[:, 3]) <= tol).all(), np.abs(uz - P[:, 3]).max()


@pytest.mark.parametrize("case", _reference()["slip"], ids=lambda c: f"{c['profile']}-{c['two_a_over_lambda1']}")
def test_partial_slip_against_stored_quadrature(case):
    """Combined load: the product less its normal part against the quadrature of the periodic tangential
    kernels over mu [p(s; a) - p(s; c)], with the stick width solved in mpmath (which the product's meets)."""
    P = np.array(case["points"])
    w, mu, fx = case["two_a_over_lambda1"], case["mu"], case["fx"]
    prof = _profile(_reference(), case["profile"])
    ratio = float(contact.stick_half_width(w, *prof, fx, periodic=True)[0])
    assert abs(ratio - case["stick_over_a"]) <= 1e-12
    ux, uz, info = disp(P[:, 0], P[:, 1], w, prof, mu=mu, fx=fx)
    nx, nz, _ = disp(P[:, 0], P[:, 1], w, prof)
    tol = info["error_estimate"] + 1e-14 * (1.0 + np.abs(P[:, 2]) + np.abs(P[:, 3]))
    assert (np.abs(ux - nx - P[:, 2]) <= tol).all(), np.abs(ux - nx - P[:, 2]).max()
    assert (np.abs(uz - nz - P[:, 3]) <= tol).all(), np.abs(uz - nz - P[:, 3]).max()


def test_live_quadrature():
    """Three points by quadrature here (not the stored file), with the reference script's routes: two
    harmonics, near the surface inside the contact, mid-depth outside it, and deep in the next period."""
    gen = _generator()
    mp.mp.dps = 15
    w = 0.45
    p, a = gen.pressure(w, F2)
    a = float(a)
    xk, zk = np.array([0.4 * a, 2.5, 7.0]), np.array([1e-3, 0.4, 3.0])
    ux, uz, info = disp(xk / a, zk / a, w)
    for i in range(xk.size):
        rx, rz = (float(v) for v in gen.normal(mp.mpf(xk[i]), mp.mpf(zk[i]), p, mp.mpf(a)))
        tol = info["error_estimate"][i] + 1e-14 * (1.0 + abs(rz) + abs(rx))
        assert abs(ux[i] - rx) <= tol and abs(uz[i] - rz) <= tol, (xk[i], zk[i], ux[i] - rx, uz[i] - rz)


CASES = [(1e-3, F1), (0.3, F2), (0.999, F2), (0.6, F11)]


@pytest.mark.parametrize("w, profile", CASES, ids=lambda v: str(v) if isinstance(v, float) else f"{len(v[1])}h")
def test_surface_is_the_surface_displacement(w, profile):
    """z = 0: u_z is the periodic surface displacement (W15) to 1e-13 Delta_1, inside, on the edge, outside the
    contact and in other periods; u_x there is -(1 - 2 nu)/(2 (1 - nu)) int_0^x p (Johnson's, odd in x), here
    at x = a and half a period against the mean pressure: int_0^pi p = pi p_inf."""
    t = np.array([0.0, 0.3, -0.7, 1.0, -1.0, 1.2, 0.99 / w, -1.0 / w, 2.5 / w, -3.3 / w])
    ux, uz, _ = disp(t, 0.0, w, profile)
    ref = contact.displacement(t, w, *profile, periodic=True)[0]
    np.testing.assert_allclose(uz, ref, rtol=0, atol=1e-13)
    pinf = float(contact.mean_pressure(w, *profile, periodic=True))
    k = (1 - 2 * NU) / (2 * (1 - NU))
    assert abs(ux[0]) <= 1e-15
    assert abs(ux[7] - k * math.pi * pinf) <= 1e-13          # x = -pi: +k int_0^pi p
    ux5, _, _ = disp(np.array([1.0, -1.0]), 0.0, w, profile, nu=0.5)
    np.testing.assert_array_equal(ux5, 0.0)                # incompressible: no lateral surface displacement


def test_mean_pressure_strain_across_a_period():
    """The k = 0 mode: u_z is periodic in x at every depth, and u_x(x + lambda_1) - u_x(x) =
    -(1 - 2 nu) p_inf lambda_1/(2 (1 - nu)) (the uniform strain of sigma_xx = sigma_zz = -p_inf), with p_inf
    the closed mean pressure (W11); u_z(z) - u_z(z') far below: -(1 - 2 nu)/(2 (1 - nu)) p_inf (z - z')."""
    w = 0.4
    a = math.pi * w
    t = np.array([0.2, -0.8, 1.5])
    per = 2 * math.pi / a
    pinf = float(contact.mean_pressure(w, *F2, periodic=True))
    k = (1 - 2 * NU) / (2 * (1 - NU))
    for zt in (0.0, 0.05, 1.0, 8.0):
        ux0, uz0, _ = disp(t, zt, w)
        ux1, uz1, _ = disp(t + per, zt, w)
        np.testing.assert_allclose(uz1, uz0, rtol=0, atol=1e-13)
        np.testing.assert_allclose(ux1 - ux0, -k * 2 * math.pi * pinf, rtol=0, atol=1e-13)
    _, d1, _ = disp(0.3, 60.0 / a, w)
    _, d2, _ = disp(0.3, 70.0 / a, w)
    assert abs((d2 - d1) + k * pinf * 10.0) <= 1e-13


def hooke_residual(x, z, w, prof, h, mu=0.0, fx=0.0):
    """The residual of plane-strain Hooke's law between central differences of u (step h in x/a, z/a) and the
    product's stresses (p* units; t = x/a): 2 (1 - nu)/a du_x/dt = sxx - nu (sxx + szz), likewise zz, and
    (1 - nu)/a (du_x/dzt + du_z/dt) = sxz."""
    a = math.pi * w
    s, _ = contact.subsurface(("sigma_xx", "sigma_zz", "sigma_xz"), x, z, w, *prof, periodic=True, mu=mu, fx=fx)
    sxx, szz, sxz = (float(s[k]) for k in ("sigma_xx", "sigma_zz", "sigma_xz"))
    tr = sxx + szz
    X = np.array([x + h, x - h, x, x])
    Z = np.array([z, z, z + h, z - h])
    ux, uz, _ = disp(X, Z, w, prof, mu=mu, fx=fx)
    exx = (ux[0] - ux[1]) / (2 * h) / a
    ezz = (uz[2] - uz[3]) / (2 * h) / a
    gxz = ((ux[2] - ux[3]) + (uz[0] - uz[1])) / (2 * h) / a
    return np.max(np.abs([2 * (1 - NU) * exx - (sxx - NU * tr), 2 * (1 - NU) * ezz - (szz - NU * tr),
                          (1 - NU) * gxz - sxz]))


@pytest.mark.parametrize("x, z, w, prof, mu, fx", [(0.4, 0.3, 0.3, F2, 0.0, 0.0), (1.3, 0.1, 0.6, F11, 0.0, 0.0),
                                                   (-0.9, 1.5, 0.3, F2, 0.0, 0.0), (0.5, 0.4, 0.3, F2, 0.4, 0.5)])
def test_hooke_against_the_stresses_falls_as_h_squared(x, z, w, prof, mu, fx):
    """Central differences of u against the product's stresses (closed and series routes, normal and combined
    load): the residual is visible at h = 4e-2 and falls by about 16 at h = 1e-2."""
    r1, r2 = hooke_residual(x, z, w, prof, 4e-2, mu, fx), hooke_residual(x, z, w, prof, 1e-2, mu, fx)
    assert r1 > 1e-9
    assert 12.0 < r1 / r2 < 20.0, (r1, r2)


def test_closed_primitive_meets_the_series_below_the_switch():
    """Below the switch depth z_s, where the series holds within its bound, the closed primitive (which the
    product uses only above z_s) agrees with it within the closed form's bound (W48) at that depth, whose
    rounding grows there as e^((j+1) z); and the displacements are continuous across the switch."""
    for w, prof in ((0.3, F2), (0.6, F11), (1e-3, F1), (0.999, F2)):
        c = contact._interior_ctx(w, *prof, True, None, contact.DEFAULT_RTOL, contact.DEFAULT_MAX_TERMS)
        pot = interior.PeriodicPotential(c.table, c.dr, c.n, c.rtol)
        a, zs = float(c.table.a[0]), float(pot.z_switch[0])
        t = np.array([0.3, -0.7, 1.3, 2.0 / w, 1.0, -1.0 / w])
        X = interior._folded(t, a)
        for k in (1.2, 2.0, 4.0):
            Z = np.full(t.shape, k * zs)
            closed, _ = pot._closed_primitive(0, t, X, Z)
            series, _ = pot._series_primitive(0, t, X, Z)
            bound = pot.closed_primitive_bound(np.zeros(t.size, int), Z) + pot.err_series[0]
            assert (np.abs(closed - series) <= bound).all(), (w, k, np.abs(closed - series).max())
        ux, uz, info = disp(t, np.array([zs * (1 - 1e-12), zs * (1 + 1e-12)])[:, None] / a, w, prof)
        assert np.max(np.abs(np.diff(uz, axis=0))) <= 2 * info["error_estimate"].max()
        assert np.max(np.abs(np.diff(ux, axis=0))) <= 2 * info["error_estimate"].max()
