"""One entry point of the wavy family: every quantity the scenario offers, normalised, in one call.

Callers (the scenario `wavy`) only map their inputs to these arguments and multiply the results by
the physical scales of docs/theory/wavy.md (W2); which computation a method selects is decided by
``routes`` alone.
"""
from __future__ import annotations

from typing import Iterable

import numpy as np
from numpy.typing import ArrayLike

from ..flags import Validity as V
from . import contact
from .contact import DEFAULT_MAX_TERMS, DEFAULT_RTOL
from .routes import approximation, substitutes

#: the names ``fields`` computes; pointwise ones depend on x_over_a, the others per contact
POINTWISE: tuple[str, ...] = ("pressure", "uz", "validity")
PER_CASE: tuple[str, ...] = ("mean_pressure", "peak_pressure", "max_pressure", "max_pressure_x",
                             "continuous_contact", "johnson_parameter", "n_terms", "periodic_correction",
                             "error_estimate", "converged")
#: below the surface (pointwise, with the depth and the tangential load) and their per-case peaks
INTERIOR: tuple[str, ...] = contact.SUBSURFACE
LOADED: tuple[str, ...] = ("stick_half_width", "tau_max_peak", "tau_max_peak_x", "tau_max_peak_depth",
                           "von_mises_peak", "von_mises_peak_x", "von_mises_peak_depth", "peak_validity")
#: the displacements below the surface (W45)-(W48)
DISPLACEMENTS: tuple[str, ...] = ("u_x", "u_z")
FIELDS: tuple[str, ...] = POINTWISE + PER_CASE + INTERIOR + LOADED + DISPLACEMENTS
_PEAK = ("validity", "peak_pressure", "n_terms", "error_estimate", "converged")


def fields(names: Iterable[str], x_over_a: ArrayLike, two_a_over_lambda1: ArrayLike, amplitudes: ArrayLike,
           wavenumbers: ArrayLike, *, periodic: bool, n_harmonics: ArrayLike | None = None, method: str = "auto",
           rtol: float = DEFAULT_RTOL, max_terms: int = DEFAULT_MAX_TERMS,
           contact_points: ArrayLike | None = None, z_over_a: ArrayLike = 0.0, nu: ArrayLike = 0.3,
           mu: ArrayLike = 0.0, fx: ArrayLike = 0.0, below: bool = False) -> dict[str, np.ndarray]:
    """The requested quantities of one domain, normalised as in docs/theory/wavy.md (W2).

    Arguments as in ``contact`` (x_over_a = x/a, the harmonic table, ``periodic`` for the periodic
    surface, ``n_harmonics`` the rows used); ``method`` one of ``routes.METHODS``, ``rtol`` the
    series tolerance; ``contact_points`` the number of points inside each contact over the caller's
    whole evaluation, which decides where ``auto`` substitutes (``contact.pressure``; default: counted
    in this call).  Returns {name: array} for ``names`` (any of ``FIELDS``), in these units:

    * pressure -- p(x)/p*, the series (W9) of the domain, (W5)-(W8); with ``auto`` the non-periodic
      series where it is within rtol of a narrow periodic contact's, (W26); with an
      ``approximate_*`` method the paper's formula (W29) instead (non-periodic only);
    * uz -- u_z(x)/Delta_1, (W15) with the approach (W16) and the gap outside the contact (W18);
    * mean_pressure -- p_inf/p*, closed forms (W11) (periodic) and (W12) (non-periodic);
    * peak_pressure -- p(0)/p*, (W13); max_pressure, max_pressure_x -- the global maximum over the
      contact /p* and its position x/a >= 0, (W14);
    * continuous_contact -- int8, 1 where (P) and (G) of (W20) hold, 0 where one fails, 2 where the series
      of p/sqrt(1 - (x/a)^2) did not meet rtol, so the test cannot decide (W25);
    * johnson_parameter -- max over the ripples i >= 2 of chi_i, (W21) (0 for one harmonic);
    * n_terms, error_estimate (/p*), converged (int8) -- the series length, its error bound and
      whether rtol was met, (W22), (W23);
    * periodic_correction -- bound on max |p_periodic - p_nonperiodic|/p* over the contact, (W26);
    * validity -- int8 per point, the codes of ``flags.Validity`` (W25): within_stated_accuracy,
      series_not_converged, approximate_formula, nonperiodic_series_within_rtol (only where
      ``pressure`` is among ``names``); with fields below the surface also (W42): series_not_converged
      where their bound exceeds rtol, undefined_direction_dependent_limit where dpdz is NaN at a surface
      edge; stick_zone_not_admissible (W43) for partial slip whose stick zone is not admissible, where the
      tangential load's values are NaN;
    * ``below``: the caller evaluates the field below the surface (at any of its points), so that
      error_estimate bounds the stresses too, whichever fields this call computes (W39);
    * sigma_xx ... dpdz, shear_traction -- at depth z_over_a = z/a (plane strain with Poisson's ratio
      nu; tangential load fx = Q/(mu P) with friction coefficient mu), ``contact.subsurface``, (W36)-(W43);
      stick_half_width (c/a) and the peaks of tau_max and von Mises with their positions (x/a, z/a),
      ``contact.subsurface_peaks`` (W44); peak_validity search_not_converged where a search ended on its
      box's border, stick_zone_not_admissible (peaks NaN) where (W43) is not the solution;
    * u_x, u_z -- the displacements /Delta_1 at depth z_over_a under the same loads (datum of uz),
      ``contact.subsurface_displacement``, (W45)-(W48); periodic: with the mean pressure's uniform strain.

    Per-contact quantities have the shape of broadcast(two_a_over_lambda1, n_harmonics), pointwise
    ones that broadcast with x_over_a.  Pure NumPy/SciPy, no state.
    """
    names = tuple(names)
    unknown = [n for n in names if n not in FIELDS]
    if unknown:
        raise ValueError(f"unknown wavy field(s) {', '.join(map(repr, unknown))}; allowed: {', '.join(FIELDS)}")
    approx = approximation(method)
    if approx is not None and (wanted_interior := set(names) & set(INTERIOR + LOADED + DISPLACEMENTS)):
        raise ValueError(f"method {method!r} replaces the pressure only; the field below the surface "
                         f"({', '.join(sorted(wanted_interior))}) needs an exact method")
    if approx is not None and periodic:
        raise ValueError(f"method {method!r} is the paper's approximation for a non-periodic indenter; "
                         "it needs periodic=False")
    wanted = set(names)
    table = (two_a_over_lambda1, amplitudes, wavenumbers)
    exact = dict(periodic=periodic, n_harmonics=n_harmonics)
    series = dict(exact, rtol=rtol, max_terms=max_terms)
    out: dict[str, np.ndarray] = {}

    substituted = np.False_
    if "pressure" in wanted:
        if approx is not None:
            out["pressure"] = approx(x_over_a, *table, n_harmonics=n_harmonics)
        else:
            value, info = contact.pressure(x_over_a, *table, **series, substitute=substitutes(method),
                                           contact_points=contact_points)
            out["pressure"] = value
            substituted = info.get("substituted", np.False_)
    interior = wanted.intersection(INTERIOR)
    if interior:
        surface = out["pressure"] if "pressure" in out else (
            contact.pressure(x_over_a, *table, **series, substitute=substitutes(method),
                             contact_points=contact_points)[0]
            if approx is None else None)
        values, sub = contact.subsurface(tuple(n for n in names if n in INTERIOR), x_over_a, z_over_a, *table,
                                         **series, nu=nu, mu=mu, fx=fx, surface_pressure=surface)
        out.update(values)
    moved = wanted.intersection(DISPLACEMENTS)
    if moved:
        ux, uz, disp = contact.subsurface_displacement(x_over_a, z_over_a, *table, **series, nu=nu, mu=mu, fx=fx)
        out.update(u_x=ux, u_z=uz)
    loaded = dict(periodic=periodic, n_harmonics=n_harmonics)
    # the stick zone's admissibility is the case's, so the flag holds it whichever variables are asked
    shear = np.where(np.asarray(mu) > 0, fx, 0.0)
    admissible = np.True_
    if "stick_half_width" in wanted or ("validity" in wanted and np.any(shear > 0.0)):
        c_over_a, admissible = contact.stick_half_width(two_a_over_lambda1, amplitudes, wavenumbers, shear,
                                                        **loaded)
        admissible = admissible | ~(shear > 0.0)
        if "stick_half_width" in wanted:
            out["stick_half_width"] = c_over_a
    if wanted.intersection(LOADED[1:]):
        pk = contact.subsurface_peaks(*table, **series, nu=nu, mu=mu, fx=fx)
        for name in ("tau_max", "von_mises"):
            out.update({f"{name}_peak": pk[name][0], f"{name}_peak_x": pk[name][1],
                        f"{name}_peak_depth": pk[name][2]})
        out["peak_validity"] = np.where(pk["stick_admissible"],
                                        np.where(pk["on_border"], V.search_not_converged, V.within_stated_accuracy),
                                        V.stick_zone_not_admissible).astype(np.int8)
    if "uz" in wanted:
        out["uz"] = contact.displacement(x_over_a, *table, **series)[0]
    if wanted.intersection(_PEAK):
        p0, info = contact.peak_pressure(*table, **series)
        out.update(peak_pressure=p0, n_terms=info["n_terms"], error_estimate=info["error_estimate"],
                   converged=info["converged"].astype(np.int8))
        if "validity" in wanted:
            # one code per point: the later causes below win (a case whose stick zone is not admissible
            # has no solution here, whatever its series did)
            v = (np.int8(V.approximate_formula) if approx is not None else
                 np.where(info["converged"],
                          np.where(substituted, V.nonperiodic_series_within_rtol, V.within_stated_accuracy),
                          V.series_not_converged).astype(np.int8))
            if moved:
                v = np.where(disp["converged"], v, V.series_not_converged)
                v = np.where(disp["stick_admissible"], v, V.stick_zone_not_admissible)
            if interior:
                v = np.where(sub["converged"], v, V.series_not_converged)
                if "dpdz" in interior:
                    v = np.where(sub["dpdz_undefined"], V.undefined_direction_dependent_limit, v)
                v = np.where(sub["stick_admissible"], v, V.stick_zone_not_admissible)
            v = np.where(admissible, v, V.stick_zone_not_admissible).astype(np.int8)
            out["validity"] = v
        if below and approx is None:
            # the per-case bound covers the stresses of the normal load as well (W38), (W39)
            out["error_estimate"] = np.maximum(out["error_estimate"], contact.subsurface_bound(*table, **series))
    if "mean_pressure" in wanted:
        out["mean_pressure"] = contact.mean_pressure(*table, **exact)
    if wanted.intersection(("max_pressure", "max_pressure_x")):
        pmax, xmax, _ = contact.max_pressure(*table, **series)
        out.update(max_pressure=pmax, max_pressure_x=xmax)
    if "continuous_contact" in wanted:
        out["continuous_contact"] = _continuous_contact(table, series)
    if "periodic_correction" in wanted:
        out["periodic_correction"] = contact.periodic_correction(*table, n_harmonics=n_harmonics, rtol=rtol,
                                                                 max_terms=max_terms)[0]
    if "johnson_parameter" in wanted:
        out["johnson_parameter"] = contact.johnson_parameter(*table, **exact)
    return {n: out[n] for n in names}


def _continuous_contact(table, series) -> np.ndarray:
    """(W20) decided only from a converged series: 1 holds, 0 fails, 2 undetermined (W25)."""
    v = contact.contact_validity(*table, **series)
    # the bound of the error of p/sqrt(1 - (x/a)^2) itself (>= the pressure's for the closed form)
    decided = v["converged"] & (v["error_estimate"] <= series["rtol"])
    return np.where(decided, v["ok"].astype(np.int8), 2).astype(np.int8)
