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
field line). One line per start and weight set; ``--json FILE`` also writes them as records, which
``tools/studies.py`` renders as the study's table (block ``magnetorquer_hold_lqr_weights_screen``).

``--field-errors``: instead, the direction error (deg) of the on-board field model
(``control.geomagnetic.OnboardField`` of degree 1, 6, 8, 10) against the IGRF-14 plant's field along the campaign's
first orbit (every 20 s): median, p95, max.

    python campaigns/adcs/magnetorquer_hold_lqr_weights.py --field-errors
"""

from __future__ import annotations

import argparse
import itertools
import json
import math
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "campaigns/adcs/scenarios/pointing_magnetorquers.yaml"
TARGET = (0.9238795325112867, 0.0, 0.3826834323650898, 0.0)
STEP_S = 1.4
DUTY = 0.8


def sweep_records(rate_scales, r_weights, alphas, starts=(0.0, 2000.0, 4000.0), theta_scales=(30.0,),
                  sets=None) -> list[dict]:
    """One record per start and weight set: the product of ``theta_scales`` (deg), ``rate_scales`` (rad/s),
    ``r_weights`` and ``alphas`` (1/s), or ``sets`` of ``(theta_scale_deg, rate_scale, r, alpha)`` when given; each
    ``{start_s, theta_scale_deg, rate_scale_rad_s, r, alpha_per_s, peak_deg, fall_median_s, fall_max_s,
    fall_field_line_s}``."""
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
    records = []
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
            records.append({"start_s": t0, "theta_scale_deg": th, "rate_scale_rad_s": ws, "r": r, "alpha_per_s": alpha,
                            "peak_deg": peak, "fall_median_s": float(np.median(falls)), "fall_max_s": max(falls),
                            "fall_field_line_s": falls[-1]})
    return records


def record_line(rec: dict) -> str:
    """One record as the line the sweep prints."""
    th = rec["theta_scale_deg"]
    theta = "" if th == 30.0 else f"θ scale {th:g}°, "
    return (f"start {rec['start_s']:.0f} s, {theta}rate scale {rec['rate_scale_rad_s']:g} rad/s, r {rec['r']:g}, "
            f"α {rec['alpha_per_s']:g} /s: peak {rec['peak_deg']:.0f}°, "
            f"fall to 15° median {rec['fall_median_s']:.0f} s, max {rec['fall_max_s']:.0f} s, "
            f"along the field line {rec['fall_field_line_s']:.0f} s")


def markdown(table: dict) -> str:
    """The ``--json`` file's table: a row per weight set (in the order flown), each figure at the starts in order,
    separated by " / ". Refuses a file whose weight sets were not each flown at the same starts."""
    starts = sorted({rec["start_s"] for rec in table["records"]})
    by_set: dict[tuple, dict] = {}
    for rec in table["records"]:
        key = (rec["theta_scale_deg"], rec["rate_scale_rad_s"], rec["r"], rec["alpha_per_s"])
        by_set.setdefault(key, {})[rec["start_s"]] = rec
    if not by_set:
        raise ValueError("no weight set flown")
    lines = ["| θ scale (deg) | rate scale (rad/s) | r | α (1/s) | peak (deg) | fall to 15°, median over the 9 axes "
             "(s) | at the worst axis (s) | along the field line (s) |", "|---|---|---|---|---|---|---|---|"]
    for (th, ws, r, alpha), at in by_set.items():
        if sorted(at) != starts:
            raise ValueError(f"weight set {th:g}/{ws:g}/{r:g}/{alpha:g} was not flown at every start {starts}")

        def row(name):
            return " / ".join(f"{at[t][name]:.0f}" for t in starts)  # noqa: B023 - used at once, in this pass

        lines.append(f"| {th:g} | {ws:g} | {r:g} | {alpha:g} | {row('peak_deg')} | {row('fall_median_s')} | "
                     f"{row('fall_max_s')} | {row('fall_field_line_s')} |")
    return "\n".join(lines) + "\n"


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
    ap.add_argument("--json", help="also write the sweep's records to this file (tools/studies.py renders it)")
    args = ap.parse_args(argv)
    if args.field_errors:
        for line in field_errors():
            print(line)
        return 0

    def floats(text):
        return [float(x) for x in text.split(",")]

    sets = [tuple(float(x) for x in s.split("/")) for s in args.sets.split(",")] if args.sets else None
    records = sweep_records(floats(args.rate_scales), floats(args.r_weights), floats(args.alphas),
                            theta_scales=floats(args.theta_scales), sets=sets)
    for rec in records:
        print(record_line(rec), flush=True)
    if args.json:
        out = pathlib.Path(args.json)
        tmp = out.with_suffix(out.suffix + ".tmp")
        tmp.write_text(json.dumps({"records": records}, indent=1) + "\n", encoding="utf-8")
        tmp.replace(out)  # written whole or not at all
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
