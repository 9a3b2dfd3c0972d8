"""The command line shared by the study scripts whose tables ``tools/studies.py`` renders from a JSON file (its
``ScriptTable``): fly, print the table, and with ``--json FILE`` keep the figures in FILE."""

from __future__ import annotations

import argparse
import pathlib
from typing import Callable


def table_script_main(argv: list[str] | None, description: str, results: Callable[[argparse.Namespace], dict],
                      markdown: Callable[[dict], str],
                      add_arguments: Callable[[argparse.ArgumentParser], None] | None = None) -> int:
    """Parse ``argv`` (``--json FILE`` and what ``add_arguments`` adds), compute ``results(args)``, write it to
    FILE as JSON if asked (atomically, folders made) and print ``markdown`` of it; exit status 0."""
    from fprime_lite.osal.atomic import atomic_write_json

    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--json", type=pathlib.Path, metavar="FILE", help="also write the figures to FILE (JSON)")
    if add_arguments is not None:
        add_arguments(parser)
    args = parser.parse_args(argv)
    table = results(args)
    if args.json is not None:
        atomic_write_json(args.json, table)
    print(markdown(table), end="")
    return 0
