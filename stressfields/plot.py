"""Quick-look PNGs of a written dataset, driven by the recipe's optional [plot] table.

    [plot]
    kind = "line"            # "line": curves along `x`, one per value of `hue`; "map": maps
    x = "x"                  # the horizontal dimension, or a variable to plot against
    marker = "o"             # optional marker (e.g. for the turning points of a history)
    hue = "mu"               # one curve per value (line plots)
    variables = ["sigma_xx", "dpdz"]   # one panel each
    ylim = [-20.0, 20.0]     # optional vertical range of line plots
Other dimensions are held at their first value. recipe.py checks the table; every table it
accepts is drawn, and so is a recipe without one (a recipe with nothing swept gets its values as
text).

Maps (``map_plane``): over x and y where the recipe sweeps both; otherwise, where it sweeps x and
the depth z, a section below the surface: filled contours in the x-z plane, depth downwards, and,
where the file holds the variable's per-case peak (``<name>_peak``, ``_peak_r``, ``_peak_depth``),
that peak marked and quoted from the file (``plot_kind``: a recipe sweeping x and z whose table asks
for no line, neither plot.x nor plot.hue, gets this section). A recipe sweeping the radius rho = r/a
and z (the graded scenarios) gets the same section over rho (peaks ``_peak_rho``), one panel per
value of its first other swept parameter (e.g. k: the graded field beside the homogeneous one). A
line along z is drawn as a depth profile, depth downwards.

Physical values are drawn in engineering units (`engineering`: MPa or GPa, µm or mm, chosen from the
data range), panel titles are the variables' short ``long_name`` in full, and flags (``region``,
``validity``) get a categorical colour bar labelled with their ``flag_meanings``.
"""
from __future__ import annotations

import os
import textwrap
from pathlib import Path

import numpy as np
import xarray as xr

from .physics.flags import Validity
from .reading import open_dataset
from .plotkeys import map_plane, plot_along, plot_kind

#: at most this many panels (3 columns)
MAX_PANELS = 6
#: characters of a panel title (the variable's long_name, shortened): one line at 7 pt on a 4.6 in panel
TITLE_CHARS = 70
#: SI unit -> its engineering forms, largest first (factor of the SI value, unit): `engineering`
PREFIXES = {
    "Pa": ((1e9, "GPa"), (1e6, "MPa"), (1e3, "kPa"), (1.0, "Pa")),
    # a pressure gradient under a micrometre contact: GPa/µm (1e15 Pa/m)
    "Pa/m": ((1e15, "GPa/µm"), (1e12, "MPa/µm"), (1e9, "MPa/mm"), (1e6, "MPa/m"), (1e3, "kPa/m"), (1.0, "Pa/m")),
    "m": ((1.0, "m"), (1e-3, "mm"), (1e-6, "µm"), (1e-9, "nm")),
    "N": ((1e3, "kN"), (1.0, "N"), (1e-3, "mN"), (1e-6, "µN")),
}


def require_matplotlib():
    """matplotlib.pyplot on the Agg backend, or an ImportError saying how to install it.

    Call it before any work when a plot is asked for, so a missing library costs nothing.
    """
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise ImportError("quick-look PNGs need matplotlib: pip install 'stressfields[plot]'") from None
    return plt


def plain(text: str) -> str:
    """``text`` drawn as written, never parsed as mathtext (a title "$\\foo$" raised
    ParseFatalException): every ``$`` escaped. Not parse_math=False: a wrapped title is measured
    by a path that ignores it (matplotlib 3.10)."""
    return text.replace("$", "\\$")


def save_figure(fig, plt, path: Path) -> Path:
    """The figure as PNG at ``path``, atomically (`_save`), then closed."""
    try:
        _save(fig, path)
    finally:
        plt.close(fig)
    return path


def quicklook(path: str | Path, recipe) -> Path:
    plt = require_matplotlib()
    path = Path(path)
    with open_dataset(path) as ds:          # choice dimensions labelled by name, for the legends
        fig = _figure(plt, ds, recipe)
        fig.suptitle(plain(recipe.title), fontsize=9, wrap=True)
        fig.tight_layout()
        png = path.with_suffix(".png")
        try:
            _save(fig, png)
        finally:
            plt.close(fig)
    return png


def _save(fig, png: Path) -> None:
    """The PNG written beside its target under a temporary name (`output.atomic.temporary`) and renamed
    onto it when complete; an I/O failure (a full disk) is one OutputError and leaves no file."""
    from .errors import OutputError
    from .output.atomic import temporary, umask

    tmp = temporary(png, ".tmp")
    try:
        fig.savefig(tmp, dpi=90, format="png")
        os.chmod(tmp, 0o666 & ~umask())     # mkstemp makes 0600; publish like any new file
        os.replace(tmp, png)
    except OSError as exc:
        raise OutputError(f"cannot write {png}: {exc.strerror or exc}") from None
    finally:
        if os.path.lexists(tmp):
            os.unlink(tmp)


def engineering(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with every variable in Pa, Pa/m, m or N rescaled to one engineering unit per SI unit
    (`PREFIXES`): the largest whose values reach 1 (210e9 Pa -> 210 GPa, 8e-6 m -> 8 µm), so axes need
    no 1e10 offset. One unit per SI unit keeps a field, its peak and its coordinates comparable."""
    biggest: dict[str, float] = {}
    for var in ds.variables.values():
        units = var.attrs.get("units")
        if units in PREFIXES and var.dtype.kind == "f" and var.size:
            values = np.abs(np.asarray(var.values, dtype=float))
            finite = values[np.isfinite(values)]
            if finite.size:
                biggest[units] = max(biggest.get(units, 0.0), float(finite.max()))
    chosen = {u: next(((f, n) for f, n in PREFIXES[u] if top >= f), PREFIXES[u][-1])
              for u, top in biggest.items()}
    chosen = {u: fn for u, fn in chosen.items() if fn[1] != u}
    if not chosen:
        return ds
    new_data, new_coords = {}, {}
    for name, var in ds.variables.items():
        units = var.attrs.get("units")
        if units in chosen and var.dtype.kind == "f":
            factor, unit = chosen[units]
            scaled = xr.Variable(var.dims, np.asarray(var.values) / factor, {**var.attrs, "units": unit})
            (new_coords if name in ds.coords else new_data)[name] = scaled
    return ds.assign_coords(new_coords).assign(new_data)


def _figure(plt, ds: xr.Dataset, recipe):
    ds = engineering(ds)
    spec, swept = recipe.plot, recipe.swept
    kind = plot_kind(spec, swept)
    plane = map_plane(swept) if kind == "map" else None
    if kind == "map" and plane is None:     # not a table recipe.py accepts: draw the values
        return _text_figure(plt, ds, recipe)
    xname = spec.get("x", plane[0] if kind == "map" else (swept[-1] if swept else None))
    hue = spec.get("hue")
    dims = {n: v.dims for n, v in ds.variables.items()}      # coordinates too: plot.x may be one (ux0)
    along = plot_along(xname, hue, swept, dims) if kind == "line" and xname else None
    need = set(plane) if kind == "map" else {along}
    names = [n for n in spec.get("variables", recipe.variables)
             if n in ds.data_vars and need <= set(ds[n].dims)][:MAX_PANELS]
    if not names:
        return _text_figure(plt, ds, recipe)
    panels = [(n, {}) for n in names]
    if plane == ("rho", "z"):        # one panel per value of the first other swept parameter, side by side
        other = [d for d in swept if d not in plane and d in ds[names[0]].dims][:1]
        panels = [(n, {other[0]: i} if other else {}) for n in names
                  for i in range(ds.sizes[other[0]] if other else 1)][:MAX_PANELS]
    ncol = min(3, len(panels))
    nrow = -(-len(panels) // ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.6 * ncol + 1.0, 3.8 * nrow + 0.4), squeeze=False)
    for ax, (name, at) in zip(axes.flat, panels):
        if kind == "map":
            _map(ax, ds, name, plane, at)
        else:
            _lines(ax, ds, name, xname, along, hue, spec.get("marker"))
            if "ylim" in spec:
                ax.set_ylim(*spec["ylim"])
        where = "".join(f"{d} = {float(ds[d][i]):g}: " for d, i in at.items())     # first: never cut off
        ax.set_title(textwrap.shorten(where + ds[name].attrs.get("long_name", name), TITLE_CHARS,
                                      placeholder=" ..."), fontsize=7)
    for ax in list(axes.flat)[len(panels):]:
        ax.set_visible(False)
    return fig


def _map(ax, ds, name, plane=("x", "y"), at=None):
    da = ds[name]
    hold = {d: (at or {}).get(d, 0) for d in da.dims if d not in plane}
    da = da.isel(hold)
    if "flag_values" in da.attrs:
        _flags(ax, ds, da, plane)
        return
    if plane[1] == "z":
        _section(ax, ds, da, hold, plane[0])
        return
    da.transpose("y", "x").plot(ax=ax, robust=True, cbar_kwargs={"label": _label(da)})
    ax.set_aspect("equal")
    ax.set_xlabel(_label(ds["x"]))
    ax.set_ylabel(_label(ds["y"]))


def _flags(ax, ds, da, plane):
    """A flag over the plane: one colour per flag value, the colour bar labelled with the meanings."""
    from matplotlib.colors import BoundaryNorm, ListedColormap

    codes = [int(v) for v in np.ravel(da.attrs["flag_values"])]
    meanings = str(da.attrs.get("flag_meanings", "")).split()
    colours = ListedColormap([f"C{i}" for i in range(len(codes))])
    edges = [c - 0.5 for c in codes] + [codes[-1] + 0.5]
    xs, ys = plane
    mesh = ax.pcolormesh(ds[xs].values, ds[ys].values, da.transpose(ys, xs).values, cmap=colours,
                         norm=BoundaryNorm(edges, len(codes)), shading="nearest")
    bar = ax.figure.colorbar(mesh, ax=ax, ticks=codes)
    bar.ax.set_yticklabels([m.replace("_", " ") for m in meanings] if len(meanings) == len(codes) else codes,
                           fontsize=6)
    if ys == "z":
        ax.set_ylim(ds["z"].values.max(), ds["z"].values.min())        # depth downwards
    ax.set_aspect("equal")
    ax.set_xlabel(_label(ds[xs]))
    ax.set_ylabel(_label(ds[ys]))


def _lines(ax, ds, name, xname, along, hue, marker):
    """One curve of `name` against `xname` along `along` per value of `hue`; other dims at index 0.
    Against the depth z the curves are depth profiles: z on the vertical axis, downwards."""
    y, x = xr.broadcast(ds[name], ds[xname])
    hold = {d: 0 for d in y.dims if d not in (along, hue)}
    y, x = y.isel(hold), x.isel(hold)
    depth = xname == "z"
    xlabel, ylabel = _label(ds[xname]), _label(ds[name])

    def draw(xs, ys, **kw):
        ax.plot(*((ys, xs) if depth else (xs, ys)), lw=1, marker=marker, **kw)

    if hue in y.dims:
        for i, text in enumerate(_legend(ds[hue])):
            draw(x.isel({hue: i}).values, y.isel({hue: i}).values, label=text)
        ax.legend(fontsize=7)
    else:
        draw(x.values, y.values)
    if depth:
        xlabel, ylabel = ylabel, _label(ds["z"])
        ax.invert_yaxis()
        ax.axvline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)


def _section(ax, ds, da, hold, across="x"):
    """Filled contours of `da` in the x-z (or rho-z) plane, depth downwards, with the file's peak marked."""
    values = np.ma.masked_invalid(da.transpose("z", across).values)
    if not values.count():
        ax.text(0.5, 0.5, "no finite values", ha="center", va="center", transform=ax.transAxes)
        return
    peak = _peak(ds, da.name, hold, across)
    levels, extend = _levels(values, peak)
    x, z = ds[across].values, ds["z"].values
    filled = ax.contourf(x, z, values, levels=levels, extend=extend, cmap="viridis")
    ax.contour(x, z, values, levels=levels, colors="k", linewidths=0.4)
    above = levels[-1] * np.sqrt(2.0) ** np.arange(1, 9)      # beyond the colours: lines that crowd
    above = above[above < values.max()]                        # towards a singular point
    if extend == "max" and above.size and levels[-1] > 0:
        ax.contour(x, z, values, levels=above, colors="w", linewidths=0.4)
    bar = ax.figure.colorbar(filled, ax=ax, orientation="horizontal", pad=0.28, aspect=40)
    bar.set_label(_bar_label(da), fontsize=7)
    bar.ax.tick_params(labelsize=7)
    p0 = _centre_pressure(ds, hold, across)
    if p0 is not None:          # the textbook scale: the centre pressure p(0) of the same case
        top = bar.ax.secondary_xaxis("top", functions=(lambda v: v / p0, lambda v: v * p0))
        top.set_xlabel(f"{da.name} / p(0), centre pressure p(0) = -sigma_zz(0, 0, 0) = {p0:#.4g} "
                       f"{_unit(ds['sigma_zz'])}", fontsize=7)
        top.tick_params(labelsize=7)
    ax.set_xlim(x.min(), x.max())
    ax.set_ylim(z.max(), z.min())               # depth downwards
    ax.set_aspect("equal")
    ax.set_xlabel(_label(ds[across]) if across == "x" else "r / a (rho)")
    ax.set_ylabel(_label(ds["z"]))
    if peak is not None:
        _mark(ax, ds, da, peak, p0, hold, across)


def _levels(values, peak):
    """About 12 contour levels from the smallest value to the file's peak where it is finite, else
    to the 98th percentile if the grid holds a singular point (+-inf: the field's growth next to it
    would take every level), else to the largest value; "max" where values lie above the top."""
    from matplotlib.ticker import MaxNLocator

    finite = values.compressed()
    if peak is not None and np.isfinite(peak["value"]):
        top = max(peak["value"], finite.max())          # the supremum; max: a grid point on it, rounded
    elif np.ma.count_masked(values):
        top = float(np.percentile(finite, 98))
    else:
        top = float(finite.max())
    low = float(finite.min())
    top = top if top > low else low + (abs(low) or 1.0)        # a uniform field: one band
    levels = MaxNLocator(nbins=12).tick_values(low, top)
    levels = levels[levels <= top + 1e-12 * abs(top)]
    if top > levels[-1]:
        levels = np.append(levels, top)
    above = finite.max() > levels[-1] or np.isposinf(values.data).any()
    return levels, "max" if above else "neither"


def _peak(ds, name, hold, across="x") -> dict | None:
    """The file's peak of `name` for the shown case and where it sits (on y = 0), or None."""
    # the position across the section: rho (graded), r (an axisymmetric field), x (a plane one: wavy)
    if across == "rho":
        along = f"{name}_peak_rho"
    else:
        along = f"{name}_peak_r" if f"{name}_peak_r" in ds.data_vars else f"{name}_peak_x"
    keys = (f"{name}_peak", along, f"{name}_peak_depth")
    if not all(k in ds.data_vars for k in keys) or _scalar(ds, "y", hold, 0.0) != 0.0:
        return None                             # no peak in the file, or the plane is not y = 0
    value, x, depth = (_scalar(ds, k, hold) for k in keys)
    flag = int(_scalar(ds, "peak_validity", hold, 0))
    return {"value": value, "x": x, "depth": depth, "flag": flag}


def _scalar(ds, name, hold, default=None):
    """The value of `name` at the held indices of the shown case (`default` if not in the file)."""
    if name not in ds.variables:
        return default
    da = ds[name]
    return da.isel({d: i for d, i in hold.items() if d in da.dims}).values.item()


def _centre_pressure(ds, hold, across="x") -> float | None:
    """p(0) = -sigma_zz at the surface centre x = y = z = 0 of the shown case, if the file holds it
    and it is finite (Hertz: p0 = 3/2 p_m)."""
    if "sigma_zz" not in ds.data_vars or _scalar(ds, "y", hold, 0.0) != 0.0:
        return None
    s = ds["sigma_zz"].isel({d: i for d, i in hold.items() if d in ds["sigma_zz"].dims})
    hit = (s[across] == 0.0) & (s["z"] == 0.0)
    if int(hit.sum()) != 1:
        return None
    p0 = -float(s.where(hit, drop=True).values.ravel()[0])
    return p0 if np.isfinite(p0) and p0 > 0.0 else None


def _mark(ax, ds, da, peak, p0, hold, across="x"):
    """The peak of the file: one marker, two at x = +-r under normal load (an axisymmetric field:
    the file gives r >= 0; one on a rho-z section), and its value and position in the legend."""
    if peak["flag"] == Validity.undefined_direction_dependent_limit or not np.isfinite(peak["x"]):  # NaN: no point
        return
    load = max(_scalar(ds, k, hold, 0.0) for k in ("ux0", "fx", "tangential_force"))
    tangential = _scalar(ds, "mu", hold, 0.0) * load > 0.0
    xs = [peak["x"]] if tangential or peak["x"] == 0.0 or across == "rho" else [-peak["x"], peak["x"]]
    length = _unit(ds[across]) if across == "x" else "a"
    unit = _unit(da)
    where = (f"{across} = {'+-' if len(xs) > 1 else ''}{peak['x']:.4g}{'' if across == 'rho' else ' ' + length}, "
             f"z = {peak['depth']:.4g} {length if across == 'x' else 'a'}")
    if np.isinf(peak["value"]):
        text = f"{da.name} unbounded at {where}"
    else:
        scale = f" = {peak['value'] / p0:#.4g} p(0)" if p0 is not None else ""
        text = f"{da.name} peak {peak['value']:#.4g} {unit}{scale} at {where}"
        if peak["flag"] == Validity.search_not_converged:
            text += " (search not converged: best found)"
    ax.plot(xs, [peak["depth"]] * len(xs), ls="", marker="X", ms=8, color="red", mec="white", mew=0.8,
            label=text, clip_on=False, zorder=5)
    ax.legend(loc="lower center", fontsize=6.5, framealpha=0.85)


def _text_figure(plt, ds, recipe):
    """Nothing varies along a line: the values as text."""
    fig, ax = plt.subplots(figsize=(6.0, 4.0))
    ax.axis("off")
    lines = [f"{n} = {ds[n].values.ravel()[0]!r}" + (" ..." if ds[n].size > 1 else "")
             for n in list(ds.data_vars)[:20]]
    ax.text(0.0, 1.0, "\n".join(lines) or "no variables", va="top", family="monospace", fontsize=7,
            transform=ax.transAxes)
    return fig


def _legend(coord) -> list[str]:
    """One entry per value of a hue dimension: the name of a choice, else ``name = value``, with
    the coordinates along the same dimension (a history's ``ux0`` beside its ``step``)."""
    values = np.asarray(coord.values)
    if values.dtype.kind in "OUST":
        return [str(v) for v in values]
    also = [c for c in coord.coords if c != coord.name and coord[c].dims == coord.dims]
    return [f"{coord.name} = {v:g}" + "".join(f", {c} = {float(coord[c][i]):.4g}" for c in also)
            for i, v in enumerate(values.tolist())]


def _unit(da) -> str:
    """The unit of a value: its units, or in normalised mode the symbol it is divided by."""
    units = da.attrs.get("units")
    if units and units != "1":
        return units
    return _symbol(da)


def _symbol(da) -> str:
    """The symbol a normalised variable is divided by ("p_m", "a", "(mu F_N)"), from its
    normalisation or the tail of its long_name ("... divided by the contact radius a"); "" if none
    or if the tail is a phrase rather than a symbol (more than 12 characters)."""
    norm = da.attrs.get("normalisation") or da.attrs.get("description", "").partition(" divided by ")[2]
    norm = norm.split(",")[0].split(" = ")[0].split(" (")[0].strip()
    norm = norm.split()[-1] if norm.startswith("the ") else norm
    if len(norm) > 12:
        return ""
    return f"({norm})" if set(norm) & set(" /") else norm


def _label(da) -> str:
    """An axis label of one short line: the variable's name and its units, or in normalised mode
    the symbol it is divided by (x / a, sigma_xx / p_m); the depth z says so (the long_name would
    wrap onto 4-8 lines; it is the panel's title)."""
    units = da.attrs.get("units")
    symbol = _symbol(da)
    text = f"{da.name} [{units}]" if units and units != "1" else (
        f"{da.name} / {symbol}" if symbol else str(da.name))
    return text + (" (depth)" if da.name == "z" else "")


def _bar_label(da) -> str:
    """The colour bar: name, unit and the long_name without the symbol it is divided by."""
    text = da.attrs.get("long_name", da.name)
    symbol = _symbol(da)
    if symbol and text.endswith(f" / {symbol}"):
        text = text[:-len(f" / {symbol}")]
    return textwrap.shorten(f"{_label(da)}: {text}", TITLE_CHARS, placeholder=" ...")
