"""The Floquet maps the study pages quote are converged in the orbit's samples (issue 27/28): MAGPT-080, MAGPT-081.

The map holds ``A`` over each sample and takes ḃ from differences, so it errs by O(1/samples); the pages' count is
``FLOQUET_SAMPLES`` of campaigns/adcs/magnetic_pointing_tables.py (200 until 2026-12-04, not converged)."""

import importlib.util
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[3]


def _load(name):
    spec = importlib.util.spec_from_file_location(name, ROOT / "campaigns" / "adcs" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_maps_sample_count_is_converged_on_doubling():
    """MAGPT-080: the present gains' slowest rate in the tilted dipole, the law seeing the scenario's bias and twice
    it (the slowest-converging case: 0.79 % from 8000 to 16000 samples), moves within spec/control.md's rule
    (< 0.5 %, or a move < MARGINAL_RATE, 2e-6 /s) from FLOQUET_SAMPLES to twice it; at 200 samples (the old maps)
    it does not (the 2 × bias rate is −2.39e-3 /s there, +9.2e-4 /s converged)."""
    tables = _load("magnetic_pointing_tables")
    kp, kd, rho, zeta = tables.GAINS["present"]
    n = tables.FLOQUET_SAMPLES
    at_n = tables.floquet_row("dipole", kp, kd, rho, zeta, factors=(1.0, 2.0), samples=n)
    at_2n = tables.floquet_row("dipole", kp, kd, rho, zeta, factors=(1.0, 2.0), samples=2 * n)
    assert all(tables.converged(a, b) for a, b in zip(at_n, at_2n, strict=True)), (at_n, at_2n)
    old = tables.floquet_row("dipole", kp, kd, rho, zeta, factors=(2.0,), samples=200, substeps=4)
    assert not tables.converged(old[0], at_2n[1])


def test_the_hold_reports_slow_rate_is_the_converged_map():
    """MAGPT-081: the slow pair's rate σ the hold report's tail band uses (report_pointing_plant's
    FLOQUET_SLOW_RATE_PER_S) is the converged map's slowest decay with the scenario's bias in the tilted dipole (the
    campaign's field) within 0.5 % (3.04e-3 /s from the 200-sample map was 16 % fast)."""
    tables = _load("magnetic_pointing_tables")
    report = _load("report_pointing_plant")
    (rate,) = tables.floquet_row("dipole", *tables.GAINS["present"], factors=(1.0,))
    assert abs(report.FLOQUET_SLOW_RATE_PER_S + rate) < 0.005 * abs(rate)
