"""StrategySelector: deadband with memory, detumble.md §4 (rates in deg/s)."""

import math

from hypothesis import given
from hypothesis import strategies as st

from detumble.control.strategy_selector import Strategy, StrategySelector

MAX, UPPER, LOWER = 720.0, 8.0, 5.0


def selector():
    s = StrategySelector()
    s.configure(MAX, UPPER, LOWER)
    return s


def test_starts_only_above_upper_and_continues_down_to_lower():
    """Deadband Activation: from rest, 6 and 7.9 deg/s stay IDLE; 8 starts B-dot; then B-dot
    continues at 7, 6 and 5 deg/s and stops below 5."""
    s = StrategySelector()
    s.configure(MAX, UPPER, LOWER)
    # Memory starts at LOWER: a rate inside the band at power-up is detumbled (target = lower).
    assert s.rotation_target == LOWER
    assert s.from_angular_velocity_magnitude(4.0) == Strategy.IDLE  # below lower: re-arm at upper
    assert s.rotation_target == UPPER
    assert s.from_angular_velocity_magnitude(6.0) == Strategy.IDLE
    assert s.from_angular_velocity_magnitude(7.9) == Strategy.IDLE
    assert s.from_angular_velocity_magnitude(8.0) == Strategy.BDOT  # ≥ upper
    assert s.rotation_target == LOWER
    for w in (7.0, 6.0, 5.0):
        assert s.from_angular_velocity_magnitude(w) == Strategy.BDOT
    assert s.from_angular_velocity_magnitude(4.99) == Strategy.IDLE
    assert s.from_angular_velocity_magnitude(7.0) == Strategy.IDLE  # back inside the band: idle


def test_initial_memory_is_lower_threshold():
    """Deadband Activation: the memory starts at the lower threshold (§4)."""
    s = selector()
    assert s.from_angular_velocity_magnitude(6.0) == Strategy.BDOT


def test_hysteresis_at_and_above_max_keeps_memory():
    """Hysteresis Strategy: w ≥ BDOT_MAX_THRESHOLD selects HYSTERESIS and leaves the target alone."""
    s = selector()
    s.from_angular_velocity_magnitude(1.0)  # target = upper
    assert s.from_angular_velocity_magnitude(720.0) == Strategy.HYSTERESIS
    assert s.from_angular_velocity_magnitude(5000.0) == Strategy.HYSTERESIS
    assert s.rotation_target == UPPER
    assert s.from_angular_velocity_magnitude(719.999) == Strategy.BDOT


def test_bdot_in_the_intermediate_range():
    """B-Dot Strategy: between the upper threshold and the maximum, B-dot is selected."""
    s = selector()
    s.from_angular_velocity_magnitude(0.0)
    for w in (8.0, 100.0, 719.0):
        assert s.from_angular_velocity_magnitude(w) == Strategy.BDOT


def test_reconfiguring_with_same_thresholds_keeps_memory():
    """DEVIATION (§4): configure before every decision with unchanged thresholds keeps the memory;
    the flight code reset it and so defeated the deadband."""
    s = selector()
    s.from_angular_velocity_magnitude(2.0)  # target = upper
    s.configure(MAX, UPPER, LOWER)
    assert s.from_angular_velocity_magnitude(6.0) == Strategy.IDLE  # still needs > upper


def test_changed_thresholds_reset_memory_to_lower():
    """Deadband Activation: new thresholds reset the memory to the (new) lower threshold."""
    s = selector()
    s.from_angular_velocity_magnitude(2.0)  # target = upper = 8
    s.configure(MAX, 9.0, 5.5)
    assert s.rotation_target == 5.5
    assert s.from_angular_velocity_magnitude(6.0) == Strategy.BDOT


def test_nan_selects_idle_and_changes_nothing():
    """Deadband Activation: a NaN rate selects IDLE without touching the memory."""
    s = selector()
    s.from_angular_velocity_magnitude(9.0)
    before = s.rotation_target
    assert s.from_angular_velocity_magnitude(math.nan) == Strategy.IDLE
    assert s.rotation_target == before


def test_unconfigured_selector_is_idle():
    """Deadband Activation: before configure every decision is IDLE."""
    s = StrategySelector()
    assert s.from_angular_velocity_magnitude(100.0) == Strategy.IDLE


def test_strategy_values_match_fprime_enum():
    """B-Dot Strategy: helper values are the Components.DetumbleStrategy values."""
    from detumble.components.types import DetumbleStrategy
    assert [int(s) for s in Strategy] == [int(s) for s in DetumbleStrategy]
    assert [s.name for s in Strategy] == [s.name for s in DetumbleStrategy]


@given(st.lists(st.floats(min_value=0.0, max_value=2000.0), min_size=1, max_size=60))
def test_no_switching_inside_the_band(rates):
    """Deadband Activation (property): the decision changes IDLE→BDOT only at ≥ upper and
    BDOT→IDLE only below lower; never both ways on a rate strictly inside the band."""
    s = selector()
    previous = None
    for w in rates:
        got = s.from_angular_velocity_magnitude(w)
        if w >= MAX:
            assert got == Strategy.HYSTERESIS
        elif w < LOWER:
            assert got == Strategy.IDLE
        elif w >= UPPER:
            assert got == Strategy.BDOT
        elif previous in (Strategy.IDLE,):
            assert got == Strategy.IDLE  # inside the band after idling: stay idle
        elif previous == Strategy.BDOT:
            assert got == Strategy.BDOT  # inside the band while detumbling: keep going
        if got != Strategy.HYSTERESIS:
            previous = got
