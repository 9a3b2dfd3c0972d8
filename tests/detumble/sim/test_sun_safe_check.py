"""SUNSAFE-001/002: SUN_SAFE in closed loop, plant-only (detumble.sim.sun_safe_check): the adcs plant from a 2 °/s
tumble with no star tracker, the six light sensors at 1 Hz with the stated noise."""

from __future__ import annotations

import statistics

from detumble.sim.sun_safe_check import POINTING_THRESHOLD_DEG, VECTOR_THRESHOLD_DEG, fly


def test_sun_safe_on_the_wheels_turns_plus_z_to_the_sun_from_a_tumble():
    """SUNSAFE-001: 300 s in sunlight (the adcs scenario's epoch starts sunlit): FORCE_MODE SUN_SAFE brings +Z within
    10° of the Sun within 60 s and keeps it there; every sunlit light-sensor Sun vector within 5° of the truth and
    none invalid. The last 100 s have a median error ≤ 1.8° and falling (0.6° by 500 s): the gyro bias across the
    Sun line is estimated from the Sun vector (control.sun_safe.SunRateBias); left out, it holds an offset
    K_D b⊥ / K_P = 2.2° (closed form)."""
    r = fly(1, duration_s=300.0)
    assert r.transitions[0][1:] == ("SUN_SAFE", "COMMAND")
    assert not any(r.eclipse)
    acq = r.acquisition_s()
    assert acq is not None and acq <= 60.0
    assert max(r.steady_sunlit()) <= POINTING_THRESHOLD_DEG
    assert statistics.median(r.pointing_deg[-100:]) <= 1.8
    assert r.vector_deg and max(r.vector_deg) <= VECTOR_THRESHOLD_DEG and r.vector_invalid_sunlit == 0


def test_sun_safe_turns_the_commanded_face():
    """SUNSAFE-002: SUN_SAFE_AXIS = MINUS_X (a solar face) is the one turned to the Sun (the error is measured on
    −X): the law does not just point +Z."""
    r = fly(2, duration_s=200.0, axis="MINUS_X")
    acq = r.acquisition_s()
    assert acq is not None and acq <= 60.0 and max(r.steady_sunlit()) <= POINTING_THRESHOLD_DEG


def test_sun_safe_on_the_magnetorquers_alone_acquires_by_spinning():
    """SUNSAFE-003: POINTING_ACTUATOR = MAGNETORQUERS, seed 1: the spinning Sun-safe law (control.sun_safe) brings +Z
    within 10° of the Sun in under 350 s of a 450 s sunlit flight from a 2 °/s tumble and keeps it there, spinning
    at about SUN_SPIN_RATE (the PD projected ⟂ B it replaced never acquired in an orbit)."""
    r = fly(1, duration_s=450.0, actuator="MAGNETORQUERS")
    acq = r.acquisition_s()
    assert acq is not None and acq <= 350.0
    assert max(r.steady_sunlit()) <= POINTING_THRESHOLD_DEG


def test_sun_safe_with_earth_albedo_flies_on_the_albedo_free_sun_vector():
    """SUNSAFE-004: the light sensors with the Earth's albedo (a = 0.3, the stated point-source model), 600 s from a
    2 °/s tumble on the wheels: with the on-board albedo model (control.albedo: TRIAD on the Sun vector and the
    magnetometer, the model's light subtracted) every sunlit Sun vector is within 5° of the truth, their median
    ≤ 1.5° (0.90° measured), and +Z holds the Sun at a median ≤ 2° (1.09°); without it the same flight's Sun
    vector has a median of 7.9° and +Z sits 8.0° off (docs/studies/sun_safe.md)."""
    from detumble.sim.sun_sensors import SunSensorSpec

    r = fly(1, duration_s=600.0, sensor_spec=SunSensorSpec(albedo=0.3), albedo_model=0.3)
    assert not any(r.eclipse) and r.vector_invalid_sunlit == 0
    assert max(r.vector_deg) <= VECTOR_THRESHOLD_DEG
    assert statistics.median(r.vector_deg) <= 1.5
    assert statistics.median(r.steady_sunlit()) <= 2.0


def test_albedo_model_option_refuses_a_bad_figure(capsys):
    """SUNSAFE-005: ``--albedo-model 1.5`` is refused (exit 2) with what to give, no traceback."""
    import pytest

    from detumble.sim.sun_safe_check import main

    with pytest.raises(SystemExit) as exc:
        main(["--albedo-model", "1.5"])
    assert exc.value.code == 2
    assert "Bond albedo in [0, 1)" in capsys.readouterr().err


def test_from_run_refuses_a_folder_without_a_run(tmp_path, capsys):
    """SUNSAFE-006: ``--from-run`` on a folder with no finished run is refused (exit 2), naming the missing files
    and what to give, no traceback."""
    import pytest

    from detumble.sim.sun_safe_check import main

    with pytest.raises(SystemExit) as exc:
        main(["--from-run", str(tmp_path)])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "no truth.csv or channels.csv there" in err and "fprime-lite run" in err


def test_coil_sun_safe_lowers_its_spin_below_the_tracker_limit_and_keeps_the_sun():
    """SUNSAFE-007: POINTING_ACTUATOR = MAGNETORQUERS, seed 1, 2500 s of the first sunlit part: once +Z has held the
    Sun within SUN_HOLD_ANGLE (10°) for SUN_HOLD_DWELL (300 s) the spin comes down on its own (measured at 520 s,
    acquisition 218 s), the true +Z stays within 10° of the Sun from then on (max 5.3° measured), and the body rate
    ends below the star tracker's 2 °/s (from 2361 s; 1.6 °/s at 2500 s). With SUN_HOLD_ANGLE 0 (no spin-down) the
    same flight's first 900 s never lower and end spinning at ~3 °/s, above the limit (docs/studies/sun_safe.md)."""
    r = fly(1, duration_s=2500.0, actuator="MAGNETORQUERS")
    assert not any(r.eclipse)
    assert r.spin_lowered_s is not None and 218.0 + 300.0 <= r.spin_lowered_s <= 600.0
    err, rate = r.after_spin_down()
    assert len(err) >= 1900 and max(err) <= POINTING_THRESHOLD_DEG
    assert max(rate[-20:]) < 2.0
    held = fly(1, duration_s=900.0, actuator="MAGNETORQUERS", params={"SUN_HOLD_ANGLE": 0.0})
    assert held.spin_lowered_s is None and min(held.rate_deg_s[-20:]) > 2.5


def test_param_option_refuses_a_bad_parameter(capsys):
    """SUNSAFE-008: ``--param`` without ``=``, with an unknown name, or outside the parameter's range (SUN_HOLD_ANGLE
    0…90°) is refused (exit 2), saying what to give, no traceback."""
    import pytest

    from detumble.sim.sun_safe_check import main

    for bad, says in ((["--param", "SUN_HOLD_ANGLE"], "give NAME=VALUE"),
                      (["--param", "SUN_HOLD=1"], "unknown attitude-controller parameter 'SUN_HOLD'"),
                      (["--param", "SUN_HOLD_ANGLE=200"], "outside its range 0.0…90.0 deg")):
        with pytest.raises(SystemExit) as exc:
            main(bad)
        assert exc.value.code == 2
        assert says in capsys.readouterr().err


def _made_up_flight():
    """Ten 1 s samples: sunlit 0–5 s, eclipse 6–7 s, sunlit 8–9 s; the spin lowered at 2 s."""
    from detumble.sim.sun_safe_check import SunSafeResult

    return SunSafeResult(times=[float(t) for t in range(10)],
                         pointing_deg=[20.0, 12.0, 8.0, 6.0, 4.0, 9.0, 50.0, 50.0, 30.0, 5.0],
                         eclipse=[False] * 6 + [True] * 2 + [False] * 2,
                         rate_deg_s=[3.0, 3.0, 2.5, 2.2, 1.9, 1.8, 1.8, 1.8, 1.8, 1.8], spin_lowered_s=2.0)


def test_spin_down_row_reads_the_figures_of_the_first_sunlit_part_after_the_spin_down():
    """SUNSAFE-040: ``spin_down_row`` on a made-up flight: first sunlit part 0–6 s, acquisition 2 s (above 10° at
    0 and 1 s), the error from the spin-down (2 s) to the part's end 8, 6, 4, 9° (median 7, p95 9, max 9, all within
    10°), the body rate below 2 °/s for good from 4 s (2.2 °/s at 3 s), two sunlit parts and no reacquisition in the
    second (30° at its first sample, above 10° to its last); the markdown row says so. With the spin lowered only
    after the first part, no figures after it; with the rate never below the limit, "never"."""
    from detumble.sim.sun_safe_check import spin_down_markdown, spin_down_row

    row = spin_down_row(1, _made_up_flight())
    assert row == {"seed": 1, "first_sunlit_part_s": (0.0, 6.0), "acquisition_s": 2.0, "spin_lowered_s": 2.0,
                   "after_deg": {"median": 7.0, "p95": 9.0, "max": 9.0}, "within": 1.0, "slow_from_s": 4.0,
                   "slow_never": False, "sunlit_parts": 2, "reacquisition_s": None}
    values = {"SUN_SPIN_RATE": 3.0, "SUN_HOLD_ANGLE": 10.0, "SUN_HOLD_DWELL": 300.0, "SUN_HOLD_SPIN_RATE": 1.5,
              "SUN_HOLD_RAMP": 0.005, "SUN_HOLD_FIELD_ANGLE": 80.0}
    assert "| 1 | 0–6 | 2 | 2 | 7.00 / 9.00 / 9.00 | 100.0 % | 4 | never |" in spin_down_markdown(
        {"rows": [row], "values": values})
    late = _made_up_flight()
    late.spin_lowered_s = 7.0
    row = spin_down_row(2, late)
    assert row["after_deg"] is None and row["within"] is None and row["slow_from_s"] is None and not row["slow_never"]
    fast = _made_up_flight()
    fast.rate_deg_s = [3.0] * 10
    row = spin_down_row(3, fast)
    assert row["slow_from_s"] is None and row["slow_never"]
