"""Basilisk's case A alone (``benchmarks/basilisk/case_a.py``; this runs it from any folder).

    python benchmarks/basilisk_case_a.py [--duration 5578] [--step 0.05]
"""
from basilisk.case_a import main

if __name__ == "__main__":
    main()
