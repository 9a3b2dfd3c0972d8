"""Plant-only check of magnetorquer-only pointing laws: ideal knowledge, continuous dipole.

No flight software: each control period the law reads the true ``q_BN``, ``ω`` and field of a
:class:`~detumble.sim.plant.Plant`, and its dipole (coil-weighted projection ⟂ B, scaled to the coil
limits) is applied as ideal torque rods of the coils' per-axis capacity — no drive-level rounding, no
duty cycle, no magnetometer coupling. Environment torques (residual dipole, gravity gradient) stay as
the scenario has them. ``docs/studies/magnetic_pointing.md`` uses it to separate the law from the flight
implementation:

    python -m detumble.sim.magnetic_pointing_check --law seed_pd --kp 2e-6 --kd 4e-4
    python -m detumble.sim.magnetic_pointing_check --law field_steering --seeds 1,2,3
    # attitude hold from the hold campaign's worst corner, with the flight's duty, magnetometer bias, gyro noise
    python -m detumble.sim.magnetic_pointing_check --seeds 1..20 --rate 0.05 --offset 20 --settle 30 \
        --duty 0.8 --mag-bias 0.012 -0.008 0.005 --rate-noise 1.4e-4 --dt 0.2 [--compensate]

Reports the true pointing error (sampled every 10 s) as median / p95 / max after the first 10 % of
the run, the run summary's convention.
"""

from __future__ import annotations

import argparse
import math
import random
import sys
from dataclasses import dataclass

from detumble.control.magnetic import project_dipole_weighted, scale_to_limits
from detumble.control.magnetic_pointing import FieldDirectionRate, field_steering_torque
from detumble.control.pointing import pd_torque
from detumble.control.quaternion import Vec3, quat_from_axis_angle, quat_mul, rotate_n_to_b
from detumble.sim.coils import TorqueRods
from detumble.sim.plant import Plant
from detumble.sim.scenario import load_scenario

#: the adcs_ref start-up target: B turned 45° about N's y axis (q_TN, scalar first)
DEFAULT_TARGET = (0.9238795325112867, 0.0, 0.3826834323650898, 0.0)
LAWS = ("seed_pd", "field_steering")


@dataclass
class CheckResult:
    times_s: list[float]
    errors_deg: list[float]

    def stats(self) -> tuple[float, float, float]:
        """``(median, p95, max)`` in degrees after the first 10 % of the samples."""
        e = sorted(self.errors_deg[len(self.errors_deg) // 10:])
        return e[len(e) // 2], e[min(len(e) - 1, int(0.95 * len(e)))], e[-1]


def _unit(v):
    n = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    return (v[0] / n, v[1] / n, v[2] / n)


def fly(law: str, k_p: float, k_d: float, *, rho: float = 2.0, zeta: float = 0.7, seed: int = 1,
        rate_deg_s: float = 0.5, duration_s: float = 5580.0, dt_s: float = 0.1, scenario: str = "adcs",
        settings: tuple[str, ...] = (), target=DEFAULT_TARGET, sample_s: float = 10.0,
        offset_deg: float | None = None, settle_s: float = 0.0, mag_bias_t: Vec3 = (0.0, 0.0, 0.0),
        residual_ff_am2: Vec3 = (0.0, 0.0, 0.0), rate_axis: Vec3 | None = None, duty: float = 1.0,
        offset_axis: Vec3 | None = None, rate_noise_rad_s: float = 0.0) -> CheckResult:
    """Fly ``law`` (``seed_pd`` or ``field_steering``) from a ``rate_deg_s`` tumble about a random axis
    (drawn from ``seed``, or ``rate_axis``) toward the inertial ``target``.

    Start attitude: the identity (``offset_deg`` None), or — an attitude-hold start, as
    ``campaigns/adcs/hold_magnetorquers.yaml`` draws it — the target turned by ``offset_deg`` about a
    random axis (also drawn from ``seed``, or ``offset_axis``). ``settle_s``: coils off for that long first (the flight
    MAG_SETTLE_TIME). ``dt_s``: dynamics step and control period (s). ``settings``: extra scenario
    ``KEY=VALUE`` strings. The field-line rate ``db̂_N/dt`` is the true one (a 1 s backward difference of
    the field model) when ``mag_bias_t`` is zero; otherwise the law sees the field plus that constant
    body-frame bias (T) and estimates ``ḃ`` from it with the flight :class:`FieldDirectionRate`.
    ``residual_ff_am2``: a feed-forward dipole (A·m², B) subtracted from every command (residual-dipole
    compensation; the plant's own residual is ``spacecraft.residual_dipole_am2``). ``duty``: the coils'
    on-time share (the flight's (CYCLE_TICKS − 1)/CYCLE_TICKS = 0.8): the applied dipole is the command
    times it, as an average over the flight cycle. ``rate_noise_rad_s``: white noise (1σ per axis, rad/s)
    on the rate the law reads, one draw per control period (the flight's mean of five gyro readings is
    ≈ 2e-4 rad/s at 10 Hz).
    """
    if law not in LAWS:
        raise ValueError(f"law must be one of {', '.join(LAWS)}, got {law!r}")
    rng = random.Random(seed)
    axis = [rng.gauss(0.0, 1.0) for _ in range(3)] if rate_axis is None else list(rate_axis)
    q0 = (1.0, 0.0, 0.0, 0.0)
    if offset_deg is not None:
        off_axis = _unit((rng.gauss(0.0, 1.0), rng.gauss(0.0, 1.0), rng.gauss(0.0, 1.0)) if offset_axis is None
                         else offset_axis)
        q0 = quat_mul(target, quat_from_axis_angle(off_axis, math.radians(offset_deg)))
    base = [f"initial.rate.magnitude_deg_s={rate_deg_s}", "initial.rate.axis=[{},{},{}]".format(*axis),
            "initial.attitude.quaternion=[{},{},{},{}]".format(*q0), f"dynamics_step_s={dt_s}",
            "control.sense_settle_s=0", f"control.period_s={dt_s}"]
    sc = load_scenario(scenario, seed=seed, settings=base + list(settings))
    plant = Plant(sc, seed)
    plant.set_pointing_target(target)
    field = plant.field
    if field is None:
        raise ValueError(f"scenario {scenario!r} has no magnetic field: magnetorquer pointing needs one")
    m_max = plant.max_dipole_per_axis()
    plant.actuators = TorqueRods(m_max)  # continuous dipole of the coils' capacity
    every = max(1, int(round(sample_s / dt_s)))
    biased = any(c != 0.0 for c in mag_bias_t)
    fdr = FieldDirectionRate()
    noise = random.Random(seed + 7919)
    times, errors = [], []
    for k in range(int(round(duration_s / dt_s))):
        q, w, b = plant.q_BN, plant.omega_BN_B, plant.b_B
        if rate_noise_rad_s > 0.0:
            w = (w[0] + noise.gauss(0.0, rate_noise_rad_s), w[1] + noise.gauss(0.0, rate_noise_rad_s),
                 w[2] + noise.gauss(0.0, rate_noise_rad_s))
        if biased:
            b = (b[0] + mag_bias_t[0], b[1] + mag_bias_t[1], b[2] + mag_bias_t[2])
            bd_est = fdr.update(q, b, dt_s)
        if law == "seed_pd":
            tau, _ = pd_torque(target, q, w, k_p, k_d)
        else:
            if biased:
                bd = bd_est if bd_est is not None else (0.0, 0.0, 0.0)
            else:
                t = plant.t
                b1 = _unit(field.b_N(t, plant.orbit.position_N(t)))
                b0 = _unit(field.b_N(t - 1.0, plant.orbit.position_N(t - 1.0)))
                bd = rotate_n_to_b(q, (b1[0] - b0[0], b1[1] - b0[1], b1[2] - b0[2]))
            tau, _ = field_steering_torque(target, q, w, b, bd, k_p, k_d, rho, zeta)
        m, _ = project_dipole_weighted(tau, b, m_max)
        m = (m[0] - residual_ff_am2[0] / duty, m[1] - residual_ff_am2[1] / duty, m[2] - residual_ff_am2[2] / duty)
        if plant.t < settle_s:
            m = (0.0, 0.0, 0.0)
        m = scale_to_limits(m, m_max)
        plant.apply_dipole_B((m[0] * duty, m[1] * duty, m[2] * duty))
        if k % every == 0:
            times.append(plant.t)
            error = plant.pointing_error_rad()
            assert error is not None  # the target was set above
            errors.append(math.degrees(error))
        plant.step(dt_s)
    return CheckResult(times, errors)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m detumble.sim.magnetic_pointing_check",
                                 description=__doc__.split("\n")[0])
    ap.add_argument("--law", choices=LAWS, default="field_steering")
    ap.add_argument("--kp", type=float, default=4.0e-6, help="N·m (default 4e-6, K_P_MAG)")
    ap.add_argument("--kd", type=float, default=4.0e-4, help="N·m·s (default 4e-4, K_D_MAG)")
    ap.add_argument("--rho", type=float, default=2.0)
    ap.add_argument("--zeta", type=float, default=1.0)
    ap.add_argument("--seeds", default="1", help="comma-separated seeds, or FIRST..LAST (initial tumble axis)")
    ap.add_argument("--rate", type=float, default=0.5, help="initial rate, deg/s")
    ap.add_argument("--duration", type=float, default=5580.0, help="s")
    ap.add_argument("--offset", type=float, default=None,
                    help="deg: start this far from the target about a random axis (attitude hold), not at identity")
    ap.add_argument("--settle", type=float, default=0.0, help="s with the coils off first (MAG_SETTLE_TIME)")
    ap.add_argument("--mag-bias", type=float, nargs=3, default=(0.0, 0.0, 0.0), metavar=("X", "Y", "Z"),
                    help="gauss: constant magnetometer bias the law sees (its field-line rate then estimated)")
    ap.add_argument("--rate-noise", type=float, default=0.0,
                    help="rad/s, 1 sigma per axis and control period, on the rate the law reads (flight: ~2e-4)")
    ap.add_argument("--duty", type=float, default=1.0, help="coil on-time share (the flight's 0.8; default 1)")
    ap.add_argument("--compensate", action="store_true",
                    help="subtract the scenario's residual dipole from every command (exact feed-forward)")
    ap.add_argument("--dt", type=float, default=0.1, help="dynamics step and control period, s (default 0.1)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="scenario setting (repeatable)")
    a = ap.parse_args(argv)
    try:
        seeds = [int(s) for s in a.seeds.split(",")] if ".." not in a.seeds else \
            list(range(int(a.seeds.split("..")[0]), int(a.seeds.split("..")[1]) + 1))
    except ValueError:
        print(f"--seeds: expected comma-separated integers or FIRST..LAST, got {a.seeds!r}", file=sys.stderr)
        return 2
    rows = []
    ff = load_scenario("adcs", settings=list(a.set)).spacecraft.residual_dipole_am2 if a.compensate \
        else (0.0, 0.0, 0.0)
    for s in seeds:
        r = fly(a.law, a.kp, a.kd, rho=a.rho, zeta=a.zeta, seed=s, rate_deg_s=a.rate, duration_s=a.duration,
                dt_s=a.dt, settings=tuple(a.set), offset_deg=a.offset, settle_s=a.settle,
                mag_bias_t=tuple(1e-4 * c for c in a.mag_bias), residual_ff_am2=ff, duty=a.duty,
                rate_noise_rad_s=a.rate_noise)
        med, p95, mx = r.stats()
        rows.append((med, p95))
        print(f"{a.law} kp={a.kp:.3g} kd={a.kd:.3g} rho={a.rho:g} seed={s}: median {med:.2f} deg, "
              f"p95 {p95:.2f} deg, max {mx:.2f} deg, final {r.errors_deg[-1]:.2f} deg", flush=True)
    if len(rows) > 1:
        meds = sorted(m for m, _ in rows)
        p95s = sorted(p for _, p in rows)
        ok = sum(1 for m, p in rows if m <= 5.0 and p <= 15.0)
        print(f"over {len(rows)} seeds: run medians: median {meds[len(meds) // 2]:.2f} deg, worst {meds[-1]:.2f} deg; "
              f"run p95s: median {p95s[len(p95s) // 2]:.2f} deg, worst {p95s[-1]:.2f} deg; "
              f"{ok}/{len(rows)} runs meet median <= 5 and p95 <= 15 deg")
    return 0


if __name__ == "__main__":
    sys.exit(main())
