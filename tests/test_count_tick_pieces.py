"""benchmarks/count_tick_pieces.py: its markers call each piece once and pass its answer on, and a flight with
pieces routed through them is the flight without (nothing is timed or counted here: callgrind does that)."""

import importlib.util
import pathlib

import pytest

from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.topology_loader import load_topology

ROOT = pathlib.Path(__file__).resolve().parents[1]
TOPOLOGY = ROOT / "deployments/adcs_ref/topology.yaml"


@pytest.fixture(scope="module")
def pieces():
    spec = importlib.util.spec_from_file_location("count_tick_pieces", ROOT / "benchmarks/count_tick_pieces.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("answer", [None, 0, "", (1.5, -2.0), 7])
def test_each_marker_calls_its_piece_once_and_passes_the_answer_on(pieces, answer):
    """BENCH-032: every marker wrapper calls the piece exactly once with the arguments given and returns what
    it returned (falsy answers included), and the eight markers are eight different C functions."""
    assert len({name for name, _ in pieces.MARKERS}) == len(pieces.MARKERS) == 8
    for name, mark in pieces.MARKERS:
        calls: list = []

        def piece(*args, calls=calls):
            calls.append(args)
            return answer

        assert mark(piece)(3, "x") == answer, name
        assert calls == [(3, "x")], name


def _flight(pieces_module, specs):
    on = None
    if specs:
        on, _ = pieces_module.install(specs, None)
    loaded = load_topology(TOPOLOGY)
    deployment = Deployment(loaded)
    deployment.start()
    deployment.run_for(1.0)
    if specs:
        pieces_module.install(specs, deployment, on)
        on[0] = True
    deployment.run_for(3.0)
    law = deployment.topology.instance("ReferenceDeployment.attitudeController").component.law
    tlm = deployment.topology.instance("CdhCore.tlmSend").component
    wall = {deployment.topology.instance(f"ReferenceDeployment.rateGroup{rate}").component.RgMaxTime.id
            for rate in ("50Hz", "10Hz", "1Hz")}  # wall-clock µs: differ between any two flights
    latest = {cid: (entry[0].total_us, entry[1]) for cid, entry in tlm._latest.items() if cid not in wall}
    assert len(latest) > 50
    return (law.mode, law.omega, law.dipole, law.wheel_torques, law.cycles, latest), on


def test_a_flight_through_the_markers_is_the_flight_without(pieces, monkeypatch):
    """BENCH-033: adcs_ref flown with eight pieces (class methods and, after the first second, a rate group's
    cycle and a channel's write) routed through the markers ends in the same law state and TlmChan table
    (values and time tags) as without them, and every piece was called through its marker."""
    specs = ["detumble.components.attitude_controller:AttitudeController.gyro",
             "detumble.components.attitude_controller:AttitudeController.drive_coils",
             "detumble.proves.imu_manager:ImuManager.angularVelocityGet",
             "detumble.drivers.spacecraft:SimulatedSpacecraft.advance_to_us",
             "detumble.drivers.magnetorquer_driver:MagnetorquerDriver.start",
             "@ReferenceDeployment.rateGroup50Hz:_cycle",
             "@ReferenceDeployment.imuManager:AngularVelocity.write",
             "fprime_lite.svc.tlm_chan:TlmChan.Run"]
    plain, _ = _flight(pieces, [])
    for spec in specs:  # the class replacements are undone after the test
        if not spec.startswith("@"):
            module, qualname = spec.split(":")
            owner, attr = qualname.rsplit(".", 1)
            cls = getattr(importlib.import_module(module), owner)
            monkeypatch.setattr(cls, attr, cls.__dict__[attr])
    marked, on = _flight(pieces, specs)
    assert marked == plain
    counts = on[1]
    assert len(counts) == len(specs) and all(n > 0 for n in counts.values())
