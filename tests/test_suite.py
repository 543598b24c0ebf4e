"""The reference suite: the release gate (regenerated datasets reproduce the registered hashes), build
and verify from the command line, and the FE benchmark datasets' key values against the closed forms
of Hertz's theory and the numbers their own documents print (suite/README.md cites them)."""
import csv
import json
import math
import subprocess
import sys
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import xarray as xr
from scipy.optimize import minimize_scalar

from stressfields import suite
from stressfields.output.formats import format_for
from stressfields.output.hashing import values_hash

#: building the suite's datasets takes seconds per worker: CI runs these with the slow tests
pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[1]
REGISTRY = suite.registry()


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    out = tmp_path_factory.mktemp("suite") / "out"
    problems = suite.build(out, say=lambda line: None)
    return out, problems


def _cli(capsys, *args):
    """`stressfields suite ARGS` in this process (the command line's own entry point, without a
    second interpreter's imports): (exit code, stdout, stderr)."""
    from stressfields.cli import main

    capsys.readouterr()
    code = main(["suite", *map(str, args)])
    out, err = capsys.readouterr()
    return code, out, err


def open_(built, name):
    return xr.open_dataset(built[0] / f"{name}.nc")


# -- the release gate --------------------------------------------------------------------------------

def test_release_gate_values_hashes_reproduce(built):
    """Every gate dataset, regenerated, has its registered values hash: a value that changes needs a
    new suite_version (and the registry rewritten by suite.register)."""
    gate = [n for n, e in REGISTRY["datasets"].items() if e["gate"]]
    assert len(gate) >= 10
    for name in gate:
        with format_for(built[0] / f"{name}.nc").read(built[0] / f"{name}.nc", raw=True) as ds:
            assert values_hash(ds) == REGISTRY["datasets"][name]["values_sha256"], name


def test_suite_version_has_its_changelog_entry():
    text = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    assert f"reference suite {REGISTRY['suite_version']}" in text


def test_registry_lists_every_recipe_and_the_catalog_every_dataset():
    import yaml

    recipes = {p.stem for p in (ROOT / "suite" / "recipes").glob("*.toml")}
    assert recipes == set(REGISTRY["datasets"])
    catalog = yaml.safe_load((ROOT / "suite" / "catalog.yaml").read_text())
    assert set(catalog["sources"]) == recipes
    for name, source in catalog["sources"].items():
        assert source["driver"] == "netcdf" and source["args"]["xarray_kwargs"]["engine"] == "netcdf4"
        assert source["metadata"]["values_sha256"] == REGISTRY["datasets"][name]["values_sha256"]
        assert source["args"]["urlpath"] == "{{ CATALOG_DIR }}/" + f"{name}.nc"


# -- build and verify --------------------------------------------------------------------------------

def test_build_matches_the_registry_and_verify_passes(built, capsys):
    out, problems = built
    assert problems == []
    code, stdout, stderr = _cli(capsys, "verify", out)
    assert code == 0, stderr
    assert stdout.strip() == "verify: ok"


def test_build_resumes_keeping_verified_files(built):
    out = built[0]
    stamp = {p.name: p.stat().st_mtime_ns for p in out.glob("*.nc")}
    said = []
    assert suite.build(out, say=said.append) == []
    assert sum(line.endswith("kept") for line in said) == len(REGISTRY["datasets"])
    assert {p.name: p.stat().st_mtime_ns for p in out.glob("*.nc")} == stamp


def test_verify_finds_a_changed_value_and_a_missing_file_and_build_repairs(built, tmp_path, capsys):
    import shutil

    out = tmp_path / "copy"
    shutil.copytree(built[0], out)
    with netCDF4.Dataset(out / "ssnv104_points.nc", "a") as nc:
        nc["sigma_zz"][3] = nc["sigma_zz"][3] * (1 + 1e-15) + 1.0
    (out / "graded_stick_radius.nc").unlink()
    code, _, stderr = _cli(capsys, "verify", out)
    assert code == 1
    bad = [line for line in stderr.splitlines() if line.startswith("MISMATCH")]
    assert len(bad) == 2 and "ssnv104_points: " in bad[1] + bad[0] and "graded_stick_radius: missing" in stderr
    said = []
    assert suite.build(out, say=said.append) == []
    rebuilt = sorted(line.split(":")[0].split()[-1] for line in said if "built" in line)
    assert rebuilt == ["graded_stick_radius", "ssnv104_points"]
    assert suite.verify(out, say=lambda line: None) == []


def test_verify_of_a_missing_directory_is_one_line_exit_2(tmp_path):
    done = subprocess.run([sys.executable, "-m", "stressfields", "suite", "verify", str(tmp_path / "nowhere")],
                          cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert done.returncode == 2
    assert len(done.stderr.strip().splitlines()) == 1 and "nowhere" in done.stderr


def test_key_values_csv_is_in_the_directory_and_the_readme(built):
    rows = list(csv.DictReader((built[0] / "key_values.csv").open()))
    assert {r["dataset"] for r in rows} == set(REGISTRY["datasets"])
    readme = (ROOT / "suite" / "README.md").read_text(encoding="utf-8")
    for r in rows:
        line = "| " + " | ".join(r[k] or "-" for k in suite.KEY_COLUMNS) + " |"
        assert line in readme, line


# -- the FE benchmarks against Hertz's closed forms, computed here -------------------------------------

def hertz_axis(nu):
    """sigma_r/p0 and sigma_z/p0 on the axis below a Hertz contact (Johnson, Contact Mechanics, eq. 3.45),
    zeta = z/a; and the depth and value of the largest (sigma_r - sigma_z)/2 found by a 1-D search."""
    def sig(zeta):
        s_r = -(1 + nu) * (1 - zeta * math.atan(1 / zeta)) + 0.5 / (1 + zeta ** 2)
        return s_r, -1 / (1 + zeta ** 2)
    res = minimize_scalar(lambda t: -0.5 * (sig(t)[0] - sig(t)[1]), bounds=(0.05, 2), method="bounded",
                          options={"xatol": 1e-12})
    return sig, res.x, -res.fun


def two_sphere_reduction(E1, nu, R1, F=None, h=None):
    """Two identical spheres: 1/E* = 2 (1 - nu^2)/E1, 1/R = 2/R1; a from the force or the approach h."""
    e_star, r = E1 / (2 * (1 - nu ** 2)), R1 / 2
    a = (3 * F * r / (4 * e_star)) ** (1 / 3) if F is not None else math.sqrt(r * h)
    F = F if F is not None else 4 * e_star * a ** 3 / (3 * r)
    return a, 3 * F / (2 * math.pi * a ** 2), F, e_star, r


def test_moose_hertz_key_values(built):
    """MOOSE hertz_spherical: R1 = R2 = 2, E1 = 1.40625e7, nu = 0.25, F = 1e4; the test file states
    E = 7.5e6, a = 0.1, d = 0.01."""
    a, p0, _, e_star, r = two_sphere_reduction(1.40625e7, 0.25, 2.0, F=1e4)
    assert (e_star, r) == pytest.approx((7.5e6, 1.0), rel=1e-15)
    assert a == pytest.approx(0.1, rel=1e-14)
    grid, pts = open_(built, "moose_hertz_grid"), open_(built, "moose_hertz_points")
    assert float(grid.contact_radius) == pytest.approx(a, rel=1e-13)
    assert float(grid.delta) == pytest.approx(a ** 2 / r, rel=1e-13) and round(float(grid.delta), 10) == 0.01
    assert float(grid.mean_pressure) == pytest.approx(2 * p0 / 3, rel=1e-13)
    sig, depth, peak = hertz_axis(0.25)
    assert float(grid.tau_max_peak) == pytest.approx(peak * p0, rel=1e-9)
    assert float(grid.tau_max_peak_depth) == pytest.approx(depth * a, rel=1e-6)
    assert float(grid.von_mises_peak_depth) == pytest.approx(depth * a, rel=1e-6)   # sigma_r = sigma_theta there
    on_axis = (pts.x == 0).values
    for z, s_xx, s_zz in zip(pts.z.values[on_axis], pts.sigma_xx.values[on_axis], pts.sigma_zz.values[on_axis]):
        s_r, s_z = sig(z / a) if z > 0 else (-(1 + 2 * 0.25) / 2, -1.0)
        assert (s_xx / p0, s_zz / p0) == pytest.approx((s_r, s_z), rel=1e-12, abs=1e-15)
    surface = (pts.z == 0).values
    x = pts.x.values[surface]
    expect = np.where(x < a, -p0 * np.sqrt(np.clip(1 - (x / a) ** 2, 0, None)), 0.0)
    # atol: at r = a the pressure is the square root of a rounding error (~1.5e-8 p0)
    np.testing.assert_allclose(pts.sigma_zz.values[surface], expect, rtol=1e-12, atol=1e-7 * p0)


def test_ssnv104_key_values(built):
    """SSNV104: E = 20000 MPa, nu = 0.3, approach h = 4 mm; the document: a = 10 mm, P0 = 2798.3 MPa."""
    E1, nu, h, a_doc = 20000e6, 0.3, 4e-3, 10e-3
    R1 = 2 * a_doc ** 2 / h                                   # the document's a = sqrt(R h/2)
    assert R1 == pytest.approx(0.05)
    a, p0, F, _, _ = two_sphere_reduction(E1, nu, R1, h=h)
    p0_doc = E1 / (math.pi * (1 - nu ** 2)) * math.sqrt(2 * h / R1)   # the document's eq. 2.1-1
    assert p0 == pytest.approx(p0_doc, rel=1e-14) and round(p0_doc / 1e6, 1) == 2798.3
    grid, pts = open_(built, "ssnv104_grid"), open_(built, "ssnv104_points")
    assert float(grid.contact_radius) == pytest.approx(a_doc, rel=1e-13)
    assert float(grid.normal_force) == pytest.approx(F, rel=1e-13)
    centre = int(np.flatnonzero((pts.x.values == 0) & (pts.z.values == 0))[0])
    assert -float(pts.sigma_zz[centre]) == pytest.approx(p0_doc, rel=1e-13)
    assert round(-float(pts.sigma_zz[centre]) / 1e6, 1) == 2798.3
    assert round(float(grid.tau_max_peak) / p0, 2) == 0.31 and round(float(grid.tau_max_peak_depth) / a, 2) == 0.48
    _, depth, peak = hertz_axis(nu)
    assert float(grid.tau_max_peak) == pytest.approx(peak * p0, rel=1e-9)
    assert float(grid.von_mises_peak_depth) == pytest.approx(depth * a, rel=1e-6)


def test_cofea_block_key_values(built):
    """tau_max = 0.31 p0 at 0.48 a (nu = 0.3), and the largest von Mises stress at the same depth
    (on the axis sigma_r = sigma_theta, so von Mises = |sigma_r - sigma_z| = 2 tau_max)."""
    ds = open_(built, "cofea_hertz_block")
    p0 = 1.5                                                  # p0 = 3/2 p_m, stresses over p_m
    _, depth, peak = hertz_axis(0.3)
    assert float(ds.tau_max_peak) / p0 == pytest.approx(peak, rel=1e-9)
    assert (round(float(ds.tau_max_peak) / p0, 2), round(float(ds.tau_max_peak_depth), 2)) == (0.31, 0.48)
    assert float(ds.von_mises_peak) == pytest.approx(2 * peak * p0, rel=1e-9)
    assert float(ds.von_mises_peak_depth) == pytest.approx(depth, rel=1e-6)
    assert float(ds.tau_max_peak_r) == 0 and float(ds.von_mises_peak_r) == 0
    pts = open_(built, "cofea_hertz_block_points")          # the axis nodes against Johnson's eq. 3.45
    sig = hertz_axis(0.3)[0]
    axis = (pts.x.values == 0) & (pts.z.values > 0)
    assert axis.sum() == 6
    for z, s_xx, s_zz, tau in zip(*(pts[v].values[axis] for v in ("z", "sigma_xx", "sigma_zz", "tau_max"))):
        s_r, s_z = sig(z)
        assert (s_xx / p0, s_zz / p0, tau / p0) == pytest.approx((s_r, s_z, (s_r - s_z) / 2), rel=1e-12)
    # the grid's own maximum is no larger than the peak, and close to it on this 0.05 a grid
    assert float(ds.tau_max.max()) <= float(ds.tau_max_peak) * (1 + 1e-12)
    assert float(ds.tau_max.max()) == pytest.approx(float(ds.tau_max_peak), rel=2e-3)


def test_abaqus_cylinders_tend_to_the_hertz_line_contact(built):
    """Two cylinders R = 254 mm, E = 206 GPa, nu = 0.3: E* = E/(2(1 - nu^2)), R_eff = R/2; Hertz line
    contact of half-width b: p0 = E* b/(2 R_eff), load per length P = pi E* b^2/(4 R_eff). The cosine
    indenter departs from it at order (pi b/lambda_1)^2: the relative differences, divided by that,
    stay bounded and alike across b (second-order convergence to the Hertz limit)."""
    ds = open_(built, "abaqus_cylinders_line")
    e_star, r_eff, lam = 206e9 / (2 * (1 - 0.3 ** 2)), 0.254 / 2, float(ds.lambda_1)
    assert float(ds.amplitudes[0]) == pytest.approx(lam ** 2 / (4 * math.pi ** 2 * r_eff), rel=1e-15)
    scaled = []
    for a in ds.a.values:
        b = a * lam / 2
        p0, load = e_star * b / (2 * r_eff), math.pi * e_star * b ** 2 / (4 * r_eff)
        order = (math.pi * b / lam) ** 2
        d_p0 = abs(float(ds.peak_pressure.sel(a=a)) / p0 - 1)
        d_load = abs(float(ds.mean_pressure.sel(a=a)) * lam / load - 1)
        assert d_p0 < order and d_load < order, (a, d_p0, d_load, order)
        scaled.append((d_p0 / order, d_load / order))
        x = ds.x.values
        inside = np.abs(x) < b * (1 - 1e-9)
        hertz = p0 * np.sqrt(np.clip(1 - (x / b) ** 2, 0, None))
        np.testing.assert_allclose(ds.pressure.sel(a=a).values[inside], hertz[inside], rtol=0, atol=order * p0)
        assert np.all(ds.pressure.sel(a=a).values[np.abs(x) > b * (1 + 1e-9)] == 0)
    scaled = np.array(scaled)
    assert np.ptp(scaled, axis=0).max() < 0.05 * scaled.max() + 1e-3
    pts = open_(built, "abaqus_cylinders_line_points")
    b = pts.a.values * lam / 2
    p0 = e_star * b / (2 * r_eff)
    hertz = p0 * np.sqrt(np.clip(1 - (pts.x.values / b) ** 2, 0, None))
    np.testing.assert_allclose(pts.pressure.values, hertz, rtol=0, atol=(math.pi * b.max() / lam) ** 2 * p0.max())
    assert np.all(pts.pressure.values[pts.x.values > b] == 0)


def test_registry_json_is_what_build_copies(built):
    assert json.loads((built[0] / "registry.json").read_text()) == REGISTRY
