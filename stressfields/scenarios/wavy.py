"""Rigid multisinusoidal wavy surface pressed on an elastic half-plane (plane strain, frictionless),
in continuous contact of prescribed half-width a: scenario `wavy`.

Profile (initial gap) g(x) = sum_i Delta_i (1 - cos(2 pi n_i x/lambda_1)), the harmonic table
(`amplitudes`, `wavenumbers`) with the base wave n_1 = 1 first. `domain` picks the periodic
surface (Hilbert/cot kernel, Westergaard for one harmonic) or a single non-periodic indenter
(Cauchy kernel, Hertz at small a); both may be swept side by side.

Normalised mode (default): x in units of a, pressures divided by p* = pi E* Delta_1/lambda_1,
u_z by Delta_1; only Delta_i/Delta_1 matters. Physical mode (the recipe gives E, nu and lambda_1;
amplitudes in metres): pascals and metres, x in metres from the contact centre. The contact
size stays the ratio 2a/lambda_1 in both modes (the paper's abscissa).

Methods: "series" is the exact series of the domain (length chosen from method.rtol, recorded in
n_terms / error_estimate / converged). "auto" (the default) is the same, except that for a periodic
surface with a contact so narrow that the periodic correction to the pressure (about
0.4 (2a/lambda_1)^2 of it, bounded per case in `periodic_correction`) plus the non-periodic series
error stays below the tolerance, `pressure` is the cheaper non-periodic series (validity = 7,
nonperiodic_series_within_rtol). "approximate_eq18" / "approximate_eq20" replace `pressure`
(only) by the paper's approximate formulas, which are inaccurate: they exist so their error can be
charted, are never the default, and are flagged validity = 6 (approximate_formula) at every point.
What each method means is decided in one place, the physics route table (`physics/wavy/routes.py`); `evaluate` maps the
recipe onto one `physics.wavy.fields` call per domain and applies the physical scales.
"""
from __future__ import annotations

import math
from typing import Any, Mapping, Sequence

import numpy as np

from ..physics.flags import Validity as V
from ..physics.flags import declare
from ..physics.names import WAVY_APPROXIMATE_METHODS, WAVY_METHODS, WAVY_SERIES_METHODS
from .base import ARRAY, INT, STR, Options, Parameter, Scenario, Variable

REFERENCE = ("I. Yu. Tsukanov, Partial contact of a rigid multisinusoidal wavy surface with an elastic "
             "half-plane, Advances in Tribology 2018, 8431467, doi:10.1155/2018/8431467 (pressures with "
             "the plane-strain modulus E* = E/(1-nu^2); see the errata of the theory page)")

PSTAR = "p* = pi E* Delta_1/lambda_1, E* = E/(1-nu^2)"
#: the largest wavenumber n_i a recipe may give: the periodic closed form sums n_max terms at each of
#: ~50 n_max quadrature nodes of the continuous-contact test, and the single-indenter series is
#: ~a n_max/2 terms long, so a periodic contact costs ~n_max^2 (measured: 300: 0.9 s, 500: 2.0 s,
#: 1000: 6.2 s, 3000: 80 s; 1e12 would never end)
MAX_WAVENUMBER = 500
DOMAINS = ("periodic", "nonperiodic")
DELTA_1 = "the amplitude Delta_1 of the base wave"
HALF_WIDTH = "the contact half-width a"
PER_HALF_WIDTH = "p*/a, with a the contact half-width"
#: what a per-contact (x-independent) quantity depends on; only the swept ones become dimensions
CASE = ("domain", "amplitudes", "wavenumbers", "n_harmonics", "E", "nu", "lambda_1", "a")

_AMPLITUDES = ("amplitudes Delta_i of the harmonics, gap g = sum Delta_i (1 - cos(2 pi n_i x/lambda_1)); row 1 "
               "is the base wave, Delta_1 > 0")
PARAMETERS = (
    Parameter("domain", "periodic wavy surface (period lambda_1) or a single non-periodic wavy indenter",
              kind=STR, default="periodic", choices=DOMAINS, label="domain"),
    Parameter("amplitudes", f"{_AMPLITUDES} (normalised mode: any length unit, only Delta_i/Delta_1 matters)",
              meaning_physical=_AMPLITUDES, units="1", units_physical="m", kind=ARRAY, required=True,
              sweepable=False, label="amplitudes Delta_i"),
    Parameter("wavenumbers", "integer wavenumbers n_i >= 1 of the harmonics (wavelength lambda_1/n_i), "
              "paired with amplitudes; the first is 1", kind=ARRAY, required=True, sweepable=False,
              label="wavenumbers n_i"),
    Parameter("n_harmonics", "number of harmonics used: the first N rows of the table (default: all)",
              kind=INT, low=1, label="number of harmonics"),
    Parameter("E", "Young's modulus of the half-plane (giving it switches to physical units)", units="Pa",
              low=0.0, low_open=True, high=1e15, sweepable=False, mode="physical", label="Young's modulus E"),
    Parameter("nu", "Poisson's ratio of the half-plane (required in physical mode; normalised mode: used by "
              "sigma_yy, the invariants and dpdz below the surface, 0.3 where z is given without it)",
              low=0.0, high=0.5, sweepable=False, label="Poisson's ratio nu"),
    Parameter("lambda_1", "wavelength lambda_1 of the base wave", units="m", low=0.0, low_open=True,
              high=1e6, sweepable=False, mode="physical", label="base wavelength lambda_1"),
    Parameter("a", "contact width 2a divided by the base wavelength lambda_1", required=True,
              low=0.0, high=1.0, low_open=True, high_open=True, label="width 2a / lambda_1"),
    Parameter("mu", "coefficient of friction of the partial-slip tangential load (with fx or tangential_force)",
              low=0.0, high=10.0, label="friction coefficient"),
    Parameter("fx", "tangential load Q divided by mu P (P the normal load per period, or per unit length of the single "
              "indenter), in [0, 1]; 1: the onset of gross slip", low=0.0, high=1.0, label="Q / (mu P)"),
    Parameter("tangential_force", "tangential load Q per period (single indenter: per unit length) along +x, at most "
              "mu times the normal load (instead of fx; physical mode)", units="N/m", low=0.0, high=1e15,
              when={"fx": (None,)}, label="tangential load Q"),
    Parameter("z", "depth below the surface divided by the contact half-width a (0: the surface)",
              meaning_physical="depth below the surface (0: the surface)", units="1", units_physical="m",
              low=0.0, high=1e6, label="depth z / a", label_physical="depth z", axis="Z"),
    Parameter("x", "surface coordinate x divided by the contact half-width a",
              meaning_physical="surface coordinate x from the contact centre", units="1", units_physical="m",
              default=0.0, low=-1e6, high=1e6, label="x / a", label_physical="x", axis="X"),
)

#: the tangential load's parameters: the surface pressure and displacement do not depend on them (uncoupled)
SHEAR = ("mu", "fx", "tangential_force")
#: what the surface pressure and displacement depend on: every parameter but the depth and the shear load
SURFACE = tuple(p.name for p in PARAMETERS if p.name not in ("z",) + SHEAR)
#: what a per-case quantity of the field below the surface depends on
LOADED = CASE + SHEAR
_INTERIOR = ("Plane strain, from the complex potential of the surface tractions (docs/theory/wavy.md (W36)-(W41)): "
             "periodic, the closed finite form near the surface and its Taylor series in w = exp(i 2 pi (x + i z)/"
             "lambda_1) at depth, switched a priori by their bounds (W39); single indenter, the series in omega "
             "(W38). The mean pressure's k = 0 mode is kept (periodic: sigma_xx = sigma_zz = -p_inf as z -> inf, the "
             "limit of the sum over all periods; (W37)). At z = 0 sigma_zz = -pressure and sigma_xz = -shear_traction "
             "exactly. Within error_estimate (p*).")
_DISPLACEMENT = ("Plane strain, from the potential G and its primitive Psi (docs/theory/wavy.md (W45)-(W48)): "
                 "2 mu_s u_x = (1 - 2 nu) Im Psi + z Re G, 2 mu_s u_z = -2 (1 - nu) Re Psi - z Im G (mu_s the shear "
                 "modulus), plus the shear traction's terms under a tangential load. Single indenter: the closed "
                 "primitive in omega. Periodic: the closed primitive near the surface and its Taylor series in w at "
                 "depth, switched where the stresses switch (W39). Datum that of uz (non-periodic: log kernel "
                 "ln|2 pi (x - xi)/lambda_1|; periodic: ln|2 sin(pi (x - xi)/lambda_1)|), so u_z at z = 0 is uz; u_x "
                 "is odd about x = 0 under normal load (at z = 0 Johnson's (1 - 2 nu)/(4 mu_s) times the load right "
                 "of x less that left of it). Periodic: the mean pressure's k = 0 mode (sigma_xx = sigma_zz = -p_inf "
                 "at depth) adds its uniform strain, u_x = -(1 - 2 nu) p_inf x/(2 mu_s) and u_z = -(1 - 2 nu) p_inf "
                 "z/(2 mu_s): u_x is not periodic in x and u_z falls linearly with depth. Within about 1e-13 Delta_1 "
                 "of independent quadratures in the tests (per-point bound <= 1e-12 Delta_1 up to 5 lambda_1 deep).")
_PEAK = ("Grid of 41 x 41 points over 0 <= z <= 3a and 0 <= x <= 2a (both signs of x under a tangential load; at "
         "most half a period), refined by 16 zooms of a 9 x 9 grid (docs/theory/wavy.md (W44)); the value to the "
         "fields' accuracy, the position to about 1e-8 a (the field is flat at its peak).")
_SERIES = ("the closed Legendre-cosine form (periodic, docs/theory/wavy.md (W30)) or the truncated Bessel "
           "series of eq. (14) (non-periodic) for this 2a/lambda_1 and harmonic count")
#: the codes of the point validity and of the peaks' (physics.flags), and those the comments name
APPROXIMATE, SUBSTITUTED, UNDEFINED = (int(V.approximate_formula), int(V.nonperiodic_series_within_rtol),
                                       int(V.undefined_direction_dependent_limit))
FIELD_CODES = (V.within_stated_accuracy, V.undefined_direction_dependent_limit, V.series_not_converged,
               V.approximate_formula, V.nonperiodic_series_within_rtol, V.stick_zone_not_admissible)
PEAK_CODES = (V.within_stated_accuracy, V.search_not_converged, V.stick_zone_not_admissible)
VARIABLES = (
    Variable("pressure", "contact pressure p(x) (compressive positive; 0 outside the contact)",
             units_physical="Pa", scale=PSTAR, dims=SURFACE,
             comment="Exact series, length chosen from method.rtol (see n_terms, error_estimate). With "
                     "method approximate_eq18/eq20 it is instead the paper's approximate formula, which is "
                     f"NOT accurate (validity = {APPROXIMATE}); all other variables stay exact.",
             label="contact pressure p(x)"),
    Variable("uz", "surface displacement u_z(x), positive into the body", units_physical="m",
             scale=DELTA_1, dims=SURFACE,
             comment="Datum (C = 0 in eq. 5): periodic domain, kernel ln|2 sin(pi (x - xi)/lambda_1)|, so u_z "
                     "has zero mean over one period; non-periodic domain, kernel ln|2 pi (x - xi)/lambda_1| "
                     "(lengths in units of lambda_1/(2 pi)). Inside the contact u_z(x) = u_z(0) - g(x).",
                     label="displacement u_z"),
    Variable("mean_pressure", "mean (nominal) pressure p_inf = (1/lambda_1) * integral of p over the contact "
             "(non-periodic: load per unit length / lambda_1)", units_physical="Pa", scale=PSTAR, dims=CASE,
             comment="Closed forms: eq. (16) (non-periodic), docs/theory/wavy.md (W12); Legendre form (periodic), "
                     "docs/theory/wavy.md (W11).", label="mean pressure p_inf"),
    Variable("peak_pressure", "pressure p(0) at the contact centre (the paper's p_max)", units_physical="Pa",
             scale=PSTAR, dims=CASE, label="centre pressure p(0)"),
    Variable("max_pressure", "global maximum of the contact pressure over the contact", units_physical="Pa",
             scale=PSTAR, dims=CASE, label="maximum pressure"),
    Variable("max_pressure_x", "position x >= 0 of the global pressure maximum (p is even)", units_physical="m",
             scale=HALF_WIDTH, dims=CASE, label="x of max. pressure"),
    Variable("continuous_contact", "exact test of the continuous-contact assumption", dtype="int8", dims=CASE,
             flag_values=(0, 1, 2), flag_meanings=("fails", "holds", "undetermined_series_not_converged"),
             comment="1 where p/sqrt(1-(x/a)^2) >= 0 over the contact and the gap outside it is >= 0 "
                     "(docs/theory/wavy.md (W20)). 0: the continuous-contact solution has tensile pressure or "
                     "the profile penetrates the surface outside the contact; the real contact is then discrete "
                     "and the values here are those of the model only. 2: the series of p/sqrt(1-(x/a)^2) did "
                     "not meet method.rtol, so the test is not decided (docs/theory/wavy.md (W25)).",
                     label="continuous-contact test"),
    Variable("johnson_parameter", "Johnson parameter chi = max over ripples i >= 2 of pi E* Delta_i/(lambda_i "
             "p_h), p_h = 2 p_inf lambda_1/(pi a) (as corrected in docs/theory/wavy.md (W21); 0 for one harmonic)",
             dims=CASE, comment="The paper's criterion chi < 1 is a heuristic, neither necessary nor sufficient: "
                                "see continuous_contact.", label="Johnson parameter chi"),
    Variable("n_terms", f"number of sine terms summed in {_SERIES}", dtype="int32", dims=CASE,
             label="number of series terms"),
    Variable("periodic_correction", "bound on max |p_periodic - p_nonperiodic| over the contact: how far the "
             "periodic surface's pressure is from a single indenter's of the same contact width",
             units_physical="Pa", scale=PSTAR, dims=CASE,
             comment="From both series on 32 Chebyshev nodes of the smooth difference (the kernels of "
                     "eqs. (1) and (2) differ by a smooth term), docs/theory/wavy.md (W26); +inf where that "
                     "interpolant is not resolved. "
                     "Method auto uses the non-periodic series for a periodic pressure where this plus the "
                     f"non-periodic series error is below the tolerance (validity = {SUBSTITUTED}).",
                     label="periodic correction"),
    Variable("error_estimate", "upper bound of the error of pressure, peak_pressure and max_pressure (only; "
             "not of uz) and, where the recipe gives z, of the stresses below the surface under normal load (under "
             "a tangential load they are within (1 + 4 mu) error_estimate): periodic, rounding of the closed form; "
             "non-periodic, truncated tail + rounding",
             units_physical="Pa", scale=PSTAR, dims=CASE,
             comment="In units of p* (docs/theory/wavy.md (W23), (W31)). It does not bound uz, whose scale is "
                     "Delta_1: inside the contact uz = u_z(0) - g(x) from closed forms; outside it is good to "
                     "about error_estimate/p* * (|x| - a) * 2 pi/lambda_1 * Delta_1 plus the gap quadrature "
                     f"(below 1e-13 Delta_1 in the tests). Where validity = {SUBSTITUTED} the pressure is "
                     "instead within periodic_correction plus the non-periodic series error of the periodic "
                     "one, together below method.rtol.", label="error bound"),
    Variable("converged", f"whether the pressure of {_SERIES} met method.rtol (error_estimate <= "
             "method.rtol * p*)", dtype="int8", dims=CASE, flag_values=(0, 1),
             flag_meanings=("not_converged", "converged"), always=True,
             comment="0: rtol was not reached (below rounding, or the length cap as 2a/lambda_1 -> 1); the "
                     "values are the best available, good to error_estimate.", label="series converged"),
    *(Variable(f"sigma_{c}", f"stress component sigma_{c} at depth z (z = 0: the surface)", units_physical="Pa",
               scale=PSTAR, comment=_INTERIOR, recorded_when=("z",), label=f"stress sigma_{c}")
      for c in ("xx", "yy", "zz", "xz")),
    Variable("sigma_1", "largest principal stress at depth z",
             units_physical="Pa", scale=PSTAR, recorded_when=("z",), label="sigma_1 (largest)"),
    Variable("sigma_2", "intermediate principal stress at depth z",
             units_physical="Pa", scale=PSTAR, recorded_when=("z",), label="sigma_2 (middle)"),
    Variable("sigma_3", "smallest principal stress at depth z",
             units_physical="Pa", scale=PSTAR, recorded_when=("z",), label="sigma_3 (smallest)"),
    Variable("tau_max", "maximum shear stress (sigma_1 - sigma_3)/2 at depth z",
             units_physical="Pa", scale=PSTAR, recorded_when=("z",), label="shear stress tau_max"),
    Variable("von_mises", "von Mises equivalent stress sqrt(3 J2) at depth z",
             units_physical="Pa", scale=PSTAR, recorded_when=("z",), label="von Mises stress"),
    Variable("dpdz", "derivative of the hydrostatic pressure p_h = -trace(sigma)/3 with depth z (at z = 0: the "
             "limit z -> 0+)", units_physical="Pa/m", scale=PER_HALF_WIDTH, recorded_when=("z",),
             comment=f"NaN (validity = {UNDEFINED}) at z = 0 on a contact edge and, under partial slip, a stick "
                     "edge, where the limit depends on the direction of approach. Not covered by error_estimate.",
             label="dp_h/dz"),
    *(Variable(f"u_{c}", f"displacement u_{c} at depth z (z = 0: the surface; {what})", units_physical="m",
               scale=DELTA_1, comment=_DISPLACEMENT, label=f"displacement u_{c}")
      for c, what in (("x", "along +x"), ("z", "positive into the body"))),
    Variable("shear_traction", "shear traction q(x) on the half-plane along +x at the surface point (partial slip: "
             "mu [p(x; a) - p(x; c)])", units_physical="Pa", scale=PSTAR, dims=SURFACE + SHEAR,
             recorded_when=("fx", "tangential_force"),
             comment="Ciavarella (1998) and Jager (1997): the normal pressure at the contact half-width a less that at "
                     "the stick half-width c, times mu (docs/theory/wavy.md (W43)); uncoupled (the shear traction "
                     "leaves the pressure unchanged).", label="shear traction q(x)"),
    Variable("stick_half_width", "half-width c of the stick zone (a: normal load only; 0: gross slip)",
             units_physical="m", scale=HALF_WIDTH, dims=LOADED, recorded_when=("fx", "tangential_force"),
             comment="The largest c <= a with P(c) = (1 - fx) P(a), P the normal load at contact half-width c "
                     "(docs/theory/wavy.md (W43)).", label="stick half-width c"),
    *(Variable(f"{name}{suffix}", f"{what}{tail}", units_physical=up, scale=sc, dims=LOADED + ("nu",),
               comment=_PEAK, label=f"{lab} {name}") for name, what in (("tau_max", "maximum shear stress"),
                                                                        ("von_mises", "von Mises equivalent stress"))
      for suffix, tail, up, sc, lab in (("_peak", " at its largest over the search box", "Pa", PSTAR, "peak"),
                                        ("_peak_x", ": x of its largest value", "m", HALF_WIDTH, "x of peak"),
                                        ("_peak_depth", ": depth z of its largest value", "m", HALF_WIDTH,
                                         "z of peak"))),
    Variable("peak_validity", "validity of the peak variables of the case", dtype="int8", dims=LOADED + ("nu",),
             always=tuple(f"{n}{s}" for n in ("tau_max", "von_mises") for s in ("_peak", "_peak_x", "_peak_depth")),
             **declare(PEAK_CODES, where={
                 V.search_not_converged: "its box: |x| = 2a or half a period, z = 3a",
                 V.stick_zone_not_admissible: "the peak variables are NaN"}),
             label="validity of the peaks"),
    Variable("validity", "validity of pressure and uz (and of the stresses below the surface) at the point",
             dtype="int8", always=True, **declare(FIELD_CODES, where={
                 V.undefined_direction_dependent_limit: "dpdz at z = 0 on a contact or stick edge",
                 V.series_not_converged: "see converged, error_estimate; below the surface also where the "
                                         "stresses' bound exceeds method.rtol",
                 V.approximate_formula: "method approximate_eq18/eq20: the pressure is the paper's approximation",
                 V.nonperiodic_series_within_rtol: "method auto, periodic domain: the pressure, see "
                                                   "periodic_correction; uz and the per-case values stay periodic",
                 V.stick_zone_not_admissible: "flagged at every point of such a case, whichever variables the "
                                              "file holds: the stresses, dpdz, shear_traction, the displacements "
                                              "below the surface and the peaks are NaN there, stick_half_width is "
                                              "the root of P(c) = (1 - fx) P(a) but not a stick zone, and pressure "
                                              "and uz stay exact (uncoupled)"}),
             label="validity"),
)
#: the variables written when a recipe names none: those of the surface (the field below it joins when
#: the recipe gives z, the shear traction and stick width with a tangential load: ``recorded_when``)
DEFAULTS = tuple(v.name for v in VARIABLES[:VARIABLES.index(next(v for v in VARIABLES if v.name == "sigma_xx"))]
                 if not v.always)
#: variable -> the scale its normalised value is multiplied by in physical mode (its declaration's)
_SCALE = {v.name: v.scale for v in VARIABLES if v.scale}


def evaluate(names: Sequence[str], p: Mapping[str, Any], options: Options) -> dict[str, np.ndarray]:
    """Each domain value is a separate physics call (periodic is a flag there), merged along its axis."""
    domain = np.asarray(p.get("domain", "periodic"), dtype=object)
    out: dict[str, np.ndarray] = {}
    for value in dict.fromkeys(domain.ravel()):
        part = _evaluate(names, p, options, periodic=value == "periodic")
        for k, v in part.items():
            out[k] = v if k not in out else np.where(domain == value, v, out[k])
    return out


def _evaluate(names: Sequence[str], p: Mapping[str, Any], options: Options, periodic: bool) -> dict[str, np.ndarray]:
    """One domain: recipe values -> wv.fields (normalised), then the scales p*, Delta_1, a (physical mode)."""
    from ..physics import wavy as wv     # when computing: the declarations need only physics.names

    amps, wns = np.asarray(p["amplitudes"], dtype=float), np.asarray(p["wavenumbers"], dtype=float)
    a = np.asarray(p["a"], dtype=float)
    if options["physical"]:
        pstar = math.pi * p["E"] / (1.0 - p["nu"] ** 2) * amps[0] / p["lambda_1"]
        length, half_width = amps[0], a * p["lambda_1"] / 2.0
    else:
        pstar, length, half_width = 1.0, 1.0, 1.0
    x = np.asarray(p.get("x", 0.0), dtype=float) / half_width
    z = np.asarray(p.get("z", 0.0), dtype=float) / half_width
    mu = np.asarray(p.get("mu", 0.0), dtype=float)
    fx = p.get("fx")
    if fx is None and p.get("tangential_force") is not None:
        # Q per period (per unit length) over mu P, P = p_inf lambda_1 with p_inf in pascals (W10)
        load = wv.mean_pressure(a, amps, wns, periodic=periodic, n_harmonics=p.get("n_harmonics")) * pstar
        with np.errstate(divide="ignore", invalid="ignore"):
            fx = np.where(mu > 0.0, np.asarray(p["tangential_force"], dtype=float) / (mu * load * p["lambda_1"]), 0.0)
    fx = np.asarray(0.0 if fx is None else fx, dtype=float)
    raw = wv.fields(names, x, a, amps, wns, periodic=periodic, n_harmonics=p.get("n_harmonics"),
                    method=options["method"], rtol=options["rtol"],
                    contact_points=_contact_points(options, a, half_width), z_over_a=z,
                    nu=np.asarray(p.get("nu", 0.3), dtype=float), mu=mu, fx=fx,
                    below=(options.get("sweep") or p).get("z") is not None)
    factor = {PSTAR: pstar, DELTA_1: length, HALF_WIDTH: half_width, PER_HALF_WIDTH: pstar / half_width}
    return {n: raw[n] * factor[_SCALE[n]] if n in _SCALE else raw[n] for n in names}


def _contact_points(options: Options, a: np.ndarray, half_width) -> np.ndarray | None:
    """Per contact of the block: how many x values of the whole recipe lie in its central contact
    |x| <= a, so that method auto's choice of series for a contact (and so every value) does not
    depend on how the sweep is cut into blocks.  None without the recipe's sweep (the physics then
    counts the block's own points)."""
    sweep = options.get("sweep")
    if sweep is None:
        return None
    x_all = np.sort(np.abs(np.ravel(np.asarray(sweep.get("x", 0.0), dtype=float))))
    # normalised mode: x is x/a, so the contact is |x| <= 1 whatever a; physical: |x| <= a lambda_1/2
    limit = np.broadcast_to(np.asarray(half_width, dtype=float), a.shape)
    return np.searchsorted(x_all, limit, side="right")


def check(values: Mapping[str, Any], physical: bool, method: str) -> list[str]:
    """Cross-parameter checks: the harmonic table, n_harmonics against it, approximations' domain."""
    amps, wns = values.get("amplitudes"), values.get("wavenumbers")
    if amps is None or wns is None:
        return []
    if len(amps) != len(wns):
        return [f"amplitudes has {len(amps)} values but wavenumbers has {len(wns)}; they must pair up "
                "(one row per harmonic)"]
    problems = []
    bad = [n for n in wns if not float(n).is_integer() or n < 1]
    if bad:
        problems.append(f"wavenumbers = {_show(wns)}: {_show(bad[0])} is not allowed; each must be an integer "
                        ">= 1 (wavelength lambda_1/n_i)")
    elif max(wns) > MAX_WAVENUMBER:
        problems.append(f"wavenumbers = {_show(wns)}: {_show(max(wns))} exceeds {MAX_WAVENUMBER}, the largest "
                        f"wavenumber allowed; each must be an integer in [1, {MAX_WAVENUMBER}] (the cost of a "
                        "contact grows with the square of the largest one)")
    elif wns[0] != 1:
        problems.append(f"wavenumbers = {_show(wns)} must start with 1: the first row is the base wave, "
                        "which fixes lambda_1")
    if not amps[0] > 0:
        problems.append(f"amplitudes = {_show(amps)}: the base-wave amplitude Delta_1 = {_show(amps[0])} "
                        "must be > 0")
    N = values.get("n_harmonics")
    if N is not None and not np.all(np.mod(N, 1) == 0):
        problems.append(f"n_harmonics = {_show(N)} must be an integer in [1, {len(wns)}] (the rows of "
                        "amplitudes/wavenumbers)")
    elif N is not None and np.max(N) > len(wns):
        problems.append(f"n_harmonics = {_show(np.max(N))} exceeds the harmonic table; allowed: an integer in "
                        f"[1, {len(wns)}] (the rows of amplitudes/wavenumbers)")
    problems += _check_loads(values, physical, method)
    moved = [v for v in ("u_x", "u_z") if v in getattr(values, "variables", ())]
    if moved and method in WAVY_APPROXIMATE_METHODS:
        problems.append(f"method.method = {method!r} is an approximate pressure; {', '.join(moved)} need an exact "
                        f"method ({', '.join(WAVY_SERIES_METHODS)})")
    domain = values.get("domain")
    if method in WAVY_APPROXIMATE_METHODS and (isinstance(domain, np.ndarray) or domain != "nonperiodic"):
        problems.append(f"method.method = {method!r} is the paper's approximation for a non-periodic indenter; "
                        f"it needs domain = 'nonperiodic', got domain = {_show(domain)}")
    return problems


def _check_loads(values: Mapping[str, Any], physical: bool, method: str) -> list[str]:
    """nu in physical mode; the depth and the tangential load: exact methods only; the tangential load with mu,
    at most mu P."""
    problems = []
    if values.get("z") is not None and method in WAVY_APPROXIMATE_METHODS:
        problems.append(f"method.method = {method!r} is an approximate pressure; the field below the surface (z) "
                        f"needs an exact method ({', '.join(WAVY_SERIES_METHODS)})")
    if physical and values.get("nu") is None:
        problems.append("missing parameter 'nu' (Poisson's ratio of the half-plane; a number in [0, 0.5]): "
                        "required in physical mode")
    load = next((k for k in ("fx", "tangential_force") if values.get(k) is not None
                 and np.any(np.asarray(values[k], dtype=float) > 0.0)), None)
    if load is None:
        return problems
    if values.get("mu") is None:
        problems.append(f"{load} is a tangential load of partial slip, which needs the friction coefficient mu; "
                        "give mu (a number in [0, 10])")
    if method in WAVY_APPROXIMATE_METHODS:
        problems.append(f"method.method = {method!r} is an approximate pressure; a tangential load ({load}) needs an "
                        f"exact method ({', '.join(WAVY_SERIES_METHODS)})")
    if load == "tangential_force" and values.get("mu") is not None and not problems and physical:
        problems += _check_tangential_force(values)
    return problems


def _check_tangential_force(values: Mapping[str, Any]) -> list[str]:
    """tangential_force <= mu P (P = p_inf lambda_1 per period, or per unit length of the single indenter),
    checked for every combination of the sweep before anything is computed."""
    from ..physics.wavy import mean_pressure

    amps, wns = np.asarray(values["amplitudes"], dtype=float), np.asarray(values["wavenumbers"], dtype=float)
    E, nu, lam = (float(values[k]) for k in ("E", "nu", "lambda_1"))
    pstar = math.pi * E / (1.0 - nu ** 2) * amps[0] / lam
    a = np.asarray(values["a"], dtype=float).reshape(-1, 1, 1, 1)
    N = values.get("n_harmonics")
    N = np.asarray(len(wns) if N is None else N).reshape(1, -1, 1, 1)
    mu = np.asarray(values["mu"], dtype=float).reshape(1, 1, -1, 1)
    Q = np.asarray(values["tangential_force"], dtype=float).reshape(1, 1, 1, -1)
    domains = values.get("domain", "periodic")
    for domain in np.atleast_1d(np.asarray(domains, dtype=object)):
        try:
            P = mean_pressure(a, amps, wns, periodic=domain == "periodic", n_harmonics=N) * pstar * lam
        except ValueError:
            return []                 # the harmonic table's own problems are reported elsewhere
        over = Q > mu * P * (1.0 + 1e-12)
        if over.any():
            i = np.argwhere(np.broadcast_to(over, np.broadcast_shapes(over.shape, P.shape)))[0]
            limit = float(np.broadcast_to(mu * P, over.shape)[tuple(i)])
            return [f"tangential_force = {float(np.broadcast_to(Q, over.shape)[tuple(i)]):.6g} N/m exceeds mu P = "
                    f"{limit:.6g} N/m (the onset of gross slip, domain = {domain!r}); allowed: [0, mu P]"]
    return []


def _complete(values: dict) -> None:
    """Normalised mode with a depth: Poisson's ratio 0.3 unless given (sigma_yy and the invariants need it);
    recipes without z keep their parameters (and content hash)."""
    if "z" in values and "nu" not in values and "E" not in values:
        values["nu"] = 0.3


def _route(values: Mapping[str, Any], method: str, rtol: float) -> tuple[str, str]:
    """The route table's (route, accuracy) of the method, whatever the values (``physics.wavy.resolve``)."""
    from ..physics.wavy import resolve

    below = values.get("z") is not None and method not in WAVY_APPROXIMATE_METHODS
    return resolve(method, rtol, below=below)


def _show(v):
    if isinstance(v, (tuple, list, np.ndarray)):
        return "[" + ", ".join(_show(x) for x in v) + "]"
    if isinstance(v, (float, np.floating)) and float(v).is_integer():
        return str(int(v))
    return repr(v.item() if isinstance(v, np.generic) else v)


WAVY = Scenario(
    name="wavy",
    summary="Rigid multisinusoidal wavy surface (periodic or single indenter) on an elastic half-plane in "
            "continuous contact: pressure, displacement, mean and peak pressure, validity of the contact model",
    references=REFERENCE, theory="wavy", parameters=PARAMETERS, variables=VARIABLES, evaluate=evaluate,
    physical_switch="E", methods=WAVY_METHODS, check=check, complete=_complete,
    default_variables=DEFAULTS,
    conventions="plane strain, frictionless; pressure positive in compression; u_z positive into the body",
    route=_route,
)
SCENARIOS: tuple = (WAVY,)
