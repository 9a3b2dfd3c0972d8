"""adcs_ref flies the AttitudeController's cycle telemetry through its ``tlmRun`` port (issue 32, ctltlm): the port
is the 1 Hz group's member just before TlmChan's ``Run``, and TlmChan sends record for record what it sent when
every 10 Hz cycle wrote (the same flight with that member's port disconnected), with far fewer writes.
"""

import pathlib

from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.model.time import TIME
from fprime_lite.svc.tlm_chan import TlmChan

TOPOLOGY = pathlib.Path(__file__).parents[1] / "deployments" / "adcs_ref" / "topology.yaml"
#: DETUMBLE from 1.2 deg/s: SPIN_STABLE near 51 s (tools/output_identity.py's adcs_ref_modes case)
SLOW_TUMBLE = {"simulation": {"settings": ["initial.rate.magnitude_deg_s=1.2"]}}
SECONDS = 60.0


def _fly(every_cycle_writes: bool):
    """``(TlmChan's sends: (send instant µs, channel id, time bytes, value bytes) in order; the controller's
    writes into TlmChan's table)``."""
    loaded = load_topology(TOPOLOGY, role_overrides=SLOW_TUMBLE)
    components = {c.name: c for c in loaded.topology.components()}
    controller, tlm = components["attitudeController"], components["tlmSend"]
    assert isinstance(tlm, TlmChan)
    group = components["rateGroup1Hz"]
    port = group.output_port("RateGroupMemberOut")
    members = [port.targets[i] for i in range(len(port)) if port.targets[i] is not None]
    names = [(p.component.name, p.name) for p, _ in members]
    # the controller's tlmRun runs just before TlmChan's Run in the 1 Hz group
    assert names[names.index(("tlmSend", "Run")) - 1] == ("attitudeController", "tlmRun")
    if every_cycle_writes:
        index = next(i for i in range(len(port)) if port.targets[i] is not None
                     and port.targets[i][0].component is controller)
        port.disconnect(index)
    clock = loaded.clock
    ours = {c.id for c in controller.channels.values()}
    wall = {c.id for comp in components.values() for name, c in comp.channels.items() if name == "RgMaxTime"}
    sends: list[tuple] = []
    writes = [0]

    class Sent(dict):
        def __setitem__(self, chan_id, entry):
            time, value, pack = entry
            value = value if pack is None else pack(value)
            sends.append((clock.current_us, chan_id, TIME.serialize(time), None if chan_id in wall else value))
            super().__setitem__(chan_id, entry)

    class Latest(dict):
        def __setitem__(self, chan_id, entry):
            if chan_id in ours:
                writes[0] += 1
            super().__setitem__(chan_id, entry)

    tlm._sent = Sent(tlm._sent)
    tlm._latest = Latest(tlm._latest)
    deployment = Deployment(loaded)
    deployment.start()
    deployment.run_for(SECONDS)
    mode = controller.mode.name
    return sends, writes[0], mode


def test_adcs_ref_sends_the_controller_telemetry_every_cycle_writing_sent():
    """TICK-032: 60 s of adcs_ref from a slow tumble (DETUMBLE, then SPIN_STABLE near 51 s): with
    ``attitudeController.tlmRun`` just before ``tlmSend.Run`` in the 1 Hz group TlmChan sends the same records
    (instant, channel, time tag, value bytes, in order; the rate groups' RgMaxTime values are wall time) as with
    that member disconnected (every cycle writes); the controller's writes into TlmChan's table fall to under a
    fifth (one a channel a second against ten). TlmChan's Run is queued, so tlmRun precedes its handler either
    side of it in the group; the topology places it before, where a synchronous Run would need it."""
    every, every_writes, every_mode = _fly(True)
    kept, kept_writes, kept_mode = _fly(False)
    assert every_mode == kept_mode == "SPIN_STABLE"
    assert len(kept) == len(every) > 60 * 30
    for i, (mine, theirs) in enumerate(zip(kept, every, strict=True)):
        assert mine == theirs, f"record {i} differs"
    assert kept_writes < every_writes / 5, (kept_writes, every_writes)
