"""One pointing run on deployments/adcs_ref for docs/studies/attitude_knowledge.md's design tables.

    python campaigns/adcs/pointing_single.py OUT_DIR ["PARAM_PRM_SET VALUE;..."] [scenario KEY=VALUE ...]

The controller's parameters are set by the sequence (at 0 s); the geometry is fixed: initial attitude 90° about
(1, 1, 1)/√3 from the target, a 0.05 °/s tumble, FORCE_MODE POINTING at 30 s, a target change to identity at
90 s, 400 s in all (seed 1). Prints the slew and the steady statistics the campaign metrics compute
(``detumble.reports.pointing_metrics``: from 60 s after the target change).
"""

from __future__ import annotations

import pathlib
import sys

from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.tools.campaign import RunOutput
from fprime_lite.tools.runner import run_deployment

from detumble.reports.pointing_metrics import percentile, steady_errors

TOPOLOGY = pathlib.Path(__file__).parents[2] / "deployments" / "adcs_ref" / "topology.yaml"
CTRL = "ReferenceDeployment.attitudeController"
SETTINGS = ["initial.rate.magnitude_deg_s=0.05",
            "initial.attitude.quaternion=[0.7071067811865476,0.4082482904638631,0.4082482904638631,0.4082482904638631]"]


def fly(out: pathlib.Path, params: list[str], settings: list[str]) -> dict:
    """One run into ``out`` with the controller parameters ``params`` ("NAME_PRM_SET VALUE", set at 0 s) and the
    scenario ``settings`` (after the geometry's): the first slew's settling below 0.1° (s, None if it never did)
    and the steady error's median / p95 / max (deg), the wheels' largest momentum fraction."""
    out.mkdir(parents=True, exist_ok=True)
    lines = [f"R00:00:00 {CTRL}.{p}" for p in params]
    lines += [f"R00:00:30 {CTRL}.FORCE_MODE POINTING", f"R00:01:00 {CTRL}.SET_TARGET_QUATERNION 1.0 0.0 0.0 0.0"]
    seq = out / "pointing.seq"
    seq.write_text("\n".join(lines) + "\n", encoding="utf-8")
    loaded = load_topology(TOPOLOGY, {"spacecraft": {"settings": SETTINGS + settings}})
    summary = run_deployment(loaded, out, duration_s=400.0, sequence=seq, plots=False, quiet=True)
    errors = steady_errors(RunOutput(summary=summary, out_dir=out))
    slew = summary["slews"][0] if summary["slews"] else {}
    return {"params": params, "settings": settings, "slew_settle_s": slew.get("settle_below_0p1_deg_s"),
            "samples": len(errors), "median_deg": percentile(errors, 0.5), "p95_deg": percentile(errors, 0.95),
            "max_deg": max(errors), "wheel_momentum_max_fraction": summary["wheel_momentum_max_fraction"]}


def main(argv: list[str]) -> int:
    if not argv:
        print(__doc__)
        return 2
    params = [p.strip() for p in (argv[1] if len(argv) > 1 else "").split(";") if p.strip()]
    r = fly(pathlib.Path(argv[0]), params, argv[2:])
    print(f"slew settled below 0.1 deg at {r['slew_settle_s']} s; steady median {r['median_deg']:.4f} p95 "
          f"{r['p95_deg']:.4f} max {r['max_deg']:.4f} deg ({r['samples']} samples); wheel "
          f"{r['wheel_momentum_max_fraction']:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
