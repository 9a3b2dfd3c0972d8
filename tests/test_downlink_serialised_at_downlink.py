"""TLM-DEFER: channel values serialised at downlink give the downlink that serialising at write gives.

The reference deployment is flown twice for the same simulated time: once as wired (every component's
``tlmOut`` straight to TlmChan's ``TlmRecv``: values are stored and packed when downlinked) and once
with each of those connections routed through a plain forwarding callable, which TlmChan cannot
recognise, so every write is packed at write time and arrives as bytes through ``TlmRecv`` — what
F´ does. The telemetry packets out of ``PktSend`` must be identical byte for byte. ``RgMaxTime``
(measured on the wall clock) is pinned by a fake ``perf_counter`` so that the two runs may be compared.
"""

import pathlib
import types

import pytest

from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.svc import rate_groups
from fprime_lite.svc.tlm_chan import TlmChan

DEPLOYMENTS = pathlib.Path(__file__).parents[1] / "deployments"


def _tap(port, sink: list) -> None:
    """Append every packet leaving output ``port`` to ``sink`` (keeping its connection, if any)."""
    if not port.is_connected(0):
        port.connect_callable(0, lambda data, context: sink.append(bytes(data)), "test tap")
        return
    downstream = port.calls[0]

    def tap(data, context):
        sink.append(bytes(data))
        downstream(data, context)

    port.calls[0] = tap


def _route_through_callables(topology, tlm: TlmChan) -> int:
    """Replace every ``tlmOut -> tlm.TlmRecv`` connection by a forwarding callable; return how many."""
    recv = tlm.input_port("TlmRecv").entries[0]
    n = 0
    for component in topology.components():
        if "tlmOut" not in component.spec.outputs:
            continue
        port = component.output_port("tlmOut")
        target = port.targets[0]
        if type(target) is tuple and target[0].component is tlm:
            port.disconnect(0)
            port.connect_callable(0, lambda chan_id, time, value: recv(chan_id, time, value), "forwarder")
            n += 1
    return n


def fly(topology_file: pathlib.Path, seconds: float, *, eager: bool):
    loaded = load_topology(topology_file)
    deployment = Deployment(loaded)
    topo = deployment.topology
    tlm = topo.instance(topo.patterns["telemetry"]).component
    assert isinstance(tlm, TlmChan)
    packets: list[bytes] = []
    _tap(tlm.output_port("PktSend"), packets)
    rerouted = _route_through_callables(topo, tlm) if eager else 0
    deployment.start()
    deployment.run_for(seconds)
    deferred = sum(1 for _time, _value, pack in tlm._latest.values() if pack is not None)
    return packets, deferred, rerouted


@pytest.fixture
def pinned_wall_clock(monkeypatch):
    monkeypatch.setattr(rate_groups, "_wall", types.SimpleNamespace(perf_counter=lambda: 0.0))


@pytest.mark.parametrize("deployment", ["proves_ref", "adcs_ref", "coursework"])
def test_downlink_bytes_do_not_depend_on_when_values_are_serialised(deployment, pinned_wall_clock):
    """TLM-DEFER-001: the telemetry downlink of a deployment whose channel values are packed at
    downlink equals, byte for byte, the downlink of the same flight with every value packed at write."""
    topology_file = DEPLOYMENTS / deployment / "topology.yaml"
    deferred_packets, deferred_entries, _ = fly(topology_file, 12.0, eager=False)
    eager_packets, eager_deferred_entries, rerouted = fly(topology_file, 12.0, eager=True)
    # both paths were exercised: values were stored unpacked in one run and never in the other
    assert deferred_entries >= 10 and eager_deferred_entries == 0 and rerouted >= 10
    assert len(deferred_packets) >= 12
    assert len(deferred_packets) == len(eager_packets)
    for i, (a, b) in enumerate(zip(deferred_packets, eager_packets, strict=True)):
        assert a == b, f"telemetry packet {i} differs"
