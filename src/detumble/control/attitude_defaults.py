"""Default settings of the three-mode attitude controller, in one place (plain values; no framework import).

The flight component (:class:`detumble.components.attitude_controller.AttitudeController`) takes
its parameter defaults from here, and the plant-only law that flies the same controller without
the framework (:mod:`detumble.sim.adcs_law`) starts from the same values, so a change here moves
both. The names are the flight parameters' own (ground-visible, hence upper case); units are those
of the parameters, as the ground reads them: rates in deg/s, angles in deg, torques in N·m,
momenta in N·m·s, dipoles in A·m², inertias in kg·m², times in s. Enumerated parameters are given
by their member names (the component maps them onto its enums). Why each value is what it is:
``docs/components/attitude_controller.md``.
"""

from __future__ import annotations

import math

__all__ = ["DEFAULTS", "PARAMETERS", "UNITS", "ENUM_CHOICES", "RATE_GROUP_PERIOD_S", "INTEGRAL_MAX_TORQUE",
           "BORESIGHT_B", "BDOT_PROVIDER_GAIN", "BDOT_MIN_FIELD_GAUSS"]

# --- pointing on the wheels (quaternion PD + integral) -----------------------------------------
K_P = 1.1e-3  # N·m: spring on q_err.v (ω_n 0.5 rad/s for 2.2e-3 kg·m²)
K_D = 2.0e-3  # N·m·s: damping (ζ ≈ 0.9)
K_I = 5.5e-5  # N·m/s: integral on q_err.v (0 turns it off)
INTEGRAL_WINDOW = 1.0  # deg: the integral runs only below this error
INTEGRAL_RATE_GATE = 0.05  # deg/s: >0: the integral runs only while the rate relative to the reference is below this
#                           (0.05: issue 27's default, docs/studies/robust_rates.md "The rate gate"; 0: no gate)
SLEW_RATE_LIMIT = 8.0  # deg/s: largest rate a slew commands
K_DUMP = 2.0e-3  # 1/s: magnetic momentum dumping while pointing on the wheels
WHEEL_MAX_TORQUE = 2.0e-3  # N·m per wheel
WHEEL_MAX_MOMENTUM = 4.0e-3  # N·m·s per wheel
POINTING_ACTUATOR = "ANY"  # ANY: wheels when they all answer, else the magnetorquers

# --- pointing on the magnetorquers alone -------------------------------------------------------
K_P_MAG = 4.0e-6  # N·m: spring ⟂ B
K_D_MAG = 4.0e-4  # N·m·s: damping ⟂ B
MAG_POINTING_LAW = "FIELD_STEERING"
MAG_STEER_RHO = 2.0  # along-field poles at ρ × the field line's rate
MAG_STEER_ZETA = 1.0  # their damping ratio
# ρ scheduled on the pointing error (magnetic_pointing.scheduled_rho): MAG_STEER_RHO up to MAG_STEER_RHO_FROM,
# MAG_STEER_RHO_LARGE from MAG_STEER_RHO_AT on, linear between; MAG_STEER_RHO_LARGE 0 (default): off
MAG_STEER_RHO_LARGE = 0.0  # ρ at large errors (0: no schedule)
MAG_STEER_RHO_FROM = 12.0  # deg: the schedule starts above this error
MAG_STEER_RHO_AT = 20.0  # deg: ... and reaches MAG_STEER_RHO_LARGE at this error
MAG_FIELD_RATE_BANDWIDTH = 0.05  # rad/s: the field-direction-rate estimator's bandwidth
MAG_FIELD_RATE_MIN = 5.0e-4  # 1/s: floor of |ḃ| in the law
MAG_SETTLE_TIME = 30.0  # s of known attitude before the coils point
MAG_RESIDUAL_MODE = "ESTIMATE"  # residual-dipole feed-forward: OFF, PARAMETER (MAG_RESIDUAL_DIPOLE_*) or ESTIMATE
MAG_RESIDUAL_DIPOLE_X = 0.0  # A·m², B: ground-calibrated residual dipole
MAG_RESIDUAL_DIPOLE_Y = 0.0  # A·m², B
MAG_RESIDUAL_DIPOLE_Z = 0.0  # A·m², B
MAG_RESIDUAL_WINDOW = 60.0  # s: the estimator's momentum-balance window
# The coils' hold as issue 27 chose it (docs/studies/magnetorquer_hold_after_acquisition.md, "The 50° switch on the
# full 100 draws"): the LQR scheduled on an on-board IGRF-14 of degree 6 below 50°, field steering above, the field
# taken from the on-board model through a 1 s bias estimate. MAG_LQR_ANGLE 0 and MAG_BIAS_TIME 0 fly the field
# steering alone on the raw reading (the default before 2026-12-05); a tilted-dipole plant wants degree 1.
MAG_BIAS_TIME = 1.0  # s: >0: while the coils are the pointing actuator (POINTING_ACTUATOR MAGNETORQUERS, or ANY
#                      without every wheel answering), the field the controller uses is the reading less an on-board
#                      bias estimate (the reading minus the on-board field model turned into B by q̂, low-passed at
#                      this time constant; three_mode._correct_mag_bias); with the wheels pointing, or 0: the reading
MAG_LQR_ANGLE = 50.0  # deg: >0: below this pointing error the coils' hold is the LQR scheduled on the on-board
#                       field model (control.magnetic_lqr; three_mode._model_lqr_torque), field steering above; 0: off
MAG_FIELD_MODEL_DEGREE = 6.0  # the on-board field model of MAG_BIAS_TIME and MAG_LQR_ANGLE: 1 the tilted dipole,
#                               2…13 IGRF-14 truncated to that degree (control.geomagnetic.OnboardField)

# --- moving targets (control.targets) ----------------------------------------------------------
GS_MIN_ELEVATION = 10.0  # deg: a ground station is tracked while it sees the spacecraft this high or higher
WHEEL_FEED_FORWARD = "REFERENCE"  # REFERENCE: I (α_r − ω × ω_r); REFERENCE_GYROSCOPIC: + ω × (I ω + h_w);
# REFERENCE_GYROSCOPIC_GRAVITY: + the modelled gravity-gradient torque cancelled (also on an inertial target)
RATE_BLEND_ANGLE = 0.1  # deg: above this pointing error (a slew) the rate observer pulls at RATE_BLEND_GAIN
RATE_BLEND_GAIN = 2.0  # 1/s: the observer's pull toward the gyro during a slew

# --- Sun-safe mode (control.sun_vector; the ADCS light sensors) --------------------------------
SUN_SAFE_AXIS = "PLUS_Z"  # the body axis SUN_SAFE turns to the Sun (BodyAxis: +Z, or the solar array's face)
SUN_SAFE_K_P = 2.0e-4  # N·m/rad: spring on the Sun-pointing angle (ω_n 0.3 rad/s for 2.2e-3 kg·m²)
SUN_SAFE_K_D = 1.2e-3  # N·m·s: damping on the body rate (ζ ≈ 0.9)
SUN_SAFE_K_P_MAG = 4.0e-6  # N·m/rad: the same on the magnetorquers alone (projected ⟂ B)
SUN_SAFE_K_D_MAG = 4.0e-4  # N·m·s
SUN_VECTOR_TIMEOUT = 10.0  # s: a Sun vector older than this (eclipse, failed sensors) is no Sun vector
SUN_SAFE_EXIT_DWELL = 10.0  # s of attitude knowledge before SUN_SAFE (entered on its loss) hands back to POINTING
SUN_SPIN_RATE = 3.0  # deg/s: the coils' Sun-safe spin about SUN_SAFE_AXIS (control.sun_safe.sun_spin_torque)
SUN_BIAS_TIME = 100.0  # s: time constant of SUN_SAFE's gyro-bias estimate from the Sun vector (SunRateBias)
# the coils' automatic spin-down: once the Sun-safe axis has been within SUN_HOLD_ANGLE of the Sun for SUN_HOLD_DWELL,
# SUN_SAFE ramps its spin to SUN_HOLD_SPIN_RATE (below the star tracker's 2 deg/s) until it is left (sun_safe.SunHold)
SUN_HOLD_ANGLE = 10.0  # deg: the Sun "held" within this of SUN_SAFE_AXIS (0: never lower the spin)
SUN_HOLD_DWELL = 300.0  # s the Sun must stay held, unbroken, before the spin is lowered
SUN_HOLD_SPIN_RATE = 1.5  # deg/s: the spin after it (the star tracker's limit is 2 deg/s in the adcs scenario)
SUN_HOLD_RAMP = 0.005  # deg/s²: how fast the spin command goes there (a step tips the axis: control.sun_safe.SunHold)
SUN_HOLD_FIELD_ANGLE = 80.0  # deg: the ramp advances only while the field is at least this far from SUN_SAFE_AXIS
SUN_HOLD_TIP_ANGLE = 0.0  # deg: >0: the ramp also advances outside that gate while its tip turns the axis toward the
# Sun and the Sun is at least this far ahead along it (sun_safe.SunHold; 0: only in the gate)

# --- detumble and spin -------------------------------------------------------------------------
K_BDOT = 3.0  # A·m²·s/G: the internal M = −k Ḃ when no dipole provider is connected
C_DAMP = 1.0e-4  # N·m·s: damper coefficient (seed c_damp)
I_D = 2.0e-4  # kg·m²: damper virtual inertia (seed I_d)
SPIN_LAW = "RATE_REGULATOR"
SPIN_RATE_TARGET = 1.5  # deg/s about body +Z (below the star tracker's 2 deg/s limit)
SPIN_K_TRANSVERSE = 2.0e-4  # N·m·s
SPIN_K_RATE = 2.0e-4  # N·m·s

# --- mode triggers -----------------------------------------------------------------------------
DETUMBLE_ENTER_RATE = 20.0  # deg/s: |ω| above this → DETUMBLE
DETUMBLE_EXIT_RATE = 1.0  # deg/s: |ω| below this for MODE_DWELL → SPIN_STABLE
MODE_DWELL = 5.0  # s
SPIN_AXIS_ENTER = 5.0  # deg: rate within this of +Z counts as stable
SPIN_AXIS_RESET = 8.0  # deg: beyond this the stability timer restarts
SPIN_RATE_ENTER = 0.05  # fraction of SPIN_RATE_TARGET
SPIN_RATE_RESET = 0.08  # fraction
SPIN_STABLE_DWELL = 60.0  # s of stable spin before POINTING
ATTITUDE_TIMEOUT = 90.0  # s on the gyro alone (no star-tracker fix) → no attitude knowledge

# --- attitude and rate estimation --------------------------------------------------------------
ESTIMATOR = "MEKF"
FILTER_KP = 0.5  # 1/s (complementary filter)
FILTER_KI = 0.02  # 1/s² (complementary filter)
#: deg/s, 1σ per axis of one gyro reading: LSM6DSO 0.0038 °/s/√Hz over 52 Hz, with the 70 mdps LSB/√12
GYRO_NOISE = math.hypot(0.0038 * math.sqrt(52.0), 0.070 / math.sqrt(12.0))
GYRO_BIAS_WALK = 1.0e-4  # deg/s/√s: MEKF bias random walk
GYRO_BIAS_SIGMA0 = 1.0  # deg/s: bias 1σ before any fix
TRACKER_NOISE_CROSS = 10.0  # arcsec 1σ across the boresight
TRACKER_NOISE_ABOUT = 70.0  # arcsec 1σ about the boresight
RATE_SOURCE = "OBSERVER"
RATE_OBSERVER_GAIN = 0.1  # 1/s: the observer's pull toward the gyro
RATE_OBSERVER_DIPOLE_TIME = 20.0  # s: >0: the observer learns the residual dipole (m̂ × B in its torque) with this
#                                   time constant while calm (rate_observer.RateObserver.learn_dipole); 0: off
#                                   (on by default since issue 27: docs/studies/robust_rates.md)
INERTIA_XX = 2.20e-3  # kg·m², the observer's model (matrix elements)
INERTIA_YY = 2.15e-3
INERTIA_ZZ = 2.05e-3
INERTIA_XY = 2.0e-5
INERTIA_XZ = -1.5e-5
INERTIA_YZ = 1.0e-5

# --- actuators and timing ----------------------------------------------------------------------
X_COIL_MAX_DIPOLE = 96 * 0.053 * 0.045 * 3.3 / 13.0  # A·m² per X coil at full drive (two X coils)
Y_COIL_MAX_DIPOLE = 96 * 0.053 * 0.045 * 3.3 / 13.0  # A·m² per Y coil (two Y coils)
Z_COIL_MAX_DIPOLE = 153 * math.pi * (0.05755 / 2) ** 2 * 3.3 / 150.7  # A·m², the single Z− coil
CYCLE_TICKS = 5  # rate-group ticks per control cycle (the coils are off on the last)

#: Every parameter default by its flight name: the upper-case names above this line (what follows is not a parameter).
DEFAULTS: dict[str, float | int | str] = {name: value for name, value in dict(globals()).items() if name.isupper()}

#: s: the period of the rate group that calls the controller (the deployments' 50 Hz group).
RATE_GROUP_PERIOD_S = 0.02
#: N·m: the largest torque the pointing integral may hold (not a parameter).
INTEGRAL_MAX_TORQUE = 1.0e-5
#: The body axis the star tracker looks along and SET_TARGET_DIRECTION points.
BORESIGHT_B = (0.0, 0.0, 1.0)
#: A·m²·s: the default gain of the BDotDetumble dipole provider (``m = −Gain·Ḃ/|B|``, B in gauss).
BDOT_PROVIDER_GAIN = 1.0
#: gauss: below this |B| the BDotDetumble provider computes no dipole.
BDOT_MIN_FIELD_GAUSS = 1e-6

#: Every parameter in the flight dictionary's order (its ids follow it): name → (units, low, high, finite), the
#: range a PRM_SET or the parameter file may give it (None: unbounded; finite: NaN and ±inf refused). Units as the
#: ground reads the value (the component declares them, ``Param(units=…)``; "" for an enumerated parameter, "1" for
#: a ratio).
PARAMETERS: dict[str, tuple[str, float | None, float | None, bool]] = {
    "K_P": ("N·m", None, None, False),
    "K_D": ("N·m·s", None, None, False),
    "K_I": ("N·m/s", None, None, False),
    "INTEGRAL_WINDOW": ("deg", None, None, False),
    "K_P_MAG": ("N·m", 0.0, 1.0e-3, False),
    "K_D_MAG": ("N·m·s", 0.0, 1.0e-2, False),
    "C_DAMP": ("N·m·s", None, None, False),
    "I_D": ("kg·m²", None, None, False),
    "K_BDOT": ("A·m²·s/G", None, None, False),
    "SPIN_LAW": ("", None, None, False),
    "SPIN_RATE_TARGET": ("deg/s", None, None, False),
    "SPIN_K_TRANSVERSE": ("N·m·s", None, None, False),
    "SPIN_K_RATE": ("N·m·s", None, None, False),
    "DETUMBLE_ENTER_RATE": ("deg/s", None, None, False),
    "DETUMBLE_EXIT_RATE": ("deg/s", None, None, False),
    "MODE_DWELL": ("s", None, None, False),
    "SPIN_AXIS_ENTER": ("deg", None, None, False),
    "SPIN_AXIS_RESET": ("deg", None, None, False),
    "SPIN_RATE_ENTER": ("1", None, None, False),
    "SPIN_RATE_RESET": ("1", None, None, False),
    "SPIN_STABLE_DWELL": ("s", None, None, False),
    "ATTITUDE_TIMEOUT": ("s", None, None, False),
    "SLEW_RATE_LIMIT": ("deg/s", None, None, False),
    "POINTING_ACTUATOR": ("", None, None, False),
    "K_DUMP": ("1/s", None, None, False),
    "WHEEL_MAX_TORQUE": ("N·m", None, None, False),
    "WHEEL_MAX_MOMENTUM": ("N·m·s", None, None, False),
    "FILTER_KP": ("1/s", None, None, False),
    "FILTER_KI": ("1/s²", None, None, False),
    "X_COIL_MAX_DIPOLE": ("A·m²", None, None, False),
    "Y_COIL_MAX_DIPOLE": ("A·m²", None, None, False),
    "Z_COIL_MAX_DIPOLE": ("A·m²", None, None, False),
    "CYCLE_TICKS": ("ticks", None, None, False),
    "ESTIMATOR": ("", None, None, False),
    "GYRO_NOISE": ("deg/s", 1e-6, 10.0, True),
    "GYRO_BIAS_WALK": ("deg/s/√s", 0.0, 1.0, True),
    "GYRO_BIAS_SIGMA0": ("deg/s", 1e-6, 10.0, True),
    "TRACKER_NOISE_CROSS": ("arcsec", 1e-3, 3600.0, True),
    "TRACKER_NOISE_ABOUT": ("arcsec", 1e-3, 3600.0, True),
    "RATE_SOURCE": ("", None, None, False),
    "RATE_OBSERVER_GAIN": ("1/s", 1e-4, 100.0, True),
    "INERTIA_XX": ("kg·m², body frame", 1e-6, 10.0, True),
    "INERTIA_YY": ("kg·m², body frame", 1e-6, 10.0, True),
    "INERTIA_ZZ": ("kg·m², body frame", 1e-6, 10.0, True),
    "INERTIA_XY": ("kg·m², body frame", -10.0, 10.0, True),
    "INERTIA_XZ": ("kg·m², body frame", -10.0, 10.0, True),
    "INERTIA_YZ": ("kg·m², body frame", -10.0, 10.0, True),
    "MAG_POINTING_LAW": ("", None, None, False),
    "MAG_STEER_RHO": ("1", 0.0, 10.0, False),
    "MAG_STEER_ZETA": ("1", 0.0, 5.0, False),
    "MAG_FIELD_RATE_BANDWIDTH": ("rad/s", 1.0e-3, 1.0, False),
    "MAG_FIELD_RATE_MIN": ("1/s", 1.0e-5, 1.0e-1, False),
    "MAG_SETTLE_TIME": ("s", 0.0, 3600.0, False),
    "MAG_RESIDUAL_MODE": ("", None, None, False),
    "MAG_RESIDUAL_DIPOLE_X": ("A·m², body frame", -0.05, 0.05, False),
    "MAG_RESIDUAL_DIPOLE_Y": ("A·m², body frame", -0.05, 0.05, False),
    "MAG_RESIDUAL_DIPOLE_Z": ("A·m², body frame", -0.05, 0.05, False),
    "MAG_RESIDUAL_WINDOW": ("s", 5.0, 600.0, False),
    "GS_MIN_ELEVATION": ("deg", 0.0, 90.0, False),
    "WHEEL_FEED_FORWARD": ("", None, None, False),
    "RATE_BLEND_ANGLE": ("deg", 0.0, 180.0, False),
    "RATE_BLEND_GAIN": ("1/s", 1e-4, 1000.0, True),
    "SUN_SAFE_AXIS": ("", None, None, False),
    "SUN_SAFE_K_P": ("N·m/rad", 0.0, 1.0e-2, True),
    "SUN_SAFE_K_D": ("N·m·s", 0.0, 1.0e-1, True),
    "SUN_SAFE_K_P_MAG": ("N·m/rad", 0.0, 1.0e-3, True),
    "SUN_SAFE_K_D_MAG": ("N·m·s", 0.0, 1.0e-2, True),
    "SUN_VECTOR_TIMEOUT": ("s", 0.1, 3600.0, True),
    "SUN_SAFE_EXIT_DWELL": ("s", 0.0, 3600.0, True),
    "SUN_SPIN_RATE": ("deg/s", 0.1, 10.0, True),
    "SUN_BIAS_TIME": ("s", 1.0, 3600.0, True),
    "SUN_HOLD_ANGLE": ("deg", 0.0, 90.0, True),
    "SUN_HOLD_DWELL": ("s", 0.0, 36000.0, True),
    "SUN_HOLD_SPIN_RATE": ("deg/s", 0.1, 10.0, True),
    "SUN_HOLD_RAMP": ("deg/s²", 1.0e-4, 1.0, True),
    "SUN_HOLD_FIELD_ANGLE": ("deg", 0.0, 89.0, True),
    "SUN_HOLD_TIP_ANGLE": ("deg", 0.0, 10.0, True),
    "INTEGRAL_RATE_GATE": ("deg/s", 0.0, 10.0, True),
    "MAG_STEER_RHO_LARGE": ("1", 0.0, 10.0, True),
    "MAG_STEER_RHO_FROM": ("deg", 0.0, 180.0, True),
    "MAG_STEER_RHO_AT": ("deg", 0.0, 180.0, True),
    "RATE_OBSERVER_DIPOLE_TIME": ("s", 0.0, 3600.0, True),
    "MAG_BIAS_TIME": ("s", 0.0, 1.0e5, True),
    "MAG_LQR_ANGLE": ("deg", 0.0, 180.0, True),
    "MAG_FIELD_MODEL_DEGREE": ("1", 1.0, 13.0, True),
}
#: Each parameter's units (the first column of :data:`PARAMETERS`).
UNITS: dict[str, str] = {name: row[0] for name, row in PARAMETERS.items()}

#: The member names each enumerated parameter accepts (those of the flight enums, in their order).
ENUM_CHOICES: dict[str, tuple[str, ...]] = {
    "SPIN_LAW": ("SEED_KANE_DAMPER", "VIRTUAL_DAMPER", "RATE_REGULATOR"),
    "POINTING_ACTUATOR": ("ANY", "WHEELS", "MAGNETORQUERS"),
    "ESTIMATOR": ("COMPLEMENTARY", "MEKF"),
    "RATE_SOURCE": ("GYRO", "OBSERVER"),
    "MAG_POINTING_LAW": ("SEED_PD", "FIELD_STEERING"),
    "MAG_RESIDUAL_MODE": ("OFF", "PARAMETER", "ESTIMATE"),
    "WHEEL_FEED_FORWARD": ("REFERENCE", "REFERENCE_GYROSCOPIC", "REFERENCE_GYROSCOPIC_GRAVITY"),
    "SUN_SAFE_AXIS": ("PLUS_X", "MINUS_X", "PLUS_Y", "MINUS_Y", "PLUS_Z", "MINUS_Z"),
}
