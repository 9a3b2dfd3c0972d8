"""Start-up removes what an earlier, killed run left half-written (issue #16 finding 7)."""

import pathlib
import subprocess
import sys

from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.topology_loader import load_topology

TOPOLOGY = pathlib.Path(__file__).parents[3] / "topology.yaml"


def _dead_pid() -> int:
    done = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                          text=True, check=True)
    return int(done.stdout)


def test_deployment_start_cleans_the_file_services_roots(tmp_path):
    """TMP-4: Deployment.start removes dead processes' temporary files under the file services' roots
    (sub-folders included) and the parameter file's folder, and nothing else."""
    uplink_root, manager_root, params = tmp_path / "up", tmp_path / "mgr", tmp_path / "params"
    for folder in (uplink_root / "seq", manager_root, params):
        folder.mkdir(parents=True)
    pid = _dead_pid()
    leftovers = [uplink_root / "seq" / f".fprime-lite-tmp.{pid}.run.seq.a1.part",
                 manager_root / f".fprime-lite-tmp.{pid}.log.txt.b2.part",
                 params / f".fprime-lite-tmp.{pid}.PrmDb.dat.c3.part"]
    keep = [uplink_root / "seq" / "run.seq", params / "PrmDb.dat"]
    for path in leftovers + keep:
        path.write_bytes(b"x")
    loaded = load_topology(TOPOLOGY)
    topo = loaded.topology
    topo.instance("FileHandling.fileUplink").component.set_default_root(uplink_root)
    topo.instance("FileHandling.fileManager").component.set_default_root(manager_root)
    Deployment(loaded).start(parameter_file=params / "PrmDb.dat")
    assert [p for p in leftovers if p.exists()] == []
    assert all(p.exists() for p in keep)
