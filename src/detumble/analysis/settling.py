"""Settling-time and detumble-time metrics: the one module every summary, campaign and test uses.

Three definitions, because they answer different questions:

* :func:`settling_time` — seed 004's definition, MATLAB ``lsiminfo(y, t, yfinal, yinit)``: the
  first sample time T after which ``|y(t) − y_final| ≤ threshold · |y_final − y_init|`` holds for
  every later sample (default threshold 2 %). With ``y_final`` given explicitly (the report gives
  ``[0, −n, 0]`` for ω and ``±1`` for the quaternion's real part) it does not depend on the horizon;
  with ``y_final=None`` the last sample is used, as ``lsiminfo`` does by default — and then the
  figure moves with the length of the run (:func:`settling_time` documents both).
* :func:`transient_time` — ``lsiminfo``'s TransientTime: the band is 2 % of the peak error.
* :func:`time_below` — the horizon-free detumble metric the rest of the project uses: the first
  time after which a magnitude (|ω|, in the caller's unit) stays below a threshold.
* :func:`envelope_settling_time` — the settling time of a rippled decay read off its envelope (the line
  through the peaks of ``|y − y_final|``, :func:`ripple_peaks`) instead of the signal: where the ripple's
  last peak above the band lies within a hair of it, ``lsiminfo``'s figure jumps by one ripple period when
  that peak's height crosses the band; the envelope's crossing moves only as much as the peaks do.

A series that never settles gives ``None``. Times in seconds, values in the caller's units.
"""
from __future__ import annotations

from typing import Sequence

import numpy as np

__all__ = ["settling_time", "transient_time", "time_below", "settling_times_per_axis", "ripple_peaks",
           "envelope_settling_time", "SettlingTracker", "BelowTracker", "DEFAULT_BAND"]

#: The report's band: 2 % (MATLAB's default SettlingTimeThreshold).
DEFAULT_BAND = 0.02


def _first_time_after_last(t: np.ndarray, violating: np.ndarray) -> float | None:
    """The first sample time after the last violating sample (t[0] if none violates)."""
    if not violating.any():
        return float(t[0])
    last = int(np.flatnonzero(violating)[-1])
    return None if last + 1 >= len(t) else float(t[last + 1])


def settling_time(t: Sequence[float], y: Sequence[float], y_final: float | None = None,
                  y_init: float | None = None, band: float = DEFAULT_BAND) -> float | None:
    """``lsiminfo``'s SettlingTime of one channel.

    ``y_final`` defaults to the last sample, ``y_init`` to 0 (``lsiminfo``'s defaults); the band
    is ``band · |y_final − y_init|``. None when the last sample is outside the band.
    """
    tt = np.asarray(t, dtype=float)
    yy = np.asarray(y, dtype=float)
    if tt.shape != yy.shape or tt.ndim != 1 or len(tt) == 0:
        raise ValueError("t and y must be 1-D sequences of the same, non-zero length")
    final = float(yy[-1]) if y_final is None else float(y_final)
    initial = 0.0 if y_init is None else float(y_init)
    width = band * abs(final - initial)
    return _first_time_after_last(tt, np.abs(yy - final) > width)


def transient_time(t: Sequence[float], y: Sequence[float], y_final: float | None = None,
                   band: float = DEFAULT_BAND) -> float | None:
    """``lsiminfo``'s TransientTime: the band is ``band`` times the peak error ``max |y − y_final|``."""
    tt = np.asarray(t, dtype=float)
    yy = np.asarray(y, dtype=float)
    final = float(yy[-1]) if y_final is None else float(y_final)
    error = np.abs(yy - final)
    return _first_time_after_last(tt, error > band * float(error.max()))


def settling_times_per_axis(t: Sequence[float], ys: Sequence[Sequence[float]],
                            y_finals: Sequence[float | None], y_inits: Sequence[float | None],
                            band: float = DEFAULT_BAND) -> tuple[list[float | None], float | None]:
    """Settling time of each channel and the overall figure (the largest; None if any never settles)."""
    each = [settling_time(t, y, f, i, band) for y, f, i in zip(ys, y_finals, y_inits, strict=True)]
    settled = [x for x in each if x is not None]
    overall = max(settled) if len(settled) == len(each) else None
    return each, overall


def time_below(t: Sequence[float], magnitude: Sequence[float], threshold: float) -> float | None:
    """First time after which ``magnitude`` stays strictly below ``threshold`` (None if it never does)."""
    tt = np.asarray(t, dtype=float)
    mm = np.asarray(magnitude, dtype=float)
    return _first_time_after_last(tt, ~(mm < threshold))


def ripple_peaks(t: Sequence[float], y: Sequence[float], y_final: float) -> list[tuple[float, float]]:
    """The local maxima of ``|y − y_final|``: ``[(time, height)]`` in time order, each refined by the parabola
    through the sample and its two neighbours (a peak on the first or last sample is not one)."""
    tt = np.asarray(t, dtype=float)
    e = np.abs(np.asarray(y, dtype=float) - float(y_final))
    if tt.shape != e.shape or tt.ndim != 1:
        raise ValueError("t and y must be 1-D sequences of the same length")
    inner = np.flatnonzero((e[1:-1] > e[:-2]) & (e[1:-1] >= e[2:])) + 1
    peaks = []
    for i in inner:
        a, b, c = e[i - 1], e[i], e[i + 1]
        curvature = a - 2.0 * b + c
        shift = 0.5 * (a - c) / curvature if curvature < 0.0 else 0.0  # in samples, within ±0.5
        step = 0.5 * (tt[i + 1] - tt[i - 1])
        peaks.append((float(tt[i] + shift * step), float(b - 0.25 * (a - c) * shift)))
    return peaks


def envelope_settling_time(t: Sequence[float], y: Sequence[float], y_final: float, y_init: float,
                           band: float = DEFAULT_BAND) -> float | None:
    """The time the envelope of ``|y − y_final|`` last falls through the band ``band · |y_final − y_init|``.

    The envelope is the straight line between successive :func:`ripple_peaks`; the figure is where it crosses
    the band between the last peak above the band and the next one (None when there is no peak after it). A
    signal with no peak above the band settles as :func:`settling_time` says. Same units as ``t``.
    """
    width = band * abs(float(y_final) - float(y_init))
    peaks = ripple_peaks(t, y, y_final)
    above = [k for k, (_, h) in enumerate(peaks) if h > width]
    if not above:
        return settling_time(t, y, y_final, y_init, band)
    k = above[-1]
    if k + 1 >= len(peaks):
        return None
    (t0, h0), (t1, h1) = peaks[k], peaks[k + 1]
    return t0 + (h0 - width) / (h0 - h1) * (t1 - t0)


class SettlingTracker:
    """:func:`settling_time` computed on line, sample by sample, for a known ``y_final``: O(1)
    memory, so a plant-only run can measure it at every control period of a long run.

    ``time`` is the settling time of the samples seen so far (None while the latest sample is
    outside the band) — the same figure :func:`settling_time` gives for the whole series.
    """

    __slots__ = ("y_final", "width", "_next_is_candidate", "time")

    def __init__(self, y_final: float, y_init: float, band: float = DEFAULT_BAND):
        self.y_final = float(y_final)
        self.width = band * abs(self.y_final - float(y_init))
        self._next_is_candidate = True
        self.time: float | None = None

    def update(self, t: float, y: float) -> None:
        if abs(y - self.y_final) > self.width:
            self._next_is_candidate = True
            self.time = None
        elif self._next_is_candidate:
            self._next_is_candidate = False
            self.time = t


class BelowTracker:
    """:func:`time_below` on line: the first time after which a magnitude stays below ``threshold``."""

    __slots__ = ("threshold", "time")

    def __init__(self, threshold: float):
        self.threshold = threshold
        self.time: float | None = None

    def update(self, t: float, magnitude: float) -> None:
        if not magnitude < self.threshold:
            self.time = None
        elif self.time is None:
            self.time = t
