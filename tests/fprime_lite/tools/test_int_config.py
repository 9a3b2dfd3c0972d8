"""Each reference deployment ships the ``int_config.json`` that F´'s reusable integration suites read
(``fprime-lite conformance`` passes it as ``--deployment-config``): every F´ component name maps to an
instance of that component type in the deployment."""

from __future__ import annotations

import json
import pathlib

import pytest

from fprime_lite.tools.api import load

ROOT = pathlib.Path(__file__).parents[3]
DEPLOYMENTS = sorted(p.parent for p in (ROOT / "deployments").glob("*/topology.yaml"))

#: F´ component → the fprime-lite class that stands for it.
TYPES = {
    "Svc.CommandDispatcher": "CmdDispatcher", "Svc.EventManager": "EventManager", "Svc.Health": "Health",
    "Svc.Version": "Version", "Svc.TlmChan": "TlmChan", "Svc.FileUplink": "FileUplink",
    "Svc.FileDownlink": "FileDownlink", "Svc.FileManager": "FileManager", "Svc.PrmDb": "PrmDb",
    "Svc.CmdSequencer": "CmdSequencer",
}
#: What F´'s suites ask for (get_mnemonic keys in ../shared/upstream/fprime_int).
NEEDED = {"Svc.CommandDispatcher", "Svc.EventManager", "Svc.Health", "Svc.FileDownlink", "Svc.FileManager",
          "Svc.PrmDb", "Svc.PrmDb.filename"}


@pytest.mark.parametrize("folder", DEPLOYMENTS, ids=lambda p: p.name)
def test_the_deployment_config_names_instances_of_the_right_types(folder):
    config = json.loads((folder / "int_config.json").read_text())
    assert NEEDED <= set(config), sorted(NEEDED - set(config))
    assert config["Svc.PrmDb.filename"].startswith("/")  # fprime_test_api.get_prm_db_path insists
    topology = load(str(folder / "topology.yaml")).topology
    for fprime_name, instance in config.items():
        if fprime_name == "Svc.PrmDb.filename":
            continue
        assert type(topology.instance(instance).component).__name__ == TYPES[fprime_name], (fprime_name, instance)


@pytest.mark.parametrize("folder", DEPLOYMENTS, ids=lambda p: p.name)
def test_every_reference_deployment_takes_the_ground_link(folder):
    """conformance flies each deployment with the ground link: its ids must not clash (the coursework
    star tracker has the link's default block 0x10070000, so the link moves above every base id)."""
    from fprime_lite.deploy.com_stack import add_ground_link
    from fprime_lite.svc.ground_link import GROUND_LINK_BASE_ID

    topology = load(str(folder / "topology.yaml")).topology
    link = add_ground_link(topology)
    bases = {i.component.base_id for i in topology.instances.values() if i.component is not link}
    if GROUND_LINK_BASE_ID in bases:
        assert link.base_id == (max(bases) & ~0xFFF) + 0x1000
    else:
        assert link.base_id == GROUND_LINK_BASE_ID  # the reference deployment's dictionary keeps its ids
