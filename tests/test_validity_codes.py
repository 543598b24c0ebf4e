"""One validity-code table for the whole product (physics/flags.py): every ``*validity`` variable of
every scenario holds codes of the table only, each code means the same cause in every scenario, and
the published numbers of the shared causes do not move.

The table is checked against a list written out here, not read from the code: a renumbered or reworded
code fails below and must be said in CHANGELOG.md."""
from __future__ import annotations

import numpy as np
import pytest

from stressfields.physics import flags
from stressfields.physics.flags import CAUSES, Validity, declare, validity_flag
from stressfields.scenarios import REGISTRY

#: the codes as published (README "The contract", CHANGELOG): code -> flag_meanings word
PUBLISHED = {0: "within_stated_accuracy", 1: "unbounded_at_singular_point", 2: "undefined_direction_dependent_limit",
             3: "not_resolved_below_the_surface", 4: "search_not_converged", 5: "series_not_converged",
             6: "approximate_formula", 7: "nonperiodic_series_within_rtol", 8: "stick_zone_not_admissible",
             9: "no_critical_point"}
#: flag variables with a vocabulary of their own: not validity codes, and not named so
OWN_VOCABULARY = {"region", "continuous_contact", "converged", "coupling"}


def _flag_variables():
    for scenario in REGISTRY.values():
        for var in scenario.variables:
            if var.flag_values:
                yield scenario.name, var


def test_the_table_is_the_published_one():
    assert {int(c): c.name for c in Validity} == PUBLISHED
    assert set(CAUSES) == set(Validity)
    assert all(text and "\n" not in text for text in CAUSES.values())
    assert len(set(CAUSES.values())) == len(CAUSES)          # one cause per code, never two codes for one


def test_every_validity_declaration_uses_the_table_and_a_code_means_one_cause_everywhere():
    seen: dict[int, set[str]] = {}
    walked = set()
    for scenario, var in _flag_variables():
        if var.name not in OWN_VOCABULARY:
            assert var.name.endswith("validity"), (scenario, var.name)
        if not var.name.endswith("validity"):
            assert var.name in OWN_VOCABULARY, (scenario, var.name)
            continue
        walked.add((scenario, var.name))
        assert len(var.flag_values) == len(var.flag_meanings) == len(set(var.flag_values))
        assert var.flag_values[0] == 0 and list(var.flag_values) == sorted(var.flag_values)
        for value, meaning in zip(var.flag_values, var.flag_meanings, strict=True):
            assert PUBLISHED.get(value) == meaning, (scenario, var.name, value, meaning)
            seen.setdefault(value, set()).add(meaning)
            if value:
                # the file's comment gives the table's cause of every nonzero code
                assert f"{value}: {CAUSES[Validity(value)]}" in var.comment, (scenario, var.name, value)
    assert all(len(meanings) == 1 for meanings in seen.values()), seen
    # the walk did reach every family and each kind of flag
    assert {s for s, _ in walked} == set(REGISTRY)
    assert {n for _, n in walked} == {"validity", "peak_validity", "stress_validity", "critical_validity"}


def test_the_file_attributes_carry_the_declared_codes():
    import stressfields as sf

    ds = sf.generate({"scenario": "wavy", "parameters": {"amplitudes": [1.0], "wavenumbers": [1], "a": 0.3,
                                                         "x": [0.0]}})
    assert list(ds.validity.attrs["flag_values"]) == [0, 2, 5, 6, 7, 8]
    assert ds.validity.attrs["flag_meanings"].split() == [PUBLISHED[c] for c in (0, 2, 5, 6, 7, 8)]


def test_declare_refuses_a_cause_for_a_code_the_flag_does_not_hold():
    with pytest.raises(ValueError, match="do not hold|does not hold"):
        declare((Validity.within_stated_accuracy,), where={Validity.series_not_converged: "here"})
    got = declare((Validity.unbounded_at_singular_point, Validity.within_stated_accuracy),
                  where={Validity.unbounded_at_singular_point: "the tip"}, note="More.")
    assert got["flag_values"] == (0, 1)
    assert got["flag_meanings"] == ("within_stated_accuracy", "unbounded_at_singular_point")
    assert got["comment"] == f"1: {CAUSES[Validity.unbounded_at_singular_point]} (the tip). More."


def test_the_shared_flag_of_non_finite_values():
    """+-inf is an unbounded limit (1), NaN a direction-dependent one (2, winning over 1), finite 0."""
    a = np.array([0.0, np.inf, -np.inf, np.nan, 1.0])
    b = np.array([np.inf, 0.0, np.nan, 0.0, 2.0])
    got = validity_flag(a, b)
    assert got.dtype == np.int8
    assert got.tolist() == [1, 1, 2, 2, 0]
    assert validity_flag() == 0 and flags.validity_flag(np.float64(3.0)) == 0
