"""Basilisk's equivalent of the adcs_ref pointing case (issue #19), written with Basilisk's own modules.

The manoeuvre, spacecraft and environment are :mod:`basilisk.side_by_side`'s (scenario
``adcs``, read through :func:`detumble.sim.scenario.load_scenario`, so both sides take the same
numbers). Two Basilisk tasks:

* dynamics, every ``--step`` s (0.02 s, the deployment's 50 Hz): ``spacecraft`` hub (RK4; mass and
  the scenario's inertia, the wheels' own contribution taken off the hub so that the total is the
  scenario's), point-mass Earth, ``GravityGradientEffector``, three ``reactionWheelStateEffector``
  wheels (BalancedWheels; the scenario's axes, J_s, torque limit and, as Ω_max, the momentum limit),
  ``magneticFieldCenteredDipole`` with the scenario's IGRF-2025 degree-1 coefficients, turned with
  the Earth from the scenario's Earth angle by ``planetEphemeris``, ``MtbEffector`` (three ideal
  rods with the controller's per-axis dipole limits), ``simpleNav`` (attitude and rate with the
  star tracker's and the gyro's 1σ as Gauss-Markov errors);
* flight software, every ``--control-period`` s (0.1 s, the AttitudeController's 10 Hz cycle).

``--control c`` (default): Basilisk's C modules: ``inertial3D`` → ``attTrackingError`` →
``mrpFeedback`` (K = 2 K_P, P = K_D: the same small-angle stiffness and damping as the quaternion
PD; no integral, no slew-rate limit); momentum dumping ``magnetometer`` → ``tamComm`` →
``mtbMomentumManagementSimple`` (K_DUMP) → ``torque2Dipole`` → ``dipoleMapping`` → the rods, and
``mtbFeedforward`` taking the rods' expected torque off the wheels' request; ``rwMotorTorque`` to
the wheels. This is the fastest Basilisk can fly the case, every law in C.

``--control python``: one Python ``SysModel`` running the project's own laws
(:mod:`detumble.control`: the quaternion PD with its slew-rate limit and integral, wheel allocation
with limits, magnetic dumping with the coil-weighted projection and its feed-forward) on
``simpleNav``'s output and the magnetometer, as a Basilisk user would add a law of their own.

The control task is disabled until POINTING_AT_S and the second target is set at
SECOND_TARGET_AT_S, between ``ExecuteSimulation`` calls. Truth (attitude, wheel speeds) is recorded
every TRACE_INTERVAL_S. Run as ``python -m basilisk.adcs [--duration S] [--step S]
[--control c|python]``; prints one JSON line: simulated and wall seconds of the run proper (set-up
excluded) and :func:`basilisk.side_by_side.plausibility`'s figures.
"""
from __future__ import annotations

import argparse
import json
import math
import time

from Basilisk.architecture import messaging, sysModel
from Basilisk.fswAlgorithms import (attTrackingError, dipoleMapping, inertial3D, mrpFeedback, mtbFeedforward,
                                    mtbMomentumManagementSimple, rwMotorTorque, tamComm, torque2Dipole)
from Basilisk.simulation import (GravityGradientEffector, MtbEffector, magneticFieldCenteredDipole, magnetometer,
                                 simpleNav, spacecraft)
from Basilisk.utilities import SimulationBaseClass, macros, orbitalMotion, simIncludeGravBody

from detumble.components.attitude_controller import AttitudeController
from detumble.control.magnetic import dump_torque, project_dipole_weighted, scale_to_limits
from detumble.control.pointing import ErrorIntegrator, pd_torque
from detumble.control.wheel_allocation import WheelAllocator
from detumble.sim.scenario import load_scenario
from basilisk import side_by_side as case
from basilisk.parts import balanced_wheels, mrp, quat, rotating_earth, schedule, wheel_momenta

_ARCSEC = math.pi / 180.0 / 3600.0


_DEFAULTS: AttitudeController | None = None


def _param(name: str) -> float:
    """The AttitudeController's default of parameter ``name`` (the deployment flies the defaults)."""
    global _DEFAULTS
    if _DEFAULTS is None:
        _DEFAULTS = AttitudeController("parameterDefaults")
    return float(getattr(_DEFAULTS, name).value)


def _coil_limits() -> tuple[float, float, float]:
    """A·m² per body axis: two X and two Y coils, one Z− coil (the controller's own limits)."""
    return (2.0 * _param("X_COIL_MAX_DIPOLE"), 2.0 * _param("Y_COIL_MAX_DIPOLE"), _param("Z_COIL_MAX_DIPOLE"))


class ProjectPointing(sysModel.SysModel):
    """The AttitudeController's POINTING on the wheels, in one Python module (``--control python``).

    Reads ``simpleNav`` (σ_BN, ω_BN_B), the wheels' speeds and the body-frame magnetometer; writes
    the wheels' motor torques and the rods' dipoles. The laws are :mod:`detumble.control`'s, with the
    controller's default parameters; the rods drive all of the cycle (no sensing tick: no coupling
    into the magnetometer is modelled on this side).
    """

    def __init__(self, axes, js, period_s: float):
        super().__init__()
        self.navInMsg = messaging.NavAttMsgReader()
        self.rwSpeedInMsg = messaging.RWSpeedMsgReader()
        self.tamInMsg = messaging.TAMSensorBodyMsgReader()
        self.rwCmdOutMsg = messaging.ArrayMotorTorqueMsg()
        self.mtbCmdOutMsg = messaging.MTBCmdMsg()
        self.axes = tuple(tuple(a) for a in axes)
        self.js = js
        self.dt = period_s
        self.target = case.FIRST_TARGET
        self.kp, self.kd, self.ki = _param("K_P"), _param("K_D"), _param("K_I")
        self.rate_limit = math.radians(_param("SLEW_RATE_LIMIT"))
        self.k_dump = _param("K_DUMP")
        self.limits = _coil_limits()
        self.integrator = ErrorIntegrator(math.radians(_param("INTEGRAL_WINDOW")), 1.0e-5,
                                          math.radians(_param("INTEGRAL_RATE_GATE")))
        self.allocator = WheelAllocator(self.axes, _param("WHEEL_MAX_TORQUE"), _param("WHEEL_MAX_MOMENTUM"))
        self.body_momentum = WheelAllocator(self.axes, 1.0, 1.0).body_momentum

    def set_target(self, q) -> None:
        self.target = q
        self.integrator.reset()

    def Reset(self, CurrentSimNanos):
        self.integrator.reset()

    def UpdateState(self, CurrentSimNanos):
        nav = self.navInMsg()
        q = quat(nav.sigma_BN)
        w = nav.omega_BN_B
        omega = (w[0], w[1], w[2])
        tau, qe = pd_torque(self.target, q, omega, self.kp, self.kd, self.rate_limit)
        ti = self.integrator.update(qe, self.dt, self.ki, omega)  # inertial targets: the reference does not turn
        speeds = self.rwSpeedInMsg().wheelSpeeds
        momenta = tuple(self.js[i] * (speeds[i] + sum(a * b for a, b in zip(self.axes[i], omega, strict=True)))
                        for i in range(len(self.axes)))
        b = self.tamInMsg().tam_B
        b = (b[0], b[1], b[2])
        dipole = (0.0, 0.0, 0.0)
        tau_mag = (0.0, 0.0, 0.0)
        if b[0] != 0.0 or b[1] != 0.0 or b[2] != 0.0:
            dipole, _ = project_dipole_weighted(dump_torque(self.body_momentum(momenta), self.k_dump), b, self.limits)
            dipole = scale_to_limits(dipole, self.limits)
            tau_mag = (dipole[1] * b[2] - dipole[2] * b[1], dipole[2] * b[0] - dipole[0] * b[2],
                       dipole[0] * b[1] - dipole[1] * b[0])
        u, _ = self.allocator.allocate((tau[0] + ti[0] - tau_mag[0], tau[1] + ti[1] - tau_mag[1],
                                        tau[2] + ti[2] - tau_mag[2]), momenta)
        rw = messaging.ArrayMotorTorqueMsgPayload()
        rw.motorTorque = list(u)
        self.rwCmdOutMsg.write(rw, CurrentSimNanos, self.moduleID)
        mtb = messaging.MTBCmdMsgPayload()
        mtb.mtbDipoleCmds = list(dipole)
        self.mtbCmdOutMsg.write(mtb, CurrentSimNanos, self.moduleID)


def run(duration_s: float, step_s: float = 0.02, control: str = "c", control_period_s: float = 0.1) -> dict:
    if control not in ("c", "python"):
        raise ValueError(f"control must be 'c' or 'python', got {control!r}")
    s = load_scenario(case.SCENARIO, settings=list(case.SETTINGS))
    sim = SimulationBaseClass.SimBaseClass()
    process = sim.CreateNewProcess("process")
    process.addTask(sim.CreateNewTask("dynamics", macros.sec2nano(step_s)), 100)
    process.addTask(sim.CreateNewTask("fsw", macros.sec2nano(control_period_s)), 50)

    # --- spacecraft, gravity, wheels ---------------------------------------------------------------
    sc = spacecraft.Spacecraft()
    sc.ModelTag = "sc"
    sc.hub.mHub = s.spacecraft.mass_kg
    wheels = s.spacecraft.reaction_wheels
    # BalancedWheels add nothing to the mass properties (Basilisk takes them as part of the hub) and
    # carry only the spin momentum J_s Ω: the hub's inertia is the scenario's whole one (wheels
    # included), whose angular momentum J ω + Σ J_s Ω_i g_i is the plant's I ω + Σ h_i g_i.
    sc.hub.IHubPntBc_B = [list(row) for row in s.spacecraft.inertia_kg_m2]
    gravity = simIncludeGravBody.gravBodyFactory()
    earth = gravity.createEarth()
    earth.isCentralBody = True
    earth.mu = s.orbit.mu_m3_s2
    gravity.addBodiesTo(sc)
    oe = orbitalMotion.ClassicElements()
    oe.a, oe.e = s.orbit.earth_radius_m + s.orbit.altitude_km * 1e3, 0.0
    oe.i, oe.Omega = math.radians(s.orbit.inclination_deg), math.radians(s.orbit.raan_deg)
    oe.omega, oe.f = 0.0, math.radians(s.orbit.arg_latitude_deg)
    r_N, v_N = orbitalMotion.elem2rv(s.orbit.mu_m3_s2, oe)
    sc.hub.r_CN_NInit = r_N
    sc.hub.v_CN_NInit = v_N
    sc.hub.sigma_BNInit = [[x] for x in mrp(s.q_BN0)]
    sc.hub.omega_BN_BInit = [[x] for x in s.omega_BN_B0]
    factory, rw_effector = balanced_wheels(sc, wheels, s.omega_BN_B0)
    gg = GravityGradientEffector.GravityGradientEffector()
    gg.ModelTag = "gravityGradient"
    gg.addPlanetName(earth.planetName)
    sc.addDynamicEffector(gg)

    # --- the Earth's rotation and its field ------------------------------------------------------
    ephemeris = rotating_earth(s.earth_angle0_rad, s.field.earth_rotation_rate_rad_s)
    field = magneticFieldCenteredDipole.MagneticFieldCenteredDipole()
    field.g10, field.g11, field.h11 = s.field.g10_nt * 1e-9, s.field.g11_nt * 1e-9, s.field.h11_nt * 1e-9
    field.planetRadius = s.field.reference_radius_m
    field.planetPosInMsg.subscribeTo(ephemeris.planetOutMsgs[0])
    field.addSpacecraftToModel(sc.scStateOutMsg)

    # --- sensors ---------------------------------------------------------------------------------
    nav = simpleNav.SimpleNav()
    nav.ModelTag = "nav"
    nav.scStateInMsg.subscribeTo(sc.scStateOutMsg)
    st = s.star_tracker
    if st is None:
        raise ValueError(f"scenario {case.SCENARIO!r} has no star tracker: the pointing case needs one")
    cross, about = st.noise_cross_boresight_arcsec * _ARCSEC, st.noise_about_boresight_arcsec * _ARCSEC
    # the cycle's rate is the mean of five 50 Hz gyro readings in the controller
    rate_sigma = math.radians(s.gyro.noise_std_dps) / math.sqrt(5.0)
    sigmas = [0.0] * 18
    sigmas[6:9] = [cross / 4.0, cross / 4.0, about / 4.0]   # MRP ≈ angle/4 (boresight +Z)
    sigmas[9:12] = [rate_sigma] * 3
    nav.PMatrix = [[sigmas[r] if r == c else 0.0 for c in range(18)] for r in range(18)]
    nav.walkBounds = [3.0 * x for x in sigmas]
    tam = magnetometer.Magnetometer()
    tam.ModelTag = "tam"
    tam.stateInMsg.subscribeTo(sc.scStateOutMsg)
    tam.magInMsg.subscribeTo(field.envOutMsgs[0])
    tam.senNoiseStd = [s.magnetometer.noise_std_gauss * 1e-4] * 3
    tam.senBias = [x * 1e-4 for x in s.magnetometer.bias_gauss]
    tam_body = tamComm.tamComm()
    tam_body.ModelTag = "tamComm"
    tam_body.dcm_BS = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
    tam_body.tamInMsg.subscribeTo(tam.tamDataOutMsg)

    # --- rods --------------------------------------------------------------------------------------
    limits = _coil_limits()
    mtb_params = messaging.MTBArrayConfigMsgPayload()
    mtb_params.numMTB = 3
    mtb_params.GtMatrix_B = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
    mtb_params.maxMtbDipoles = list(limits)
    mtb_params_msg = messaging.MTBArrayConfigMsg().write(mtb_params)
    rods = MtbEffector.MtbEffector()
    rods.ModelTag = "rods"
    rods.mtbParamsInMsg.subscribeTo(mtb_params_msg)
    rods.magInMsg.subscribeTo(field.envOutMsgs[0])
    sc.addDynamicEffector(rods)

    # --- flight software ---------------------------------------------------------------------------
    fsw: list = [tam, tam_body]
    python_law = None
    if control == "c":
        i_total = [c for row in s.spacecraft.inertia_kg_m2 for c in row]
        vehicle = messaging.VehicleConfigMsgPayload()
        vehicle.ISCPntB_B = i_total
        vehicle_msg = messaging.VehicleConfigMsg().write(vehicle)
        rw_params_msg = factory.getConfigMessage()
        guidance = inertial3D.inertial3D()
        guidance.ModelTag = "inertial3D"
        guidance.sigma_R0N = mrp(case.FIRST_TARGET)
        error = attTrackingError.attTrackingError()
        error.ModelTag = "attTrackingError"
        error.attNavInMsg.subscribeTo(nav.attOutMsg)
        error.attRefInMsg.subscribeTo(guidance.attRefOutMsg)
        feedback = mrpFeedback.mrpFeedback()
        feedback.ModelTag = "mrpFeedback"
        feedback.guidInMsg.subscribeTo(error.attGuidOutMsg)
        feedback.vehConfigInMsg.subscribeTo(vehicle_msg)
        feedback.rwParamsInMsg.subscribeTo(rw_params_msg)
        feedback.rwSpeedsInMsg.subscribeTo(rw_effector.rwSpeedOutMsg)
        feedback.K = 2.0 * _param("K_P")   # σ ≈ φ/4 against q_v ≈ φ/2: the same N·m per radian
        feedback.P = _param("K_D")
        feedback.Ki = -1.0                 # no integral term
        dumping = mtbMomentumManagementSimple.mtbMomentumManagementSimple()
        dumping.ModelTag = "mtbMomentumManagementSimple"
        dumping.Kp = _param("K_DUMP")
        dumping.rwParamsInMsg.subscribeTo(rw_params_msg)
        dumping.rwSpeedsInMsg.subscribeTo(rw_effector.rwSpeedOutMsg)
        to_dipole = torque2Dipole.torque2Dipole()
        to_dipole.ModelTag = "torque2Dipole"
        to_dipole.tamSensorBodyInMsg.subscribeTo(tam_body.tamOutMsg)
        to_dipole.tauRequestInMsg.subscribeTo(dumping.tauMtbRequestOutMsg)
        mapping = dipoleMapping.dipoleMapping()
        mapping.ModelTag = "dipoleMapping"
        mapping.steeringMatrix = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
        mapping.dipoleRequestBodyInMsg.subscribeTo(to_dipole.dipoleRequestOutMsg)
        mapping.mtbArrayConfigParamsInMsg.subscribeTo(mtb_params_msg)
        feedforward = mtbFeedforward.mtbFeedforward()
        feedforward.ModelTag = "mtbFeedforward"
        feedforward.vehControlInMsg.subscribeTo(feedback.cmdTorqueOutMsg)
        feedforward.dipoleRequestMtbInMsg.subscribeTo(mapping.dipoleRequestMtbOutMsg)
        feedforward.tamSensorBodyInMsg.subscribeTo(tam_body.tamOutMsg)
        feedforward.mtbArrayConfigParamsInMsg.subscribeTo(mtb_params_msg)
        motor = rwMotorTorque.rwMotorTorque()
        motor.ModelTag = "rwMotorTorque"
        motor.controlAxes_B = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
        motor.vehControlInMsg.subscribeTo(feedforward.vehControlOutMsg)
        motor.rwParamsInMsg.subscribeTo(rw_params_msg)
        rw_effector.rwMotorCmdInMsg.subscribeTo(motor.rwMotorTorqueOutMsg)
        rods.mtbCmdInMsg.subscribeTo(mapping.dipoleRequestMtbOutMsg)
        fsw += [guidance, error, feedback, dumping, to_dipole, mapping, feedforward, motor]
    else:
        python_law = ProjectPointing([w.axis_B for w in wheels], [w.inertia_kg_m2 for w in wheels],
                                     control_period_s)
        python_law.ModelTag = "projectPointing"
        python_law.navInMsg.subscribeTo(nav.attOutMsg)
        python_law.rwSpeedInMsg.subscribeTo(rw_effector.rwSpeedOutMsg)
        python_law.tamInMsg.subscribeTo(tam_body.tamOutMsg)
        rw_effector.rwMotorCmdInMsg.subscribeTo(python_law.rwCmdOutMsg)
        rods.mtbCmdInMsg.subscribeTo(python_law.mtbCmdOutMsg)
        fsw.append(python_law)

    state_log, speed_log = schedule(sim, [ephemeris, sc, rw_effector, gg, field, nav, rods], fsw, sc, rw_effector,
                                    case.TRACE_INTERVAL_S)
    sim.InitializeSimulation()

    # the controller is IDLE (wheels at zero torque, rods off) until POINTING is forced
    stops = [t for t in (case.POINTING_AT_S, case.SECOND_TARGET_AT_S) if t < duration_s] + [duration_s]
    sim.disableTask("fsw")
    t0 = time.perf_counter()
    for stop in stops:
        sim.ConfigureStopTime(macros.sec2nano(stop))
        sim.ExecuteSimulation()
        if stop == case.POINTING_AT_S:
            sim.enableTask("fsw")
        elif stop == case.SECOND_TARGET_AT_S:
            if python_law is not None:
                python_law.set_target(case.SECOND_TARGET)
            else:
                guidance.sigma_R0N = mrp(case.SECOND_TARGET)
    wall = time.perf_counter() - t0
    total = sc.scMassOutMsg.read().ISC_PntB_B  # hub and wheels, as the dynamics saw them
    inertia_error = max(abs(total[r][c] - s.spacecraft.inertia_kg_m2[r][c]) for r in range(3) for c in range(3))

    trace = [(t * 1e-9, quat(state_log.sigma_BN[k]), wheel_momenta(wheels, speed_log.wheelSpeeds[k],
                                                                    state_log.omega_BN_B[k]))
             for k, t in enumerate(state_log.times())]
    return {"sim_seconds": duration_s, "step_s": step_s, "control": control, "wall_s": wall,
            "real_time_factor": duration_s / wall, "inertia_error_kg_m2": inertia_error,
            **case.plausibility(trace)}


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=600.0)
    parser.add_argument("--step", type=float, default=0.02)
    parser.add_argument("--control", choices=("c", "python"), default="c")
    parser.add_argument("--control-period", type=float, default=0.1)
    args = parser.parse_args(argv)
    print(json.dumps(run(args.duration, args.step, args.control, args.control_period)))


if __name__ == "__main__":
    main()
