"""Detumble strategy from the angular-rate magnitude: a deadband with memory (detumble.md §4).

Plain Python (no framework import). All thresholds and rates are in **deg/s**.

Detumbling starts only above the deadband's *upper* threshold and, once started, continues down to
the *lower* threshold (seed requirement "Deadband Activation"); above ``bdot_max_threshold`` the
hysteresis (bang-bang) strategy is used because B-dot cannot follow such fast rotation.

The memory (``rotation_target``) starts at the lower threshold and is reset to it only when the
thresholds change, so calling :meth:`StrategySelector.configure` with the same values before every
decision (as the component does) keeps the memory. (DEVIATION from the flight code, whose
configure always reset the memory and so defeated the deadband.)
"""

from __future__ import annotations

import enum

__all__ = ["Strategy", "StrategySelector"]


class Strategy(enum.IntEnum):
    """Numeric values match ``Components.DetumbleStrategy``."""

    IDLE = 0
    BDOT = 1
    HYSTERESIS = 2


class StrategySelector:
    """Chooses IDLE, BDOT or HYSTERESIS from |ω| (deg/s).

    Unconfigured, every threshold is NaN and every decision is IDLE.
    """

    def __init__(self) -> None:
        nan = float("nan")
        self.bdot_max_threshold = nan
        self.deadband_upper_threshold = nan
        self.deadband_lower_threshold = nan
        self.rotation_target = nan

    def configure(self, bdot_max_threshold: float, deadband_upper_threshold: float,
                  deadband_lower_threshold: float) -> None:
        """Store the thresholds (deg/s). The memory is reset to the lower threshold only when a
        threshold differs from the stored one."""
        new = (float(bdot_max_threshold), float(deadband_upper_threshold), float(deadband_lower_threshold))
        old = (self.bdot_max_threshold, self.deadband_upper_threshold, self.deadband_lower_threshold)
        if new == old:  # NaN never compares equal, so NaN thresholds always count as changed
            return
        self.bdot_max_threshold, self.deadband_upper_threshold, self.deadband_lower_threshold = new
        self.rotation_target = self.deadband_lower_threshold

    def from_angular_velocity_magnitude(self, angular_velocity_magnitude_deg_sec: float) -> Strategy:
        """The strategy for |ω| = ``angular_velocity_magnitude_deg_sec`` (deg/s).

        Checks, in order: below the lower threshold → IDLE (and re-arm at the upper threshold);
        at or above the B-dot maximum → HYSTERESIS; at or above the current target → BDOT (and keep
        going down to the lower threshold); otherwise IDLE (inside the deadband). A NaN rate
        selects IDLE and changes nothing.
        """
        w = angular_velocity_magnitude_deg_sec
        if w < self.deadband_lower_threshold:
            self.rotation_target = self.deadband_upper_threshold
            return Strategy.IDLE
        if w >= self.bdot_max_threshold:
            return Strategy.HYSTERESIS
        if w >= self.rotation_target:
            self.rotation_target = self.deadband_lower_threshold
            return Strategy.BDOT
        return Strategy.IDLE

    #: Short name used by detumble.md §4.
    select = from_angular_velocity_magnitude
