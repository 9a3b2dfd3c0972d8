"""The command line shared by the study scripts whose tables ``tools/studies.py`` renders from a JSON file (its
``ScriptTable``): fly, print the table, and with ``--json FILE`` keep the figures in FILE."""

from __future__ import annotations

import argparse
import importlib
import pathlib
import sys
from types import ModuleType
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


def runs_table_script_main(argv: list[str] | None, description: str, results: Callable[[pathlib.Path], dict],
                           markdown: Callable[[dict], str], runs_dir: pathlib.Path) -> int:
    """:func:`table_script_main` for a script that flies runs: ``--runs DIR`` (default ``runs_dir``) is where the
    runs' folders go, and ``results(DIR)`` flies them."""
    def option(parser: argparse.ArgumentParser) -> None:
        parser.add_argument("--runs", type=pathlib.Path, default=runs_dir,
                            help=f"where the runs' folders go (default {runs_dir})")

    return table_script_main(argv, description, lambda args: results(args.runs), markdown, option)


def sibling_script(here: pathlib.Path, name: str) -> ModuleType:
    """The study script ``name`` of the folder ``here`` (campaigns/adcs/: scripts, not a package) as a module."""
    sys.path.insert(0, str(here))
    try:
        return importlib.import_module(name)
    finally:
        sys.path.remove(str(here))
