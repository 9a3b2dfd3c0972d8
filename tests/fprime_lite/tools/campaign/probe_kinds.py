"""A run kind for the engine's tests, imported by campaigns as
``tests.fprime_lite.tools.campaign.probe_kinds:PROBE_RUN`` (the ``module:NAME`` form).

Its run section: ``mode`` — ``ok`` (summary ``value`` = 2·x), ``stuck`` (writes its pid to
``BASE/stuck-SEED.pid``, then busy-loops without ever polling ``should_stop``) or
``fail_if_marker`` (raises while ``BASE/marker`` exists, else as ``ok``) or ``exit`` (ends its
process with status 3) or ``slow_import`` (as ``ok``, but its build imports a module that takes
1.5 s to import: a first run's cost) or ``instant`` (as ``ok``, writing no file: the engine's own
cost). Varied keys: ``x``, ``mode``. Every run but ``instant`` writes ``out.txt`` into its folder
(a per-run file to keep or delete).
"""

from __future__ import annotations

import os

from fprime_lite.tools.campaign.kinds import Prepared, RunKind, RunOutput, RunRequest


def _check_key(key: str) -> str | None:
    return None if key in ("x", "mode") else "the probe kind varies x and mode"


def _prepare(req: RunRequest) -> Prepared:
    mode = req.config.get("mode", "ok")
    x = float(req.values.get("x", 1.0))
    if mode == "slow_import":
        import tests.fprime_lite.tools.campaign.probe_slow_import  # noqa: F401
    if mode == "instant":
        return Prepared(simulation=None, readback=lambda key: {"x": x, "mode": mode}[key],
                        execute=lambda: RunOutput(summary={"value": 2.0 * x, "sim_seconds": 1.0}))

    def execute() -> RunOutput:
        req.out_dir.mkdir(parents=True, exist_ok=True)
        (req.out_dir / "out.txt").write_text(f"x={x!r} seed={req.seed}\n")
        if mode == "stuck":
            (req.base_dir / f"stuck-{req.seed}.pid").write_text(str(os.getpid()))
            while True:  # never polls req.should_stop()
                pass
        if mode == "exit":
            os._exit(3)
        if mode == "fail_if_marker" and (req.base_dir / "marker").exists():
            raise RuntimeError("the marker file is there")
        return RunOutput(summary={"value": 2.0 * x, "sim_seconds": 1.0}, out_dir=req.out_dir)

    return Prepared(simulation=None, readback=lambda key: {"x": x, "mode": mode}[key], execute=execute)


PROBE_RUN = RunKind(name="probe", fields=frozenset({"mode"}), required=frozenset(), check_key=_check_key,
                    prepare=_prepare, description="the engine tests' probe")
