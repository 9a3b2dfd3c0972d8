"""FPP models in (issue 30, docs/fpp.md): the reference deployments as FPP, bound to their Python
implementations, give fprime-lite's dictionary of the YAML form, and fpp-to-dict's dictionary of
the same FPP differs from it only by the differences named below."""

from __future__ import annotations

import json
import pathlib
import shutil
import subprocess
import sys

import pytest

pytest.importorskip("fpp", reason="FPP models need fprime-fpp-python (the test extra installs it)")

from fprime_lite.deploy.dictionary import build_dictionary  # noqa: E402
from fprime_lite.deploy.fpp import export  # noqa: E402
from fprime_lite.deploy.fpp.dict_diff import dictionary_differences  # noqa: E402
from fprime_lite.deploy.fpp.loader import FppError, load_fpp  # noqa: E402
from fprime_lite.deploy.topology_loader import load_topology  # noqa: E402
from fprime_lite.tools.cli import main  # noqa: E402

#: several seconds each on 2 cores (fpp-to-dict, three deployments loaded both ways); CI runs them
pytestmark = pytest.mark.slow

ROOT = pathlib.Path(__file__).resolve().parents[3]
DEPLOYMENTS = ["proves_ref", "adcs_ref", "coursework"]


def _fpp_files(deployment: str) -> list[str]:
    folder = ROOT / "deployments" / deployment / "fpp"
    return [str(folder / "components.fpp"), str(folder / "topology.fpp")]


def _known_differences(deployment: str) -> list[str]:
    """What fprime-lite's dictionary has that fpp-to-dict 3.0's has not (docs/fpp.md "Differences"):
    the definitions /work/shared/spec/fprime_compat.md has every dictionary carry and fprime-gds
    4.4.1 reads (ComCfg.Apid, whose GDS fallback numbers FW_PACKET_IDLE 5 where F´ v4 says 6; the
    ComCfg constants; FwIdType, FwPrmIdType). F´'s own configuration marks them with FPP's
    `dictionary` specifier, which fpp-python 3.4 takes and fpp-to-dict 3.0 does not parse; 3.0
    lists a definition only when a command, event, channel or parameter uses it."""
    return ["constants ComCfg.SpacecraftId: only in ours",
            "constants ComCfg.TmFrameFixedSize: only in ours",
            "typeDefinitions ComCfg.Apid: only in ours",
            "typeDefinitions FwIdType: only in ours",
            "typeDefinitions FwPrmIdType: only in ours"]


@pytest.mark.parametrize("deployment", DEPLOYMENTS)
def test_fpp_and_yaml_forms_give_the_same_dictionary(deployment):
    """FPP-001: `fprime-lite dict` of the FPP form equals that of the YAML form (ids, opcodes,
    types, formats, limits, defaults)."""
    model = load_fpp(_fpp_files(deployment))
    from_fpp = build_dictionary(model)  # type: ignore[arg-type]
    from_yaml = build_dictionary(load_topology(ROOT / "deployments" / deployment / "topology.yaml").topology)
    assert dictionary_differences(from_fpp, from_yaml, left="fpp", right="yaml") == []
    assert len(from_fpp["commands"]) > 50 and len(from_fpp["events"]) > 50


@pytest.mark.parametrize("deployment", DEPLOYMENTS)
def test_fpp_to_dict_gives_fprime_lites_dictionary_but_for_the_named_differences(deployment, tmp_path):
    """FPP-002: F´'s own fpp-to-dict, run on the deployment's FPP with the framework's FPP as
    imports, builds the dictionary fprime-lite builds, but for the differences docs/fpp.md names."""
    tool = shutil.which("fpp-to-dict")
    if tool is None:
        pytest.skip("fpp-to-dict is not installed (pip install 'fprime-lite[fpp]' installs fprime-fpp-to-dict)")
    imports = ",".join(str(p) for p in export.framework_files())
    subprocess.run([tool, "-i", imports, *_fpp_files(deployment), "-d", str(tmp_path)], check=True,
                   capture_output=True, timeout=120)
    (theirs_path,) = tmp_path.glob("*Dictionary.json")
    theirs = json.loads(theirs_path.read_text())
    ours = build_dictionary(load_topology(ROOT / "deployments" / deployment / "topology.yaml").topology)
    assert dictionary_differences(ours, theirs) == _known_differences(deployment)


def test_the_committed_fpp_is_what_the_exporter_writes_now():
    """FPP-003: framework/svc.fpp and each deployment's FPP are what the exporter writes from the
    Python today (regenerate: python -m fprime_lite.deploy.fpp.export --framework / TOPOLOGY)."""
    assert (export.FRAMEWORK_DIR / "svc.fpp").read_text() == export.framework_svc_text()
    for deployment in DEPLOYMENTS:
        texts = export.deployment_texts(f"deployments/{deployment}/topology.yaml")
        for name, text in texts.items():
            path = ROOT / "deployments" / deployment / "fpp" / name
            assert path.read_text() == text, f"{path} is stale: regenerate it"


def _mutated(tmp_path, old: str, new: str) -> list[str]:
    files = _fpp_files("proves_ref")
    text = pathlib.Path(files[0]).read_text()
    assert old in text
    (tmp_path / "components.fpp").write_text(text.replace(old, new, 1))
    (tmp_path / "topology.fpp").write_text(pathlib.Path(files[1]).read_text())
    return [str(tmp_path / "components.fpp"), str(tmp_path / "topology.fpp")]


@pytest.mark.parametrize("old, new, expected", [
    ("sync command SET_MODE(mode: Components.DetumbleMode) opcode 0x0",
     "sync command SET_MODE(mode: Components.DetumbleMode) opcode 0x0\n    sync command NEW_CMD opcode 0x70",
     "command NEW_CMD has no handler"),
    ("sync command SET_MODE(mode: Components.DetumbleMode) opcode 0x0",
     "sync command SET_MODE(level: Components.DetumbleMode) opcode 0x0",
     "command SET_MODE's handler takes (mode), FPP declares (level)"),
    ('severity warning low id 0x0 format "Failed to enable detumbling',
     'severity warning high id 0x0 format "Failed to enable detumbling',
     "event EnableFailedSafeMode is EventSeverity.WarningHigh in FPP, WARNING_LO in Python"),
    ("output port xPlusStart: Drv.StartMagnetorquer", "output port xPlusStart: [2] Drv.StartMagnetorquer",
     "port xPlusStart has 2 index(es) in FPP, 1 in Python"),
    ("sync input port setMode: Components.SetDetumbleMode", "guarded input port setMode: Components.SetDetumbleMode",
     "input port setMode is guarded in FPP, sync in Python"),
    ("sync input port setMode: Components.SetDetumbleMode", "sync input port setMode: Components.SystemModeChanged",
     "port setMode is of type Components.SystemModeChanged in FPP, Components.SetDetumbleMode in Python"),
    ("sync command SET_MODE(mode: Components.DetumbleMode) opcode 0x0",
     "sync command SET_MODE(mode: Components.DetumbleMode) opcode 0x7F",
     "command SET_MODE has opcode 0x7F in FPP, 0x0 in Python"),
])
def test_a_mismatch_is_refused_with_both_places(tmp_path, old, new, expected):
    """FPP-004: an FPP member the Python class does not implement as declared is refused before
    flying, naming the FPP file:line and the Python class's file:line."""
    with pytest.raises(FppError) as caught:
        load_fpp(_mutated(tmp_path, old, new))
    lines = [p for p in caught.value.problems if expected in p]
    assert lines, caught.value.problems
    assert lines[0].startswith(str(tmp_path / "components.fpp") + ":")
    assert "detumble_manager.py:" in lines[0]


def test_a_component_without_implementation_is_refused(tmp_path):
    """FPP-005: a component that no rule binds to a class is refused, saying what was tried."""
    files = _mutated(tmp_path, "@ fprime-lite: detumble.components.detumble_manager.DetumbleManager\n", "")
    with pytest.raises(FppError) as caught:
        load_fpp(files)
    assert any("component Components.DetumbleManager has no Python implementation" in p and "detumble_manager.py"
               in p for p in caught.value.problems), caught.value.problems


def test_the_verbs_take_fpp_files(tmp_path, capsys):
    """FPP-006: check, dict and graph take the FPP files of a topology."""
    files = _fpp_files("proves_ref")
    assert main(["check", *files]) == 0
    # the FPP form binds every instance of the topology YAML it was exported from
    yaml_instances = len(load_topology(ROOT / "deployments" / "proves_ref" / "topology.yaml").topology.instances)
    assert f"{yaml_instances} instances bound" in capsys.readouterr().out
    out = tmp_path / "d.json"
    assert main(["dict", *files, "-o", str(out)]) == 0
    yaml_dict = build_dictionary(load_topology(ROOT / "deployments/proves_ref/topology.yaml").topology)
    assert dictionary_differences(json.loads(out.read_text()), yaml_dict) == []
    assert main(["graph", *files, "--format", "mermaid"]) == 0
    assert "CdhCore_cmdDisp" in capsys.readouterr().out
    assert main(["check", files[0]]) == 0  # the components alone: each bound to its class
    assert "Components.DetumbleManager → detumble.components.detumble_manager.DetumbleManager" in \
        capsys.readouterr().out


def _run(argv: list[str], out: pathlib.Path) -> int:
    return main(["run", *argv, "--duration", "10", "--out", str(out), "--no-plots", "--no-progress"])


def test_run_flies_the_fpp_form_as_the_yaml_form(tmp_path):
    """FPP-008: `fprime-lite run components.fpp topology.fpp` (the FPP's instances and connections,
    the run file's constructor arguments, divisors and resources) flies as the YAML form: the same
    events, dictionary and truth, the same channels but for the rate groups' wall-clock RgMaxTime."""
    assert _run(_fpp_files("coursework"), tmp_path / "fpp") == 0
    assert _run([str(ROOT / "deployments/coursework/topology.yaml")], tmp_path / "yaml") == 0
    for name in ("events.log", "dictionary.json", "truth.csv"):
        assert (tmp_path / "fpp" / name).read_bytes() == (tmp_path / "yaml" / name).read_bytes(), name

    def channels(folder: str) -> list[str]:
        return [line for line in (tmp_path / folder / "channels.csv").read_text().splitlines()
                if "RgMaxTime" not in line]
    assert len(channels("fpp")) > 100 and channels("fpp") == channels("yaml")
    assert "CdhCore.cmdDisp.OpCodeDispatched" in (tmp_path / "fpp" / "events.log").read_text()


def _coursework_copy(tmp_path: pathlib.Path, run_text: str | None) -> list[str]:
    folder = ROOT / "deployments" / "coursework" / "fpp"
    for name in ("components.fpp", "topology.fpp"):
        (tmp_path / name).write_text((folder / name).read_text())
    if run_text is not None:
        (tmp_path / "run.yaml").write_text(run_text)
    return [str(tmp_path / "components.fpp"), str(tmp_path / "topology.fpp")]


@pytest.mark.parametrize("change, expected", [
    (None, "run.yaml: no run file — an FPP topology does not say the constructor arguments"),
    (("      divisor: 100\n", ""), "rate group CourseworkDeployment.rateGroup10Hz has no divisor"),
    (("      wheelY:\n        args:\n          spacecraft: $spacecraft\n          wheel: 1\n", ""),
     "instance CourseworkDeployment.wheelY (Components.ReactionWheelDriver, ReactionWheelDriver) needs constructor "
     "argument(s) spacecraft, wheel — give them in modules.CourseworkDeployment.instances.wheelY.args"),
    (("rate_groups:\n", "connections: {}\nrate_groups:\n"), "'connections' is the FPP topology's connections"),
])
def test_run_of_fpp_refuses_what_the_run_file_lacks(tmp_path, capsys, change, expected):
    """FPP-009: what an FPP topology does not say and the run file does not give (no run file, a
    divisor, a constructor argument) or gives twice is refused before anything flies, exit 2."""
    run_text = None
    if change is not None:
        run_text = (ROOT / "deployments/coursework/fpp/run.yaml").read_text()
        assert change[0] in run_text
        run_text = run_text.replace(change[0], change[1], 1)
    files = _coursework_copy(tmp_path, run_text)
    assert _run(files, tmp_path / "out") == 2
    assert expected in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_load_and_bind_of_proves_ref_leaves_the_plant_and_the_scenario_schema_unimported():
    """FPP-030: binding proves_ref's FPP imports each component's module, and those need only the
    spacecraft's name: the plant and the scenario schema (the bulk of the cold load, docs/fpp.md)
    are imported when a spacecraft is made, not by load + bind."""
    folder = ROOT / "deployments" / "proves_ref" / "fpp"
    code = ("import sys; from fprime_lite.deploy.fpp.loader import load_fpp; "
            f"m = load_fpp([{str(folder / 'components.fpp')!r}, {str(folder / 'topology.fpp')!r}]); "
            "print(len(m.instances), sorted(n for n in ('detumble.sim.plant', 'detumble.sim.scenario') "
            "if n in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True, timeout=120)
    assert out.stdout.split() == ["65", "[]"], out.stdout
