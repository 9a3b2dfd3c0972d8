"""Exceptions raised by fprime_lite.

Every error names what is wrong and, where it can, what to do instead. Errors that a user's own
declaration or wiring causes are raised as early as possible: declaration errors when the component
class is created, connection errors when ports are connected.
"""

from __future__ import annotations

import difflib
from typing import Iterable


class FprimeLiteError(Exception):
    """Base class of every fprime_lite error."""


class DeclarationError(FprimeLiteError):
    """A component, port type or data type declaration is inconsistent.

    Raised when the class is created, with the class and member named in the message.
    """


def check_member_name(name, what: str):
    """``name`` if it is None or a valid F´ member name (an identifier); else DeclarationError."""
    if name is not None and not (isinstance(name, str) and name.isidentifier()):
        raise DeclarationError(f"{what} name must be an identifier, got {name!r}")
    return name


def closest(word, choices: Iterable[str]) -> str | None:
    """The choice closest to ``word`` (difflib's; the one suggestion of every reader), or None."""
    guess = difflib.get_close_matches(str(word), list(choices), n=1)
    return guess[0] if guess else None


def did_you_mean(word, choices: Iterable[str], otherwise: str, template: str = "did you mean '{}'?") -> str:
    """The hint of a message about an unknown name: ``template`` filled with the choice
    :func:`closest` to ``word``, or ``otherwise`` when none is close."""
    guess = closest(word, choices)
    return template.format(guess) if guess is not None else otherwise


def check_units(units, what: str):
    """``units`` if it is None or a non-empty text without ``]`` (it is shown as ``name [units]``);
    else DeclarationError."""
    if units is not None and (not isinstance(units, str) or not units.strip() or "]" in units):
        raise DeclarationError(f"{what} units must be a non-empty text without ']', got {units!r}")
    return units


class SerializationError(FprimeLiteError, ValueError):
    """A value does not fit its F´ type, or bytes do not deserialize to that type."""


class PortConnectionError(FprimeLiteError):
    """Two ports cannot be connected (type mismatch, index out of range, already connected).

    ``what`` says what is wrong and ``fix`` what to do (may be empty); the message is
    ``what — fix``, so callers that add a location need not take the text apart.
    """

    def __init__(self, what: str, fix: str = ""):
        self.what = what
        self.fix = fix
        super().__init__(f"{what} — {fix}" if fix else what)


class UnconnectedPortError(FprimeLiteError):
    """An output port was called while nothing is connected to it."""


class QueueFullError(FprimeLiteError):
    """An async input port's queue was full and its overflow behaviour is ``assert``."""


class FwAssertionError(AssertionError):
    """A framework invariant was broken (F´'s FW_ASSERT).

    The message names the component and the port or member involved.
    """
