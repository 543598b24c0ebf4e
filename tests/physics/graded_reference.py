"""The graded reference points (tests/data/graded_power_law.json), shared by the graded physics
tests."""
from conftest import load_reference

REF = load_reference("graded_power_law")


def nu_of(case) -> float:
    """The case's Poisson ratio; "1/(2+k)" is the Holl ratio."""
    return 1.0 / (2.0 + case["k"]) if case["nu"] == "1/(2+k)" else float(case["nu"])


# ---------------------------------------------------------------- independent routes (scipy quadpack)
# Used by test_graded_contract.py; none of them calls the package.

def _quad(f, lo, hi, **kw):
    from scipy.integrate import quad
    return quad(f, lo, hi, epsabs=0.0, epsrel=2e-14, limit=400, **kw)[0]


def kappa_minus_one_ref(n, k):
    """kappa(n, k) - 1 = (n/2) int_0^inf (1 - e^-y)^(n/2-1) e^-y expm1(q y) dy, q = (1-k)/2
    (eq. 9 with 1 - t^2 = e^-y): a positive integrand, no cancellation as k -> 1."""
    import math
    q, h = 0.5 * (1.0 - k), 0.5 * n

    def near(y):   # the factor y^(h-1) is the quadpack weight
        return h * ((-math.expm1(-y) / y) if y > 0 else 1.0) ** (h - 1.0) * math.exp(-y) * math.expm1(q * y)

    def far(y):
        tail = math.exp(-y) * math.expm1(q * y) if y < 600 else math.exp(-(1.0 - q) * y)
        return h * (-math.expm1(-y)) ** (h - 1.0) * tail

    return _quad(near, 0.0, 1.0, weight="alg", wvar=(h - 1.0, 0.0)) + _quad(far, 1.0, math.inf)


def uz_outside_ref(rho, k, n):
    """u_z/(kappa A_n a^n) for rho = r/a >= 1 by quadrature of eq. (15) (docs/theory/graded.md (G20)):
    (2/pi) cos(k pi/2) int_0^1 xi^k (1 - xi^n) (rho^2 - xi^2)^(-(1+k)/2) dxi, in w = 1 - xi, the
    interval cut geometrically around the edge distance rho - 1 (exact for rho in [1, 2])."""
    import math
    d = rho - 1.0

    def f(w):
        one_minus = 1.0 if w >= 1.0 else -math.expm1(n * math.log1p(-w))
        return one_minus * (d + w) ** (-0.5 * (1 + k)) * (rho + 1.0 - w) ** (-0.5 * (1 + k))

    cuts, x = [0.0], max(d, 1e-300)
    while x < 1.0:
        if x > 1e-30:
            cuts.append(x)
        x *= 8.0
    cuts.append(1.0)
    total = 0.0
    for lo, hi in zip(cuts[:-1], cuts[1:]):
        if hi == 1.0:
            total += _quad(f, lo, hi, weight="alg", wvar=(0.0, k))
        else:
            total += _quad(lambda w: f(w) * (1.0 - w) ** k, lo, hi)
    return 2.0 / math.pi * math.sin(0.5 * math.pi * (1.0 - k)) * total


def stick_zone_ref(rho, fx, k, n):
    """J(rho) = int_c^1 xi^(n-1) (xi^2 - rho^2)^(-(1-k)/2) dxi for 0 <= rho <= c = c/a < 1: the shear
    traction in the stick zone over mu (c_N* n kappa A_n / pi) a^(n+k-1) (eq. 45 written as one
    integral, docs/theory/graded.md (G45)).  In v = xi - c, with the slip width D = 1 - c from (G33)
    without rounding and the distance c - rho = (1 - rho) - D; the interval cut geometrically
    around that distance (the kernel's near-singular end)."""
    import math
    D = -math.expm1(math.log1p(-fx) / (n + k + 1.0))
    delta = (1.0 - rho) - D
    alpha = -0.5 * (1.0 - k)

    def f(v):      # without the factor (delta + v)^alpha
        xi = (1.0 - D) + v
        return xi ** (n - 1.0) * (xi + rho) ** alpha

    cuts, x = [0.0], max(delta, 1e-300)
    while x < D:
        if x > 1e-30 * D:
            cuts.append(x)
        x *= 8.0
    cuts.append(D)
    total = 0.0
    for lo, hi in zip(cuts[:-1], cuts[1:]):
        if lo == 0.0 and delta == 0.0:
            total += _quad(f, lo, hi, weight="alg", wvar=(alpha, 0.0))
        else:
            total += _quad(lambda v: f(v) * (delta + v) ** alpha, lo, hi)
    return total
