"""DRV2605 face-coil model: hand-computed numbers, mounting signs, L/R lag, level mapping."""

import math

import pytest

from detumble.sim.coils import (X_MINUS, X_PLUS, Y_MINUS, Y_PLUS, Z_MINUS, CoilSet, CoilSpec, Magnetorquer,
                                TorqueRods, default_coil_layout, level_for_coil_dipole)

AM2 = 1.0  # A m^2


def test_default_geometry_max_dipoles_hand_computed():
    """X/Y: 96 * (0.053*0.045) * 3.3/13 = 0.05812 A m^2; Z-: 153 * pi (0.05755/2)^2 * 3.3/150.7 = 0.008715 A m^2."""
    layout = default_coil_layout()
    assert sorted(layout) == [0, 1, 2, 3, 5]
    xy = 96 * (0.053 * 0.045) * (3.3 / 13)
    z = 153 * math.pi * (0.05755 / 2) ** 2 * (3.3 / 150.7)
    assert abs(xy - 0.0581206) < 1e-6 and abs(z - 0.0087151) < 1e-6  # the hand numbers themselves
    for face in (X_PLUS, X_MINUS, Y_PLUS, Y_MINUS):
        assert abs(layout[face].max_dipole_am2 - xy) < 1e-15 * AM2
    assert abs(layout[Z_MINUS].max_dipole_am2 - z) < 1e-15 * AM2
    assert CoilSet(layout).max_dipole_per_axis() == pytest.approx((2 * xy, 2 * xy, z), rel=1e-15)


def test_level_to_dipole_chain_and_mirrored_minus_faces():
    """level 64 on X+: V = 64/127*3.3 = 1.663 V, I = V/13 = 0.12792 A, m = 96*0.002385*I = +0.029289 A m^2 along +x."""
    coils = CoilSet(default_coil_layout())
    coils.set_level(X_PLUS, 64)
    i = 64 / 127 * 3.3 / 13
    assert abs(i - 0.1279225) < 1e-6
    m = 96 * 0.053 * 0.045 * i
    assert coils.dipole_B == pytest.approx((m, 0.0, 0.0), abs=1e-15)
    coils.set_level(X_PLUS, 0)
    coils.set_level(X_MINUS, 64)  # positive level on X- gives a -X dipole
    assert coils.dipole_B == pytest.approx((-m, 0.0, 0.0), abs=1e-15)
    coils.set_level(X_MINUS, -127)
    coils.set_level(Y_MINUS, 127)
    coils.set_level(Z_MINUS, 127)  # Z- positive -> -Z
    xy, z = 96 * 0.053 * 0.045 * 3.3 / 13, 153 * math.pi * 0.028775**2 * 3.3 / 150.7
    assert coils.dipole_B == pytest.approx((xy, -xy, -z), rel=1e-14)
    # the flight manager's pairing: X+ = L and X- = -L add up on +X
    coils.set_level(X_PLUS, 100)
    coils.set_level(X_MINUS, -100)
    assert coils.dipole_B[0] == pytest.approx(2 * 96 * 0.053 * 0.045 * 100 / 127 * 3.3 / 13, rel=1e-14)


def test_dipole_sum_follows_every_level_change_without_lag():
    """Without lag the total dipole is summed when read (one sum for several level changes): it
    must equal (==, the same floats) the per-coil dipoles summed in face order after every change,
    both as ``dipole_B`` and as what ``advance`` hands the integrator."""
    coils = CoilSet(default_coil_layout())

    def reference():
        mx = my = mz = 0.0
        for c in coils.coils.values():
            m = c.dipole_B()
            mx += m[0]
            my += m[1]
            mz += m[2]
        return (mx, my, mz)

    steps = [(X_PLUS, 64), (Y_MINUS, -90), (Z_MINUS, 127), (X_MINUS, -64), (Y_PLUS, 13), (X_PLUS, 64),
             (Z_MINUS, -5)]
    for k, (face, level) in enumerate(steps):
        coils.set_level(face, level)
        if k % 2 == 0:
            assert coils.advance(0.02) == reference()  # advance first (the plant's order) ...
            assert coils.dipole_B == reference()
        else:
            assert coils.dipole_B == reference()  # ... or read first (the magnetometer's)
            assert coils.advance(0.02) == reference()
    coils.set_level(Y_PLUS, 0)
    coils.set_level(X_PLUS, 0)  # two changes, one read
    assert coils.advance(0.02) == reference() != (0.0, 0.0, 0.0)


def test_level_validation_messages():
    coil = Magnetorquer(X_PLUS, CoilSpec())
    with pytest.raises(ValueError, match=r"drive level 128 outside -127\.\.127"):
        coil.set_level(128)
    with pytest.raises(TypeError, match=r"drive level must be an int in -127\.\.127, got 1\.5"):
        coil.set_level(1.5)
    with pytest.raises(ValueError, match=r"no coil on face 4; faces are X\+ 0, X- 1, Y\+ 2, Y- 3, Z- 5"):
        Magnetorquer(4, CoilSpec())
    with pytest.raises(ValueError, match=r"no coil on face 4; this spacecraft has faces \[0, 1, 2, 3, 5\]"):
        CoilSet(default_coil_layout()).set_level(4, 10)


def test_lr_time_constant_lag_and_mean_current():
    """L/R lag: after one tau the current is 1 - 1/e of the step; the mean over dt is exact."""
    spec = CoilSpec(inductance_h=0.13)  # tau = 0.13/13 = 10 ms
    coil = Magnetorquer(X_PLUS, spec)
    coil.set_level(127)
    assert coil.current_a == 0.0  # does not jump
    i_final = 3.3 / 13
    mean = coil.advance(0.01)
    assert coil.current_a == pytest.approx(i_final * (1 - math.exp(-1)), rel=1e-12)
    # mean of i_final (1 - e^{-t/tau}) over [0, tau] = i_final * (1 - (1 - e^-1)) = i_final / e
    assert mean == pytest.approx(i_final * math.exp(-1), rel=1e-12)
    for _ in range(100):
        coil.advance(0.01)
    assert coil.current_a == pytest.approx(i_final, rel=1e-12)


def test_level_for_dipole_keeps_flight_operation_order():
    """0.1 x 0.2 m coil: area 0.020000000000000004, so a 'half' request lands on 63, not 64."""
    spec = CoilSpec(turns=1.0, voltage_v=1.0, resistance_ohm=1.0, length_m=0.1, width_m=0.2)
    assert spec.area_m2 == 0.020000000000000004
    assert level_for_coil_dipole(spec, 0.5 * 0.02) == 63
    assert level_for_coil_dipole(spec, -0.5 * 0.02) == -63
    assert level_for_coil_dipole(spec, 10.0) == 127  # saturates
    assert level_for_coil_dipole(spec, -10.0) == -127


def test_plant_and_flight_coil_arithmetic_are_one_function():
    """COIL-ONE-001: the plant's drive level is the flight Magnetorquer's for every request,
    including 0.49999999999999994 of a level, where the plant's old floor(|x| + 0.5) said 1."""
    import random

    from detumble.control.coil_layout import DirectionSign, FLIGHT_XY_COIL, FLIGHT_Z_COIL
    from detumble.control.magnetorquer import Magnetorquer

    for geometry in (FLIGHT_XY_COIL, FLIGHT_Z_COIL):
        spec = CoilSpec.from_geometry(geometry)
        flight = Magnetorquer(turns=geometry.turns, voltage=geometry.voltage_v, resistance=geometry.resistance_ohm,
                              direction_sign=DirectionSign.POSITIVE, shape=geometry.shape, width=geometry.width_m,
                              length=geometry.length_m, diameter=geometry.diameter_m)
        rng = random.Random(4)
        for _ in range(2000):
            m = rng.uniform(-1.5, 1.5) * flight.max_dipole_moment()
            assert level_for_coil_dipole(spec, m) == flight.dipole_moment_to_current(m)
        per_level = flight.max_dipole_moment() / 127
        edge = 0.49999999999999994 * per_level
        assert level_for_coil_dipole(spec, edge) == flight.dipole_moment_to_current(edge)


def test_apply_dipole_splits_over_pairs_and_rods_clamp():
    coils = CoilSet(default_coil_layout())
    coils.apply_dipole_B((0.05, -0.03, 0.004))
    lv = coils.levels()
    assert lv[X_PLUS] == -lv[X_MINUS] > 0 and lv[Y_PLUS] == -lv[Y_MINUS] < 0 and lv[Z_MINUS] < 0
    assert coils.dipole_B == pytest.approx((0.05, -0.03, 0.004), abs=0.06 / 127)  # within one level per coil
    rods = TorqueRods((0.2, 0.2, 0.2))
    rods.apply_dipole_B((0.5, -0.1, -0.3))
    assert rods.dipole_B == (0.2, -0.1, -0.2)


def test_settled_lagged_coils_skip_the_lag_update_with_the_same_dipoles():
    """SIM-COIL-010: with an L/R lag, advance() skips the update once every current sits at its
    target - and returns exactly (==) the mean and present dipoles of the full update, step for
    step, through level changes that unsettle it again."""
    import dataclasses

    layout = {face: dataclasses.replace(spec, inductance_h=0.02) for face, spec in default_coil_layout().items()}
    fast, full = CoilSet(layout), CoilSet(layout)
    skipped = 0
    for k in range(400):
        if k in (0, 150, 151, 300):
            for coils in (fast, full):
                coils.set_level(X_PLUS, 40 + k % 7)
                coils.set_level(Z_MINUS, -90 if k < 300 else 0)
        skipped += fast._settled
        full._settled = False  # always the full lag update
        assert fast.advance(0.02) == full.advance(0.02), k
        assert fast.dipole_B == full.dipole_B, k
    assert skipped > 300  # the fast path was taken (the currents settle within a few steps)
