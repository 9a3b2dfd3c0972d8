"""Regenerate docs/img/reference_run_<kind>.png: one full detumble of the reference deployment.

    python docs/img/run_plots.py            # run from the repository root

The same as ``python tools/studies.py --only readme_figures`` (which regenerates every study's tables
and figures, docs/studies/README.md): it flies ``deployments/proves_ref/topology.yaml`` for 3100
simulated seconds (the default scenario, 30 deg/s to below the deadband) and copies every plot the
run's own plotters drew here.
"""
import pathlib
import runpy
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]

if __name__ == "__main__":
    sys.argv = [str(ROOT / "tools" / "studies.py"), "--only", "readme_figures", *sys.argv[1:]]
    runpy.run_path(sys.argv[0], run_name="__main__")
