"""Quick looks below the surface: every *_subsurface recipe validates and draws (a small grid, the
Agg backend), its x-z section is a contour map with the depth downwards and the file's own peak
marked, and its depth profiles run downwards. The marked Hertz peak is held against Johnson's
formulas on the axis (an independent route)."""
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

import stressfields as sf
from stressfields import plot
from stressfields.recipe import load

pytest.importorskip("matplotlib")
plt = plot.require_matplotlib()          # Agg: headless

ROOT = Path(__file__).resolve().parents[1]
RECIPES = sorted(p.stem for p in (ROOT / "recipes").glob("*subsurface*.toml"))
SECTIONS = ["cone_subsurface", "hertz_mindlin_subsurface", "hertz_subsurface", "power_law_n4_subsurface"]
#: the wavy family's sections (plane strain: the peak's position is x itself, `<name>_peak_x`)
WAVY_SECTIONS = ["wavy_subsurface_indenter", "wavy_subsurface_periodic"]
GRADED = ["graded_subsurface", "graded_subsurface_adhesive"]
#: a small grid holding x = 0 and z = 0 (the centre pressure p(0) is read there)
SMALL = {"x": {"start": -2.0, "stop": 2.0, "num": 13}, "z": {"start": 0.0, "stop": 2.0, "num": 9},
         "rho": {"start": 0.0, "stop": 2.0, "num": 9}}


def _small(stem: str) -> dict:
    data = tomllib.loads((ROOT / "recipes" / f"{stem}.toml").read_text())
    params = data["parameters"]
    for key, value in SMALL.items():
        if isinstance(params.get(key), dict):
            params[key] = value
    if stem in GRADED:      # the graded peak search at k > 0 takes ~10 s a case: the map without its marker
        data["output"]["variables"] = [v for v in data["output"]["variables"] if "_peak" not in v]
    return data


@pytest.fixture(scope="module")
def drawn(tmp_path_factory):
    """stem -> (recipe, path of the written small file); the files are written once."""
    out = tmp_path_factory.mktemp("subsurface")
    files = {}
    for stem in RECIPES:
        data = _small(stem)
        files[stem] = load(data), sf.write(sf.generate(data), out / f"{stem}.nc")
    return files


def _figure(drawn, stem):
    recipe, path = drawn[stem]
    ds = sf.open_dataset(path)
    return recipe, ds, plot._figure(plt, ds, recipe)


def _maps(fig):
    return [ax for ax in fig.axes if ax.get_visible() and ax.get_ylabel().startswith("z")]


def test_the_subsurface_recipes_are_the_quick_looks():
    assert (set(SECTIONS + WAVY_SECTIONS + GRADED) | {"history_hertz_fretting_subsurface", "wavy_subsurface_slip"}
            == set(RECIPES))


@pytest.mark.parametrize("stem", WAVY_SECTIONS)
def test_a_wavy_section_marks_its_peak_at_x(drawn, stem):
    """The plane field's peak is marked where the file puts it (x >= 0 under normal load, mirrored)."""
    recipe, ds, fig = _figure(drawn, stem)
    maps = _maps(fig)
    assert len(maps) == len(recipe.plot["variables"])
    ax = maps[0]                                    # tau_max, the one with peaks in the file
    value, x, depth = (float(ds[f"tau_max_peak{s}"]) for s in ("", "_x", "_depth"))
    line = _marker(ax)
    np.testing.assert_array_equal(line.get_xdata(), [x] if x == 0 else [-x, x])
    np.testing.assert_array_equal(line.get_ydata(), [depth] * len(line.get_xdata()))
    assert f"tau_max peak {value:#.4g} p*" in ax.get_legend().get_texts()[0].get_text()
    assert float(ds.tau_max.max()) <= value * (1 + 1e-8)


@pytest.mark.parametrize("stem", GRADED)
def test_a_graded_section_is_a_rho_z_map_per_grading_exponent(drawn, stem):
    """One panel per value of k, side by side: the graded field beside the homogeneous one."""
    recipe, ds, fig = _figure(drawn, stem)
    maps = _maps(fig)
    assert len(maps) == ds.sizes["k"] == 2
    for ax, k in zip(maps, ds.k.values):
        assert ax.get_title().startswith(f"k = {k:g}: ") and ax.get_xlabel() == "r / a (rho)"
        bottom, top = ax.get_ylim()
        assert bottom == float(ds.z.max()) and top == 0.0 and ax.collections
    plt.close(fig)


@pytest.mark.parametrize("stem", RECIPES)
def test_each_recipe_validates_and_draws_a_png(drawn, stem, tmp_path):
    load(ROOT / "recipes" / f"{stem}.toml")                 # the full recipe passes the check
    recipe, path = drawn[stem]
    png = plot.quicklook(path, recipe)
    assert png.exists() and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("stem", SECTIONS)
def test_a_section_is_a_contour_map_depth_downwards(drawn, stem):
    recipe, ds, fig = _figure(drawn, stem)
    maps = _maps(fig)
    assert len(maps) == len(recipe.plot["variables"])
    for ax, name in zip(maps, recipe.plot["variables"]):
        bottom, top = ax.get_ylim()
        assert bottom == 2.0 and top == 0.0                 # depth downwards
        assert ax.get_xlabel() == "x / a" and ax.get_ylabel() == "z / a (depth)"
        assert ax.collections                               # filled contours and lines
        bar = next(a for a in fig.axes if a.get_xlabel().startswith(f"{name} / p_m: "))
        assert ds[name].attrs["long_name"].startswith(bar.get_xlabel().split(": ", 1)[1].rstrip(" ."))
        for text in (ax.get_xlabel(), ax.get_ylabel(), ax.get_title(), bar.get_xlabel()):
            assert "\n" not in text and len(text) <= plot.TITLE_CHARS, text
    plt.close(fig)


def _marker(ax):
    (line,) = [ln for ln in ax.get_lines() if ln.get_marker() == "X"]
    return line


@pytest.mark.parametrize("stem", SECTIONS)
def test_the_marked_peak_is_the_files(drawn, stem):
    """Position and value of the marker and its legend are the file's tau_max_peak* (von_mises_peak*);
    under normal load the field is axisymmetric and the peak is marked at x = +-r."""
    recipe, ds, fig = _figure(drawn, stem)
    for ax, name in zip(_maps(fig), recipe.plot["variables"]):
        value, r, depth = (float(ds[f"{name}_peak{s}"]) for s in ("", "_r", "_depth"))
        line, text = _marker(ax), ax.get_legend().get_texts()[0].get_text()
        tangential = float(ds.mu) * float(ds.ux0) > 0
        xs = [r] if tangential or r == 0 else [-r, r]
        np.testing.assert_array_equal(line.get_xdata(), xs)
        np.testing.assert_array_equal(line.get_ydata(), [depth] * len(xs))
        if math.isinf(value):
            assert int(ds.peak_validity) == 1 and f"{name} unbounded at x = 0 a, z = 0 a" in text
        else:
            assert int(ds.peak_validity) == 0 and f"{name} peak {value:#.4g} p_m" in text
            assert f"z = {depth:.4g} a" in text
            grid = float(ds[name].max())
            assert grid <= value * (1 + 1e-8)                # the peak is the supremum of the field
    plt.close(fig)


def test_cone_tip_is_marked_unbounded_and_the_colours_stop_below_it(drawn):
    recipe, ds, fig = _figure(drawn, "cone_subsurface")
    (ax,) = _maps(fig)
    assert float(ds.tau_max.sel(x=0.0, z=0.0)) == np.inf and int(ds.validity.sel(x=0.0, z=0.0)) == 1
    filled = ax.collections[0]
    assert np.all(np.isfinite(filled.levels)) and filled.extend == "max"
    plt.close(fig)


def _johnson_axis_tau(z, nu=0.3):
    """tau_max / p0 on the Hertz axis from the axis formulas of sigma_z and sigma_r (Johnson 1985, sec. 3.4)."""
    sz = -1.0 / (1.0 + z * z)
    sr = -(1.0 + nu) * (1.0 - z * math.atan(1.0 / z)) + 0.5 / (1.0 + z * z)
    return 0.5 * (sr - sz)


def test_hertz_mark_is_johnsons_peak_in_p0(drawn):
    """0.31 p0 at 0.48 a, in p_m and in p(0) = 3/2 p_m (Hertz): the legend against a bounded 1-D
    search on Johnson's axis formulas; p(0) read from the file's sigma_zz at the surface centre."""
    best = minimize_scalar(lambda z: -_johnson_axis_tau(z), bounds=(0.2, 1.0), method="bounded",
                           options={"xatol": 1e-10})
    tau0, z0 = -best.fun, best.x
    assert tau0 == pytest.approx(0.3100205, abs=1e-7) and z0 == pytest.approx(0.4808645, abs=1e-6)
    recipe, ds, fig = _figure(drawn, "hertz_subsurface")
    (ax,) = _maps(fig)
    line, text = _marker(ax), ax.get_legend().get_texts()[0].get_text()
    assert line.get_xdata()[0] == 0.0 and line.get_ydata()[0] == pytest.approx(z0, abs=1e-6)
    assert f"= {tau0:#.4g} p(0) at x = 0 a" in text and f"{1.5 * tau0:#.4g} p_m" in text
    top = [c for a in fig.axes for c in a.child_axes if c.get_xlabel().startswith("tau_max / p(0)")]
    assert top and "p(0) = -sigma_zz(0, 0, 0) = 1.500 p_m" in top[0].get_xlabel()
    assert ax.collections[0].levels[-1] == pytest.approx(float(ds.tau_max_peak), rel=1e-15)
    plt.close(fig)


def test_hertz_mindlin_section_is_asymmetric_with_c_06(drawn):
    recipe, ds, fig = _figure(drawn, "hertz_mindlin_subsurface")
    assert float(ds.stick_radius) == pytest.approx(0.6, rel=1e-12)          # (c/a)^2 = 1 - u_x0/u*
    vm = ds.von_mises.values
    assert np.max(np.abs(vm - vm[:, ::-1])) > 0.05                           # not even in x
    assert float(ds.von_mises_peak_r) > 0 and float(ds.tau_max_peak_r) > 0  # signed x, one marker each
    assert [len(_marker(ax).get_xdata()) for ax in _maps(fig)] == [1, 1]
    plt.close(fig)


def test_power_law_peak_is_off_axis_on_both_sides(drawn):
    recipe, ds, fig = _figure(drawn, "power_law_n4_subsurface")
    (ax,) = _maps(fig)
    r = float(ds.tau_max_peak_r)
    assert 0.5 < r < 1.0
    np.testing.assert_array_equal(_marker(ax).get_xdata(), [-r, r])
    # MDR: p(r) ~ (a^2 + 2 r^2) sqrt(a^2 - r^2) for f = A r^4, whose mean is 6/5 of p(0): p(0) = 5/6 p_m
    top = [c for a in fig.axes for c in a.child_axes if c.get_xlabel().startswith("tau_max / p(0)")]
    assert top and "p(0) = -sigma_zz(0, 0, 0) = 0.8333 p_m" in top[0].get_xlabel()
    tau = ds.tau_max.values                                                  # axisymmetric: even in x
    np.testing.assert_allclose(tau, tau[:, ::-1], rtol=1e-7, atol=1e-8)
    plt.close(fig)


def test_fretting_depth_profiles_run_downwards_one_per_step(drawn):
    recipe, ds, fig = _figure(drawn, "history_hertz_fretting_subsurface")
    axes = [ax for ax in fig.axes if ax.get_visible()]
    assert len(axes) == 3
    for ax, name in zip(axes, recipe.plot["variables"]):
        bottom, top = ax.get_ylim()
        assert bottom > top and ax.get_ylabel() == "z / a (depth)" and ax.get_xlabel() == f"{name} / p_m"
        lines = [ln for ln in ax.get_lines() if ln.get_label().startswith("step")]
        assert [ln.get_label() for ln in lines] == [
            f"step = {s}, ux0 = {u:.4g}" for s, u in zip(ds.step.values, ds.ux0.values)]
        for i, ln in enumerate(lines):
            np.testing.assert_array_equal(ln.get_ydata(), ds.z.values)
            np.testing.assert_array_equal(ln.get_xdata(), ds[name].isel(step=i).values)
    plt.close(fig)


@pytest.mark.parametrize("table, kind", [
    ({}, "map"), ({"variables": ["tau_max"]}, "map"), ({"x": "z"}, "line"), ({"hue": "z"}, "line"),
    ({"kind": "line"}, "line"), ({"kind": "map"}, "map")])
def test_an_x_z_sweep_draws_a_section_unless_the_table_asks_for_lines(table, kind):
    assert plot.plot_kind(table, ("z", "x")) == kind
    assert plot.map_plane(("z", "x")) == ("x", "z") and plot.map_plane(("z", "y", "x")) == ("x", "y")
    assert plot.plot_kind({}, ("mu", "x")) == "line" and plot.plot_kind({"x": "x"}, ("y", "x")) == "map"


@pytest.mark.parametrize("values", [np.zeros((4, 5)), np.full((4, 5), np.nan), np.arange(20.0).reshape(4, 5)])
def test_a_uniform_or_empty_section_still_draws(values):
    import xarray as xr

    coords = {"x": ("x", np.linspace(-1, 1, 5), {"units": "1", "long_name": "x / a",
                                               "description": "x divided by the contact radius a"}),
              "z": ("z", np.linspace(0, 1, 4), {"units": "1", "long_name": "depth z / a",
                                               "description": "depth divided by the contact radius a"})}
    ds = xr.Dataset({"tau_max": (("z", "x"), values, {"units": "1", "normalisation": "the mean pressure p_m"})},
                    coords=coords)
    recipe = type("R", (), {"plot": {}, "swept": ("z", "x"), "variables": ("tau_max",), "title": "t"})
    fig = plot._figure(plt, ds, recipe)
    fig.canvas.draw()
    finite = np.isfinite(values).any()
    assert any(a.get_xlabel() == "x / a" for a in fig.axes) == finite
    plt.close(fig)


def test_physical_quick_looks_are_in_engineering_units(tmp_path):
    """The steel cone (E = 210 GPa, x up to 8 µm): MPa/GPa and µm on the axes, no offset such as 1e10."""
    data = tomllib.loads((ROOT / "recipes" / "steel_cone_physical.toml").read_text())
    data["parameters"]["x"] = {"start": -8e-6, "stop": 8e-6, "num": 33}
    recipe = load(data)
    with sf.open_dataset(sf.write(sf.generate(data), tmp_path / "steel.nc")) as ds:
        shown = plot.engineering(ds)
        assert shown["x"].attrs["units"] == "µm" and shown["sigma_xx"].attrs["units"] in ("MPa", "GPa")
        np.testing.assert_allclose(shown["x"].values, ds["x"].values * 1e6, rtol=1e-12)
        factor = {"MPa": 1e6, "GPa": 1e9}[shown["sigma_xx"].attrs["units"]]
        np.testing.assert_allclose(shown["sigma_xx"].values * factor, ds["sigma_xx"].values, rtol=1e-12)
        fig = plot._figure(plt, ds, recipe)
        fig.canvas.draw()
        panels = [ax for ax in fig.axes if ax.get_visible() and ax.get_title()]
        assert panels
        for ax in panels:
            assert "[µm]" in ax.get_xlabel()
            assert ax.yaxis.get_offset_text().get_text() == "" and ax.xaxis.get_offset_text().get_text() == ""
            assert ax.get_title() in {var.attrs.get("long_name") for var in ds.data_vars.values()}   # not cut
        plt.close(fig)


def test_flags_get_a_categorical_colour_bar():
    data = tomllib.loads((ROOT / "recipes" / "hertz_mindlin_map.toml").read_text())
    for key in ("x", "y"):
        data["parameters"][key] = {"start": -1.5, "stop": 1.5, "num": 21}
    data["plot"]["variables"] = ["sigma_xx", "region"]
    ds = sf.generate(data)
    fig = plot._figure(plt, ds, load(data))
    bars = [ax for ax in fig.axes if [t.get_text() for t in ax.get_yticklabels()][:1] == ["outside contact"]]
    assert len(bars) == 1
    assert [t.get_text() for t in bars[0].get_yticklabels()] == ["outside contact", "stick", "slip",
                                                                 "contact without tangential traction"]
    plt.close(fig)
