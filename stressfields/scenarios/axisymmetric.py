"""Axisymmetric rigid indenters on a homogeneous elastic half-space: surface stress tensor and
hydrostatic-pressure gradient under normal and Cattaneo–Mindlin tangential load.

Scenarios `conical`, `parabolic` and `axisymmetric` (power law, tabulated profile, flat punch).
Normalised mode (default): x, y in units of the contact radius a, stresses divided by the mean
contact pressure p_m = F_N / (pi a^2), dp/dz by p_m / a. Physical mode (the recipe gives E):
metres, pascals. Equations, conventions and errata: docs/theory/axisymmetric.md (A1)-(A64).
"""
from __future__ import annotations

import math

import numpy as np

from ..physics import axisymmetric as ax
from ..physics.invariants import principal_stresses, von_mises
from .base import ARRAY, STR, Parameter, Scenario, Variable, nonfinite_flag

REFERENCE = ("E. Willert, F. Forsbach, V. L. Popov, Stress tensor and gradient of hydrostatic pressure "
             "in the contact plane of axisymmetric bodies under normal and tangential loading, "
             "Forschung im Ingenieurwesen (2020)")

STRESS = ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "sigma_yz")
PRINCIPAL = ("sigma_1", "sigma_2", "sigma_3")
PM = "the mean contact pressure p_m = F_N/(pi a^2)"
SPATIAL = ("y", "x")  # x last: a line along x is contiguous on disk

# -- parameters shared by the three scenarios ------------------------------------------------
NU = Parameter("nu", "Poisson's ratio of the half-space", default=0.3, low=0.0, high=0.5)
MU = Parameter("mu", "coefficient of friction", default=0.0, low=0.0, high=10.0)
UX0 = Parameter("ux0", "tangential rigid-body displacement u_x0 divided by the indentation depth delta "
                "(0: normal load only)", default=0.0, low=0.0, high=1e3)
E = Parameter("E", "Young's modulus of the half-space (giving it switches to physical units)",
              units="Pa", low=0.0, low_open=True, high=1e15, mode="physical")
DELTA = Parameter("delta", "indentation depth", units="m", low=0.0, low_open=True, high=1e3,
                  mode="physical")
X = Parameter("x", "surface coordinate x (direction of the tangential load) divided by the contact "
              "radius a", units="1", units_physical="m", required=True, low=-1e6, high=1e6)
Y = Parameter("y", "surface coordinate y divided by the contact radius a", units="1",
              units_physical="m", default=0.0, low=-1e6, high=1e6)
THETA = Parameter("theta", "inclination angle of the cone flank to the undeformed surface", units="rad",
                  low=0.0, low_open=True, high=math.pi / 2, high_open=True, sweepable=False,
                  mode="physical")
R = Parameter("R", "radius of curvature of the paraboloid tip, f = r^2/(2R)", units="m", low=0.0,
              low_open=True, high=1e6, sweepable=False, mode="physical")
PROFILE = Parameter("profile", "indenter profile", kind=STR, default="power_law",
                    choices=("power_law", "tabulated", "flat_punch"), sweepable=False)
N = Parameter("n", "exponent of the power-law profile f = A r^n", low=0.0, low_open=True, high=50.0,
              required=True, sweepable=False, when={"profile": ("power_law",)})
A = Parameter("A", "amplitude of the power-law profile f = A r^n, with r and f in metres (units m^(1-n))",
              low=0.0, low_open=True, high=1e30, sweepable=False, mode="physical",
              when={"profile": ("power_law",)})
RADIUS = Parameter("radius", "radius of the flat punch", units="m", low=0.0, low_open=True, high=1e6,
                   sweepable=False, mode="physical", when={"profile": ("flat_punch",)})
PROFILE_R = Parameter("profile_r", "radii of the tabulated profile f(r), from 0 (normalised mode: "
                      "divided by the contact radius a, covering [0, 1])", units="1", units_physical="m",
                      kind=ARRAY, required=True, sweepable=False, when={"profile": ("tabulated",)})
PROFILE_F = Parameter("profile_f", "heights f(r) of the tabulated profile, non-decreasing (normalised "
                      "mode: any length unit, the scale cancels)", units="1", units_physical="m",
                      kind=ARRAY, required=True, sweepable=False, when={"profile": ("tabulated",)})


def _variables(case: tuple[str, ...], geometry: tuple[str, ...]) -> tuple[Variable, ...]:
    """The output variables; `case` lists the non-spatial parameters, `geometry` the profile's."""
    everything = case + SPATIAL
    load = ("nu", "E", "delta") + geometry     # what fixes a, F_N and p_m
    stress = [Variable(f"sigma_{c}", f"surface stress component sigma_{c} at z = 0", units_physical="Pa",
                       scale=PM, dims=everything) for c in ("xx", "yy", "zz", "xy", "xz", "yz")]
    return tuple(stress) + (
        Variable("von_mises", "von Mises equivalent stress sqrt(3 J2) at z = 0", units_physical="Pa",
                 scale=PM, dims=everything),
        Variable("sigma_1", "largest principal stress at z = 0", units_physical="Pa", scale=PM, dims=everything),
        Variable("sigma_2", "intermediate principal stress at z = 0", units_physical="Pa", scale=PM,
                 dims=everything),
        Variable("sigma_3", "smallest principal stress at z = 0", units_physical="Pa", scale=PM, dims=everything),
        Variable("dpdz", "derivative of the hydrostatic pressure p_h = -trace(sigma)/3 with depth z at z = 0+",
                 units_physical="Pa m-1", scale="p_m/a, with p_m = F_N/(pi a^2) and a the contact radius",
                 dims=everything),
        Variable("stick_radius", "radius c of the stick zone (Cattaneo-Mindlin; 0 in gross slip; a under "
                 "normal load only)", units_physical="m", scale="the contact radius a", dims=case),
        Variable("mean_pressure", "mean contact pressure p_m = F_N/(pi a^2)", units_physical="Pa",
                 scale="the effective modulus E* = E/(1-nu^2)", dims=load),
        Variable("contact_radius", "contact radius a", units="m", dims=("delta",) + geometry, mode="physical"),
        Variable("normal_force", "normal force F_N", units="N", dims=load, mode="physical"),
        Variable("region", "contact region of the surface point", dtype="int8", dims=everything,
                 flag_values=(0, 1, 2, 3),
                 flag_meanings=("outside_contact", "stick", "slip", "contact_without_tangential_traction")),
        Variable("validity", "validity of the field values at the surface point", dtype="int8",
                 dims=everything, flag_values=(0, 1, 2),
                 flag_meanings=("finite", "unbounded_at_singular_point", "undefined_direction_dependent_limit"),
                 comment="1: a value is +-inf where the exact field is unbounded (cone tip r = 0; dpdz at the "
                         "contact edge r = a and the stick edge r = c; flat-punch edge); 2: a value is NaN where "
                         "the exact limit depends on the direction of approach (r = 0 under gross slip of a "
                         "cone). Only the variables in this file are considered.",
                 always=True),
    )


def _evaluate(make_profile):
    """An evaluate(names, params, options) for one profile family; make_profile(params, physical)."""

    def evaluate(names, p, options):
        physical = options["physical"]
        profile = make_profile(p, physical)
        f = lambda key: np.asarray(p[key], dtype=float)  # noqa: E731 - only what the group has
        if physical:
            a = _contact_radius(profile, f("delta"))
        else:
            a = np.float64(1.0)
        out: dict[str, np.ndarray] = {}
        if "contact_radius" in names:
            out["contact_radius"] = a
        pm_hat = ax.mean_pressure(a, profile)          # p_m / E*
        e_star = f("E") / (1.0 - f("nu") ** 2) if physical and ("E" in p) else None
        if "mean_pressure" in names:
            out["mean_pressure"] = pm_hat * e_star if physical else pm_hat
        if "normal_force" in names:
            out["normal_force"] = profile.normal_force(a) * e_star
        local = [n for n in names if n not in ("contact_radius", "mean_pressure", "normal_force")]
        if not local:
            return out

        nu, mu, ux0 = f("nu"), f("mu"), f("ux0")
        c = ax.stick_radius(a, nu, mu, ux0, profile)
        c_kernel, mu_kernel = c, mu
        if profile.kind == "flat_punch":
            # a flat punch either sticks whole or slides; sticking, its traction is the sliding one
            # with mu E* delta replaced by G* u_x0 (eq. 20), which the kernels take as c = 0
            stuck = (c == a) & (ux0 > 0) & (mu > 0)
            mu_kernel = np.where(stuck, 2.0 * (1.0 - nu) / (2.0 - nu) * ux0, mu)
            c_kernel = np.where(stuck, 0.0, c)
        if "stick_radius" in names:
            out["stick_radius"] = c if physical else c / a
        spatial = [n for n in local if n != "stick_radius"]
        if not spatial:
            return out
        xs, ys = (f(k) * (1.0 if physical else a) for k in ("x", "y"))
        method = options["method"]
        if method == "auto":
            method = "closed" if profile.has_closed_form else "quadrature"
        stress_scale = e_star if physical else 1.0 / pm_hat

        want_stress = [n for n in names if n in STRESS]
        if any(n in names for n in ("von_mises",) + PRINCIPAL):
            want_stress = list(STRESS)
        if want_stress:
            comps = tuple(n.removeprefix("sigma_") for n in want_stress)
            sig = ax.surface_stress(xs, ys, a, c_kernel, nu, mu_kernel, profile, components=comps, method=method,
                                    rtol=options["rtol"])
            stress = {f"sigma_{k}": v * stress_scale for k, v in sig.items()}
            out.update({n: stress[n] for n in names if n in STRESS})
            if "von_mises" in names:
                out["von_mises"] = von_mises(*(stress[s] for s in STRESS))
            if any(n in names for n in PRINCIPAL):
                out.update(zip(PRINCIPAL, principal_stresses(*(stress[s] for s in STRESS))))
        if "dpdz" in names:
            g = ax.surface_dpdz(xs, ys, a, c_kernel, nu, mu_kernel, profile, method=method, rtol=options["rtol"])
            out["dpdz"] = g * (e_star if physical else a / pm_hat)
        if "region" in names:
            out["region"] = _region(np.hypot(xs, ys), a, c, mu, ux0)
        if "validity" in names:
            fields = [out[n] for n in out if n in STRESS + PRINCIPAL + ("von_mises", "dpdz")]
            out["validity"] = nonfinite_flag(*fields) if fields else np.int8(0)
        return out

    return evaluate


def _region(r, a, c, mu, ux0):
    region = np.where(r > a, 0, np.where(r < c, 1, 2)).astype(np.int8)
    no_traction = (np.asarray(mu) == 0) | (np.asarray(ux0) == 0)
    return np.where(no_traction & (r <= a), np.int8(3), region)


def _contact_radius(profile, delta: np.ndarray) -> np.ndarray:
    return np.vectorize(profile.contact_radius, otypes=[float])(delta)


def _cone(p, physical):
    return ax.cone(math.tan(p["theta"]) if physical else 1.0)


def _paraboloid(p, physical):
    return ax.paraboloid(p["R"] if physical else 1.0)


def _general(p, physical):
    kind = p["profile"]
    if kind == "power_law":
        return ax.power_law(p["A"] if physical else 1.0, p["n"])
    if kind == "flat_punch":
        return ax.flat_punch(p["radius"], depth=float(p["delta"])) if physical else ax.flat_punch(1.0)
    return ax.tabulated(np.asarray(p["profile_r"]), np.asarray(p["profile_f"]))


def _check_general(values, physical, method):
    problems = []
    if values.get("profile") == "tabulated" and "profile_r" in values and "profile_f" in values:
        r, f = np.asarray(values["profile_r"]), np.asarray(values["profile_f"])
        if r.shape != f.shape:
            return [f"profile_r has {r.size} values but profile_f has {f.size}; they must pair up"]
        try:
            profile = ax.tabulated(r, f)
        except ValueError as exc:
            return [f"profile_r/profile_f: {exc}"]
        if r[0] != 0.0:
            problems.append(f"profile_r must start at 0, got {r[0]!r}")
        if not physical and r[-1] < 1.0:
            problems.append(f"profile_r must cover the contact, r/a in [0, 1]; it ends at {r[-1]!r}")
        if physical and "delta" in values:
            deltas = np.atleast_1d(values["delta"])
            reach = float(profile.depth(r[-1]))
            if np.any(deltas > reach):
                problems.append(f"delta = {float(deltas.max())!r} m exceeds the depth {reach!r} m at which the "
                                f"contact reaches the end of the table, r = {r[-1]!r} m; extend profile_r")
    if values.get("profile") == "flat_punch" and isinstance(values.get("delta"), np.ndarray):
        problems.append("delta cannot be swept for profile = 'flat_punch': its contact radius is the punch "
                        "radius and every field scales with delta; give one value")
    if method == "closed" and values.get("profile") in ("tabulated", "power_law") and not (
            values.get("profile") == "power_law" and values.get("n") in (1.0, 2.0)):
        problems.append(f"method.method = 'closed' has no closed form for profile = {values.get('profile')!r}; "
                        "use 'auto' or 'quadrature'")
    return problems


def route(values, method, rtol):
    """Which route `auto` takes (closed forms where they exist, eq. 1, 3, 14-17, 36-41) and how
    accurate it is; the quadrature's order comes from a table verified against rtol."""
    profile = values.get("profile")
    closed = profile in (None, "flat_punch", "cone", "paraboloid") or (
        profile == "power_law" and values.get("n") in (1.0, 2.0))
    if method == "closed" or (method == "auto" and closed):
        return "closed form", "double-precision rounding (relative error about 1e-14)"
    return ("one-dimensional Gauss quadrature of the MDR integrals",
            f"relative error below rtol = {rtol:g} of the mean contact pressure scale")


def _scenario(name, summary, geometry, make_profile, check=None):
    params = (NU, MU, UX0, E, DELTA) + geometry + (Y, X)
    case = tuple(p.name for p in params if p.name not in SPATIAL)
    return Scenario(
        name=name, summary=summary, references=REFERENCE, theory="axisymmetric", parameters=params,
        variables=_variables(case, tuple(p.name for p in geometry)), evaluate=_evaluate(make_profile), physical_switch="E",
        methods=("auto", "closed", "quadrature"),
        default_variables=STRESS + ("von_mises",) + PRINCIPAL + ("dpdz", "stick_radius", "region"),
        check=check, route=route,
    )


CONICAL = _scenario("conical", "Rigid cone on an elastic half-space: surface stresses and dp/dz under normal "
                    "and Cattaneo-Mindlin tangential load", (THETA,), _cone)
PARABOLIC = _scenario("parabolic", "Rigid paraboloid (Hertz-Mindlin) on an elastic half-space: surface stresses "
                      "and dp/dz under normal and Cattaneo-Mindlin tangential load", (R,), _paraboloid)
AXISYMMETRIC = _scenario("axisymmetric", "Rigid axisymmetric indenter of any profile (power law, tabulated, flat "
                         "punch) on an elastic half-space: surface stresses and dp/dz (MDR, 1-D integrals)",
                         (PROFILE, N, A, RADIUS, PROFILE_R, PROFILE_F), _general, _check_general)
