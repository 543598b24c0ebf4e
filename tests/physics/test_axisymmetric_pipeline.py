"""The one pipeline of the axisymmetric family (``fields``, ``history_fields``, ``loading``).

Evidence:
* a monotonic load is a history of one term: ``fields`` and ``history_fields`` with the history
  (1,) agree on the surface and below it, for every field, on a closed-form and a 1-D route;
* a reversal is Mindlin–Deresiewicz, N + T(c_1) - 2 T(c_r) (docs/theory/axisymmetric.md (A69)),
  with the tangential parts T taken from two monotonic loads: the history's terms are summed as
  the superposition says, on the surface (the annulus form of ``history_stress``) and below it;
* the values are per unit E*, and the invariants of a scaled tensor (``invariants=False``, then
  ``stress_invariants``) are within 3 ulp of the tensor's Frobenius norm of the exact invariants
  (mpmath); at scale 1 they, and the validity flag, are ``fields``' own to the last bit, singular
  points included, and at singular points the limits scale with the tensor;
* no module of the family imports another module's private name.
"""
from __future__ import annotations

import ast
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest

from stressfields.physics import axisymmetric as ax

NU, MU = 0.3, 0.5
VALUED = list(ax.STRESS) + ["dpdz", "u_x", "u_y", "u_z"]
INVARIANTS = ["von_mises", "sigma_1", "sigma_2", "sigma_3", "tau_max"]
PROFILES = {"paraboloid": (ax.paraboloid(1.0), "auto"), "power_law": (ax.power_law(1.0, 1.5), "quadrature")}


def _points():
    """Surface and interior points away from the singular rings r = a, r = c (z = 0)."""
    rng = np.random.default_rng(7)
    x, y = rng.uniform(-1.6, 1.6, 40), rng.uniform(-0.8, 0.8, 40)
    z = np.where(np.arange(40) % 3 == 0, 0.0, rng.uniform(0.01, 1.5, 40))
    r = np.hypot(x, y)
    keep = (z > 0) | ((np.abs(r - 1.0) > 0.05) & (np.abs(r - 0.8) > 0.05) & (np.abs(r - 0.5) > 0.05) & (r > 0.05))
    return x[keep], y[keep], z[keep]


def _close(got, want, rtol, names):
    for n in names:
        scale = np.max(np.abs(want[n]))
        np.testing.assert_allclose(got[n], want[n], rtol=0, atol=rtol * scale, err_msg=n)


@pytest.mark.parametrize("kind", sorted(PROFILES))
def test_monotonic_load_is_a_history_of_one_term(kind):
    profile, method = PROFILES[kind]
    x, y, z = _points()
    ux0 = 0.3 * MU * (2 - NU) / (2 * (1 - NU))      # slip ratio 0.3: partial slip
    names = VALUED + ["region", "validity", "stick_radius"]
    mono, rm = ax.fields(names, profile, x, y, z, a=1.0, nu=NU, mu=MU, ux0=ux0, method=method)
    hist, rh = ax.history_fields(names, profile, x, y, z, a=1.0, nu=NU, mu=MU, amplitude=ux0, history=[1.0],
                                 step=0, method=method)
    assert rm == rh
    # the monotonic load hands the slip ratio to the kernels (a - c without rounding), the history
    # the rounded radii: equal to rounding (closed forms 1e-12, the 1-D route its rtol 1e-10)
    _close(hist, mono, 1e-12 if kind == "paraboloid" else 1e-10, VALUED)
    for n in ("region", "validity"):
        np.testing.assert_array_equal(hist[n], mono[n], err_msg=n)
    np.testing.assert_array_equal(np.broadcast_to(hist["stick_radius"], x.shape),
                                  np.broadcast_to(mono["stick_radius"], x.shape))


@pytest.mark.parametrize("kind", sorted(PROFILES))
def test_reversal_is_mindlin_deresiewicz(kind):
    """Load to u, reverse to u/2: the memory terms (u, +1) and (u/4, -2), so the fields are
    N + T(u) - 2 T(u/4), T(lam) = fields(ux0 = lam) - fields(ux0 = 0)."""
    profile, method = PROFILES[kind]
    x, y, z = _points()
    u = 0.5 * MU * (2 - NU) / (2 * (1 - NU))
    names = VALUED

    def mono(lam):
        return ax.fields(names, profile, x, y, z, a=1.0, nu=NU, mu=MU, ux0=lam, method=method)[0]

    n, t1, tr = mono(0.0), mono(u), mono(u / 4)
    want = {k: n[k] + (t1[k] - n[k]) - 2 * (tr[k] - n[k]) for k in names}
    got, _ = ax.history_fields(names, profile, x, y, z, a=1.0, nu=NU, mu=MU, amplitude=u, history=[1.0, 0.5],
                               step=1, method=method)
    _close(got, want, 1e-12 if kind == "paraboloid" else 1e-10, names)


def _frobenius(t):
    return np.sqrt(t[0] ** 2 + t[1] ** 2 + t[2] ** 2 + 2 * (t[3] ** 2 + t[4] ** 2 + t[5] ** 2))


#: the scales of the scenarios: 1/p_m (normalised, Hertz a = R = 1) and E* (physical, steel)
SCALES = (3 * np.pi / 4, 210e9 / (1 - 0.3 ** 2))


def _scaled_invariants(values, s):
    """The invariants of ``s`` times the tensor of ``fields(..., invariants=False)``, as the scenarios form them."""
    tensor = {n: values[n] * s for n in ax.STRESS}
    return ax.stress_invariants(INVARIANTS, tensor, values["singular"], s)


def test_invariants_of_the_scaled_tensor_are_within_3_ulp_of_the_exact_ones():
    """The invariants of s T against those of the exact product s T, in 30 digits (mpmath's symmetric
    eigenvalue solver): within 3 ulp of |s T|_F (measured 2.5 over 300 points)."""
    x, y, z = _points()
    values, _ = ax.fields(INVARIANTS, ax.paraboloid(1.0), x, y, z, a=1.0, nu=NU, mu=MU, ux0=0.2, invariants=False)
    T = [values[n] for n in ax.STRESS]
    mp.mp.dps = 30
    for s in SCALES:
        v = _scaled_invariants(values, s)
        norm = _frobenius([s * t for t in T])
        for i in range(0, T[0].size, 2):
            xx, yy, zz, xy, xz, yz = (mp.mpf(float(t[i] * s)) for t in T)
            ev = sorted(mp.eigsy(mp.matrix([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]))[0], reverse=True)
            vm = mp.sqrt(((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2) / 2 + 3 * (xy ** 2 + xz ** 2 + yz ** 2))
            exact = dict(zip(INVARIANTS, (vm, ev[0], ev[1], ev[2], (ev[0] - ev[2]) / 2)))
            for n in INVARIANTS:
                err = abs(mp.mpf(float(v[n][i])) - exact[n])
                assert err <= 3 * np.spacing(norm[i]), (n, s, i, float(err / np.spacing(norm[i])))


#: singular points on the surface: a cone's tip (nu = 1/2 and mu = 0: von Mises' limit is the
#: remainder's, sigma_xz; partial and gross slip) and a flat punch's edge (nu = 0: the limit of the
#: principal stress along the hoop direction is the remainder's), with regular points around them
SINGULAR = {
    "cone": (ax.cone(0.2), dict(x=np.array([0.0, 0.0, 0.3, 0.7]), y=np.array([0.0]), nu=np.array([[0.5], [0.3]]),
                                mu=np.array([[[0.0]], [[0.4]]]), ux0=np.array([[[[0.0]]], [[[0.05]]], [[[5.0]]]]))),
    "flat_punch": (ax.flat_punch(1.0), dict(x=np.array([1.0, 0.6, 0.0, 0.3]), y=np.array([0.0, 0.8, 0.0, 0.0]),
                                            nu=np.array([[0.0], [0.3]]),
                                            mu=np.array([[[0.0]], [[0.3]]]), ux0=np.array([[[[0.0]]], [[[0.05]]]]))),
}


@pytest.mark.parametrize("kind", sorted(SINGULAR))
def test_invariants_and_validity_of_the_tensor_and_its_singular_points_are_those_of_fields(kind):
    """``fields`` with ``invariants=False`` then ``stress_invariants`` at scale 1 gives the invariants
    and the validity flag of ``fields`` bit for bit, singular points (+-inf, finite limits, NaN)
    included; at a scale s the limits are s times those at scale 1 to rounding, +-inf and NaN alike."""
    profile, kw = SINGULAR[kind]
    names = INVARIANTS + ["validity"]
    whole, _ = ax.fields(names, profile, a=1.0, **kw)
    parts, _ = ax.fields(names, profile, a=1.0, invariants=False, **kw)
    assert parts["singular"].index.size > 0
    formed = ax.stress_invariants(INVARIANTS, parts, parts["singular"], 1.0, validity=parts["validity"])
    for n in names:
        np.testing.assert_array_equal(formed[n], whole[n], err_msg=n)
    # the cases are there: a finite limit (from the remainder) at a point with an infinite component
    assert np.any([np.isfinite(whole[n]) & (whole["validity"] == 1) for n in INVARIANTS])
    s = SCALES[1]
    scaled = _scaled_invariants(parts, s)
    for n in INVARIANTS:
        finite = np.isfinite(whole[n])
        np.testing.assert_array_equal(np.isnan(scaled[n]), np.isnan(whole[n]), err_msg=n)
        np.testing.assert_array_equal(scaled[n][~finite], whole[n][~finite], err_msg=n)
        # two roundings of the same value: 4 ulp of the largest (measured 1)
        np.testing.assert_allclose(scaled[n][finite], s * whole[n][finite], rtol=0.0,
                                   atol=4 * np.spacing(s * np.max(np.abs(whole[n][finite]))), err_msg=n)


def _private_imports(path: Path) -> list[str]:
    """Names starting with one underscore that ``path`` imports from another module."""
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.module != "__future__":
            out += [f"{node.module}.{a.name}" for a in node.names
                    if a.name.startswith("_") and not a.name.startswith("__")]
    return out


def test_no_module_of_the_family_imports_another_modules_private_name():
    root = Path(ax.__file__).parent
    found = {p.name: _private_imports(p) for p in sorted(root.glob("*.py"))}
    assert {k: v for k, v in found.items() if v} == {}
    # nor does a module elsewhere in the package reach into the family's private names
    package = root.parents[1]
    outside = {str(p.relative_to(package)): [n for n in _private_imports(p) if "axisymmetric" in n]
               for p in package.rglob("*.py") if root not in p.parents}
    assert {k: v for k, v in outside.items() if v} == {}
