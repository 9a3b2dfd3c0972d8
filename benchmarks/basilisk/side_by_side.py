"""The cases flown side by side with Basilisk for the newer deployments (issue #19): their
definitions and their plausibility figures. One definition serves both sides, so that they fly the
same manoeuvre.

**adcs_ref pointing** (``deployments/adcs_ref``; Basilisk: :mod:`basilisk.adcs`):

* spacecraft, orbit, field, wheels and sensors: scenario ``adcs`` (``deployments/adcs_ref``) with
  :data:`SETTINGS` (a 0.5 °/s start, as ``docs/studies/attitude_modes.md``'s "pointing on the wheels"; and the
  centred tilted dipole of the scenario's degree-1 coefficients, the field Basilisk's side flies, where
  adcs_ref's own default is IGRF-14);
* the commands, at simulated times: :data:`FIRST_TARGET` (``q_TN``, scalar first: 45° about N's y
  axis, the deployment's own start-up target) at 0 s, POINTING forced at :data:`POINTING_AT_S`, and
  the study's 90° change of target, :data:`SECOND_TARGET`, at :data:`SECOND_TARGET_AT_S`.

:func:`plausibility` reduces a truth trace (time, ``q_BN``, wheel momenta) to the figures both
sides report: when each slew settles below :data:`SETTLED_DEG` for good, the final true error and
the largest wheel momentum.

**coursework wheels** (``deployments/coursework`` as shipped: its start-up sequence flies WHEELS_PD;
Basilisk: :mod:`basilisk.coursework`): scenario ``surrey``, the report's eq. 26 on
the wheels from 214 °/s to the orbit frame. :func:`coursework_plausibility` reduces a trace of
(time, ``q_BO``, ``ω_BN_B``, wheel momenta) to when the attitude to the orbit frame settles below
:data:`COURSEWORK_SETTLED_DEG` for good, the final error and rate and the largest wheel momentum.

Plain floats; no framework and no Basilisk import.
"""
from __future__ import annotations

import math
from typing import Iterable, Sequence

from detumble.control.quaternion import quat_angle, quat_error

__all__ = ["SCENARIO", "SETTINGS", "FIRST_TARGET", "SECOND_TARGET", "POINTING_AT_S", "SECOND_TARGET_AT_S",
           "SETTLED_DEG", "TRACE_INTERVAL_S", "sequence_text", "plant_only_settings", "target_at", "plausibility",
           "COURSEWORK_SCENARIO", "COURSEWORK_SETTLED_DEG", "coursework_plausibility"]

SCENARIO = "adcs"
#: the 0.5 °/s start; the centred tilted dipole Basilisk flies (magneticFieldCenteredDipole), not adcs_ref's IGRF-14
SETTINGS = ("initial.rate.magnitude_deg_s=0.5", "field.model=dipole")
FIRST_TARGET = (0.9238795325112867, 0.0, 0.3826834323650898, 0.0)
SECOND_TARGET = (0.6532814824381883, 0.6532814824381882, 0.2705980500730985, -0.2705980500730985)
POINTING_AT_S = 5.0
SECOND_TARGET_AT_S = 300.0
SETTLED_DEG = 0.1
TRACE_INTERVAL_S = 1.0  #: both sides sample their truth at this interval (s)

_CONTROLLER = "ReferenceDeployment.attitudeController"


def sequence_text() -> str:
    """The start-up sequence the deployment flies (relative times: each after the previous)."""
    q1 = " ".join(repr(c) for c in FIRST_TARGET)
    q2 = " ".join(repr(c) for c in SECOND_TARGET)
    wait = SECOND_TARGET_AT_S - POINTING_AT_S
    return (f"; issue #19's pointing case (basilisk.side_by_side)\n"
            f"R00:00:00 {_CONTROLLER}.SET_TARGET_QUATERNION {q1}\n"
            f"R00:00:{POINTING_AT_S:02.0f} {_CONTROLLER}.FORCE_MODE POINTING\n"
            f"R00:{int(wait // 60):02d}:{wait % 60:02.0f} {_CONTROLLER}.SET_TARGET_QUATERNION {q2}\n")


def plant_only_settings() -> list[str]:
    """The scenario settings that fly the same case on the plant-only ``adcs`` law (``fprime-lite sim adcs --law
    adcs --set ...``): the start, and the sequence's commands as ``control.adcs`` keys — the same flight to the
    last bit (ADCS-078)."""
    second = ", ".join(repr(c) for c in SECOND_TARGET)
    return [*SETTINGS, "control.adcs.force_mode=POINTING", f"control.adcs.force_at_s={POINTING_AT_S!r}",
            f"control.adcs.target_q_bn={list(FIRST_TARGET)!r}",
            f"control.adcs.target_changes=[[{SECOND_TARGET_AT_S!r}, {second}]]"]


def _quat(q: Sequence[float]) -> tuple[float, float, float, float]:
    return (float(q[0]), float(q[1]), float(q[2]), float(q[3]))


def target_at(t_s: float):
    """The target ``q_TN`` in force at simulated time ``t_s``."""
    return FIRST_TARGET if t_s < SECOND_TARGET_AT_S else SECOND_TARGET


def _settle(samples: Sequence[tuple[float, float]], start_s: float, limit_deg: float = SETTLED_DEG) -> float | None:
    """Seconds from ``start_s`` to the first sample after which every error stays below ``limit_deg``."""
    settled_at = None
    for t, err in samples:
        if err >= limit_deg:
            settled_at = None
        elif settled_at is None:
            settled_at = t
    return None if settled_at is None else settled_at - start_s


def plausibility(trace: Iterable[tuple[float, Sequence[float], Sequence[float]]]) -> dict:
    """Figures of a truth trace of ``(t_s, q_BN, wheel momenta N·m·s)`` rows.

    ``slew1_settle_s``: from POINTING_AT_S until the true error to FIRST_TARGET is below SETTLED_DEG
    for good (before SECOND_TARGET_AT_S); ``slew2_settle_s`` likewise from SECOND_TARGET_AT_S (None
    when the run ends before it, or it never settles); ``final_error_deg``; ``max_wheel_momentum_nms``
    (largest |h_i| over the run).
    """
    first: list[tuple[float, float]] = []
    second: list[tuple[float, float]] = []
    h_max = 0.0
    last_err = None
    for t, q, h in trace:
        err = math.degrees(quat_angle(quat_error(target_at(t), _quat(q))))
        last_err = err
        if t >= POINTING_AT_S:
            (first if t < SECOND_TARGET_AT_S else second).append((t, err))
        for x in h:
            h_max = max(h_max, abs(x))
    return {"slew1_settle_s": _settle(first, POINTING_AT_S) if first else None,
            "slew2_settle_s": _settle(second, SECOND_TARGET_AT_S) if second else None,
            "final_error_deg": last_err, "max_wheel_momentum_nms": h_max}


COURSEWORK_SCENARIO = "surrey"
COURSEWORK_SETTLED_DEG = 1.0


def coursework_plausibility(trace: Iterable[tuple[float, Sequence[float], Sequence[float], Sequence[float]]],
                            target_q_bo: Sequence[float] = (1.0, 0.0, 0.0, 0.0)) -> dict:
    """Figures of a trace of ``(t_s, q_BO, ω_BN_B rad/s, wheel momenta N·m·s)`` rows: ``settle_s`` (the
    attitude to the orbit frame within COURSEWORK_SETTLED_DEG of ``target_q_bo`` for good, from t = 0),
    ``final_error_deg``, ``final_rate_deg_s`` and ``max_wheel_momentum_nms``."""
    errors: list[tuple[float, float]] = []
    h_max = 0.0
    rate = None
    target = _quat(target_q_bo)
    for t, q, w, h in trace:
        errors.append((t, math.degrees(quat_angle(quat_error(target, _quat(q))))))
        rate = math.degrees(math.sqrt(w[0] ** 2 + w[1] ** 2 + w[2] ** 2))
        for x in h:
            h_max = max(h_max, abs(x))
    return {"settle_s": _settle(errors, 0.0, COURSEWORK_SETTLED_DEG) if errors else None,
            "final_error_deg": errors[-1][1] if errors else None, "final_rate_deg_s": rate,
            "max_wheel_momentum_nms": h_max}
