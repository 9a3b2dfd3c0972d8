"""The settling figures of a plant-only run, measured on line at every control period.

Seed 004's definition (:mod:`detumble.analysis.settling`): each body-rate axis settles when it
stays within 2 % of its step ``|ω_final − ω(0)|`` of its final value. The final value is the
controllers' goal: the coursework's synchronous rotation ``ω = [0, −n, 0]`` for its three laws, a
body at rest for the detumble laws. For the wheel law the attitude is included, as the report
does: the real part of ``q_BO`` settles within 2 % of its full range (from −1 to +1: a band of
0.04) of +1. The overall figure is the largest. The horizon-free figure is the time after which
|ω − ω_final| stays below ``threshold_deg_s``.
"""
from __future__ import annotations

import math

from detumble.analysis.settling import DEFAULT_BAND, BelowTracker, SettlingTracker

__all__ = ["SettlingMetrics", "COURSEWORK_LAWS"]

#: Laws whose goal is the coursework's synchronous rotation (ω_final = [0, −n, 0]).
COURSEWORK_LAWS = ("cross_product", "beta_pd", "wheels_pd")


class SettlingMetrics:
    """Settling trackers for one plant; call :meth:`update` once per control period."""

    def __init__(self, plant, *, omega_final, include_attitude: bool = False, threshold_deg_s: float = 1.0,
                 band: float = DEFAULT_BAND):
        w0 = plant.omega_BN_B
        self.omega_final = tuple(float(x) for x in omega_final)
        self.axes = [SettlingTracker(self.omega_final[i], w0[i], band) for i in range(3)]
        self.attitude = SettlingTracker(1.0, -1.0, band) if include_attitude else None
        self.threshold_deg_s = threshold_deg_s
        self.below = BelowTracker(math.radians(threshold_deg_s))
        self.update(plant)

    def update(self, plant, q_BO=None) -> None:
        """Feed the plant's present state; ``q_BO``: its attitude relative to the orbit frame when
        already computed for this instant (a ``TruthSample``'s), else read from the plant."""
        t = plant.t
        w = plant.omega_BN_B
        f = self.omega_final
        axes = self.axes
        axes[0].update(t, w[0])
        axes[1].update(t, w[1])
        axes[2].update(t, w[2])
        if self.attitude is not None:
            self.attitude.update(t, (plant.q_BO if q_BO is None else q_BO)[0])
        dx, dy, dz = w[0] - f[0], w[1] - f[1], w[2] - f[2]
        self.below.update(t, math.sqrt(dx * dx + dy * dy + dz * dz))

    def summary(self) -> dict:
        axes = [a.time for a in self.axes]
        channels = axes + ([self.attitude.time] if self.attitude is not None else [])
        settled = [x for x in channels if x is not None]
        overall = max(settled) if len(settled) == len(channels) else None
        out = {
            "settling_time_2pct_s": overall,
            "settling_time_2pct_axes_s": axes,
            "settling_omega_final_rad_s": list(self.omega_final),
            "time_below_threshold_s": self.below.time,
            "time_below_threshold_deg_s": self.threshold_deg_s,
        }
        if self.attitude is not None:
            out["settling_time_2pct_attitude_s"] = self.attitude.time
        return out
