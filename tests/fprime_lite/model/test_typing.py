"""The component model's declarations as a type checker sees them (issue #11 item 5)."""

from __future__ import annotations

from pathlib import Path

import pytest

HERE = Path(__file__).parent / "typecheck"
ROOT = Path(__file__).resolve().parents[3]


def _mypy(path: Path) -> tuple[str, int]:
    api = pytest.importorskip("mypy.api", reason="mypy is a test dependency: pip install -e .[test]")
    out, err, status = api.run(["--config-file", str(ROOT / "pyproject.toml"), "--no-incremental",
                                "--follow-imports=silent", str(path)])
    return out + err, status


@pytest.mark.typecheck
def test_declarations_type_check_in_a_component():
    """TYP-011-3: events are callable, channels have write(value), parameters have .value of the
    declared type, output ports are lists of callables, Annotated[str, String(n)] is a string."""
    out, status = _mypy(HERE / "heater.py")
    assert status == 0, out


@pytest.mark.typecheck
def test_wrong_uses_are_reported():
    """TYP-011-4: a str written to an F64 channel, an int to a string channel, an F64 parameter
    read as str and a channel read as a parameter are each reported (4 errors, on those lines)."""
    out, status = _mypy(HERE / "heater_wrong.py")
    lines = (HERE / "heater_wrong.py").read_text().splitlines()
    wrong = {i + 1 for i, line in enumerate(lines) if line.endswith("# wrong")}
    reported = {int(line.split(":")[1]) for line in out.splitlines() if ": error:" in line}
    assert status == 1 and reported == wrong, out


def test_the_sample_component_runs(fprime_harness):
    """TYP-011-5: the type-checked sample is a working component: Annotated[str, String(20)] is a
    bounded string argument (longer is FORMAT_ERROR), the echo and the port call work."""
    import importlib.util

    from fprime_lite import CmdResponse
    spec = importlib.util.spec_from_file_location("heater_sample", HERE / "heater.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    h = fprime_harness(module.Heater("heater"))
    h.send_command("RENAME", "north")
    h.send_raw_command(h.component.opcode("RENAME"), b"\x00\x15" + b"x" * 21)
    assert [r.response for r in h.cmd_responses] == [CmdResponse.OK, CmdResponse.FORMAT_ERROR]
    h.invoke("run", 0)
    assert h.from_port("powerOut")[0].args == (10.0,) and h.events_named("TooCold") == [(15.0,)]
    assert h.tlm_values("Label") == ["north", "ok"]
