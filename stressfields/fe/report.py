"""The report of `stressfields compare`: report.md and report.json (every figure, machine-readable;
the convergence table of a mesh sequence), comparison.nc (comparison_<k>.nc for several tables), and
unless --no-plot a PNG per table with depth drawn downward, zoomed on the largest differences, and
convergence.png for a mesh sequence.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import xarray as xr

from .validate import stats_summary


def nc_names(count: int) -> list[str]:
    return ["comparison.nc"] if count == 1 else [f"comparison_{k + 1}.nc" for k in range(count)]


def png_names(count: int) -> list[str]:
    return ["comparison.png"] if count == 1 else [f"comparison_{k + 1}.png" for k in range(count)]


def report_json(datasets: list[xr.Dataset], recipe_label: str, conv: dict | None) -> str:
    body = {"recipe": recipe_label, "result": overall(datasets),
            "tables": [dict(stats_summary(ds), file=name) for ds, name in zip(datasets, nc_names(len(datasets)))]}
    if conv is not None:
        body["convergence"] = conv
    return json.dumps(body, indent=1, default=_default, allow_nan=False) + "\n"


def _default(v):
    if isinstance(v, np.generic):
        return v.item()
    return str(v)


def overall(datasets: list[xr.Dataset]) -> str:
    results = [ds.attrs["compare_result"] for ds in datasets]
    if any(r == "FAIL" for r in results):
        return "FAIL"
    return "PASS" if all(r == "PASS" for r in results) else results[0]


def _f(v) -> str:
    return f"{v:.3e}" if isinstance(v, (int, float)) and not isinstance(v, bool) else "-"


def report_markdown(datasets: list[xr.Dataset], recipe_label: str, conv: dict | None, plots: str) -> str:
    """One section per table (file, time step): a row per variable with max, RMS, p50/p95/p99 and L2
    of |Δ| / S, the edge ring apart, the verdict; then the convergence table."""
    lines = [f"# FE comparison against the stressfields reference: **{overall(datasets)}**", "",
             f"- recipe: `{recipe_label}` (scenario `{datasets[0].attrs['stressfields_scenario']}`, "
             f"{datasets[0].attrs['stressfields_units_mode']} units)",
             "- S: the variable's normalisation scale (p_m for stresses); Δ = user - reference; statistics "
             "over the nodes where the reference is finite", ""]
    for ds, name in zip(datasets, nc_names(len(datasets))):
        s = stats_summary(ds)
        lines += [f"## {s['user_data']}", "",
                  f"- {s['points']} points; frame: {s['frame']}; tolerance: {s.get('tolerance', 'none')}; "
                  f"**{s['result']}**; every value: `{name}`"]
        if "edge_ring" in s:
            lines.append(f"- edge ring (reported apart, not in the verdict): {s['edge_ring']}")
        if "energy_relative_error" in s:
            lines.append(f"- relative energy-norm error of the stress: {_f(s['energy_relative_error'])}")
        if "weights" in s:
            lines.append(f"- weighted norms: {s['weights']}")
        lines += ["", "| variable | max Δ/S | RMS Δ/S | p50 | p95 | p99 | rel. L2 | weighted L2 | worst point | at |"
                  " edge ring: points, max Δ/S | result |", "|---" * 12 + "|"]
        for var, v in s["variables"].items():
            node = f" (node {v['worst_node']})" if "worst_node" in v else ""
            edge = (f"{v['edge_compared_points']}, {_f(v.get('edge_max_abs_difference_over_scale'))}"
                    if "edge_compared_points" in v else "-")
            lines.append(f"| `{var}` | {_f(v.get('max_abs_difference_over_scale'))} | "
                         f"{_f(v.get('rms_difference_over_scale'))} | "
                         f"{_f(v.get('p50_abs_difference_over_scale'))} | "
                         f"{_f(v.get('p95_abs_difference_over_scale'))} | "
                         f"{_f(v.get('p99_abs_difference_over_scale'))} | "
                         f"{_f(v.get('relative_l2'))} | {_f(v.get('weighted_relative_l2'))} | {v.get('worst_point')}"
                         f"{node} | {v.get('worst_coordinates', '-')} | {edge} | {v['result']} |")
        notes = [f"`{var}`: {v['note']}" for var, v in s["variables"].items() if "note" in v]
        notes += [f"`{var}`: rigid offset {v['rigid_offset_removed']:.6g} removed" for var, v in s["variables"].items()
                  if "rigid_offset_removed" in v]
        notes += [f"`{var}`: {v['excluded_points']} points left out (reference not finite: see "
                  "`reference_validity`)" for var, v in s["variables"].items() if v.get("excluded_points")]
        lines += [""] + [f"- {n}" for n in notes] + ([""] if notes else [])
    if conv is not None:
        lines += ["## Convergence", "", f"- meshes: {', '.join(conv['meshes'])}",
                  f"- mesh size h: {conv['h_definition']}: " + ", ".join(f"{h:.4g}" for h in conv["h"]),
                  f"- edges where the exact field is not smooth: {conv['edges']}",
                  f"- expected orders: {conv['expected']}",
                  "- remainder: Richardson-style estimate of the difference left as h -> 0 (near 0: "
                  "discretisation error only)", "",
                  "| variable | statistic | errors (coarse to fine) | orders | fitted order | remainder |",
                  "|---|---|---|---|---|---|"]
        for var, row in conv["variables"].items():
            for key, o in row.items():
                lines.append(f"| `{var}` | {key} | {', '.join(_f(e) for e in o['errors'])} | "
                             f"{', '.join(f'{p:.3f}' for p in o['orders'])} | {o['fitted_order']:.3f} | "
                             f"{_f(o['richardson_remainder'])} |")
        lines.append("")
    lines += [plots, ""]
    return "\n".join(lines)


def plot_table(ds: xr.Dataset, path: Path) -> None:
    """Per variable |Δ| / S over the nodes, depth downward (the horizontal axis the radius or x),
    zoomed on the nodes of the largest differences (those above half the largest, with a margin)."""
    from ..plot import require_matplotlib, save_figure

    plt = require_matplotlib()
    names = ds.attrs["compare_variables"].split()
    unit, to_user = _user_length(ds)
    x = ds["x"].values / to_user if "x" in ds.coords else np.zeros(ds.sizes["point"])
    y = ds["y"].values / to_user if "y" in ds.coords else np.zeros_like(x)
    z = ds["z"].values / to_user if "z" in ds.coords else np.zeros_like(x)
    horizontal = np.hypot(x, y) if np.ptp(y) > 0 else x
    cols = min(len(names), 2)
    rows = -(-len(names) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(5.0 * cols, 3.8 * rows), squeeze=False)
    for ax, name in zip(axes.flat, names):
        ratio = np.abs(ds[f"{name}_difference"].values / ds[f"{name}_scale"].values)
        ratio = np.where(np.isfinite(ratio), ratio, np.nan)
        art = ax.scatter(horizontal, z, c=ratio, s=10, cmap="viridis")
        fig.colorbar(art, ax=ax, label="|Δ| / S")
        big = np.isfinite(ratio) & (ratio >= 0.5 * np.nanmax(ratio)) if np.isfinite(ratio).any() else None
        if big is not None and big.any():
            h0, h1, z0, z1 = horizontal[big].min(), horizontal[big].max(), z[big].min(), z[big].max()
            # the largest differences and their surroundings: at least 15 % of the model's extent
            pad = max(0.5 * (h1 - h0), 0.5 * (z1 - z0), 0.15 * max(np.ptp(horizontal), np.ptp(z)), 1e-300)
            ax.set_xlim(h0 - pad, h1 + pad)
            ax.set_ylim(z0 - pad, z1 + pad)
        ax.invert_yaxis()       # depth downward, as the body lies
        ax.set(xlabel=("r" if np.ptp(y) > 0 else "x") + ("" if unit == "1" else f" [{unit}]"),
               ylabel="depth z" + ("" if unit == "1" else f" [{unit}]"))
        worst = ds.attrs.get(f"compare_{name}_max_abs_difference_over_scale", math.nan)
        ax.set_title(f"{name}: max |Δ|/S = {worst:.3g} (zoomed on the largest)", fontsize=8)
    for ax in list(axes.flat)[len(names):]:
        ax.set_visible(False)
    fig.tight_layout()
    save_figure(fig, plt, path)


def _user_length(ds: xr.Dataset) -> tuple[str, float]:
    """The unit the user gave the coordinates in, and its factor to the recipe's."""
    from .units import UnitProblem, factor

    for c in ("x", "z", "y"):
        if c in ds.coords:
            target = ds[c].attrs.get("units", "1")
            given = ds[c].attrs.get("user_units")
            if given:
                try:
                    return given, factor(given, target, c)
                except UnitProblem:
                    break
            return target, 1.0
    return "1", 1.0


def plot_convergence(conv: dict, path: Path) -> None:
    """Error against mesh size on log axes, per variable: RMS and max of |Δ| / S."""
    from ..plot import require_matplotlib, save_figure

    plt = require_matplotlib()
    fig, ax = plt.subplots(figsize=(6, 4.5))
    h = np.asarray(conv["h"])
    for var, row in conv["variables"].items():
        for key, style in (("rms", "o-"), ("max", "s--"), ("energy", "^-")):
            if key in row and np.all(np.asarray(row[key]["errors"]) > 0):
                ax.loglog(h, row[key]["errors"], style, ms=4,
                          label=f"{var} {key} (order {row[key]['fitted_order']:.2f})")
    ax.set(xlabel="mesh size h", ylabel="|Δ| / S", title="convergence against the reference")
    ax.legend(fontsize=6)
    fig.tight_layout()
    save_figure(fig, plt, path)

