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
