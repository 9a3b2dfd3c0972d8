"""The side-by-side comparison of fprime-lite with Basilisk (issue #19), kept out of the installed package.

* :mod:`.side_by_side` — the cases both sides fly (adcs_ref pointing, coursework wheels) and their
  plausibility figures; plain floats, no Basilisk import (``tests/test_adcs_plant_only_vs_deployment.py``
  flies its pointing case too);
* :mod:`.bench` — the measurement: every kind of run in a child process, interleaved round by round;
* :mod:`.case_a`, :mod:`.adcs`, :mod:`.coursework` — Basilisk's sides, written with Basilisk's own
  modules (``python -m basilisk.case_a`` from ``benchmarks/``), sharing :mod:`.parts`.

Run ``python benchmarks/bench_vs_basilisk.py`` (needs ``pip install -e '.[bsk]'``); ``fprime-lite bench``
runs it as its ``basilisk`` piece from a checkout (:mod:`detumble.tools.bench_basilisk`).
"""
