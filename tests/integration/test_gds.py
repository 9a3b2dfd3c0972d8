"""The stock fprime-gds 4.4.1 commands and monitors the flying reference deployment.

For each framing, a fixture starts ``fprime-gds`` headless on 127.0.0.1 (its own ZMQ sockets and
an ephemeral port, so parallel runs do not collide, in a new session so that the whole process
group can be killed) and the deployment in realtime mode connected to it:

- ``fprime`` framing: the deployment is started by the fixture, ``fprime-lite run --gds``;
- ``ccsds`` framing: fprime-gds launches it itself, ``fprime-gds -d DIR --app fprime-lite-app``.

Then the GDS's own pytest plugin (``fprime_test_api``) runs ``gds_inner/gds_checks.py`` in a
pytest subprocess: NO-OP round trip, SET_MODE AUTO → DetumbleStarted and State, GAIN_PRM_SET →
GainParamSet, GET_MAGNETIC_FIELD → MagneticFieldData, a file uplinked by the GDS landing
byte-identical, a file downlinked with SendFile reaching the GDS's store, a text sequence
compiled and uplinked by the GDS then run with CS_RUN, and the PROVES flight components as an
operator drives them: FORCE_SAFE_MODE / GET_SAFE_MODE_REASON / EXIT_SAFE_MODE with the face
switches following, a load switch cycled, INA219 and power-monitor readings, and a COLD_RESET after
which the boot count is 2 and the link is still up. Every process group is killed at the end,
pass or fail. Skipped only when fprime-gds is not installed.
"""

from __future__ import annotations

import importlib.util
import json
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import pytest

from fprime_lite.tools.cli import main as fprime_lite
from fprime_lite.tools.processes import ProcessGroups, free_port

ROOT = pathlib.Path(__file__).parents[2]
TOPOLOGY = ROOT / "deployments" / "proves_ref" / "topology.yaml"
INNER = pathlib.Path(__file__).parent / "gds_inner" / "gds_checks.py"
BIN = pathlib.Path(sys.executable).parent
GDS = shutil.which("fprime-gds", path=str(BIN)) or shutil.which("fprime-gds")
GDS_FRAMING = {"fprime": "fprime", "ccsds": "space-packet-space-data-link"}

pytestmark = pytest.mark.skipif(
    GDS is None or importlib.util.find_spec("fprime_gds") is None,
    reason="fprime-gds is not installed (it is a test dependency: pip install -e .[test])")


def wait_for_file(pattern_dir: pathlib.Path, pattern: str, timeout: float) -> pathlib.Path | None:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        found = sorted(pattern_dir.glob(pattern))
        if found:
            return found[0]
        time.sleep(0.1)
    return None


@pytest.fixture(params=["fprime", "ccsds"])
def flying(request):
    framing = request.param
    # A short path of our own: ZMQ ipc socket paths must stay under ~100 characters.
    work = pathlib.Path(tempfile.mkdtemp(prefix=f"fl-gds-{framing}-"))
    dictionary = work / "dictionary.json"
    assert fprime_lite(["dict", str(TOPOLOGY), "--gds", "-o", str(dictionary)]) == 0
    idle = work / "idle.seq"  # instead of the start-up SET_MODE AUTO, so the test can command it
    idle.write_text("; keep detumbling disabled until the ground commands it\n"
                    "R00:00:00 CdhCore.cmdDisp.CMD_NO_OP\n")
    port = free_port()
    zmq = [f"ipc://{work}/zmq-in", f"ipc://{work}/zmq-out"]
    groups = ProcessGroups(work)
    gds = [GDS, "--dictionary", str(dictionary), "--framing-selection", GDS_FRAMING[framing],
           "--ip-address", "127.0.0.1", "--ip-port", str(port), "-g", "none", "--zmq-transport", *zmq,
           "--logs", str(work / "gds-logs"), "--log-directly"]
    env = dict(os.environ)
    runs = work / "runs"
    try:
        if framing == "fprime":
            groups.start("gds", gds + ["-n"], cwd=work)  # -n: --no-app
            groups.start("deployment", [sys.executable, "-m", "fprime_lite.tools.cli", "run", str(TOPOLOGY),
                                        "--gds", f"127.0.0.1:{port}", "--framing", framing, "--duration", "300",
                                        "--out", str(runs / "run"), "--no-plots", "--seq", str(idle)], cwd=work)
        else:
            app = shutil.which("fprime-lite-app", path=str(BIN))
            assert app is not None, "fprime-lite-app is missing: reinstall the project (pip install -e .[test])"
            env.update(FPRIME_LITE_FRAMING=framing, FPRIME_LITE_SEQ=str(idle), FPRIME_LITE_OUT=str(runs),
                       FPRIME_LITE_DURATION="300")
            groups.start("gds", gds + ["-d", str(work), "--app", app], cwd=work, env=env)
        yield {"framing": framing, "work": work, "dictionary": dictionary, "zmq": zmq, "groups": groups,
               "runs": runs}
    finally:
        groups.stop_all()
        shutil.rmtree(work, ignore_errors=True)


def test_the_stock_gds_flies_the_deployment(flying):
    work, groups = flying["work"], flying["groups"]
    figures = work / "figures.json"
    inner = subprocess.run(
        [sys.executable, "-m", "pytest", str(INNER), "-q", "-p", "no:cacheprovider", "--dictionary",
         str(flying["dictionary"]), "--zmq-transport", *flying["zmq"], "--logs", str(work / "api-logs"),
         "--log-directly"],
        # a guard against a hang, not a timing check: the ten operator checks take ~30 s on a quiet
        # machine and several minutes when eight processes share its two cores
        cwd=ROOT, capture_output=True, text=True, timeout=600,
        env={**os.environ, "FPRIME_LITE_GDS_FIGURES": str(figures), "FPRIME_LITE_GDS_RUNS": str(flying["runs"])})
    assert inner.returncode == 0, (f"inner GDS test run failed:\n{inner.stdout[-6000:]}\n{inner.stderr[-3000:]}\n"
                                   f"--- gds ---\n{groups.log('gds')}\n--- deployment ---\n"
                                   f"{groups.log('deployment')}")
    assert "10 passed" in inner.stdout

    # End the flight as fprime-gds does (SIGTERM): the run stops cleanly and writes its summary.
    name = "deployment" if flying["framing"] == "fprime" else "gds"
    groups.signal(name, signal.SIGTERM)
    summary_path = wait_for_file(flying["runs"], "*/summary.json", timeout=30)
    assert summary_path is not None, f"no summary after SIGTERM:\n{groups.log(name)}"
    summary = json.loads(summary_path.read_text())
    assert summary["handler_faults"] == 0 and summary["member_faults"] == 0
    assert summary["command_errors"] == 0
    assert 0.9 < summary["real_time_factor"] < 1.1, summary["real_time_factor"]
    assert summary["detumble_started_s"] is not None  # the ground's SET_MODE AUTO started it
    events = (summary_path.parent / "events.log").read_text()
    assert "ReferenceDeployment.comDriver.LinkConnected" in events
    assert "ReferenceDeployment.detumbleManager.GainParamSet" in events
    measured = json.loads(figures.read_text())
    print(f"\n{flying['framing']}: NO-OP round trips "
          f"{', '.join(f'{t * 1e3:.0f}' for t in measured['no_op_round_trip_s'])} ms; "
          f"|B| components {measured['magnetic_field_G']} G; RTF {summary['real_time_factor']:.4f}; "
          f"sim {summary['sim_seconds']:.1f} s")
