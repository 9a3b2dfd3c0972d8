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


def test_file_services_sharing_a_root_sweep_it_once(tmp_path, monkeypatch):
    """TMP-5: file services that share a root (the working directory when no run folder is given) have it
    swept once at start-up, not once each; a service with a root of its own has that one swept too, and the
    leftovers under both are removed."""
    import fprime_lite.svc.file_root as file_root

    shared, own = tmp_path / "shared", tmp_path / "own"
    for folder in (shared / "sub", own):
        folder.mkdir(parents=True)
    pid = _dead_pid()
    leftovers = [shared / "sub" / f".fprime-lite-tmp.{pid}.a.bin.x1.part", own / f".fprime-lite-tmp.{pid}.b.x2.part"]
    for path in leftovers:
        path.write_bytes(b"x")
    swept: list[str] = []
    sweep = file_root.clean_temporary_files

    def counted(folder, **kwargs):
        swept.append(str(folder))
        return sweep(folder, **kwargs)

    monkeypatch.setattr(file_root, "clean_temporary_files", counted)
    loaded = load_topology(TOPOLOGY)
    topo = loaded.topology
    for name in ("FileHandling.fileUplink", "FileHandling.fileDownlink"):
        topo.instance(name).component.set_default_root(shared)
    topo.instance("FileHandling.fileManager").component.set_default_root(own)
    Deployment(loaded).start(parameter_file=tmp_path / "PrmDb.dat")
    assert sorted(swept) == sorted([str(shared.resolve()), str(own.resolve())])
    assert [p for p in leftovers if p.exists()] == []
