"""The detumble application's command-line verbs, reached by ``fprime-lite`` through the
``fprime_lite.verbs`` entry points (pyproject.toml)."""
from __future__ import annotations

from fprime_lite.tools.plugins import Verb


def _sim(argv: list[str]) -> int:
    from detumble.sim.runner import main
    from fprime_lite.osal.atomic import clean_temporary_files

    return main(argv, prog="fprime-lite sim", clean_out=clean_temporary_files)


#: ``fprime-lite sim SCENARIO --law …``: a plant-only run of a scenario with a reference law.
SIM_VERB = Verb(name="sim", help="plant-only run of a scenario with a reference control law", main=_sim)
