"""The peaks of tau_max and von Mises in the lower body of the graded Cattaneo-Mindlin contact at k = 0
(physics.graded.interior.tangential_peaks, docs/theory/graded.md (G69)): against Johnson's axis formula
without tangential load, against a search of our own (a dense grid and scipy's Powell refinement of the
graded field itself) under partial slip, and the unbounded conical tip."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import minimize, minimize_scalar

from stressfields.physics import graded as gp
from stressfields.physics.graded.interior import tangential_interior_fields, tangential_peaks

R, A0, E0, C0 = 0.02, 1e-3, 2e9, 1e-2
PARA = gp.Indenter.parabolic(R)


def test_without_tangential_load_the_peak_is_johnsons_on_the_axis():
    nu = 0.3
    got = tangential_peaks(PARA, a=A0, fx=0.0, mu=0.3, k=0.0, nu=nu, E0=E0, c0=C0, E0_2=np.inf)

    def tau(z):       # tau_max / p0 on the Hertz axis (Johnson 1985, sec. 3.4)
        return 0.5 * ((-(1 + nu) * (1 - z * math.atan(1 / z)) + 0.5 / (1 + z * z)) + 1 / (1 + z * z))
    best = minimize_scalar(lambda z: -tau(z), bounds=(0.2, 1.0), method="bounded", options={"xatol": 1e-10})
    p0 = 2 * A0 * E0 / (1 - nu * nu) / (math.pi * R)          # rigid indenter: c_N* = E*
    assert float(got["tau_max_peak"]) == pytest.approx(-best.fun * p0, rel=1e-9)
    assert float(got["tau_max_peak_depth"]) == pytest.approx(best.x, abs=1e-6)
    assert float(got["tau_max_peak_x"]) == 0.0 and int(got["peak_validity"]) == 0


@pytest.mark.parametrize("fx,mu,name", [(0.8, 0.4, "tau_max"), (0.8, 0.4, "von_mises"), (0.3, 0.2, "tau_max")])
def test_under_partial_slip_the_peak_is_the_fields_maximum(fx, mu, name):
    """A search of our own on the graded field (identical bodies; at fx = 0.8, mu = 0.4 the peak sits on the
    surface at the trailing edge, at fx = 0.3, mu = 0.2 below the surface): the best of a 121 x 46 grid
    over x/a in [-1.5, 1.5] and z/a in {0} u [1e-3, 2], with the surface kinks x = +-a and +-c (the stick
    radius c = a (1 - fx)^(1/3), (G33) at n = 2, k = 0) on it, refined by Powell (bounded to z >= 0); a
    maximum on a kink stays there."""
    kw = dict(a=A0, fx=fx, mu=mu, k=0.0, nu=0.25, E0=E0, c0=C0)
    got = tangential_peaks(PARA, **kw)

    def f(x, z):
        return tangential_interior_fields([name], PARA, x=x, z=z, **kw)[name]
    c = (1 - fx) ** (1 / 3)
    xs = np.union1d(np.linspace(-1.5, 1.5, 121), [-1.0, -c, c, 1.0])
    zs = np.concatenate([[0.0], np.geomspace(1e-3, 2.0, 45)])
    grid = f(xs[None, :], zs[:, None])
    i, j = np.unravel_index(np.argmax(grid), grid.shape)
    res = minimize(lambda v: -f(v[0], max(v[1], 0.0)), [xs[j], zs[i]], method="Powell",
                   bounds=[(-1.5, 1.5), (0.0, 2.0)], options={"xtol": 1e-10, "ftol": 1e-15})
    value, x, z = (-res.fun, res.x[0], max(res.x[1], 0.0)) if -res.fun > grid[i, j] else (grid[i, j], xs[j], zs[i])
    assert float(got[f"{name}_peak"]) == pytest.approx(value, rel=1e-9)
    assert float(got[f"{name}_peak_x"]) == pytest.approx(x, abs=1e-4)
    assert float(got[f"{name}_peak_depth"]) == pytest.approx(z, abs=1e-4)
    assert int(got["peak_validity"]) == 0


def test_the_conical_tip_is_an_unbounded_peak():
    got = tangential_peaks(gp.Indenter.conical(0.1), a=A0, fx=0.5, mu=0.3, k=0.0, nu=0.3, E0=E0, c0=C0)
    assert np.isposinf(got["tau_max_peak"]) and float(got["tau_max_peak_depth"]) == 0.0
    assert float(got["tau_max_peak_x"]) == 0.0 and int(got["peak_validity"]) == 1


def test_k_above_zero_and_clamped_tabulated_profiles_are_refused():
    with pytest.raises(ValueError, match=r"k = 0\.5 is not solved below the surface under tangential load"):
        tangential_peaks(PARA, a=A0, fx=0.5, mu=0.3, k=0.5, nu=0.4, E0=E0, c0=C0)
    r = np.linspace(0.0, 2e-3, 8)
    clamped = gp.Indenter("tabulated", (), gp.Tabulated(r, r ** 2 / (2 * R), slope_at_0=0.0))
    with pytest.raises(ValueError, match=r"slope_at_0 set is not solved below the surface"):
        tangential_peaks(clamped, a=A0, fx=0.5, mu=0.3, k=0.0, nu=0.3, E0=E0, c0=C0)
