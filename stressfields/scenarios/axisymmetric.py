"""Axisymmetric rigid indenters on a homogeneous elastic half-space: stress tensor and
hydrostatic-pressure gradient under normal and Cattaneo–Mindlin tangential load, on the surface and
below it (depth z > 0).

Scenarios `conical`, `parabolic` and `axisymmetric` (power law, tabulated profile, flat punch).
Normalised mode (default): x, y, z in units of the contact radius a, stresses divided by the mean
contact pressure p_m = F_N / (pi a^2), dp/dz by p_m / a. Physical mode (the recipe gives E):
metres, pascals. Load control: the normal load as delta or normal_force (physical mode), the
tangential load as ux0, fx = F_x/(mu F_N) or tangential_force (physical mode); the others are
derived (Cattaneo–Mindlin in the MDR, (A4), (A32)-(A34)) and can be written as variables.
Equations, conventions and errata: docs/theory/axisymmetric.md (A1)-(A64), below the surface
docs/theory/interior.md (I1)-(I28).

This module declares and maps: recipe values -> a ``physics.axisymmetric`` profile -> one call of
``physics.axisymmetric.fields`` (which decides the route, ``physics.axisymmetric.resolve``) -> the
variables' units (``scales``).  The `axisymmetric_history` scenario shares the public helpers.
The functions that compute import ``physics.axisymmetric`` when they run: the declarations need only
``physics.names``, so that listing and describing the scenarios loads no kernel and no SciPy.
"""
from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, Any, Mapping

import numpy as np

from ..physics.flags import Validity as V
from ..physics.flags import declare
from ..physics.names import AXISYMMETRIC_METHODS, PRINCIPAL, STRESS
from .base import ARRAY, MAX_TABLE_SIZE, STR, Parameter, Scenario, Variable, table_step_problem
from .scales import Case, Scale, apply_scales, effective_modulus

if TYPE_CHECKING:
    from ..physics.axisymmetric import Profile

REFERENCE = ("E. Willert, F. Forsbach, V. L. Popov, Stress tensor and gradient of hydrostatic pressure "
             "in the contact plane of axisymmetric bodies under normal and tangential loading, "
             "Forschung im Ingenieurwesen (2020)")

#: the codes of the field validity and of the peaks' (physics.flags)
FIELD_CODES = (V.within_stated_accuracy, V.unbounded_at_singular_point, V.undefined_direction_dependent_limit,
               V.not_resolved_below_the_surface)
PEAK_CODES = (V.within_stated_accuracy, V.unbounded_at_singular_point, V.undefined_direction_dependent_limit,
              V.search_not_converged)
# -- the family's scales: the physics' values are per unit E* (stresses; dp/dz per E*/length),
# per delta (displacements), lengths in the profile's unit; the block's Case (``case_of``) holds
# a, p_m/E*, E*, delta, F_N/E* and mu, each computed when a factor first asks for it.  In normalised
# mode the geometry is the unit one (a = 1), so dividing by a is exact.
PM = Scale("p_m", "the mean contact pressure p_m = F_N/(pi a^2)",
           lambda c, physical: c["E*"] if physical else 1.0 / c["p_m/E*"],
           value=lambda q: q["mean_pressure"], needs=("mean_pressure",), definition="mean_pressure")
PM_PER_A = Scale("(p_m/a)", "p_m/a, with p_m = F_N/(pi a^2) and a the contact radius",
                 lambda c, physical: c["E*"] if physical else c["a"] / c["p_m/E*"],
                 value=lambda q: q["mean_pressure"] / q["contact_radius"], needs=("mean_pressure", "contact_radius"),
                 definition="mean_pressure / contact_radius")
E_STAR = Scale("E*", "the effective modulus E* = E/(1-nu^2)", lambda c, physical: c["E*"] if physical else 1.0)
RADIUS_A = Scale("a", "the contact radius a", lambda c, physical: 1.0 if physical else 1.0 / c["a"],
                 value=lambda q: q["contact_radius"], needs=("contact_radius",), definition="contact_radius")
DEPTH_DELTA = Scale("delta", "the indentation depth delta", lambda c, physical: c["delta"] if physical else 1.0)
MU_FN = Scale("(mu F_N)", "mu F_N, the normal force times the coefficient of friction",
              lambda c, physical: c["mu"] * c["F_N/E*"] * c["E*"] if physical else 1.0)
MU_FN_DELTA = Scale("(mu F_N delta)", "mu F_N delta (coefficient of friction times normal force times indentation "
                    "depth)", lambda c, physical: c["mu"] * c["F_N/E*"] * c["E*"] * c["delta"] if physical else 1.0)
SPATIAL = ("y", "x")  # x last: a line along x is contiguous on disk
DEPTH = ("z",) + SPATIAL  # z before y, x: a surface-parallel plane is contiguous on disk

# -- parameters shared by the three scenarios ------------------------------------------------
NU = Parameter("nu", "Poisson's ratio of the half-space", default=0.3, low=0.0, high=0.5,
               label="Poisson's ratio nu")
MU = Parameter("mu", "coefficient of friction", default=0.0, low=0.0, high=10.0)
UX0 = Parameter("ux0", "tangential rigid-body displacement u_x0 divided by the indentation depth delta "
                "(0: normal load only; or give fx, or tangential_force in physical mode)", default=0.0, low=0.0,
                high=1e3, when={"fx": (None,), "tangential_force": (None,)}, label="u_x0 / delta")
FX = Parameter("fx", "tangential force F_x divided by mu F_N (Cattaneo-Mindlin, instead of ux0; 1: onset of gross "
               "slip)", low=0.0, high=1.0, label="F_x / (mu F_N)")
# mode None, not "physical": a physical-mode parameter is required, and these are alternatives (the
# check refuses them in normalised mode, in the words of the recipe's own mode check)
TANGENTIAL_FORCE = Parameter("tangential_force", "tangential force F_x on the half-space along +x, at most mu F_N "
                             "(instead of ux0; physical mode)", units="N", low=0.0, high=1e15,
                             when={"fx": (None,)}, label="tangential force F_x")
E = Parameter("E", "Young's modulus of the half-space (giving it switches to physical units)",
              units="Pa", low=0.0, low_open=True, high=1e15, mode="physical", label="Young's modulus E")
DELTA = Parameter("delta", "indentation depth (or give normal_force instead)", units="m", low=0.0, low_open=True,
                  high=1e3, mode="physical", when={"normal_force": (None,)}, label="indentation depth delta")
NORMAL_FORCE = Parameter("normal_force", "normal force F_N pressing the indenter (instead of delta; physical mode)",
                         units="N", low=0.0, low_open=True, high=1e15, label="normal force F_N")
#: the parameters above that only physical mode gives meaning to, though not declared physical
PHYSICAL_LOADS = ("normal_force", "tangential_force")
X = Parameter("x", "surface coordinate x (direction of the tangential load) divided by the contact "
              "radius a", units="1", units_physical="m", required=True, low=-1e6, high=1e6,
              meaning_physical="surface coordinate x (direction of the tangential load)",
              label="x / a", label_physical="x", axis="X")
Y = Parameter("y", "surface coordinate y divided by the contact radius a", units="1",
              units_physical="m", default=0.0, low=-1e6, high=1e6, meaning_physical="surface coordinate y",
              label="y / a", label_physical="y", axis="Y")
Z = Parameter("z", "depth below the surface divided by the contact radius a (0: the surface)", units="1",
              units_physical="m", default=0.0, low=0.0,
              high=1e6, meaning_physical="depth below the surface (0: the surface)",
              label="depth z / a", label_physical="depth z", axis="Z")
THETA = Parameter("theta", "inclination angle of the cone flank to the undeformed surface", units="rad",
                  low=0.0, low_open=True, high=math.pi / 2, high_open=True, sweepable=False,
                  mode="physical", label="cone angle theta")
R = Parameter("R", "radius of curvature of the paraboloid tip, f = r^2/(2R)", units="m", low=0.0,
              low_open=True, high=1e6, sweepable=False, mode="physical", label="tip radius R")
PROFILE = Parameter("profile", "indenter profile", kind=STR, default="power_law",
                    choices=("power_law", "tabulated", "flat_punch"), sweepable=False)
N = Parameter("n", "exponent of the power-law profile f = A r^n", low=0.0, low_open=True, high=50.0,
              required=True, sweepable=False, when={"profile": ("power_law",)}, label="power-law exponent n")
A = Parameter("A", "amplitude of the power-law profile f = A r^n, with r and f in metres (units m^(1-n))",
              low=0.0, low_open=True, high=1e30, sweepable=False, mode="physical",
              when={"profile": ("power_law",)}, label="power-law amplitude A")
RADIUS = Parameter("radius", "radius of the flat punch", units="m", low=0.0, low_open=True, high=1e6,
                   sweepable=False, mode="physical", when={"profile": ("flat_punch",)})
PROFILE_R = Parameter("profile_r", "radii of the tabulated profile f(r), from 0 (normalised mode: "
                      "divided by the contact radius a, covering [0, 1])", units="1", units_physical="m",
                      kind=ARRAY, required=True, sweepable=False, when={"profile": ("tabulated",)},
                      max_size=MAX_TABLE_SIZE,
                      meaning_physical="radii of the tabulated profile f(r), from 0",
                      label="profile radii r / a", label_physical="profile radii r")
PROFILE_F = Parameter("profile_f", "heights f(r) of the tabulated profile, non-decreasing (normalised "
                      "mode: any length unit, the scale cancels), interpolated by a not-a-knot cubic spline; "
                      "data whose contact pressure would be tensile anywhere in the contact (p < -1e-9 p_m) "
                      "are refused by the recipe check", units="1", units_physical="m",
                      kind=ARRAY, required=True, sweepable=False, when={"profile": ("tabulated",)},
                      max_size=MAX_TABLE_SIZE,
                      meaning_physical="heights f(r) of the tabulated profile, non-decreasing, interpolated by a "
                                       "not-a-knot cubic spline; data whose contact pressure would be tensile "
                                       "anywhere in the contact (p < -1e-9 p_m) are refused by the recipe check",
                                       label="profile heights f")


DISPLACEMENT_COMMENT = (
    "The displacement of the half-space, vanishing at infinity: normal and Cattaneo-Mindlin tangential parts "
    "superposed (uncoupled, as the stresses), so at the surface inside the contact u_z = delta - f(r) plus the "
    "(1-2nu) Cerruti part of the tangential traction, and in the stick zone u_x is the rigid-body displacement "
    "u_x0 plus the radial displacement of the normal pressure (both extra parts vanish at nu = 0.5). Finite "
    "everywhere, edge rings included (docs/theory/interior.md (I36)-(I44)). Closed forms for the flat punch and the "
    "paraboloid; other profiles by the 1-D superposition of punches within rtol * delta, whatever the method.")


def variables(case: tuple[str, ...], geometry: tuple[str, ...], spatial: tuple[str, ...] = SPATIAL,
              tangential: bool = True) -> tuple[Variable, ...]:
    """The output variables; `case` lists the non-spatial parameters, `geometry` the profile's,
    `spatial` the point's coordinates (SPATIAL: the surface; DEPTH: with the depth z); `tangential`:
    with the tangential load variables (ux0, fx, tangential_force) of a Cattaneo–Mindlin load."""
    everything = case + spatial
    surface = case + SPATIAL
    load = ("nu", "E", "delta", "normal_force") + geometry     # what fixes a, F_N and p_m
    deep = "z" in spatial
    at = "at depth z (z = 0: the surface)" if deep else "at z = 0"
    stress = [Variable(f"sigma_{c}", f"{'stress' if deep else 'surface stress'} component sigma_{c} {at}",
                       units_physical="Pa", scale=PM, dims=everything,
                       label=f"stress sigma_{c}") for c in ("xx", "yy", "zz", "xy", "xz", "yz")]
    singular = ("cone tip r = 0; dpdz at the contact edge r = a and the stick edge r = c; flat-punch edge")
    return tuple(stress) + (
        Variable("von_mises", f"von Mises equivalent stress sqrt(3 J2) {at}", units_physical="Pa",
                 scale=PM, dims=everything, label="von Mises stress"),
        Variable("sigma_1", f"largest principal stress {at}", units_physical="Pa", scale=PM, dims=everything,
                 label="sigma_1 (largest)"),
        Variable("sigma_2", f"intermediate principal stress {at}", units_physical="Pa", scale=PM,
                 dims=everything, label="sigma_2 (middle)"),
        Variable("sigma_3", f"smallest principal stress {at}", units_physical="Pa", scale=PM, dims=everything,
                 label="sigma_3 (smallest)"),
        Variable("tau_max", f"maximum shear stress (sigma_1 - sigma_3)/2 {at}", units_physical="Pa", scale=PM,
                 dims=everything, label="shear stress tau_max"),
        Variable("dpdz", "derivative of the hydrostatic pressure p_h = -trace(sigma)/3 with depth z "
                 + ("(at z = 0: the limit z -> 0+)" if deep else "at z = 0+"),
                 units_physical="Pa/m", scale=PM_PER_A,
                 dims=everything, label="gradient dp_h/dz"),
    ) + tuple(
        Variable(f"u_{c}", f"displacement component u_{c} {at}" + (" (positive into the body)" if c == "z" else ""),
                 units_physical="m", scale=DEPTH_DELTA, dims=everything,
                 comment=DISPLACEMENT_COMMENT, label=f"displacement u_{c}") for c in "xyz"
    ) + (
        Variable("stick_radius", "radius c of the stick zone (Cattaneo-Mindlin; 0 in gross slip; a under "
                 "normal load only)", units_physical="m", scale=RADIUS_A, dims=case,
                 label="stick radius c"),
        Variable("mean_pressure", "mean contact pressure p_m = F_N/(pi a^2)", units_physical="Pa",
                 scale=E_STAR, dims=load, label="mean pressure p_m"),
        Variable("contact_radius", "contact radius a", units="m", dims=load, mode="physical",
                 recorded_when=("normal_force",)),
        Variable("normal_force", "normal force F_N", units="N", dims=load, mode="physical"),
        Variable("delta", "indentation depth delta", units="m", dims=load, mode="physical",
                 recorded_when=("normal_force",), label="indentation depth delta"),
        Variable("region", "contact region of the surface point", dtype="int8", dims=surface,
                 label="contact region",
                 flag_values=(0, 1, 2, 3),
                 flag_meanings=("outside_contact", "stick", "slip", "contact_without_tangential_traction"),
                 comment=("Of the surface point (x, y) above the field point: independent of the depth z."
                          if deep else None)),
        Variable("validity", f"validity of the field values at the {'point' if deep else 'surface point'}",
                 dtype="int8", dims=everything,
                 **declare(FIELD_CODES, where={
                     V.unbounded_at_singular_point: singular + ("; all at z = 0" if deep else ""),
                     V.undefined_direction_dependent_limit: "r = 0 under gross slip of a cone",
                     **({V.not_resolved_below_the_surface: "below the surface (z > 0) every exact value is finite; "
                         "a NaN there lies closer than ~1e-100 a to the axis or the surface"} if deep else {})},
                     note="Only the variables in this file are considered."),
                 always=True, label="validity of the field values"),
    ) + (tangential_loads(case) if tangential else ())


def group_of(name: str) -> str:
    """The route group of a variable of the family (``routes.GROUPS``)."""
    if name.startswith("u_"):
        return "displacement"
    if name == "dpdz":
        return name
    if name.endswith(("_peak", "_peak_r", "_peak_depth")):
        return "peaks"
    if name.startswith("sigma_") or name in ("von_mises", "tau_max"):
        return "stress"
    return "contact"


def grouped(declared) -> tuple[Variable, ...]:
    """The declarations, each float variable with its route group (``group_of``)."""
    return tuple(dataclasses.replace(v, group=group_of(v.name)) if not v.flag_values else v for v in declared)


def tangential_loads(case: tuple[str, ...]) -> tuple[Variable, ...]:
    """The tangential load in its three forms (the one the recipe gives is a coordinate instead)."""
    return (
        Variable("ux0", "tangential rigid-body displacement u_x0 divided by the indentation depth delta "
                 "(Cattaneo-Mindlin, docs/theory/axisymmetric.md (A32))", dims=case,
                 recorded_when=("fx", "tangential_force"),
                 comment="at fx = 1 the displacement of the onset of gross slip, mu E*/G*", label="u_x0 / delta"),
        Variable("fx", "tangential force F_x divided by mu F_N (1 in gross slip)", dims=case,
                 recorded_when=("tangential_force",),
                 comment="at mu = 0 with ux0 > 0 the limit mu -> 0+ (1, gross slip)", label="F_x / (mu F_N)"),
        Variable("tangential_force", "tangential force F_x on the half-space along +x", units="N", dims=case,
                 mode="physical", recorded_when=("fx",), label="tangential force F_x"),
    )


# -- evaluation: recipe values -> profile -> physics.axisymmetric.fields -> variables' units --------

def _f(p, key: str) -> np.ndarray:
    return np.asarray(p[key], dtype=float)


def make_profile(kind: str, p: Mapping[str, Any], physical: bool) -> Profile:
    """The physics profile of a recipe (``kind`` a profile kind of ``physics.axisymmetric``).  In
    normalised mode the geometry is the unit one: lengths are in units of a and stresses in units
    of p_m, which the profile's scale cancels from."""
    from ..physics import axisymmetric as ax
    if kind == "cone":
        return ax.cone(math.tan(p["theta"]) if physical else 1.0)
    if kind == "paraboloid":
        return ax.paraboloid(p["R"] if physical else 1.0)
    if kind == "power_law":
        return ax.power_law(p["A"] if physical else 1.0, p["n"])
    if kind == "flat_punch":
        return ax.flat_punch(p["radius"], depth=float(punch_depth(p))) if physical else ax.flat_punch(1.0)
    return ax.tabulated(np.asarray(p["profile_r"]), np.asarray(p["profile_f"]))


def e_star(p: Mapping[str, Any]) -> np.ndarray:
    """E* = E/(1 - nu^2) of the recipe (physical mode; ``scales.effective_modulus``)."""
    return effective_modulus(_f(p, "E"), _f(p, "nu"))


def punch_depth(p: Mapping[str, Any]) -> np.ndarray:
    """The flat punch's depth: delta, or F_N/(2 E* radius) of the normal force
    (docs/theory/axisymmetric.md (A8))."""
    if "normal_force" in p:
        return _f(p, "normal_force") / (2.0 * e_star(p) * _f(p, "radius"))
    return _f(p, "delta")


def case_of(p: Mapping[str, Any], profile: Profile, a) -> Case:
    """The quantities the family's scales read for a block: the contact radius a (1 normalised),
    p_m/E*, E* (physical mode), delta, F_N/E* and mu, each computed on first use."""
    from ..physics.axisymmetric import mean_pressure

    return Case(a=a, mu=lambda: _f(p, "mu"), delta=lambda: profile.depth(a), **{
        "p_m/E*": lambda: mean_pressure(a, profile), "E*": lambda: e_star(p),
        "F_N/E*": lambda: profile.normal_force(a)})


#: the variables of the normal contact alone (dims: the load, not the tangential parameters)
CONTACT = ("contact_radius", "delta", "mean_pressure", "normal_force")


def contact(names, p: Mapping[str, Any], profile: Profile, physical: bool) -> tuple[np.ndarray, dict]:
    """The contact radius a (physical mode: from delta (A3), or from normal_force by inverting (A4); 1
    normalised, lengths in units of a) and the requested ones of contact_radius, delta, mean_pressure,
    normal_force in the variables' units."""
    from ..physics import axisymmetric as ax
    from ..physics.axisymmetric.profiles import radius_at_force

    if not physical:
        a = np.float64(1.0)
    elif "normal_force" in p:
        a = radius_at_force(profile, _f(p, "normal_force") / e_star(p))
    else:
        a = ax.contact_radius(profile, _f(p, "delta"))
    out: dict[str, np.ndarray] = {}
    if "contact_radius" in names:
        out["contact_radius"] = a
    if "delta" in names:
        out["delta"] = profile.depth(a)
    if "mean_pressure" in names:
        out["mean_pressure"] = ax.mean_pressure(a, profile)          # p_m / E*: its scale is E*
    if "normal_force" in names:
        out["normal_force"] = profile.normal_force(a) * e_star(p)
    return a, out


def tangential_load(names, p: Mapping[str, Any], profile: Profile, physical: bool, a) -> tuple:
    """ux0 = u_x0/delta for the kernels, from ux0, fx or tangential_force (Cattaneo–Mindlin in the MDR,
    docs/theory/axisymmetric.md (A32)-(A34), (A37)), and the requested ones of ux0, fx, tangential_force."""
    from ..physics.axisymmetric.profiles import (displacement_ratio, force_ratio, slip_of_displacement, slip_ratio,
                                                 stick_radius_of_force)

    nu, mu = _f(p, "nu"), _f(p, "mu")
    if "ux0" in p:
        ux0 = _f(p, "ux0")
        fx = c = None
    else:
        fx, keep = _ratio_of_force(p, profile, a) if "tangential_force" in p else (_f(p, "fx"), 1.0 - _f(p, "fx"))
        ux0 = displacement_ratio(slip_ratio(profile, a, fx, keep), nu, mu)
        # the stick radius from the force itself (not through ux0): F_N(c) = (1 - fx) F_N(a), (A107)
        c = stick_radius_of_force(profile, a, keep)
    out: dict[str, np.ndarray] = {}
    if "ux0" in names:
        out["ux0"] = ux0
    if fx is None and ({"fx", "tangential_force"} & set(names)):
        fx = force_ratio(profile, a, slip_of_displacement(ux0, nu, mu))
    if "fx" in names:
        out["fx"] = fx
    if "tangential_force" in names:
        out["tangential_force"] = fx * mu * _normal_force(p, profile, a)
    return ux0, c, out


def _normal_force(p, profile, a) -> np.ndarray:
    """F_N (physical): as given, else of the contact radius (A4); the given one exactly, so that
    tangential_force = mu * normal_force is gross slip (fx = 1) without rounding."""
    return _f(p, "normal_force") if "normal_force" in p else profile.normal_force(a) * e_star(p)


def _ratio_of_force(p, profile, a) -> tuple[np.ndarray, np.ndarray]:
    """fx = F_x/(mu F_N) of tangential_force and 1 - fx formed without cancellation
    (``profiles.remaining_force``); fx 0 without force (also at mu = 0, which the check allows only
    then); at most 1 (the check refuses more than mu F_N: the ratio exceeds 1 only by rounding), and 1
    where 1 - fx is 0."""
    from ..physics.axisymmetric.profiles import remaining_force

    force, mu, normal = _f(p, "tangential_force"), _f(p, "mu"), _normal_force(p, profile, a)
    keep = remaining_force(force, mu, normal)
    with np.errstate(divide="ignore", invalid="ignore"):
        fx = np.where(force == 0.0, 0.0, np.where(keep <= 0.0, 1.0, np.minimum(force / (mu * normal), 1.0)))
    return fx, keep


def surface_point(p: Mapping[str, Any], physical: bool, a, keys: tuple[str, ...] = ("x", "y")) -> tuple:
    """x, y (and z, if in ``keys``) in the profile's length unit (None where the group has none)."""
    length = 1.0 if physical else a
    return tuple(_f(p, k) * length if k in p else None for k in keys)


def _evaluate(kind: str | None, declared: Mapping[str, Variable]):
    """An evaluate(names, params, options) for one profile kind (None: the recipe's `profile`) and the
    scenario's variables ``declared`` (name -> Variable: their scales)."""

    def evaluate(names, p, options):
        from ..physics import axisymmetric as ax

        physical = options["physical"]
        profile = make_profile(kind or p["profile"], p, physical)
        a, out = contact(names, p, profile, physical)
        case = case_of(p, profile, a)
        if set(names) <= set(CONTACT):      # their group's block carries no tangential parameter
            return apply_scales(out, declared, case, physical)
        ux0, stick, loads = tangential_load(names, p, profile, physical, a)
        out.update(loads)
        p = {**p, "ux0": ux0}
        local = [n for n in names if n in ax.FIELDS]
        if any(n in ax.PEAKS for n in names):
            out.update(peak_values(names, p, options, profile, a))
        if local:
            # per unit E* (the kernels' own unit): the scales follow, then the invariants
            values, _ = ax.fields(local, profile, *surface_point(p, physical, a, ("x", "y", "z")), a=a,
                                  nu=_f(p, "nu"), mu=_f(p, "mu"), ux0=_f(p, "ux0"), stick=stick,
                                  method=options["method"], rtol=options["rtol"], invariants=False)
            out.update(values)
        return scaled_fields(out, names, declared, case, physical)

    return evaluate


def scaled_fields(values: dict, names, declared: Mapping[str, Variable], case, physical: bool) -> dict:
    """``values`` in their variables' units (``apply_scales``) and the invariants asked for in
    ``names`` formed from the scaled stress tensor (``physics.axisymmetric.stress_invariants``).

    ``values`` holds what ``fields`` / ``history_fields`` return with ``invariants=False``: the six
    stress components and "singular" where invariants were asked for, and the other values' validity
    flag.  The invariants of the tensor in the variables' units are not the scaled invariants per unit
    E* to the last bit: formed here, they keep the tensor's rounding, as the stress components do."""
    from ..physics import axisymmetric as ax

    values = dict(values)
    singular = values.pop("singular", None)
    out = apply_scales(values, declared, case, physical)
    inv = [n for n in ax.INVARIANTS if n in names]
    if inv:
        factor = declared["sigma_xx"].scale.factor(case, physical)   # the tensor's, which the remainder takes
        out.update(ax.stress_invariants(inv, out, singular, factor,
                                        validity=out["validity"] if "validity" in names else None))
        for s in ax.STRESS:
            if s not in names:
                del out[s]
    return out


def peak_values(names, p, options, profile, a) -> dict:
    """The requested peak variables: ``physics.axisymmetric.peaks`` per case, in the physics' units
    (stresses per E*, positions in the profile's length unit; their scales follow)."""
    from ..physics import axisymmetric as ax

    found = ax.peaks(profile, a=a, nu=_f(p, "nu"), mu=_f(p, "mu"), ux0=_f(p, "ux0"), method=options["method"],
                     rtol=options["rtol"])
    return {n: found[n] for n in names if n in ax.PEAKS}


def check_profile(values, physical):
    """User messages for the profile parameters (a method the profile has no route for is the route
    table's to refuse: ``Scenario.route_problems``).  Only a tabulated profile imports the physics (a
    plain recipe is checked without it)."""
    problems = []
    kind = values.get("profile")
    if kind == "tabulated" and "profile_r" in values and "profile_f" in values:
        r, f = np.asarray(values["profile_r"]), np.asarray(values["profile_f"])
        if r.shape != f.shape:
            return [f"profile_r has {r.size} values but profile_f has {f.size}; they must pair up"]
        step = table_step_problem("profile_r", r)    # before building: a 1e-300 step stalls the table
        if step:
            return [step]
        from ..physics import axisymmetric as ax

        try:
            profile = ax.tabulated(r, f)
        except ValueError as exc:
            return [f"profile_r/profile_f: {exc}"]
        if r[0] != 0.0:
            problems.append(f"profile_r must start at 0, got {r[0]!r}")
        if not physical and r[-1] < 1.0:
            problems.append(f"profile_r must cover the contact, r/a in [0, 1]; it ends at {r[-1]!r}")
        radii = [1.0] if not physical and r[-1] >= 1.0 else []
        floor = _tabulated_floor(profile, values) if physical and "E" in values else None
        if floor:
            return problems + [floor]
        if physical and "delta" in values:
            deltas = np.atleast_1d(values["delta"])
            reach = float(profile.depth(r[-1]))
            if np.any(deltas > reach):
                problems.append(f"delta = {float(deltas.max())!r} m exceeds the depth {reach!r} m at which the "
                                f"contact reaches the end of the table, r = {r[-1]!r} m; extend profile_r")
            elif np.all(deltas > 0.0):
                radii = [float(v) for v in ax.contact_radius(profile, np.unique(deltas))]
        elif physical and "normal_force" in values:
            radii, problem = _radii_of_force(values, profile, float(r[-1]))
            problems += [problem] if problem else []
        problems += _tensile(profile, radii, physical)
    if kind == "flat_punch" and isinstance(values.get("delta"), np.ndarray):
        problems.append("delta cannot be swept for profile = 'flat_punch': its contact radius is the punch "
                        "radius and every field scales with delta; give one value")
    swept = [k for k in ("normal_force", "E", "nu") if np.ndim(values.get(k, 0.0)) > 0]
    if kind == "flat_punch" and "normal_force" in values and swept:
        problems.append(f"{', '.join(swept)} cannot be swept for profile = 'flat_punch' with normal_force: the depth "
                        "F_N/(2 E* radius) scales every field; give one value")
    return problems


def check_depth(kind: str | None = None):
    """The check of a scenario with the depth z (``kind`` its profile kind; None: the recipe's
    `profile`, with ``check_profile``); ``options`` the recipe's [method] table (its routes are
    checked by ``Scenario.route_problems``)."""

    def check(values, physical, options):
        problems = check_profile(values, physical) if kind is None else []
        return problems + check_load(kind, values, physical)

    return check


def _radii_of_force(values, profile, end: float) -> tuple[list[float], str | None]:
    """The contact radii of a tabulated profile under every normal force of the recipe, or why the
    largest force pushes the contact beyond the table."""
    from ..physics.axisymmetric.profiles import radius_at_force

    e_star = effective_modulus(np.atleast_1d(values["E"])[:, None], np.atleast_1d(values["nu"])[None, :])
    with np.errstate(over="ignore"):     # a force beyond the table by 1e300 is refused below, as any beyond it
        forces = np.unique(np.atleast_1d(values["normal_force"])[:, None] / e_star.ravel()[None, :])
    reach = float(profile.normal_force(end))
    if forces.max() > reach:
        most = float(np.max(values["normal_force"]))
        return [], (f"normal_force = {most!r} N exceeds the force {reach * float(e_star.min())!r} N at which the "
                    f"contact reaches the end of the table, r = {end!r} m (with E* = {float(e_star.min())!r} Pa); "
                    "extend profile_r")
    return [float(v) for v in radius_at_force(profile, forces)], None


def _tabulated_floor(profile, values) -> str | None:
    """Why the smallest load of a tabulated profile is too small, or None: every quantity of its
    contact (a, a^2, delta, F_N/E*, p_m/E* and F_N, p_m at every E* of the sweep) must stay at or above
    ``LOAD_RANGE[0]``; they all grow with a, so the smallest admissible radius is a bisection away and
    the load's floor is the load at that radius (the ceiling is the end of the table, checked after)."""
    from ..physics.axisymmetric.profiles import SMALLEST_RADIUS
    from ..physics.roots import bisect

    control = "normal_force" if "normal_force" in values else "delta"
    if control not in values:
        return None
    nu = np.atleast_1d(values.get("nu", NU.default))
    e_low = effective_modulus(float(np.min(values["E"])), float(np.min(nu)))
    e_high = effective_modulus(float(np.max(values["E"])), float(np.max(nu)))
    tiny, top = LOAD_RANGE[0], float(profile.max_radius)

    def below(a):
        force = np.asarray(profile.normal_force(a), dtype=float)
        with np.errstate(under="ignore"):
            pm = force / (math.pi * a * a)
            least = np.minimum.reduce([a, a * a, np.asarray(profile.depth(a), dtype=float), force, pm,
                                       force * e_low, pm * e_low])
        return least < tiny

    if top <= SMALLEST_RADIUS or below(np.array(top)):
        return None                         # a table too small to hold any contact: said elsewhere
    a_min = float(bisect(below, np.array(SMALLEST_RADIUS), np.array(top), 66, geometric=True)) * (1.0 + 1e-12)
    if control == "normal_force":
        floor = float(profile.normal_force(a_min)) * e_high
        unit = "N"
    else:
        floor = float(profile.depth(a_min))
        unit = "m"
    least = float(np.min(values[control]))
    if least >= floor:
        return None
    return (f"{control} = {least!r} {unit} is outside the range where the contact's quantities (a, delta, F_N, "
            f"F_N/E*, p_m, p_m/E*) stay within [{LOAD_RANGE[0]:g}, {LOAD_RANGE[1]:g}] in SI units and are computed "
            f"to full precision; with E = {float(np.min(values['E'])):.6g} Pa and this table, give {control} >= "
            f"{floor:.3g} {unit} (and at most the load at the end of the table)")


def check_load(kind: str | None, values, physical) -> list[str]:
    """The load-control parameters: normal_force and tangential_force only in physical mode; no
    tangential force without friction; tangential_force at most mu F_N (the onset of gross slip)."""
    problems = [] if physical else [f"parameter '{k}' is only used in physical mode; give 'E' to switch to "
                                    "physical units" for k in PHYSICAL_LOADS if k in values]
    mu = np.atleast_1d(values.get("mu", MU.default))
    for key in ("fx", "tangential_force"):
        load = np.atleast_1d(values.get(key, 0.0))
        if np.any(load > 0.0) and np.any(mu == 0.0):
            problems.append(f"{key} = {float(load.max())!r} with mu = 0: a contact without friction carries no "
                            f"tangential force; give mu > 0 or {key} = 0")
    if physical:
        problems += load_range_problems(kind or values.get("profile", PROFILE.default), values)
    if physical and "tangential_force" in values and not problems:
        problems += _force_limit(kind or values.get("profile", PROFILE.default), values, float(mu.min()))
    return problems


#: the magnitudes every derived quantity of the normal contact must keep (natural logs): well inside
#: the normal range of float64 (2.2e-308 to 1.8e308), so that the closed forms, which form powers of
#: the contact radius and products with the profile's constants, never round to subnormal numbers
#: (1e-310 N on a 10 mm steel ball gave a^3 52 % off), to 0 or to inf
LOAD_RANGE = (1e-300, 1e300)


def _geometry_law(kind: str, values) -> tuple[float, float] | None:
    """(n, B) of the power-law families, g(a) = (B/n) a^n and F_N/E* = 2B a^(n+1)/(n+1)
    (docs/theory/axisymmetric.md (A5)-(A7)); None for a flat punch or a tabulated profile."""
    if kind == "cone" and "theta" in values:
        return 1.0, 0.5 * math.pi * math.tan(float(values["theta"]))
    if kind == "paraboloid" and "R" in values:
        return 2.0, 2.0 / float(values["R"])
    if kind == "power_law" and "A" in values and "n" in values:
        n = float(values["n"])
        kappa = math.sqrt(math.pi) * math.exp(math.lgamma(0.5 * n + 1.0) - math.lgamma(0.5 * n + 0.5))
        return n, kappa * float(values["A"]) * n
    return None


def _load_logs(kind: str, values, control: str) -> dict[str, tuple[float, float, float]] | None:
    """The natural logs of the normal contact's quantities as linear functions alpha*log(load) +
    beta*log(E*) + gamma of the load (``control``: normal_force or delta) and E*, name -> (alpha, beta,
    gamma); None where the profile's quantities are not closed forms (tabulated: only F_N/E*)."""
    force = control == "normal_force"
    law = _geometry_law(kind, values)
    if law is not None:
        n, B = law
        # log a = (log F - log E* - log(2B/(n+1)))/(n+1), or (log delta - log(B/n))/n
        la = ((1 / (n + 1), -1 / (n + 1), -math.log(2 * B / (n + 1)) / (n + 1)) if force
              else (1 / n, 0.0, -math.log(B / n) / n))
        power = {f"a^{p:g}": tuple(p * v for v in la) for p in (2.0, n, n + 1.0)}
        shifted = lambda k, c, e=0.0: (k * la[0], k * la[1] + e, k * la[2] + c)
        out = {"contact radius a": la, **power, "delta": shifted(n, math.log(B / n)),
               "F_N/E*": shifted(n + 1, math.log(2 * B / (n + 1))),
               "p_m/E*": shifted(n - 1, math.log(2 * B / (math.pi * (n + 1))))}
    elif kind == "flat_punch" and "radius" in values:
        lr = math.log(float(values["radius"]))
        # delta = F_N/(2 E* radius); F_N/E* = 2 radius delta; p_m/E* = 2 delta/(pi radius)
        ld = (1.0, -1.0, -math.log(2.0) - lr) if force else (1.0, 0.0, 0.0)
        out = {"contact radius a": (0.0, 0.0, lr), "a^2": (0.0, 0.0, 2 * lr), "delta": ld,
               "F_N/E*": (ld[0], ld[1], ld[2] + math.log(2.0) + lr),
               "p_m/E*": (ld[0], ld[1], ld[2] + math.log(2.0 / math.pi) - lr)}
    elif force:
        out = {"F_N/E*": (1.0, -1.0, 0.0)}
    else:
        return None
    out["F_N"] = (out["F_N/E*"][0], out["F_N/E*"][1] + 1.0, out["F_N/E*"][2])
    out["p_m"] = (out["p_m/E*"][0], out["p_m/E*"][1] + 1.0, out["p_m/E*"][2]) if "p_m/E*" in out else None
    return {k: v for k, v in out.items() if v is not None}


def load_range_problems(kind: str, values) -> list[str]:
    """The normal load (normal_force or delta) whose contact would leave ``LOAD_RANGE`` in any of a, its
    powers, delta, F_N, F_N/E*, p_m, p_m/E* (or E* itself), at any corner of the sweep, refused with the
    range of the load that keeps them all inside, for the recipe's E, nu and geometry.  Every quantity
    is a linear function of log(load) and log(E*), so the corners of the sweep bound it."""
    control = "normal_force" if "normal_force" in values else "delta"
    if control not in values or "E" not in values:
        return []
    loads = np.asarray(values[control], dtype=float)
    e_star = [effective_modulus(float(np.min(values["E"])), float(np.min(values.get("nu", NU.default)))),
              effective_modulus(float(np.max(values["E"])), float(np.max(values.get("nu", NU.default))))]
    lo, hi = (math.log(v) for v in LOAD_RANGE)
    if not all(lo <= math.log(e) <= hi for e in e_star if e > 0.0):
        return [f"E = {float(np.min(values['E'])):.6g} Pa gives E* = E/(1-nu^2) = {min(e_star):.6g} Pa, outside "
                f"[{LOAD_RANGE[0]:g}, {LOAD_RANGE[1]:g}] Pa; give E >= {LOAD_RANGE[0]:g} Pa"]
    try:
        logs = _load_logs(kind, values, control)
    except (ValueError, OverflowError, ZeroDivisionError):     # a geometry out of its range: said elsewhere
        return []
    if not logs:
        return []
    low, high = -math.inf, math.inf           # log(load) keeping every quantity inside, at both E* corners
    for alpha, beta, gamma in logs.values():
        for le in (math.log(e) for e in e_star):
            if alpha == 0.0:
                if not lo <= beta * le + gamma <= hi:
                    low, high = math.inf, -math.inf
                continue
            ends = sorted(((lo - beta * le - gamma) / alpha, (hi - beta * le - gamma) / alpha))
            low, high = max(low, ends[0]), min(high, ends[1])
    declared = NORMAL_FORCE if control == "normal_force" else DELTA
    high = min(high, math.log(declared.high))
    smallest, largest = float(np.min(loads)), float(np.max(loads))
    if low <= math.log(smallest) and math.log(largest) <= high:
        return []
    unit = "N" if control == "normal_force" else "m"
    bad = smallest if not low <= math.log(smallest) else largest
    what = (f"give {control} in [{math.exp(low):.3g}, {math.exp(high):.3g}] {unit}" if low <= high
            else "no load does: change E or the geometry")
    return [f"{control} = {bad!r} {unit} is outside the range where the contact's quantities (a, delta, F_N, "
            f"F_N/E*, p_m, p_m/E*) stay within [{LOAD_RANGE[0]:g}, {LOAD_RANGE[1]:g}] in SI units and are "
            f"computed to full precision; with E = {float(np.min(values['E'])):.6g} Pa and this geometry, {what}"]


#: with delta given, tangential_force is accepted up to (1 - this) mu F_N: the relative rounding of the
#: derived F_N (at most ~1e-15) over 1 - fx stays below the stick radius's 1e-12
NEAR_GROSS_SLIP = 1e-3


def _force_limit(kind: str, values, mu: float) -> list[str]:
    """tangential_force <= mu F_N at every point of the sweep: against the least mu F_N (F_N grows with
    delta or normal_force, with E and with nu)."""
    force = float(np.max(values["tangential_force"]))
    least_modulus = effective_modulus(float(np.min(values["E"])), float(np.min(values["nu"])))
    if "normal_force" in values:
        least = float(np.min(values["normal_force"]))
    else:
        from ..physics.axisymmetric import contact_radius

        delta = float(np.min(values["delta"]))
        profile = make_profile(kind, {**values, "delta": delta}, True)
        try:
            least = float(profile.normal_force(contact_radius(profile, delta))) * least_modulus
        except ValueError:          # beyond a tabulated profile: check_profile says so
            return []
    limit = mu * least
    if force <= limit and ("normal_force" in values or force <= (1.0 - NEAR_GROSS_SLIP) * limit):
        return []
    if force <= limit:
        # F_N of delta carries its rounding (~1e-16, more through the profile's constants), which
        # 1 - fx would magnify: c/a = (1 - fx)^(1/(n+1)) was 7e-5 off at 1 - fx = 1e-12
        return [f"tangential_force = {force!r} N is within {NEAR_GROSS_SLIP:g} of mu F_N = {limit!r} N with delta "
                "given: the stick radius there would follow the rounding of F_N(delta) rather than the load; give "
                f"normal_force instead of delta, or the load as fx, or tangential_force <= "
                f"{(1.0 - NEAR_GROSS_SLIP) * limit!r} N"]
    return [f"tangential_force = {force!r} N exceeds mu F_N = {limit!r} N (mu = {mu!r}, F_N = {least!r} N), the "
            "largest tangential force the contact carries (the onset of gross slip, fx = 1); give "
            f"tangential_force <= {limit!r} N"]


#: p / p_m below this is tensile: far beyond the quadrature's error (1e-10 p_m) of ``min_pressure``
_TENSILE = -1e-9


def _tensile(profile, radii, physical) -> list[str]:
    """A tabulated profile whose contact pressure would be tensile somewhere (outside the model:
    no adhesion) is refused, with where and how much (``physics.axisymmetric.min_pressure``)."""
    from ..physics import axisymmetric as ax

    for a in radii:
        p, at = ax.min_pressure(profile, a)
        if p < _TENSILE:
            where = f"r = {at!r} m with a = {a!r} m" if physical else f"r/a = {at:.6g}"
            return [f"profile_r/profile_f: the contact pressure of this profile would be tensile, p = {p:.4g} p_m "
                    f"at {where} (the cubic spline through the points, the profile used, makes the surface "
                    f"bend away from the indenter there): a contact without adhesion cannot reach this "
                    f"radius; give more points or a profile that does not flatten inside the contact"]
    return []


def route_of(kind: str | None = None, default: str = PROFILE.default):
    """The scenario's route(values, method, rtol, groups) -> {group: (route, accuracy)}:
    ``physics.axisymmetric.resolve`` for the profile ``kind`` (None: the recipe's `profile`, else
    ``default``), the recipe's depths and whether a tangential load acts."""

    def route(values, method, rtol, groups):
        from ..physics.axisymmetric.routes import resolve

        which = kind or values.get("profile", default)
        tangential = bool(np.any(np.asarray(values.get("mu", 0.0)) > 0.0)
                          and any(np.any(np.asarray(values.get(k, 0.0)) > 0.0)
                                  for k in ("ux0", "fx", "tangential_force")))
        return {g: tuple(resolve(which, method, rtol, values.get("n"), group=g, z=values.get("z"),
                                 tangential=tangential)) for g in groups}

    return route


_SEARCH = ("Found by a converged search (physics.axisymmetric.peaks): a coarse grid on the load axis y = 0 "
           "(x >= 0 under normal load, both signs of x under tangential load; depths 0 and 1e-3 a to 3a), then "
           "a bounded Nelder-Mead refinement in (x, z) to 1e-9 a; the surface z = 0 is searched too. The value "
           "is the field at the refined point (the fields' accuracy; the refinement stops when its values differ "
           "by < 1e-14 of the peak); "
           "the position is accurate to about 1e-7 a. Where the field is unbounded at a surface singular "
           "point (cone tip and power laws n <= 1 at r = 0, a tabulated spline with a nonzero slope at r = 0, "
           "flat-punch edge r = a) the peak is +inf at that point, depth 0, and "
           "peak_validity is 1.")


def peak_variables(case: tuple[str, ...]) -> tuple[Variable, ...]:
    """The per-case peaks of tau_max and von Mises below the surface and where they sit."""
    out = []
    for name, what in (("tau_max", "maximum shear stress (sigma_1 - sigma_3)/2"),
                       ("von_mises", "von Mises equivalent stress sqrt(3 J2)")):
        out += [
            Variable(f"{name}_peak", f"largest {what} in the half-space z >= 0", units_physical="Pa",
                     scale=PM, dims=case, comment=_SEARCH, label=f"peak {name}"),
            Variable(f"{name}_peak_r", f"x coordinate (on the load axis y = 0; the radius r >= 0 under normal "
                     f"load) of the largest {what}", units_physical="m", scale=RADIUS_A,
                     dims=case, comment=_SEARCH, label=f"x of peak {name}"),
            Variable(f"{name}_peak_depth", f"depth z below the surface of the largest {what}",
                     units_physical="m", scale=RADIUS_A, dims=case, comment=_SEARCH,
                     label=f"z of peak {name}"),
        ]
    out.append(Variable(
        "peak_validity", "validity of the peak variables of the case", dtype="int8", dims=case,
        **declare(PEAK_CODES, where={
            V.unbounded_at_singular_point: "at a surface singular point, e.g. cone tip, flat-punch edge: the peaks "
                                           "are +inf there, depth 0",
            V.undefined_direction_dependent_limit: "at a surface singular point: the peaks are NaN",
            V.search_not_converged: "its box: |x| = 2a, z = 3a"},
            note="Written whenever a peak variable is."),
        always=tuple(v.name for v in out), label="validity of the peaks"))
    return tuple(out)


def _scenario(name, summary, geometry, kind):
    params = (NU, MU, UX0, FX, TANGENTIAL_FORCE, E, DELTA, NORMAL_FORCE) + geometry + (Z, Y, X)
    case = tuple(p.name for p in params if p.name not in DEPTH)
    declared = grouped(variables(case, tuple(p.name for p in geometry), DEPTH) + peak_variables(case))
    return Scenario(
        name=name, summary=summary, references=REFERENCE, theory="axisymmetric", parameters=params,
        variables=declared, evaluate=_evaluate(kind, {v.name: v for v in declared}),
        physical_switch="E", methods=AXISYMMETRIC_METHODS,
        default_variables=STRESS + ("von_mises",) + PRINCIPAL + ("dpdz", "stick_radius", "region"),
        check=check_depth(kind), route=route_of(kind),
    )


CONICAL = _scenario("conical", "Rigid cone on an elastic half-space: surface stresses and dp/dz under normal "
                    "and Cattaneo-Mindlin tangential load, and below the surface", (THETA,), "cone")
PARABOLIC = _scenario("parabolic", "Rigid paraboloid (Hertz-Mindlin) on an elastic half-space: surface stresses "
                      "and dp/dz under normal and Cattaneo-Mindlin tangential load, and below the surface",
                      (R,), "paraboloid")
AXISYMMETRIC = _scenario("axisymmetric", "Rigid axisymmetric indenter of any profile (power law, tabulated, flat "
                         "punch) on an elastic half-space: surface stresses and dp/dz (MDR, 1-D integrals), and "
                         "below the surface (1-D superposition of flat and sliding punches)",
                         (PROFILE, N, A, RADIUS, PROFILE_R, PROFILE_F), None)
