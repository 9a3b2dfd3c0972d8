"""Topology resources: objects a topology builds beside its components (a simulated spacecraft,
a run report) and the roles through which the command line reaches them.

A topology's ``resources:`` entry names a factory by import path. The factory declares itself
with :func:`topology_resource`, optionally taking a *role*: the command line then passes its
options to whichever resource holds that role, without knowing the resource's name or its
application. Roles the tools use:

``simulation``
    takes ``scenario`` (a packaged name or a file), ``settings`` (``KEY.PATH=VALUE`` overrides)
    and ``seed`` — ``fprime-lite run --scenario/--set/--seed``.
``report``
    takes ``truth_interval_s`` — ``fprime-lite run --truth-interval``.

The loader builds only factories marked this way (any other callable named as a resource's
``type`` is refused), and it builds them whenever it loads a topology, ``fprime-lite check``
included. Marking a factory therefore promises that **calling it has no effect outside the
process**: no file written, no process started, no socket opened — those belong in the run hooks
(``begin``, ``finish``) that only ``fprime-lite run`` calls.

A resource wired to the flight computer's reset line (the simulated spacecraft) says so by
deriving from :class:`ResetLine`: the deployment attaches itself to it at start and tells it
before each software restart.
"""
from __future__ import annotations

from abc import ABC, abstractmethod
from typing import Callable, TypeVar

from fprime_lite.model.errors import FprimeLiteError

__all__ = ["topology_resource", "resource_role", "resource_fingerprint", "ROLES", "ResetLine", "RoleOptionError",
           "SimulationEnded"]


class SimulationEnded(BaseException):
    """Raised by a resource when the simulated world cannot go on (a plant whose state is no longer
    finite). It is not a flight-software fault, so it derives from BaseException: the components' fault
    containment (``except Exception``) lets it through, as it does KeyboardInterrupt. ``fprime-lite run``
    ends the flight there, writes every output up to that instant with ``stopped_by`` = :attr:`kind` and
    ``stop_reason`` = the message, and reports the message as the run's problem.

    Args: ``kind``, a short name for ``stopped_by`` ("plant diverged"); ``message``, one line: what
    happened and what to do."""

    def __init__(self, kind: str, message: str) -> None:
        super().__init__(message)
        self.kind = kind
        self.message = message

    def __str__(self) -> str:
        return self.message


class RoleOptionError(FprimeLiteError):
    """A command-line option passed to a resource through its role is wrong (``run --set KEY=VALUE``
    naming no key, a value out of range …). The factory raises it with a complete one-line message
    that names the option; the loader passes it on as it is instead of blaming the topology's args."""

#: Roles a resource may hold, and what the tools pass to it.
ROLES = {
    "simulation": "run --scenario NAME|FILE, --set KEY.PATH=VALUE, --seed N",
    "report": "run --truth-interval SECONDS",
}

F = TypeVar("F", bound=Callable)

_ROLE_ATTRIBUTE = "__fprime_lite_resource_role__"
_FINGERPRINT_ATTRIBUTE = "__fprime_lite_resource_fingerprint__"


def topology_resource(factory: F | None = None, *, role: str | None = None,
                      fingerprint: Callable[[dict], dict] | None = None):
    """Mark ``factory`` (a class or a function) as a topology resource holding ``role``.

    Usable bare (``@topology_resource``) or with a role (``@topology_resource(role="simulation")``).
    ``fingerprint(args)`` (optional) says what the resource would resolve its configuration from,
    given its topology ``args``, without building it: a JSON-able dict (a simulation's scenario
    source, a digest of the values it resolves to) that a campaign manifest records, so a change of
    what a topology's defaults resolve to is seen (:func:`resource_fingerprint`).
    """
    if role is not None and role not in ROLES:
        raise ValueError(f"unknown resource role {role!r}; roles: {', '.join(ROLES)}")

    def mark(f: F) -> F:
        setattr(f, _ROLE_ATTRIBUTE, role or "")
        if fingerprint is not None:
            setattr(f, _FINGERPRINT_ATTRIBUTE, fingerprint)
        return f

    return mark(factory) if factory is not None else mark


def resource_role(factory: object) -> str | None:
    """The role ``factory`` declared with :func:`topology_resource` ('' for none); None if it never
    declared itself a resource."""
    return getattr(factory, _ROLE_ATTRIBUTE, None)


def resource_fingerprint(factory: object, args: dict) -> dict | None:
    """What ``factory`` would resolve its configuration from with topology ``args`` (its
    ``fingerprint`` hook, see :func:`topology_resource`); None when it declared no hook."""
    hook = getattr(factory, _FINGERPRINT_ATTRIBUTE, None)
    return None if hook is None else hook(dict(args))


class ResetLine(ABC):
    """A resource that holds the flight computer's reset line (a simulated spacecraft).

    The deployment calls :meth:`attach_flight_software` once, at its first start, and
    :meth:`flight_software_reset` before each software restart (:class:`~.deployment.Deployment`).
    """

    @abstractmethod
    def attach_flight_software(self, deployment) -> None:
        """Wire the reset line to ``deployment`` (its ``request_reset(kind)`` restarts the software)."""

    @abstractmethod
    def flight_software_reset(self) -> None:
        """The software restarts: reset what the flight computer's reset resets in the hardware."""
