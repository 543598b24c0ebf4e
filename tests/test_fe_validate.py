"""`stressfields compare` on an FE model's raw output (stressfields/fe/): the same nodes and values
written as the solver writes them (an Abaqus-style CSV, Exodus II with 3 time steps, a 2-D
axisymmetric VTU in mm/MPa with z up and cylindrical names) give the statistics of the hand-converted
CSV to 1e-12; a mesh sequence's observed order matches the order computed here from the planted
errors; edge exclusion; hostile node files.

Each route is checked against another route to the same numbers (the hand conversion, or errors
planted on Hertz's closed-form surface pressure), never against a value the comparison computed alone.
"""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from stressfields.cli import main

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "fe_hertz_mindlin"
RECIPE, NODES = EXAMPLE / "recipe.toml", EXAMPLE / "nodes.csv"
STATS = ("max_abs_difference_over_scale", "rms_difference_over_scale", "p50_abs_difference_over_scale",
         "p95_abs_difference_over_scale", "p99_abs_difference_over_scale", "relative_l2", "worst_point")
#: Hertz under normal load only, physical units (a = sqrt(R delta) = 0.1 mm)
NORMAL = 'scenario = "parabolic"\n[parameters]\nE = 210e9\nnu = 0.3\nR = 0.01\ndelta = 1e-6\n'


def run(tmp_path, name, *args):
    out = tmp_path / name
    code = main(["compare", *map(str, args), "-o", str(out), "--no-plot"])
    return code, out


def report(out: Path) -> dict:
    return json.loads((out / "report.json").read_text())


def same_statistics(a: dict, b: dict, names) -> None:
    for name in names:
        for key in STATS:
            x, y = a["variables"][name][key], b["variables"][name][key]
            assert x == pytest.approx(y, rel=1e-12, abs=1e-300), (name, key, x, y)


def example_table():
    lines = NODES.read_text().splitlines()
    return lines[0].split(","), np.array([[float(v) for v in line.split(",")] for line in lines[1:]])


def test_abaqus_style_csv_is_the_hand_converted_one(tmp_path):
    header, table = example_table()
    abaqus = ["Node Label", "X(mm)", "Y (mm)", "Z[mm]", "S-S11 (N/mm^2)", "S22 [N/mm2]", "S-S33 (MPa)", "S13 [N/mm²]"]
    (tmp_path / "abaqus.csv").write_text(", ".join(abaqus) + "\n" + "\n".join(
        ", ".join(repr(float(v)) for v in row) for row in table) + "\n")
    assert run(tmp_path, "hand", RECIPE, NODES)[0] == 0
    assert run(tmp_path, "abaqus", RECIPE, tmp_path / "abaqus.csv")[0] == 0
    a, b = report(tmp_path / "hand")["tables"][0], report(tmp_path / "abaqus")["tables"][0]
    same_statistics(a, b, ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz"))
    assert b["variables"]["sigma_xx"]["worst_node"] == 1138       # the planted error's node (make_nodes.py)


def _exodus(path: Path, xyz_up: np.ndarray, names: list[str], steps: list[np.ndarray]) -> Path:
    """An Exodus II file as netCDF4 writes one: coordx/y/z, name_nod_var, vals_nod_var{i}, time_whole."""
    import netCDF4

    with netCDF4.Dataset(path, "w", format="NETCDF3_64BIT_OFFSET") as ds:
        n = xyz_up.shape[0]
        ds.createDimension("len_string", 33)
        ds.createDimension("num_dim", 3)
        ds.createDimension("num_nodes", n)
        ds.createDimension("time_step", None)
        ds.createDimension("num_nod_var", len(names))
        for k, a in enumerate("xyz"):
            ds.createVariable(f"coord{a}", "f8", ("num_nodes",))[:] = xyz_up[:, k]
        ds.createVariable("time_whole", "f8", ("time_step",))[:] = np.arange(1.0, len(steps) + 1)
        var = ds.createVariable("name_nod_var", "S1", ("num_nod_var", "len_string"))
        var[:] = netCDF4.stringtochar(np.array(names, dtype="S33"))
        for i in range(len(names)):
            v = ds.createVariable(f"vals_nod_var{i + 1}", "f8", ("time_step", "num_nodes"))
            for s, values in enumerate(steps):
                v[s, :] = values[:, i]
    return path


def test_exodus_three_steps_z_up_is_the_hand_converted_csv(tmp_path):
    header, table = example_table()
    xyz = table[:, 1:4] * np.array([1.0, 1.0, -1.0])            # z up: the body at z <= 0
    values = table[:, 4:].copy()
    values[:, 3] *= -1                                          # sigma_xz changes sign with z
    steps = [values, values * 1.01, values]
    exo = _exodus(tmp_path / "model.e", xyz, ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz"], steps)
    scaled = table.copy()
    scaled[:, 4:] *= 1.01
    hand2 = tmp_path / "step2.csv"
    hand2.write_text(",".join(header) + "\n" + "\n".join(",".join(repr(float(v)) for v in r) for r in scaled) + "\n")
    code, out = run(tmp_path, "exo", RECIPE, exo, "--z-up", "--units", "length=mm,stress=MPa")
    assert code == 0
    tables = report(out)["tables"]
    assert len(tables) == 3 and [t["file"] for t in tables] == ["comparison_1.nc", "comparison_2.nc", "comparison_3.nc"]
    run(tmp_path, "hand", RECIPE, NODES)
    run(tmp_path, "hand2", RECIPE, hand2)
    names = ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz")
    same_statistics(report(tmp_path / "hand")["tables"][0], tables[0], names)
    same_statistics(report(tmp_path / "hand2")["tables"][0], tables[1], names)
    same_statistics(report(tmp_path / "hand")["tables"][0], tables[2], names)
    code, out = run(tmp_path, "step2", RECIPE, exo, "--z-up", "--units", "length=mm,stress=MPa", "--step", "2")
    assert len(report(out)["tables"]) == 1
    same_statistics(report(tmp_path / "hand2")["tables"][0], report(out)["tables"][0], names)


def test_axisymmetric_vtu_in_mm_mpa_z_up_is_the_hand_converted_csv(tmp_path):
    meshio = pytest.importorskip("meshio")
    r, zu = np.meshgrid(np.linspace(0.0, 0.3, 9), np.linspace(-0.3, 0.0, 7))      # mm, z up
    pts = np.column_stack([r.ravel(), zu.ravel(), np.zeros(r.size)])     # VTU stores 3 coordinates
    idx = np.arange(pts.shape[0]).reshape(r.shape)
    tri = np.concatenate([np.column_stack([idx[:-1, :-1].ravel(), idx[:-1, 1:].ravel(), idx[1:, 1:].ravel()]),
                          np.column_stack([idx[:-1, :-1].ravel(), idx[1:, 1:].ravel(), idx[1:, :-1].ravel()])])
    rng = np.random.default_rng(7)
    data = {k: rng.normal(-500.0, 300.0, pts.shape[0]) for k in ("sigma_rr", "sigma_thetatheta", "sigma_zz",
                                                                  "sigma_rz")}
    data["u_r"], data["u_z"] = rng.normal(0, 1e-4, pts.shape[0]), rng.normal(-5e-4, 1e-4, pts.shape[0])   # mm
    meshio.write(tmp_path / "axi.vtu", meshio.Mesh(pts, [("triangle", tri)], point_data=data))
    hand = np.column_stack([pts[:, 0], np.zeros(len(pts)), -pts[:, 1], data["sigma_rr"], data["sigma_thetatheta"],
                            data["sigma_zz"], -data["sigma_rz"], data["u_r"], -data["u_z"]])
    (tmp_path / "hand.csv").write_text(
        "x[mm],y[mm],z[mm],sigma_xx[MPa],sigma_yy[MPa],sigma_zz[MPa],sigma_xz[MPa],u_x[mm],u_z[mm]\n"
        + "\n".join(",".join(repr(float(v)) for v in row) for row in hand) + "\n")
    (tmp_path / "normal.toml").write_text(NORMAL)
    run(tmp_path, "hand", tmp_path / "normal.toml", tmp_path / "hand.csv")
    code, out = run(tmp_path, "vtu", tmp_path / "normal.toml", tmp_path / "axi.vtu", "--axisymmetric", "--z-up",
                    "--units", "length=mm,stress=MPa")
    assert code == 0
    a, b = report(tmp_path / "hand")["tables"][0], report(out)["tables"][0]
    same_statistics(a, b, ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz", "u_x", "u_z"))
    assert b["variables"]["sigma_rr"]["label"] == "sigma_rr" if "sigma_rr" in b["variables"] else True


def _surface_csv(path: Path, r: np.ndarray, sigma_zz: np.ndarray) -> Path:
    path.write_text("r,z,sigma_zz\n" + "\n".join(f"{float(a)!r},0.0,{float(b)!r}" for a, b in zip(r, sigma_zz)) + "\n")
    return path


def hertz_surface_szz(r):
    """Hertz's surface pressure p = p0 sqrt(1 - r^2/a^2) with p0 = (3/2) p_m (the classical closed form):
    sigma_zz / p_m = -p / p_m inside the contact, 0 outside (r, a = 1: normalised)."""
    return -1.5 * np.sqrt(np.clip(1.0 - r * r, 0.0, None))


def test_three_mesh_sequence_reports_the_planted_order(tmp_path):
    (tmp_path / "normal.toml").write_text('scenario = "parabolic"\n[parameters]\nnu = 0.3\n')
    files, rms = [], []
    for n in (20, 40, 80):
        r = np.linspace(0.0, 0.9, n)
        error = 0.3 * n ** -1.5 * np.sin(3.0 * r + 0.2)         # O(h^1.5), h = 1/N (nodes along a line)
        rms.append(math.sqrt(np.mean(error ** 2)))
        files.append(_surface_csv(tmp_path / f"L{n}.csv", r, hertz_surface_szz(r) + error))
    code, out = run(tmp_path, "conv", tmp_path / "normal.toml", *files, "--axisymmetric")
    assert code == 0
    conv = report(out)["convergence"]
    h = [1 / 20, 1 / 40, 1 / 80]
    assert conv["h"] == pytest.approx(h, rel=1e-12)
    row = conv["variables"]["sigma_zz"]["rms"]
    assert row["errors"] == pytest.approx(rms, rel=1e-6)      # Hertz's closed form against the kernel: ~1e-10
    by_hand = [math.log(rms[i] / rms[i + 1]) / math.log(h[i] / h[i + 1]) for i in range(2)]
    assert row["orders"] == pytest.approx(by_hand, abs=1e-4)
    assert row["fitted_order"] == pytest.approx(np.polyfit(np.log(h), np.log(rms), 1)[0], abs=1e-4)
    assert abs(row["richardson_remainder"]) < 0.05 * rms[-1]    # nothing left as h -> 0 but rounding


def test_edge_exclusion_passes_a_converged_mesh_and_reports_the_ring(tmp_path):
    (tmp_path / "normal.toml").write_text('scenario = "parabolic"\n[parameters]\nnu = 0.3\n')
    r = np.linspace(0.0, 1.3, 131)
    ring = np.abs(r - 1.0) <= 0.055
    error = np.where(ring, 0.02, 2e-4)              # the edge's singular gradient: the worst nodes there
    path = _surface_csv(tmp_path / "mesh.csv", r, hertz_surface_szz(r) + error)
    code, out = run(tmp_path, "plain", tmp_path / "normal.toml", path, "--axisymmetric", "--tolerance", "1e-3")
    assert code == 1
    code, out = run(tmp_path, "edge", tmp_path / "normal.toml", path, "--axisymmetric", "--tolerance", "1e-3",
                    "--exclude-edge", "0.055")
    assert code == 0
    v = report(out)["tables"][0]["variables"]["sigma_zz"]
    assert v["result"] == "PASS" and v["max_abs_difference_over_scale"] == pytest.approx(2e-4, rel=1e-6)
    assert v["edge_compared_points"] == int(ring.sum()) and v["compared_points"] == int((~ring).sum())
    assert v["edge_max_abs_difference_over_scale"] == pytest.approx(0.02, rel=1e-6)
    assert "edge ring" in (out / "report.md").read_text()


def test_rms_tolerance_and_sign_hint(tmp_path, capsys):
    (tmp_path / "normal.toml").write_text('scenario = "parabolic"\n[parameters]\nnu = 0.3\n')
    r = np.linspace(0.05, 0.9, 30)
    path = _surface_csv(tmp_path / "flip.csv", r, -hertz_surface_szz(r))       # the opposite sign convention
    code, out = run(tmp_path, "flip", tmp_path / "normal.toml", path, "--axisymmetric", "--tolerance", "rms=1e-3")
    assert code == 1
    v = report(out)["tables"][0]["variables"]["sigma_zz"]
    assert "sign-convention" in v["note"] and v["result"].startswith("FAIL: rms")


def test_second_body_is_the_mirror_image(tmp_path):
    """Normal load: body 2's field at (x, y, -h) is the reflection of body 1's at (x, y, h), so the
    reflected nodes with reflected values (sigma_xz, sigma_yz, u_z negated) compare alike."""
    header, table = example_table()
    (tmp_path / "normal.toml").write_text(NORMAL)
    keep = [0, 1, 2, 3, 4, 5, 6, 7]
    (tmp_path / "b1.csv").write_text(",".join(header[k] for k in keep) + "\n" + "\n".join(
        ",".join(repr(float(row[k])) for k in keep) for row in table) + "\n")
    mirror = table.copy()
    mirror[:, 3] *= -1
    mirror[:, 7] *= -1
    (tmp_path / "b2.csv").write_text(",".join(header[k] for k in keep) + "\n" + "\n".join(
        ",".join(repr(float(row[k])) for k in keep) for row in mirror) + "\n")
    run(tmp_path, "one", tmp_path / "normal.toml", tmp_path / "b1.csv")
    run(tmp_path, "two", tmp_path / "normal.toml", tmp_path / "b2.csv", "--body", "2")
    same_statistics(report(tmp_path / "one")["tables"][0], report(tmp_path / "two")["tables"][0],
                    ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz"))


def _vtu_2d(path: Path) -> Path:
    import meshio

    pts = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0]])     # z = 0 everywhere: a 2-D mesh
    meshio.write(path, meshio.Mesh(pts, [("triangle", np.array([[0, 1, 2]]))],
                                   point_data={"sigma_zz": np.array([1.0, 2.0, 3.0])}))
    return path


GOOD = "x[mm],y[mm],z[mm],sigma_xx[MPa]\n0.01,0.02,0.0,-900\n0.03,0.0,0.05,-700\n"


@pytest.mark.parametrize("make, extra, words", [
    (lambda p: (p / "u.csv", GOOD.replace("sigma_xx[MPa]", "sigma_xx[um]")), [], ["unit 'um' is not stress"]),
    (lambda p: (p / "m.csv", "x[mm],y[mm],z[mm]\n0.01,0.02,0.0\n"), [], ["no value column"]),
    (lambda p: (p / "n.csv", GOOD.replace("-700", "NaN")), [], ["data row 1 (from 0)", "'sigma_xx[MPa]'"]),
    (lambda p: (p / "f.csv", "x[mm],y[mm],z[mm],sigma_xx[MPa],sigma_rr[MPa]\n0.01,0.0,0.0,1,1\n"), [],
     ["mixed frames"]),
    (lambda p: (p / "z.csv", GOOD), ["--z-up"], ["column 'z[mm]'", "with --z-up the body lies at z <= 0"]),
    (lambda p: (p / "bin.foo", b"\x00\x01binary"), [], ["unknown format"]),
    (lambda p: (p / "x.csv", '<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid"/>\n'), [],
     ["an XML file with the suffix '.csv'"]),
])
def test_hostile_node_files_exit_2_in_one_line(tmp_path, capsys, make, extra, words):
    path, content = make(tmp_path)
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content)
    code, out = run(tmp_path, "report", RECIPE, path, *extra)
    err = capsys.readouterr().err.strip()
    assert code == 2 and len(err.splitlines()) == 1 and err.startswith("error:"), err
    for w in words:
        assert w in err, (w, err)
    assert not out.exists()                                     # nothing written


def test_hostile_meshes_exit_2_in_one_line(tmp_path, capsys):
    pytest.importorskip("meshio")
    path = _vtu_2d(tmp_path / "plane.vtu")
    (tmp_path / "normal.toml").write_text(NORMAL)
    for extra, words in (([], "give --axisymmetric"),
                         (["--axisymmetric", "--z-up"], "carries no units")):
        code, out = run(tmp_path, "report", tmp_path / "normal.toml", path, *extra)
        err = capsys.readouterr().err.strip()
        assert code == 2 and len(err.splitlines()) == 1 and words in err, err
        assert not out.exists()


def test_units_pint_converts_and_table_fallback():
    from stressfields.fe.units import UnitProblem, factor

    assert factor("N/mm2", "Pa", "c") == factor("N/mm^2", "Pa", "c") == factor("MPa", "Pa", "c") == 1e6
    assert factor("psi", "Pa", "c") == pytest.approx(6894.757293168361, rel=1e-12)     # 1 lbf / in^2, exact SI
    assert factor("ksi", "Pa", "c") == pytest.approx(6894757.293168361, rel=1e-12)
    assert factor("µm", "m", "c") == pytest.approx(1e-6, rel=1e-15)
    assert factor("in", "m", "c") == pytest.approx(0.0254, rel=1e-15)
    with pytest.raises(UnitProblem, match="column 'c': unit 'mm' is not stress"):
        factor("mm", "Pa", "c")


def test_points_file_reads_the_csv_compare_reads(tmp_path):
    """The example's comparison CSV (node ids, x[mm], values) as a [points] file: the coordinates in
    metres, the node and value columns left out; an unknown column is still refused by name."""
    from stressfields.recipe import RecipeError, load

    header, table = example_table()
    recipe = RECIPE.read_text() + f'\n[points]\nfile = "{NODES}"\n'
    (tmp_path / "r.toml").write_text(recipe)
    r = load(tmp_path / "r.toml", allow_read=[NODES.parent])
    np.testing.assert_array_equal(r.values["x"], table[:, 1] * 1e-3)
    np.testing.assert_array_equal(r.values["z"], table[:, 3] * 1e-3)
    (tmp_path / "bad.csv").write_text("Node Label,X(mm),Y(mm),Z(mm),muu\n1,0.01,0.0,0.0,0.2\n")
    (tmp_path / "b.toml").write_text(RECIPE.read_text() + '\n[points]\nfile = "bad.csv"\n')
    with pytest.raises(RecipeError, match="unknown parameter 'muu'"):
        load(tmp_path / "b.toml")
    (tmp_path / "u.csv").write_text("x[MPa],y,z\n0.01,0.0,0.0\n")
    (tmp_path / "u.toml").write_text(RECIPE.read_text() + '\n[points]\nfile = "u.csv"\n')
    with pytest.raises(RecipeError, match="column 'x': unit 'MPa' cannot be converted to x's unit"):
        load(tmp_path / "u.toml")


def test_cylindrical_components_of_a_3d_model_are_the_rotated_tensor(tmp_path):
    """On the y axis (theta = 90 degrees, cos = 0 and sin = 1 exactly) sigma_rr = sigma_yy,
    sigma_tt = sigma_xx, sigma_rt = -sigma_xy, sigma_rz = sigma_yz, u_r = u_y: the cylindrical file and
    its Cartesian twin give the same statistics (Hertz-Mindlin: sigma_xy, sigma_yz are not zero)."""
    rng = np.random.default_rng(3)
    n = 12
    y, z = rng.uniform(0.01, 0.2, n), rng.uniform(0.0, 0.1, n)
    v = rng.normal(-300.0, 200.0, (n, 4))
    rows = lambda vals: "\n".join(",".join(repr(float(a)) for a in row)       # noqa: E731
                                  for row in np.column_stack([np.zeros(n), y, z, vals]))
    (tmp_path / "cyl.csv").write_text("x[mm],y[mm],z[mm],sigma_rr[MPa],sigma_thetatheta[MPa],sigma_rtheta[MPa],"
                                      "sigma_rz[MPa]\n" + rows(v) + "\n")
    cart = np.column_stack([v[:, 0], v[:, 1], -v[:, 2], v[:, 3]])
    (tmp_path / "cart.csv").write_text("x[mm],y[mm],z[mm],sigma_yy[MPa],sigma_xx[MPa],sigma_xy[MPa],sigma_yz[MPa]\n"
                                       + rows(cart) + "\n")
    run(tmp_path, "cyl", RECIPE, tmp_path / "cyl.csv")
    run(tmp_path, "cart", RECIPE, tmp_path / "cart.csv")
    a, b = report(tmp_path / "cyl")["tables"][0], report(tmp_path / "cart")["tables"][0]
    for cyl, car in (("sigma_rr", "sigma_yy"), ("sigma_tt", "sigma_xx"), ("sigma_rz", "sigma_yz")):
        for key in STATS:
            assert a["variables"][cyl][key] == pytest.approx(b["variables"][car][key], rel=1e-12), (cyl, key)
    assert a["variables"]["sigma_rt"]["rms_difference_over_scale"] == pytest.approx(
        b["variables"]["sigma_xy"]["rms_difference_over_scale"], rel=1e-12)


def test_exodus_element_variables_at_centroids(tmp_path):
    """An element variable is compared at its element's centroid: one hexahedron's corners around a
    node of the example; its value there gives that node's statistics."""
    import netCDF4

    header, table = example_table()
    row = table[137]                                        # the planted error's node (make_nodes.py)
    centre = row[1:4] * np.array([1, 1, -1])                # z up
    corners = centre + 0.001 * np.array([[sx, sy, sz] for sz in (-1, 1) for sy in (-1, 1) for sx in (-1, 1)])
    path = _exodus(tmp_path / "el.e", corners, ["dummy"], [np.zeros((8, 1))])
    with netCDF4.Dataset(path, "a") as ds:
        ds.createDimension("num_el_in_blk1", 1)
        ds.createDimension("num_nod_per_el1", 8)
        ds.createDimension("num_elem_var", 1)
        ds.createVariable("connect1", "i4", ("num_el_in_blk1", "num_nod_per_el1"))[:] = np.arange(1, 9)[None, :]
        names = ds.createVariable("name_elem_var", "S1", ("num_elem_var", "len_string"))
        names[:] = netCDF4.stringtochar(np.array(["sigma_xx"], dtype="S33"))
        ds.createVariable("vals_elem_var1eb1", "f8", ("time_step", "num_el_in_blk1"))[:] = [[row[4]]]
    (tmp_path / "one.csv").write_text("x[mm],y[mm],z[mm],sigma_xx[MPa]\n" + ",".join(
        repr(float(v)) for v in (*row[1:4], row[4])) + "\n")
    run(tmp_path, "one", RECIPE, tmp_path / "one.csv")
    code, out = run(tmp_path, "el", RECIPE, path, "--z-up", "--units", "length=mm,stress=MPa",
                    "--variables", "sigma_xx")
    tables = report(out)["tables"]
    assert "element centroids" in tables[-1]["user_data"]
    assert tables[-1]["variables"]["sigma_xx"]["max_abs_difference_over_scale"] == pytest.approx(
        report(tmp_path / "one")["tables"][0]["variables"]["sigma_xx"]["max_abs_difference_over_scale"], rel=1e-9)


def test_shipped_convergence_example_reports_what_the_readme_says(tmp_path):
    import importlib.util

    folder = EXAMPLE.parent / "fe_convergence"
    files = [folder / f"L{k}.csv" for k in (1, 2, 3)]
    spec = importlib.util.spec_from_file_location("make_meshes", folder / "make_meshes.py")
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    for level, path in zip((1, 2, 3), files):               # the committed files are the generator's
        h, r = gen.mesh(level)
        table = np.loadtxt(path, delimiter=",", skiprows=1)
        np.testing.assert_allclose(table[:, 1], r, rtol=1e-9)
        np.testing.assert_allclose(table[:, 3], gen.values(h, r), rtol=1e-9)
    assert sum(f.stat().st_size for f in folder.iterdir()) < 1_000_000
    code, out = run(tmp_path, "conv", folder / "recipe.toml", *files, "--axisymmetric", "--exclude-edge", "0.1",
                    "--h", "0.025,0.0125,0.00625", "--tolerance", "rms=1e-2")
    rep = report(out)
    orders = rep["convergence"]["variables"]["sigma_zz"]["rms"]["orders"]
    readme = (EXAMPLE.parents[1] / "README.md").read_text()
    assert f"RMS: {orders[0]:.3f} and {orders[1]:.3f} between successive meshes" in readme
    assert [t["result"] for t in rep["tables"]] == ["FAIL", "FAIL", "PASS"] and code == 1
    assert all(t["variables"]["sigma_zz"]["edge_compared_points"] >= 1 for t in rep["tables"])


def hertz_axis(z, nu=0.3):
    """Hertz on the axis r = 0 below the surface (the classical closed form, written out in the axis
    limits of docs/theory/interior.md in units of p0), here in p_m (p0 = 1.5 p_m, a = 1):
    sigma_zz = -p0 / (1 + z^2), sigma_rr = sigma_tt = -p0 [(1 + nu)(1 - z arctan(1/z)) - 1 / (2 (1 + z^2))];
    no shear on the axis."""
    p0 = 1.5
    szz = -p0 / (1 + z * z)
    srr = -p0 * ((1 + nu) * (1 - z * np.arctan(1 / z)) - 0.5 / (1 + z * z))
    return srr, szz


def test_weighted_and_energy_norms_are_the_integrals(tmp_path):
    (tmp_path / "normal.toml").write_text('scenario = "parabolic"\n[parameters]\nnu = 0.3\n')
    rng = np.random.default_rng(5)
    z = np.linspace(0.1, 2.0, 12)
    w = rng.uniform(0.5, 2.0, z.size)                           # quadrature weights
    srr, szz = hertz_axis(z)
    zero = np.zeros_like(z)
    ref = {"sigma_xx": srr, "sigma_yy": srr, "sigma_zz": szz, "sigma_xy": zero, "sigma_xz": zero, "sigma_yz": zero}
    delta = {k: rng.normal(0.0, 1e-3, z.size) for k in ref}
    names = list(ref)
    table = np.column_stack([zero, zero, z, w] + [ref[k] + delta[k] for k in names])
    (tmp_path / "axis.csv").write_text("x,y,z,weight," + ",".join(names) + "\n" + "\n".join(
        ",".join(repr(float(v)) for v in row) for row in table) + "\n")
    code, out = run(tmp_path, "w", tmp_path / "normal.toml", tmp_path / "axis.csv",
                    "--tolerance", "energy=1e-2,max=1e-2")
    t = report(out)["tables"][0]
    d, r = delta["sigma_zz"], szz
    assert t["variables"]["sigma_zz"]["weighted_relative_l2"] == pytest.approx(
        math.sqrt(np.sum(w * d * d) / np.sum(w * r * r)), rel=1e-6)

    def density(s, nu=0.3):
        tr = s["sigma_xx"] + s["sigma_yy"] + s["sigma_zz"]
        sq = sum(s[k] ** 2 for k in names[:3]) + 2 * sum(s[k] ** 2 for k in names[3:])
        return (1 + nu) * sq - nu * tr * tr

    assert t["energy_relative_error"] == pytest.approx(math.sqrt(np.sum(w * density(delta)) / np.sum(w * density(ref))),
                                                       rel=1e-6)
    assert code == 0 and t["result"] == "PASS"
    assert t["variables"]["sigma_xy"]["relative_l2"] == "inf"         # a zero reference: no relative norm


def test_scale_p0_and_rigid_offset(tmp_path):
    """Hertz at the surface inside the contact (a = 1, normalised): p / p0 = sqrt(1 - r^2) and
    u_z / delta = 1 - r^2 / 2 (the rigid approach minus the profile r^2 / (2R), a^2 = R delta)."""
    (tmp_path / "normal.toml").write_text('scenario = "parabolic"\n[parameters]\nnu = 0.3\n')
    r = np.linspace(0.0, 0.9, 10)
    rows = np.column_stack([r, np.zeros_like(r), -np.sqrt(1 - r * r), 1 - r * r / 2 + 0.011])
    (tmp_path / "s.csv").write_text("r,z,sigma_zz,u_z\n" + "\n".join(",".join(repr(float(v)) for v in row)
                                                                     for row in rows) + "\n")
    code, out = run(tmp_path, "p0", tmp_path / "normal.toml", tmp_path / "s.csv", "--axisymmetric", "--scale", "p0",
                    "--remove-rigid-offset", "--tolerance", "1e-8")
    v = report(out)["tables"][0]["variables"]
    assert code == 0 and v["u_z"]["rigid_offset_removed"] == pytest.approx(0.011, abs=1e-9)
    code, out = run(tmp_path, "pm", tmp_path / "normal.toml", tmp_path / "s.csv", "--axisymmetric", "--scale", "p_m",
                    "--tolerance", "1e-8")
    v = report(out)["tables"][0]["variables"]
    assert code == 1 and v["sigma_zz"]["max_abs_difference_over_scale"] == pytest.approx(0.5, rel=1e-6)  # 1.5 - 1
    assert v["u_z"]["max_abs_difference_over_scale"] == pytest.approx(0.011, rel=1e-6)
