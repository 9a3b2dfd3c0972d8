"""The detumble application's command-line verbs, reached by ``fprime-lite`` through the
``fprime_lite.verbs`` entry points (pyproject.toml)."""
from __future__ import annotations

import pathlib

from fprime_lite.tools.plugins import Verb


def _sim(argv: list[str]) -> int:
    from detumble.sim.runner import main
    from fprime_lite.osal.atomic import clean_temporary_files

    return main(argv, prog="fprime-lite sim", clean_out=clean_temporary_files, draw_plots=_sim_plots)


def _sim_plots(out_dir: str) -> list:
    """The plots of a finished ``fprime-lite sim`` run, from its folder (what ``fprime-lite plot`` draws)."""
    from detumble.reports.plots import plot_run_dir

    return plot_run_dir(pathlib.Path(out_dir))


#: ``fprime-lite sim SCENARIO --law …``: a plant-only run of a scenario with a reference law.
SIM_VERB = Verb(name="sim", help="plant-only run of a scenario with a reference control law", main=_sim)
