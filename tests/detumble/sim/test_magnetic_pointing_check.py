"""Plant-only magnetorquer pointing (detumble.sim.magnetic_pointing_check): the reproduction of seed 003's
failure and the convergence of the steering law on the adcs plant (ideal knowledge, continuous dipole,
residual dipole and gravity gradient on; 0.5 °/s start 45° from the target; one orbit at 0.2 s)."""

import pytest

from detumble.sim.magnetic_pointing_check import fly, main


def test_seed_projected_pd_does_not_converge_with_ideal_knowledge():
    """MAGPT-020: seed 003's projected PD with the old controller gains (K_P 2e-6 N·m, K_D 4e-4 N·m·s) keeps
    turning: median error over the orbit (after its first 10 %) above 60° — the failure is the law's, not
    the flight implementation's (no noise, no drive levels, no duty cycle here)."""
    med, _, _ = fly("seed_pd", 2.0e-6, 4.0e-4, dt_s=0.2).stats()
    assert med > 60.0


def test_field_steering_converges_on_the_plant():
    """MAGPT-021: the steering law with the controller's defaults (1e-6 N·m, 1e-4 N·m·s, ρ 2, ζ 0.7) converges on
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
