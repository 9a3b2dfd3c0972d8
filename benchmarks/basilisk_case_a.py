"""Basilisk's case A (moved into the package: ``detumble.sitl.basilisk_case_a``; this runs it).

    python benchmarks/basilisk_case_a.py [--duration 5578] [--step 0.05]
"""
from detumble.sitl.basilisk_case_a import main

if __name__ == "__main__":
    main()
