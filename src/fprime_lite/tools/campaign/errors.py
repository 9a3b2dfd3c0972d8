"""The campaign's user-facing errors."""

from __future__ import annotations

from fprime_lite.model.errors import FprimeLiteError

__all__ = ["CampaignError", "RunSetupError", "MetricUnavailable"]


class CampaignError(FprimeLiteError):
    """A campaign cannot start; ``problems`` lists each issue as ``file:line: what — what to do``."""

    def __init__(self, problems: list[str]):
        self.problems = list(problems)
        count = len(self.problems)
        super().__init__(f"{count} problem{'s' if count != 1 else ''} in the campaign:\n"
                         + "\n".join(f"  {p}" for p in self.problems))


class RunSetupError(FprimeLiteError):
    """A run kind cannot build a run; ``key`` is the campaign key at fault (None: the run section)."""

    def __init__(self, message: str, key: str | None = None):
        super().__init__(message)
        self.key = key


class MetricUnavailable(Exception):
    """A metric that cannot be computed for this run; the message is the recorded reason."""
