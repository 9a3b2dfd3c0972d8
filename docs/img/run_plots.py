"""Regenerate docs/img/reference_run_<kind>.png: one full detumble of the reference deployment.

    python docs/img/run_plots.py            # about 30 s; run from the repository root

Flies ``deployments/proves_ref/topology.yaml`` for 3100 simulated seconds (the default scenario,
30 deg/s to below the deadband) into a temporary folder and copies every plot the run drew
(rate, drive levels, state, field, dipole, attitude, power) here. :func:`regenerate` does it and
returns the files written, for a script that regenerates every figure of the docs.
"""
import pathlib
import shutil
import tempfile

from fprime_lite.tools import run

ROOT = pathlib.Path(__file__).resolve().parents[2]
HERE = pathlib.Path(__file__).resolve().parent
DURATION_S = 3100.0


def regenerate(target: pathlib.Path = HERE, duration_s: float = DURATION_S) -> list[pathlib.Path]:
    """Fly the reference deployment for ``duration_s`` and copy its plots to
    ``target/reference_run_<name>.png``; return the paths written."""
    written = []
    with tempfile.TemporaryDirectory() as scratch:
        result = run(ROOT / "deployments" / "proves_ref" / "topology.yaml", duration_s=duration_s,
                     out=pathlib.Path(scratch) / "run", plots=True)
        for png in sorted(result.out_dir.glob("*.png")):
            path = pathlib.Path(target) / f"reference_run_{png.name}"
            shutil.copyfile(png, path)
            written.append(path)
    return written


if __name__ == "__main__":
    for path in regenerate():
        print(f"wrote {path.relative_to(ROOT)}")
