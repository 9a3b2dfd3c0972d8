"""The coils' automatic spin-down flown with its parameters changed: the variant tables of docs/studies/sun_safe.md
("Handing back with no operator"), plant-only, seeds 1–3 from issue 27's 2 °/s tumble.

Each variant is one set of attitude-controller parameters (``SUN_HOLD_*``, ``SUN_SPIN_RATE``) flown by
``detumble.sim.sun_safe_check.spin_down_table`` (the coils, the star tracker off, FORCE_MODE SUN_SAFE at the start)
for seeds 1–3, each seed giving ``sun_safe_check.spin_down_row``'s figures: the acquisition, when the spin was
lowered, the true pointing error (deg) and body rate from then to the end of the first sunlit part (0–2809 s), and
the reacquisition after the eclipse (the one-orbit variants). Four tables are rendered from the one JSON file:

* ``gate``: how the spin comes down (a near-step, a ramp with no field gate, gates 60–85°, a faster ramp): the
  largest error from the spin-down to the part's end, and when |ω| stays below the tracker's 2 °/s;
* ``tip``: SUN_HOLD_TIP_ANGLE 0 (off, the default), 3°, 1°: the error's median / p95 / max after the spin-down;
* ``hold_rate``: SUN_HOLD_SPIN_RATE 1.5 (the default), 1.7, 1.9, 2.4 °/s over one orbit: the reacquisition after
  the eclipse;
* ``spin_rate``: SUN_SPIN_RATE 3 (the default), 1.8, 1.5 °/s: the acquisition in the first sunlit part.

The default variant flies one orbit (its first sunlit part is the gate table's 80° row and the tip table's 0 row;
its seeds 1–3 are the plant-only spin-down table's, ``python -m detumble.sim.sun_safe_check --spin-down --seeds 5``,
to the float: tests/test_studies.py STUDY-111).

    python campaigns/adcs/sun_spin_down_variants.py [--json FILE]

45 plant-only flights, about 160,000 simulated s (~8 CPU-minutes on this machine unloaded).
"""

from __future__ import annotations

import argparse
import json
import pathlib
import sys

from detumble.sim.sun_safe_check import _slow_text, spin_down_table

ORBIT_S = 5580.0
FIRST_PART_S = 2810.0  # s: the first sunlit part is 0–2809 s
SEEDS = (1, 2, 3)
#: key → (what the row is called, the parameters changed, the flight's duration s)
VARIANTS = {
    "default": ("the defaults", {}, ORBIT_S),
    "step": ("near-step: ramp 1 °/s² (1.5 s), no gate", {"SUN_HOLD_RAMP": 1.0, "SUN_HOLD_FIELD_ANGLE": 0.0},
             FIRST_PART_S),
    "no_gate": ("ramp 0.005 °/s², no gate", {"SUN_HOLD_FIELD_ANGLE": 0.0}, FIRST_PART_S),
    "no_gate_18": ("ramp 0.005 °/s² to 1.8 °/s, no gate", {"SUN_HOLD_FIELD_ANGLE": 0.0, "SUN_HOLD_SPIN_RATE": 1.8},
                   FIRST_PART_S),
    "gate_60": ("ramp 0.005, gate 60°", {"SUN_HOLD_FIELD_ANGLE": 60.0}, FIRST_PART_S),
    "gate_70": ("gate 70°", {"SUN_HOLD_FIELD_ANGLE": 70.0}, FIRST_PART_S),
    "gate_75": ("gate 75°", {"SUN_HOLD_FIELD_ANGLE": 75.0}, FIRST_PART_S),
    "gate_85": ("gate 85°", {"SUN_HOLD_FIELD_ANGLE": 85.0}, FIRST_PART_S),
    "gate_80_fast": ("gate 80°, ramp 0.02 °/s²", {"SUN_HOLD_RAMP": 0.02}, FIRST_PART_S),
    "gate_85_fast": ("gate 85°, ramp 0.02 °/s²", {"SUN_HOLD_FIELD_ANGLE": 85.0, "SUN_HOLD_RAMP": 0.02},
                     FIRST_PART_S),
    "tip_3": ("3°", {"SUN_HOLD_TIP_ANGLE": 3.0}, FIRST_PART_S),
    "tip_1": ("1°", {"SUN_HOLD_TIP_ANGLE": 1.0}, FIRST_PART_S),
    "hold_17": ("1.7 °/s", {"SUN_HOLD_SPIN_RATE": 1.7}, ORBIT_S),
    "hold_19": ("1.9 °/s", {"SUN_HOLD_SPIN_RATE": 1.9}, ORBIT_S),
    "hold_24": ("2.4 °/s", {"SUN_HOLD_SPIN_RATE": 2.4}, ORBIT_S),
    "spin_18": ("1.8 °/s", {"SUN_SPIN_RATE": 1.8}, FIRST_PART_S),
    "spin_15": ("1.5 °/s", {"SUN_SPIN_RATE": 1.5}, FIRST_PART_S),
}
#: each table's rows: (variant key, the row's label; None: the variant's own)
TABLES = {
    "gate": (("step", None), ("no_gate", None), ("no_gate_18", None), ("gate_60", None), ("gate_70", None),
             ("gate_75", None), ("default", "**gate 80° (the default)**"), ("gate_85", None),
             ("gate_80_fast", None), ("gate_85_fast", None)),
    "tip": (("default", "0 (the default: the gate only)"), ("tip_3", None), ("tip_1", None)),
    "hold_rate": (("default", "1.5 °/s (the default)"), ("hold_17", None), ("hold_19", None), ("hold_24", None)),
    "spin_rate": (("default", "3 °/s (the default)"), ("spin_18", None), ("spin_15", None)),
}


def fly_variants(keys=None) -> dict:
    """Fly the variants ``keys`` (default: all) for seeds 1–3: ``{key: {"params", "duration_s", "rows", "values"}}``."""
    out = {}
    for key in keys or VARIANTS:
        _, params, duration = VARIANTS[key]
        figures = spin_down_table(SEEDS, duration_s=duration, params=dict(params))
        out[key] = {"params": params, "duration_s": duration, "rows": figures["rows"], "values": figures["values"]}
        print(f"{key}: flown", file=sys.stderr, flush=True)
    return out


def _variant(table: dict, key: str) -> dict:
    flown = table["variants"].get(key)
    if flown is None or flown["params"] != VARIANTS[key][1] or flown["duration_s"] != VARIANTS[key][2]:
        raise ValueError(f"variant {key!r} is missing or was flown with other settings: fly the script again")
    return flown


def _label(key: str, label: str | None) -> str:
    return VARIANTS[key][0] if label is None else label


def _per_seed(rows: list[dict], text) -> str:
    return " / ".join(text(r) for r in rows)


def _max(r: dict) -> str:
    return "—" if r["after_deg"] is None else f"{r['after_deg']['max']:.1f}°"


def _three(r: dict) -> str:
    st = r["after_deg"]
    return "—" if st is None else f"{st['median']:.2f} / {st['p95']:.2f} / {st['max']:.2f}"


def _within(r: dict) -> str:
    return "—" if r["within"] is None else f"{100 * r['within']:.1f} %"


def _seconds(value) -> str:
    return "never" if value is None else f"{value:.0f}"


def gate_markdown(table: dict) -> str:
    """How the spin comes down: the largest error after it and when |ω| stays below 2 °/s, per seed."""
    lines = ["| spin-down | max error from the spin-down to 2809 s, seeds 1 / 2 / 3 | \\|ω\\| < 2 °/s from, seeds "
             "1 / 2 / 3 (s) | spin lowered at, seeds 1 / 2 / 3 (s) |", "|---|---|---|---|"]
    for key, label in TABLES["gate"]:
        rows = _variant(table, key)["rows"]
        lines.append(f"| {_label(key, label)} | {_per_seed(rows, _max)} | {_per_seed(rows, _slow_text)} | "
                     f"{_per_seed(rows, lambda r: _seconds(r['spin_lowered_s']))} |")
    return "\n".join(lines) + "\n"


def tip_markdown(table: dict) -> str:
    """SUN_HOLD_TIP_ANGLE: the error after the spin-down, its share within 10°, and when |ω| stays below 2 °/s."""
    lines = ["| SUN_HOLD_TIP_ANGLE | error from the spin-down to 2809 s: median / p95 / max (deg), seeds 1; 2; 3 | "
             "within 10°, seeds 1 / 2 / 3 | acquisition ≤ 10° (s), seeds 1 / 2 / 3 | \\|ω\\| < 2 °/s from (s) |",
             "|---|---|---|---|---|"]
    for key, label in TABLES["tip"]:
        rows = _variant(table, key)["rows"]
        lines.append(f"| {_label(key, label)} | {'; '.join(_three(r) for r in rows)} | "
                     f"{_per_seed(rows, _within)} | "
                     f"{_per_seed(rows, lambda r: _seconds(r['acquisition_s']))} | {_per_seed(rows, _slow_text)} |")
    return "\n".join(lines) + "\n"


def hold_rate_markdown(table: dict) -> str:
    """SUN_HOLD_SPIN_RATE over one orbit: the open gate the ramp needs, the reacquisition after the eclipse, and
    when |ω| stays below 2 °/s in the first sunlit part."""
    lines = ["| SUN_HOLD_SPIN_RATE | open gate needed (s) | after the eclipse: reacquisition, seeds 1 / 2 / 3 (s) | "
             "\\|ω\\| < 2 °/s from (s) |", "|---|---|---|---|"]
    for key, label in TABLES["hold_rate"]:
        flown = _variant(table, key)
        v, rows = flown["values"], flown["rows"]
        need = (v["SUN_SPIN_RATE"] - v["SUN_HOLD_SPIN_RATE"]) / v["SUN_HOLD_RAMP"]
        reacq = _per_seed(rows, lambda r: "—" if r["sunlit_parts"] < 2 else _seconds(r["reacquisition_s"]))
        lines.append(f"| {_label(key, label)} | {need:.0f} | {reacq} | {_per_seed(rows, _slow_text)} |")
    return "\n".join(lines) + "\n"


def spin_rate_markdown(table: dict) -> str:
    """SUN_SPIN_RATE: the acquisition ≤ 10° in the first sunlit part (the spin-down at its defaults)."""
    lines = ["| SUN_SPIN_RATE | acquisition ≤ 10° in the first sunlit part, seeds 1 / 2 / 3 (s) |", "|---|---|"]
    for key, label in TABLES["spin_rate"]:
        rows = _variant(table, key)["rows"]
        lines.append(f"| {_label(key, label)} | {_per_seed(rows, lambda r: _seconds(r['acquisition_s']))} |")
    return "\n".join(lines) + "\n"


def markdown(table: dict) -> str:
    """All four tables."""
    return "\n".join(f(table) for f in (gate_markdown, tip_markdown, hold_rate_markdown, spin_rate_markdown))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--json", type=pathlib.Path, metavar="FILE", help="also keep the flights' figures in FILE")
    args = parser.parse_args(argv)
    table = {"script": "campaigns/adcs/sun_spin_down_variants.py", "seeds": list(SEEDS),
             "variants": fly_variants()}
    print(markdown(table), end="")
    if args.json is not None:
        from detumble.sim.runner import write_atomic

        args.json.parent.mkdir(parents=True, exist_ok=True)
        write_atomic(args.json, json.dumps(table, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
