"""Nanoseconds per call through a connected output port vs a plain bound-method call.

Run: ``python benchmarks/bench_port_call.py``. Both are measured in the same run and reported as a
ratio (target ≤ 1.5). Timings vary from machine to machine; the ratio is what to compare.
"""

from __future__ import annotations

import timeit

from fprime_lite import I8, OutputPort, PassiveComponent, PortType, sync_input

Start = PortType("Bench.Start", returns=bool, level=I8)


class Driver(PassiveComponent):
    @sync_input(Start)
    def start(self, level):
        return True


class Caller(PassiveComponent):
    startOut = OutputPort(Start)


def measure(number: int = 2_000_000, repeat: int = 7) -> dict:
    caller, driver = Caller("caller"), Driver("driver")
    caller.startOut.connect(0, driver.input_port("start"))
    env = {"caller": caller, "driver": driver}
    plain = min(timeit.repeat("driver.start(5)", globals=env, number=number, repeat=repeat)) / number
    port = min(timeit.repeat("caller.startOut[0](5)", globals=env, number=number, repeat=repeat)) / number
    return {"plain_ns": plain * 1e9, "port_ns": port * 1e9, "ratio": port / plain}


def main() -> None:
    r = measure()
    print(f"plain bound-method call : {r['plain_ns']:6.1f} ns")
    print(f"connected output port   : {r['port_ns']:6.1f} ns")
    print(f"ratio (target <= 1.5)   : {r['ratio']:6.2f}")


if __name__ == "__main__":
    main()
