"""Basilisk's equivalent of the coursework deployment as shipped (issue #19): seed 004's wheel law.

``deployments/coursework`` flies WHEELS_PD from its start-up sequence: the ``surrey`` scenario's
isotropic 1U (J = 1.77e-3 kg·m², rotors included) from ω = (1, 2, 3) rad/s (214 °/s), three
±1 mN·m / ±0.1 N·m·s wheels, the report's eq. 26 at 100 Hz on ideal sensors, turning the body to
the orbit frame. Here, in Basilisk (the scenario read through
:func:`detumble.sim.scenario.load_scenario`, so both sides take the same numbers):

* dynamics every ``--step`` s (0.01 s, the scenario's): ``spacecraft`` hub (RK4) with the whole
  inertia, point-mass Earth of the scenario's μ on its 7000 km circular orbit (the plant's own
  position and velocity at t = 0), three ``reactionWheelStateEffector`` wheels (BalancedWheels; the
  scenario's axes, J_s, torque limit, Ω_max from the momentum limit; each starts at Ω = −g·ω so
  that its absolute momentum is 0, as the plant's), ``simpleNav`` without errors (the scenario's
  sensors are ideal);
* control every ``--control-period`` s (0.01 s): one Python ``SysModel`` running the project's
  :class:`detumble.control.coursework.WheelsPd` and ``limit_wheel_torque`` (the report's law has no
  Basilisk counterpart: ``mrpFeedback`` would fly a different law, the short way), with the orbit
  frame from ``simpleNav``'s position and velocity (what the deployment's OrbitEphemeris gives).

The field (constant in the orbit frame) and the rods are left out: WHEELS_PD commands no dipole, so
they put no torque on the body (the deployment still evaluates the field: it reads the
magnetometer every cycle). No gravity gradient (the scenario has none). Truth is recorded every
TRACE_INTERVAL_S. Run as ``python -m basilisk.coursework [--duration S]``; prints
one JSON line: simulated and wall seconds of the run proper and
:func:`basilisk.side_by_side.coursework_plausibility`'s figures.
"""
from __future__ import annotations

import argparse
import json
import time

from Basilisk.architecture import messaging, sysModel
from Basilisk.simulation import simpleNav, spacecraft
from Basilisk.utilities import SimulationBaseClass, macros, simIncludeGravBody

from detumble.components.coursework_controller import CourseworkController
from detumble.control import coursework as cw
from detumble.sim import frames
from detumble.sim.plant import build_orbit
from detumble.sim.scenario import load_scenario
from basilisk import side_by_side as case
from basilisk.parts import balanced_wheels, mrp, quat, schedule, wheel_momenta



def _q_bo(sigma_BN, r_N, v_N):
    """``q_BO`` (scalar first) from MRP σ_BN and the position and velocity in N."""
    q_on = frames.dcm_to_quat(frames.orbit_axes_N(tuple(r_N), tuple(v_N)))
    return frames.q_BO(quat(sigma_BN), q_on)


class ReportWheelLaw(sysModel.SysModel):
    """Eq. 26 with the report's limits, as the CourseworkController flies it (its default parameters)."""

    def __init__(self, axes, js):
        super().__init__()
        self.attInMsg = messaging.NavAttMsgReader()
        self.transInMsg = messaging.NavTransMsgReader()
        self.rwSpeedInMsg = messaging.RWSpeedMsgReader()
        self.rwCmdOutMsg = messaging.ArrayMotorTorqueMsg()
        defaults = CourseworkController("parameterDefaults")
        inertia = ((defaults.INERTIA_XX.value, 0.0, 0.0), (0.0, defaults.INERTIA_YY.value, 0.0),
                   (0.0, 0.0, defaults.INERTIA_ZZ.value))
        self.law = cw.WheelsPd(defaults.WHEEL_KP.value, defaults.WHEEL_KD.value, inertia,
                               cw.from_plant_quaternion((1.0, 0.0, 0.0, 0.0)))
        self.torque_limit = defaults.WHEEL_TORQUE_LIMIT.value
        self.momentum_limit = defaults.WHEEL_MOMENTUM_LIMIT.value
        self.axes = axes
        self.js = js

    def UpdateState(self, CurrentSimNanos):
        att = self.attInMsg()
        trans = self.transInMsg()
        w = att.omega_BN_B
        w_B = (w[0], w[1], w[2])
        r, v = trans.r_BN_N, trans.v_BN_N
        q = _q_bo(att.sigma_BN, r, v)
        self.law.n = frames.orbit_rate((r[0], r[1], r[2]), (v[0], v[1], v[2]))
        speeds = self.rwSpeedInMsg().wheelSpeeds
        h = tuple(js * (speeds[i] + sum(a * b for a, b in zip(axis, w_B, strict=True)))
                  for i, (js, axis) in enumerate(zip(self.js, self.axes, strict=True)))
        torque = self.law.torque(cw.from_plant_quaternion(q), w_B, h)
        torque = cw.limit_wheel_torque(torque, h, self.torque_limit, self.momentum_limit)
        rw = messaging.ArrayMotorTorqueMsgPayload()
        rw.motorTorque = list(torque)
        self.rwCmdOutMsg.write(rw, CurrentSimNanos, self.moduleID)


def run(duration_s: float, step_s: float | None = None, control_period_s: float | None = None) -> dict:
    s = load_scenario(case.COURSEWORK_SCENARIO)
    step_s = s.dynamics_step_s if step_s is None else step_s
    control_period_s = s.control.period_s if control_period_s is None else control_period_s
    sim = SimulationBaseClass.SimBaseClass()
    process = sim.CreateNewProcess("process")
    process.addTask(sim.CreateNewTask("dynamics", macros.sec2nano(step_s)), 100)
    process.addTask(sim.CreateNewTask("fsw", macros.sec2nano(control_period_s)), 50)

    orbit = build_orbit(s)
    r0, v0 = orbit.position_N(0.0), orbit.velocity_N(0.0)
    q0 = s.q_BN0
    if s.attitude_frame == "orbit":
        q0 = frames.q_BN_from_orbit(q0, frames.q_ON(orbit, 0.0))
    w0 = s.omega_BN_B0

    sc = spacecraft.Spacecraft()
    sc.ModelTag = "sc"
    sc.hub.mHub = s.spacecraft.mass_kg
    sc.hub.IHubPntBc_B = [list(row) for row in s.spacecraft.inertia_kg_m2]  # BalancedWheels: the whole
    sc.hub.r_CN_NInit = list(r0)
    sc.hub.v_CN_NInit = list(v0)
    sc.hub.sigma_BNInit = [[x] for x in mrp(q0)]
    sc.hub.omega_BN_BInit = [[x] for x in w0]
    gravity = simIncludeGravBody.gravBodyFactory()
    earth = gravity.createEarth()
    earth.isCentralBody = True
    earth.mu = s.orbit.mu_m3_s2
    gravity.addBodiesTo(sc)
    wheels = s.spacecraft.reaction_wheels
    _, rw_effector = balanced_wheels(sc, wheels, w0)
    nav = simpleNav.SimpleNav()
    nav.ModelTag = "nav"
    nav.scStateInMsg.subscribeTo(sc.scStateOutMsg)
    law = ReportWheelLaw([w.axis_B for w in wheels], [w.inertia_kg_m2 for w in wheels])
    law.ModelTag = "reportWheelLaw"
    law.attInMsg.subscribeTo(nav.attOutMsg)
    law.transInMsg.subscribeTo(nav.transOutMsg)
    law.rwSpeedInMsg.subscribeTo(rw_effector.rwSpeedOutMsg)
    rw_effector.rwMotorCmdInMsg.subscribeTo(law.rwCmdOutMsg)

    state_log, speed_log = schedule(sim, [sc, rw_effector, nav], [law], sc, rw_effector, case.TRACE_INTERVAL_S)
    sim.InitializeSimulation()
    sim.ConfigureStopTime(macros.sec2nano(duration_s))
    t0 = time.perf_counter()
    sim.ExecuteSimulation()
    wall = time.perf_counter() - t0

    trace = [(t * 1e-9, _q_bo(state_log.sigma_BN[k], state_log.r_BN_N[k], state_log.v_BN_N[k]),
              tuple(state_log.omega_BN_B[k]), wheel_momenta(wheels, speed_log.wheelSpeeds[k], state_log.omega_BN_B[k]))
             for k, t in enumerate(state_log.times())]
    return {"sim_seconds": duration_s, "step_s": step_s, "control": "python", "wall_s": wall,
            "real_time_factor": duration_s / wall, **case.coursework_plausibility(trace)}


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=600.0)
    parser.add_argument("--step", type=float, default=None, help="dynamics step, s (default: the scenario's)")
    parser.add_argument("--control-period", type=float, default=None, help="s (default: the scenario's)")
    args = parser.parse_args(argv)
    print(json.dumps(run(args.duration, args.step, args.control_period)))


if __name__ == "__main__":
    main()
