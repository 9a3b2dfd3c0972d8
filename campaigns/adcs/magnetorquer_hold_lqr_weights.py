"""Issue 27's hold scheduled on the on-board field model: the LQR weights on the linearised hold (numpy; analysis only).

    python campaigns/adcs/magnetorquer_hold_lqr_weights.py                      # ≈ 1 CPU-minute a weight set
    python campaigns/adcs/magnetorquer_hold_lqr_weights.py --rate-scales 0.01 --r-weights 1 --alphas 0.008
    python campaigns/adcs/magnetorquer_hold_lqr_weights.py --sets 30/0.03/1/0.002,20/0.03/1/0.002   # θ/ω/r/α

For each weight set (rate scale ``s_ω`` rad/s, dipole weight ``r``, α-shift 1/s; θ scale 30°) and each of three start
times along the orbit (0, 2000, 4000 s), the gains of ``control.magnetic_lqr.hold_gains`` over two orbits of the
campaign's tilted dipole turned into the adcs_ref target frame (1.4 s steps, inertia / 0.8 for the coils' duty), and
the linear hold (``analysis.magnetic_periodic_lqr.sampled_double_integrator``, the dipole scaled down to the coils'
capacity, direction kept) flown for 3000 s from 30° at rest about 8 random axes and the field line: the largest error
reached (deg; "peak") and the time after which the error stays ≤ 15° (s; median, max over the 9 axes, and along the
field line). One line per start and weight set.

``--field-errors``: instead, the direction error (deg) of the on-board field model
(``control.geomagnetic.OnboardField`` of degree 1, 6, 8, 10) against the IGRF-14 plant's field along the campaign's
first orbit (every 20 s): median, p95, max.

    python campaigns/adcs/magnetorquer_hold_lqr_weights.py --field-errors
"""

from __future__ import annotations

import argparse
import itertools
import math
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "campaigns/adcs/scenarios/pointing_magnetorquers.yaml"
TARGET = (0.9238795325112867, 0.0, 0.3826834323650898, 0.0)
STEP_S = 1.4
DUTY = 0.8


def sweep(rate_scales, r_weights, alphas, starts=(0.0, 2000.0, 4000.0), theta_scales=(30.0,),
          sets=None) -> list[str]:
    """One line per start and weight set: the product of ``theta_scales`` (deg), ``rate_scales`` (rad/s),
    ``r_weights`` and ``alphas`` (1/s), or ``sets`` of ``(theta_scale_deg, rate_scale, r, alpha)`` when given."""
    import numpy as np

    from detumble.analysis.magnetic_periodic_lqr import sampled_double_integrator
    from detumble.control.magnetic_lqr import hold_gains
    from detumble.control.quaternion import rotate_n_to_b
    from detumble.sim.plant import Plant
    from detumble.sim.scenario import load_scenario

    sc = load_scenario(str(SCENARIO), seed=1)
    plant = Plant(sc)
    inertia = np.array(sc.spacecraft.inertia_kg_m2) / DUTY
    m_max = np.array(plant.max_dipole_per_axis())
    axes = np.random.default_rng(0).normal(size=(8, 3))
    axes /= np.linalg.norm(axes, axis=1)[:, None]
    period = 2.0 * math.pi / plant.orbit.mean_motion
    lines = []
    for t0 in starts:
        n = int(2 * period / STEP_S)
        fields = [rotate_n_to_b(TARGET, plant.field.b_N(t0 + k * STEP_S, plant.orbit.position_N(t0 + k * STEP_S)))
                  for k in range(n)]
        steps = [sampled_double_integrator(b, inertia, STEP_S) for b in fields]
        line = np.array(fields[0]) / np.linalg.norm(fields[0])
        for th, ws, r, alpha in sets or itertools.product(theta_scales, rate_scales, r_weights, alphas):
            gains = hold_gains(fields, inertia.tolist(), STEP_S, tuple(m_max), math.radians(th), ws, r, alpha)
            peak, falls = 0.0, []
            for axis in [*axes, line]:
                x = np.concatenate([math.radians(30.0) * axis, np.zeros(3)])
                last = 0.0
                for k in range(int(3000.0 / STEP_S)):
                    a, b = steps[k]
                    m = -np.array(gains[k]).reshape(3, 6) @ x  # the gain's 18 floats row by row
                    m = m / max(1.0, float(np.max(np.abs(m) / m_max)))
                    x = a @ x + b @ m
                    err = math.degrees(float(np.linalg.norm(x[:3])))
                    peak = max(peak, err)
                    if err > 15.0:
                        last = (k + 1) * STEP_S
                falls.append(last)
            theta = "" if th == 30.0 else f"θ scale {th:g}°, "
            lines.append(f"start {t0:.0f} s, {theta}rate scale {ws:g} rad/s, r {r:g}, α {alpha:g} /s: "
                         f"peak {peak:.0f}°, "
                         f"fall to 15° median {float(np.median(falls)):.0f} s, max {max(falls):.0f} s, "
                         f"along the field line {falls[-1]:.0f} s")
    return lines


def field_errors(degrees=(1, 6, 8, 10)) -> list[str]:
    from detumble.control.geomagnetic import OnboardField
    from detumble.sim.plant import Plant
    from detumble.sim.scenario import load_scenario

    sc = load_scenario(str(SCENARIO), seed=1, settings=["field.model=igrf14", "field.table_step_s=10"])
    plant = Plant(sc)
    lines = []
    for degree in degrees:
        model, errors = OnboardField(degree), []
        for t in range(0, 5580, 20):
            r = plant.orbit.position_N(t)
            truth = plant.field.b_N(t, r)
            b = model(r, sc.earth_angle0_rad + sc.field.earth_rotation_rate_rad_s * t)
            c = sum(x * y for x, y in zip(truth, b, strict=True)) / math.hypot(*truth) / math.hypot(*b)
            errors.append(math.degrees(math.acos(max(-1.0, min(1.0, c)))))
        errors.sort()
        lines.append(f"degree {degree}: direction error median {errors[len(errors) // 2]:.2f}°, "
                     f"p95 {errors[int(0.95 * len(errors))]:.2f}°, max {errors[-1]:.2f}°")
    return lines


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rate-scales", default="0.03,0.01", help="rad/s, comma-separated (default 0.03,0.01)")
    ap.add_argument("--r-weights", default="1", help="comma-separated (default 1)")
    ap.add_argument("--alphas", default="0,0.002,0.008", help="1/s, comma-separated (default 0,0.002,0.008)")
    ap.add_argument("--theta-scales", default="30", help="deg, comma-separated (default 30)")
    ap.add_argument("--sets", help="instead of the product: weight sets 'θ deg/rate rad/s/r/α 1/s', comma-separated")
    ap.add_argument("--field-errors", action="store_true", help="the on-board model's direction error instead")
    args = ap.parse_args(argv)
    if args.field_errors:
        for line in field_errors():
            print(line)
        return 0

    def floats(text):
        return [float(x) for x in text.split(",")]

    sets = [tuple(float(x) for x in s.split("/")) for s in args.sets.split(",")] if args.sets else None
    for line in sweep(floats(args.rate_scales), floats(args.r_weights), floats(args.alphas),
                      theta_scales=floats(args.theta_scales), sets=sets):
        print(line, flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
