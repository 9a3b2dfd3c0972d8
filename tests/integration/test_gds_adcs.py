"""The stock fprime-gds commands a new pointing target while deployments/adcs_ref flies (realtime).

Reuses the process handling of ``test_gds.py``. The deployment starts slowly turning (0.5 °/s, so the star
tracker has a solution at once); its start-up sequence forces POINTING on an identity target after 3 s; then
``gds_inner/adcs_checks.py`` runs inside fprime-gds's pytest plugin: a 90° target from the GDS is flown to
within 0.1°, FORCE_MODE / SET_AUTO answer with their events, a non-unit target is refused. Slow (about a
minute of realtime flight); skipped when fprime-gds is not installed.
"""

from __future__ import annotations

import importlib.util
import json
import pathlib
import shutil
import signal
import subprocess
import sys
import tempfile

import pytest

from fprime_lite.tools.cli import main as fprime_lite

_spec = importlib.util.spec_from_file_location("_gds_support", pathlib.Path(__file__).with_name("test_gds.py"))
_gds = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_gds)

ROOT = pathlib.Path(__file__).parents[2]
TOPOLOGY = ROOT / "deployments" / "adcs_ref" / "topology.yaml"
INNER = pathlib.Path(__file__).parent / "gds_inner" / "adcs_checks.py"

pytestmark = [_gds.pytestmark, pytest.mark.slow]


def test_the_gds_commands_a_new_target_while_flying():
    """ADCS-050/051: see gds_inner/adcs_checks.py; the run then ends on SIGTERM with no handler fault."""
    work = pathlib.Path(tempfile.mkdtemp(prefix="fl-gds-adcs-"))
    dictionary = work / "dictionary.json"
    assert fprime_lite(["dict", str(TOPOLOGY), "--gds", "-o", str(dictionary)]) == 0
    seq = work / "pointing.seq"
    seq.write_text("R00:00:00 ReferenceDeployment.attitudeController.SET_TARGET_QUATERNION 1 0 0 0\n"
                   "R00:00:03 ReferenceDeployment.attitudeController.FORCE_MODE POINTING\n")
    port = _gds.free_port()
    zmq = [f"ipc://{work}/zmq-in", f"ipc://{work}/zmq-out"]
    groups = _gds.ProcessGroups(work)
    try:
        groups.start("gds", [_gds.GDS, "--dictionary", str(dictionary), "--framing-selection", "fprime",
                             "--ip-address", "127.0.0.1", "--ip-port", str(port), "-g", "none", "--zmq-transport",
                             *zmq, "--logs", str(work / "gds-logs"), "--log-directly", "-n"], cwd=work)
        groups.start("deployment", [sys.executable, "-m", "fprime_lite.tools.cli", "run", str(TOPOLOGY), "--gds",
                                    f"127.0.0.1:{port}", "--framing", "fprime", "--duration", "400", "--out",
                                    str(work / "runs" / "run"), "--no-plots", "--seq", str(seq),
                                    "--set", "initial.rate.magnitude_deg_s=0.5"], cwd=work)
        figures = work / "figures.json"
        inner = subprocess.run(
            [sys.executable, "-m", "pytest", str(INNER), "-q", "-p", "no:cacheprovider", "--dictionary",
             str(dictionary), "--zmq-transport", *zmq, "--logs", str(work / "api-logs"), "--log-directly"],
            cwd=ROOT, capture_output=True, text=True, timeout=600,  # guards a hang, not the speed of a loaded machine
            env={**__import__("os").environ, "FPRIME_LITE_GDS_FIGURES": str(figures)})
        assert inner.returncode == 0, (f"inner GDS test run failed:\n{inner.stdout[-6000:]}\n{inner.stderr[-3000:]}"
                                       f"\n--- deployment ---\n{groups.log('deployment')}")
        assert "2 passed" in inner.stdout
        groups.signal("deployment", signal.SIGTERM)
        summary_path = _gds.wait_for_file(work / "runs", "*/summary.json", timeout=30)
        assert summary_path is not None, f"no summary after SIGTERM:\n{groups.log('deployment')}"
        summary = json.loads(summary_path.read_text())
        assert summary["handler_faults"] == 0 and summary["member_faults"] == 0
        modes = [t["mode"] for t in summary["control_mode_transitions"]]
        assert modes[:2] == ["POINTING", "SPIN_STABLE"], modes
        print(f"\nGDS 90° slew settled below 0.1° in {json.loads(figures.read_text())['slew_90_deg_settle_s']:.1f} s")
    finally:
        groups.stop_all()
        shutil.rmtree(work, ignore_errors=True)
