"""The tools around a deployment: the runner, the command line, the benchmark, the GDS app, and
the Python entry point (:mod:`fprime_lite.tools.api`): ``from fprime_lite.tools import run, open_run``."""

from fprime_lite.tools.api import RunResult, RunSetupError, open_run, run

__all__ = ["run", "open_run", "RunResult", "RunSetupError"]
