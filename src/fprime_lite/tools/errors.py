"""The one error of a run that cannot be set up, shared by the Python API and the campaigns."""

from __future__ import annotations

from fprime_lite.model.errors import FprimeLiteError

__all__ = ["RunSetupError"]


class RunSetupError(FprimeLiteError):
    """A mistake in what a run was asked to do (a path, an option, a campaign value); the message
    says what to change. ``key`` is the campaign key at fault, when a campaign's run kind raised it
    (None: the run section, or not a campaign)."""

    def __init__(self, message: str, key: str | None = None):
        super().__init__(message)
        self.key = key
