"""The application's root error.

Every error class of ``detumble`` derives from :class:`DetumbleError`, keeping its other bases
(``ScenarioError`` and ``LawError`` are still ``ValueError``\\ s, ``KernelUnavailableError`` a
``RuntimeError``). It is not a ``FprimeLiteError``: ``control``, ``sim`` and ``analysis`` import no
framework (docs/architecture.md), and the framework never needs to know the application's errors —
a resource's error reaches the user as the ``TopologyError`` the loader makes of it. This module
imports nothing, so every layer of the application may import it.
"""

from __future__ import annotations

__all__ = ["DetumbleError"]


class DetumbleError(Exception):
    """Base class of every error the detumble application raises."""
