"""Plant-only magnetorquer pointing (detumble.sim.magnetic_pointing_check): the reproduction of seed 003's
failure and the convergence of the steering law on the adcs plant (ideal knowledge, continuous dipole,
residual dipole and gravity gradient on; 0.5 °/s start 45° from the target; one orbit at 0.2 s)."""

import pytest

from detumble.sim.magnetic_pointing_check import DEFAULT_TARGET, fly, main


def test_seed_projected_pd_does_not_converge_with_ideal_knowledge():
    """MAGPT-020: seed 003's projected PD with the old controller gains (K_P 2e-6 N·m, K_D 4e-4 N·m·s) keeps
    turning: median error over the orbit (after its first 10 %) above 60° — the failure is the law's, not
    the flight implementation's (no noise, no drive levels, no duty cycle here)."""
    med, _, _ = fly("seed_pd", 2.0e-6, 4.0e-4, dt_s=0.2).stats()
    assert med > 60.0


def test_field_steering_converges_on_the_plant():
    """MAGPT-021: the steering law with the previous controller defaults (1e-6 N·m, 1e-4 N·m·s, ρ 2, ζ 0.7) converges on
    the same plant: median ≤ 5° (issue 13's target) and the last sample below 5° (the floor, 2.6°, is the residual
    dipole's torque against K_P_MAG). Its p95 is set by how much of the initial momentum lies along B, which only
    the field's turning can remove: 15.8° for this draw, under 20° asserted (the study gives the spread)."""
    r = fly("field_steering", 1.0e-6, 1.0e-4, rho=2.0, zeta=0.7, dt_s=0.2)
    med, p95, _ = r.stats()
    assert med <= 5.0
    assert p95 < 20.0
    assert r.errors_deg[-1] < 5.0


def test_cli_reports_bad_seeds_without_a_traceback(capsys):
    """MAGPT-022: --seeds that are not integers: exit 2 and a message naming the option."""
    assert main(["--seeds", "one"]) == 2
    assert "--seeds" in capsys.readouterr().err


def test_unknown_law_is_refused():
    """MAGPT-022: fly() refuses a law it does not know, naming the known ones."""
    with pytest.raises(ValueError, match="field_steering"):
        fly("bdot", 1.0, 1.0, duration_s=1.0)


HOLD = dict(rate_deg_s=0.05, offset_deg=20.0, settle_s=30.0, mag_bias_t=(1.2e-6, -0.8e-6, 0.5e-6), dt_s=0.2,
            duty=0.8, rate_noise_rad_s=1.4e-4, seed=9)


def test_attitude_hold_from_the_worst_corner_meets_the_target():
    """MAGPT-023: the hold campaign's worst corner on the plant — 20° from the target at 0.05 °/s (seed 9: the worst
    p95 of 20 such draws with the previous gains), the coils' 80 % duty, the LIS2MDL bias in the field the law sees
    (its ḃ from the flight estimator), rate noise 1.4e-4 rad/s, coils off for the 30 s settle. The defaults (4e-6 N·m,
    4e-4 N·m·s, ρ 2, ζ 1) give median 1.50°, p95 5.06° (asserted ≤ 5° and ≤ 15°, and p95 below the previous
    defaults' 14.3° by more than 5°); with the residual dipole compensated exactly the last sample is 0.30°
    (asserted < 1°; the previous defaults end at 3.8°, the residual torque against K_P_MAG 1e-6)."""
    new = fly("field_steering", 4.0e-6, 4.0e-4, rho=2.0, zeta=1.0, **HOLD)
    old = fly("field_steering", 1.0e-6, 1.0e-4, rho=2.0, zeta=0.7, **HOLD)
    med, p95, _ = new.stats()
    assert med <= 5.0 and p95 <= 15.0
    assert p95 < old.stats()[1] - 5.0
    assert old.errors_deg[-1] > 2.0
    comp = fly("field_steering", 4.0e-6, 4.0e-4, rho=2.0, zeta=1.0, residual_ff_am2=(1.0e-3, -5.0e-4, 8.0e-4), **HOLD)
    assert comp.errors_deg[-1] < 1.0


def test_the_floor_with_compensation_is_the_gravity_gradient_along_the_field():
    """MAGPT-024: with the residual dipole compensated exactly (and no magnetometer bias), what is left is the
    gravity-gradient torque's component along b̂, which only the soft along-field stiffness J r² meets
    (closed form ``α = −τ∥/(J r²)``, 0–1.45° over the orbit for this body at this target in IGRF-14, the scenario's
    field, 0.17–0.93° in the tilted dipole: magnetic_floquet.along_field_offset_from_gravity_gradient,
    docs/studies/magnetic_pointing/floor.json). The plant's error after 2000 s follows it: its largest value within
    20 % of the closed form's (measured 1.36° vs 1.45° in IGRF-14; 0.96° vs 0.93° in the dipole); with gravity
    gradient off the median is below 0.05° (measured 0.001°)."""
    import numpy as np

    from detumble.analysis.magnetic_floquet import along_field_offset_from_gravity_gradient
    from detumble.sim.plant import Plant
    from detumble.sim.scenario import load_scenario

    kw = dict(rate_deg_s=0.02, offset_deg=10.0, settle_s=30.0, dt_s=0.2, duty=0.8, seed=3,
              residual_ff_am2=(1.0e-3, -5.0e-4, 8.0e-4))
    with_gg = fly("field_steering", 4.0e-6, 4.0e-4, rho=2.0, zeta=1.0, **kw)
    _, alpha = along_field_offset_from_gravity_gradient(Plant(load_scenario("adcs")), DEFAULT_TARGET)
    late = max(e for t, e in zip(with_gg.times_s, with_gg.errors_deg, strict=True) if t >= 2000.0)
    assert late == pytest.approx(float(np.degrees(np.max(np.abs(alpha)))), rel=0.2)
    without = fly("field_steering", 4.0e-6, 4.0e-4, rho=2.0, zeta=1.0, settings=("spacecraft.gravity_gradient=false",),
                  **kw)
    assert without.stats()[0] < 0.05
