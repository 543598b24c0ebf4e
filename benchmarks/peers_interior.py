"""Peers below the surface: the Hertz stress field under the exact Hertz pressure, computed by tamaas'
FFT volume operators (a periodic boundary-integral code), and ContactMechanics' closed-form Hertz
reference (Hamilton's Cartesian forms) timed at the same points. Part of the benchmark harness, not
of the package; called by harness.measure with ``--peers``.

tamaas is given the exact pressure p(r) = p0 sqrt(1 - r^2/a^2) and no contact is solved: the rows
measure the elastic interior operator alone, i.e. its discretisation of the surface pressure and its
periodic images. Units: a = R = E* = 1, so p0 = 2/pi and p_m = 4/(3 pi); stresses in units of E*, z
the depth (positive into the solid), as in stressfields.physics.axisymmetric.interior_stress.

tamaas' conventions, measured with single harmonic pressures against the plane-strain solution
(tests/test_peer_interior.py::test_tamaas_conventions_single_harmonic):

- a ``volume_2d`` model of size [Lz, Lx, Ly] and discretisation [Nz, Nx, Ny] holds Nz layers at the
  depths k Lz / (Nz - 1), k = 0 .. Nz - 1 (layer 0 the surface); in-plane node i sits at x = i Lx / Nx;
- the normal traction (component 2 of ``traction``) is the pressure, compressive when positive;
- ``boussinesq_gradient`` maps the surface traction to the strain in the volume and ``hooke`` the
  strain to the stress, both as 6-vectors (xx, yy, zz, xy, xz, yz) with the shears times sqrt(2)
  (Mandel's notation);
- the uniform (wave number 0) part of the pressure, p_mean = pi a^2 p_m / L^2 on a box of side L,
  produces the laterally constrained state sigma_xx = sigma_yy = -nu/(1 - nu) p_mean
  (tests/test_peer_interior.py::test_tamaas_mean_pressure_is_laterally_constrained), where the
  isolated half-space's limit is -(1 + 2 nu)/2 p_mean. The periodic field therefore differs from the
  isolated one by the periodic images plus a uniform in-plane offset of
  ((1 + 2 nu)/2 - nu/(1 - nu)) p_mean = 0.37 p_mean for nu = 0.3: 0.018 p_m for L = 8a, 0.0046 p_m for
  L = 16a (measured on 256^2 grids, median of sigma_xx - exact at z = a/8: 0.017 p_m and 0.0045 p_m,
  falling with depth as the images take over). The rows keep it: it is what a periodic code delivers
  for an isolated contact, and on L = 8a it bounds the error from below (0.019 at 256^2) once the
  grid resolves the pressure's edge (0.030 at 128^2, where the error is still the discretisation's:
  the same at L = 16a and 256^2).
"""
from __future__ import annotations

import statistics
import sys
import time

import numpy as np

CASE = "below the surface, paraboloid, normal: six stresses"
TAMAAS = "tamaas (FFT volume operators, periodic)"
HAMILTON = "ContactMechanics Hertz reference (Hamilton's Cartesian forms)"
COMPONENTS = ("xx", "yy", "zz", "xy", "xz", "yz")
#: tamaas' order of the 6-vector components (the same as ours), and the factor on its shears
TAMAAS_ORDER = COMPONENTS
MANDEL = np.sqrt(2.0)
#: the peer's order of components (ContactMechanics.ReferenceSolutions.Hertz)
HAMILTON_ORDER = ("xx", "yy", "zz", "yz", "xz", "xy")

NU = 0.3                                   # as the harness' own interior case
SIDE = 8.0                                 # periodic box side / a
#: the layers compared, a/8 .. 2a: the same physical depths on every grid, so that the rows measure
#: the in-plane refinement (layers at z ~ dx would see the pressure's edge unresolved on every grid)
DEPTHS = np.arange(1, 17) / 8.0
RADIUS = 2.0                               # points compared: r <= 2a, 0 < z <= 2a
AXIS_RADII = (1e-16, 1e-8, 1e-5)           # ContactMechanics near the axis
P0 = 2.0 / np.pi                           # Hertz, a = R = E* = 1: p0 = 2 a E* / (pi R)
PM = 2.0 * P0 / 3.0                        # mean pressure, the stresses' normalisation scale


def _error(value: dict, exact: dict) -> float:
    """max over the six components of |value - exact| / max(p_m, |exact|)."""
    return float(max(np.max(np.abs(value[k] - exact[k]) / np.maximum(PM, np.abs(exact[k]))) for k in COMPONENTS))


def _uniform_depths(depths) -> tuple[np.ndarray, float]:
    """The depths as an array, checked to be h, 2h, ..., m h: tamaas' layers are uniform from the surface."""
    depths = np.asarray(depths, dtype=float)
    h = float(depths[0]) if depths.size else 0.0
    if h <= 0 or not np.allclose(depths, h * np.arange(1, depths.size + 1), rtol=1e-12, atol=0.0):
        raise ValueError(f"depths must be h, 2h, ..., m h with h > 0 (tamaas' uniform layers), got {depths}")
    return depths, h


def tamaas_volume_stress(pressure, side: float, depths, nu: float) -> dict[str, np.ndarray]:
    """The six stresses {"xx", ...: (m, n, n)} at ``depths`` (h, 2h, ..., m h) below a periodic n x n
    grid of surface pressure (node i at x = i side / n), by tamaas' Boussinesq volume operator. The
    stresses do not depend on E: tamaas' modulus is set to E* = 1."""
    import tamaas as tm

    pressure = np.asarray(pressure, dtype=float)
    n = pressure.shape[0]
    depths, h = _uniform_depths(depths)
    layers = depths.size + 1                                    # layer 0 is the surface
    model = tm.ModelFactory.createModel(tm.model_type.volume_2d, [h * (layers - 1), side, side], [layers, n, n])
    model.E, model.nu = 1.0 - nu ** 2, nu                       # E* = E / (1 - nu^2) = 1
    tm.ModelFactory.registerVolumeOperators(model)
    traction = np.zeros((n, n, 3))
    traction[..., 2] = pressure
    strain = np.zeros((layers, n, n, 6))
    model.operators["boussinesq_gradient"](traction, strain)
    stress = np.zeros_like(strain)
    model.operators["hooke"](strain, stress)
    return {k: stress[1:, ..., i] / (MANDEL if i >= 3 else 1.0) for i, k in enumerate(TAMAAS_ORDER)}


def _grid(n: int, side: float) -> np.ndarray:
    """In-plane node coordinates / a, the contact centred on node n // 2 (so the axis is sampled)."""
    return (np.arange(n) - n // 2) * (side / n)


def tamaas_hertz_interior(n_grid: int, depths=DEPTHS, *, nu: float = NU, side: float = SIDE):
    """tamaas' Hertz stresses below the surface on an n_grid x n_grid periodic box of side ``side`` a,
    under the exact pressure p0 sqrt(1 - r^2/a^2) (a = R = E* = 1, p0 = 2/pi), at ``depths`` (h, 2h, ...).

    Returns (seconds, stresses, (x, y, z)): the wall time of tamaas' work (model, operators, the two
    operator applications), the six stresses / E* {"xx", ...: (m, n, n)}, and the coordinates / a
    shaped (1, n, 1), (1, 1, n), (m, 1, 1) so that they broadcast onto the stresses."""
    xs = _grid(n_grid, side)
    depths, _h = _uniform_depths(depths)
    r2 = xs[:, None] ** 2 + xs[None, :] ** 2
    pressure = P0 * np.sqrt(np.clip(1.0 - r2, 0.0, None))
    start = time.perf_counter()
    stresses = tamaas_volume_stress(pressure, side, depths, nu)
    seconds = time.perf_counter() - start
    return seconds, stresses, (xs[None, :, None], xs[None, None, :], depths[:, None, None])


def _exact(x, y, z, nu: float) -> dict[str, np.ndarray]:
    from stressfields.physics import axisymmetric as ax

    return ax.interior_stress(x, y, z, 1.0, nu, ax.paraboloid(1.0))


def _compared_points(coords):
    """(x, y, z) flattened onto the grid points with r <= 2a (all layers are 0 < z <= 2a)."""
    x, y, z = np.broadcast_arrays(*coords)
    keep = np.hypot(x, y) <= RADIUS
    return x[keep], y[keep], z[keep], keep


def tamaas_rows(grids=(32, 64, 128), depths=DEPTHS, *, nu: float = NU, side: float = SIDE,
                repeats: int = 3) -> dict:
    """{CASE: {(TAMAAS, n): (seconds per point, error)}} on n x n grids.

    Error: max over the six stresses and the grid points with r <= 2a, 0 < z <= 2a of
    |value - exact| / max(p_m, |exact|), exact our closed-form Hertz interior field
    (stressfields.physics.axisymmetric.interior_stress, paraboloid). Time per point: the median
    wall time of ``repeats`` runs (after a warm-up run) over the n^2 m grid points below the surface
    that tamaas evaluates (m = len(depths))."""
    rows = {}
    tamaas_hertz_interior(16, depths[:2], nu=nu, side=side)      # warm-up: imports, FFT plans
    for n in grids:
        seconds, stresses, coords = tamaas_hertz_interior(n, depths, nu=nu, side=side)
        if repeats > 1:
            seconds = statistics.median(tamaas_hertz_interior(n, depths, nu=nu, side=side)[0]
                                        for _ in range(repeats))
        x, y, z, keep = _compared_points(coords)
        err = _error({k: v[keep] for k, v in stresses.items()}, _exact(x, y, z, nu))
        rows[(TAMAAS, float(n))] = (seconds / stresses["xx"].size, err)
    return {CASE: rows}


def _hamilton(x, y, z, nu: float) -> dict[str, np.ndarray]:
    """ContactMechanics' Hertz stresses / E* (the peer returns them / p0)."""
    from ContactMechanics.ReferenceSolutions import Hertz

    with np.errstate(all="ignore"):         # its Cartesian forms divide by r^2 and r^4
        return {k: P0 * v for k, v in zip(HAMILTON_ORDER, Hertz.stress_Cartesian(x, y, z, poisson=nu))}


def _timed(fn, repeats: int):
    """(median wall seconds of ``repeats`` runs after a warm-up, the result)."""
    out = fn()
    times = []
    for _ in range(max(1, repeats)):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times), out


def hamilton_rows(n_grid: int = 128, depths=DEPTHS, *, nu: float = NU, side: float = SIDE,
                  repeats: int = 3) -> dict:
    """ContactMechanics' closed-form Hertz field (Hamilton's Cartesian forms) against ours.

    CASE, order 0: timed at the grid points of the n_grid x n_grid tamaas case (r <= 2a, 0 < z <= 2a,
    the axis r = 0 included, which the peer special-cases). One case per radius r of AXIS_RADII
    (points r (cos phi, sin phi) at 32 angles, at the same depths), order 0: its error beside the
    axis, where its forms cancel. Error as in :func:`tamaas_rows`."""
    depths, _h = _uniform_depths(depths)
    xs = _grid(n_grid, side)
    x, y, z, _keep = _compared_points((xs[None, :, None], xs[None, None, :], depths[:, None, None]))
    seconds, theirs = _timed(lambda: _hamilton(x, y, z, nu), repeats)
    out = {CASE: {(HAMILTON, 0.0): (seconds / x.size, _error(theirs, _exact(x, y, z, nu)))}}
    phi = np.linspace(0.0, 2.0 * np.pi, 32, endpoint=False)
    for r in AXIS_RADII:
        x, y, z = (v.ravel() for v in np.broadcast_arrays(r * np.cos(phi)[None, :], r * np.sin(phi)[None, :],
                                                          depths[:, None]))
        seconds, theirs = _timed(lambda x=x, y=y, z=z: _hamilton(x, y, z, nu), repeats)
        out[axis_case(r)] = {(HAMILTON, 0.0): (seconds / x.size, _error(theirs, _exact(x, y, z, nu)))}
    return out


def axis_case(r: float) -> str:
    return f"below the surface near the axis (r = {r:g} a), paraboloid, normal: six stresses"


def _available(module: str, note: str) -> bool:
    try:
        __import__(module)
    except ImportError as exc:
        print(f"bench: {note} skipped, {module} is not installed ({exc})", file=sys.stderr)
        return False
    return True


def peer_interior_rows(cfg) -> dict:
    """{case: {(method, order): (seconds per point, error)}} of the peers below the surface, for
    harness.measure with --peers; each peer is skipped with a note when it is not installed.

    tamaas grids: 32, 64, 128 up to a quarter of the largest surface-peer grid (FULL: all three,
    QUICK: 32 and 64, TINY: 32); ContactMechanics at the points of the largest of them."""
    grids = tuple(n for n in (32, 64, 128) if n <= max(32, max(cfg.peer_grids) // 4))
    out: dict = {}
    if _available("tamaas", "tamaas (volume operators below the surface)"):
        for case, rows in tamaas_rows(grids, repeats=cfg.repeats).items():
            out.setdefault(case, {}).update(rows)
            for (_m, n), (sec, err) in rows.items():
                print(f"bench: tamaas below the surface, {n:.0f}^2 x {DEPTHS.size} layers: "
                      f"{sec:.2g} s per point, max error {err:.2g}", file=sys.stderr)
    if _available("ContactMechanics", "ContactMechanics' Hertz reference below the surface"):
        for case, rows in hamilton_rows(grids[-1], repeats=cfg.repeats).items():
            out.setdefault(case, {}).update(rows)
    return out
