"""Power-law graded elastic half-space, E(z) = E0 (z/c0)^k: MDR normal, adhesive and tangential contact.

Scenarios `graded_normal`, `graded_adhesive` (rigid axisymmetric indenter on one graded half-space)
and `graded_tangential` (Cattaneo-Mindlin partial slip of two graded bodies). Physical units only
(SI): lengths in m, E0 and pressures in Pa, forces in N; the contact radius a is `contact_radius` and
the radial coordinate is `rho` = r/a.

Method "auto" and "closed" use the closed forms of the paper (power-law profiles f = A r^n, with
the paraboloid n = 2, A = 1/(2R) and the cone n = 1, A = tan(theta)); "quadrature" evaluates the
MDR integral rules for the profile object (mandatory for a tabulated profile), with the recipe's
rtol. Defaults: nu = 0.3, k = 0.5, c0 = 1 m (E0 is then the modulus at 1 m depth; only the
combination E0/c0^k enters), rho = r/a = 0.

This module declares; the numerics are the entry points of ``physics.graded.fields`` (one per
scenario), and the route table is ``physics.graded.resolve``.  The functions that compute import
``physics.graded`` when they run: the declarations need only ``physics.names``.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from ..physics.flags import Validity as V
from ..physics.flags import declare
from ..physics.names import GRADED_METHODS
from .base import ARRAY, MAX_TABLE_SIZE, STR, Parameter, Scenario, Variable, table_step_problem

REFERENCE = ("M. Hess, V. L. Popov, Method of dimensionality reduction in contact mechanics and friction: "
             "a user's handbook. II. Power-law graded materials, Facta Universitatis, Series Mechanical "
             "Engineering 14(3), 2016, 251-268, doi:10.22190/FUME1603251H")
BIG = 1e30

# -- parameters ---------------------------------------------------------------------------------
PROFILE = Parameter("profile", "indenter profile (parabolic: r^2/(2R); conical: r tan(theta); power_law: "
                    "A r^n; tabulated: spline through profile_r, profile_f)", kind=STR, default="parabolic",
                    choices=("parabolic", "conical", "power_law", "tabulated"), sweepable=False,
                    label="indenter profile")
R = Parameter("R", "radius of curvature of the paraboloid f = r^2/(2R)", units="m", low=0.0, low_open=True,
              high=1e6, required=True, when={"profile": ("parabolic",)}, label="tip radius R")
TAN = Parameter("tan_theta", "slope tan(theta) of the cone f = r tan(theta)", low=0.0, low_open=True, high=1e6,
                required=True, when={"profile": ("conical",)}, label="cone slope tan(theta)")
N = Parameter("n", "exponent of the power-law profile f = A r^n", low=0.0, low_open=True, high=50.0,
              required=True, when={"profile": ("power_law",)}, label="power-law exponent n")
# units depend on n (m^(1-n)), which UDUNITS cannot express: the number is declared "1" and its SI
# meaning is said in the text, as in the axisymmetric scenario
A = Parameter("A", "amplitude of the power-law profile f = A r^n, with r and f in metres (SI units m^(1-n))",
              low=0.0, low_open=True, high=BIG, required=True, when={"profile": ("power_law",)},
              label="power-law amplitude A")
PROFILE_R = Parameter("profile_r", "radii of the tabulated profile f(r), from 0, strictly increasing", units="m",
                      kind=ARRAY, required=True, sweepable=False, when={"profile": ("tabulated",)},
                      max_size=MAX_TABLE_SIZE, label="profile radii r")
PROFILE_F = Parameter("profile_f", "heights f(r) of the tabulated profile, strictly increasing", units="m",
                      kind=ARRAY, required=True, sweepable=False, when={"profile": ("tabulated",)},
                      max_size=MAX_TABLE_SIZE, label="profile heights f")
E0 = Parameter("E0", "Young's modulus E0 at the characteristic depth c0, E(z) = E0 (z/c0)^k", units="Pa",
               low=0.0, low_open=True, high=1e15, required=True, label="modulus E0")
C0 = Parameter("c0", "characteristic depth c0 at which E = E0", units="m", default=1.0, low=0.0, low_open=True,
               high=1e6, label="depth c0 of E0")
NU = Parameter("nu", "Poisson's ratio (constant with depth)", default=0.3, low=-1.0, low_open=True, high=0.5,
               label="Poisson's ratio nu")
K = Parameter("k", "grading exponent k of E(z) = E0 (z/c0)^k", default=0.5, low=0.0, high=1.0, high_open=True,
              label="grading exponent k")
# no two names differ only by case (CF 2.3; compliance-checker warns on r/R and a/A in one file): the
# contact radius is named as in the axisymmetric scenarios, the radial coordinate rho = r/a
A_RAD = Parameter("contact_radius", "contact radius a", units="m", low=0.0, low_open=True, high=1e6, required=True)
R_REL = Parameter("rho", "radial coordinate rho = r/a: the radius r divided by the contact radius a", default=0.0,
                  low=0.0, high=1e6, label="radius rho = r/a")
#: the former names of the two above, told to a recipe that still uses them
RENAMED = {"a": "contact_radius", "r": "rho"}
GEOMETRY = (PROFILE, R, TAN, N, A, PROFILE_R, PROFILE_F)
MATERIAL = (E0, C0, NU, K)
#: below the surface (docs/theory/graded.md section 10): solved for k = 0 (any nu) and for k > 0 with
#: nu = 1/(2+k), which `poisson = "holl_ratio"` sets
Z = Parameter("z", "depth below the surface divided by the contact radius a (0: the surface); given, the "
              "stress variables are computed below the surface, for k = 0 (any nu, every profile) or nu = "
              "1/(2+k) (the power-law profiles: parabolic, conical, power_law)", low=0.0, high=1e6,
              label="depth z / a", axis="Z")
# no default: a recipe without it is recorded (and hashed) as before the choice existed
POISSON_N = Parameter("poisson", "Poisson's ratio: 'given' (the parameter nu; also when omitted) or 'holl_ratio' "
                      "(nu = 1/(2+k), following a sweep of k: the case solved below the surface at k > 0)", kind=STR,
                      choices=("given", "holl_ratio"), sweepable=False, label="Poisson's ratio rule")
NU_N = Parameter(NU.name, NU.meaning, default=NU.default, low=NU.low, low_open=True, high=NU.high,
                 when={"poisson": (None, "given")}, label=NU.label)
MATERIAL_N = (E0, C0, POISSON_N, NU_N, K)
STRESS_NAMES = ("sigma_rr", "sigma_tt", "sigma_zz", "sigma_rz", "von_mises", "sigma_1", "sigma_2", "sigma_3",
                "tau_max")
_AT = "at (r, z) on a plane through the axis, r = rho a, depth z a (z = 0: the surface)"
#: the short labels (files' long_name) of the stress variables below the surface
#: the codes of the surface fields' validity, of the stresses', of the peaks' and at pull-off (physics.flags)
SURFACE_CODES = (V.within_stated_accuracy, V.unbounded_at_singular_point, V.undefined_direction_dependent_limit)
STRESS_CODES = SURFACE_CODES + (V.not_resolved_below_the_surface,)
PEAK_CODES = SURFACE_CODES + (V.search_not_converged,)
CRITICAL_CODES = (V.within_stated_accuracy, V.no_critical_point)
STRESS_LABELS = {"sigma_1": "sigma_1 (largest)", "sigma_2": "sigma_2 (middle)", "sigma_3": "sigma_3 (smallest)",
                 "tau_max": "shear stress tau_max", "von_mises": "von Mises stress",
                 **{f"sigma_{c}": f"stress sigma_{c}" for c in ("rr", "tt", "zz", "rz", "xx", "yy", "xz")}}


def stress_variables(dims: tuple[str, ...], adhesive: bool) -> tuple[Variable, ...]:
    """The stress below the surface and its invariants, and their validity flag (``dims`` ends in z, rho)."""
    what = [("sigma_rr", "radial stress sigma_rr"), ("sigma_tt", "hoop stress sigma_theta_theta"),
            ("sigma_zz", "normal stress sigma_zz"), ("sigma_rz", "shear stress sigma_rz"),
            ("von_mises", "von Mises equivalent stress sqrt(3 J2)"), ("sigma_1", "largest principal stress"),
            ("sigma_2", "intermediate principal stress"), ("sigma_3", "smallest principal stress"),
            ("tau_max", "maximum shear stress (sigma_1 - sigma_3)/2")]
    edge = ("the adhesive edge r = a at z = 0 (+inf: the tensile edge singularity; sigma_rz NaN, its sign "
            "depends on the direction of approach), " if adhesive else "")
    return tuple(Variable(n, f"{m} {_AT}", units="Pa", dims=dims, label=STRESS_LABELS[n],
                          comment="tension positive, z into the body; docs/theory/graded.md section 10")
                 for n, m in what) + (
        Variable("stress_validity", "validity of the stress variables at the point", dims=dims, dtype="int8",
                 always=True, **declare(STRESS_CODES, where={
                     V.unbounded_at_singular_point: f"{edge}the centre r = 0 at z = 0 where the pressure is "
                                                    "unbounded: the cone (or a tabulated tip of nonzero slope) at "
                                                    "k = 0, a power law with n + k <= 1"},
                     note="Only the stress variables in this file are considered."),
                 label="validity of the stresses"),
    )


_SEARCH = ("Found by the search of physics.axisymmetric.peaks on the graded field (physics.graded.interior.peaks): "
           "the surface singular points r = 0 and r = a first, a grid over rho in [0, 2] and depths 0 and 1e-3 a to "
           "3a, a bounded Nelder-Mead refinement to 1e-9 a; the value is the field at the refined point, the "
           "position accurate to about 1e-7 a. Where the field is unbounded at a surface singular point (the "
           "adhesive edge, the conical tip at k = 0) the peak is +inf there, depth 0, and peak_validity is 1.")


_SEARCH_T = ("Found by the search of physics.axisymmetric.peaks on the field of the lower body at k = 0 "
             "(physics.graded.interior.tangential_peaks: c_N* of the pair times the axisymmetric family's peaks): "
             "the surface singular points x = 0, +-c, +-a first, a grid over x in [-2, 2] and depths 0 and 1e-3 a "
             "to 3a, a bounded Nelder-Mead refinement to 1e-9 a; the value is the field at the refined point, the "
             "position accurate to about 1e-7 a. Where the field is unbounded at a surface singular point (the "
             "conical tip) the peak is +inf there, depth 0, and peak_validity is 1.")


def peak_variables(case: tuple[str, ...], position: str = "rho") -> tuple[Variable, ...]:
    """The per-case peaks of tau_max and von Mises in the half-space and where they sit: ``position`` "rho"
    (the radius r/a) or "x" (x/a signed along the tangential load, graded_tangential)."""
    out = []
    search = _SEARCH if position == "rho" else _SEARCH_T
    where = "radius r/a" if position == "rho" else "coordinate x/a (signed, along the tangential load)"
    for name, what in (("tau_max", "maximum shear stress (sigma_1 - sigma_3)/2"),
                       ("von_mises", "von Mises equivalent stress sqrt(3 J2)")):
        out += [Variable(f"{name}_peak", f"largest {what} in the half-space z >= 0", units="Pa", dims=case,
                         comment=search, label=f"peak {name}"),
                Variable(f"{name}_peak_{position}", f"{where} of the largest {what}", dims=case, comment=search,
                         label=f"{'r' if position == 'rho' else 'x'}/a of peak {name}"),
                Variable(f"{name}_peak_depth", f"depth z/a of the largest {what}", dims=case, comment=search,
                         label=f"z/a of peak {name}")]
    out.append(Variable(
        "peak_validity", "validity of the peak variables of the case", dtype="int8", dims=case,
        always=tuple(v.name for v in out), **declare(PEAK_CODES, where={
            V.unbounded_at_singular_point: "at a surface singular point: +inf there, depth 0",
            V.undefined_direction_dependent_limit: "at a surface singular point",
            V.search_not_converged: f"its box: {'rho = 2' if position == 'rho' else '|x| = 2'}, z = 3a"},
            note="Written whenever a peak variable is."),
        label="validity of the peaks"))
    return tuple(out)


def _peaks(names, p, options, **extra) -> dict:
    from ..physics.graded.interior import PEAKS, peaks

    if not any(n in PEAKS for n in names):
        return {}
    found = peaks(_indenter(p), a=_f(p, "contact_radius"), k=_f(p, "k"), nu=_nu(p), E0=_f(p, "E0"),
                  c0=_f(p, "c0"), method=options["method"], rtol=options["rtol"], **extra)
    return {n: found[n] for n in names if n in PEAKS}


def _depth_problems(values) -> list[str]:
    """With `z` given or a peak asked for: the (k, nu) and the profile must be solved below the surface (one
    line)."""
    peaks = [n for n in getattr(values, "variables", ()) if n.endswith("_peak") or "_peak_" in n]
    if values.get("z") is None and not peaks:
        return []
    what = "z is given" if values.get("z") is not None else f"{peaks[0]} is asked for"
    from ..physics.graded import holl_ratio
    from ..physics.graded.interior import check_supported

    g = _grid(values, ("k", "nu"))
    nu = holl_ratio(g["k"]) if values.get("poisson") == "holl_ratio" else g["nu"]
    try:
        check_supported(g["k"], nu, values.get("profile", PROFILE.default))
    except ValueError as exc:
        return [f"{what}, but {exc}"]
    return []


def _nu(p):
    """nu as the physics takes it: the parameter, or Holl's ratio 1/(2+k) with poisson = 'holl_ratio'."""
    if p.get("poisson") == "holl_ratio":
        k = _f(p, "k")
        return None if k is None else 1.0 / (2.0 + k)
    return _f(p, "nu")


def _stress(names, p, options, **extra) -> dict:
    """The requested stress variables below the surface and their validity flag."""
    from ..physics.flags import validity_flag
    from ..physics.graded.interior import INTERIOR, UNRESOLVED, interior_fields

    wanted = [n for n in names if n in INTERIOR]
    flag = "stress_validity" in names
    if not wanted and not flag:
        return {}
    asked = wanted or list(INTERIOR)
    z = _f(p, "z")
    z = np.zeros(()) if z is None else z
    out = interior_fields(asked, _indenter(p), a=_f(p, "contact_radius"), rho=_f(p, "rho"), z=z, k=_f(p, "k"),
                          nu=_nu(p), E0=_f(p, "E0"), c0=_f(p, "c0"), method=options["method"], rtol=options["rtol"],
                          **extra)
    if flag:
        deep = np.broadcast_to(z > 0.0, np.shape(out[asked[0]]))
        code = validity_flag(*(out[n] for n in asked))
        unresolved = deep & np.any([np.isnan(out[n]) for n in asked], axis=0)
        out["stress_validity"] = np.where(unresolved, np.int8(UNRESOLVED), code).astype(np.int8)
    return {n: v for n, v in out.items() if n in names}
GEOM = ("R", "tan_theta", "n", "A")          # swept geometry parameters, as dimensions

#: the methods of the route table (physics.graded.routes.METHODS, one definition in physics.names)
METHODS = GRADED_METHODS


def _f(p, key):
    """The value as a float array; None where the block does not carry it (a field that does not
    depend on a swept parameter is evaluated without it)."""
    v = p.get(key)
    return None if v is None else np.asarray(v, dtype=float)


def _where(p):
    """The contact radius a and the radial coordinate rho = r/a, as the physics names them."""
    return {"a": _f(p, "contact_radius"), "rho": _f(p, "rho")}


def _indenter(p):
    """The recipe's profile as the physics' description (kind + geometry arrays)."""
    from ..physics import graded as gp

    kind = p["profile"]
    if kind == "tabulated":
        return gp.Indenter.tabulated(p["profile_r"], p["profile_f"])
    if kind == "parabolic":
        return gp.Indenter.parabolic(_f(p, "R"))
    if kind == "conical":
        return gp.Indenter.conical(_f(p, "tan_theta"))
    return gp.Indenter.power_law(A=_f(p, "A"), n=_f(p, "n"))


def _fields(entry, known, names, p, options, **values):
    """entry(the requested names among ``known``, the indenter, values, method, rtol); {} if none."""
    wanted = [n for n in names if n in known]
    if not wanted:          # (a block holding only flags may lack the geometry)
        return {}
    return entry(wanted, _indenter(p), **values, method=options["method"], rtol=options["rtol"])


def _check_profile(values):
    """Cross-parameter rules shared by the three scenarios; messages name key, value and range (a method
    without a route, e.g. ``closed`` on a tabulated profile, is the route table's to refuse)."""
    problems = []
    kind = values.get("profile")
    if kind == "tabulated":
        r, f = (np.asarray(values.get(key, ()), dtype=float) for key in ("profile_r", "profile_f"))
        if r.shape != f.shape:
            return [f"profile_r has {r.size} values but profile_f has {f.size}; they must pair up"]
        if r.size < 4 or r[0] != 0.0 or np.any(np.diff(r) <= 0) or np.any(np.diff(f) <= 0):
            # the first offending value, not the whole table (up to MAX_TABLE_SIZE numbers)
            where = ("" if r.size < 4 else f": profile_r[0] = {r[0]!r}" if r[0] != 0.0 else
                     f": profile_r[{int(np.argmax(np.diff(r) <= 0)) + 1}] does not increase"
                     if np.any(np.diff(r) <= 0) else
                     f": profile_f[{int(np.argmax(np.diff(f) <= 0)) + 1}] does not increase")
            return [f"profile_r / profile_f ({r.size} values){where}; need at least 4 points, profile_r from 0 "
                    "and strictly increasing, profile_f strictly increasing"]
        step = table_step_problem("profile_r", r)
        if step:
            return [step]
        a_max = float(np.max(values["contact_radius"]))
        if a_max > r[-1]:
            problems.append(f"contact_radius = {a_max!r} m exceeds the tabulated range: it must be in "
                            f"(0, {float(r[-1])!r}] (the last profile_r); extend the table")
    return problems


def _grid(values, names):
    """The named values as mutually broadcasting arrays: one axis per swept parameter, and one axis
    (last) shared by the [points] columns (``values.points``: one value per point, paired as the
    points pair them, not crossed as a sweep is)."""
    columns = set(getattr(values, "points", ()))
    arrays = [n for n in names if isinstance(values.get(n), np.ndarray)]
    swept = [n for n in arrays if n not in columns]
    ndim = len(swept) + any(n in columns for n in arrays)
    out = {}
    for n in names:
        v = values.get(n)
        if isinstance(v, np.ndarray):
            shape = [1] * ndim
            shape[-1 if n in columns else swept.index(n)] = v.size
            v = v.reshape(shape)
        out[n] = v
    return out


def _validity(field_dims, fields, unbounded):
    """The validity flag of ``fields``: evaluated from them whether or not the file holds them, so that
    it is the same requested alone, beside them, or beside other variables; ``unbounded`` says where
    they are +-inf."""
    return Variable("validity", f"validity of {' and '.join(fields)}", dims=field_dims, dtype="int8", always=True,
                    **declare(SURFACE_CODES, where={V.unbounded_at_singular_point: unbounded},
                              note=f"It flags {' and '.join(fields)}, evaluated whether or not the file holds "
                                   "them."),
                    label=f"validity of {' and '.join(fields)}")


def _flag(entry, known, flagged, out, p, options, **values):
    """The validity flag of the ``flagged`` fields, evaluating those the block did not request."""
    from ..physics.flags import validity_flag

    missing = [n for n in flagged if n not in out]
    extra = _fields(entry, known, missing, p, options, **values) if missing else {}
    return validity_flag(*({**out, **extra}[n] for n in flagged))


# -- graded_normal -------------------------------------------------------------------------------
N_DIMS = ("E0", "c0", "k", "nu", "contact_radius") + GEOM
N_FLAGGED = ("pressure", "uz")
N_VARS = (
    Variable("kappa", "profile scaling factor g(a)/f(a) of the MDR transform (eq. 9: kappa(n, k) = "
             "(n/2) B(n/2, (1+k)/2) for a power law f = A r^n)", dims=("k", "contact_radius") + GEOM,
             label="scaling factor kappa"),
    Variable("depth", "indentation depth d(a)", units="m", dims=("k", "contact_radius") + GEOM),
    Variable("normal_force", "normal force F_N(a)", units="N", dims=N_DIMS),
    Variable("pressure", "contact pressure p(r; a) (compressive positive)", units="Pa", dims=N_DIMS + ("rho",),
             label="contact pressure p(r; a)"),
    Variable("uz", "normal surface displacement u_z(r; a), positive into the body", units="m",
             dims=("k", "contact_radius") + GEOM + ("rho",), label="displacement u_z(r; a)"),
    _validity(N_DIMS + ("rho",), N_FLAGGED, "pressure = +inf at r = 0 for a profile with n + k <= 1 (e.g. the "
              "cone at k = 0), where the exact pressure is unbounded"),
) + stress_variables(N_DIMS + ("z", "rho"), adhesive=False) + peak_variables(N_DIMS)


def _grouped(declared) -> tuple[Variable, ...]:
    """The declarations, the stress below the surface and its peaks in the route table's "stress" group
    (``physics.graded.resolve``), the rest in its "surface" group."""
    return tuple(dataclasses.replace(v, group="stress") if not v.flag_values and (
        v.name.startswith("sigma_") or v.name in ("von_mises", "tau_max") or "_peak" in v.name) else v
        for v in declared)


N_VARS = _grouped(N_VARS)


def _evaluate_normal(names, p, options):
    from ..physics import graded as gp

    values = dict(**_where(p), k=_f(p, "k"), nu=_nu(p), E0=_f(p, "E0"), c0=_f(p, "c0"))
    out = _fields(gp.normal_fields, gp.fields.NORMAL, names, p, options, **values)
    out.update(_stress(names, p, options))
    out.update(_peaks(names, p, options))
    if "validity" in names:
        out["validity"] = _flag(gp.normal_fields, gp.fields.NORMAL, N_FLAGGED, out, p, options, **values)
    return out


def _check_normal(values, physical, options):
    return _check_profile(values) + _depth_problems(values)


def route(values, method, rtol, groups):
    """``physics.graded.resolve`` for each group: closed forms of the paper for power-law profiles, the
    MDR quadrature for tabulated ones; the stress group below the surface where the recipe gives z."""
    from ..physics import graded as gp

    k = values.get("k", K.default) if values.get("z") is not None else None
    return {g: gp.resolve(values.get("profile", PROFILE.default), method, rtol, group=g, k=k, n=values.get("n"))
            for g in groups}


CONVENTIONS = ("pressure p positive in compression; surface displacement u_z and indentation depth d positive "
               "into the body; adhesive (tensile) forces negative; shear traction along the tangential force")

GRADED_NORMAL = Scenario(
    name="graded_normal",
    summary="Rigid axisymmetric indenter on a power-law graded half-space E = E0 (z/c0)^k: depth, force, "
            "pressure and surface displacement (MDR)",
    references=REFERENCE, theory="graded", parameters=GEOMETRY + MATERIAL_N + (A_RAD, Z, R_REL), variables=N_VARS,
    evaluate=_evaluate_normal, methods=METHODS, check=_check_normal, conventions=CONVENTIONS, route=route,
    renamed=RENAMED,
    default_variables=("depth", "normal_force", "pressure", "uz"),
)

# -- graded_adhesive -----------------------------------------------------------------------------
DGAM = Parameter("delta_gamma", "work of adhesion Delta gamma", units="J/m^2", low=0.0, high=1e6, required=True,
                 label="work of adhesion")
CONTROL = Parameter("control", "loading condition at the critical (pull-off) point", kind=STR,
                    choices=("fixed_load", "fixed_grips"),
                    default=np.array(["fixed_load", "fixed_grips"], dtype=object),
                    label="loading condition at pull-off")
AD_DIMS = ("E0", "c0", "k", "nu", "delta_gamma", "contact_radius") + GEOM
CRIT_DIMS = ("E0", "c0", "k", "nu", "delta_gamma") + GEOM + ("control",)
AD_VARS = (
    Variable("depth", "indentation depth d(a) with adhesion (negative: below the undeformed surface)",
             units="m", dims=AD_DIMS, label="indentation depth d(a)"),
    Variable("normal_force", "normal force F_N(a) with adhesion (negative: tensile)", units="N", dims=AD_DIMS,
             label="normal force F_N(a)"),
    Variable("pressure", "contact pressure p(r; a) with adhesion (compressive positive; -inf at r = a)",
             units="Pa", dims=AD_DIMS + ("rho",), label="contact pressure p(r; a)"),
    Variable("critical_radius", "critical contact radius a_c at pull-off", units="m", dims=CRIT_DIMS,
             label="pull-off radius a_c"),
    Variable("critical_depth", "indentation depth d_c at pull-off", units="m", dims=CRIT_DIMS,
             label="pull-off depth d_c"),
    Variable("critical_force", "normal force F_c at pull-off (negative: tensile)", units="N", dims=CRIT_DIMS,
             label="pull-off force F_c"),
    _validity(AD_DIMS + ("rho",), ("pressure",), "pressure = -inf at r = a (the adhesive edge singularity, "
              "eq. 37) or +inf at r = 0 for a profile with n + k <= 1, where the exact pressure is unbounded"),
    Variable("critical_validity", "validity of the critical (pull-off) values", dims=CRIT_DIMS, dtype="int8",
             always=True, **declare(CRITICAL_CODES, where={
                 V.no_critical_point: "power law with n <= (1-k)/2, Table 3, or a critical point beyond the "
                                      "tabulated profile"}),
             label="validity at pull-off"),
) + stress_variables(AD_DIMS + ("z", "rho"), adhesive=True) + peak_variables(AD_DIMS)


def _evaluate_adhesive(names, p, options):
    from ..physics import graded as gp

    wanted = list(names)
    if "critical_validity" in names and "critical_radius" not in names:
        wanted.append("critical_radius")        # the flag is read off a_c
    values = dict(**_where(p), k=_f(p, "k"), nu=_nu(p), E0=_f(p, "E0"), c0=_f(p, "c0"),
                  delta_gamma=_f(p, "delta_gamma"), mode=p.get("control"))
    out = _fields(gp.adhesive_fields, gp.fields.ADHESIVE, wanted, p, options, **values)
    out.update(_stress(names, p, options, delta_gamma=_f(p, "delta_gamma")))
    out.update(_peaks(names, p, options, delta_gamma=_f(p, "delta_gamma")))
    if "critical_validity" in names:
        out["critical_validity"] = np.where(np.isnan(out["critical_radius"]), np.int8(V.no_critical_point),
                                            np.int8(V.within_stated_accuracy))
    if "validity" in names:
        out["validity"] = _flag(gp.adhesive_fields, gp.fields.ADHESIVE, ("pressure",), out, p, options, **values)
    return out


GRADED_ADHESIVE = Scenario(
    name="graded_adhesive",
    summary="Adhesive (JKR-type) contact of a rigid axisymmetric indenter and a power-law graded half-space: "
            "depth, force, pressure and the pull-off point at fixed load and fixed grips (MDR)",
    references=REFERENCE, theory="graded", parameters=GEOMETRY + MATERIAL_N + (DGAM, CONTROL, A_RAD, Z, R_REL),
    variables=_grouped(AD_VARS),
    evaluate=_evaluate_adhesive, methods=METHODS, check=_check_normal, conventions=CONVENTIONS, route=route,
    renamed=RENAMED,
    default_variables=("depth", "normal_force", "pressure", "critical_radius", "critical_depth", "critical_force"),
)

# -- graded_tangential ---------------------------------------------------------------------------
BODY2 = Parameter("body2", "counter-body: identical (the same graded material, eqs. 46-47), rigid, or elastic "
                  "(graded with the same k and c0, modulus E0_2 and Poisson's ratio nu_2)", kind=STR,
                  default="identical", choices=("identical", "rigid", "elastic"), sweepable=False, label="counter-body")
E0_2 = Parameter("E0_2", "modulus E0 of the elastic counter-body at depth c0", units="Pa", low=0.0, low_open=True,
                 high=1e15, required=True, when={"body2": ("elastic",)}, label="counter-body modulus E0_2")
NU_2 = Parameter("nu_2", "Poisson's ratio of the elastic counter-body (with poisson = 'holl_ratio': 1/(2+k) too)",
                 low=-1.0, low_open=True, high=0.5, required=True,
                 when={"body2": ("elastic",), "poisson": ("given",)}, label="counter-body nu_2")
POISSON = Parameter("poisson", "Poisson's ratio: 'given' (the parameter nu) or 'holl_ratio' (nu = 1/(2+k) for "
                    "every graded body, so that nu follows a sweep of k; Fig. 10)", kind=STR, default="given",
                    choices=("given", "holl_ratio"), sweepable=False, label="Poisson's ratio rule")
NU_T = Parameter(NU.name, NU.meaning, default=NU.default, low=NU.low, low_open=True, high=NU.high,
                 when={"poisson": ("given",)}, label=NU.label)
UNCOUPLED = Parameter("uncoupled_approximation", "where the normal and tangential problems do not decouple (sec. "
                      "5): 'reject' the recipe, or 'flag' the points (variable coupling) and compute the uncoupled "
                      "approximation", kind=STR, default="reject", choices=("reject", "flag"), sweepable=False,
                      label="uncoupled approximation")
MU = Parameter("mu", "coefficient of friction", default=0.3, low=0.0, low_open=True, high=10.0)
FX = Parameter("fx", "tangential force F_x divided by mu F_N (force control; 1: onset of gross slip)",
               default=0.0, low=0.0, high=1.0, label="F_x / (mu F_N)")
DELTA_X = Parameter("delta_x", "imposed tangential displacement delta_x (displacement control; the force "
                    "saturates at mu F_N once delta_x >= max_tangential_displacement)", units="m", default=0.0,
                    low=0.0, high=1e3, label="tangential shift delta_x")
PAIR = ("E0", "k", "nu", "E0_2", "nu_2")
T_FIELD = PAIR + ("c0", "mu", "contact_radius") + GEOM + ("fx", "rho")
T_DEEP = PAIR + ("c0", "mu", "contact_radius") + GEOM + ("fx", "z", "x")
X_T = Parameter("x", "coordinate x/a on the plane y = 0 through the axis along the tangential load (signed): "
                "where the stress variables are computed (with z)", low=-1e6, high=1e6, label="x / a", axis="X")
Z_T = Parameter("z", "depth below the surface divided by the contact radius a (0: the surface) of the stress "
                "variables; solved at k = 0", low=0.0, high=1e6, label="depth z / a", axis="Z")
T_VARS = (
    Variable("stick_radius", "radius c of the stick zone divided by the contact radius a (eq. 51)",
             dims=("k", "contact_radius") + GEOM + ("fx",), label="stick radius c / a"),
    Variable("tangential_displacement", "relative tangential displacement delta_x of the bodies (eq. 49)",
             units="m", dims=PAIR + ("mu", "contact_radius") + GEOM + ("fx",), label="tangential shift delta_x"),
    Variable("max_tangential_displacement", "tangential displacement delta_x,max at the onset of gross slip "
             "(eq. 50)", units="m", dims=PAIR + ("mu", "contact_radius") + GEOM,
             label="delta_x at gross slip"),
    Variable("force_ratio", "tangential force F_x divided by mu F_N under the imposed displacement delta_x "
             "(eq. 51; 1 in gross slip)", dims=PAIR + ("mu", "contact_radius") + GEOM + ("delta_x",),
             label="F_x / (mu F_N)"),
    Variable("normal_force", "normal force F_N pressing the bodies together at contact radius a", units="N",
             dims=PAIR + ("c0", "contact_radius") + GEOM, label="normal force F_N"),
    Variable("shear_traction", "tangential traction tau_x(r) = mu [p(r; a) - p(r; c)] on the lower body "
             "(eq. 45)", units="Pa", dims=T_FIELD, label="shear traction tau_x(r)"),
    # always: joins every variable that depends on the body pair
    Variable("coupling", "normal-tangential coupling of the body pair", dims=PAIR, dtype="int8", flag_values=(0, 1),
             flag_meanings=("decoupled_exact", "uncoupled_approximation"), always=True,
             comment="0: identical bodies, or nu = 1/(2+k) for every elastic body (sec. 5): the MDR solution is "
                     "exact; 1: the coupling is neglected (only with uncoupled_approximation = 'flag')",
                     label="normal-tangential coupling"),
    _validity(T_FIELD, ("shear_traction",), "shear_traction = +inf at r = 0 in gross slip (fx = 1) for a profile "
              "with n + k <= 1; under partial slip the traction at r = 0 is finite (docs/theory/graded.md (G47)) "
              "and flagged 0"),
) + tuple(
    Variable(n, f"{m} at (x, 0, z) on the plane y = 0 along the tangential load, x = x a, depth z a (z = 0: the "
             "surface), in the lower body", units="Pa", dims=T_DEEP, label=STRESS_LABELS[n],
             comment="tension positive, z into the body; k = 0 only; docs/theory/graded.md (G69)")
    for n, m in (("sigma_xx", "normal stress sigma_xx"), ("sigma_yy", "normal stress sigma_yy"),
                 ("sigma_zz", "normal stress sigma_zz"), ("sigma_xz", "shear stress sigma_xz"),
                 ("von_mises", "von Mises equivalent stress sqrt(3 J2)"), ("sigma_1", "largest principal stress"),
                 ("sigma_2", "intermediate principal stress"), ("sigma_3", "smallest principal stress"),
                 ("tau_max", "maximum shear stress (sigma_1 - sigma_3)/2"))
) + (
    Variable("stress_validity", "validity of the stress variables at the point", dims=T_DEEP, dtype="int8",
             always=True, **declare(STRESS_CODES, where={
                 V.unbounded_at_singular_point: "the conical tip r = 0 at z = 0",
                 V.undefined_direction_dependent_limit: "the tip in gross slip",
                 V.not_resolved_below_the_surface: "the 1-D routes of the axisymmetric family"}),
             label="validity of the stresses"),
) + peak_variables(PAIR + ("c0", "mu", "contact_radius") + GEOM + ("fx",), position="x")


def _pair(p):
    """Material pair in the physics' terms: (k, nu, E0, E0_2, nu_2); rigid body 2 is E0_2 = inf."""
    from ..physics import graded as gp

    k = _f(p, "k")
    nu = gp.holl_ratio(k) if p["poisson"] == "holl_ratio" else _f(p, "nu")
    body = p["body2"]
    if body == "identical":
        return k, nu, _f(p, "E0"), _f(p, "E0"), nu
    if body == "rigid":
        return k, nu, _f(p, "E0"), np.inf, None
    return k, nu, _f(p, "E0"), _f(p, "E0_2"), (nu if p["poisson"] == "holl_ratio" else _f(p, "nu_2"))


def _evaluate_tangential(names, p, options):
    from ..physics import graded as gp

    k, nu, e0, e2, nu2 = _pair(p)
    values = dict(**_where(p), fx=_f(p, "fx"), delta_x=_f(p, "delta_x"), mu=_f(p, "mu"), c0=_f(p, "c0"), k=k,
                  nu=nu, E0=e0, E0_2=e2, nu_2=nu2, require_decoupled=p["uncoupled_approximation"] == "reject")
    out = _fields(gp.tangential_fields, gp.fields.TANGENTIAL, names, p, options, **values)
    out.update(_tangential_stress(names, p, options, values))
    out.update(_tangential_peaks(names, p, options, values))
    if "coupling" in names:
        ok = gp.tangential_decoupled(k, nu, E0=e0, E0_2=e2, nu_2=nu2)
        out["coupling"] = np.where(ok, np.int8(0), np.int8(1))
    if "validity" in names:
        out["validity"] = _flag(gp.tangential_fields, gp.fields.TANGENTIAL, ("shear_traction",), out, p, options,
                                **values)
    return out


def _tangential_stress(names, p, options, values) -> dict:
    """The requested stress variables of the lower body (k = 0) and their validity flag."""
    from ..physics.graded.interior import TANGENTIAL_INTERIOR, tangential_interior_fields

    wanted = [n for n in names if n in TANGENTIAL_INTERIOR and n != "validity"]   # (that name is the surface's flag)
    if "stress_validity" in names:
        wanted.append("validity")
    if not wanted:
        return {}
    x, z = _f(p, "x"), _f(p, "z")
    got = tangential_interior_fields(
        wanted, _indenter(p), a=values["a"], x=np.zeros(()) if x is None else x, z=np.zeros(()) if z is None else z,
        fx=values["fx"], mu=values["mu"], k=values["k"], nu=values["nu"], E0=values["E0"], c0=values["c0"],
        E0_2=values["E0_2"], nu_2=values["nu_2"], method=options["method"], rtol=options["rtol"])
    if "validity" in got:
        got["stress_validity"] = got.pop("validity")
    return got


def _tangential_peaks(names, p, options, values) -> dict:
    """The requested peaks of the lower body (k = 0)."""
    from ..physics.graded.interior import TANGENTIAL_PEAKS, tangential_peaks

    if not any(n in TANGENTIAL_PEAKS for n in names):
        return {}
    found = tangential_peaks(_indenter(p), a=values["a"], fx=values["fx"], mu=values["mu"], k=values["k"],
                             nu=values["nu"], E0=values["E0"], c0=values["c0"], E0_2=values["E0_2"],
                             nu_2=values["nu_2"], method=options["method"], rtol=options["rtol"])
    return {n: found[n] for n in names if n in TANGENTIAL_PEAKS}


def _check_tangential(values, physical, options):
    problems = _check_profile(values)
    below = values.get("z") is not None or values.get("x") is not None
    peaks = [n for n in getattr(values, "variables", ()) if n.endswith("_peak") or "_peak_" in n]
    what = "z or x is given" if below else f"{peaks[0]} is asked for" if peaks else ""
    if what and np.any(np.asarray(values.get("k")) > 0.0):
        problems.append(f"{what} with k = {float(np.max(values['k']))!r}: below the surface under tangential "
                        "load the graded family solves k = 0")
    if values.get("uncoupled_approximation") == "flag" or values.get("body2") == "identical":
        return problems
    from ..physics import graded as gp

    g = _grid(values, PAIR)
    p = {**g, "poisson": values["poisson"], "body2": values["body2"]}
    k, nu, e0, e2, nu2 = _pair(p)
    ok = gp.tangential_decoupled(k, nu, E0=e0, E0_2=e2, nu_2=nu2)
    if not np.all(ok):
        bad = tuple(np.argwhere(~ok)[0])
        at = lambda v: float(np.broadcast_to(v, ok.shape)[bad])  # noqa: E731
        holl = 1.0 / (2.0 + at(k))
        need = ("nu must equal the Holl ratio 1/(2+k)" if values["body2"] == "rigid" else
                "the bodies must be identical (E0_2 = E0, nu_2 = nu) or both have nu = nu_2 = 1/(2+k)")
        where = f"nu = {at(nu)!r} with k = {at(k)!r}" + (
            f", E0 = {at(e0)!r}, E0_2 = {at(e2)!r}, nu_2 = {at(nu2)!r}" if values["body2"] == "elastic" else "")
        if set(PAIR) & set(getattr(values, "points", ())):
            where += f" at point {int(bad[-1])}"       # the [points] columns share the last axis
        problems.append(f"{where} (body2 = {values['body2']!r}): the normal and tangential problems do not "
                        f"decouple; {need}, here {holl:.12g} (Hess & Popov 2016, sec. 5). Set poisson = "
                        "'holl_ratio', or uncoupled_approximation = 'flag' to compute the uncoupled approximation "
                        "with a flag")
    return problems


GRADED_TANGENTIAL = Scenario(
    name="graded_tangential",
    summary="Cattaneo-Mindlin partial slip between power-law graded bodies: stick radius, tangential "
            "displacement and force, shear traction (MDR)",
    references=REFERENCE, theory="graded",
    parameters=GEOMETRY + (E0, C0, POISSON, NU_T, K, BODY2, E0_2, NU_2, UNCOUPLED, MU, A_RAD, FX, DELTA_X, R_REL,
                           Z_T, X_T),
    variables=_grouped(T_VARS), evaluate=_evaluate_tangential, methods=METHODS, check=_check_tangential,
    conventions=CONVENTIONS, route=route, renamed=RENAMED,
    default_variables=("stick_radius", "tangential_displacement", "max_tangential_displacement", "normal_force",
                       "shear_traction"),
)

SCENARIOS: tuple = (GRADED_NORMAL, GRADED_ADHESIVE, GRADED_TANGENTIAL)
