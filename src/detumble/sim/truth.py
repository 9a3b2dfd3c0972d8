"""What an ADCS engineer logs: the truth columns shared by ``rate.csv`` (sim) and ``truth.csv`` (run).

:func:`adcs_header` names the columns for a plant (the wheel columns depend on its wheel count),
:func:`adcs_row` gives their values now. Evaluated only when a row is written (1 Hz by default),
never on the per-tick path. Units are in the names:

==============================  ===========================================================
``q0 q1 q2 q3``                 ``q_BN``, scalar first
``qo0 qo1 qo2 qo3``             ``q_BO``: attitude relative to the orbit frame (z nadir, y −orbit normal)
``wo_x_deg_s`` …                ``omega_BO_B``: body rate relative to O, in B (seed 004 eq. 14)
``pointing_error_deg``          angle to the controller's target (``Plant.set_pointing_target``); empty without one
``b_x_uT`` …                    true geomagnetic field in B (optional: ``truth.csv`` has its own)
``mcmd_x_Am2`` …                commanded dipole (the last request, or what the levels give once settled)
``m_x_Am2`` …                   achieved actuator dipole (after limits and the L/R lag), B
``tmag_x_Nm`` …                 magnetic torque ``(m + m_residual) x b_B``
``tgg_x_Nm`` …                  gravity-gradient torque
``trw_x_Nm`` …                  torque of the wheel motors on the body, ``-sum u_i g_i``
``h<i>_Nms speed<i>_rad_s u<i>_Nm``  per wheel: momentum, speed relative to the body, motor torque
==============================  ===========================================================
"""

from __future__ import annotations

import math

from detumble.sim.vec import cross

_AX = ("x", "y", "z")


def adcs_header(plant, with_field: bool = True) -> list[str]:
    cols = ["q0", "q1", "q2", "q3", "qo0", "qo1", "qo2", "qo3"]
    cols += [f"wo_{a}_deg_s" for a in _AX] + ["pointing_error_deg"]
    if with_field:
        cols += [f"b_{a}_uT" for a in _AX]
    for prefix, unit in (("mcmd", "Am2"), ("m", "Am2"), ("tmag", "Nm"), ("tgg", "Nm"), ("trw", "Nm")):
        cols += [f"{prefix}_{a}_{unit}" for a in _AX]
    for i in range(plant.wheel_count):
        cols += [f"h{i}_Nms", f"speed{i}_rad_s", f"u{i}_Nm"]
    return cols


def adcs_row(plant, with_field: bool = True, sample=None) -> list:
    """The columns' values now. ``sample``: the ``TruthSample`` just taken of this plant's present
    state (``SimulatedSpacecraft.truth``, a truth trace's callback argument), whose attitude, the
    attitude relative to the orbit frame, rate relative to it, pointing error, field in B and the
    commanded and achieved dipoles are then taken as computed there (the same floats: the same plant
    state, the same functions) instead of a second time; a sample of another instant is ignored."""
    if sample is not None and sample.t_s == plant.t_ns * 1e-9:
        q = sample.q_BN
        qo = sample.q_BO
        wo = sample.omega_BO_B
        err = sample.pointing_error_rad
        b = sample.b_B
        m = sample.m_coils_B
        mcmd = sample.m_commanded_B
    else:
        q = plant.q_BN
        qo = plant.q_BO
        wo = plant.omega_BO_B
        err = plant.pointing_error_rad()
        b = plant.b_B
        m = plant.m_coils_B
        mcmd = plant.m_commanded_B
    degrees = math.degrees
    row: list = [q[0], q[1], q[2], q[3], qo[0], qo[1], qo[2], qo[3], degrees(wo[0]), degrees(wo[1]),
                 degrees(wo[2]), "" if err is None else degrees(err)]
    if with_field:
        row += (b[0] * 1e6, b[1] * 1e6, b[2] * 1e6)
    res = plant.residual_dipole_B
    t_mag = cross((m[0] + res[0], m[1] + res[1], m[2] + res[2]), b)
    row += (*mcmd, *m, *t_mag, *plant.gravity_gradient_torque_B(), *plant.wheel_torque_on_body_B())
    if plant.wheel_count:
        for h, w, u in zip(plant.wheel_momenta, plant.wheel_speeds_rad_s, plant.wheel_torques_nm, strict=True):
            row += (h, w, u)
    return row
