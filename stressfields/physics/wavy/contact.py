"""The wavy (multisinusoidal) contact: its pressure, displacements, per-contact quantities and the field below.

Tsukanov, I. Yu. (2018) "Partial contact of a rigid multisinusoidal wavy surface with an elastic
half-plane", Advances in Tribology 2018, 8431467, doi:10.1155/2018/8431467, with the equations,
stable forms and errata of docs/theory/wavy.md (W1).  Plane strain, frictionless, rigid
indenter, prescribed contact half-width a, continuous contact.

Common arguments
----------------
x_over_a : array, x/a (any real; pressure is 0 for |x/a| > 1).
two_a_over_lambda1 : array, 2a/lambda_1 in (0, 1).
amplitudes, wavenumbers : 1-D harmonic table, gap g(x) = sum_i Delta_i (1 - cos(2 pi n_i x/lambda_1));
    row 0 is the base wave (n = 1, Delta_1 > 0).  Only Delta_i/Delta_1 matters.
periodic : True for the periodic surface (cot kernel), False for a single indenter (Cauchy kernel).
n_harmonics : optional int array, use the first N rows of the table (default: all).
rtol : tolerance: |error| <= rtol * max(|value|, p*) (see ``series``).
max_terms : cap on the number of series terms (per contact width).

All array arguments broadcast together.  Normalisation, docs/theory/wavy.md (W2): p* = pi E* Delta_1/lambda_1
with E* = E/(1 - nu^2); lengths u_z, gap in units of Delta_1; x in units of a.
Series quantities return ``(value, info)`` with info = {"n_terms", "error_estimate",
"converged"} broadcast to the value's shape: n_terms sine terms were summed (highest order
2*n_terms - 1); error_estimate (in the value's units) = bound of the truncated tail + an estimate
of rounding, an upper bound of |error|; converged = error_estimate <= rtol * p* (docs/theory/wavy.md (W22),
(W23)).
When rtol cannot be met (2a/lambda_1 -> 1 with the length capped at max_terms, or rtol below
rounding) the best value is returned with converged = False and the honest estimate.
"""

from __future__ import annotations

import numpy as np

from . import nonperiodic, periodic
from . import periodic as _periodic
from . import profile as _profile
from . import interior as _interior
from . import series, validity

DEFAULT_RTOL = 1e-12
DEFAULT_MAX_TERMS = 16384


class _Context:
    """Inputs validated, coefficient table built once, element -> table row map."""

    def __init__(self, two_a_over_lambda1, amplitudes, wavenumbers, periodic_, n_harmonics,
                 rtol, max_terms, build=True, weighted=False):
        self.dr, self.n = _profile.harmonic_table(amplitudes, wavenumbers)
        self.a_in = _profile.contact_angle(two_a_over_lambda1)
        self.N_in = _profile.harmonic_counts(n_harmonics, len(self.n))
        self.mod = periodic if periodic_ else nonperiodic
        self.periodic = bool(periodic_)
        ua, ia = np.unique(self.a_in, return_inverse=True)
        uN, iN = np.unique(self.N_in, return_inverse=True)
        self.ua, self.uN = ua, uN
        self.row = np.asarray(ia).reshape(self.a_in.shape) * len(uN) + np.asarray(iN).reshape(self.N_in.shape)
        self.table = None
        if build and self.periodic:   # closed form (W30): no series, converges for every 2a/lambda_1
            self.table = periodic.build_table(ua, uN, self.dr, self.n, rtol=rtol)
        elif build:
            self.table = series.build_table(ua, uN, self.dr, self.n, is_periodic=False,
                                            rtol=rtol, max_terms=max_terms, weighted=weighted)
        self._outside = None
        self.interior = None      # the periodic potential below the surface, built when first needed
        self.rtol = rtol

    def info(self, shape, rows=None, err=None):
        rows = self.row if rows is None else rows
        t = self.table
        e = t.err[rows] if err is None else err
        return {"n_terms": np.broadcast_to(t.K[rows], shape).copy(),
                "error_estimate": np.broadcast_to(e, shape).copy(),
                "converged": np.broadcast_to(t.converged[rows], shape).copy()}

    def outside(self, rows):
        """Periodic outside-contact integral table for the (unique) rows needed."""
        rows = np.unique(rows)
        if self._outside is None or not np.isin(rows, self._outside.rows).all():
            self._outside = periodic.OutsideTable(self.table, self.dr, self.n, rows)
        return self._outside


def _ctx(two_a, amplitudes, wavenumbers, periodic_, n_harmonics, rtol, max_terms, build=True, weighted=False):
    return _Context(two_a, amplitudes, wavenumbers, periodic_, n_harmonics, rtol, max_terms, build, weighted)


# --------------------------------------------------------------------------------- pressure

def pressure(x_over_a, two_a_over_lambda1, amplitudes, wavenumbers, *, periodic: bool,
             n_harmonics=None, rtol=DEFAULT_RTOL, max_terms=DEFAULT_MAX_TERMS, substitute=False,
             contact_points=None):
    """Contact pressure p(x)/p*, zero for |x| > a.

    Periodic: eqs. (10)-(12) with coefficients by DCT (docs/theory/wavy.md (W6), (W7)); non-periodic:
    Bessel series eq. (14), docs/theory/wavy.md (W8).  Combined with E* (not the printed
    E/(2(1-nu^2))), docs/theory/wavy.md (W5), into the sine series of docs/theory/wavy.md (W9).
    Returns (p_over_pstar, info).

    ``substitute=True`` (periodic only) evaluates the non-periodic series (eq. 14: ~30 ns cheaper
    per point, a third) for every contact whose periodic correction (``periodic_correction``) plus
    the non-periodic series error stays within the periodic series' own tolerance, rtol * scale,
    and that has at least ``SUBSTITUTE_MIN_POINTS`` points inside it (the test costs ~2 ms per
    contact); info then has "substituted" (bool), and error_estimate includes the correction there
    (docs/theory/wavy.md (W26)).  ``contact_points`` (broadcasting with two_a_over_lambda1 and
    n_harmonics) is that number of points as the caller counts it over its whole evaluation, so that
    the choice, and every value, is the same however the caller cuts its points into calls; by
    default the points of this call inside each contact are counted.
    """
    c = _ctx(two_a_over_lambda1, amplitudes, wavenumbers, periodic, n_harmonics, rtol, max_terms)
    shape, t, row, a = _reduced(c, x_over_a)      # periodic: folded into one period (|x| <= pi)
    p = np.zeros(shape)
    inside = t <= 1.0
    if not periodic:
        p[inside] = series.sine_sum(c.table, row[inside], c.mod.theta_of_t(t[inside], a[inside]))
        return p, c.info(shape, row)
    if not substitute:
        p[inside] = _periodic.closed_pressure(c.table, row[inside], t[inside])
        return p, c.info(shape, row)
    if contact_points is None:
        many = np.bincount(np.ravel(row[inside]), minlength=c.table.K.size) >= SUBSTITUTE_MIN_POINTS
    else:
        count = np.zeros(c.table.K.size)
        np.maximum.at(count, np.ravel(c.row), np.ravel(np.broadcast_to(contact_points, c.row.shape)))
        many = count >= SUBSTITUTE_MIN_POINTS
    use, err = _substitution(c, many, amplitudes, wavenumbers, rtol, max_terms)
    sub = np.broadcast_to(use[c.row], shape)
    own = inside & ~sub
    p[own] = _periodic.closed_pressure(c.table, row[own], t[own])
    part = inside & sub
    if part.any():
        ctx = _ctx(two_a_over_lambda1, amplitudes, wavenumbers, False, n_harmonics, rtol, max_terms)
        p[part] = series.sine_sum(ctx.table, row[part], ctx.mod.theta_of_t(t[part], a[part]))
    info = c.info(shape, row, err[row])
    info["substituted"] = sub.copy()
    return p, info


#: Chebyshev nodes on which the periodic correction is resolved (it is smooth and even in x/a)
_PROBES = 32
#: cos(pi k (j + 1/2) / _PROBES): row k, column j, the type-II DCT on the probes
_DCT = np.cos(np.pi * np.arange(_PROBES)[:, None] * (np.arange(_PROBES)[None, :] + 0.5) / _PROBES)
#: points inside a contact from which substituting pays: ~2 ms of test and table against ~30 ns
#: saved per point (measured, one and three harmonics, 2a/lambda_1 = 1e-4 and 1e-3)
SUBSTITUTE_MIN_POINTS = 100_000


def periodic_correction(two_a_over_lambda1, amplitudes, wavenumbers, *, n_harmonics=None, rtol=DEFAULT_RTOL,
                        max_terms=DEFAULT_MAX_TERMS):
    """Bound on max over |x| <= a of |p_periodic(x) - p_nonperiodic(x)|/p* for the same contact,
    docs/theory/wavy.md (W26).

    The two solutions differ by the smooth part of the periodic kernel, (1/2)cot(y/2) - 1/y =
    -y/12 - ..., so the difference of phi = p/sqrt(1 - (x/a)^2) is smooth: it is interpolated on
    32 Chebyshev nodes from both series (at rtol/100), and the bound is the sum of its Chebyshev
    coefficients' magnitudes plus the sampled series errors times the Lebesgue constant plus
    four times the last coefficients (the interpolation error). It grows like (2a/lambda_1)^2:
    about 0.4 (2a/lambda_1)^2 of the pressure. +inf where the interpolant is not resolved.
    Returns (bound, info) with info["scale"] = the periodic series' rtol scale.
    """
    c = _ctx(two_a_over_lambda1, amplitudes, wavenumbers, True, n_harmonics, rtol, max_terms)
    shape = c.row.shape
    s = np.cos(np.pi * (np.arange(_PROBES) + 0.5) / _PROBES)
    w = (c.ua[:, None] / np.pi * np.ones(len(c.uN)))              # unique rows (a, N), row-major
    N = np.ones(len(c.ua))[:, None] * c.uN[None, :]
    w, N = w.reshape(-1), N.reshape(-1).astype(int)
    probe_rtol = max(rtol * 1e-2, 1e-15)
    kw = dict(n_harmonics=N[None, :], rtol=probe_rtol, max_terms=max_terms)
    phi_p, ip = pressure_shape(s[:, None], w[None, :], amplitudes, wavenumbers, periodic=True, **kw)
    phi_n, inp = pressure_shape(s[:, None], w[None, :], amplitudes, wavenumbers, periodic=False, **kw)
    # the Chebyshev coefficients (a type-II DCT) as a plain sum down the probes: each contact's
    # coefficients then do not depend on which other contacts share the array (scipy's DCT of a
    # 2-D array rounds differently with the number of columns: 1.4e-15 measured), so neither does
    # the file's content hash on the chunking
    # (numpy's sum over an axis is pairwise or sequential depending on the array's shape: with one
    # column it groups the probes differently, so the sums run in a fixed order, series.row_dot)
    coef = (2.0 / _PROBES) * series.row_dot(_DCT[:, None, :] * (phi_p - phi_n).T[None, :, :], np.ones(_PROBES))
    coef[0] *= 0.5
    lebesgue = 2.0 / np.pi * np.log(_PROBES) + 1.0
    noise = lebesgue * np.max(ip["error_estimate"] + inp["error_estimate"], axis=0)
    tail = 4.0 * series.row_sum(np.abs(coef[-6:]).T)
    bound = series.row_sum(np.abs(coef).T) + noise + tail
    resolved = tail <= 1e-2 * np.maximum(bound, 1e-300) + 1e-15
    bound = np.where(resolved & np.all(ip["converged"] & inp["converged"], axis=0), bound, np.inf)
    return bound[c.row].reshape(shape), {"scale": c.table.scale[c.row].reshape(shape)}


def _substitution(c, candidates, amplitudes, wavenumbers, rtol, max_terms):
    """Per row of the periodic context c: (use the non-periodic series?, error estimate then).

    Only candidate rows with (2a/lambda_1)^2 <= 4 rtol are tested: the correction is 0.41-0.44
    (2a/lambda_1)^2 of the series scale (one and three harmonics, 2a/lambda_1 from 1e-5 to 0.3), so
    wider contacts do not qualify and testing them would only cost time."""
    use = np.zeros(c.table.K.shape, dtype=bool)
    err = c.table.err.copy()
    w = c.table.a / np.pi
    probe = candidates & (w * w <= 4.0 * rtol) & c.table.converged
    if probe.any():
        N = c.table.N[probe]
        bound, _ = periodic_correction(w[probe], amplitudes, wavenumbers, n_harmonics=N, rtol=rtol,
                                       max_terms=max_terms)
        nonper = _ctx(w[probe], amplitudes, wavenumbers, False, N, rtol, max_terms)
        total = bound + nonper.table.err[nonper.row]
        ok = (total <= rtol * c.table.scale[probe]) & nonper.table.converged[nonper.row]
        use[probe] = ok
        err[np.flatnonzero(probe)[ok]] = total[ok]
    return use, err


def pressure_shape(x_over_a, two_a_over_lambda1, amplitudes, wavenumbers, *, periodic: bool,
                   n_harmonics=None, rtol=DEFAULT_RTOL, max_terms=DEFAULT_MAX_TERMS):
    """phi = p(x)/sqrt(1 - (x/a)^2) / p*, defined for |x/a| <= 1 only (ValueError otherwise).

    At |x| = a it is the edge coefficient K/p*: nonperiodic K = E* sum_i Delta_i n_i (a n_i/2) J_0(a n_i),
    periodic K = sqrt(a/(2 tan(a/2))) dW/da / pi, docs/theory/wavy.md (W19).  Its sign is test (P) of
    docs/theory/wavy.md (W20).
    info["error_estimate"] bounds the series error of phi.
    """
    c = _ctx(two_a_over_lambda1, amplitudes, wavenumbers, periodic, n_harmonics, rtol, max_terms, weighted=True)
    t = np.abs(np.asarray(x_over_a, dtype=float))
    if np.any(~(t <= 1.0)):
        raise ValueError("pressure_shape is defined for |x_over_a| <= 1 only")
    shape = np.broadcast(t, c.row).shape
    t, row, a = (np.ravel(v) for v in np.broadcast_arrays(t, c.row, c.a_in))
    if c.periodic:
        phi = _periodic.closed_shape(c.table, row, t).reshape(shape)
        row = row.reshape(shape)
        return phi, c.info(shape, row, c.table.err_shape[row])
    th = c.mod.theta_of_t(t, a)
    phi = (series.sine_sum(c.table, row, th, over_sin=True) * c.mod.shape_ratio(t, a)).reshape(shape)
    row = row.reshape(shape)
    return phi, c.info(shape, row, c.table.err_shape[row])


def mean_pressure(two_a_over_lambda1, amplitudes, wavenumbers, *, periodic: bool, n_harmonics=None):
    """Mean (nominal) pressure p_inf/p*, p_inf = (1/lambda_1) int_{-a}^{a} p dx (eq. 6),
    docs/theory/wavy.md (W10).

    Closed forms, no series: non-periodic eq. (16), docs/theory/wavy.md (W12); periodic the Legendre
    form docs/theory/wavy.md (W11) (not in the paper).  For a single indenter p_inf is the load per
    unit length divided by lambda_1.
    """
    c = _ctx(two_a_over_lambda1, amplitudes, wavenumbers, periodic, n_harmonics, 1.0, 16, build=False)
    return c.mod.mean_pressure(c.a_in, c.dr, c.n, c.N_in)


def peak_pressure(two_a_over_lambda1, amplitudes, wavenumbers, *, periodic: bool,
                  n_harmonics=None, rtol=DEFAULT_RTOL, max_terms=DEFAULT_MAX_TERMS):
    """p(0)/p*, the paper's p_max (eq. 21 for the non-periodic problem): sum_m (-1)^m D_m,
    docs/theory/wavy.md (W13).  Returns (value, info)."""
    c = _ctx(two_a_over_lambda1, amplitudes, wavenumbers, periodic, n_harmonics, rtol, max_terms)
    t = c.table
    if c.periodic:
        return _periodic.closed_peak(t, c.row), c.info(c.row.shape)
    sign = np.where(np.arange(t.D.shape[1]) % 2 == 0, 1.0, -1.0)
    p0 = series.row_dot(t.D, sign)[c.row]
    return p0, c.info(p0.shape)


def max_pressure(two_a_over_lambda1, amplitudes, wavenumbers, *, periodic: bool,
                 n_harmonics=None, rtol=DEFAULT_RTOL, max_terms=DEFAULT_MAX_TERMS):
    """Global maximum of p over [-a, a]: (p_max/p*, x/a >= 0 where it occurs, info).

    p is even; grid + golden-section search of the truncated series, docs/theory/wavy.md (W14)
    (it is at x = 0 in all the reference cases of tests/data, but not in general for rough
    profiles)."""
    c = _ctx(two_a_over_lambda1, amplitudes, wavenumbers, periodic, n_harmonics, rtol, max_terms)
    rows = np.unique(c.row)
    t_r, v_r = validity.extreme_over_contact(c.table, c.mod, rows, shape=False)
    pos = np.searchsorted(rows, c.row)
    return v_r[pos], t_r[pos], c.info(c.row.shape)


# ----------------------------------------------------------------------------- displacement

def approach(two_a_over_lambda1, amplitudes, wavenumbers, *, periodic: bool, n_harmonics=None):
    """delta/Delta_1 = u_z(0)/Delta_1 with C = 0 in eq. (5) (datum as in ``displacement``).
    Closed forms from Betti's theorem, docs/theory/wavy.md (W16) (see periodic.approach,
    nonperiodic.approach)."""
    c = _ctx(two_a_over_lambda1, amplitudes, wavenumbers, periodic, n_harmonics, 1.0, 16, build=False)
    return c.mod.approach(c.a_in, c.dr, c.n, c.N_in)


def _outside_gap(c, row, t, a):
    """gap/Delta_1 for |x| > a (x already reduced to a < |x| <= pi for the periodic problem)."""
    tau = np.sqrt(np.clip((t - 1.0) * a / (np.pi - a), 0.0, None))
    return validity.gap_outside(c.table, c.outside(row) if c.periodic else None, row, tau, c.dr, c.n)


def _reduced(c, x_over_a):
    """|x|/a after folding the periodic problem into one period (|x| <= pi)."""
    t = np.abs(np.asarray(x_over_a, dtype=float))
    shape = np.broadcast(t, c.row).shape
    t, row, a = (np.array(v) for v in np.broadcast_arrays(t, c.row, c.a_in))
    if c.periodic:
        # only points beyond half a period move: folding in x (t a + pi - pi) would round t by
        # eps pi/a, i.e. 1e-7 p* next to the edge of a contact with 2a/lambda_1 = 0.01 (measured)
        k = np.round(t * a / (2.0 * np.pi))
        t = np.where(t * a > np.pi, np.abs(t - k * (2.0 * np.pi / a)), t)
    return shape, t, row, a


def separation(x_over_a, two_a_over_lambda1, amplitudes, wavenumbers, *, periodic: bool,
               n_harmonics=None, rtol=DEFAULT_RTOL, max_terms=DEFAULT_MAX_TERMS):
    """Gap after loading, (g(x) + u_z(x) - u_z(0))/Delta_1: 0 inside the contact; negative
    values outside mean the rigid profile would penetrate the surface (test (G)),
    docs/theory/wavy.md (W18).

    Non-periodic: closed form from integrating eq. (14)'s Cauchy transform off the cut,
    (u_z(x) - u_z(a))/Delta_1 = -a sum_m D_m G_{2m+1}(x/a) (validity.gap_outside);
    periodic: the same transform in r = tan(x/2)/tan(a/2), integrated by Gauss-Legendre panels
    (periodic.OutsideTable).  Returns (gap_over_Delta1, info); error_estimate (Delta_1 units) is the
    slope series' error bound times (|x| - a); the panel quadrature error (< 1e-13 against
    Westergaard's closed form and brute-force quadrature in the tests) is not included.
    """
    c = _ctx(two_a_over_lambda1, amplitudes, wavenumbers, periodic, n_harmonics, rtol, max_terms)
    shape, t, row, a = _reduced(c, x_over_a)
    out = np.zeros(shape)
    o = t > 1.0
    if o.any():
        out[o] = _outside_gap(c, row[o], t[o], a[o])
    # |u_z' error| <= tail of sum |D_m| (|w^k| <= 1), integrated over |x| - a
    err = c.table.err[row] * np.maximum(t - 1.0, 0.0) * a
    return out, c.info(shape, row, err)


def displacement(x_over_a, two_a_over_lambda1, amplitudes, wavenumbers, *, periodic: bool,
                 n_harmonics=None, rtol=DEFAULT_RTOL, max_terms=DEFAULT_MAX_TERMS):
    """Surface displacement u_z(x)/Delta_1, positive into the body, eq. (5) with C = 0,
    docs/theory/wavy.md (W15).

    Datum (where the constant is fixed): periodic kernel ln|2 sin((x - xi)/2)|, so u_z has zero
    mean over one period; non-periodic kernel ln|x - xi| with lengths in units where
    lambda_1 = 2 pi (x = 2 pi x_phys/lambda_1), i.e. u_z = -(2/(pi E*)) int p(xi) ln|x - xi| dxi.
    These match tests/data/wavy_tsukanov.json (uz0_over_Delta1).  Inside the contact
    u_z = u_z(0) - g(x) (closed form); outside u_z = u_z(0) - g(x) + gap(x) (see ``separation``).
    Returns (uz_over_Delta1, info).
    """
    c = _ctx(two_a_over_lambda1, amplitudes, wavenumbers, periodic, n_harmonics, rtol, max_terms)
    shape, t, row, a = _reduced(c, x_over_a)
    delta = np.broadcast_to(c.mod.approach(c.a_in, c.dr, c.n, c.N_in), shape)
    N = c.table.N[row]
    uz = delta - _profile.gap(t * a, c.dr, c.n, N)
    o = t > 1.0
    if o.any():
        uz[o] += _outside_gap(c, row[o], t[o], a[o])
    err = c.table.err[row] * np.maximum(t - 1.0, 0.0) * a
    return uz, c.info(shape, row, err)


def initial_gap(x_over_a, two_a_over_lambda1, amplitudes, wavenumbers, *, n_harmonics=None):
    """g(x)/Delta_1 = sum_{i<N} (Delta_i/Delta_1)(1 - cos n_i x), x = a * x_over_a (eq. 3),
    docs/theory/wavy.md (W1)."""
    c = _ctx(two_a_over_lambda1, amplitudes, wavenumbers, True, n_harmonics, 1.0, 16, build=False)
    x = np.asarray(x_over_a, dtype=float) * c.a_in
    return _profile.gap(x, c.dr, c.n, np.broadcast_to(c.N_in, np.broadcast(x, c.N_in).shape))


# --------------------------------------------------------------------------------- validity

def contact_validity(two_a_over_lambda1, amplitudes, wavenumbers, *, periodic: bool,
                     n_harmonics=None, rtol=DEFAULT_RTOL, max_terms=DEFAULT_MAX_TERMS, atol=1e-10):
    """Exact admissibility of the continuous-contact solution, docs/theory/wavy.md (W20).

    Returns a dict of arrays (shape of broadcast(a, N)):
      ok                    -- pressure_ok & gap_ok
      pressure_ok           -- (P) min over [-a, a] of phi = p/sqrt(1 - (x/a)^2) >= -atol  (p* units)
      gap_ok                -- (G) min gap for a < |x| <= pi >= -atol  (Delta_1 units)
      min_phi_over_pstar, x_of_min_phi_over_a
      min_gap_over_Delta1, x_of_min_gap_over_a  (searched from x - a = 1e-6 (pi - a) on)
      edge_phi_over_pstar   -- phi at |x| = a (edge coefficient K/p*)
      n_terms, error_estimate (bound on the series error of phi), converged
    atol absorbs rounding only; the series error is reported, not added.
    """
    c = _ctx(two_a_over_lambda1, amplitudes, wavenumbers, periodic, n_harmonics, rtol, max_terms, weighted=True)
    rows = np.unique(c.row)
    t_phi, v_phi = validity.extreme_over_contact(c.table, c.mod, rows, shape=True)
    outside = c.outside(rows) if c.periodic else None
    t_gap, v_gap = validity.min_gap_outside(c.table, outside, rows, c.dr, c.n)
    if c.periodic:
        edge = _periodic.closed_shape(c.table, rows, np.ones(rows.shape))
    else:
        edge = series.row_dot(c.table.D[rows], 2.0 * np.arange(c.table.D.shape[1]) + 1.0)
    pos = np.searchsorted(rows, c.row)
    take = lambda v: v[pos]
    p_ok, g_ok = v_phi >= -atol, v_gap >= -atol
    inf = c.info(c.row.shape, err=c.table.err_shape[c.row])
    return {"ok": take(p_ok & g_ok), "pressure_ok": take(p_ok), "gap_ok": take(g_ok),
            "min_phi_over_pstar": take(v_phi), "x_of_min_phi_over_a": take(t_phi),
            "min_gap_over_Delta1": take(v_gap), "x_of_min_gap_over_a": take(t_gap),
            "edge_phi_over_pstar": take(edge), **inf}


def continuous_contact(two_a_over_lambda1, amplitudes, wavenumbers, *, periodic: bool,
                       n_harmonics=None, rtol=DEFAULT_RTOL, max_terms=DEFAULT_MAX_TERMS, atol=1e-10):
    """True where the continuous-contact solution is physical: (P) and (G) of docs/theory/wavy.md (W20).
    Boolean array of shape broadcast(two_a_over_lambda1, n_harmonics)."""
    return contact_validity(two_a_over_lambda1, amplitudes, wavenumbers, periodic=periodic,
                            n_harmonics=n_harmonics, rtol=rtol, max_terms=max_terms, atol=atol)["ok"]


def johnson_parameter(two_a_over_lambda1, amplitudes, wavenumbers, *, periodic: bool, n_harmonics=None,
                      per_harmonic=False):
    """Johnson parameter as corrected in docs/theory/wavy.md (W21) (see its errata):

        chi_i = pi E* Delta_i / (lambda_i p_h),  p_h = 2 p_inf lambda_1/(pi a)  (Hertz peak)
              = |Delta_i/Delta_1| n_i a / (4 p_inf/p*)     (a in lambda_1 = 2 pi units),

    p_inf of the chosen problem.  Default: the largest over the ripples 2 <= i <= N (0 where
    N = 1: no ripple on the base wave).  per_harmonic=True: array (..., len(table)) of chi_i
    (i = 1 included; 0 for rows beyond N).  The paper's criterion chi < 1 is a heuristic only --
    neither necessary nor sufficient; decide with ``continuous_contact``.
    """
    c = _ctx(two_a_over_lambda1, amplitudes, wavenumbers, periodic, n_harmonics, 1.0, 16, build=False)
    pinf = c.mod.mean_pressure(c.a_in, c.dr, c.n, c.N_in)
    a = np.broadcast_to(c.a_in, pinf.shape)
    N = np.broadcast_to(c.N_in, pinf.shape)
    chi = np.stack([np.where(N > i, np.abs(c.dr[i]) * c.n[i] * a / (4.0 * pinf), 0.0)
                    for i in range(len(c.n))], axis=-1)
    if per_harmonic:
        return chi
    return np.max(chi[..., 1:], axis=-1) if len(c.n) > 1 else np.zeros(pinf.shape)


# ---------------------------------------------------------------------- paper approximations

def approximate_pressure_eq18(x_over_a, two_a_over_lambda1, amplitudes, wavenumbers, *, n_harmonics=None,
                              n_terms=None):
    """The paper's approximation (18), non-periodic: NOT accurate (exact only at x = 0; errors up
    to 0.9 Delta n, docs/theory/wavy.md (W29)).  For benchmarks of its error only; p/p*, 0 for |x| > a."""
    return _approximate(x_over_a, two_a_over_lambda1, amplitudes, wavenumbers, n_harmonics, 18, n_terms)


def approximate_pressure_eq20(x_over_a, two_a_over_lambda1, amplitudes, wavenumbers, *, n_harmonics=None):
    """The paper's approximation (20) as read in docs/theory/wavy.md (W29), non-periodic: NOT
    accurate (errors 0.15-0.9 Delta n even at x = 0).  For benchmarks of its error only; p/p*."""
    return _approximate(x_over_a, two_a_over_lambda1, amplitudes, wavenumbers, n_harmonics, 20, None)


def _approximate(x_over_a, two_a, amplitudes, wavenumbers, n_harmonics, eq, n_terms):
    from scipy.special import j0, j1, jv

    c = _ctx(two_a, amplitudes, wavenumbers, False, n_harmonics, 1.0, 16, build=False)
    s = np.asarray(x_over_a, dtype=float)
    shape = np.broadcast(s, c.a_in, c.N_in).shape
    s, a, N = np.broadcast_arrays(s, c.a_in, c.N_in)
    root = np.sqrt(np.clip(1.0 - s * s, 0.0, None))
    out = np.zeros(shape)
    for i in range(len(c.n)):
        z = a * c.n[i]
        if eq == 18:
            K = n_terms or int(np.max(z) / 2 + 2 * np.cbrt(np.max(z)) + 20)
            acc = sum(jv(2 * j + 1, z) * np.cos((2 * j + 1) * s) for j in range(K))
        else:
            acc = j1(z) + 0.5 * np.cos((z + 1.0) * np.sin(s)) - 0.5 * j0(z + 1.0)
        out += np.where(N > i, 2.0 * c.dr[i] * c.n[i] * root * acc, 0.0)
    return np.where(np.abs(s) <= 1.0, out, 0.0)


# ----------------------------------------------------------------------- below the surface

#: the fields of ``subsurface`` (the stresses in p*, dpdz in p*/a, shear_traction q/p* at the surface)
SUBSURFACE = ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz", "sigma_1", "sigma_2", "sigma_3", "tau_max",
              "von_mises", "dpdz", "shear_traction")
#: grid of the stick-width search (W43): P(c) tabulated on this many widths before bisection
_STICK_GRID = 256


def stick_half_width(two_a_over_lambda1, amplitudes, wavenumbers, fx, *, periodic: bool, n_harmonics=None):
    """Stick half-width c/a of wavy partial slip (Ciavarella 1998, Jager 1997), docs/theory/wavy.md (W43):
    the largest c <= a with P(c) = (1 - fx) P(a), P the load per period of the same profile at contact
    half-width c (closed forms (W11)/(W12)), fx = Q/(mu P) in [0, 1].

    Returns (c_over_a, admissible): admissible is False where P is not increasing on [c, a] (on the
    search grid), so that the stick zone would not shrink monotonically under the growing load and
    the superposition is not the solution of the loading history."""
    fx = np.asarray(fx, dtype=float)
    c = _ctx(two_a_over_lambda1, amplitudes, wavenumbers, periodic, n_harmonics, 1.0, 16, build=False)
    a, N, fx = np.broadcast_arrays(c.a_in, c.N_in, fx)
    P = lambda ang: c.mod.mean_pressure(ang, c.dr, c.n, N[..., None])
    k = np.arange(1, _STICK_GRID + 1) / _STICK_GRID
    grid = a[..., None] * k
    Pg = P(grid)
    target = (1.0 - fx) * Pg[..., -1]
    below = Pg <= target[..., None]
    # the largest grid width with P <= target: the root lies above it (P(a) >= target)
    idx = np.where(below.any(axis=-1), _STICK_GRID - 1 - np.argmax(below[..., ::-1], axis=-1), -1)
    lo = np.where(idx >= 0, np.take_along_axis(grid, np.maximum(idx, 0)[..., None], -1)[..., 0], 0.0)
    hi = np.take_along_axis(grid, np.minimum(idx + 1, _STICK_GRID - 1)[..., None], -1)[..., 0]
    for _ in range(64):
        mid = 0.5 * (lo + hi)
        low = P(mid[..., None])[..., 0] <= target
        lo, hi = np.where(low, mid, lo), np.where(low, hi, mid)
    cw = np.where(fx <= 0.0, a, np.where(fx >= 1.0, 0.0, 0.5 * (lo + hi)))
    rising = np.diff(Pg, axis=-1) > 0.0
    above = grid[..., :-1] >= cw[..., None] - a[..., None] / _STICK_GRID
    admissible = np.all(rising | ~above, axis=-1)
    return cw / a, admissible


def _interior_ctx(two_a, amplitudes, wavenumbers, periodic_, n_harmonics, rtol, max_terms):
    """The context of the potential: periodic, the closed form (W30) (its bound is the potential's own,
    (W39)); non-periodic, the series truncated on the (2m + 1)-weighted tail at rtol/2, which bounds
    z G' as the plain tail bounds G (W38), so that both together stay within rtol."""
    if periodic_:
        c = _ctx(two_a, amplitudes, wavenumbers, True, n_harmonics, rtol, max_terms)
    else:
        c = _ctx(two_a, amplitudes, wavenumbers, False, n_harmonics, 0.5 * rtol, max_terms, weighted=True)
    c.rtol = rtol
    return c


def subsurface_bound(two_a_over_lambda1, amplitudes, wavenumbers, *, periodic: bool, n_harmonics=None,
                     rtol=DEFAULT_RTOL, max_terms=DEFAULT_MAX_TERMS):
    """Per case, the bound (p* units) of the normal load's stresses below the surface at every depth:
    periodic, the larger of the closed form's and the series' bounds at their switch (W39); single
    indenter, the series tail and rounding of G plus the (2m + 1)-weighted one of z G' (W38)."""
    c = _interior_ctx(two_a_over_lambda1, amplitudes, wavenumbers, periodic, n_harmonics, rtol, max_terms)
    if periodic:
        c.interior = _interior.PeriodicPotential(c.table, c.dr, c.n, rtol)
        return c.interior.err[c.row]
    return (c.table.err + c.table.err_shape)[c.row]


def _potential(c, row, t, zt):
    """(G, dG/dt, err, converged) of the pressure of context c at x/a = t, z/a = zt > 0 for table rows
    ``row`` (1-D arrays of one length), docs/theory/wavy.md (W37), (W38)."""
    if c.periodic:
        if c.interior is None:
            c.interior = _interior.PeriodicPotential(c.table, c.dr, c.n, c.rtol)
        G, Gt, err = c.interior.evaluate(row, t, zt)
        return G, Gt, err, c.interior.converged[row]
    G, Gt, e, es = _interior.nonperiodic_potential(c.table, row, t, zt)
    return G, Gt, e + es, c.table.converged[row]


def _points(c, x_over_a, z_over_a, nu, mu, fx):
    """The points below the surface of context c, flat: (shape, (t, zt, nu, mu, fx, row, a, N)); z >= 0 checked."""
    t = np.asarray(x_over_a, dtype=float)
    zt = np.asarray(z_over_a, dtype=float)
    if np.any(~(zt >= 0.0)) or not np.all(np.isfinite(zt)):
        raise ValueError("z_over_a must be finite and >= 0 (depth into the body)")
    nu, mu, fx = (np.asarray(v, dtype=float) for v in (nu, mu, fx))
    shape = np.broadcast_shapes(t.shape, zt.shape, np.shape(c.row), nu.shape, mu.shape, fx.shape)
    flat = [np.broadcast_to(v, shape).reshape(-1) for v in (t, zt, nu, mu, fx, c.row, c.a_in, c.N_in)]
    return shape, flat


def _not_solved(values, where):
    """``values`` NaN ``where`` the superposition (W43) is not the solution (a stick zone that is not
    admissible): no value of the loading is known there, and a finite one would look plausible."""
    if not np.any(where):
        return values
    return {k: (None if v is None else np.where(where, np.nan, v)) for k, v in values.items()}


def _stick(a, N, mu, fx, amplitudes, wavenumbers, periodic):
    """Per point (flat arrays): whether a tangential load acts, c/a and its admissibility (W43), and whether a
    stick zone remains (the corrective term at width c); one search per distinct case, not per point."""
    shearing = mu * fx > 0.0
    ratio, admissible = np.ones(a.shape), np.ones(a.shape, dtype=bool)
    if shearing.any():
        keys = np.stack([a[shearing], N[shearing], fx[shearing]])
        uniq, inv = np.unique(keys, axis=1, return_inverse=True)
        r_u, ok_u = stick_half_width(uniq[0] / np.pi, amplitudes, wavenumbers, uniq[2], periodic=periodic,
                                     n_harmonics=uniq[1].astype(int))
        ratio[shearing], admissible[shearing] = r_u[inv.reshape(-1)], ok_u[inv.reshape(-1)]
    return shearing, ratio, admissible, shearing & (ratio > 0.0)


def subsurface(names, x_over_a, z_over_a, two_a_over_lambda1, amplitudes, wavenumbers, *, periodic: bool,
               n_harmonics=None, nu=0.3, mu=0.0, fx=0.0, rtol=DEFAULT_RTOL, max_terms=DEFAULT_MAX_TERMS,
               surface_pressure=None):
    """The plane-strain field at (x/a, z/a), z >= 0, docs/theory/wavy.md (W36)-(W43): the fields
    ``names`` (of ``SUBSURFACE``) and an info dict.

    Normal load: the pressure of the domain; tangential load fx = Q/(mu P) in [0, 1] along +x with
    friction coefficient mu: the shear traction q = mu [p(x; a) - p(x; c)] of Ciavarella and Jager,
    c from ``stick_half_width`` (uncoupled: the shear traction does not change the pressure).  At
    z = 0 the surface values: sigma_zz = -p, sigma_xz = -q (``surface_pressure``: the caller's own
    p/p* at these points, so that both agree to the bit; default: ``pressure``).  The mean pressure
    acts at every depth (sigma_xx = sigma_zz = -p_inf as z -> inf, periodic; the k = 0 mode).
    ``shear_traction`` is q/p* of the surface point above (x/a) (independent of z).

    info: "error_estimate" per point (p* units, a bound of the stresses' error), "normal_error" its
    part from the normal pressure (the whole under normal load), "converged" (every potential's own
    bound within rtol: the stresses are then within (1 + 4 mu) rtol p*), "stick_over_a" and
    "stick_admissible" per point's case,
    "dpdz_undefined" per point (at z = 0 on a contact or stick edge the limit of dpdz depends on the
    direction of approach).
    """
    names = tuple(names)
    bad = [n for n in names if n not in SUBSURFACE]
    if bad:
        raise ValueError(f"unknown subsurface field(s) {bad}; allowed: {', '.join(SUBSURFACE)}")
    c = _interior_ctx(two_a_over_lambda1, amplitudes, wavenumbers, periodic, n_harmonics, rtol, max_terms)
    shape, (t, zt, nu, mu, fx, row, a, N) = _points(c, x_over_a, z_over_a, nu, mu, fx)
    shearing, ratio, admissible, sliding = _stick(a, N, mu, fx, amplitudes, wavenumbers, periodic)
    deep = zt > 0.0

    # the potential of the full-width pressure and, under partial slip, of the stick-width one
    # (at z = 0 the routes give the limit z -> 0+; G' is unbounded on the edges, where dpdz is flagged)
    with np.errstate(invalid="ignore", divide="ignore"):
        G, Gt, err, conv = _potential(c, row, t, zt)
    with np.errstate(invalid="ignore"):
        H = np.where(shearing, mu * G, 0.0)
        Ht = np.where(shearing, mu * Gt, 0.0)
    err_h = np.where(shearing, mu * err, 0.0)
    if sliding.any():
        cc = _interior_ctx(a[sliding] / np.pi * ratio[sliding], amplitudes, wavenumbers, periodic, N[sliding], rtol,
                           max_terms)
        k = 1.0 / ratio[sliding]
        with np.errstate(invalid="ignore", divide="ignore"):
            Gc, Gct, ec, okc = _potential(cc, cc.row, t[sliding] * k, zt[sliding] * k)
        H[sliding] -= mu[sliding] * Gc
        Ht[sliding] -= mu[sliding] * k * Gct
        err_h[sliding] += mu[sliding] * ec
        conv[sliding] &= okc
    normal_err = err
    err = err + 2.0 * err_h                      # sigma_xx carries 2 Re H: within (1 + 4 mu) of the bounds
    with np.errstate(invalid="ignore"):
        sxx, szz, sxz = _interior.normal_stresses(G, Gt, zt)
        txx, tzz, txz = _interior.shear_stresses(H, Ht, zt)
        sxx, szz, sxz = sxx + txx, szz + tzz, sxz + txz
        dpdz = -(2.0 / 3.0) * (1.0 + nu) * (Gt.real + Ht.imag)

    surf = ~deep
    q = None
    if surf.any() or "shear_traction" in names:
        p = (pressure(t, a / np.pi, amplitudes, wavenumbers, periodic=periodic, n_harmonics=N, rtol=rtol,
                      max_terms=max_terms)[0] if surface_pressure is None
             else np.broadcast_to(surface_pressure, shape).reshape(-1))
        q = np.where(shearing, mu * p, 0.0)
        if sliding.any():
            pc = pressure(t[sliding] / ratio[sliding], a[sliding] / np.pi * ratio[sliding], amplitudes,
                          wavenumbers, periodic=periodic, n_harmonics=N[sliding], rtol=rtol, max_terms=max_terms)[0]
            q[sliding] -= mu[sliding] * pc
        # at z = 0: sigma_zz = -p, sigma_xz = -q exactly; sigma_xx = -p - 2 Re H (the Hilbert transform of q)
        sxx = np.where(surf, -p - 2.0 * H.real, sxx)
        szz = np.where(surf, 0.0 - p, szz)         # -p, with +0 where p = 0
        sxz = np.where(surf, -q, sxz)
    # on a contact edge (and under partial slip a stick edge) G' is unbounded at z = 0
    undefined = surf & ~np.isfinite(dpdz)
    dpdz = np.where(undefined, np.nan, dpdz)
    syy, s1, s2, s3, tau, vm = _interior.plane_strain_invariants(sxx, szz, sxz, nu)
    values = dict(sigma_xx=sxx, sigma_yy=syy, sigma_zz=szz, sigma_xz=sxz, sigma_1=s1, sigma_2=s2, sigma_3=s3,
                  tau_max=tau, von_mises=vm, dpdz=dpdz, shear_traction=q)
    values = _not_solved(values, shearing & ~admissible)
    info = {"error_estimate": err, "normal_error": normal_err, "converged": conv, "stick_over_a": ratio,
            "stick_admissible": admissible | ~shearing, "dpdz_undefined": undefined}
    shaped = lambda v: np.asarray(v).reshape(shape)
    return {n: shaped(values[n]) for n in names}, {k: shaped(v) for k, v in info.items()}


#: the peak search (W44): a grid of _PEAK_GRID^2 points over the box, then _PEAK_ROUNDS zooms by 4 of a
#: 9 x 9 grid around the best point (spacing 2.5e-2/4^16 ~ 6e-12 of the box: the value's error is
#: second order in the position's)
_PEAK_GRID, _PEAK_ROUNDS = 41, 16
PEAK_DEPTH = 3.0


def subsurface_peaks(two_a_over_lambda1, amplitudes, wavenumbers, *, periodic: bool, n_harmonics=None, nu=0.3,
                     mu=0.0, fx=0.0, rtol=DEFAULT_RTOL, max_terms=DEFAULT_MAX_TERMS):
    """Per case, the largest tau_max and von Mises over 0 <= z/a <= 3 and |x|/a <= 2 (periodic: at most
    half a period; x >= 0 under normal load, by symmetry) and where they sit, docs/theory/wavy.md (W44).

    Returns {"tau_max": (value, x/a, z/a), "von_mises": (...), "on_border": bool, "stick_admissible": bool}
    per case (shape of broadcast(two_a_over_lambda1, n_harmonics, nu, mu, fx)); on_border: the best point
    of a search lies on the border of the box (|x| at its limit or z/a = 3), so it may not be the peak;
    where the stick zone is not admissible (``stick_half_width``) the field is not known and the peaks
    are NaN, unsearched."""
    w = np.asarray(two_a_over_lambda1, dtype=float)
    N = np.asarray(len(np.atleast_1d(wavenumbers)) if n_harmonics is None else n_harmonics)
    shape = np.broadcast_shapes(w.shape, N.shape, np.shape(nu), np.shape(mu), np.shape(fx))
    cases = [np.broadcast_to(v, shape).reshape(-1) for v in (w, N, nu, mu, fx)]
    out = {k: (np.zeros(shape), np.zeros(shape), np.zeros(shape)) for k in ("tau_max", "von_mises")}
    border = np.zeros(shape, dtype=bool)
    shearing = cases[3] * cases[4] > 0.0
    admissible = np.ones(shape, dtype=bool)
    if shearing.any():
        admissible.reshape(-1)[shearing] = stick_half_width(cases[0][shearing], amplitudes, wavenumbers,
                                                            cases[4][shearing], periodic=periodic,
                                                            n_harmonics=cases[1][shearing])[1]
    for i, (wi, Ni, nui, mui, fxi) in enumerate(zip(*cases)):
        flat = np.unravel_index(i, shape)
        if not admissible[flat]:
            for arr in (*out["tau_max"], *out["von_mises"]):
                arr[flat] = np.nan
            continue
        xmax = min(2.0, 1.0 / wi) if periodic else 2.0
        xmin = -xmax if mui * fxi > 0.0 else 0.0
        for name in ("tau_max", "von_mises"):
            def f(x, z):
                return subsurface((name,), x, z, wi, amplitudes, wavenumbers, periodic=periodic, n_harmonics=Ni,
                                  nu=nui, mu=mui, fx=fxi, rtol=rtol, max_terms=max_terms)[0][name]
            xs = np.linspace(xmin, xmax, _PEAK_GRID)
            zs = np.linspace(0.0, PEAK_DEPTH, _PEAK_GRID)
            X, Z = np.meshgrid(xs, zs, indexing="ij")
            v = np.nan_to_num(f(X, Z), nan=-np.inf)
            k = np.unravel_index(np.argmax(v), v.shape)
            x0, z0, best = xs[k[0]], zs[k[1]], v[k]
            hx, hz = xs[1] - xs[0], zs[1] - zs[0]
            for _ in range(_PEAK_ROUNDS):
                gx = np.clip(x0 + hx * np.linspace(-1.0, 1.0, 9), xmin, xmax)
                gz = np.clip(z0 + hz * np.linspace(-1.0, 1.0, 9), 0.0, PEAK_DEPTH)
                X, Z = np.meshgrid(gx, gz, indexing="ij")
                v = np.nan_to_num(f(X, Z), nan=-np.inf)
                k = np.unravel_index(np.argmax(v), v.shape)
                if v[k] >= best:
                    x0, z0, best = gx[k[0]], gz[k[1]], v[k]
                hx, hz = hx / 4.0, hz / 4.0
            for arr, val in zip(out[name], (best, x0, z0)):
                arr[flat] = val
            border[flat] |= (abs(x0) >= xmax) or (z0 >= PEAK_DEPTH)
    return {**out, "on_border": border, "stick_admissible": admissible}


def subsurface_displacement(x_over_a, z_over_a, two_a_over_lambda1, amplitudes, wavenumbers, *, periodic: bool,
                            n_harmonics=None, nu=0.3, mu=0.0, fx=0.0, rtol=DEFAULT_RTOL,
                            max_terms=DEFAULT_MAX_TERMS):
    """u_x/Delta_1 and u_z/Delta_1 at (x/a, z/a), z >= 0 (u_z positive into the body, u_x along +x),
    docs/theory/wavy.md (W45)-(W48); returns (u_x, u_z, info).

    Normal load, and under a tangential load fx = Q/(mu P) with friction coefficient mu the displacements of
    the shear traction q = mu [p(x; a) - p(x; c)] of ``subsurface`` added (uncoupled).  Datum: that of the
    surface ``displacement`` (the log kernel ln|x - xi| in the lambda_1 = 2 pi unit), which u_z of the normal
    load reproduces at z = 0 and u_x of the shear traction likewise; the other component is odd about the
    load's centre: at z = 0 Johnson's (1 - 2 nu)/(4 mu_s) [int_x^inf - int_-inf^x] of the traction (mu_s the
    shear modulus); single indenter by the closed primitive in omega (W45).  Periodic surface (W46)-(W48): the
    same relations with the periodic primitive, whose datum is that of the periodic uz (kernel
    ln|2 sin((x - xi)/2)|: u_z at z = 0 is uz, of zero mean over a period); the mean pressure's k = 0 mode adds
    the uniform strain of sigma_xx = sigma_zz = -p_inf, so u_x carries -(1 - 2 nu) p_inf x/(2 mu_s) and is not
    periodic.  info: "error_estimate" a bound per point (Delta_1 units),
    "converged" as the stresses'."""
    c = _interior_ctx(two_a_over_lambda1, amplitudes, wavenumbers, periodic, n_harmonics, rtol, max_terms)
    shape, (t, zt, nu, mu, fx, row, a, N) = _points(c, x_over_a, z_over_a, nu, mu, fx)
    zk = a * zt

    def primitive(ctx, rows, tt, zz, aa):
        if ctx.periodic:
            if ctx.interior is None:
                ctx.interior = _interior.PeriodicPotential(ctx.table, ctx.dr, ctx.n, ctx.rtol)
            with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
                Psi, G, e = ctx.interior.primitive(rows, tt, zz)
            return G, Psi, e, ctx.interior.converged[rows].copy()
        with np.errstate(invalid="ignore", divide="ignore"):
            G, _, eG, _ = _interior.nonperiodic_potential(ctx.table, rows, tt, zz)
        Psi, ePsi = _interior.nonperiodic_primitive(ctx.table, rows, tt, zz, aa)
        # the bound of both displacement components: Psi's and z |G|'s over 2 (1 - nu) <= 1
        return G, Psi, ePsi + aa * zz * eG, ctx.table.converged[rows]

    G, Psi, err, conv = primitive(c, row, t, zt, a)
    ux, uz = _interior.normal_displacements(Psi, G, zk, nu)
    shearing, ratio, admissible, sliding = _stick(a, N, mu, fx, amplitudes, wavenumbers, periodic)
    if shearing.any():
        # the shear traction's potential and primitive: mu times those of p(x; a) less p(x; c) (W43)
        H, Phi = mu * G, mu * Psi
        err = err + np.where(shearing, mu * err, 0.0)
        if sliding.any():
            cc = _interior_ctx(a[sliding] / np.pi * ratio[sliding], amplitudes, wavenumbers, periodic, N[sliding],
                               rtol, max_terms)
            k = 1.0 / ratio[sliding]
            Gc, Pc, ec, okc = primitive(cc, cc.row, t[sliding] * k, zt[sliding] * k, cc.a_in)
            H[sliding] -= mu[sliding] * Gc
            Phi[sliding] -= mu[sliding] * Pc
            err[sliding] += mu[sliding] * ec
            conv[sliding] &= okc
        tx, tz = _interior.shear_displacements(Phi, H, zk, nu)
        ux = np.where(shearing, ux + tx, ux)
        uz = np.where(shearing, uz + tz, uz)
    ux, uz = _not_solved(dict(ux=ux, uz=uz), shearing & ~admissible).values()
    info = {"error_estimate": err, "converged": conv, "stick_admissible": admissible | ~shearing}
    shaped = lambda v: np.asarray(v).reshape(shape)
    return shaped(ux), shaped(uz), {k: shaped(v) for k, v in info.items()}
