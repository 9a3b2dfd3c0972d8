# Written by fprime-lite (python -m fprime_lite.deploy.fpp.export deployments/coursework/topology.yaml) from deployments/coursework/topology.yaml.
# Regenerate it rather than edit it; tests/fprime_lite/deploy/test_fpp.py checks it is current.

module Components {
  enum AngularUnit : I32 {
    RAD_PER_SEC = 0
    DEG_PER_SEC = 1
  } default RAD_PER_SEC

  enum AxisOrientation : I32 {
    STANDARD = 0
    ROTATED_90_DEG_CW = 1
    ROTATED_90_DEG_CCW = 2
    ROTATED_180_DEG = 3
  } default STANDARD

  enum CourseworkLaw : I32 {
    OFF = 0
    CROSS_PRODUCT = 1
    BETA_PD = 2
    WHEELS_PD = 3
  } default OFF

  enum Lis2mdlSamplingFrequency : I32 {
    SF_10Hz = 0
    SF_20Hz = 1
    SF_50Hz = 2
    SF_100Hz = 3
  } default SF_10Hz

  enum Lsm6dsoSamplingFrequency : I32 {
    SF_12_5Hz = 0
    SF_26Hz = 1
    SF_52Hz = 2
    SF_104Hz = 3
    SF_208Hz = 4
    SF_416Hz = 5
    SF_833Hz = 6
    SF_1_66kHz = 7
    SF_3_33kHz = 8
    SF_6_66kHz = 9
  } default SF_12_5Hz

  array Vector3 = [3] F64 default [0.0, 0.0, 0.0]

  enum WheelError : I32 {
    REPORT = 0
    SHORTEST_PATH = 1
  } default REPORT

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port AccelerationGet

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port AngularVelocityGet

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port AngularVelocityMagnitudeGet(unit: Components.AngularUnit)

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port MagneticFieldGet

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port SamplingPeriodGet

  @ fprime-lite: detumble.proves.imu_manager.ImuManager
  passive component ImuManager {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    param get port prmGetOut
    param set port prmSetOut
    sync input port run: Svc.Sched
    sync input port accelerationGet: Components.AccelerationGet
    sync input port angularVelocityGet: Components.AngularVelocityGet
    sync input port angularVelocityMagnitudeGet: Components.AngularVelocityMagnitudeGet
    sync input port magneticFieldGet: Components.MagneticFieldGet
    sync input port magneticFieldSamplingPeriodGet: Components.SamplingPeriodGet
    sync command GET_ACCELERATION opcode 0x8
    sync command GET_ANGULAR_VELOCITY opcode 0x9
    sync command GET_MAGNETIC_FIELD opcode 0xA
    sync command SIM_SET_READ_FAULT(sensor: Sim.SimImuSensor, fault: Sim.SimReadFault) opcode 0xB
    event Lis2mdlDeviceNotReady severity warning high id 0x0 format "LIS2MDL device not ready" throttle 5
    event Lsm6dsoDeviceNotReady severity warning high id 0x1 format "LSM6DSO device not ready" throttle 5
    event AccelerometerSamplingFrequencyNotConfigured severity warning high id 0x2 format "LSM6DSO accelerometer sampling frequency not configured" throttle 5
    event GyroscopeSamplingFrequencyNotConfigured severity warning high id 0x3 format "LSM6DSO gyroscope sampling frequency not configured" throttle 5
    event MagnetometerSamplingFrequencyNotConfigured severity warning high id 0x4 format "LIS2MDL magnetomiter sampling frequency not configured" throttle 5
    event MagnetometerSamplingFrequencyGetFailed severity warning low id 0x5 format "Failed to retrieve LIS2MDL magnetometer sampling frequency" throttle 5
    event MagnetometerSamplingFrequencyZeroHz severity warning low id 0x6 format "LIS2MDL magnetometer sampling frequency is set to 0 Hz" throttle 5
    event AccelerationData(x: F64, y: F64, z: F64) severity activity low id 0x7 format "Acceleration: x={} m/s^2, y={} m/s^2, z={} m/s^2"
    event AngularVelocityData(x: F64, y: F64, z: F64) severity activity low id 0x8 format "Angular Velocity: x={} rad/s, y={} rad/s, z={} rad/s"
    event MagneticFieldData(x: F64, y: F64, z: F64) severity activity low id 0x9 format "Magnetic Field: x={} gauss, y={} gauss, z={} gauss"
    event InvalidAngularUnit(unit: I32) severity warning low id 0x80 format "Invalid angular unit {d}; use RAD_PER_SEC or DEG_PER_SEC" throttle 5
    event SimReadFaultSet(sensor: Sim.SimImuSensor, fault: Sim.SimReadFault) severity activity high id 0x81 format "SIM: {} read fault set to {}"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x82 format "Handler {} raised {}" throttle 10
    event ParamSetRefused($param: string size 40, reason: string size 120) severity warning low id 0x83 format "{} PRM_SET refused: {}"
    event ParamDefaulted($param: string size 40, reason: string size 120) severity warning high id 0x84 format "{} parameter file value refused ({}); default loaded"
    telemetry AxisOrientation: Components.AxisOrientation id 0x0 update always
    telemetry Acceleration: Drv.Acceleration id 0x1 update always
    telemetry AngularVelocity: Drv.AngularVelocity id 0x2 update always
    telemetry MagneticField: Drv.MagneticField id 0x3 update always
    telemetry AccelerometerSamplingFrequency: Components.Lsm6dsoSamplingFrequency id 0x4 update on change
    telemetry GyroscopeSamplingFrequency: Components.Lsm6dsoSamplingFrequency id 0x5 update on change
    telemetry MagnetometerSamplingFrequency: Components.Lis2mdlSamplingFrequency id 0x6 update on change
    telemetry HandlerFaults: U32 id 0x7 update on change
    param ACCELEROMETER_SAMPLING_FREQUENCY: Components.Lsm6dsoSamplingFrequency default Components.Lsm6dsoSamplingFrequency.SF_12_5Hz id 0x0 set opcode 0x0 save opcode 0x1
    param GYROSCOPE_SAMPLING_FREQUENCY: Components.Lsm6dsoSamplingFrequency default Components.Lsm6dsoSamplingFrequency.SF_104Hz id 0x1 set opcode 0x2 save opcode 0x3
    param MAGNETOMETER_SAMPLING_FREQUENCY: Components.Lis2mdlSamplingFrequency default Components.Lis2mdlSamplingFrequency.SF_100Hz id 0x2 set opcode 0x4 save opcode 0x5
    param AXIS_ORIENTATION: Components.AxisOrientation default Components.AxisOrientation.STANDARD id 0x3 set opcode 0x6 save opcode 0x7
  }

  @ fprime-lite: detumble.drivers.star_tracker.StarTracker
  passive component StarTracker {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port attitudeGet: Drv.AttitudeGet
    sync input port run: Svc.Sched
    sync command GET_ATTITUDE opcode 0x0
    sync command SIM_SET_FAULT(fault: Sim.SimStarTrackerFault) opcode 0x1
    event AttitudeData(q0: F64, q1: F64, q2: F64, q3: F64) severity activity low id 0x0 format "Attitude q_BN: {.9f}, {.9f}, {.9f}, {.9f}"
    event AttitudeReadFailed severity warning low id 0x1 format "Star tracker read failed" throttle 5
    event NoSolution severity warning low id 0x2 format "Star tracker has no attitude solution" throttle 5
    event SimFaultSet(fault: Sim.SimStarTrackerFault) severity activity high id 0x3 format "SIM: star tracker fault set to {}"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x4 format "Handler {} raised {}" throttle 10
    telemetry Attitude: Drv.AttitudeQuaternion id 0x0 update always
    telemetry Solutions: U32 id 0x1 update on change
    telemetry HandlerFaults: U32 id 0x2 update on change
  }

  @ fprime-lite: detumble.drivers.orbit_ephemeris.OrbitEphemeris
  passive component OrbitEphemeris {
    time get port timeCaller
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port orbitFrameGet: Drv.OrbitFrameGet
    sync input port ephemerisGet: Drv.EphemerisGet
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x0 format "Handler {} raised {}" throttle 10
    telemetry HandlerFaults: U32 id 0x0 update on change
  }

  @ fprime-lite: detumble.drivers.torque_rod_driver.TorqueRodDriver
  passive component TorqueRodDriver {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port dipoleSet: Drv.DipoleMomentSet
    sync command STOP opcode 0x0
    event InvalidDipole(x: F64, y: F64, z: F64) severity warning low id 0x0 format "Invalid dipole request ({}, {}, {}) A m^2; rods off" throttle 5
    event DipoleLimited(x: F64, y: F64, z: F64) severity warning low id 0x1 format "Dipole request ({.4g}, {.4g}, {.4g}) A m^2 beyond the rods' limits; limited" throttle 5
    event RodsStopped severity activity high id 0x2 format "Torque rods stopped"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x3 format "Handler {} raised {}" throttle 10
    telemetry Dipole: Drv.DipoleMoment id 0x0 update always
    telemetry HandlerFaults: U32 id 0x1 update on change
  }

  @ fprime-lite: detumble.drivers.reaction_wheel_driver.ReactionWheelDriver
  passive component ReactionWheelDriver {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port torqueSet: Drv.WheelTorqueSet
    sync input port speedSet: Drv.WheelSpeedSet
    sync input port enableSet: Drv.WheelEnableSet
    sync input port wheelStateGet: Drv.WheelStateGet
    sync input port run: Svc.Sched
    sync command SET_TORQUE(torque: F64) opcode 0x0
    sync command SET_SPEED(speed: F64) opcode 0x1
    sync command ENABLE opcode 0x2
    sync command DISABLE opcode 0x3
    sync command SIM_SET_FAULT(fault: Sim.SimWheelFault) opcode 0x4
    event TorqueSaturated(commanded: F64, limit: F64) severity warning low id 0x0 format "Torque {.6g} N m beyond the limit {.6g} N m; clipped" throttle 5
    event MomentumSaturated(momentum: F64, limit: F64) severity warning high id 0x1 format "Momentum {.6g} N m s at the limit {.6g} N m s; torque cut" throttle 5
    event DeviceNotReady severity warning low id 0x2 format "Wheel not ready" throttle 5
    event WheelNotEnabled severity warning low id 0x3 format "Wheel disabled; command refused (send ENABLE first)" throttle 5
    event InvalidTorque(torque: F64) severity warning low id 0x4 format "Invalid torque {.6g}; motor torque set to 0" throttle 5
    event InvalidSpeed(speed: F64) severity warning low id 0x5 format "Invalid speed {.6g}; motor torque set to 0" throttle 5
    event WheelReadFailed severity warning low id 0x6 format "Wheel read failed" throttle 5
    event WheelEnabled severity activity high id 0x7 format "Wheel enabled"
    event WheelDisabled severity activity high id 0x8 format "Wheel disabled"
    event SimFaultSet(fault: Sim.SimWheelFault) severity activity high id 0x9 format "SIM: wheel fault set to {}"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0xA format "Handler {} raised {}" throttle 10
    telemetry Mode: Drv.WheelMode id 0x0 update on change
    telemetry Speed: F64 id 0x1 update always
    telemetry Momentum: F64 id 0x2 update always
    telemetry Torque: F64 id 0x3 update always
    telemetry Command: F64 id 0x4 update on change
    telemetry HandlerFaults: U32 id 0x5 update on change
  }

  @ fprime-lite: detumble.components.coursework_controller.CourseworkController
  passive component CourseworkController {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    param get port prmGetOut
    param set port prmSetOut
    sync input port run: Svc.Sched
    output port magneticFieldGet: Components.MagneticFieldGet
    output port angularVelocityGet: Components.AngularVelocityGet
    output port attitudeGet: Drv.AttitudeGet
    output port orbitFrameGet: Drv.OrbitFrameGet
    output port wheelStateGet: [3] Drv.WheelStateGet
    output port wheelTorqueSet: [3] Drv.WheelTorqueSet
    output port dipoleSet: Drv.DipoleMomentSet
    sync command SET_LAW(law: Components.CourseworkLaw) opcode 0x1E
    sync command SET_TARGET(q0: F64, q1: F64, q2: F64, q3: F64) opcode 0x1F
    event LawChanged(law: Components.CourseworkLaw) severity activity high id 0x0 format "Coursework law now {}"
    event TargetSet(q0: F64, q1: F64, q2: F64, q3: F64) severity activity high id 0x1 format "Wheel target q_BO set to ({.6f}, {.6f}, {.6f}, {.6f})"
    event TargetRejected(q0: F64, q1: F64, q2: F64, q3: F64) severity warning low id 0x2 format "Target ({}, {}, {}, {}) is not a unit quaternion; kept the old one"
    event SensorReadFailed(sensor: string size 40) severity warning high id 0x3 format "{} read failed; actuators safe" throttle 10
    event ControlFault(kind: string size 40, $text: string size 80) severity warning high id 0x4 format "Control cycle raised {}: {}; actuators safe" throttle 10
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x5 format "Handler {} raised {}" throttle 10
    event ParamSetRefused($param: string size 40, reason: string size 120) severity warning low id 0x6 format "{} PRM_SET refused: {}"
    event ParamDefaulted($param: string size 40, reason: string size 120) severity warning high id 0x7 format "{} parameter file value refused ({}); default loaded"
    telemetry Law: Components.CourseworkLaw id 0x0 update on change
    telemetry DipoleCommand: Components.Vector3 id 0x1 update always
    telemetry WheelTorqueCommand: Components.Vector3 id 0x2 update always
    telemetry Beta: F64 id 0x3 update always
    telemetry HandlerFaults: U32 id 0x4 update on change
    param LAW: Components.CourseworkLaw default Components.CourseworkLaw.OFF id 0x0 set opcode 0x0 save opcode 0x1
    @ units: A·m²/(rad/s·T)
    param CROSS_PRODUCT_GAIN: F64 default 146.0 id 0x1 set opcode 0x2 save opcode 0x3
    @ units: A·m²/(rad/s)
    param BETA_KS: F64 default 990.0 id 0x2 set opcode 0x4 save opcode 0x5
    @ units: A·m²/(rad/s)
    param BETA_KD: F64 default 0.06 id 0x3 set opcode 0x6 save opcode 0x7
    param BETA_SWITCHED: bool default true id 0x4 set opcode 0x8 save opcode 0x9
    @ units: 1/s²
    param WHEEL_KP: F64 default 5.0 id 0x5 set opcode 0xA save opcode 0xB
    @ units: 1/s
    param WHEEL_KD: F64 default 9.0 id 0x6 set opcode 0xC save opcode 0xD
    param WHEEL_ERROR: Components.WheelError default Components.WheelError.SHORTEST_PATH id 0x7 set opcode 0xE save opcode 0xF
    @ units: kg·m², body frame
    param INERTIA_XX: F64 default 0.00167 id 0x8 set opcode 0x10 save opcode 0x11
    @ units: kg·m², body frame
    param INERTIA_YY: F64 default 0.00167 id 0x9 set opcode 0x12 save opcode 0x13
    @ units: kg·m², body frame
    param INERTIA_ZZ: F64 default 0.00167 id 0xA set opcode 0x14 save opcode 0x15
    @ units: A·m² per body axis
    param DIPOLE_LIMIT: F64 default 1.0 id 0xB set opcode 0x16 save opcode 0x17
    @ units: N·m per wheel
    param WHEEL_TORQUE_LIMIT: F64 default 0.001 id 0xC set opcode 0x18 save opcode 0x19
    @ units: N·m·s per wheel
    param WHEEL_MOMENTUM_LIMIT: F64 default 0.1 id 0xD set opcode 0x1A save opcode 0x1B
    @ units: 1/s
    param DUMP_GAIN: F64 default 0.0 id 0xE set opcode 0x1C save opcode 0x1D
  }
}

module Drv {
  struct Acceleration {
    x: F64
    y: F64
    z: F64
  } default { x = 0.0, y = 0.0, z = 0.0 }

  struct AngularVelocity {
    x: F64
    y: F64
    z: F64
  } default { x = 0.0, y = 0.0, z = 0.0 }

  struct AttitudeQuaternion {
    q0: F64
    q1: F64
    q2: F64
    q3: F64
    valid: bool
    timestamp: Fw.TimeValue
  } default { q0 = 0.0, q1 = 0.0, q2 = 0.0, q3 = 0.0, valid = false, timestamp = { timeBase = TimeBase.TB_NONE, timeContext = 0, seconds = 0, useconds = 0 } }

  struct DipoleMoment {
    x: F64
    y: F64
    z: F64
  } default { x = 0.0, y = 0.0, z = 0.0 }

  struct MagneticField {
    x: F64
    y: F64
    z: F64
    timestamp: Fw.TimeValue
  } default { x = 0.0, y = 0.0, z = 0.0, timestamp = { timeBase = TimeBase.TB_NONE, timeContext = 0, seconds = 0, useconds = 0 } }

  enum WheelMode : I32 {
    DISABLED = 0
    TORQUE = 1
    SPEED = 2
  } default DISABLED

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port AttitudeGet

  port DipoleMomentSet(dipole: Drv.DipoleMoment) -> Fw.Success

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port EphemerisGet

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port OrbitFrameGet

  port WheelEnableSet(enable: bool) -> Fw.Success

  port WheelSpeedSet(speed: F64) -> Fw.Success

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port WheelStateGet

  port WheelTorqueSet(torque: F64) -> Fw.Success
}

module Sim {
  enum SimImuSensor : U8 {
    ALL = 0
    MAGNETOMETER = 1
    GYROSCOPE = 2
    ACCELEROMETER = 3
    MAGNETOMETER_PERIOD = 4
  } default ALL

  enum SimReadFault : U8 {
    NONE = 0
    FAIL = 1
    NAN = 2
    INF = 3
  } default NONE

  enum SimStarTrackerFault : U8 {
    NONE = 0
    FAIL = 1
    NAN = 2
    FROZEN = 3
  } default NONE

  enum SimWheelFault : U8 {
    NONE = 0
    NOT_READY = 1
    STUCK = 2
    READ_FAIL = 3
    READ_NAN = 4
  } default NONE
}
