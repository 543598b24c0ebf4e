"""Tangential loading histories (fretting) on axisymmetric indenters at constant normal load.

Scenario `axisymmetric_history`: the fields of the `axisymmetric` scenarios after every
step of a tangential displacement history u_x0(t), from the MDR spring memory of eq. (27)-(28)
(``physics.axisymmetric.history_fields``; docs/theory/axisymmetric.md (A65)-(A77)), plus the tangential
force, the stick radius, and the energy dissipated by friction.  Parameters, normalisation
(p_m = F_N/(pi a^2)), physical mode (give E; the normal load as delta or normal_force) and flags
are those of the `axisymmetric` scenarios, and so is the depth `z`: below the surface the normal
interior field plus the same weighted sum of Cattaneo–Mindlin interior fields as on the surface
(docs/theory/axisymmetric.md (A69), docs/theory/interior.md (I23), (I33)).

The history is a sweep-free array parameter; its index is the dimension `step`.  `step` is an
ordinary sweepable integer parameter; when the recipe does not give it, the scenario's check fills
in every step (a parameter default cannot depend on another parameter).  `amplitude` multiplies
the whole history, so one history can be swept over amplitudes.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from ..physics.names import AXISYMMETRIC_METHODS, PRINCIPAL, STRESS
from .axisymmetric import (A, DELTA, DEPTH, E, MU, MU_FN, MU_FN_DELTA, N, NORMAL_FORCE, NU, PROFILE_F, PROFILE_R, R,
                           RADIUS_A, REFERENCE, THETA, X, Y, Z, case_of, check_depth, contact, grouped, make_profile,
                           route_of, scaled_fields, surface_point, variables)
from .base import ARRAY, INT, STR, Parameter, Scenario, Variable

HISTORY = Parameter("ux0_history", "tangential rigid-body displacements u_x0 divided by the indentation depth "
                    "delta, in order, starting from the unloaded state u_x0 = 0 (each step is reached "
                    "monotonically from the previous one)", kind=ARRAY, required=True, sweepable=False,
                    # cost grows with the steps: 10 points, 0.17 s at 10 steps, 4.2 s at 100
                    max_size=200, label="history of u_x0 / delta")
AMPLITUDE = Parameter("amplitude", "factor multiplying every value of ux0_history (sweep it to run one "
                      "history at several amplitudes)", default=1.0, low=0.0, high=1e3,
                      label="amplitude factor")
STEP = Parameter("step", "index of the step in ux0_history, from 0 (default: every step)", kind=INT,
                 low=0, high=10_000_000, label="step index")
PROFILE = Parameter("profile", "indenter profile", kind=STR, default="paraboloid",
                    choices=("paraboloid", "cone", "power_law", "tabulated"), sweepable=False)
THETA_H = dataclasses.replace(THETA, when={"profile": ("cone",)})
R_H = dataclasses.replace(R, when={"profile": ("paraboloid",)})
GEOMETRY = (PROFILE, THETA_H, R_H, N, A, PROFILE_R, PROFILE_F)
PARAMETERS = (NU, MU, AMPLITUDE, STEP, E, DELTA, NORMAL_FORCE) + GEOMETRY + (HISTORY, Z, Y, X)
CASE = tuple(p.name for p in PARAMETERS if p.name not in DEPTH)

LOADS = ("stick_radius", "tangential_force", "dissipated_energy", "cycle_energy", "ux0")


def _history_variables() -> tuple[Variable, ...]:
    base = []
    for v in variables(CASE, tuple(p.name for p in GEOMETRY), DEPTH, tangential=False):
        if v.name == "stick_radius":
            continue
        if v.name == "region":
            v = dataclasses.replace(v, comment=(
                "stick: r below the stick radius of the current step (these springs do not slip while"
                " u_x0 moves into this step; they may hold traction locked in by earlier steps); slip: the "
                "annulus that slips during that move; contact_without_tangential_traction: mu = 0 or no "
                "tangential displacement yet"))
        base.append(v)
    return tuple(base) + (
        Variable("stick_radius", "radius of the zone that does not slip during the move into this step (stick "
                 "radius of the current loading branch; a before any tangential displacement, 0 in gross slip)",
                 units_physical="m", scale=RADIUS_A, dims=CASE, label="stick radius c"),
        Variable("tangential_force", "tangential force F_x transmitted to the half-space (resultant of the shear "
                 "traction, along +x)", units_physical="N",
                 scale=MU_FN, dims=CASE,
                 comment="at mu = 0 the normalised value is the limit mu -> 0+ (+-1, gross slip)",
                 label="tangential F_x"),
        Variable("dissipated_energy", "energy dissipated by friction from the unloaded start up to this step",
                 units_physical="J", scale=MU_FN_DELTA, dims=CASE,
                 comment="over a closed cycle the difference equals the area of the F_x-u_x0 loop; at mu = 0 "
                         "the normalised value is the limit mu -> 0+ (the sum of |du_x0|/delta)",
                         label="W_diss"),
        Variable("cycle_energy", "energy dissipated in the hysteresis cycle that closes during the move into "
                 "this step, at its end or on the way (the area of its F_x-u_x0 loop; 0 where no cycle closes)",
                 units_physical="J",
                 scale=MU_FN_DELTA, dims=CASE,
                 comment="a cycle closes where u_x0 returns to the turning point that opened it (or passes the "
                         "mirror -e_1 of the only one), so that the spring state equals that of an earlier "
                         "point of the history (the latest such, with other states in between); cycle_energy "
                         "is the energy dissipated between the two, for the outermost cycle closing during the "
                         "move (cycles closing within one move are nested). For a cycle closing at the end of "
                         "step j on the state of step i it is dissipated_energy[j] - dissipated_energy[i]",
                         label="W_cycle"),
        # a coordinate, in every file: the loops are read and plotted against it
        Variable("ux0", "tangential rigid-body displacement u_x0 at this step divided by the indentation depth "
                 "delta (amplitude times ux0_history)", dims=("amplitude", "step"), always=True, coordinate=True,
                 label="u_x0 / delta"),
    )


VARIABLES = grouped(_history_variables())
DECLARED = {v.name: v for v in VARIABLES}


def evaluate(names, p, options):
    """Recipe values -> profile -> ``physics.axisymmetric.history_fields`` -> the variables' units."""
    from ..physics import axisymmetric as ax     # when computing: the declarations need only physics.names

    physical = options["physical"]
    profile = make_profile(p["profile"], p, physical)
    a, out = contact(names, p, profile, physical)
    if "ux0" in names:
        history = np.asarray(p["ux0_history"], dtype=float).ravel()
        out["ux0"] = np.asarray(p["amplitude"], dtype=float) * history[np.asarray(p["step"], dtype=np.int64)]
    local = [n for n in names if n in ax.HISTORY_FIELDS]
    if local:
        # per unit E* (the kernels' own unit): the scales follow, then the invariants
        values, _ = ax.history_fields(local, profile, *surface_point(p, physical, a, ("x", "y", "z")), a=a,
                                      nu=np.asarray(p["nu"], dtype=float), mu=np.asarray(p["mu"], dtype=float),
                                      amplitude=np.asarray(p["amplitude"], dtype=float), history=p["ux0_history"],
                                      step=p["step"], method=options["method"], rtol=options["rtol"],
                                      invariants=False)
        out.update(values)
    return scaled_fields(out, names, DECLARED, case_of(p, profile, a), physical)


_ROUTE = route_of(default=PROFILE.default)


def _route(values, method, rtol, groups):
    """The route of the `axisymmetric` scenarios, under tangential load where some step moves: the
    largest |u_x0|/delta of the history stands for their `ux0` (only whether it is > 0 matters)."""
    history = np.abs(np.asarray(values.get("ux0_history", ()), dtype=float))
    moved = np.max(np.asarray(values.get("amplitude", AMPLITUDE.default), dtype=float)) * (
        float(history.max()) if history.size else 0.0)
    return _ROUTE({**values, "ux0": moved}, method, rtol, groups)


def _complete(values):
    """`step` is always a dimension: every step of the history by default, or the ones given."""
    n = len(values.get("ux0_history", ()))
    if n == 0:
        return
    if "step" not in values:
        values["step"] = np.arange(n, dtype=np.int32)
    else:
        values["step"] = np.atleast_1d(np.asarray(values["step"], dtype=np.int32))


def _check(values, physical, options):
    problems = check_depth()({"profile": PROFILE.default, **values}, physical, options)
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
            "load and an arbitrary tangential displacement history (fretting): stresses and dp/dz on and below "
            "the surface, stick zone, tangential force and frictional dissipation per step (MDR springs with memory, "
            "Mindlin-Deresiewicz)",
    theory="axisymmetric",
    references=REFERENCE + "; R. D. Mindlin, H. Deresiewicz, Elastic spheres in contact under varying oblique "
                           "forces, J. Appl. Mech. 20 (1953) 327-344",
    parameters=PARAMETERS,
    variables=VARIABLES,
    evaluate=evaluate,
    physical_switch="E",
    conventions=("tension positive, z points into the body, p_h = -trace(sigma)/3, tangential traction on the "
                 "half-space along +x for u_x0 > 0, F_x the force on the half-space along +x"),
    methods=AXISYMMETRIC_METHODS,
    default_variables=STRESS + ("von_mises",) + PRINCIPAL + ("dpdz", "region") + LOADS,
    check=_check, complete=_complete, route=_route,
)

SCENARIOS: tuple = (AXISYMMETRIC_HISTORY,)
