"""Output folders the user names (``--out DIR``): why one cannot take a run's files, in one wording
for every command that writes into one."""

from __future__ import annotations

import pathlib


def file_in_the_way(path: pathlib.Path) -> str | None:
    """Why ``path`` cannot be an output folder because a file is there, or None."""
    if path.exists() and not path.is_dir():
        return "is a file, not a folder — give a new or empty folder"
    return None


def make_output_folder(path: pathlib.Path) -> str | None:
    """Create ``path`` and its parents unless they are there; None, or why it cannot be created
    and what to do."""
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        return f"cannot create the folder ({exc.strerror}) — choose a folder you can write"
    return None
