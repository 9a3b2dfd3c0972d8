"""Issue 27's magnetorquer hold: can ANY linear coil law make the slow fall from 30° fast enough? A periodic LQR bound.

    python campaigns/adcs/magnetic_lqr_bound.py \
        --json docs/studies/magnetorquer_hold_after_acquisition/lqr_bound.json     # ≈ 4 CPU-minutes

The linearised hold about the adcs_ref target (``detumble.analysis.magnetic_periodic_lqr``: ``θ̇ = ω``, ``J ω̇ = m ×
B(t)``, inertia × 1.25 for the coils' 80 % duty as in magnetorquer_hold_candidates.py) over one orbit of the campaign's
tilted dipole, :data:`SAMPLES` samples (the dipole held over each). For each weight ``r`` of the dipole (``R = r
diag(1/m_max²)``, ``Q = diag(I/(30°)², I/s_ω²)``, ``s_ω`` in :data:`W_SCALES`) and each α-shift, the periodic LQR's
gains (perfect knowledge of B(t)) and: the closed loop's slowest Floquet rate (1/s); the same gains computed from the
field seen through the scenario's LIS2MDL bias applied to the true field; the peak per-axis dipole over the coils'
capacity (``Plant.max_dipole_per_axis``) from a 30° error at rest in the worst direction, flown for two orbits from the
worst of :data:`PHASES` start phases, or the first step's from any sample if larger (exact over directions: the rows of
the gain times the transition's θ columns); the fall from 30° to 15° (the time after which ``|θ|`` stays ≤ 15°) of a
30° error at rest along the field line, per phase, with the true gains and with the biased ones; and the longest fall
over :data:`DIRECTIONS` directions and the field line. ``tools/studies.py --only magnetorquer_hold_lqr_bound`` renders
the block (:func:`markdown`).
"""

from __future__ import annotations

import argparse
import itertools
import json
import math
import pathlib
import sys

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
TARGET = (0.9238795325112867, 0.0, 0.3826834323650898, 0.0)
BIAS_G = (0.012, -0.008, 0.005)
#: samples of the orbit: the peak dipole at one weight (r 1e4, α 6e-3) was 0.96, 1.02, 1.58, 1.59 × the capacity at
#: 1000, 2000, 4000, 8000 samples (2026-12-04); the rates and falls agreed within 1 % from 1000 on
SAMPLES = 4000
PHASES = 12
DIRECTIONS = 12
THETA0 = math.radians(30.0)
W_SCALES = (0.01, 0.001)  # rad/s: the rate weight's scales
R_WEIGHTS = (1e-2, 1.0, 1e2, 1e4, 1e6)
ALPHAS = (0.0, 2e-3, 4e-3, 5e-3, 6e-3, 8e-3, 1.2e-2)
#: the page's target: a 200 s fall from a peak at 30° on a critically damped pair needs σ ≥ 1.678 / 200 s
SIGMA_TARGET = 1.678 / 200.0


def _directions(n: int) -> np.ndarray:
    """``n`` unit vectors spread over a hemisphere (a Fibonacci lattice; ±θ give the same |θ| in a linear loop)."""
    k = np.arange(n) + 0.5
    z = k / n
    phi = math.pi * (3.0 - math.sqrt(5.0)) * k
    s = np.sqrt(1.0 - z * z)
    return np.stack([s * np.cos(phi), s * np.sin(phi), z], axis=1)


def _falls(a_seq, b_seq, gains, h, x0) -> list[float | None]:
    """Per column of ``x0`` (θ rad; rate 0), flown from sample 0 of the (rotated) sequences for two periods: the time
    (s) after which ``|θ|`` stays ≤ 15° (None: still above at the end)."""
    n = len(a_seq)
    xs = np.vstack([x0, np.zeros_like(x0)])
    last_above = np.zeros(x0.shape[1])
    with np.errstate(all="ignore"):
        for j in range(2 * n):
            xs = a_seq[j % n] @ xs - b_seq[j % n] @ (gains[j % n] @ xs)
            above = ~(np.linalg.norm(xs[:3], axis=0) <= math.radians(15.0))
            last_above[above] = (j + 1) * h
    return [None if t >= 2 * n * h - 1e-9 else float(t) for t in last_above]


def _saturated_fall(a_seq, b_seq, gains, h, x0, m_max) -> float | None:
    """The fall (s) from ``x0`` (θ rad, rate 0) with the dipole scaled down, direction kept, to the capacity on every
    axis (the plant's ``scale_to_limits``): the linear law flown by the coils. None: above 15° after two periods."""
    n = len(a_seq)
    cap = np.asarray(m_max, dtype=float)
    x = np.concatenate([np.asarray(x0, dtype=float), np.zeros(3)])
    last = 0.0
    with np.errstate(all="ignore"):
        for j in range(2 * n):
            m = -gains[j % n] @ x
            m = m / max(1.0, float(np.max(np.abs(m) / cap)))
            x = a_seq[j % n] @ x + b_seq[j % n] @ m
            if not float(np.linalg.norm(x[:3])) <= math.radians(15.0):
                last = (j + 1) * h
    return None if last >= 2 * n * h - 1e-9 else last


def _peak_ratio(a_seq, b_seq, gains, m_max) -> float:
    """The largest per-axis dipole over the capacity from a 30° error at rest in the worst direction, flown from
    sample 0 for two periods: exact over directions (the norm of each row of the gain times θ's columns)."""
    cap = np.asarray(m_max, dtype=float)
    x = np.vstack([np.eye(3) * THETA0, np.zeros((3, 3))])
    worst = 0.0
    n = len(a_seq)
    for j in range(2 * n):
        km = gains[j % n] @ x
        worst = max(worst, float(np.max(np.linalg.norm(km, axis=1) / cap)))
        x = a_seq[j % n] @ x - b_seq[j % n] @ km
    return worst


def _rotate(seq, start: int) -> list:
    return list(seq[start:]) + list(seq[:start])


def _figures(a_seq, b_seq, gains, gains_law, m_max, h, field_hat) -> dict:
    """Over :data:`PHASES` start phases: the worst peak ratio (and the first step's at every sample); the fall of a
    30° error along the field line (per phase, with the true gains and with the gains seen through the bias); the
    worst fall over :data:`DIRECTIONS` and the field line."""
    n = len(a_seq)
    cap = np.asarray(m_max, dtype=float)
    # the first step's dipole from every sample (the flights below see 12 phases; the kick depends on the phase)
    first = max(float(np.max(np.linalg.norm(k[:, :3], axis=1) * THETA0 / cap)) for k in gains)
    out: dict = {"peak_ratio": first, "fall_field_s": [], "fall_field_bias_s": [], "fall_any_s": 0.0,
                 "fall_field_saturated_s": [], "fall_field_saturated_bias_s": []}
    spread = _directions(DIRECTIONS).T * THETA0
    for start in (round(i * n / PHASES) for i in range(PHASES)):
        a, b, k, kl = (_rotate(x, start) for x in (a_seq, b_seq, gains, gains_law))
        out["peak_ratio"] = max(out["peak_ratio"], _peak_ratio(a, b, k, m_max))
        along = field_hat[start][:, None] * THETA0
        out["fall_field_s"].append(_falls(a, b, k, h, along)[0])
        out["fall_field_bias_s"].append(_falls(a, b, kl, h, along)[0])
        out["fall_field_saturated_s"].append(_saturated_fall(a, b, k, h, along[:, 0], m_max))
        out["fall_field_saturated_bias_s"].append(_saturated_fall(a, b, kl, h, along[:, 0], m_max))
        falls = _falls(a, b, k, h, spread)
        if out["fall_any_s"] is not None:
            out["fall_any_s"] = None if None in falls else max(out["fall_any_s"], *falls)
    return out


def _present_law(plant, inertia, samples: int, h: float, field_hat) -> dict:
    """The field-steering law as flown (K_P_MAG 4e-6 N·m, K_D_MAG 4e-4 N·m·s, ρ 2, ζ 1; magnetic_floquet's
    linearisation, the torque request ⟂ B without the coils' limit) in the same sampled model: its slowest rate and the
    fall along the field per phase, with the field seen truly and through the bias."""
    from detumble.analysis.magnetic_floquet import closed_loop_matrix, field_line_along_orbit

    _, b, bd = field_line_along_orbit(plant, TARGET, samples=samples)
    _, bl, bdl = field_line_along_orbit(plant, TARGET, samples=samples, bias_t=[1e-4 * c for c in BIAS_G])
    out: dict = {}
    for key, law_b, law_bd in (("", b, bd), ("_bias", bl, bdl)):
        steps = []
        for k in range(samples):
            ah = h * closed_loop_matrix("field_steering", b[k], bd[k], inertia, 4e-6, 4e-4, rho=2.0, zeta=1.0,
                                        b_law=law_b[k], bd_law=law_bd[k])
            ah2 = ah @ ah
            steps.append(np.eye(6) + ah + ah2 / 2.0 + ah2 @ ah / 6.0 + ah2 @ ah2 / 24.0)  # RK4's step, A held
        zero_b, zero_k = [np.zeros((6, 3))] * samples, [np.zeros((3, 6))] * samples
        phi = np.eye(6)
        for step in steps:
            phi = step @ phi
        out["rate" + key] = math.log(max(abs(np.linalg.eigvals(phi)))) / (samples * h)
        out["fall_field" + key + "_s"] = [
            _falls(_rotate(steps, start), zero_b, zero_k, h, field_hat[start][:, None] * THETA0)[0]
            for start in (round(i * samples / PHASES) for i in range(PHASES))]
    return out


def compute(samples: int = SAMPLES, r_weights=R_WEIGHTS, alphas=ALPHAS, w_scales=W_SCALES) -> dict:
    from detumble.analysis.magnetic_periodic_lqr import (
        closed_loop_rate,
        field_vector_along_orbit,
        periodic_riccati_gains,
        sampled_double_integrator,
    )
    from detumble.sim.plant import Plant
    from detumble.sim.scenario import load_scenario

    plant = Plant(load_scenario("adcs", settings=["field.model=dipole"]))
    inertia = 1.25 * np.array(plant.scenario.spacecraft.inertia_kg_m2)
    m_max = np.array(plant.max_dipole_per_axis())
    period, field = field_vector_along_orbit(plant, TARGET, samples)
    _, seen = field_vector_along_orbit(plant, TARGET, samples, bias_t=[1e-4 * c for c in BIAS_G])
    h = period / samples
    true = [sampled_double_integrator(b, inertia, h) for b in field]
    law = [sampled_double_integrator(b, inertia, h) for b in seen]
    a_seq, b_seq = [t[0] for t in true], [t[1] for t in true]
    field_hat = field / np.linalg.norm(field, axis=1)[:, None]
    rows = []
    for w_scale, r, alpha in itertools.product(w_scales, r_weights, alphas):
        q = np.diag([1.0 / THETA0 ** 2] * 3 + [1.0 / w_scale ** 2] * 3)
        weight = r * np.diag(1.0 / m_max ** 2)
        row: dict = {"w_scale": w_scale, "r": r, "alpha": alpha}
        try:
            gains, _, periods = periodic_riccati_gains(a_seq, b_seq, q, weight, h, alpha)
            gains_law, _, _ = periodic_riccati_gains(a_seq, [t[1] for t in law], q, weight, h, alpha)
        except ArithmeticError as exc:
            row["error"] = str(exc)
            rows.append(row)
            continue
        biased = closed_loop_rate(a_seq, b_seq, gains_law, period)
        row.update({"periods": periods, "rate": closed_loop_rate(a_seq, b_seq, gains, period),
                    "rate_bias": biased if math.isfinite(biased) else None,
                    **_figures(a_seq, b_seq, gains, gains_law, m_max, h, field_hat)})
        rows.append(row)
        print({k: v for k, v in row.items() if "fall" not in k or k == "fall_any_s"}, file=sys.stderr, flush=True)
    present = _present_law(plant, inertia, samples, h, field_hat)
    print({"present": present}, file=sys.stderr, flush=True)
    return {"samples": samples, "period_s": period, "present": present, "m_max_am2": m_max.tolist(),
            "sigma_target": SIGMA_TARGET,
            "field_t_range": [float(np.min(np.linalg.norm(field, axis=1))),
                              float(np.max(np.linalg.norm(field, axis=1)))],
            "rows": rows}


def _sci(x: float) -> str:
    """``x`` as the pages write it (magnetorquer_hold_candidates.py's form: −3.04e-3)."""
    sys.path.insert(0, str(ROOT / "campaigns" / "adcs"))
    from magnetorquer_hold_candidates import _sci as sci

    return sci(x)


def _falls_cell(falls: list) -> str:
    """Median (max) over the phases (s); ``> 2 orbits`` for the phases that never stay below 15°."""
    kept = sorted(f for f in falls if f is not None)
    if len(kept) < len(falls):
        return f"> 2 orbits in {len(falls) - len(kept)} of {len(falls)}"
    mid = len(kept) // 2
    median = kept[mid] if len(kept) % 2 else 0.5 * (kept[mid - 1] + kept[mid])
    return f"{median:.0f} ({kept[-1]:.0f})"


def _rate_cell(rate) -> str:
    """A rate (1/s) as the candidates' table writes it: bold when it grows, ``grows past the floats`` for None."""
    sys.path.insert(0, str(ROOT / "campaigns" / "adcs"))
    from magnetorquer_hold_candidates import _e

    return _e(rate)


def summary(table: dict) -> dict:
    """The verdict's figures: the fastest rate within the capacity (peak ≤ 1), the shortest worst-phase fall along
    the field within it, and the least peak of a law whose worst-phase fall is ≤ 200 s (None: none)."""
    rows = [r for r in table["rows"] if "error" not in r]
    fits = [r for r in rows if r["peak_ratio"] <= 1.0]

    def worst(r):
        return math.inf if None in r["fall_field_s"] else max(r["fall_field_s"])

    def worst_of(key):
        return lambda r: math.inf if None in r[key] else max(r[key])

    fast = [r for r in rows if worst(r) <= 200.0]
    return {"fastest": min(fits, key=lambda r: r["rate"]) if fits else None,
            "shortest_fall": min(fits, key=worst) if fits else None,
            "fall_200": min(fast, key=lambda r: r["peak_ratio"]) if fast else None,
            "saturated": min(rows, key=worst_of("fall_field_saturated_s")) if rows else None,
            "saturated_bias": min(rows, key=worst_of("fall_field_saturated_bias_s")) if rows else None}


def _law(row: dict) -> str:
    """A law of the family by its weights, and its peak dipole."""
    return (f"rate scale {row['w_scale']:g}, r {row['r']:g}, α {row['alpha']:g}; peak {row['peak_ratio']:.2f} × the "
            "capacity")


def markdown(table: dict) -> str:
    m = table["m_max_am2"]
    lines = ["| rate weight's scale (rad/s) | dipole weight r | α-shift (1/s) | slowest rate (1/s) | with the bias "
             "| peak dipole / capacity, 30° at rest | fall 30° → 15° along the field (s): median (max) "
             "| with the bias | longest fall, 13 directions (s) "
             "| fall along the field, the dipole scaled to the capacity (s): median (max) | the same with the bias |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for row in table["rows"]:
        head = f"| {row['w_scale']:g} | {row['r']:g} | {row['alpha']:g}"
        if "error" in row:
            lines.append(f"{head} | no gain: {row['error']} | | | | | | | |")
            continue
        ratio = f"{row['peak_ratio']:.2f}"
        ratio = f"**{ratio}**" if row["peak_ratio"] <= 1.0 else ratio
        fall_any = "> 2 orbits" if row["fall_any_s"] is None else f"{row['fall_any_s']:.0f}"
        lines.append(f"{head} | {_rate_cell(row['rate'])} | {_rate_cell(row['rate_bias'])} | {ratio} | "
                     f"{_falls_cell(row['fall_field_s'])} | {_falls_cell(row['fall_field_bias_s'])} | {fall_any} | "
                     f"{_falls_cell(row['fall_field_saturated_s'])} | "
                     f"{_falls_cell(row['fall_field_saturated_bias_s'])} |")
    lo, hi = table["field_t_range"]
    lines += ["", f"Tilted dipole (the campaign's field, {lo * 1e6:.0f}–{hi * 1e6:.0f} µT), {table['samples']} samples "
              f"of the {table['period_s']:.0f} s orbit (the dipole held over each), inertia × 1.25; capacity "
              f"{m[0]:.3f}, {m[1]:.3f}, {m[2]:.4f} A·m² (x, y, z); {PHASES} start phases (the peak: also the "
              "first step's from every sample); bold peak: within the "
              "capacity; bold rate: grows. \"with the bias\": the gains solved from the field seen through the "
              "scenario's LIS2MDL bias, flown in the true field.", ""]
    s = summary(table)
    pr = table["present"]
    lines.append(f"- The present law (field steering, K_P_MAG 4e-6 N·m, K_D_MAG 4e-4 N·m·s, ρ 2, ζ 1, its torque "
                 f"request ⟂ B, no coil limit) in the same model: {_sci(pr['rate'])} /s ({_sci(pr['rate_bias'])} "
                 f"with the bias); its fall along the field {_falls_cell(pr['fall_field_s'])} s "
                 f"({_falls_cell(pr['fall_field_bias_s'])} with the bias).")
    f, g = s["fastest"], s["shortest_fall"]
    if f is not None:
        lines.append(f"- Fastest slowest-mode rate within the capacity: **{_sci(f['rate'])} /s** ({_law(f)}; "
                     f"{_rate_cell(f['rate_bias'])} /s with the bias); its fall along the field "
                     f"{_falls_cell(f['fall_field_s'])} s.")
        lines.append(f"- Shortest fall along the field within the capacity (worst phase): "
                     f"**{_falls_cell(g['fall_field_s'])} s** ({_law(g)}; rate {_sci(g['rate'])} /s).")
    f = s["fall_200"]
    if f is None:
        lines.append("- No law of the family falls from 30° to 15° along the field within 200 s at every phase.")
    else:
        lines.append(f"- A fall ≤ 200 s along the field at every phase first at **{f['peak_ratio']:.1f} × the "
                     f"capacity** ({_law(f)}; {_falls_cell(f['fall_field_s'])} s; "
                     f"with the bias {_falls_cell(f['fall_field_bias_s'])}, "
                     f"rate {_rate_cell(f['rate_bias'])} /s).")
    for key, label in (("saturated", "the true field"), ("saturated_bias", "the field seen through the bias")):
        f = s[key]
        if f is not None:
            lines.append(f"- Shortest fall along the field (worst phase) with the dipole scaled to the capacity, gains "
                         f"from {label}: **{_falls_cell(f['fall_field_' + key + '_s'])} s** ({_law(f)}).")
    return "\n".join(lines) + "\n"


#: the probe's weight (rate scale, r, α): recomputed and compared with the committed row
PROBE = (0.01, 1e4, 4e-3)


def probe(committed: dict) -> list[str]:
    """Recompute :data:`PROBE`'s row (≈ 5 CPU-s) and name the figures that differ from the committed ones by more
    than 1e-6 relative."""
    now = compute(committed["samples"], r_weights=(PROBE[1],), alphas=(PROBE[2],), w_scales=(PROBE[0],))["rows"][0]
    then = [r for r in committed["rows"] if (r["w_scale"], r["r"], r["alpha"]) == PROBE]
    if not then:
        return [f"no committed row for {PROBE}"]
    out = []
    for key in ("rate", "rate_bias", "peak_ratio", "fall_field_s", "fall_field_bias_s", "fall_any_s",
                "fall_field_saturated_s", "fall_field_saturated_bias_s"):
        a, b = np.array(now[key], dtype=float), np.array(then[0][key], dtype=float)
        if a.shape != b.shape or not np.allclose(a, b, rtol=1e-6, atol=0.0, equal_nan=True):
            out.append(f"{key} of {PROBE}: {then[0][key]} committed, {now[key]} now")
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--json", required=True, help="write the figures here")
    ap.add_argument("--samples", type=int, default=SAMPLES)
    args = ap.parse_args(argv)
    table = compute(args.samples)
    path = pathlib.Path(args.json)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(table, indent=1) + "\n", encoding="utf-8")
    print(markdown(table))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
