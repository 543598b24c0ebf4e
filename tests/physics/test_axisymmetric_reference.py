"""Every point of tests/data/axisymmetric_surface.json (an independent Boussinesq/Cerruti
superposition route; provenance in tests/data/README.md) through both the closed forms and the
quadrature route."""
import math

import numpy as np
import pytest
from conftest import load_reference

from stressfields.physics import axisymmetric as ax
from stressfields.physics.invariants import principal_stresses, von_mises

KEYS = ("xx", "yy", "zz", "xy", "xz", "yz")
A = 1.3                      # contact radius used here (the points are in units of a)


@pytest.fixture(scope="module")
def cases():
    pts = load_reference("axisymmetric_surface")["points"]
    assert len(pts) >= 100
    out = []
    for p in pts:
        if p["profile"] == "cone":
            tan = 0.8
            prof, p0 = ax.cone(tan), 0.5 * tan                     # p0 = E* tan(theta)/2 (E* = 1)
        else:
            assert p["profile"] == "parabolic"
            R = 2.7
            prof, p0 = ax.paraboloid(R), 2.0 * A / (math.pi * R)   # p0 = 2 E* a / (pi R)
        out.append((p, prof, p0))
    return out


def _arrays(group):
    """Vectorised evaluation of one (profile, nu, mu, c) group."""
    p = group[0][0]
    x = np.array([q["x_over_a"] for q, _, _ in group]) * A
    y = np.array([q["y_over_a"] for q, _, _ in group]) * A
    c = p["c_over_a"] * A if p["mu"] > 0 else 0.0
    return x, y, c


def _groups(cases):
    groups = {}
    for item in cases:
        p = item[0]
        groups.setdefault((p["profile"], p["nu"], p["mu"], p["c_over_a"]), []).append(item)
    return list(groups.values())


@pytest.mark.parametrize("method,rtol,tol", [("closed", 1e-10, 1e-12),
                                             ("quadrature", 1e-6, 1e-6),
                                             ("quadrature", 1e-10, 1e-10)])
def test_reference_points(cases, method, rtol, tol):
    worst = 0.0
    for group in _groups(cases):
        p, prof, p0 = group[0]
        x, y, c = _arrays(group)
        s = ax.surface_stress(x, y, A, c, p["nu"], p["mu"], prof, method=method, rtol=rtol)
        dp = ax.surface_dpdz(x, y, A, c, p["nu"], p["mu"], prof, method=method, rtol=rtol)
        vm = von_mises(*(s[k] for k in KEYS))
        pr = np.stack(principal_stresses(*(s[k] for k in KEYS)), axis=1)
        for i, (q, _, _) in enumerate(group):
            got = [s[k][i] / p0 for k in KEYS] + [dp[i] * A / p0, vm[i] / p0] + list(pr[i] / p0)
            ref = [q["sigma"][k] for k in KEYS] + [q["dpdz"], q["von_mises"]] + list(q["principal"])
            for g, r, name in zip(got, ref, KEYS + ("dpdz", "von_mises", "s1", "s2", "s3")):
                err = abs(g - r) / max(1.0, abs(r))
                worst = max(worst, err)
                assert err <= tol, f"{q['id']} {name}: {g!r} vs {r!r} ({method}, rtol={rtol})"
    assert worst > 0.0   # the comparison ran


def test_stick_radius_of_reference_cases(cases):
    """c/a of the u_x0 = delta/4 cases from eq. (38)/(42)."""
    seen = 0
    for p, prof, _ in cases:
        if p["ux0_over_delta"] is None:
            continue
        c = ax.stick_radius(A, p["nu"], p["mu"], p["ux0_over_delta"], prof)
        assert float(c) / A == pytest.approx(p["c_over_a"], abs=1e-14), p["id"]
        seen += 1
    assert seen > 0


def test_figure_stick_radii():
    """The paper's figure cases (docs/theory/axisymmetric.md, errata: u_x0 = delta/4, not delta/2) by
    eq. (38), docs/theory/axisymmetric.md (A32)-(A33): cone, nu = 0.3: c/a = 0 (mu 0.1, 0.2), 16/51 (0.3),
    33/68 (0.4)."""
    c = ax.stick_radius(1.0, 0.3, np.array([0.1, 0.2, 0.3, 0.4]), 0.25, ax.cone(1.0))
    np.testing.assert_allclose(c, [0.0, 0.0, 16 / 51, 33 / 68], rtol=1e-14, atol=0)
