# Written by fprime-lite (python -m fprime_lite.deploy.fpp.export deployments/adcs_ref/topology.yaml) from deployments/adcs_ref/topology.yaml.
# Regenerate it rather than edit it; tests/fprime_lite/deploy/test_fpp.py checks it is current.

module Components {
  enum AlbedoUnavailableReason : I32 {
    NO_EPHEMERIS = 0
    NO_MAGNETOMETER = 1
    MAGNETOMETER_STALE = 2
    EARTH_DARK = 3
    FIELD_ALONG_SUN = 4
  } default NO_EPHEMERIS

  enum AngularUnit : I32 {
    RAD_PER_SEC = 0
    DEG_PER_SEC = 1
  } default RAD_PER_SEC

  enum AttitudeEstimator : I32 {
    COMPLEMENTARY = 0
    MEKF = 1
  } default COMPLEMENTARY

  enum AxisOrientation : I32 {
    STANDARD = 0
    ROTATED_90_DEG_CW = 1
    ROTATED_90_DEG_CCW = 2
    ROTATED_180_DEG = 3
  } default STANDARD

  enum BodyAxis : I32 {
    PLUS_X = 0
    MINUS_X = 1
    PLUS_Y = 2
    MINUS_Y = 3
    PLUS_Z = 4
    MINUS_Z = 5
  } default PLUS_X

  enum CoilShape : I32 {
    RECTANGULAR = 0
    CIRCULAR = 1
  } default RECTANGULAR

  enum ControlAutonomy : I32 {
    MANUAL = 0
    AUTO = 1
  } default MANUAL

  enum ControlMode : I32 {
    IDLE = 0
    DETUMBLE = 1
    SPIN_STABLE = 2
    POINTING = 3
    SUN_SAFE = 4
  } default IDLE

  enum DeployResult : I32 {
    DEPLOY_RESULT_SUCCESS = 0
    DEPLOY_RESULT_ABORT = 1
    DEPLOY_RESULT_FAILED = 2
  } default DEPLOY_RESULT_SUCCESS

  enum DetumbleMode : I32 {
    DISABLED = 0
    AUTO = 1
  } default DISABLED

  enum DetumbleState : I32 {
    COOLDOWN = 0
    SENSING_ANGULAR_VELOCITY = 1
    SENSING_MAGNETIC_FIELD = 2
    ACTUATING_BDOT = 3
    ACTUATING_HYSTERESIS = 4
  } default COOLDOWN

  enum DetumbleStrategy : I32 {
    IDLE = 0
    BDOT = 1
    HYSTERESIS = 2
  } default IDLE

  enum HysteresisAxis : I32 {
    X_AXIS = 0
    Y_AXIS = 1
    Z_AXIS = 2
  } default X_AXIS

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

  enum MagPointingLaw : I32 {
    SEED_PD = 0
    FIELD_STEERING = 1
  } default SEED_PD

  enum MagResidualMode : I32 {
    OFF = 0
    PARAMETER = 1
    ESTIMATE = 2
  } default OFF

  enum MagnetorquerFace : I32 {
    X_PLUS = 0
    X_MINUS = 1
    Y_PLUS = 2
    Y_MINUS = 3
    Z_MINUS = 5
  } default X_PLUS

  enum ModeChangeReason : I32 {
    COMMAND = 0
    AUTO_START = 1
    RATE_HIGH = 2
    RATE_LOW = 3
    SPIN_STABLE_REACHED = 4
    ATTITUDE_LOST = 5
    SYSTEM_SAFE_MODE = 6
    KNOWLEDGE_RESTORED = 7
  } default COMMAND

  enum PacketAuthenticatorStatus : I32 {
    Authenticated = 0
    VerifyError = 1
  } default Authenticated

  enum PacketParserStatus : I32 {
    Ok = 0
    SpiParseError = 1
    SequenceNumberParseError = 2
    MacParseError = 3
  } default Ok

  enum PointingActuator : I32 {
    ANY = 0
    WHEELS = 1
    MAGNETORQUERS = 2
  } default ANY

  enum PointingReference : I32 {
    INERTIAL = 0
    NADIR = 1
    GROUND_STATION = 2
    STATION_FALLBACK = 3
    SUN = 4
  } default INERTIAL

  struct Quaternion {
    q0: F64
    q1: F64
    q2: F64
    q3: F64
  } default { q0 = 0.0, q1 = 0.0, q2 = 0.0, q3 = 0.0 }

  enum RateSource : I32 {
    GYRO = 0
    OBSERVER = 1
  } default GYRO

  enum SafeModeReason : I32 {
    NONE = 0
    LOW_BATTERY = 1
    SYSTEM_FAULT = 2
    GROUND_COMMAND = 3
    EXTERNAL_REQUEST = 4
    LORA = 5
    COMMAND_LOSS = 6
  } default NONE

  enum SpinLaw : I32 {
    SEED_KANE_DAMPER = 0
    VIRTUAL_DAMPER = 1
    RATE_REGULATOR = 2
  } default SEED_KANE_DAMPER

  enum SystemMode : I32 {
    SAFE_MODE = 1
    NORMAL = 2
  } default SAFE_MODE

  enum TargetKind : I32 {
    INERTIAL = 0
    NADIR = 1
    GROUND_STATION = 2
    SUN = 3
  } default INERTIAL

  array Vector3 = [3] F64 default [0.0, 0.0, 0.0]

  enum WheelFeedForward : I32 {
    REFERENCE = 0
    REFERENCE_GYROSCOPIC = 1
    REFERENCE_GYROSCOPIC_GRAVITY = 2
  } default REFERENCE

  array WheelValues = [4] F64 default [0.0, 0.0, 0.0, 0.0]

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port AccelerationGet

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port AngularVelocityGet

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port AngularVelocityMagnitudeGet(unit: Components.AngularUnit)

  port ForceSafeModeWithReason(reason: Components.SafeModeReason)

  port GetSystemMode -> Components.SystemMode

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port MagneticFieldGet

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port SamplingPeriodGet

  port SetDetumbleMode(mode: Components.DetumbleMode)

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port SunVectorGet

  port SystemModeChanged(mode: Components.SystemMode)

  port loadSwitchStateChanged($state: Fw.On) -> Fw.Success

  @ fprime-lite: detumble.proves.mode_manager.ModeManager
  passive component ModeManager {
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
    sync input port completeSequence: Fw.CmdResponse
    sync input port forceSafeMode: Components.ForceSafeModeWithReason
    sync input port getMode: Components.GetSystemMode
    sync input port prepareForReboot: Fw.Signal
    sync input port packetRouted: Fw.Signal
    output port modeChanged: Components.SystemModeChanged
    output port runSequence: Svc.CmdSeqIn
    output port loadSwitchTurnOn: [8] Fw.Signal
    output port loadSwitchTurnOff: [8] Fw.Signal
    output port voltageGet: Drv.VoltageGet
    output port stopWatchdog: Fw.Signal
    sync command FORCE_SAFE_MODE opcode 0x0
    sync command EXIT_SAFE_MODE opcode 0x1
    sync command GET_CURRENT_MODE opcode 0x2
    sync command GET_SAFE_MODE_REASON opcode 0x3
    event EnteringSafeMode(reason: string size 100) severity warning high id 0x0 format "ENTERING SAFE MODE: {}"
    event ExitingSafeMode severity activity high id 0x1 format "Exiting safe mode"
    event ManualSafeModeEntry severity activity high id 0x2 format "Safe mode entry commanded manually"
    event ExternalFaultDetected severity warning high id 0x3 format "External fault detected - external component forced safe mode"
    event StatePersistenceFailure(operation: string size 20, status: I32) severity warning low id 0x4 format "State persistence {} failed with status {}"
    event AutoSafeModeEntry(reason: Components.SafeModeReason, voltage: F32) severity warning high id 0x5 format "AUTO SAFE MODE ENTRY: reason={} voltage={}V"
    event AutoSafeModeExit(voltage: F32) severity activity high id 0x6 format "AUTO SAFE MODE EXIT: Voltage recovered to {}V"
    event UnintendedRebootDetected severity warning high id 0x7 format "UNINTENDED REBOOT DETECTED: Entering safe mode"
    event PreparingForReboot severity activity high id 0x8 format "Preparing for intentional reboot - setting clean shutdown flag"
    event SafeModeSequenceCompleted severity activity high id 0x9 format "Safe Mode Radio Sequence Completed"
    event SafeModeSequenceFailed(response: Fw.CmdResponse) severity warning low id 0xA format "Safe Mode Radio Sequence Failed: {}"
    event SafeModeRequestIgnored severity warning low id 0xB format "SafeMode Request Ignored: Already in Safe Mode"
    event CurrentModeReading(mode: Components.SystemMode) severity activity low id 0xC format "Current mode: {}"
    event CurrentSafeModeReasonReading(reason: Components.SafeModeReason) severity activity low id 0xD format "Current safe mode reason: {}"
    event CommandLossDetected(duration: U32) severity warning high id 0xE format "Command loss detected after {} seconds without contact - entering safe mode"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0xF format "Handler {} raised {}" throttle 10
    event ParamSetRefused($param: string size 40, reason: string size 120) severity warning low id 0x10 format "{} PRM_SET refused: {}"
    event ParamDefaulted($param: string size 40, reason: string size 120) severity warning high id 0x11 format "{} parameter file value refused ({}); default loaded"
    telemetry CurrentMode: U8 id 0x0 update always
    telemetry SafeModeEntryCount: U32 id 0x1 update always
    telemetry CurrentSafeModeReason: Components.SafeModeReason id 0x2 update always
    telemetry HandlerFaults: U32 id 0x3 update on change
    @ units: V
    param SafeModeEntryVoltage: F32 default 6.7 id 0x0 set opcode 0x4 save opcode 0x5
    @ units: V
    param SafeModeRecoveryVoltage: F32 default 8.0 id 0x1 set opcode 0x6 save opcode 0x7
    @ units: s
    param SafeModeDebounceSeconds: U32 default 10 id 0x2 set opcode 0x8 save opcode 0x9
    param SAFEMODE_SEQUENCE_FILE: string size 200 default "/seq/enter_safe.bin" id 0x3 set opcode 0xA save opcode 0xB
    @ units: s, µs
    param COMM_LOSS_TIME: Fw.TimeIntervalValue default { seconds = 259200, useconds = 0 } id 0x4 set opcode 0xC save opcode 0xD
  }

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

  @ fprime-lite: detumble.drivers.magnetorquer_driver.MagnetorquerDriver
  passive component MagnetorquerDriver {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port start: Drv.StartMagnetorquer
    sync input port stop: Drv.StopMagnetorquer
    sync input port loadSwitchStateChanged: Components.loadSwitchStateChanged
    sync command START(val: I8) opcode 0x0
    sync command STOP opcode 0x1
    sync command SIM_SET_FAULT(fault: Sim.SimDriverFault) opcode 0x2
    event DeviceNotReady severity warning low id 0x0 format "Device not ready" throttle 5
    event DeviceInitialized severity activity low id 0x8 format "DRV2605 device initialized."
    event InvalidDriveLevel(val: I32) severity warning low id 0x80 format "Invalid drive level {d}; levels are -127..127" throttle 5
    event SimFaultSet(fault: Sim.SimDriverFault) severity activity high id 0x81 format "SIM: driver fault set to {}"
    event DriveReadbackMismatch(actual: I32, commanded: I32) severity warning high id 0x82 format "Coil drive read back {} after writing {}" throttle 5
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x83 format "Handler {} raised {}" throttle 10
    telemetry DriveLevel: I8 id 0x0 update on change
    telemetry HandlerFaults: U32 id 0x1 update on change
  }

  @ fprime-lite: detumble.components.detumble_manager.DetumbleManager
  passive component DetumbleManager {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    param get port prmGetOut
    param set port prmSetOut
    sync input port setMode: Components.SetDetumbleMode
    sync input port systemModeChanged: Components.SystemModeChanged
    sync input port run: Svc.Sched
    output port angularVelocityMagnitudeGet: Components.AngularVelocityMagnitudeGet
    output port magneticFieldGet: Components.MagneticFieldGet
    output port magneticFieldSamplingPeriodGet: Components.SamplingPeriodGet
    output port getSystemMode: Components.GetSystemMode
    output port xPlusStart: Drv.StartMagnetorquer
    output port xPlusStop: Drv.StopMagnetorquer
    output port xMinusStart: Drv.StartMagnetorquer
    output port xMinusStop: Drv.StopMagnetorquer
    output port yPlusStart: Drv.StartMagnetorquer
    output port yPlusStop: Drv.StopMagnetorquer
    output port yMinusStart: Drv.StartMagnetorquer
    output port yMinusStop: Drv.StopMagnetorquer
    output port zMinusStart: Drv.StartMagnetorquer
    output port zMinusStop: Drv.StopMagnetorquer
    output port dipoleMomentGet: Drv.DipoleMomentGet
    sync command SET_MODE(mode: Components.DetumbleMode) opcode 0x0
    sync command ENABLE_COIL(face: Components.MagnetorquerFace) opcode 0x45
    sync command ISOLATE_COIL(face: Components.MagnetorquerFace) opcode 0x46
    event EnableFailedSafeMode severity warning low id 0x0 format "Failed to enable detumbling because system is in SAFE_MODE." throttle 5
    event DetumbleStarted(angular_velocity_magnitude_deg_sec: F64) severity activity low id 0x1 format "Detumble started. Angular velocity magnitude: {} deg/s" throttle 1
    event DetumbleCompleted(angular_velocity_magnitude_deg_sec: F64) severity activity low id 0x2 format "Detumble complete. Angular velocity magnitude: {} deg/s" throttle 1
    event MagneticFieldRetrievalFailed severity warning low id 0x3 format "Failed to retrieve magnetic field." throttle 5
    event MagneticFieldSamplingPeriodRetrievalFailed severity warning low id 0x4 format "Failed to retrieve magnetic field sampling frequency." throttle 5
    event AngularVelocityRetrievalFailed severity warning low id 0x5 format "Failed to retrieve angular velocity." throttle 5
    event DipoleMomentRetrievalFailed severity warning low id 0x28 format "Failed to retrieve dipole moment." throttle 5
    event CoilStopFailed(face: Components.MagnetorquerFace) severity warning high id 0x29 format "Magnetorquer {} did not stop (stop answered FAILURE): coil isolated until ENABLE_COIL" throttle 10
    event CoilEnabled(face: Components.MagnetorquerFace) severity activity high id 0x2A format "Magnetorquer {} enabled by command"
    event CoilIsolatedByCommand(face: Components.MagnetorquerFace) severity activity high id 0x2B format "Magnetorquer {} isolated by command"
    event BdotMaxThresholdParamSet(value: F64) severity activity high id 0x6 format "BDOT_MAX_THRESHOLD parameter set to {} deg/s."
    event DeadbandUpperThresholdParamSet(value: F64) severity activity high id 0x8 format "DEADBAND_UPPER_THRESHOLD parameter set to {} deg/s."
    event DeadbandLowerThresholdParamSet(value: F64) severity activity high id 0x9 format "DEADBAND_LOWER_THRESHOLD parameter set to {} deg/s."
    event CooldownDurationParamSet(value: Fw.TimeIntervalValue) severity activity high id 0x7 format "COOLDOWN_DURATION parameter set to {}."
    event TorqueDurationParamSet(value: Fw.TimeIntervalValue) severity activity high id 0xC format "TORQUE_DURATION parameter set to {}."
    event GainParamSet(value: F64) severity activity high id 0xA format "GAIN parameter set to {}."
    event HysteresisAxisParamSet(value: Components.HysteresisAxis) severity activity high id 0xB format "HYSTERESIS_AXIS parameter set to {}."
    event XTurnsParamSet(value: F64) severity activity high id 0x17 format "X_TURNS parameter set to {}."
    event YTurnsParamSet(value: F64) severity activity high id 0x22 format "Y_TURNS parameter set to {}."
    event ZTurnsParamSet(value: F64) severity activity high id 0x27 format "Z_TURNS parameter set to {}."
    event XPlusVoltageParamSet(value: F64) severity activity high id 0x15 format "X_PLUS_VOLTAGE parameter set to {} V."
    event XPlusResistanceParamSet(value: F64) severity activity high id 0x13 format "X_PLUS_RESISTANCE parameter set to {} Ω."
    event XPlusLengthParamSet(value: F64) severity activity high id 0x12 format "X_PLUS_LENGTH parameter set to {} m."
    event XPlusWidthParamSet(value: F64) severity activity high id 0x16 format "X_PLUS_WIDTH parameter set to {} m."
    event XPlusShapeParamSet(value: Components.CoilShape) severity activity high id 0x14 format "X_PLUS_SHAPE parameter set to {}."
    event XMinusVoltageParamSet(value: F64) severity activity high id 0x10 format "X_MINUS_VOLTAGE parameter set to {} V."
    event XMinusResistanceParamSet(value: F64) severity activity high id 0xE format "X_MINUS_RESISTANCE parameter set to {} Ω."
    event XMinusLengthParamSet(value: F64) severity activity high id 0xD format "X_MINUS_LENGTH parameter set to {} m."
    event XMinusWidthParamSet(value: F64) severity activity high id 0x11 format "X_MINUS_WIDTH parameter set to {} m."
    event XMinusShapeParamSet(value: Components.CoilShape) severity activity high id 0xF format "X_MINUS_SHAPE parameter set to {}."
    event YPlusVoltageParamSet(value: F64) severity activity high id 0x20 format "Y_PLUS_VOLTAGE parameter set to {} V."
    event YPlusResistanceParamSet(value: F64) severity activity high id 0x1E format "Y_PLUS_RESISTANCE parameter set to {} Ω."
    event YPlusLengthParamSet(value: F64) severity activity high id 0x1D format "Y_PLUS_LENGTH parameter set to {} m."
    event YPlusWidthParamSet(value: F64) severity activity high id 0x21 format "Y_PLUS_WIDTH parameter set to {} m."
    event YPlusShapeParamSet(value: Components.CoilShape) severity activity high id 0x1F format "Y_PLUS_SHAPE parameter set to {}."
    event YMinusVoltageParamSet(value: F64) severity activity high id 0x1B format "Y_MINUS_VOLTAGE parameter set to {} V."
    event YMinusResistanceParamSet(value: F64) severity activity high id 0x19 format "Y_MINUS_RESISTANCE parameter set to {} Ω."
    event YMinusLengthParamSet(value: F64) severity activity high id 0x18 format "Y_MINUS_LENGTH parameter set to {} m."
    event YMinusWidthParamSet(value: F64) severity activity high id 0x1C format "Y_MINUS_WIDTH parameter set to {} m."
    event YMinusShapeParamSet(value: Components.CoilShape) severity activity high id 0x1A format "Y_MINUS_SHAPE parameter set to {}."
    event ZMinusVoltageParamSet(value: F64) severity activity high id 0x26 format "Z_MINUS_VOLTAGE parameter set to {} V."
    event ZMinusResistanceParamSet(value: F64) severity activity high id 0x24 format "Z_MINUS_RESISTANCE parameter set to {} Ω."
    event ZMinusDiameterParamSet(value: F64) severity activity high id 0x23 format "Z_MINUS_DIAMETER parameter set to {} m."
    event ZMinusShapeParamSet(value: Components.CoilShape) severity activity high id 0x25 format "Z_MINUS_SHAPE parameter set to {}."
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x2C format "Handler {} raised {}" throttle 10
    event ParamSetRefused($param: string size 40, reason: string size 120) severity warning low id 0x2D format "{} PRM_SET refused: {}"
    event ParamDefaulted($param: string size 40, reason: string size 120) severity warning high id 0x2E format "{} parameter file value refused ({}); default loaded"
    telemetry Mode: Components.DetumbleMode id 0x0 update always
    telemetry State: Components.DetumbleState id 0x1 update always
    telemetry DetumbleStrategy: Components.DetumbleStrategy id 0x2 update always
    telemetry AngularVelocityMagnitude: F64 id 0x3 update always format "{.3f}"
    telemetry TorqueDuration: Fw.TimeIntervalValue id 0xB update always
    telemetry TimeBetweenMagneticFieldReadings: Fw.TimeIntervalValue id 0xC update always
    telemetry XPlusTurnsParam: F64 id 0xF update always
    telemetry XMinusTurnsParam: F64 id 0x15 update always
    telemetry YPlusTurnsParam: F64 id 0x1C update always
    telemetry YMinusTurnsParam: F64 id 0x22 update always
    telemetry ZMinusTurnsParam: F64 id 0x29 update always
    telemetry IsolatedCoils: U8 id 0x2D update on change
    telemetry CoilStopFailures: U32 id 0x2E update on change
    telemetry BdotMaxThresholdParam: F64 id 0x4 update always
    telemetry DeadbandUpperThresholdParam: F64 id 0x5 update always
    telemetry DeadbandLowerThresholdParam: F64 id 0x6 update always
    telemetry CooldownDurationParam: Fw.TimeIntervalValue id 0x9 update always
    telemetry TorqueDurationParam: Fw.TimeIntervalValue id 0xA update always
    telemetry GainParam: F64 id 0x7 update always
    telemetry HysteresisAxisParam: Components.HysteresisAxis id 0x8 update always
    telemetry XTurnsParam: F64 id 0x19 update always
    telemetry YTurnsParam: F64 id 0x26 update always
    telemetry ZTurnsParam: F64 id 0x2C update always
    telemetry XPlusVoltageParam: F64 id 0xD update always
    telemetry XPlusResistanceParam: F64 id 0xE update always
    telemetry XPlusLengthParam: F64 id 0x10 update always
    telemetry XPlusWidthParam: F64 id 0x11 update always
    telemetry XPlusShapeParam: Components.CoilShape id 0x12 update always
    telemetry XMinusVoltageParam: F64 id 0x13 update always
    telemetry XMinusResistanceParam: F64 id 0x14 update always
    telemetry XMinusLengthParam: F64 id 0x16 update always
    telemetry XMinusWidthParam: F64 id 0x17 update always
    telemetry XMinusShapeParam: Components.CoilShape id 0x18 update always
    telemetry YPlusVoltageParam: F64 id 0x1A update always
    telemetry YPlusResistanceParam: F64 id 0x1B update always
    telemetry YPlusLengthParam: F64 id 0x1D update always
    telemetry YPlusWidthParam: F64 id 0x1E update always
    telemetry YPlusShapeParam: Components.CoilShape id 0x1F update always
    telemetry YMinusVoltageParam: F64 id 0x20 update always
    telemetry YMinusResistanceParam: F64 id 0x21 update always
    telemetry YMinusLengthParam: F64 id 0x23 update always
    telemetry YMinusWidthParam: F64 id 0x24 update always
    telemetry YMinusShapeParam: Components.CoilShape id 0x25 update always
    telemetry ZMinusVoltageParam: F64 id 0x27 update always
    telemetry ZMinusResistanceParam: F64 id 0x28 update always
    telemetry ZMinusDiameterParam: F64 id 0x2A update always
    telemetry ZMinusShapeParam: Components.CoilShape id 0x2B update always
    telemetry HandlerFaults: U32 id 0x2F update on change
    @ units: deg/s
    param BDOT_MAX_THRESHOLD: F64 default 720.0 id 0x28 set opcode 0x1 save opcode 0x2
    @ units: deg/s
    param DEADBAND_UPPER_THRESHOLD: F64 default 8.0 id 0x29 set opcode 0x3 save opcode 0x4
    @ units: deg/s
    param DEADBAND_LOWER_THRESHOLD: F64 default 5.0 id 0x1 set opcode 0x5 save opcode 0x6
    @ units: s, µs
    param COOLDOWN_DURATION: Fw.TimeIntervalValue default { seconds = 0, useconds = 20000 } id 0x3 set opcode 0x7 save opcode 0x8
    @ units: s, µs
    param TORQUE_DURATION: Fw.TimeIntervalValue default { seconds = 0, useconds = 320000 } id 0x26 set opcode 0x9 save opcode 0xA
    @ units: A·m²·s/G
    param GAIN: F64 default 3.0 id 0x27 set opcode 0xB save opcode 0xC
    param HYSTERESIS_AXIS: Components.HysteresisAxis default Components.HysteresisAxis.X_AXIS id 0x2A set opcode 0xD save opcode 0xE
    @ units: turns
    param X_TURNS: F64 default 96.0 id 0xB set opcode 0xF save opcode 0x10
    @ units: turns
    param Y_TURNS: F64 default 96.0 id 0x15 set opcode 0x11 save opcode 0x12
    @ units: turns
    param Z_TURNS: F64 default 153.0 id 0x1F set opcode 0x13 save opcode 0x14
    @ units: V
    param X_PLUS_VOLTAGE: F64 default 3.3 id 0x9 set opcode 0x15 save opcode 0x16
    @ units: Ω
    param X_PLUS_RESISTANCE: F64 default 13.0 id 0xA set opcode 0x17 save opcode 0x18
    @ units: m
    param X_PLUS_LENGTH: F64 default 0.053 id 0xC set opcode 0x19 save opcode 0x1A
    @ units: m
    param X_PLUS_WIDTH: F64 default 0.045 id 0xD set opcode 0x1B save opcode 0x1C
    param X_PLUS_SHAPE: Components.CoilShape default Components.CoilShape.RECTANGULAR id 0x21 set opcode 0x1D save opcode 0x1E
    @ units: V
    param X_MINUS_VOLTAGE: F64 default 3.3 id 0xE set opcode 0x1F save opcode 0x20
    @ units: Ω
    param X_MINUS_RESISTANCE: F64 default 13.0 id 0xF set opcode 0x21 save opcode 0x22
    @ units: m
    param X_MINUS_LENGTH: F64 default 0.053 id 0x11 set opcode 0x23 save opcode 0x24
    @ units: m
    param X_MINUS_WIDTH: F64 default 0.045 id 0x12 set opcode 0x25 save opcode 0x26
    param X_MINUS_SHAPE: Components.CoilShape default Components.CoilShape.RECTANGULAR id 0x22 set opcode 0x27 save opcode 0x28
    @ units: V
    param Y_PLUS_VOLTAGE: F64 default 3.3 id 0x13 set opcode 0x29 save opcode 0x2A
    @ units: Ω
    param Y_PLUS_RESISTANCE: F64 default 13.0 id 0x14 set opcode 0x2B save opcode 0x2C
    @ units: m
    param Y_PLUS_LENGTH: F64 default 0.053 id 0x16 set opcode 0x2D save opcode 0x2E
    @ units: m
    param Y_PLUS_WIDTH: F64 default 0.045 id 0x17 set opcode 0x2F save opcode 0x30
    param Y_PLUS_SHAPE: Components.CoilShape default Components.CoilShape.RECTANGULAR id 0x23 set opcode 0x31 save opcode 0x32
    @ units: V
    param Y_MINUS_VOLTAGE: F64 default 3.3 id 0x18 set opcode 0x33 save opcode 0x34
    @ units: Ω
    param Y_MINUS_RESISTANCE: F64 default 13.0 id 0x19 set opcode 0x35 save opcode 0x36
    @ units: m
    param Y_MINUS_LENGTH: F64 default 0.053 id 0x1B set opcode 0x37 save opcode 0x38
    @ units: m
    param Y_MINUS_WIDTH: F64 default 0.045 id 0x1C set opcode 0x39 save opcode 0x3A
    param Y_MINUS_SHAPE: Components.CoilShape default Components.CoilShape.RECTANGULAR id 0x24 set opcode 0x3B save opcode 0x3C
    @ units: V
    param Z_MINUS_VOLTAGE: F64 default 3.3 id 0x1D set opcode 0x3D save opcode 0x3E
    @ units: Ω
    param Z_MINUS_RESISTANCE: F64 default 150.7 id 0x1E set opcode 0x3F save opcode 0x40
    @ units: m
    param Z_MINUS_DIAMETER: F64 default 0.05755 id 0x20 set opcode 0x41 save opcode 0x42
    param Z_MINUS_SHAPE: Components.CoilShape default Components.CoilShape.CIRCULAR id 0x25 set opcode 0x43 save opcode 0x44
  }

  @ fprime-lite: detumble.proves.load_switch.LoadSwitch
  passive component LoadSwitch {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port turnOn: Fw.Signal
    sync input port turnOff: Fw.Signal
    output port loadSwitchStateChanged: [3] Components.loadSwitchStateChanged
    sync command TURN_ON opcode 0x0
    sync command TURN_OFF opcode 0x1
    sync command GET_IS_ON opcode 0x2
    event StatusChanged($state: Fw.On) severity activity high id 0x1 format "Load switch state changed to {}"
    event IsOn($state: Fw.On) severity activity low id 0x2 format "Current load switch state: {}"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x3 format "Handler {} raised {}" throttle 10
    telemetry IsOn: Fw.On id 0x0 update always
    telemetry HandlerFaults: U32 id 0x1 update on change
  }

  @ fprime-lite: detumble.proves.watchdog.Watchdog
  passive component Watchdog {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port run: Svc.Sched
    sync input port start: Fw.Signal
    sync input port stop: Fw.Signal
    output port prepareForReboot: Fw.Signal
    sync command START_WATCHDOG opcode 0x0
    sync command STOP_WATCHDOG opcode 0x1
    event WatchdogStart severity activity high id 0x0 format "Watchdog started"
    event WatchdogStop severity activity high id 0x1 format "Watchdog stopped"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x2 format "Handler {} raised {}" throttle 10
    telemetry WatchdogTransitions: U32 id 0x0 update always
    telemetry HandlerFaults: U32 id 0x1 update on change
  }

  @ fprime-lite: detumble.proves.rtc_manager.RtcManager
  passive component RtcManager {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port timeGetPort: Fw.Time
    output port cancelSequences: [3] Svc.CmdSeqCancel
    output port alarmTriggered: Drv.AlarmTriggered
    sync command TIME_SET(t: Drv.TimeData) opcode 0x0
    sync command ALARM_SET(t: Drv.TimeData) opcode 0x1
    sync command ALARM_CANCEL(ID: U16) opcode 0x2
    sync command ALARM_LIST opcode 0x3
    event DeviceNotReady severity warning high id 0x0 format "RTC not ready" throttle 1
    event TimeSet(seconds: U32, useconds: U32) severity activity high id 0x3 format "Time set on RTC, previous time: {}.{}"
    event TimeNotSet(rc: I32) severity warning high id 0x4 format "Time not set on RTC: {}"
    event YearValidationFailed(year: U32) severity warning high id 0x5 format "Provided year is invalid should be >= 1900: {}"
    event MonthValidationFailed(month: U32) severity warning high id 0x6 format "Provided month is invalid should be in [1, 12]: {}"
    event DayValidationFailed(day: U32) severity warning high id 0x7 format "Provided day is invalid should be in [1, 31]: {}"
    event HourValidationFailed(hour: U32) severity warning high id 0x8 format "Provided hour is invalid should be in [0, 23]: {}"
    event MinuteValidationFailed(minute: U32) severity warning high id 0x9 format "Provided minute is invalid should be in [0, 59]: {}"
    event SecondValidationFailed(second: U32) severity warning high id 0xA format "Provided second is invalid should be in [0, 59]: {}"
    event AlarmSet(ID: U16, t: Drv.TimeData) severity activity high id 0xB format "Alarm set on RTC with ID {}, time: {}"
    event AlarmNotSet(t: Drv.TimeData, rc: I32) severity warning high id 0xC format "Alarm not set on RTC for time: {}, return code: {}"
    event AlarmTriggered(ID: U16) severity activity high id 0xD format "Alarm with ID {} triggered"
    event AlarmCanceled(ID: U16) severity activity high id 0xE format "Alarm with ID {} canceled"
    event AlarmNotCanceled(ID: U16, rc: I32) severity warning high id 0xF format "Alarm with ID {} not canceled, return code: {}"
    event AlarmHardwareError(ID: U16, rc: I32) severity warning high id 0x10 format "Alarm with ID {} had a hardware error, return code: {}"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x11 format "Handler {} raised {}" throttle 10
    telemetry HandlerFaults: U32 id 0x0 update on change
  }

  @ fprime-lite: detumble.proves.reset_manager.ResetManager
  passive component ResetManager {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port coldReset: Fw.Signal
    sync input port warmReset: Fw.Signal
    output port prepareForReboot: Fw.Signal
    sync command COLD_RESET opcode 0x0
    sync command WARM_RESET opcode 0x1
    event INITIATE_COLD_RESET severity activity high id 0x0 format "Initiating cold reset"
    event INITIATE_WARM_RESET severity activity high id 0x1 format "Initiating warm reset"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x2 format "Handler {} raised {}" throttle 10
    telemetry HandlerFaults: U32 id 0x0 update on change
  }

  @ fprime-lite: detumble.proves.startup_manager.StartupManager
  passive component StartupManager {
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
    sync input port completeSequence: Fw.CmdResponse
    sync input port sequenceStarted: Svc.CmdSeqIn
    output port runSequence: Svc.CmdSeqIn
    sync command WAIT_FOR_QUIESCENCE opcode 0x0
    sync command GET_BOOT_COUNT opcode 0x1
    event CurrentBootCount(i: I64) severity activity low id 0x0 format "Current boot count: {}"
    event BootCountUpdateFailure severity warning low id 0x1 format "Failed to update boot count file"
    event QuiescenceFileInitFailure severity warning low id 0x2 format "Failed to initialize quiescence start time file"
    event StartupSequenceFinished severity activity low id 0x3 format "Start-up sequence finished successfully"
    event StartupSequenceFailed(response: Fw.CmdResponse) severity warning low id 0x4 format "Start-up sequence failed with response code {}"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x5 format "Handler {} raised {}" throttle 10
    event ParamSetRefused($param: string size 40, reason: string size 120) severity warning low id 0x6 format "{} PRM_SET refused: {}"
    event ParamDefaulted($param: string size 40, reason: string size 120) severity warning high id 0x7 format "{} parameter file value refused ({}); default loaded"
    telemetry BootCount: U64 id 0x0 update always
    telemetry QuiescenceEndTime: Fw.TimeValue id 0x1 update on change
    telemetry HandlerFaults: U32 id 0x2 update on change
    param ARMED: bool default true id 0x0 set opcode 0x2 save opcode 0x3
    @ units: s, µs
    param QUIESCENCE_TIME: Fw.TimeIntervalValue default { seconds = 2700, useconds = 0 } id 0x1 set opcode 0x4 save opcode 0x5
    param QUIESCENCE_START_FILE: string size 200 default "/quiescence_start.bin" id 0x2 set opcode 0x6 save opcode 0x7
    param STARTUP_SEQUENCE_FILE: string size 200 default "/seq/startup.bin" id 0x3 set opcode 0x8 save opcode 0x9
    param BOOT_COUNT_FILE: string size 200 default "/boot_count.bin" id 0x4 set opcode 0xA save opcode 0xB
  }

  @ fprime-lite: detumble.proves.power_monitor.PowerMonitor
  passive component PowerMonitor {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port run: Svc.Sched
    output port sysVoltageGet: Drv.VoltageGet
    output port sysCurrentGet: Drv.CurrentGet
    output port sysPowerGet: Drv.PowerGet
    output port solVoltageGet: Drv.VoltageGet
    output port solCurrentGet: Drv.CurrentGet
    output port solPowerGet: Drv.PowerGet
    sync command RESET_TOTAL_POWER opcode 0x0
    sync command RESET_TOTAL_GENERATION opcode 0x1
    sync command GET_TOTAL_POWER opcode 0x2
    event TotalPowerReset severity activity low id 0x0 format "Total power consumption reset to 0 mWh"
    event TotalGenerationReset severity activity low id 0x1 format "Total power generation reset to 0 mWh"
    event TotalPowerConsumptionReading(power: F32) severity activity low id 0x2 format "Total power consumption: {} mWh"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x3 format "Handler {} raised {}" throttle 10
    telemetry TotalPowerConsumption: F32 id 0x0 update always
    telemetry TotalPowerGenerated: F32 id 0x1 update always
    telemetry HandlerFaults: U32 id 0x2 update on change
  }

  @ fprime-lite: detumble.proves.ina219_manager.Ina219Manager
  passive component Ina219Manager {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port voltageGet: Drv.VoltageGet
    sync input port currentGet: Drv.CurrentGet
    sync input port powerGet: Drv.PowerGet
    sync command GetVoltage opcode 0x0
    sync command GetCurrent opcode 0x1
    sync command GetPower opcode 0x2
    sync command SIM_SET_NOT_READY(not_ready: bool) opcode 0x3
    event DeviceNotReady severity warning high id 0x0 format "INA219 device not ready" throttle 5
    event VoltageReading(voltage: F64) severity activity low id 0x1 format "Voltage: {} V"
    event CurrentReading(current: F64) severity activity low id 0x2 format "Current: {} A"
    event PowerReading(power: F64) severity activity low id 0x3 format "Power: {} W"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x4 format "Handler {} raised {}" throttle 10
    telemetry Voltage: F64 id 0x0 update always
    telemetry Current: F64 id 0x1 update always
    telemetry Power: F64 id 0x2 update always
    telemetry HandlerFaults: U32 id 0x3 update on change
  }

  @ fprime-lite: detumble.proves.burnwire.Burnwire
  passive component Burnwire {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    param get port prmGetOut
    param set port prmSetOut
    sync input port burnStart: Fw.Signal
    sync input port burnStop: Fw.Signal
    sync input port schedIn: Svc.Sched
    sync command START_BURNWIRE opcode 0x0
    sync command STOP_BURNWIRE opcode 0x1
    event SetBurnwireState(burnwire_state: Fw.On) severity activity high id 0x0 format "Burnwire State: {}"
    event SafetyTimerStatus(burnwire_state: Fw.On) severity activity high id 0x1 format "Safety Timer State: {} "
    event SafetyTimerState(burnwire_status: U32) severity activity high id 0x2 format "Safety Timer Will Burn For: {} Seconds"
    event BurnwireEndCount(end_count: U32) severity activity low id 0x3 format "Burnwire Burned for {} Seconds"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x4 format "Handler {} raised {}" throttle 10
    event ParamSetRefused($param: string size 40, reason: string size 120) severity warning low id 0x5 format "{} PRM_SET refused: {}"
    event ParamDefaulted($param: string size 40, reason: string size 120) severity warning high id 0x6 format "{} parameter file value refused ({}); default loaded"
    telemetry HandlerFaults: U32 id 0x0 update on change
    @ units: s
    param SAFETY_TIMER: U32 default 10 id 0x0 set opcode 0x2 save opcode 0x3
  }

  @ fprime-lite: detumble.proves.antenna_deployer.AntennaDeployer
  passive component AntennaDeployer {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    param get port prmGetOut
    param set port prmSetOut
    sync input port schedIn: Svc.Sched
    output port burnStart: Fw.Signal
    output port burnStop: Fw.Signal
    sync command DEPLOY opcode 0x0
    sync command DEPLOY_STOP opcode 0x1
    sync command RESET_DEPLOYMENT_STATE opcode 0x2
    sync command SET_DEPLOYMENT_STATE(deployed: bool) opcode 0x3
    event DeployAttempt(attempt: U32) severity activity high id 0x0 format "Antenna deployment attempt {} started"
    event DeploySuccess(attempt: U32) severity activity high id 0x1 format "Antenna deployment succeeded on attempt {}"
    event DeployFinish(result: Components.DeployResult, attempts: U32) severity activity high id 0x2 format "Antenna deployment finished with result {} after {} attempts"
    event AntennaBurnSignalCount(ticks: U32) severity activity low id 0x3 format "Burn signal active for {} scheduler ticks"
    event DeploymentAlreadyComplete severity activity high id 0x4 format "Antenna deployment skipped - antenna already deployed"
    event FileOperationError(filePath: string size 200, operation: string size 40) severity warning high id 0x5 format "File operation failed: {} on file {}"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x6 format "Handler {} raised {}" throttle 10
    event ParamSetRefused($param: string size 40, reason: string size 120) severity warning low id 0x7 format "{} PRM_SET refused: {}"
    event ParamDefaulted($param: string size 40, reason: string size 120) severity warning high id 0x8 format "{} parameter file value refused ({}); default loaded"
    telemetry DeployAttemptCount: U32 id 0x0 update always
    telemetry HandlerFaults: U32 id 0x1 update on change
    @ units: s
    param RETRY_DELAY_SEC: U32 default 30 id 0x0 set opcode 0x4 save opcode 0x5
    param MAX_DEPLOY_ATTEMPTS: U32 default 3 id 0x1 set opcode 0x6 save opcode 0x7
    @ units: s
    param BURN_DURATION_SEC: U32 default 8 id 0x2 set opcode 0x8 save opcode 0x9
  }

  @ fprime-lite: detumble.proves.com_delay.ComDelay
  passive component ComDelay {
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
    sync input port comStatusIn: Fw.SuccessCondition
    output port comStatusOut: Fw.SuccessCondition
    event DividerSet(divider: U16) severity activity high id 0x0 format "Set divider to: {}"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x1 format "Handler {} raised {}" throttle 10
    event ParamSetRefused($param: string size 40, reason: string size 120) severity warning low id 0x2 format "{} PRM_SET refused: {}"
    event ParamDefaulted($param: string size 40, reason: string size 120) severity warning high id 0x3 format "{} parameter file value refused ({}); default loaded"
    telemetry HandlerFaults: U32 id 0x0 update on change
    @ units: ticks
    param DIVIDER: U16 default 299 id 0x0 set opcode 0x0 save opcode 0x1
  }

  @ fprime-lite: detumble.proves.lora.LoRa
  passive component LoRa {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    param get port prmGetOut
    param set port prmSetOut
    sync input port enableTransmit: Fw.Signal
    sync input port disableTransmit: Fw.Signal
    sync input port comStatusIn: Fw.SuccessCondition
    output port comStatusOut: Fw.SuccessCondition
    sync command CONTINUOUS_WAVE(seconds: U16) opcode 0x8
    sync command TRANSMIT(enabled: Zephyr.TransmitState) opcode 0x9
    event ConfigurationFailed(mode: Zephyr.LoRaMode) severity warning high id 0x0 format "Failed to configure LoRa into mode: {}" throttle 2
    event SendFailed(status: I32) severity warning high id 0x1 format "Failed to send LoRa message: {}" throttle 2
    event AllocationFailed(allocation_size: U64) severity warning high id 0x2 format "Failed to allocate buffer of: {} bytes" throttle 2
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x3 format "Handler {} raised {}" throttle 10
    event ParamSetRefused($param: string size 40, reason: string size 120) severity warning low id 0x4 format "{} PRM_SET refused: {}"
    event ParamDefaulted($param: string size 40, reason: string size 120) severity warning high id 0x5 format "{} parameter file value refused ({}); default loaded"
    telemetry BytesReceived: U64 id 0x0 update on change
    telemetry BytesSent: U64 id 0x1 update on change
    telemetry LastRssi: I16 id 0x2 update on change
    telemetry LastSnr: I8 id 0x3 update on change
    telemetry HandlerFaults: U32 id 0x4 update on change
    param CODING_RATE: Zephyr.LoRaCodingRate default Zephyr.LoRaCodingRate.CR_4_5 id 0x0 set opcode 0x0 save opcode 0x1
    param DATA_RATE: Zephyr.LoRaDataRate default Zephyr.LoRaDataRate.SF_8 id 0x1 set opcode 0x2 save opcode 0x3
    param BANDWIDTH_TX: Zephyr.LoRaBandwidth default Zephyr.LoRaBandwidth.BW_125_KHZ id 0x2 set opcode 0x4 save opcode 0x5
    param BANDWIDTH_RX: Zephyr.LoRaBandwidth default Zephyr.LoRaBandwidth.BW_125_KHZ id 0x3 set opcode 0x6 save opcode 0x7
  }

  @ fprime-lite: detumble.proves.fs_format.FsFormat
  passive component FsFormat {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync command FORMAT opcode 0x0
    event FileSystemFormatted severity activity high id 0x0 format "File System formatted successfully"
    event FileSystemFormatFailed severity warning high id 0x1 format "File System format failed"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x2 format "Handler {} raised {}" throttle 10
    telemetry HandlerFaults: U32 id 0x0 update on change
  }

  @ fprime-lite: detumble.proves.pico_temp_manager.PicoTempManager
  passive component PicoTempManager {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port picoTemperatureGet: Drv.picoTemperatureGet
    sync command GetPicoTemperature opcode 0x0
    event DeviceNotReady severity warning low id 0x0 format "Device not ready" throttle 5
    event SensorSampleFetchFailed(ret: I32) severity warning low id 0x1 format "Sensor fetch failed with return code: {}" throttle 5
    event SensorChannelGetFailed(ret: I32) severity warning low id 0x2 format "Sensor channel get failed with return code: {}" throttle 5
    event PicoTemperature(temperature: F64) severity activity high id 0x3 format "Pico Temperature: {}°C"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x4 format "Handler {} raised {}" throttle 10
    telemetry PicoTemperature: F64 id 0x0 update always
    telemetry HandlerFaults: U32 id 0x1 update on change
  }

  @ fprime-lite: detumble.proves.tmp112_manager.Tmp112Manager
  passive component Tmp112Manager {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port temperatureGet: Drv.temperatureGet
    sync input port loadSwitchStateChanged: Components.loadSwitchStateChanged
    sync command GetTemperature opcode 0x0
    event DeviceNotReady severity warning low id 0x0 format "Device not ready" throttle 5
    event DeviceInitFailed(ret: I32) severity warning low id 0x1 format "Initialization failed with return code: {}" throttle 5
    event DeviceNil severity warning low id 0x2 format "Device is nil" throttle 5
    event DeviceStateNil severity warning low id 0x3 format "Device state is nil" throttle 5
    event TcaUnhealthy severity warning low id 0x4 format "TCA device is unhealthy" throttle 5
    event MuxUnhealthy severity warning low id 0x5 format "MUX device is unhealthy" throttle 5
    event SensorSampleFetchFailed(ret: I32) severity warning low id 0x6 format "Sensor fetch failed with return code: {}" throttle 5
    event SensorChannelGetFailed(ret: I32) severity warning low id 0x7 format "Sensor channel get failed with return code: {}" throttle 5
    event Temperature(temperature: F64) severity activity high id 0x8 format "Temperature: {}°C"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x9 format "Handler {} raised {}" throttle 10
    telemetry Temperature: F64 id 0x0 update always
    telemetry HandlerFaults: U32 id 0x1 update on change
  }

  @ fprime-lite: detumble.proves.veml6031_manager.Veml6031Manager
  passive component Veml6031Manager {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    param get port prmGetOut
    param set port prmSetOut
    sync input port visibleLightGet: Drv.lightGet
    sync input port loadSwitchStateChanged: Components.loadSwitchStateChanged
    sync command GetVisibleLight opcode 0x6
    event DeviceNotReady severity warning low id 0x0 format "Device not ready" throttle 5
    event DeviceInitFailed(ret: I32) severity warning low id 0x1 format "Initialization failed with return code: {}" throttle 5
    event DeviceNil severity warning low id 0x2 format "Device is nil" throttle 5
    event DeviceStateNil severity warning low id 0x3 format "Device state is nil" throttle 5
    event TcaUnhealthy severity warning low id 0x4 format "TCA device is unhealthy" throttle 5
    event MuxUnhealthy severity warning low id 0x5 format "MUX device is unhealthy" throttle 5
    event SensorSampleFetchFailed(ret: I32) severity warning low id 0x6 format "Sensor fetch failed with return code: {}" throttle 5
    event SensorChannelGetFailed(ret: I32) severity warning low id 0x7 format "Sensor channel get failed with return code: {}" throttle 5
    event InvalidGainParam(gain: U8) severity warning low id 0x8 format "Invalid gain parameter: {}" throttle 5
    event InvalidIntegrationTimeParam(it: U8) severity warning low id 0x9 format "Invalid integration time parameter: {}" throttle 5
    event InvalidDiv4Param(div4: U8) severity warning low id 0xA format "Invalid effective photodiode size parameter: {}" throttle 5
    event SensorAttrSetFailed(attr: string size 40, val: U8, ret: I32) severity warning low id 0xB format "Sensor attribute {}={} set failed with return code: {}" throttle 5
    event VisibleLight(lux: F32) severity activity high id 0xC format "Visible light: {} lux"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0xD format "Handler {} raised {}" throttle 10
    event ParamSetRefused($param: string size 40, reason: string size 120) severity warning low id 0xE format "{} PRM_SET refused: {}"
    event ParamDefaulted($param: string size 40, reason: string size 120) severity warning high id 0xF format "{} parameter file value refused ({}); default loaded"
    telemetry VisibleLight: F32 id 0x0 update always
    telemetry HandlerFaults: U32 id 0x1 update on change
    param GAIN: Drv.GAIN default Drv.GAIN.VEML6031_GAIN_0_5 id 0x0 set opcode 0x0 save opcode 0x1
    param INTEGRATION_TIME: Drv.IT default Drv.IT.VEML6031_IT_25 id 0x1 set opcode 0x2 save opcode 0x3
    param EFFECTIVE_PHOTODIODE_SIZE: Drv.DIV4 default Drv.DIV4.VEML6031_SIZE_1_4 id 0x2 set opcode 0x4 save opcode 0x5
  }

  @ fprime-lite: detumble.proves.camera_handler.CameraHandler
  passive component CameraHandler {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port schedIn: Svc.Sched
    sync command TAKE_IMAGE opcode 0x0
    sync command PING opcode 0x1
    sync command SEND_COMMAND(cmd: string size 40) opcode 0x2
    event CommandError(cmd: string size 40) severity warning high id 0x0 format "Failed to send {} command"
    event CommandSuccess(cmd: string size 40) severity activity high id 0x1 format "Command {} sent successfully"
    event ImageTransferStarted($size: U32) severity activity high id 0x2 format "Image transfer started, expecting {} bytes"
    event ImageTransferProgress(percent: U8, received: U32, expected: U32) severity activity high id 0x3 format "Image transfer {}% complete ({}/{} bytes)"
    event ImageTransferComplete(path: string size 100, $size: U32) severity activity high id 0x4 format "Image saved: {} ({} bytes)"
    event FailedCommandCurrentlyReceiving severity warning low id 0x5 format "Cannot send command while image is receiving!"
    event PongReceived severity activity high id 0x6 format "Ping Received"
    event BadPongReceived severity warning high id 0x7 format "Ping Received when we did not expect it!"
    event FileWriteError severity warning high id 0x8 format "File write error occurred during image transfer"
    event FileReadError severity warning high id 0x9 format "File read error occurred during image transfer"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0xA format "Handler {} raised {}" throttle 10
    telemetry BytesReceived: U32 id 0x0 update always
    telemetry ExpectedSize: U32 id 0x1 update always
    telemetry IsReceiving: bool id 0x2 update always
    telemetry FileOpen: bool id 0x3 update always
    telemetry FileErrorCount: U32 id 0x4 update always
    telemetry ImagesSaved: U32 id 0x5 update always
    telemetry HandlerFaults: U32 id 0x6 update on change
  }

  @ fprime-lite: detumble.proves.thermal_manager.ThermalManager
  passive component ThermalManager {
    enum TempSensorType : I32 {
      FACE = 0
      BATTERY = 1
    } default FACE
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
    output port faceTempGet: [5] Drv.temperatureGet
    output port battCellTempGet: [4] Drv.temperatureGet
    output port picoTempGet: Drv.picoTemperatureGet
    event TemperatureBelowThreshold(sensorType: Components.ThermalManager.TempSensorType, sensorId: U32, temperature: F64) severity warning low id 0x0 format "{} temperature below threshold: Sensor {} at {} °C" throttle 5
    event TemperatureAboveThreshold(sensorType: Components.ThermalManager.TempSensorType, sensorId: U32, temperature: F64) severity warning low id 0x1 format "{} temperature above threshold: Sensor {} at {} °C" throttle 5
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x2 format "Handler {} raised {}" throttle 10
    event ParamSetRefused($param: string size 40, reason: string size 120) severity warning low id 0x3 format "{} PRM_SET refused: {}"
    event ParamDefaulted($param: string size 40, reason: string size 120) severity warning high id 0x4 format "{} parameter file value refused ({}); default loaded"
    telemetry HandlerFaults: U32 id 0x0 update on change
    @ units: C
    param FACE_TEMP_LOWER_THRESHOLD: F64 default -40.0 id 0x0 set opcode 0x0 save opcode 0x1
    @ units: C
    param FACE_TEMP_UPPER_THRESHOLD: F64 default 60.0 id 0x1 set opcode 0x2 save opcode 0x3
    @ units: C
    param BATT_CELL_TEMP_LOWER_THRESHOLD: F64 default 5.0 id 0x2 set opcode 0x4 save opcode 0x5
    @ units: C
    param BATT_CELL_TEMP_UPPER_THRESHOLD: F64 default 60.0 id 0x3 set opcode 0x6 save opcode 0x7
  }

  @ fprime-lite: detumble.components.bdot_detumble.BDotDetumble
  passive component BDotDetumble {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    param get port prmGetOut
    param set port prmSetOut
    sync input port dipoleMomentGet: Drv.DipoleMomentGet
    output port magneticFieldGet: Components.MagneticFieldGet
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x0 format "Handler {} raised {}" throttle 10
    event ParamSetRefused($param: string size 40, reason: string size 120) severity warning low id 0x1 format "{} PRM_SET refused: {}"
    event ParamDefaulted($param: string size 40, reason: string size 120) severity warning high id 0x2 format "{} parameter file value refused ({}); default loaded"
    telemetry GainParam: F64 id 0x0 update always
    telemetry HandlerFaults: U32 id 0x1 update on change
    @ units: A·m²·s
    param Gain: F64 default 1.0 id 0x0 set opcode 0x0 save opcode 0x1
  }

  @ fprime-lite: detumble.components.attitude_controller.AttitudeController
  passive component AttitudeController {
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
    sync input port tlmRun: Svc.Sched
    output port angularVelocityGet: Components.AngularVelocityGet
    output port magneticFieldGet: Components.MagneticFieldGet
    output port attitudeGet: Drv.AttitudeGet
    output port dipoleMomentGet: Drv.DipoleMomentGet
    output port xPlusStart: Drv.StartMagnetorquer
    output port xPlusStop: Drv.StopMagnetorquer
    output port xMinusStart: Drv.StartMagnetorquer
    output port xMinusStop: Drv.StopMagnetorquer
    output port yPlusStart: Drv.StartMagnetorquer
    output port yPlusStop: Drv.StopMagnetorquer
    output port yMinusStart: Drv.StartMagnetorquer
    output port yMinusStop: Drv.StopMagnetorquer
    output port zMinusStart: Drv.StartMagnetorquer
    output port zMinusStop: Drv.StopMagnetorquer
    output port wheelTorqueSet: [4] Drv.WheelTorqueSet
    output port wheelStateGet: [4] Drv.WheelStateGet
    output port wheelEnableSet: [4] Drv.WheelEnableSet
    output port ephemerisGet: Drv.EphemerisGet
    output port sunVectorGet: Components.SunVectorGet
    output port getSystemMode: Components.GetSystemMode
    sync command FORCE_MODE(mode: Components.ControlMode) opcode 0x0
    sync command SET_AUTO opcode 0x1
    sync command SET_TARGET_QUATERNION(q0: F64, q1: F64, q2: F64, q3: F64) opcode 0x2
    sync command SET_TARGET_DIRECTION(x: F64, y: F64, z: F64) opcode 0x3
    sync command SET_TARGET_NADIR(primary: Components.BodyAxis, secondary: Components.BodyAxis) opcode 0x4
    sync command SET_TARGET_GROUND_STATION(latitude: F64, longitude: F64, altitude: F64, primary: Components.BodyAxis, secondary: Components.BodyAxis) opcode 0x5
    sync command SET_TARGET_SUN(primary: Components.BodyAxis, secondary: Components.BodyAxis) opcode 0x6
    event ControlModeChanged(from_mode: Components.ControlMode, to_mode: Components.ControlMode, reason: Components.ModeChangeReason) severity activity high id 0x0 format "Attitude mode {} -> {} ({})"
    event AutonomyChanged(autonomy: Components.ControlAutonomy) severity activity high id 0x1 format "Attitude autonomy set to {}"
    event TargetSet(q0: F64, q1: F64, q2: F64, q3: F64) severity activity high id 0x2 format "Pointing target q_TN = ({.6f}, {.6f}, {.6f}, {.6f})"
    event TargetNotUnitQuaternion(q0: F64, q1: F64, q2: F64, q3: F64, norm: F64) severity warning low id 0x3 format "Target ({}, {}, {}, {}) refused: norm {} is not 1 (within 1e-3)" throttle 5
    event TargetDirectionInvalid(x: F64, y: F64, z: F64) severity warning low id 0x4 format "Target direction ({}, {}, {}) refused: not a non-zero finite vector" throttle 5
    event NoAttitudeKnowledge severity warning low id 0x5 format "No attitude knowledge (star tracker): pointing not available" throttle 5
    event ModeUnavailableNoWheels(mode: Components.ControlMode) severity warning low id 0x6 format "Mode {} needs reaction wheels and none answer" throttle 5
    event AttitudeKnowledgeLost severity warning high id 0x7 format "Attitude knowledge lost while pointing: to SUN_SAFE (with light sensors) or SPIN_STABLE" throttle 5
    event GyroRetrievalFailed severity warning low id 0x8 format "Failed to retrieve angular velocity." throttle 5
    event MagneticFieldRetrievalFailed severity warning low id 0x9 format "Failed to retrieve magnetic field." throttle 5
    event DipoleMomentRetrievalFailed severity warning low id 0xA format "Failed to retrieve the B-dot dipole moment." throttle 5
    event WheelCommandFailed(wheel: U32) severity warning low id 0xB format "Wheel {} did not accept its command" throttle 5
    event EstimatorSelected(estimator: Components.AttitudeEstimator) severity activity high id 0xC format "Attitude estimator {} (attitude and bias carried over)"
    event AttitudeReinitialised severity warning low id 0xD format "MEKF attitude re-initialised on the star tracker (residual or 3-sigma above 5 deg)" throttle 5
    event InertiaModelRefused severity warning low id 0xE format "INERTIA_* parameters do not form a positive definite matrix: the rate observer keeps its previous model" throttle 1
    event WheelLimitReached severity warning low id 0xF format "A wheel torque or momentum limit cut the requested torque" throttle 5
    event ResidualDipoleEstimated(x: F64, y: F64, z: F64) severity activity low id 0x10 format "Residual dipole estimate ready: ({}, {}, {}) A m^2"
    event ResidualDipoleEstimateRefused(x: F64, y: F64, z: F64) severity warning low id 0x11 format "Residual dipole estimate ({}, {}, {}) A m^2 beyond the coil limits or not finite: feed-forward uses MAG_RESIDUAL_DIPOLE_*" throttle 5
    event TargetNadirSet(primary: Components.BodyAxis, secondary: Components.BodyAxis) severity activity high id 0x12 format "Pointing target: {} to nadir, {} along the velocity"
    event TargetStationSet(latitude: F64, longitude: F64, altitude: F64, primary: Components.BodyAxis, secondary: Components.BodyAxis) severity activity high id 0x13 format "Pointing target: ground station at {.4f} deg, {.4f} deg, {.1f} m with {} ({} along the velocity)"
    event TargetSunSet(primary: Components.BodyAxis, secondary: Components.BodyAxis) severity activity high id 0x14 format "Pointing target: {} to the Sun, {} toward the orbit normal"
    event TargetAxesInvalid(primary: Components.BodyAxis, secondary: Components.BodyAxis) severity warning low id 0x15 format "Target axes {} and {} refused: give two perpendicular axes" throttle 5
    event TargetStationInvalid(latitude: F64, longitude: F64, altitude: F64) severity warning low id 0x16 format "Ground station ({}, {}, {}) refused: latitude in [-90, 90] deg, longitude in [-180, 360] deg, altitude in [-500, 10000] m, all finite" throttle 5
    event NoEphemeris severity warning low id 0x17 format "No ephemeris (ephemerisGet): nadir, ground-station and Sun targets are not available" throttle 5
    event EphemerisRetrievalFailed severity warning low id 0x18 format "Failed to retrieve the ephemeris: holding the last reference attitude" throttle 5
    event TargetReferenceUndefined(kind: Components.TargetKind) severity warning low id 0x19 format "The {} target's reference is undefined now (its two directions are parallel): holding the last reference attitude" throttle 5
    event GroundStationInView severity activity low id 0x1A format "Ground station in view: tracking it"
    event GroundStationOutOfView severity activity low id 0x1B format "Ground station out of view: pointing at nadir"
    event SunSafeEntered(reason: Components.ModeChangeReason) severity warning high id 0x1C format "Entering SUN_SAFE ({}): turning SUN_SAFE_AXIS to the light sensors' Sun vector"
    event SunSafeExited(to_mode: Components.ControlMode, reason: Components.ModeChangeReason) severity activity high id 0x1D format "Leaving SUN_SAFE for {} ({})"
    event SunSensorsUnavailable severity warning low id 0x1E format "SUN_SAFE refused: no Sun vector source (sunVectorGet) is connected" throttle 5
    event SunVectorRetrievalFailed severity warning low id 0x1F format "Failed to retrieve the Sun vector: carrying the last one on the gyro" throttle 5
    event SunSpinLowered(spin_rate: F64) severity activity high id 0x20 format "Sun held for SUN_HOLD_DWELL: lowering the SUN_SAFE spin to {} deg/s (below the star tracker's rate limit)"
    event MagLqrTableFailed(reason: string size 80, retry_s: F64) severity warning low id 0x21 format "The magnetorquer hold's gain table failed ({}): field steering, next attempt in {} s" throttle 5
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x22 format "Handler {} raised {}" throttle 10
    event ParamSetRefused($param: string size 40, reason: string size 120) severity warning low id 0x23 format "{} PRM_SET refused: {}"
    event ParamDefaulted($param: string size 40, reason: string size 120) severity warning high id 0x24 format "{} parameter file value refused ({}); default loaded"
    telemetry Mode: Components.ControlMode id 0x0 update always
    telemetry Autonomy: Components.ControlAutonomy id 0x1 update always
    telemetry AngularRate: F64 id 0x2 update always format "{.3f}"
    telemetry PointingError: F64 id 0x3 update always format "{.4f}"
    telemetry SpinAxisError: F64 id 0x4 update always format "{.3f}"
    telemetry SpinRate: F64 id 0x5 update always format "{.3f}"
    telemetry DamperState: F64 id 0x6 update always
    telemetry RequestedTorque: Components.Vector3 id 0x7 update always
    telemetry CommandedDipole: Components.Vector3 id 0x8 update always
    telemetry WheelTorqueCommand: Components.WheelValues id 0x9 update always
    telemetry WheelMomentum: Components.WheelValues id 0xA update always
    telemetry TargetQuaternion: Components.Quaternion id 0xB update always
    telemetry GyroBiasEstimate: Components.Vector3 id 0xC update always
    telemetry AttitudeValid: U32 id 0xD update always
    telemetry AttitudeSigma3: F64 id 0xE update always format "{.5f}"
    telemetry FieldLineRate: F64 id 0xF update always format "{.5f}"
    telemetry ResidualDipole: Components.Vector3 id 0x10 update always
    telemetry ActiveTarget: Components.PointingReference id 0x11 update always
    telemetry ReferenceRate: Components.Vector3 id 0x12 update always
    telemetry SunVectorEstimate: Components.Vector3 id 0x13 update always
    telemetry SunPointingError: F64 id 0x14 update always format "{.3f}"
    telemetry HandlerFaults: U32 id 0x15 update on change
    @ units: N·m
    param K_P: F64 default 0.0011 id 0x0 set opcode 0x7 save opcode 0x8
    @ units: N·m·s
    param K_D: F64 default 0.002 id 0x1 set opcode 0x9 save opcode 0xA
    @ units: N·m/s
    param K_I: F64 default 0.000055 id 0x2 set opcode 0xB save opcode 0xC
    @ units: deg
    param INTEGRAL_WINDOW: F64 default 1.0 id 0x3 set opcode 0xD save opcode 0xE
    @ units: N·m
    param K_P_MAG: F64 default 0.000004 id 0x4 set opcode 0xF save opcode 0x10
    @ units: N·m·s
    param K_D_MAG: F64 default 0.0004 id 0x5 set opcode 0x11 save opcode 0x12
    @ units: N·m·s
    param C_DAMP: F64 default 0.0001 id 0x6 set opcode 0x13 save opcode 0x14
    @ units: kg·m²
    param I_D: F64 default 0.0002 id 0x7 set opcode 0x15 save opcode 0x16
    @ units: A·m²·s/G
    param K_BDOT: F64 default 3.0 id 0x8 set opcode 0x17 save opcode 0x18
    param SPIN_LAW: Components.SpinLaw default Components.SpinLaw.RATE_REGULATOR id 0x9 set opcode 0x19 save opcode 0x1A
    @ units: deg/s
    param SPIN_RATE_TARGET: F64 default 1.5 id 0xA set opcode 0x1B save opcode 0x1C
    @ units: N·m·s
    param SPIN_K_TRANSVERSE: F64 default 0.0002 id 0xB set opcode 0x1D save opcode 0x1E
    @ units: N·m·s
    param SPIN_K_RATE: F64 default 0.0002 id 0xC set opcode 0x1F save opcode 0x20
    @ units: deg/s
    param DETUMBLE_ENTER_RATE: F64 default 20.0 id 0xD set opcode 0x21 save opcode 0x22
    @ units: deg/s
    param DETUMBLE_EXIT_RATE: F64 default 1.0 id 0xE set opcode 0x23 save opcode 0x24
    @ units: s
    param MODE_DWELL: F64 default 5.0 id 0xF set opcode 0x25 save opcode 0x26
    @ units: deg
    param SPIN_AXIS_ENTER: F64 default 5.0 id 0x10 set opcode 0x27 save opcode 0x28
    @ units: deg
    param SPIN_AXIS_RESET: F64 default 8.0 id 0x11 set opcode 0x29 save opcode 0x2A
    @ units: 1
    param SPIN_RATE_ENTER: F64 default 0.05 id 0x12 set opcode 0x2B save opcode 0x2C
    @ units: 1
    param SPIN_RATE_RESET: F64 default 0.08 id 0x13 set opcode 0x2D save opcode 0x2E
    @ units: s
    param SPIN_STABLE_DWELL: F64 default 60.0 id 0x14 set opcode 0x2F save opcode 0x30
    @ units: s
    param ATTITUDE_TIMEOUT: F64 default 90.0 id 0x15 set opcode 0x31 save opcode 0x32
    @ units: deg/s
    param SLEW_RATE_LIMIT: F64 default 8.0 id 0x16 set opcode 0x33 save opcode 0x34
    param POINTING_ACTUATOR: Components.PointingActuator default Components.PointingActuator.ANY id 0x17 set opcode 0x35 save opcode 0x36
    @ units: 1/s
    param K_DUMP: F64 default 0.002 id 0x18 set opcode 0x37 save opcode 0x38
    @ units: N·m
    param WHEEL_MAX_TORQUE: F64 default 0.002 id 0x19 set opcode 0x39 save opcode 0x3A
    @ units: N·m·s
    param WHEEL_MAX_MOMENTUM: F64 default 0.004 id 0x1A set opcode 0x3B save opcode 0x3C
    @ units: 1/s
    param FILTER_KP: F64 default 0.5 id 0x1B set opcode 0x3D save opcode 0x3E
    @ units: 1/s²
    param FILTER_KI: F64 default 0.02 id 0x1C set opcode 0x3F save opcode 0x40
    @ units: A·m²
    param X_COIL_MAX_DIPOLE: F64 default 0.058120615384615375 id 0x1D set opcode 0x41 save opcode 0x42
    @ units: A·m²
    param Y_COIL_MAX_DIPOLE: F64 default 0.058120615384615375 id 0x1E set opcode 0x43 save opcode 0x44
    @ units: A·m²
    param Z_COIL_MAX_DIPOLE: F64 default 0.008715105638149638 id 0x1F set opcode 0x45 save opcode 0x46
    @ units: ticks
    param CYCLE_TICKS: U32 default 5 id 0x20 set opcode 0x47 save opcode 0x48
    param ESTIMATOR: Components.AttitudeEstimator default Components.AttitudeEstimator.MEKF id 0x21 set opcode 0x49 save opcode 0x4A
    @ units: deg/s
    param GYRO_NOISE: F64 default 0.03404722210890829 id 0x22 set opcode 0x4B save opcode 0x4C
    @ units: deg/s/√s
    param GYRO_BIAS_WALK: F64 default 0.0001 id 0x23 set opcode 0x4D save opcode 0x4E
    @ units: deg/s
    param GYRO_BIAS_SIGMA0: F64 default 1.0 id 0x24 set opcode 0x4F save opcode 0x50
    @ units: arcsec
    param TRACKER_NOISE_CROSS: F64 default 10.0 id 0x25 set opcode 0x51 save opcode 0x52
    @ units: arcsec
    param TRACKER_NOISE_ABOUT: F64 default 70.0 id 0x26 set opcode 0x53 save opcode 0x54
    param RATE_SOURCE: Components.RateSource default Components.RateSource.OBSERVER id 0x27 set opcode 0x55 save opcode 0x56
    @ units: 1/s
    param RATE_OBSERVER_GAIN: F64 default 0.1 id 0x28 set opcode 0x57 save opcode 0x58
    @ units: kg·m², body frame
    param INERTIA_XX: F64 default 0.0022 id 0x29 set opcode 0x59 save opcode 0x5A
    @ units: kg·m², body frame
    param INERTIA_YY: F64 default 0.00215 id 0x2A set opcode 0x5B save opcode 0x5C
    @ units: kg·m², body frame
    param INERTIA_ZZ: F64 default 0.00205 id 0x2B set opcode 0x5D save opcode 0x5E
    @ units: kg·m², body frame
    param INERTIA_XY: F64 default 0.00002 id 0x2C set opcode 0x5F save opcode 0x60
    @ units: kg·m², body frame
    param INERTIA_XZ: F64 default -0.000015 id 0x2D set opcode 0x61 save opcode 0x62
    @ units: kg·m², body frame
    param INERTIA_YZ: F64 default 0.00001 id 0x2E set opcode 0x63 save opcode 0x64
    param MAG_POINTING_LAW: Components.MagPointingLaw default Components.MagPointingLaw.FIELD_STEERING id 0x2F set opcode 0x65 save opcode 0x66
    @ units: 1
    param MAG_STEER_RHO: F64 default 2.0 id 0x30 set opcode 0x67 save opcode 0x68
    @ units: 1
    param MAG_STEER_ZETA: F64 default 1.0 id 0x31 set opcode 0x69 save opcode 0x6A
    @ units: rad/s
    param MAG_FIELD_RATE_BANDWIDTH: F64 default 0.05 id 0x32 set opcode 0x6B save opcode 0x6C
    @ units: 1/s
    param MAG_FIELD_RATE_MIN: F64 default 0.0005 id 0x33 set opcode 0x6D save opcode 0x6E
    @ units: s
    param MAG_SETTLE_TIME: F64 default 30.0 id 0x34 set opcode 0x6F save opcode 0x70
    param MAG_RESIDUAL_MODE: Components.MagResidualMode default Components.MagResidualMode.ESTIMATE id 0x35 set opcode 0x71 save opcode 0x72
    @ units: A·m², body frame
    param MAG_RESIDUAL_DIPOLE_X: F64 default 0.0 id 0x36 set opcode 0x73 save opcode 0x74
    @ units: A·m², body frame
    param MAG_RESIDUAL_DIPOLE_Y: F64 default 0.0 id 0x37 set opcode 0x75 save opcode 0x76
    @ units: A·m², body frame
    param MAG_RESIDUAL_DIPOLE_Z: F64 default 0.0 id 0x38 set opcode 0x77 save opcode 0x78
    @ units: s
    param MAG_RESIDUAL_WINDOW: F64 default 60.0 id 0x39 set opcode 0x79 save opcode 0x7A
    @ units: deg
    param GS_MIN_ELEVATION: F64 default 10.0 id 0x3A set opcode 0x7B save opcode 0x7C
    param WHEEL_FEED_FORWARD: Components.WheelFeedForward default Components.WheelFeedForward.REFERENCE id 0x3B set opcode 0x7D save opcode 0x7E
    @ units: deg
    param RATE_BLEND_ANGLE: F64 default 0.1 id 0x3C set opcode 0x7F save opcode 0x80
    @ units: 1/s
    param RATE_BLEND_GAIN: F64 default 2.0 id 0x3D set opcode 0x81 save opcode 0x82
    param SUN_SAFE_AXIS: Components.BodyAxis default Components.BodyAxis.PLUS_Z id 0x3E set opcode 0x83 save opcode 0x84
    @ units: N·m/rad
    param SUN_SAFE_K_P: F64 default 0.0002 id 0x3F set opcode 0x85 save opcode 0x86
    @ units: N·m·s
    param SUN_SAFE_K_D: F64 default 0.0012 id 0x40 set opcode 0x87 save opcode 0x88
    @ units: N·m/rad
    param SUN_SAFE_K_P_MAG: F64 default 0.000004 id 0x41 set opcode 0x89 save opcode 0x8A
    @ units: N·m·s
    param SUN_SAFE_K_D_MAG: F64 default 0.0004 id 0x42 set opcode 0x8B save opcode 0x8C
    @ units: s
    param SUN_VECTOR_TIMEOUT: F64 default 10.0 id 0x43 set opcode 0x8D save opcode 0x8E
    @ units: s
    param SUN_SAFE_EXIT_DWELL: F64 default 10.0 id 0x44 set opcode 0x8F save opcode 0x90
    @ units: deg/s
    param SUN_SPIN_RATE: F64 default 3.0 id 0x45 set opcode 0x91 save opcode 0x92
    @ units: s
    param SUN_BIAS_TIME: F64 default 100.0 id 0x46 set opcode 0x93 save opcode 0x94
    @ units: deg
    param SUN_HOLD_ANGLE: F64 default 10.0 id 0x47 set opcode 0x95 save opcode 0x96
    @ units: s
    param SUN_HOLD_DWELL: F64 default 300.0 id 0x48 set opcode 0x97 save opcode 0x98
    @ units: deg/s
    param SUN_HOLD_SPIN_RATE: F64 default 1.5 id 0x49 set opcode 0x99 save opcode 0x9A
    @ units: deg/s²
    param SUN_HOLD_RAMP: F64 default 0.005 id 0x4A set opcode 0x9B save opcode 0x9C
    @ units: deg
    param SUN_HOLD_FIELD_ANGLE: F64 default 80.0 id 0x4B set opcode 0x9D save opcode 0x9E
    @ units: deg
    param SUN_HOLD_TIP_ANGLE: F64 default 0.0 id 0x4C set opcode 0x9F save opcode 0xA0
    @ units: deg/s
    param INTEGRAL_RATE_GATE: F64 default 0.05 id 0x4D set opcode 0xA1 save opcode 0xA2
    @ units: 1
    param MAG_STEER_RHO_LARGE: F64 default 0.0 id 0x4E set opcode 0xA3 save opcode 0xA4
    @ units: deg
    param MAG_STEER_RHO_FROM: F64 default 12.0 id 0x4F set opcode 0xA5 save opcode 0xA6
    @ units: deg
    param MAG_STEER_RHO_AT: F64 default 20.0 id 0x50 set opcode 0xA7 save opcode 0xA8
    @ units: s
    param RATE_OBSERVER_DIPOLE_TIME: F64 default 20.0 id 0x51 set opcode 0xA9 save opcode 0xAA
    @ units: s
    param MAG_BIAS_TIME: F64 default 1.0 id 0x52 set opcode 0xAB save opcode 0xAC
    @ units: deg
    param MAG_LQR_ANGLE: F64 default 50.0 id 0x53 set opcode 0xAD save opcode 0xAE
    @ units: 1
    param MAG_FIELD_MODEL_DEGREE: F64 default 6.0 id 0x54 set opcode 0xAF save opcode 0xB0
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

  @ fprime-lite: detumble.proves.adcs.ADCS
  passive component ADCS {
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
    sync input port sunVectorGet: Components.SunVectorGet
    output port visibleLightGet: [6] Drv.lightGet
    output port ephemerisGet: Drv.EphemerisGet
    output port magneticFieldGet: Components.MagneticFieldGet
    output port angularVelocityGet: Components.AngularVelocityGet
    event SunVectorAcquired(x: F64, y: F64, z: F64, lit: U32) severity activity low id 0x0 format "Sun vector valid: ({.3f}, {.3f}, {.3f}) in B, {} faces lit"
    event SunVectorLost(lit: U32, magnitude: F64) severity activity low id 0x1 format "Sun vector lost: {} faces lit, magnitude {.3f} of full Sun (eclipse, or no usable reading)"
    event LightSensorReadFailed(sensor: U32) severity warning low id 0x2 format "Light sensor {} did not answer: its face counts as dark" throttle 5
    event AlbedoCorrectionUnavailable(reason: Components.AlbedoUnavailableReason) severity warning low id 0x3 format "Albedo correction unavailable ({}): the Sun vector is the uncorrected one" throttle 5
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x4 format "Handler {} raised {}" throttle 10
    event ParamSetRefused($param: string size 40, reason: string size 120) severity warning low id 0x5 format "{} PRM_SET refused: {}"
    event ParamDefaulted($param: string size 40, reason: string size 120) severity warning high id 0x6 format "{} parameter file value refused ({}); default loaded"
    telemetry SunVector: Components.Vector3 id 0x0 update always
    telemetry SunVectorValid: U32 id 0x1 update always
    telemetry LitFaces: U32 id 0x2 update always
    telemetry SunVectorRaw: Components.Vector3 id 0x3 update always
    telemetry AlbedoCorrected: U32 id 0x4 update always
    telemetry HandlerFaults: U32 id 0x5 update on change
    @ units: lux
    param SUN_FULL_SCALE_LUX: F64 default 133000.0 id 0x0 set opcode 0x0 save opcode 0x1
    @ units: 1
    param SUN_LIT_FRACTION: F64 default 0.02 id 0x1 set opcode 0x2 save opcode 0x3
    @ units: 1
    param SUN_MAGNITUDE_TOLERANCE: F64 default 0.25 id 0x2 set opcode 0x4 save opcode 0x5
    param SUN_ALBEDO_CORRECTION: Fw.FwEnabled default Fw.FwEnabled.DISABLED id 0x3 set opcode 0x6 save opcode 0x7
    @ units: 1
    param SUN_ALBEDO_MODEL: F64 default 0.3 id 0x4 set opcode 0x8 save opcode 0x9
    @ units: s
    param SUN_FIELD_MAX_AGE: F64 default 2.0 id 0x5 set opcode 0xA save opcode 0xB
  }

  @ fprime-lite: detumble.proves.tc_security_deframer.TcSecurityDeframer
  passive component TcSecurityDeframer {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    param get port prmGetOut
    param set port prmSetOut
    sync command GET_SEQ_NUM opcode 0x0
    sync command SET_SEQ_NUM(seq_num: U32) opcode 0x1
    event AuthenticationFailed(auth_status: Components.PacketAuthenticatorStatus, rc: I32) severity warning high id 0x1 format "Authentication failed: Status={}, PSA Return Code={}" throttle 2
    event SequenceNumberInvalid(packet_seq_num: U32, seq_num: U32, window: U32) severity warning high id 0x2 format "Sequence number less than last accepted or out of window: Received={}, LastAccepted={}, Window={}" throttle 2
    event ParsingFailed(parse_status: Components.PacketParserStatus) severity warning high id 0x3 format "Parsing failed: {}" throttle 2
    event SpiInvalid(packet_spi: U32) severity warning high id 0x4 format "SPI invalid: Received={}" throttle 2
    event SequenceNumberGet(seq_num: U32) severity activity high id 0x6 format "Sequence number is {}"
    event SequenceNumberSet(seq_num: U32) severity activity high id 0x7 format "Sequence number set to {}"
    event SequenceNumberWriteFailed(status: Os.FileStatus) severity warning high id 0x8 format "Failed to write sequence number, error: {}" throttle 2
    event SequenceNumberReadFailed(status: Os.FileStatus) severity warning high id 0xE format "Failed to read sequence number, error: {}" throttle 2
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0xF format "Handler {} raised {}" throttle 10
    event ParamSetRefused($param: string size 40, reason: string size 120) severity warning low id 0x10 format "{} PRM_SET refused: {}"
    event ParamDefaulted($param: string size 40, reason: string size 120) severity warning high id 0x11 format "{} parameter file value refused ({}); default loaded"
    telemetry CurrentSequenceNumber: U32 id 0x0 update always
    telemetry HandlerFaults: U32 id 0x1 update on change
    param SEQ_NUM_WINDOW: U32 default 50000 id 0x0 set opcode 0x2 save opcode 0x3
    param SEQ_NUM_FILE_PATH: string size 200 default "//sequence_number.txt" id 0x1 set opcode 0x4 save opcode 0x5
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

  enum DIV4 : U8 {
    VEML6031_SIZE_4_4 = 0
    VEML6031_SIZE_1_4 = 1
  } default VEML6031_SIZE_4_4

  enum GAIN : U8 {
    VEML6031_GAIN_1 = 0
    VEML6031_GAIN_2 = 1
    VEML6031_GAIN_0_66 = 2
    VEML6031_GAIN_0_5 = 3
  } default VEML6031_GAIN_1

  enum IT : U8 {
    VEML6031_IT_3_125 = 0
    VEML6031_IT_6_25 = 1
    VEML6031_IT_12_5 = 2
    VEML6031_IT_25 = 3
    VEML6031_IT_50 = 4
    VEML6031_IT_100 = 5
    VEML6031_IT_200 = 6
    VEML6031_IT_400 = 7
  } default VEML6031_IT_3_125

  struct MagneticField {
    x: F64
    y: F64
    z: F64
    timestamp: Fw.TimeValue
  } default { x = 0.0, y = 0.0, z = 0.0, timestamp = { timeBase = TimeBase.TB_NONE, timeContext = 0, seconds = 0, useconds = 0 } }

  struct TimeData {
    Year: U32
    Month: U32
    Day: U32
    Hour: U32
    Minute: U32
    Second: U32
  } default { Year = 0, Month = 0, Day = 0, Hour = 0, Minute = 0, Second = 0 }

  enum WheelMode : I32 {
    DISABLED = 0
    TORQUE = 1
    SPEED = 2
  } default DISABLED

  port AlarmTriggered

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port AttitudeGet

  port CurrentGet -> F64

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port DipoleMomentGet

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port EphemerisGet

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port OrbitFrameGet

  port PowerGet -> F64

  port StartMagnetorquer(val: I8) -> Fw.Success

  port StopMagnetorquer -> Fw.Success

  port VoltageGet -> F64

  port WheelEnableSet(enable: bool) -> Fw.Success

  port WheelSpeedSet(speed: F64) -> Fw.Success

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port WheelStateGet

  port WheelTorqueSet(torque: F64) -> Fw.Success

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port lightGet

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port picoTemperatureGet

  @ fprime-lite: not F´ types in Python, left out here: the return value (Result)
  port temperatureGet
}

module Fw {
  port SuccessCondition(condition: Fw.Success)
}

module Os {
  enum FileStatus : I32 {
    OP_OK = 0
    DOESNT_EXIST = 1
    NO_SPACE = 2
    NO_PERMISSION = 3
    BAD_SIZE = 4
    NOT_OPENED = 5
    FILE_EXISTS = 6
    NOT_SUPPORTED = 7
    INVALID_MODE = 8
    INVALID_ARGUMENT = 9
    NO_MORE_RESOURCES = 10
    OTHER_ERROR = 11
  } default OP_OK
}

module Sim {
  enum SimDriverFault : U8 {
    NONE = 0
    NOT_READY = 1
    STUCK = 2
    STOP_FAILS = 3
    LATCHED = 4
  } default NONE

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

module Zephyr {
  enum LoRaBandwidth : U16 {
    BW_125_KHZ = 125
    BW_250_KHZ = 250
    BW_500_KHZ = 500
  } default BW_125_KHZ

  enum LoRaCodingRate : U8 {
    CR_4_5 = 1
    CR_4_6 = 2
    CR_4_7 = 3
    CR_4_8 = 4
  } default CR_4_5

  enum LoRaDataRate : U8 {
    SF_7 = 7
    SF_8 = 8
    SF_9 = 9
    SF_10 = 10
  } default SF_7

  enum LoRaMode : U8 {
    Transmit = 0
    Receive = 1
  } default Transmit

  enum TransmitState : U8 {
    ENABLED = 0
    DISABLED = 1
    DISABLING = 2
  } default ENABLED
}
