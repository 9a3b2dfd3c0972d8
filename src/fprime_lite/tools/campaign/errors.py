"""The campaign's user-facing errors."""

from __future__ import annotations

from fprime_lite.model.errors import FprimeLiteError
from fprime_lite.tools.errors import RunSetupError  # the API's: a run kind raises it for bad input

__all__ = ["CampaignError", "CampaignInterrupted", "RunSetupError", "MetricUnavailable"]


class CampaignError(FprimeLiteError):
    """A campaign cannot start; ``problems`` lists each issue as ``file:line: what — what to do``."""

    def __init__(self, problems: list[str]):
        self.problems = list(problems)
        count = len(self.problems)
        super().__init__(f"{count} problem{'s' if count != 1 else ''} in the campaign:\n"
                         + "\n".join(f"  {p}" for p in self.problems))


class MetricUnavailable(FprimeLiteError):
    """A metric that cannot be computed for this run; the message is the recorded reason."""


class CampaignInterrupted(KeyboardInterrupt):
    """SIGINT or SIGTERM ended a campaign run with ``interruptible=True``: the rows that came back are
    in ``out`` (parts, ``results.parquet``, a manifest whose status is ``interrupted``) and the cluster
    is shut down. ``signal``: ``"SIGINT"``/``"SIGTERM"``; ``done``/``planned``: rows recorded / runs
    in the plan."""

    def __init__(self, signal: str, done: int, planned: int, out):
        self.signal, self.done, self.planned, self.out = signal, done, planned, out
        super().__init__(f"interrupted by {signal} after {done} of {planned} runs")
