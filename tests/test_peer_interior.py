"""Smoke test of the peers below the surface (benchmarks/peers_interior.py): tamaas' conventions held
against the exact periodic solution of a single harmonic pressure, and its Hertz rows getting more
accurate as the grid refines. Skipped unless tamaas is installed; no timing assertions."""
import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("tamaas")
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))   # the harness is not in the package
import peers_interior as pi  # noqa: E402


def _harmonic(x, y, z, k, nu):
    """Stresses under the pressure cos(k . x) on the half-space z >= 0: in the frame (s along k, t
    across), sigma_ss = -(1 - q z) e^{-qz} cos, sigma_zz = -(1 + q z) e^{-qz} cos, tau_sz = -q z e^{-qz} sin,
    sigma_tt = nu (sigma_ss + sigma_zz) (plane strain), q = |k|: the Airy function (1 + q z) e^{-qz} cos(q s) / q^2,
    which is biharmonic, decays with depth, and gives sigma_zz = -cos, tau_sz = 0 on z = 0."""
    q = np.hypot(*k)
    c, s = k[0] / q, k[1] / q
    phase = k[0] * x + k[1] * y
    decay = np.exp(-q * z)
    ss = -(1 - q * z) * decay * np.cos(phase)
    zz = -(1 + q * z) * decay * np.cos(phase)
    sz = -q * z * decay * np.sin(phase)
    tt = nu * (ss + zz)
    return {"xx": ss * c * c + tt * s * s, "yy": ss * s * s + tt * c * c, "zz": zz,
            "xy": (ss - tt) * c * s, "xz": sz * c, "yz": sz * s}


def test_tamaas_conventions_single_harmonic():
    """Component order, the sqrt(2) on the shears, the layer depths, the sign of the pressure and of z:
    all six stresses of an oblique harmonic (k along (1, 2): no component vanishes) to rounding."""
    n, side, nu = 16, 4.0, 0.3
    depths = 0.25 * np.arange(1, 7)
    xs = np.arange(n) * side / n                      # tamaas' node i sits at i side / n
    x, y, z = xs[None, :, None], xs[None, None, :], depths[:, None, None]
    k = 2 * np.pi / side * np.array([1.0, 2.0])
    got = pi.tamaas_volume_stress(np.cos(k[0] * xs[:, None] + k[1] * xs[None, :]), side, depths, nu)
    exact = _harmonic(x, y, z, k, nu)
    for name in pi.COMPONENTS:
        # measured 4e-16: one resolved Fourier mode is exact to rounding
        assert np.max(np.abs(got[name] - exact[name])) < 1e-13, name


def test_tamaas_mean_pressure_is_laterally_constrained():
    """The uniform part of the pressure: sigma_zz = -p, sigma_xx = sigma_yy = -nu/(1 - nu) p (zero
    in-plane strain), not the isolated half-space's -(1 + 2 nu)/2 p: the caveat of the module docstring."""
    nu = 0.3
    got = pi.tamaas_volume_stress(np.ones((8, 8)), 4.0, [0.5, 1.0], nu)
    assert np.allclose(got["zz"], -1.0, rtol=0, atol=1e-14)
    assert np.allclose(got["xx"], -nu / (1 - nu), rtol=0, atol=1e-14)
    assert np.allclose(got["yy"], -nu / (1 - nu), rtol=0, atol=1e-14)


def test_depths_must_be_tamaas_uniform_layers():
    with pytest.raises(ValueError, match="h, 2h"):
        pi.tamaas_hertz_interior(8, [0.1, 0.3])


def test_tamaas_hertz_rows_converge():
    rows = pi.tamaas_rows(grids=(32, 64), repeats=1)[pi.CASE]
    (t32, e32), (t64, e64) = rows[(pi.TAMAAS, 32.0)], rows[(pi.TAMAAS, 64.0)]
    assert t32 > 0 and t64 > 0
    # measured 0.15 and 0.079 (the largest at z = a/8 beside the contact edge, where the grid
    # resolves the pressure's square-root fall only coarsely)
    assert e64 < 0.75 * e32 < 0.3


def test_hamilton_rows():
    pytest.importorskip("ContactMechanics")
    rows = pi.hamilton_rows(32, repeats=1)
    sec, err = rows[pi.CASE][(pi.HAMILTON, 0.0)]
    # off the axis and on it (which the peer special-cases): test_peer_crosscheck's tolerance
    assert sec > 0 and err < 1e-11
    assert {pi.axis_case(r) for r in pi.AXIS_RADII} <= set(rows)


def test_peer_interior_rows_skip_without_the_peers(monkeypatch, capsys):
    class Cfg:
        peer_grids, repeats = (32,), 1

    monkeypatch.setitem(sys.modules, "tamaas", None)             # import tamaas -> ImportError
    monkeypatch.setitem(sys.modules, "ContactMechanics", None)
    assert pi.peer_interior_rows(Cfg()) == {}
    err = capsys.readouterr().err
    assert "tamaas is not installed" in err and "ContactMechanics is not installed" in err
