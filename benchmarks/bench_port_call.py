"""Nanoseconds per call through a connected output port vs a plain bound-method call.

Run: ``python benchmarks/bench_port_call.py``. Both are measured in the same run and reported as a
ratio (target ≤ 1.5). Timings vary from machine to machine; the ratio is what to compare.
"""

from fprime_lite.tools.bench import measure_port_call

if __name__ == "__main__":
    r = measure_port_call()
    print(f"plain bound-method call : {r['plain_ns']:6.1f} ns")
    print(f"connected output port   : {r['port_ns']:6.1f} ns")
    print(f"ratio (target <= 1.5)   : {r['ratio']:6.2f}")
