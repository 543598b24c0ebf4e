"""Oracle-free checks of a stress field below the surface, shared by the interior tests: the
equilibrium and Beltrami–Michell residuals by central differences (they fall like h^2 for a field
that solves the equations of elasticity)."""
import numpy as np

NU = 0.3
RNG = np.random.default_rng(7)
#: scattered interior points (x, y, z), z away from the surface
POINTS = np.column_stack([RNG.uniform(-1.6, 1.6, 10), RNG.uniform(-1.6, 1.6, 10), RNG.uniform(0.15, 1.6, 10)])
ROWS = [("xx", "xy", "xz"), ("xy", "yy", "yz"), ("xz", "yz", "zz")]


def tensor(f, p, nu=NU):
    """The field f(x, y, z, nu) -> {component: array} as 3 x 3 tensors at the points p."""
    s = f(p[..., 0], p[..., 1], p[..., 2], nu)
    return np.stack([np.stack([s[c] for c in row], -1) for row in ROWS], -2)


def residuals(f, h, p=POINTS, nu=NU):
    """max |div sigma| and max |Beltrami–Michell residual| by central differences of step h."""
    e = np.eye(3)
    t = lambda q: tensor(f, q, nu)
    div = sum((t(p + h * e[j])[..., :, j] - t(p - h * e[j])[..., :, j]) / (2 * h) for j in range(3))
    bm = sum((t(p + h * e[k]) - 2 * t(p) + t(p - h * e[k])) / h ** 2 for k in range(3))
    tr = lambda q: np.trace(t(q), axis1=-2, axis2=-1)
    for i in range(3):
        for j in range(3):
            d2 = (tr(p + h * e[i] + h * e[j]) - tr(p + h * e[i] - h * e[j]) - tr(p - h * e[i] + h * e[j])
                  + tr(p - h * e[i] - h * e[j])) / (4 * h * h)
            bm[:, i, j] += d2 / (1 + nu)
    return np.abs(div).max(), np.abs(bm).max()
