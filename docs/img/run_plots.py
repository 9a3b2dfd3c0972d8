"""Regenerate docs/img/reference_run_<kind>.png: one full detumble of the reference deployment.

    python docs/img/run_plots.py            # about 30 s; run from the repository root

Flies ``deployments/proves_ref/topology.yaml`` for 3100 simulated seconds (the default scenario,
30 deg/s to below the deadband) into a temporary folder and copies every plot the run drew
(rate, drive levels, state, field, and dipole/attitude/wheels when the truth log has them) here.
"""
import pathlib
import shutil
import tempfile

from fprime_lite.tools import run

ROOT = pathlib.Path(__file__).resolve().parents[2]
HERE = pathlib.Path(__file__).resolve().parent

with tempfile.TemporaryDirectory() as scratch:
    result = run(ROOT / "deployments" / "proves_ref" / "topology.yaml", duration_s=3100,
                 out=pathlib.Path(scratch) / "run", plots=True)
    for png in sorted(result.out_dir.glob("*.png")):
        target = HERE / f"reference_run_{png.name}"
        shutil.copyfile(png, target)
        print(f"wrote {target.relative_to(ROOT)}")
    print(result)
