"""The validity codes of the whole product and the flag every family writes beside its fields.

One table, ``CAUSES``: every code a ``*validity`` variable of any scenario can hold, its CF
``flag_meanings`` word and the one-line cause the files' comments give. A code means the same cause in
every scenario and is never reused for another: the shared causes (0-4: within accuracy, an unbounded
or a direction-dependent limit, a point not resolved below the surface, a peak search that did not
converge) come first, the family-specific ones follow. The scenarios declare their flags with
:func:`declare` and the kernels write the members of :class:`Validity` by name, never a bare number
(docs/theory/README.md, conventions).
"""
from __future__ import annotations

import enum
import functools
from typing import Iterable, Mapping

import numpy as np


class Validity(enum.IntEnum):
    """The validity codes; a member's name is its CF ``flag_meanings`` word."""

    within_stated_accuracy = 0
    unbounded_at_singular_point = 1
    undefined_direction_dependent_limit = 2
    not_resolved_below_the_surface = 3
    search_not_converged = 4
    series_not_converged = 5
    approximate_formula = 6
    nonperiodic_series_within_rtol = 7
    stick_zone_not_admissible = 8
    no_critical_point = 9


#: code -> the cause in one line, as the files' comments say it (a declaration may add where it occurs)
CAUSES: Mapping[Validity, str] = {
    Validity.within_stated_accuracy: "every value is within its stated accuracy (stressfields_accuracy)",
    Validity.unbounded_at_singular_point: "a value is +-inf where its exact limit is infinite (a singular point)",
    Validity.undefined_direction_dependent_limit: "a value is NaN where its exact limit depends on the direction "
                                                  "of approach",
    Validity.not_resolved_below_the_surface: "a value below the surface is NaN at a point the numerical route "
                                             "does not resolve",
    Validity.search_not_converged: "the peak search did not converge or ended on the border of its box: the "
                                   "values are the best found, not necessarily the peak",
    Validity.series_not_converged: "the series did not meet method.rtol: the values are the best available, "
                                   "within error_estimate",
    Validity.approximate_formula: "the value is the published approximate formula the method names, NOT within "
                                  "the stated accuracy",
    Validity.nonperiodic_series_within_rtol: "the periodic value is the cheaper non-periodic series, within "
                                             "method.rtol of the periodic one",
    Validity.stick_zone_not_admissible: "partial slip whose load P(c) is not increasing on [c, a]: the stick zone "
                                        "would not shrink monotonically, the superposition is not the solution, "
                                        "and the values of the tangential load are NaN",
    Validity.no_critical_point: "no critical point exists: the critical values are NaN",
}


def declare(codes: Iterable[Validity], where: Mapping[Validity, str] | None = None,
            note: str = "") -> dict:
    """The ``flag_values``, ``flag_meanings`` and ``comment`` of a validity variable holding ``codes``,
    from the table: the comment gives each nonzero code's cause, with ``where`` it occurs in this
    variable (in brackets), then ``note``. Pass the result to ``Variable(**...)``."""
    codes = sorted(Validity(c) for c in codes)
    where = dict(where or {})
    if unknown := set(where) - set(codes):
        raise ValueError(f"causes given for codes the flag does not hold: {sorted(unknown)}")
    said = [f"{int(c)}: {CAUSES[c]}" + (f" ({where[c]})" if c in where else "")
            for c in codes if c != Validity.within_stated_accuracy]
    comment = "; ".join(said) + "." + (f" {note}" if note else "")
    return dict(flag_values=tuple(int(c) for c in codes), flag_meanings=tuple(c.name for c in codes),
                comment=comment)


def quiet(kernel):
    """Run ``kernel`` with floating-point warnings off.

    A kernel's overflow, 0/0 or inf - inf is not news for its caller: the value it produces (+-inf
    where the exact limit is infinite, NaN where it depends on the direction) is the report, and the
    validity flag names its cause. Warnings would only repeat that, once per dask block.
    """
    @functools.wraps(kernel)
    def silent(*args, **kwargs):
        with np.errstate(all="ignore"):
            return kernel(*args, **kwargs)
    return silent


def validity_flag(*arrays: np.ndarray) -> np.ndarray:
    """Per point: ``within_stated_accuracy`` every value finite, ``unbounded_at_singular_point`` some
    value unbounded (+-inf: the exact limit is infinite), ``undefined_direction_dependent_limit`` some
    value undefined (NaN: the limit depends on the direction of approach); ``np.int8(0)`` for no arrays."""
    if not arrays:
        return np.int8(Validity.within_stated_accuracy)
    shape = np.broadcast_shapes(*(np.shape(v) for v in arrays))
    flag = np.full(shape, Validity.within_stated_accuracy, dtype=np.int8)
    for v in arrays:
        flag = np.where(np.isinf(np.broadcast_to(v, shape)), np.int8(Validity.unbounded_at_singular_point), flag)
    for v in arrays:
        flag = np.where(np.isnan(np.broadcast_to(v, shape)), np.int8(Validity.undefined_direction_dependent_limit),
                        flag)
    return flag.astype(np.int8)
