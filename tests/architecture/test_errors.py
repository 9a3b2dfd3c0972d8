"""One root per package for the errors it raises (docs/architecture.md, "Errors").

Every exception class defined in ``fprime_lite`` derives from ``FprimeLiteError`` (but osal's
``PathRefused``, an OS error of the layer below the root, and ``SimulationEnded``, the run's stop signal);
every one defined in ``detumble`` from
``DetumbleError``, which the framework does not know. The classes are found by importing every
module of both packages, so a new module's error class is checked without being listed here.
"""
from __future__ import annotations

import importlib
import inspect
import pkgutil

import pytest

import detumble
import fprime_lite
from detumble.errors import DetumbleError
from fprime_lite.model.errors import FprimeLiteError, FwAssertionError
from fprime_lite.deploy.resources import SimulationEnded
from fprime_lite.ground.writer_process import OutputWriterError
from fprime_lite.osal.confine import PathRefused
from fprime_lite.tools.campaign.errors import CampaignInterrupted

#: Below the root's layer (osal imports nothing of the model): an OSError by contract. And the run's stop
#: signal when the simulated world cannot go on: a BaseException on purpose (the fault containment's
#: ``except Exception`` must let it through, as it does KeyboardInterrupt), not an error; and a campaign's
#: stop on SIGINT/SIGTERM, a KeyboardInterrupt on purpose (what a Python caller's Ctrl-C handling expects); and the
#: output writer process's failure, an OSError on purpose (a full disk there is reported as one written inline is:
#: the CLI's "cannot write or read", exit 1).
OUTSIDE_THE_ROOT = {PathRefused, SimulationEnded, CampaignInterrupted, OutputWriterError}


def _exception_classes(package) -> list[type[BaseException]]:
    found = []
    for info in pkgutil.walk_packages(package.__path__, package.__name__ + "."):
        try:
            module = importlib.import_module(info.name)
        except ImportError:  # an optional extra (Basilisk, the GDS) that is not installed
            continue
        found += [obj for obj in vars(module).values()
                  if inspect.isclass(obj) and issubclass(obj, BaseException) and obj.__module__ == info.name]
    return found


def test_every_framework_error_is_a_fprime_lite_error():
    """ARCH-010: every exception class of fprime_lite derives from FprimeLiteError."""
    classes = _exception_classes(fprime_lite)
    assert len(classes) > 20
    assert [c.__qualname__ for c in classes if not issubclass(c, FprimeLiteError) and c not in OUTSIDE_THE_ROOT] == []


def test_every_application_error_is_a_detumble_error_and_no_framework_error():
    """ARCH-011: every exception class of detumble derives from DetumbleError, none from FprimeLiteError."""
    classes = _exception_classes(detumble)
    assert len(classes) >= 4
    assert [c.__qualname__ for c in classes if not issubclass(c, DetumbleError)] == []
    assert [c.__qualname__ for c in classes if issubclass(c, FprimeLiteError)] == []


def test_the_other_bases_are_kept():
    """ARCH-012: callers that catch the built-in base still catch the error."""
    from detumble.sim.plant_kernel import KernelUnavailableError
    from detumble.sim.runner import LawError
    from detumble.sim.scenario import ScenarioError
    from fprime_lite.model.errors import SerializationError
    from fprime_lite.tools.stop_condition import StopConditionError

    for cls, base in [(SerializationError, ValueError), (StopConditionError, ValueError),
                      (FwAssertionError, AssertionError), (ScenarioError, ValueError), (LawError, ValueError),
                      (KernelUnavailableError, RuntimeError)]:
        assert issubclass(cls, base), cls


def test_one_run_setup_error():
    """ARCH-013: the API and the campaigns raise the same RunSetupError."""
    from fprime_lite.tools import RunSetupError
    from fprime_lite.tools.api import RunSetupError as ApiRunSetupError
    from fprime_lite.tools.campaign import RunSetupError as CampaignRunSetupError

    assert RunSetupError is ApiRunSetupError is CampaignRunSetupError
    assert RunSetupError("x", "law").key == "law" and RunSetupError("x").key is None


@pytest.mark.parametrize("error, exit_code", [("UserError", 2), ("PluginError", 2), ("FwAssertionError", None)])
def test_the_cli_prints_a_mistake_in_one_line_and_lets_a_broken_invariant_through(monkeypatch, capsys, error,
                                                                                  exit_code):
    """ARCH-014: a FprimeLiteError is one line on stderr, exit 2; FwAssertionError keeps its traceback."""
    from fprime_lite.tools import cli
    from fprime_lite.tools.plugins import PluginError

    cls = {"UserError": cli.UserError, "PluginError": PluginError, "FwAssertionError": FwAssertionError}[error]

    def fails(args):
        raise cls("what is wrong — what to do")

    monkeypatch.setitem(cli.COMMANDS, "check", fails)
    if exit_code is None:
        with pytest.raises(FwAssertionError):
            cli.main(["check"])
        return
    assert cli.main(["check"]) == exit_code
    assert capsys.readouterr().err == "fprime-lite check: what is wrong — what to do\n"
