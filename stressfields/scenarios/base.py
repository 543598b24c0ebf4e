"""The one declaration of a scenario: its parameters, its variables, and how it evaluates.

Everything user-facing is derived from these declarations: recipe validation and its error
messages, CLI help (`stressfields describe`), CF attributes of the dataset, and data_schema.md.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable, Collection, Mapping, Protocol, Sequence, TypedDict

import numpy as np

from .scales import Scale

#: Values a parameter may take.
FLOAT, INT, STR, ARRAY = "float", "int", "str", "float array"
#: default size limit of ARRAY parameters (a history on 10 points: 0.17 s at 10 steps, 4.2 s at 100)
MAX_ARRAY_SIZE = 1000
#: the longest label (the files' ``long_name``); the full sentence goes in ``description``
LABEL_CHARS = 40
#: xarray's default plot label "<long_name> [<units>]" is wrapped at 30 characters: a label with its
#: units within this fits one line (`plot_label`, checked for every declaration by the tests)
PLOT_LABEL_CHARS = 30
#: size limit of a tabulated profile's samples (profile_r, profile_f): its set-up costs
#: O(samples log samples) and is cached per profile (physics/setup_cache.py); a measured indenter
#: profile has 1e3-1e4 samples
MAX_TABLE_SIZE = 10000


class Options(TypedDict):
    """What a scenario's evaluate receives besides the parameter values."""

    method: str        # the recipe's [method] method: "auto" or one of Scenario.methods
    rtol: float        # the accuracy target of quadrature and series
    physical: bool     # physical units (the recipe gave the scenario's physical_switch)
    sweep: Mapping[str, Any]   # the recipe's values over the whole sweep (not this block's)


class Evaluate(Protocol):
    """The evaluate contract: the requested variables on one block of points.

    ``params`` maps each parameter to a NumPy value broadcastable to the block (a scalar, or a
    string for a choice, where the parameter is fixed); the result maps each requested name to an
    array broadcastable to the block, in the units of the variable's declaration for the mode.
    """

    def __call__(self, names: Sequence[str], params: Mapping[str, Any], options: Options) -> dict[str, np.ndarray]: ...


class Route(Protocol):
    """route(values, method, rtol, groups) -> {group: (the method used, its accuracy)}: the family's
    route table (``physics.<family>.routes.resolve``) for each group of variables, said in the
    attributes of that group's variables; ValueError where the method has no route."""

    def __call__(self, values: Mapping[str, Any], method: str, rtol: float,
                 groups: Sequence[str]) -> dict[str, tuple[str, str]]: ...


@dataclass(frozen=True)
class Parameter:
    """One recipe parameter: a single value or, if ``sweepable``, a sweep that becomes a dimension.

    ``units`` is the UDUNITS string in the default (normalised) mode and ``units_physical`` the
    one used when the recipe switches to physical units (``None``: the same in both modes);
    ``meaning_physical`` likewise replaces ``meaning`` in physical mode, for a parameter whose
    normalised meaning says what it is divided by (``None``: the same in both modes). ``label``
    (and ``label_physical``) is the short name of at most LABEL_CHARS characters written as the
    coordinate's ``long_name``, the meaning going to ``description``; without one the meaning is
    the label, so a meaning longer than that needs a label. ``axis`` ("X", "Y" or "Z") marks a
    spatial coordinate for CF-aware readers (`cf.coord_attrs`).
    """

    name: str
    meaning: str
    meaning_physical: str | None = None
    units: str = "1"
    units_physical: str | None = None
    kind: str = FLOAT
    default: Any = None
    required: bool = False
    low: float | None = None
    high: float | None = None
    low_open: bool = False
    high_open: bool = False
    choices: tuple[str, ...] = ()
    sweepable: bool = True
    #: only meaningful in this mode ("normalised" or "physical"); None: both
    mode: str | None = None
    #: only meaningful when another parameter has one of these values, e.g. {"profile": ("power_law",)}
    when: Mapping[str, tuple] = field(default_factory=dict)
    #: ARRAY parameters: the most values accepted (None: MAX_ARRAY_SIZE)
    max_size: int | None = None
    label: str | None = None
    label_physical: str | None = None
    axis: str | None = None

    @property
    def size_limit(self) -> int:
        """The most values an ARRAY parameter accepts, checked before anything is computed."""
        return MAX_ARRAY_SIZE if self.max_size is None else self.max_size

    def units_in(self, physical: bool) -> str:
        return self.units_physical if (physical and self.units_physical) else self.units

    def meaning_in(self, physical: bool) -> str:
        """The meaning in the mode, as said in the files' ``description``."""
        return self.meaning_physical if (physical and self.meaning_physical) else self.meaning

    def label_in(self, physical: bool) -> str:
        """The short name in the mode, as said in the files' ``long_name`` (at most LABEL_CHARS)."""
        if physical and self.label_physical:
            return self.label_physical
        return self.label or self.meaning_in(physical)

    def plot_label(self, physical: bool) -> str:
        """The label xarray's ``.plot()`` draws: the long_name and the units in brackets."""
        return _with_units(self.label_in(physical), "" if self.choices else self.units_in(physical))

    def condition(self) -> str:
        """The `when` condition in words: keys joined by 'and', values of one key by 'or'; the value
        None reads "<key> is not given" (a parameter that is the alternative of another, e.g. delta
        applies when normal_force is not given)."""
        return " and ".join(" or ".join(f"{k} is not given" if v is None else f"{k} = {v!r}" for v in vs)
                            for k, vs in self.when.items())

    @property
    def per_point(self) -> bool:
        """Whether the parameter may be a column of a recipe's [points] (one number per point)."""
        return self.sweepable and self.kind != ARRAY and not self.choices

    def allowed(self) -> str:
        """Plain-language description of the allowed values, used in errors and in the schema."""
        if self.choices:
            return "one of " + ", ".join(repr(c) for c in self.choices)
        if self.kind == ARRAY:
            return f"an array of at most {self.size_limit} finite numbers"
        lo = "(" if self.low_open else "["
        hi = ")" if self.high_open else "]"
        low = "-inf" if self.low is None else _fmt(self.low)
        high = "inf" if self.high is None else _fmt(self.high)
        what = "an integer" if self.kind == INT else "a number"
        if self.low is None and self.high is None:
            return what
        return f"{what} in {lo}{low}, {high}{hi}"

    def check(self, value) -> str | None:
        """Return why ``value`` (one scalar) is not allowed, or None."""
        if self.choices:
            if value not in self.choices:
                return f"must be {self.allowed()}"
            return None
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            return f"must be {self.allowed()}, got a {type(value).__name__}"
        if self.kind == INT and (not float(value).is_integer() or abs(value) > 2 ** 31 - 1):
            return f"must be {self.allowed()} (a 32-bit integer)"
        try:
            v = float(value)
        except OverflowError:       # an integer beyond the float range
            v = math.inf
        if not math.isfinite(v):
            return f"must be finite ({self.allowed()})"
        if self.low is not None and (v < self.low or (self.low_open and v == self.low)):
            return f"must be {self.allowed()}"
        if self.high is not None and (v > self.high or (self.high_open and v == self.high)):
            return f"must be {self.allowed()}"
        return None

    def check_many(self, values: np.ndarray) -> tuple[Any, str] | None:
        """The first value of a numeric sweep that is not allowed and why, or None.

        Vectorised: a 1e7-value sweep is checked in about 0.1 s (one value at a time: ~20 s).
        """
        v = np.asarray(values, dtype=np.float64)
        bad = ~np.isfinite(v)
        if self.kind == INT:
            bad |= (v != np.round(v)) | (np.abs(v) > 2 ** 31 - 1)
        if self.low is not None:
            bad |= (v <= self.low) if self.low_open else (v < self.low)
        if self.high is not None:
            bad |= (v >= self.high) if self.high_open else (v > self.high)
        if not bad.any():
            return None
        first = v[int(np.argmax(bad))].item()
        return first, self.check(first) or f"must be {self.allowed()}"


@dataclass(frozen=True)
class Variable:
    """One output variable.

    ``dims`` lists the parameters it depends on (a swept one becomes a dimension of the
    variable); ``None`` means all of them. ``scale`` is the family's ``Scale`` of the variable (None:
    not normalised): ``scales.apply_scales`` multiplies the physics' values by its factor, and its
    text becomes the ``normalisation`` attribute and is said in ``description`` and, by its symbol,
    in the label. ``group`` names the variable's route group (the key of the scenario's ``route``
    table: which computation, closed form, quadrature or series, produced it and to what accuracy).
    ``long_name`` is the full sentence (the files' ``description``); ``label`` the short name of the
    files' ``long_name`` (`label_in`; without one ``long_name`` serves, so a ``long_name`` longer than
    LABEL_CHARS needs a label).
    """

    name: str
    long_name: str
    units: str = "1"
    units_physical: str | None = None
    scale: Scale | None = None
    dims: tuple[str, ...] | None = None
    dtype: str = "float64"
    flag_values: tuple[int, ...] = ()
    flag_meanings: tuple[str, ...] = ()
    comment: str | None = None
    mode: str | None = None
    #: computed whenever any other variable spanning its dims is requested (True, e.g. the validity
    #: flag), or whenever one of the named variables is (a tuple: the flag of those variables only)
    always: bool | tuple[str, ...] = False
    #: stored as a coordinate (not a dimension): a value the others are read and plotted against,
    #: e.g. the displacement of each step of a history (``ds.plot(x="ux0")``)
    coordinate: bool = False
    #: joins the default variable list when the recipe gives one of these parameters: a load derived
    #: from them (e.g. delta when normal_force is given); recipes giving none keep their list and hash
    recorded_when: tuple[str, ...] = ()
    label: str | None = None
    #: the route group of a float variable (``Scenario.route`` gives its method and accuracy)
    group: str = "surface"

    def units_in(self, physical: bool) -> str:
        return self.units_physical if (physical and self.units_physical) else self.units

    def long_name_in(self, physical: bool) -> str:
        """The full sentence in the mode, as said in the files' ``description``."""
        if self.scale and not physical:
            return f"{self.long_name} divided by {self.scale.text}"
        return self.long_name

    def label_in(self, physical: bool) -> str:
        """The short name in the mode, as said in the files' ``long_name``: the label, then in
        normalised mode " / " and the symbol of the scale ("stress sigma_xx / p_m")."""
        text = self.label or self.long_name
        if self.scale and not physical:
            return f"{text} / {self.scale.symbol}"
        return text

    def plot_label(self, physical: bool) -> str:
        """The label xarray's ``.plot()`` draws: the long_name and the units in brackets."""
        return _with_units(self.label_in(physical), "" if self.flag_values else self.units_in(physical))


@dataclass(frozen=True)
class Scenario:
    """A user-facing scenario: the registry maps ``name`` to one of these."""

    name: str
    summary: str
    #: the papers (with DOI where known); files cite them with the theory page below
    references: str
    parameters: tuple[Parameter, ...]
    variables: tuple[Variable, ...]
    #: evaluate(names, params, options) -> {name: array}; params maps each parameter name to a
    #: NumPy value broadcastable to the block (a scalar for a fixed one); options holds the
    #: recipe's [method] table and the mode ("physical": bool).
    evaluate: Evaluate
    #: parameters whose presence switches the scenario to physical units
    physical_switch: str | None = None
    #: sign conventions of the data, said in each file's `comment`
    conventions: str = ("tension positive, z points into the body, p_h = -trace(sigma)/3, tangential "
                        "traction on the half-space along +x")
    methods: tuple[str, ...] = ("auto",)
    default_variables: tuple[str, ...] | None = None
    #: extra checks across parameters: check(values, physical, options) -> list of messages, with
    #: options the recipe's [method] table ({"method": ..., "rtol": ...}); a method without a route is
    #: refused by `route_problems`, in the route table's words
    check: Callable[..., list[str]] | None = None
    #: route(values, method, rtol, groups) -> {group: (the method used, its accuracy)}, said in the
    #: attributes of each group's variables (``Variable.group``)
    route: Route | None = None
    #: defaults that depend on other parameters: complete(values) fills them in place, before `check`
    complete: Callable[[dict], None] | None = None
    #: the page of docs/theory/ that gives the equations the scenario implements
    theory: str = ""
    #: former parameter names -> current ones: a recipe using an old name is told the new one
    renamed: Mapping[str, str] = field(default_factory=dict)

    @property
    def full_references(self) -> str:
        """The papers and the theory page, as written in every file's ``references``."""
        if not self.theory:
            return self.references
        return (f"{self.references}. Equations as implemented, with conventions and errata: "
                f"stressfields documentation, docs/theory/{self.theory}.md")

    def parameter(self, name: str) -> Parameter:
        return {p.name: p for p in self.parameters}[name]

    def variable(self, name: str) -> Variable:
        return {v.name: v for v in self.variables}[name]

    def routed(self, names: Collection[str]) -> tuple[str, ...]:
        """The route groups of the float variables among ``names`` (flags and integers have none), in
        declaration order."""
        wanted = set(names)
        return tuple(dict.fromkeys(v.group for v in self.variables if v.name in wanted and not v.flag_values
                                   and v.dtype.startswith("float")))

    def routes(self, values: Mapping[str, Any], method: str, rtol: float,
               names: Collection[str]) -> dict[str, tuple[str, str]]:
        """{group: (route, accuracy)} of the float variables among ``names`` (``route``; {} without one)."""
        groups = self.routed(names)
        if self.route is None or not groups:
            return {}
        return self.route(values, method, rtol, groups)

    def route_problems(self, values: Mapping[str, Any], options: Mapping[str, Any],
                       names: Collection[str]) -> list[str]:
        """The route table's refusal of the recipe's method for the variables ``names``, as the one
        message of a recipe check ("method." and the table's words), or []."""
        try:
            self.routes(values, options["method"], options["rtol"], names)
        except ValueError as exc:
            return [f"method.{exc}"]
        return []

    def variables_in(self, physical: bool) -> tuple[Variable, ...]:
        mode = "physical" if physical else "normalised"
        return tuple(v for v in self.variables if v.mode in (None, mode))

    def available(self, physical: bool, given: Collection[str] = ()) -> tuple[Variable, ...]:
        """The variables a recipe may request: those of the mode, less any whose name is a parameter
        the recipe has a value for (``given``): that value is already a coordinate of the dataset."""
        return tuple(v for v in self.variables_in(physical) if v.name not in given)

    def defaults(self, physical: bool, given: Collection[str] = ()) -> tuple[str, ...]:
        """The variables written when the recipe names none: ``default_variables`` (else every
        available one that is not always-on), then those ``recorded_when`` a parameter in ``given``."""
        names = {v.name for v in self.available(physical, given)}
        base = self.default_variables or [v.name for v in self.variables_in(physical) if not v.always]
        extra = [v.name for v in self.variables_in(physical) if set(v.recorded_when) & set(given)]
        return tuple(n for n in dict.fromkeys([*base, *extra]) if n in names)


#: the smallest step of a tabulated profile, relative to its span: the graded quadrature breaks
#: between 1e-100 and 1e-200 and the axisymmetric table construction stalls at 1e-300 (measured);
#: a step below 1e-12 of the span carries no geometry a contact resolves
MIN_TABLE_STEP = 1e-12


def table_step_problem(name: str, r) -> str | None:
    """Why the radii ``r`` of a tabulated profile are spaced too finely, or None."""
    r = np.asarray(r, dtype=float)
    if r.size < 2 or not np.all(np.isfinite(r)) or r[-1] <= r[0]:
        return None
    step = float(np.min(np.diff(r)))
    span = float(r[-1] - r[0])
    if 0.0 < step < MIN_TABLE_STEP * span:
        return (f"{name} has a step of {step:.3g}, below {MIN_TABLE_STEP:g} of its span {span:.6g}; "
                "merge samples closer than that")
    return None


def _with_units(label: str, units: str) -> str:
    return f"{label} [{units}]" if units else label


def _fmt(v: float) -> str:
    return repr(int(v)) if float(v).is_integer() and abs(v) < 1e7 else f"{float(v):.10g}"
