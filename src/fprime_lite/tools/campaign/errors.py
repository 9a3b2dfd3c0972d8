"""The campaign's user-facing errors."""

from __future__ import annotations

from fprime_lite.model.errors import FprimeLiteError
from fprime_lite.tools.errors import RunSetupError  # the API's: a run kind raises it for bad input

__all__ = ["CampaignError", "RunSetupError", "MetricUnavailable"]


class CampaignError(FprimeLiteError):
    """A campaign cannot start; ``problems`` lists each issue as ``file:line: what — what to do``."""

    def __init__(self, problems: list[str]):
        self.problems = list(problems)
        count = len(self.problems)
        super().__init__(f"{count} problem{'s' if count != 1 else ''} in the campaign:\n"
                         + "\n".join(f"  {p}" for p in self.problems))


class MetricUnavailable(FprimeLiteError):
    """A metric that cannot be computed for this run; the message is the recorded reason."""
