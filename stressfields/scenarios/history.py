"""Tangential loading histories (fretting) on axisymmetric indenters at constant normal load.

Scenario `axisymmetric_history`: the surface fields of the `axisymmetric` scenarios after every
step of a tangential displacement history u_x0(t), from the MDR spring memory of eq. (27)-(28)
(``physics.axisymmetric.history``; docs/theory/axisymmetric.md (A65)-(A77)), plus the tangential
force, the stick radius, and the energy dissipated by friction.  Parameters, normalisation
(p_m = F_N/(pi a^2)), physical mode (give E) and flags are those of the `axisymmetric` scenarios.

The history is a sweep-free array parameter; its index is the dimension `step`.  `step` is an
ordinary sweepable integer parameter; when the recipe does not give it, the scenario's check fills
in every step (a parameter default cannot depend on another parameter).  `amplitude` multiplies
the whole history, so one history can be swept over amplitudes.
"""
from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np

from ..physics import axisymmetric as ax
from ..physics.axisymmetric import history as hist
from ..physics.invariants import principal_stresses, von_mises
from .axisymmetric import (A, DELTA, E, MU, N, NU, PRINCIPAL, PROFILE_F, PROFILE_R, R, REFERENCE, SPATIAL,
                           STRESS, THETA, X, Y, _check_general, _contact_radius, _general, _variables, route)
from .base import ARRAY, INT, STR, Parameter, Scenario, Variable, nonfinite_flag

HISTORY = Parameter("ux0_history", "tangential rigid-body displacements u_x0 divided by the indentation depth "
                    "delta, in order, starting from the unloaded state u_x0 = 0 (each step is reached "
                    "monotonically from the previous one)", kind=ARRAY, required=True, sweepable=False)
AMPLITUDE = Parameter("amplitude", "factor multiplying every value of ux0_history (sweep it to run one "
                      "history at several amplitudes)", default=1.0, low=0.0, high=1e3)
STEP = Parameter("step", "index of the step in ux0_history, from 0 (default: every step)", kind=INT,
                 low=0, high=10_000_000)
PROFILE = Parameter("profile", "indenter profile", kind=STR, default="paraboloid",
                    choices=("paraboloid", "cone", "power_law", "tabulated"), sweepable=False)
THETA_H = dataclasses.replace(THETA, when={"profile": ("cone",)})
R_H = dataclasses.replace(R, when={"profile": ("paraboloid",)})
GEOMETRY = (PROFILE, THETA_H, R_H, N, A, PROFILE_R, PROFILE_F)
PARAMETERS = (NU, MU, AMPLITUDE, STEP, E, DELTA) + GEOMETRY + (HISTORY, Y, X)
CASE = tuple(p.name for p in PARAMETERS if p.name not in SPATIAL)

LOADS = ("stick_radius", "tangential_force", "dissipated_energy", "cycle_energy", "ux0")
_NOT_LOCAL = ("contact_radius", "mean_pressure", "normal_force")


def _history_variables() -> tuple[Variable, ...]:
    base = []
    for v in _variables(CASE, tuple(p.name for p in GEOMETRY)):
        if v.name == "stick_radius":
            continue
        if v.name == "region":
            v = dataclasses.replace(v, comment=(
                "stick: r below the stick radius of the current step (these springs do not slip while "
                "u_x0 moves into this step; they may hold traction locked in by earlier steps); slip: the "
                "annulus that slips during that move; contact_without_tangential_traction: mu = 0 or no "
                "tangential displacement yet"))
        base.append(v)
    return tuple(base) + (
        Variable("stick_radius", "radius of the zone that does not slip during the move into this step (stick "
                 "radius of the current loading branch; a before any tangential displacement, 0 in gross slip)",
                 units_physical="m", scale="the contact radius a", dims=CASE),
        Variable("tangential_force", "tangential force F_x transmitted to the half-space (resultant of the shear "
                 "traction, along +x)", units_physical="N",
                 scale="mu F_N, the normal force times the coefficient of friction", dims=CASE,
                 comment="at mu = 0 the normalised value is the limit mu -> 0+ (+-1, gross slip)"),
        Variable("dissipated_energy", "energy dissipated by friction from the unloaded start up to this step",
                 units_physical="J", scale="mu F_N delta (coefficient of friction times normal force times "
                 "indentation depth)", dims=CASE,
                 comment="over a closed cycle the difference equals the area of the F_x-u_x0 loop; at mu = 0 "
                         "the normalised value is the limit mu -> 0+ (the sum of |du_x0|/delta)"),
        Variable("cycle_energy", "energy dissipated in the hysteresis cycle that closes at this step (the area "
                 "of its F_x-u_x0 loop; 0 where no cycle closes)", units_physical="J",
                 scale="mu F_N delta (coefficient of friction times normal force times indentation depth)",
                 dims=CASE,
                 comment="a cycle closes at step j when the spring state equals that of an earlier step i "
                         "(the latest such, with other states in between): cycle_energy = dissipated_energy[j] "
                         "- dissipated_energy[i]"),
        Variable("ux0", "tangential rigid-body displacement u_x0 at this step divided by the indentation depth "
                 "delta (amplitude times ux0_history)", dims=("amplitude", "step")),
    )


def _profile(p, physical):
    kind = p["profile"]
    if kind == "cone":
        return ax.cone(math.tan(p["theta"]) if physical else 1.0)
    if kind == "paraboloid":
        return ax.paraboloid(p["R"] if physical else 1.0)
    return _general(p, physical)


@functools.lru_cache(maxsize=32)
def _memory(history: tuple) -> tuple[list, list]:
    sts = hist.states(history)
    return sts, hist.closed_cycles(sts)


@functools.lru_cache(maxsize=256)
def _energy(history: tuple, a: float, nu: float, mu: float, profile, amplitude: float) -> np.ndarray:
    return hist.dissipated_energy(history, a, nu, mu, profile, scale=amplitude)


def evaluate(names, p, options):
    physical = options["physical"]
    profile = _profile(p, physical)
    f = lambda key: np.asarray(p[key], dtype=float)  # noqa: E731
    a = _contact_radius(profile, f("delta")) if physical else np.float64(1.0)
    out: dict[str, np.ndarray] = {}
    history = tuple(float(v) for v in np.asarray(p["ux0_history"]).ravel())
    if "ux0" in names:
        out["ux0"] = f("amplitude") * np.asarray(history)[np.asarray(p["step"], dtype=np.int64)]
    pm_hat = ax.mean_pressure(a, profile)
    e_star = f("E") / (1.0 - f("nu") ** 2) if physical else None
    if "contact_radius" in names:
        out["contact_radius"] = a
    if "mean_pressure" in names:
        out["mean_pressure"] = pm_hat * e_star if physical else pm_hat
    if "normal_force" in names:
        out["normal_force"] = profile.normal_force(a) * e_star
    local = [n for n in names if n not in _NOT_LOCAL + ("ux0",)]
    if not local:
        return out

    sts, cycles = _memory(history)
    steps = np.asarray(p["step"], dtype=np.int64)
    spatial = [n for n in local if n not in LOADS]
    keys = ["nu", "mu", "amplitude"] + (["x", "y"] if spatial else [])
    arrays = {k: f(k) for k in keys}
    arrays["a"] = np.asarray(a, dtype=float)
    arrays["step"] = steps
    if physical:
        arrays["e_star"] = np.asarray(e_star, dtype=float)
    shape = np.broadcast_shapes(*(np.shape(v) for v in arrays.values()))
    flat = {k: np.broadcast_to(v, shape).ravel() for k, v in arrays.items()}
    size = int(np.prod(shape, dtype=np.int64))
    results = {n: np.empty(size, dtype=np.int8 if n == "region" else float) for n in local if n != "validity"}

    method = options["method"]
    if method == "auto":
        method = "closed" if profile.has_closed_form else "quadrature"
    for s in np.unique(flat["step"]):
        idx = np.flatnonzero(flat["step"] == s)
        P = {k: v[idx] for k, v in flat.items()}
        terms = [(lam * P["amplitude"], w) for lam, w in sts[int(s)].terms()]
        terms = terms if np.any(P["amplitude"] > 0) else []
        _loads(names, results, idx, P, terms, profile, history, int(s), cycles, physical)
        if spatial:
            _fields(spatial, results, idx, P, terms, profile, physical, method, options["rtol"])
    out.update({n: v.reshape(shape) for n, v in results.items()})
    if "validity" in names:
        fields = [out[n] for n in out if n in STRESS + PRINCIPAL + ("von_mises", "dpdz")]
        out["validity"] = nonfinite_flag(*fields) if fields else np.int8(0)
    return out


def _loads(names, results, idx, P, terms, profile, history, step, cycles, physical):
    a, nu, mu = P["a"], P["nu"], P["mu"]
    force_scale = mu * profile.normal_force(a) * P["e_star"] if physical else 1.0
    if "stick_radius" in names:
        c = hist.current_stick_radius(terms, a, nu, mu, profile)
        results["stick_radius"][idx] = c if physical else c / a
    if "tangential_force" in names:
        results["tangential_force"][idx] = hist.tangential_force(terms, a, nu, mu, profile) * force_scale
    want = [n for n in ("dissipated_energy", "cycle_energy") if n in names]
    if want:
        energy_scale = force_scale * (profile.depth(a) if physical else 1.0)
        combos = np.stack([a, nu, mu, P["amplitude"]], axis=-1)
        uniq, inverse = np.unique(combos, axis=0, return_inverse=True)
        total = np.empty(len(uniq))
        cycle = np.zeros(len(uniq))
        for i, (ai, nui, mui, ampi) in enumerate(uniq):
            w = _energy(history, float(ai), float(nui), float(mui), profile, float(ampi))
            total[i] = w[step]
            if cycles[step] is not None:
                cycle[i] = w[step] - w[cycles[step]]
        inverse = inverse.ravel()
        if "dissipated_energy" in names:
            results["dissipated_energy"][idx] = total[inverse] * energy_scale
        if "cycle_energy" in names:
            results["cycle_energy"][idx] = cycle[inverse] * energy_scale


def _fields(spatial, results, idx, P, terms, profile, physical, method, rtol):
    a, nu, mu = P["a"], P["nu"], P["mu"]
    xs, ys = (P[k] * (1.0 if physical else a) for k in ("x", "y"))
    pm_hat = ax.mean_pressure(a, profile)
    stress_scale = P["e_star"] if physical else 1.0 / pm_hat
    want = [n for n in spatial if n in STRESS]
    if any(n in spatial for n in ("von_mises",) + PRINCIPAL):
        want = list(STRESS)
    if want:
        comps = tuple(n.removeprefix("sigma_") for n in want)
        sig = hist.history_stress(xs, ys, a, nu, mu, profile, terms, components=comps, method=method, rtol=rtol)
        stress = {f"sigma_{k}": v * stress_scale for k, v in sig.items()}
        for n in spatial:
            if n in STRESS:
                results[n][idx] = stress[n]
        if "von_mises" in spatial:
            results["von_mises"][idx] = von_mises(*(stress[s] for s in STRESS))
        if any(n in spatial for n in PRINCIPAL):
            for n, v in zip(PRINCIPAL, principal_stresses(*(stress[s] for s in STRESS))):
                if n in spatial:
                    results[n][idx] = v
    if "dpdz" in spatial:
        g = hist.history_dpdz(xs, ys, a, nu, mu, profile, terms, method=method, rtol=rtol)
        results["dpdz"][idx] = g * (P["e_star"] if physical else a / pm_hat)
    if "region" in spatial:
        r = np.hypot(xs, ys)
        c = hist.current_stick_radius(terms, a, nu, mu, profile)
        region = np.where(r > a, 0, np.where(r < c, 1, 2)).astype(np.int8)
        free = (mu == 0) | (P["amplitude"] == 0) | (not terms)
        results["region"][idx] = np.where(free & (r <= a), np.int8(3), region)


def _complete(values):
    """`step` is always a dimension: every step of the history by default, or the ones given."""
    n = len(values.get("ux0_history", ()))
    if n == 0:
        return
    if "step" not in values:
        values["step"] = np.arange(n, dtype=np.int32)
    else:
        values["step"] = np.atleast_1d(np.asarray(values["step"], dtype=np.int32))


def _check(values, physical, method):
    problems = _check_general(values, physical, method)
    n = len(values.get("ux0_history", ()))
    if n == 0:
        return problems
    steps = values["step"]
    if np.any(steps >= n):
        problems.append(f"step = {int(steps.max())} is beyond the history: ux0_history has {n} values "
                        f"(steps 0 to {n - 1})")
    return problems


AXISYMMETRIC_HISTORY = Scenario(
    name="axisymmetric_history",
    summary="Rigid axisymmetric indenter (paraboloid, cone, power law, tabulated profile) under constant normal "
            "load and an arbitrary tangential displacement history (fretting): surface stresses, dp/dz, "
            "stick zone, tangential force and frictional dissipation per step (MDR springs with memory, "
            "Mindlin-Deresiewicz)",
    theory="axisymmetric",
    references=REFERENCE + "; R. D. Mindlin, H. Deresiewicz, Elastic spheres in contact under varying oblique "
                           "forces, J. Appl. Mech. 20 (1953) 327-344",
    parameters=PARAMETERS,
    variables=_history_variables(),
    evaluate=evaluate,
    physical_switch="E",
    conventions=("tension positive, z points into the body, p_h = -trace(sigma)/3, tangential traction on the "
                 "half-space along +x for u_x0 > 0, F_x the force on the half-space along +x"),
    methods=("auto", "closed", "quadrature"),
    default_variables=STRESS + ("von_mises",) + PRINCIPAL + ("dpdz", "region") + LOADS,
    check=_check, complete=_complete, route=route,
)

SCENARIOS: tuple = (AXISYMMETRIC_HISTORY,)
