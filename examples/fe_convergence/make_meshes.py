"""Write a synthetic three-mesh convergence study of Hertz: the surface nodes of an axisymmetric
(r, z) model in mm and N/mm^2 as an FE code exports them (an Abaqus-style CSV, and a VTU), on meshes
of h = a/4, a/8, a/16.

The "FE" values are the exact Hertz surface pressure p0 sqrt(1 - r^2/a^2) plus a smooth synthetic
error 0.5 (h/a)^1.5 p_m sin(3 r/a) (a discretisation error of order 1.5), and at the node on the
contact edge r = a an error 0.3 (h/a)^0.5 p_m, which falls as a real mesh's does there. Run from
this folder:

    python make_meshes.py          # writes L1.csv, L2.csv, L3.csv (and L*.vtu with meshio installed)
"""
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
A_MM = 0.1                      # contact radius a (recipe.toml: R = 10 mm, delta = 1 um)


def mean_pressure_mpa() -> float:
    """p_m = (4/(3 pi)) E* a / R with E* = E/(1 - nu^2) (Hertz), in MPa."""
    e_star = 210e3 / (1 - 0.3 ** 2)
    return 4.0 / (3.0 * np.pi) * e_star * A_MM / 10.0


def mesh(level: int):
    """Surface nodes r in [0, 2a], z = 0, spaced h = a / 2^(level+1)."""
    h = A_MM / 2 ** (level + 1)
    r = np.arange(0.0, 2 * A_MM + h / 2, h)
    return h, r


def values(h: float, r: np.ndarray) -> np.ndarray:
    pm = mean_pressure_mpa()
    rho = r / A_MM
    exact = -1.5 * pm * np.sqrt(np.clip(1.0 - rho ** 2, 0.0, None))      # sigma_zz at the surface
    smooth = 0.5 * (h / A_MM) ** 1.5 * pm * np.sin(3.0 * rho)
    edge = np.where(np.abs(rho - 1.0) < 1e-9, 0.3 * (h / A_MM) ** 0.5 * pm, 0.0)      # the node at r = a
    return exact + smooth + edge


def main() -> None:
    for level in (1, 2, 3):
        h, r = mesh(level)
        szz = values(h, r)
        rows = "\n".join(f"{k + 1},{a:.9g},0,{s:.10g}" for k, (a, s) in enumerate(zip(r, szz)))
        (HERE / f"L{level}.csv").write_text("Node Label,r(mm),z(mm),sigma_zz(N/mm^2)\n" + rows + "\n")
        try:
            import meshio
        except ImportError:
            continue
        pts = np.column_stack([r, np.zeros_like(r), np.zeros_like(r)])
        lines = np.column_stack([np.arange(len(r) - 1), np.arange(1, len(r))])
        meshio.write(HERE / f"L{level}.vtu", meshio.Mesh(pts, [("line", lines)], point_data={"sigma_zz": szz}))


if __name__ == "__main__":
    main()
