"""The reference deployment's speed and memory (same as ``fprime-lite bench``).

Run: ``python benchmarks/bench_deployment.py [--duration S] [--memory] [--json FILE]``.
"""

import sys

from fprime_lite.tools.bench import main

if __name__ == "__main__":
    sys.exit(main())
