"""Seed 004's tumble taken out by a real 1U wheel with magnetic momentum dumping: coursework_reproduction.md's
"Beyond the report" table.

One orbit of the coursework plant (``fprime-lite sim surrey``, scenario ``surrey``, 0.01 s) with the
``cubesat_1u`` wheel class (4 mN·m, 15 mN·m·s; ``detumble/sim/wheels.py``), the wheel PD with the corrected
quaternion error and the wheels' own limits, and the rods unloading the wheels (``M = k (h × B)/|B|²``,
k = :data:`DUMP_GAIN` s⁻¹). It reports the run's 2 % settling time and the time |ω − ω_final| falls under 1 °/s
(``summary.json``), and the wheels' stored momentum (N·m·s, body frame B, from ``rate.csv``'s ``h0…h2``) at
:data:`AFTER_S` s and at the end of the orbit: its norm over the three wheels and the largest single wheel, each
also as a fraction of one wheel's capacity.

    python campaigns/coursework/real_wheel.py [--json FILE]

About 15 CPU-s.
"""

from __future__ import annotations

import csv
import json
import math
import pathlib
import subprocess
import sys
import tempfile

from detumble.sim.wheels import CATALOGUE

WHEEL = "cubesat_1u"
DUMP_GAIN = 0.002  # s⁻¹
DURATION_S = 5833.0  # one orbit of `surrey` (5832.9 s)
AFTER_S = 1000.0  # s: the momentum once the tumble is out, before the rods have unloaded much
SETTINGS = (f"spacecraft.reaction_wheels.model={WHEEL}", "control.wheels_pd.limits=wheel",
            f"control.wheels_pd.dump_gain={DUMP_GAIN:g}", "control.wheels_pd.error=shortest_path")


def command(out: str) -> list[str]:
    """The ``fprime-lite sim`` command of the flight, writing into ``out``."""
    args = ["fprime-lite", "sim", "surrey", "--law", "wheels_pd", "--duration", f"{DURATION_S:g}", "--out", out]
    for setting in SETTINGS:
        args += ["--set", setting]
    return args


def _momentum(row: dict) -> dict:
    h = [float(row[f"h{i}_Nms"]) for i in range(3)]
    capacity = CATALOGUE[WHEEL].max_momentum_nms
    norm, largest = math.sqrt(sum(x * x for x in h)), max(abs(x) for x in h)
    return {"time_s": float(row["time_s"]), "h_Nms": h, "norm_Nms": norm, "largest_Nms": largest,
            "norm_of_capacity": norm / capacity, "largest_of_capacity": largest / capacity}


def fly() -> dict:
    """Fly the orbit (a subprocess of this interpreter's ``fprime-lite``) and read its figures."""
    with tempfile.TemporaryDirectory() as scratch:
        out = str(pathlib.Path(scratch) / "run")
        args = command(out)
        subprocess.run([sys.executable, "-m", "fprime_lite.tools.cli", *args[1:]], check=True,
                       stdout=subprocess.DEVNULL)
        summary = json.loads((pathlib.Path(out) / "summary.json").read_text(encoding="utf-8"))
        with open(pathlib.Path(out) / "rate.csv", encoding="utf-8", newline="") as f:
            rows = list(csv.DictReader(f))
    after = min(rows, key=lambda r: abs(float(r["time_s"]) - AFTER_S))
    return {"command": " ".join(command("runs/cw_real_wheel")), "wheel": WHEEL,
            "capacity_Nms": CATALOGUE[WHEEL].max_momentum_nms, "duration_s": DURATION_S,
            "settling_time_2pct_s": summary["settling_time_2pct_s"],
            "time_below_threshold_s": summary["time_below_threshold_s"],
            "threshold_deg_s": summary["time_below_threshold_deg_s"],
            "momentum_after": _momentum(after), "momentum_end": _momentum(rows[-1])}


def markdown(table: dict) -> str:
    """The wheel's row of the page's table (the magnetic laws' rows are added by tools/studies.py)."""
    a, e = table["momentum_after"], table["momentum_end"]
    unloaded = 1.0 - e["norm_Nms"] / a["norm_Nms"]
    return (f"| real 1U wheel + dumping | {table['settling_time_2pct_s']:.2f} s | "
            f"{table['time_below_threshold_s']:.1f} s | ‖h‖ {a['norm_Nms']:.2e} N·m·s at {a['time_s']:g} s "
            f"({100 * a['norm_of_capacity']:.0f} % of one wheel's capacity; largest wheel {a['largest_Nms']:.2e}) "
            f"→ {e['norm_Nms']:.2e} after one orbit ({e['time_s']:g} s; largest wheel {e['largest_Nms']:.2e}): "
            f"{100 * unloaded:.0f} % unloaded |")


def main(argv: list[str] | None = None) -> int:
    from detumble.reports.study_table import table_script_main

    return table_script_main(argv, __doc__.split("\n\n")[0], lambda args: fly(), markdown)


if __name__ == "__main__":
    sys.exit(main())
