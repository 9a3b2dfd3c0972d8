"""How much disk a long run's outputs would take, measured before it flies (``fprime-lite run``).

A run streams its logs (``channels.csv``, ``channels_wide.csv``, ``events.log``, the reports' truth
logs) for the whole flight: about 4 kB per simulated second for the reference deployment, so a year is
over 100 GB. Before a run longer than :data:`CHECK_ABOVE_S` flies, :func:`estimate_output_bytes` flies
the same deployment for :data:`PROBE_S` simulated seconds into a temporary folder and scales what it
wrote to the requested duration; :func:`check_disk` refuses a run whose estimate exceeds the free
space of the output folder's disk, or :data:`ASK_ABOVE_BYTES`, unless ``--force``.
"""
from __future__ import annotations

import pathlib
import shutil
import tempfile
from typing import Callable

from fprime_lite.tools.errors import RunSetupError

__all__ = ["CHECK_ABOVE_S", "PROBE_S", "ASK_ABOVE_BYTES", "OutputEstimate", "estimate_output_bytes", "check_disk"]

#: Runs longer than this (simulated seconds, 6 h) are estimated before they fly.
CHECK_ABOVE_S = 6 * 3600.0
#: The probe flight's length, simulated seconds.
PROBE_S = 60.0
#: An estimate above this asks for ``--force`` even when the disk has room (10 GB).
ASK_ABOVE_BYTES = 10e9
#: Share of the free space a run may fill.
FREE_SHARE = 0.9

_FIXED = ("dictionary.json", "summary.json")  # written once, whatever the duration


class OutputEstimate:
    """``fixed_bytes`` (written once) + ``bytes_per_s`` × duration."""

    def __init__(self, fixed_bytes: int, bytes_per_s: float) -> None:
        self.fixed_bytes = fixed_bytes
        self.bytes_per_s = bytes_per_s

    def bytes_for(self, duration_s: float) -> float:
        return self.fixed_bytes + self.bytes_per_s * duration_s

    def duration_for(self, budget_bytes: float) -> float:
        """The longest duration whose outputs fit ``budget_bytes``."""
        return max(0.0, (budget_bytes - self.fixed_bytes) / self.bytes_per_s) if self.bytes_per_s > 0 else float("inf")


def estimate_output_bytes(fly: Callable[[pathlib.Path, float], object], probe_s: float = PROBE_S) -> OutputEstimate:
    """Fly ``fly(folder, duration_s)`` (a fresh deployment, quietly, no plots) for ``probe_s`` and measure."""
    with tempfile.TemporaryDirectory(prefix="fprime-lite-disk-probe-") as tmp:
        folder = pathlib.Path(tmp) / "probe"
        fly(folder, probe_s)
        fixed = streamed = 0
        for f in folder.rglob("*"):
            if f.is_file():
                size = f.stat().st_size
                if f.name in _FIXED:
                    fixed += size
                else:
                    streamed += size
    return OutputEstimate(fixed, streamed / probe_s)


def _existing(path: pathlib.Path) -> pathlib.Path:
    path = path.resolve()
    while not path.exists() and path != path.parent:
        path = path.parent
    return path


def _size(n: float) -> str:
    for unit, scale in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if n >= scale:
            return f"{n / scale:,.1f} {unit}"
    return f"{n:,.0f} B"


#: How the remedies are spelt: the command line's options, or the Python API's arguments (``run()``).
_SPELLING = {
    "cli": {"duration": "--duration", "force": "pass --force", "truth": "--truth-interval"},
    "api": {"duration": "duration_s", "force": "pass force=True", "truth": "truth_interval_s="},
}


def check_disk(estimate: OutputEstimate, duration_s: float, out: pathlib.Path, *, spelling: str = "cli") -> None:
    """Raise :class:`RunSetupError` (one line: the estimate, the room, what to do) when the outputs of a
    ``duration_s`` run would not fit in :data:`FREE_SHARE` of the free space under ``out`` or exceed
    :data:`ASK_ABOVE_BYTES`. ``spelling`` names the remedies as the caller offers them (``"cli"``:
    ``--duration``/``--force``; ``"api"``: ``duration_s``/``force=True``)."""
    words = _SPELLING[spelling]
    need = estimate.bytes_for(duration_s)
    free = shutil.disk_usage(_existing(out)).free
    budget = min(FREE_SHARE * free, ASK_ABOVE_BYTES)
    if need <= budget:
        return
    rate = f"{_size(estimate.bytes_per_s * 3600)} per simulated hour, measured over a {PROBE_S:.0f} s probe flight"
    longest = estimate.duration_for(budget)
    force = words["force"].split(" ", 1)[1]
    room = (f"{_size(free)} free there" if FREE_SHARE * free < ASK_ABOVE_BYTES
            else f"more than {_size(ASK_ABOVE_BYTES)} asks for {force}")
    raise RunSetupError(f"{words['duration']} {duration_s:g} s would write about {_size(need)} of outputs ({rate}); "
                        f"{room} — shorten {words['duration']} (at most about {longest:,.0f} s here), write fewer "
                        f"truth rows ({words['truth']}), or {words['force']} to fly it anyway")
