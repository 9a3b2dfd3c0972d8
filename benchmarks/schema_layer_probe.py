"""The evidence of decision 0009: the same mistakes given to today's readers and to pydantic 2.

    python benchmarks/schema_layer_probe.py

For a few mistakes the tests pin (an unknown key, a value out of range, a bool or a string where a
number belongs), prints what the topology, scenario and campaign readers say and what a pydantic
model of the same section says (``loc``, ``type``, ``msg``); then what importing pydantic and the
scenario reader costs in a fresh interpreter, and what validating one small section costs.
pydantic is not a dependency of fprime-lite: it is installed with the ``test`` extra (fprime-gds
needs it). Nothing here is imported by the product.
"""

from __future__ import annotations

import pathlib
import subprocess
import sys
import tempfile
import time

TOPOLOGY = """\
deployment: Demo
modules:
  Demo:
    instances:
      driver: {type: fprime_lite.svc.rate_group_driver.RateGroupDriver, base_id: 0x100, queue_sise: 3}
      rg: {type: fprime_lite.svc.rate_groups.PasiveRateGroup, base_id: 0x200}
rate_groups:
  driver: Demo.driver
  base_rate_hz: 10
  groups:
    Demo.rg: {divisor: 0, ofset: 1}
"""
SCENARIO = "orbit:\n  altitud_km: 400\n  inclination_deg: true\nspacecraft:\n  mass_kg: -1\n"
CAMPAIGN = "campaign: probe\nrun: {kind: plant, scenario: default, duration_s: 10}\nseeds: 0\nmetrix: [settle_s]\n"


def ours(tmp: pathlib.Path) -> None:
    from detumble.sim.scenario import ScenarioError, parse_scenario
    from fprime_lite.deploy.topology_loader import TopologyError, load_topology
    from fprime_lite.tools.campaign.errors import CampaignError
    from fprime_lite.tools.campaign.spec import load_campaign

    (tmp / "topology.yaml").write_text(TOPOLOGY)
    (tmp / "campaign.yaml").write_text(CAMPAIGN)
    for label, call, error in (("topology", lambda: load_topology(tmp / "topology.yaml"), TopologyError),
                               ("scenario", lambda: parse_scenario(SCENARIO, "scenario.yaml"), ScenarioError),
                               ("campaign", lambda: load_campaign(tmp / "campaign.yaml"), CampaignError)):
        try:
            call()
        except error as exc:
            problems = getattr(exc, "problems", None) or [str(exc)]
            for problem in problems:
                print(f"  ours  {label:9} {problem.replace(str(tmp) + '/', '')}")


def theirs() -> None:
    from pydantic import BaseModel, ConfigDict, Field, ValidationError

    class RateGroup(BaseModel):
        model_config = ConfigDict(extra="forbid", strict=True)
        divisor: int = Field(ge=1, le=0xFFFFFFFF)
        offset: int = 0
        members: list[str] = []

    class Instance(BaseModel):
        model_config = ConfigDict(extra="forbid", strict=True)
        type: str
        base_id: int = Field(0, ge=0, le=0xFFFFFFFF)
        queue_size: int | None = Field(None, ge=1, le=1_000_000)

    class Orbit(BaseModel):
        model_config = ConfigDict(extra="forbid", strict=True)
        altitude_km: float = Field(420.0, gt=0)
        inclination_deg: float = 51.6

    class Spacecraft(BaseModel):
        model_config = ConfigDict(extra="forbid", strict=True)
        mass_kg: float = Field(1.3, gt=0)

    class Scenario(BaseModel):
        model_config = ConfigDict(extra="forbid", strict=True)
        orbit: Orbit = Orbit()
        spacecraft: Spacecraft = Spacecraft()

    for label, model, data in (
            ("topology", Instance, {"type": "fprime_lite.svc.rate_group_driver.RateGroupDriver", "base_id": 0x100,
                                    "queue_sise": 3}),
            ("topology", RateGroup, {"divisor": 0, "ofset": 1}),
            ("scenario", Scenario, {"orbit": {"altitud_km": 400, "inclination_deg": True},
                                    "spacecraft": {"mass_kg": -1}}),
            ("scenario", Orbit, {"altitude_km": "4.2e5"})):
        try:
            model.model_validate(data)
        except ValidationError as exc:
            for e in exc.errors():
                print(f"  pyd   {label:9} loc={e['loc']} type={e['type']}: {e['msg']}")


def import_ms(statement: str, repeat: int = 3) -> float:
    """Best wall time of ``statement`` in a fresh interpreter, in ms."""
    code = f"import time; t = time.perf_counter(); {statement}; print(time.perf_counter() - t)"
    return min(float(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                                    check=True).stdout) for _ in range(repeat)) * 1000


def main() -> None:
    print("the same mistakes:")
    with tempfile.TemporaryDirectory() as tmp:
        ours(pathlib.Path(tmp))
    theirs()
    print("cost (best of 3, fresh interpreter):")
    print(f"  import yaml                          {import_ms('import yaml'):7.1f} ms")
    print(f"  from pydantic import BaseModel       {import_ms('from pydantic import BaseModel'):7.1f} ms")
    print(f"  import detumble.sim.scenario         {import_ms('import detumble.sim.scenario'):7.1f} ms")
    from pydantic import BaseModel, ConfigDict, Field

    from detumble.sim.scenario import _Ctx, _orbit, _Section  # the reader's own orbit section

    class Orbit(BaseModel):
        model_config = ConfigDict(extra="forbid", strict=True)
        altitude_km: float = Field(420.0, gt=0)
        inclination_deg: float = 51.6

    data = {"altitude_km": 500.0, "inclination_deg": 97.0}
    n = 5000
    t = time.perf_counter()
    for _ in range(n):
        Orbit.model_validate(data)
    pyd = (time.perf_counter() - t) / n * 1e6
    t = time.perf_counter()
    for _ in range(n):
        _orbit(_Section(data, ("orbit",), _Ctx("scenario.yaml", {})))
    own = (time.perf_counter() - t) / n * 1e6
    print(f"  the orbit section, 2 keys: pydantic  {pyd:7.1f} µs")
    print(f"  the orbit section, 2 keys: ours      {own:7.1f} µs (all 12 keys read, defaults filled)")


if __name__ == "__main__":
    main()
