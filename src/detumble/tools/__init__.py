"""The application's pieces of ``fprime-lite``'s tools, reached through entry points (pyproject.toml).

* :mod:`.cli` — the ``sim`` verb (``fprime-lite sim SCENARIO --law …``, plant only);
* :mod:`.bench` — the ``deployment`` piece of ``fprime-lite bench``;
* :mod:`.bench_basilisk` — its ``basilisk`` piece, which runs a checkout's ``benchmarks/basilisk/``.
"""
