"""Stop conditions: ``KEY OP VALUE`` over a run's report values (fprime_lite.tools.stop_condition)."""

import enum

import pytest

from fprime_lite.tools.stop_condition import StopConditionError, holds_all, parse_stop_condition


class Mode(enum.Enum):
    SPIN_STABLE = 2
    POINTING = 3


@pytest.mark.parametrize("text, values, expected", [
    ("spin_settled_for_s >= 300", {"spin_settled_for_s": 300.0}, True),
    ("spin_settled_for_s >= 300", {"spin_settled_for_s": 299.5}, False),
    ("rate_deg_s<1", {"rate_deg_s": 0.99}, True),
    ("rate_deg_s < 1", {"rate_deg_s": 1.0}, False),
    ("rate_deg_s > 1e-3", {"rate_deg_s": 2e-3}, True),
    ("n <= 2", {"n": 3}, False),
    ("n == 2", {"n": 2}, True),
    ("n != 2", {"n": 2}, False),
    ("mode == POINTING", {"mode": "POINTING"}, True),
    ("mode == POINTING", {"mode": Mode.POINTING}, True),       # an enum compares by its name
    ("mode == POINTING", {"mode": Mode.SPIN_STABLE}, False),
    ("mode != POINTING", {"mode": "SPIN_STABLE"}, True),
    ("rate_deg_s < 1", {}, False),                              # not published (yet): does not hold
    ("rate_deg_s < 1", {"rate_deg_s": float("nan")}, False),
    ("rate_deg_s < 1", {"rate_deg_s": "low"}, False),           # a number against text: does not hold
    ("flag == 1", {"flag": True}, False),                       # a bool is not a number here
])
def test_a_condition_holds_exactly_when_its_comparison_does(text, values, expected):
    """RUN-060: each operator compares the published value with the condition's; a missing, NaN or non-numeric
    value never satisfies a numeric condition; words compare with an enum's name."""
    assert parse_stop_condition(text).holds(values) is expected


def test_all_conditions_must_hold_and_an_empty_list_never_stops():
    """RUN-060: a list stops only when every condition holds; no conditions never stop a run."""
    conditions = [parse_stop_condition("mode == SPIN_STABLE"), parse_stop_condition("spin_settled_for_s >= 10")]
    assert holds_all(conditions, {"mode": "SPIN_STABLE", "spin_settled_for_s": 12.0})
    assert not holds_all(conditions, {"mode": "SPIN_STABLE", "spin_settled_for_s": 9.0})
    assert not holds_all(conditions, {"mode": "POINTING", "spin_settled_for_s": 12.0})
    assert not holds_all([], {"anything": 1})


@pytest.mark.parametrize("text, message", [
    ("spin_settled_for_s", "is not KEY OP VALUE"),
    ("spin >= ", "is not KEY OP VALUE"),
    ("1x >= 3", "is not KEY OP VALUE"),
    ("mode >= POINTING", "a word compares only with == or !="),
    ("rate < inf", "the value must be finite"),
    ("rate < 1-2", "the value is a number or a word"),
    (42, "a stop condition is text KEY OP VALUE, got int"),
])
def test_a_malformed_condition_says_what_to_write(text, message):
    """RUN-061: a condition that cannot be read is refused with what is wrong and an example."""
    with pytest.raises(StopConditionError, match=message) as info:
        parse_stop_condition(text)
    assert "e.g. 'spin_settled_for_s >= 300'" in str(info.value)
