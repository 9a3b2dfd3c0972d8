"""Where along the orbit the coils can lower the Sun-safe spin: the angle between the geomagnetic field and the Sun
line (no framework; no attitude flown).

The coils' spin-down (``control.sun_safe.SunHold``) moves its command only while the field is at least
SUN_HOLD_FIELD_ANGLE from the spin axis â. Once the Sun is held, â is within SUN_HOLD_ANGLE (10°) of the Sun, which
is inertially fixed over an orbit, so the gate is open when ``β(t) = ∠(B_N(t), ±ŝ_N)`` (the field along the orbit
against the Sun line, folded to 0–90°) is at or above the gate: a property of the orbit, the field model and the
epoch, not of the seed. :func:`geometry` samples it once a second over one orbit of a scenario; the spin command then
moves ``ramp`` °/s per second of open gate, so from a spin-down starting at ``t0`` it reaches a rate ``ω`` after
``(ω_acquire − ω) / ramp`` s of open gate (:func:`reach_time`): the time the gate is open, not the ramp, sets how
long the spin-down takes.

Why a gate at all (closed form): a coil torque is ⟂ B, so the least torque with the component ``τ_a`` along â is
``τ_a (â − cos β B̂) / sin² β``, whose part across â is ``τ_a cot β`` along ``−sign(cos β) B̂⊥â``. The Sun-pointing
term can only tip â about the one direction ⟂ both â and B (``â × B̂``), which is ⟂ that tip: the tip the spin change
makes cannot be taken out until the field turns. Hence the gate (``cot 80° = 0.18``: a spin change of ΔH tips the
momentum by at most 0.18 ΔH) rather than a weighting.

``python -m detumble.sim.spin_down_geometry [--scenario adcs] [--gates 60,70,75,80,85] [--starts 520,1958,...]
[--json FILE]`` prints the tables of ``docs/studies/sun_safe.md`` ("Why the spin-down waits") from one pass over
the orbit (~10 s of CPU); :func:`markdown` renders them from the JSON.
"""

from __future__ import annotations

import argparse
import json
import math

from detumble.sim.epoch import julian_date
from detumble.sim.plant import build_field, build_orbit
from detumble.sim.scenario import load_scenario
from detumble.sim.sun import in_umbra, sun_direction_N
from detumble.sim.sun_safe_check import SunSafeResult

__all__ = ["geometry", "reach_time", "windows", "markdown", "main"]

#: The spin-down's defaults as flown (control.attitude_defaults): acquisition and hold spin (deg/s), ramp (deg/s²),
#: and the star tracker's rate limit in the adcs scenario (deg/s).
ACQUIRE_DEG_S, HOLD_DEG_S, RAMP_DEG_S2, TRACKER_LIMIT_DEG_S = 3.0, 1.5, 0.005, 2.0


def _angle_deg(a, b) -> float:
    na = math.sqrt(sum(c * c for c in a))
    nb = math.sqrt(sum(c * c for c in b))
    d = sum(x * y for x, y in zip(a, b, strict=True)) / (na * nb)
    return math.degrees(math.acos(max(-1.0, min(1.0, d))))


def geometry(scenario: str = "adcs", duration_s: float = 5580.0, step_s: float = 1.0) -> dict:
    """``{"t": [s], "beta_deg": [deg], "eclipse": [bool], "field_ut": [µT]}`` over ``duration_s``: β the angle
    between the field and the Sun line folded to 0–90° (90°: the field across the Sun line, the gate fully open), the
    eclipse the cylindrical shadow (the light sensors' default), |B| the field's magnitude."""
    sc = load_scenario(scenario)
    orbit = build_orbit(sc)
    field = build_field(sc, orbit)
    if field is None:
        raise ValueError(f"scenario {scenario!r} has no field model")
    jd0 = julian_date(sc.epoch)
    out: dict = {"t": [], "beta_deg": [], "eclipse": [], "field_ut": []}
    for k in range(int(round(duration_s / step_s)) + 1):
        t = k * step_s
        r = orbit.position_N(t)
        s = sun_direction_N(jd0 + t / 86400.0)[0]
        b = field.b_N(t, r)
        beta = _angle_deg(b, s)
        out["field_ut"].append(1e6 * math.sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]))
        out["t"].append(t)
        out["beta_deg"].append(min(beta, 180.0 - beta))
        out["eclipse"].append(in_umbra(r, s, sc.orbit.earth_radius_m))
    return out


def windows(geo: dict, gate_deg: float, start_s: float = 0.0, end_s: float = math.inf) -> list[tuple[float, float]]:
    """The ``(start, end)`` s stretches in ``[start_s, end_s)`` with β ≥ ``gate_deg``."""
    out, opened = [], None
    for t, b in zip(geo["t"], geo["beta_deg"], strict=True):
        if not start_s <= t < end_s:
            continue
        if b >= gate_deg and opened is None:
            opened = t
        elif b < gate_deg and opened is not None:
            out.append((opened, t))
            opened = None
    if opened is not None:
        out.append((opened, min(end_s, geo["t"][-1])))
    return out


def reach_time(geo: dict, gate_deg: float, start_s: float, open_s: float) -> float | None:
    """The time (s) at which the gate has been open ``open_s`` s in total since ``start_s`` (None: not within the
    samples). Each sample stands for the ``step`` after it."""
    t_list = geo["t"]
    step = t_list[1] - t_list[0]
    total = 0.0
    for t, b in zip(t_list, geo["beta_deg"], strict=True):
        if t < start_s or b < gate_deg:
            continue
        total += step
        if total >= open_s - 1e-9:
            return t + step
    return None


def _sunlit_parts(geo: dict) -> list[tuple[float, float]]:
    return SunSafeResult(times=geo["t"], eclipse=geo["eclipse"]).sunlit_parts()


def table(geo: dict, gates: list[float], starts: list[float], scenario: str) -> dict:
    """The figures kept by ``--json``: per gate, the open time and windows in the first sunlit part; per
    spin-down start, when the command reaches the tracker's limit and the hold spin; the 80° gate's windows after
    the first sunlit part, the sunlit parts, and the field's range over the orbit (µT)."""
    parts = _sunlit_parts(geo)
    part = parts[0]
    to_limit = (ACQUIRE_DEG_S - TRACKER_LIMIT_DEG_S) / RAMP_DEG_S2
    to_hold = (ACQUIRE_DEG_S - HOLD_DEG_S) / RAMP_DEG_S2
    rows = []
    for g in gates:
        w = windows(geo, g, *part)
        rows.append({"gate_deg": g, "open_s": sum(b - a for a, b in w), "windows": w})
    reach = []
    for t0 in starts:
        reach.append({"start_s": t0, "gate_deg": 80.0, "limit_s": reach_time(geo, 80.0, t0, to_limit),
                      "hold_s": reach_time(geo, 80.0, t0, to_hold)})
    sunlit_beta = [b for t, b in zip(geo["t"], geo["beta_deg"], strict=True) if part[0] <= t < part[1]]
    sunlit_field = [b for t, b in zip(geo["t"], geo["field_ut"], strict=True) if part[0] <= t < part[1]]
    return {"scenario": scenario, "first_sunlit_part": part, "gates": rows, "reach": reach,
            "open_to_limit_s": to_limit, "open_to_hold_s": to_hold, "beta_max_deg": max(sunlit_beta),
            "beta_min_deg": min(sunlit_beta), "sunlit_parts": parts, "windows_80_after": windows(geo, 80.0, part[1]),
            "field_min_ut": min(geo["field_ut"]), "field_max_ut": max(geo["field_ut"]),
            "sunlit_field_min_ut": min(sunlit_field), "sunlit_field_max_ut": max(sunlit_field)}


def _fmt_windows(w) -> str:
    return ", ".join(f"{a:.0f}–{b:.0f}" for a, b in w) if w else "none"


def markdown(data: dict) -> str:
    """The two tables of the JSON ``data`` (:func:`table`)."""
    a, b = data["first_sunlit_part"]
    lines = [f"| gate ∠(B, Sun line) ≥ | open in the first sunlit part ({a:.0f}–{b:.0f} s) | windows (s) |",
             "|---|---|---|"]
    for r in data["gates"]:
        lines.append(f"| {r['gate_deg']:g}° | {r['open_s']:.0f} s ({100 * r['open_s'] / (b - a):.1f} %) | "
                     f"{_fmt_windows(r['windows'])} |")
    lines += ["", f"β over the part: {data['beta_min_deg']:.1f}–{data['beta_max_deg']:.1f}°. With the gate at 80° "
              f"and the ramp {RAMP_DEG_S2} °/s², the command needs {data['open_to_limit_s']:.0f} s of open gate to "
              f"reach {TRACKER_LIMIT_DEG_S} °/s and {data['open_to_hold_s']:.0f} s to reach {HOLD_DEG_S} °/s:", "",
              "| spin-down starts at (s) | command at 2 °/s (s) | command at 1.5 °/s (s) |", "|---|---|---|"]
    for r in data["reach"]:
        cells = [f"{r[k]:.0f}" if r[k] is not None else "not in the orbit" for k in ("limit_s", "hold_s")]
        lines.append(f"| {r['start_s']:.0f} | {cells[0]} | {cells[1]} |")
    lines += ["", f"After the first sunlit part the 80° gate is open at {_fmt_windows(data['windows_80_after'])} s "
              f"(sunlit parts of the orbit: {_fmt_windows(data['sunlit_parts'])} s, the cylindrical shadow); |B| "
              f"{data['sunlit_field_min_ut']:.0f}–{data['sunlit_field_max_ut']:.0f} µT over the first sunlit part, "
              f"{data['field_min_ut']:.0f}–{data['field_max_ut']:.0f} µT over the orbit."]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m detumble.sim.spin_down_geometry", description=__doc__.split("\n")[0])
    ap.add_argument("--scenario", default="adcs")
    ap.add_argument("--gates", default="60,70,75,80,85", help="gate angles, deg (comma-separated)")
    ap.add_argument("--starts", default="520,570,1958,2124,2714",
                    help="spin-down start times, s (comma-separated; default the plant-only flights' SunSpinLowered)")
    ap.add_argument("--json", metavar="FILE", help="also keep the figures in FILE (JSON)")
    args = ap.parse_args(argv)
    try:
        gates = [float(g) for g in args.gates.split(",")]
        starts = [float(s) for s in args.starts.split(",")]
    except ValueError as exc:
        ap.error(str(exc))
    if 80.0 not in gates:
        ap.error("--gates must include 80 (the flown gate, used for the reach table)")
    data = table(geometry(args.scenario), gates, starts, args.scenario)
    print(markdown(data))
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump(data, f, indent=1)
            f.write("\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
