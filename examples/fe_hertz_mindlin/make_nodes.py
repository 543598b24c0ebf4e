"""Write nodes.csv: synthetic "FE" results of recipe.toml at 200 scattered nodes.

The values are the stressfields reference plus a known error: a smooth field of about 1e-3 p_m
(what a fine mesh leaves) on every stress component, and one planted error of 5e-2 p_m on sigma_xx
at one node. p_m comes from Hertz's formula, not from the reference, so that the planted error's
size is known independently of the code that reports it. Seeded: the committed nodes.csv is this
script's output (python examples/fe_hertz_mindlin/make_nodes.py).
"""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
SEED = 20261125
N_SURFACE, N_BELOW = 80, 120
VARIABLES = ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz")
#: the planted error: this variable, at this node (row index from 0), this many p_m
PLANTED_VARIABLE, PLANTED_INDEX, PLANTED_SIZE = "sigma_xx", 137, 5e-2
SMOOTH_SIZE = 1e-3
#: node identities as an FE export numbers them
FIRST_NODE_ID = 1001


def parameters() -> dict:
    return tomllib.loads((HERE / "recipe.toml").read_text())["parameters"]


def hertz() -> tuple[float, float]:
    """Contact radius a = sqrt(R delta) and mean pressure p_m = 4 E* sqrt(delta/R) / (3 pi) (Hertz)."""
    p = parameters()
    e_star = p["E"] / (1 - p["nu"] ** 2)
    return math.sqrt(p["R"] * p["delta"]), 4 * e_star * math.sqrt(p["delta"] / p["R"]) / (3 * math.pi)


def nodes() -> dict[str, np.ndarray]:
    """Node coordinates in mm, rounded to the 6 decimals written (the file's values are exact)."""
    rng = np.random.default_rng(SEED)
    a_mm = hertz()[0] * 1e3
    n = N_SURFACE + N_BELOW
    x = rng.uniform(-2 * a_mm, 2 * a_mm, n)
    y = rng.uniform(-2 * a_mm, 2 * a_mm, n)
    z = np.concatenate([np.zeros(N_SURFACE), rng.uniform(0.05 * a_mm, 2 * a_mm, N_BELOW)])
    return {k: np.array([float(f"{v:.6f}") for v in c]) for k, c in (("x", x), ("y", y), ("z", z))}


def offsets(x_mm, y_mm, z_mm) -> dict[str, np.ndarray]:
    """The known error of each variable, divided by p_m: smooth everywhere, plus the planted one."""
    a_mm = hertz()[0] * 1e3
    u, v, w = np.asarray(x_mm) / a_mm, np.asarray(y_mm) / a_mm, np.asarray(z_mm) / a_mm
    out = {}
    for k, name in enumerate(VARIABLES):
        out[name] = SMOOTH_SIZE * np.sin(0.5 * math.pi * u + k) * np.cos(0.5 * math.pi * v) * np.exp(-w)
    out[PLANTED_VARIABLE][PLANTED_INDEX] += PLANTED_SIZE
    return out


def main() -> Path:
    import stressfields as sf

    xyz = nodes()
    recipe = {"scenario": "parabolic", "parameters": parameters(),
              "points": {k: v * 1e-3 for k, v in xyz.items()},       # mm -> m, as `compare` converts
              "output": {"variables": list(VARIABLES)}}
    ref = sf.generate(recipe).compute()
    p_m = hertz()[1]
    off = offsets(xyz["x"], xyz["y"], xyz["z"])
    columns = {"node": np.arange(FIRST_NODE_ID, FIRST_NODE_ID + len(xyz["x"]))}
    columns.update({f"{k}[mm]": v for k, v in xyz.items()})
    columns.update({f"{n}[MPa]": (ref[n].values + off[n] * p_m) / 1e6 for n in VARIABLES})
    lines = [",".join(columns)]
    for i in range(len(xyz["x"])):
        lines.append(",".join(f"{c[i]}" if c.dtype.kind == "i" else f"{c[i]:.6f}" if "mm" in k else f"{c[i]:.10g}"
                              for k, c in columns.items()))
    path = HERE / "nodes.csv"
    path.write_text("\n".join(lines) + "\n")
    return path


if __name__ == "__main__":
    print(main())
