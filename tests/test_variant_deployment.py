"""The variant deployment (extends the reference; BDotDetumble provides the dipole), and `extends`."""

import pathlib
import textwrap

import pytest

from fprime_lite.tools.runner import run_deployment
from fprime_lite.deploy.topology_loader import TopologyError, load_topology

DEPLOYMENT = pathlib.Path(__file__).parents[1] / "deployments" / "proves_ref"


def test_variant_wires_bdot_detumble_as_the_dipole_provider(tmp_path):
    loaded = load_topology(DEPLOYMENT / "topology_bdot_detumble.yaml")
    topo = loaded.topology
    manager = topo.instance("ReferenceDeployment.detumbleManager").component
    assert manager.output_port("dipoleMomentGet").target_name(0) == "bdotDetumble.dipoleMomentGet[0]"
    assert len(topo.instances) == len(load_topology(DEPLOYMENT / "topology.yaml").topology.instances) + 1
    summary = run_deployment(loaded, tmp_path, duration_s=120.0, plots=False)
    provider = topo.instance("ReferenceDeployment.bdotDetumble").component
    assert provider.GainParam.written, "BDotDetumble telemeters its gain on every computation"
    assert summary["final_rate_deg_s"] < summary["initial_rate_deg_s"] - 1.0


def write(folder, name, text):
    path = folder / name
    path.write_text(textwrap.dedent(text))
    return path


BASE = """\
deployment: Base
modules:
  Core:
    instances:
      driver: {type: fprime_lite.svc.rate_group_driver.RateGroupDriver, base_id: 0x100}
      rg: {type: fprime_lite.svc.rate_groups.PassiveRateGroup, base_id: 0x200}
rate_groups:
  driver: Core.driver
  base_rate_hz: 100
  groups:
    Core.rg: {divisor: 10, members: []}
"""


def test_extends_merges_instances_and_overrides_scalars(tmp_path):
    (tmp_path / "base").mkdir()
    write(tmp_path / "base", "base.yaml", BASE)
    variant = write(tmp_path, "variant.yaml", """\
    extends: base/base.yaml
    deployment: Variant
    modules:
      Core:
        instances:
          rg2: {type: fprime_lite.svc.rate_groups.PassiveRateGroup, base_id: 0x300}
    """)
    topo = load_topology(variant).topology
    assert topo.deployment == "Variant"
    assert set(topo.instances) == {"Core.driver", "Core.rg", "Core.rg2"}


def test_errors_in_the_base_file_name_the_base_file(tmp_path):
    write(tmp_path, "base.yaml", BASE.replace("base_id: 0x200", "base_id: -1"))
    variant = write(tmp_path, "variant.yaml", "extends: base.yaml\n")
    with pytest.raises(TopologyError, match=r"base\.yaml:6: instance Core\.rg: base_id must be an integer"):
        load_topology(variant)


def test_extends_cycle_and_missing_base(tmp_path):
    write(tmp_path, "a.yaml", "extends: b.yaml\ndeployment: A\nmodules: {}\n")
    write(tmp_path, "b.yaml", "extends: a.yaml\ndeployment: B\nmodules: {}\n")
    with pytest.raises(TopologyError, match=r"makes a cycle of topology files"):
        load_topology(tmp_path / "a.yaml")
    write(tmp_path, "c.yaml", "extends: nowhere.yaml\ndeployment: C\nmodules: {}\n")
    with pytest.raises(TopologyError, match=r"c\.yaml:1: base topology 'nowhere\.yaml' not found"):
        load_topology(tmp_path / "c.yaml")
