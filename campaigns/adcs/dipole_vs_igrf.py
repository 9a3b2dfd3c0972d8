"""How far the on-board field model's direction (``control.geomagnetic``: IGRF-2025's tilted dipole) is from the
plant's field (IGRF-14 to degree 13, ``sim.igrf``) on the adcs orbit's shell: points uniform on the sphere at
420 km altitude within the 51.6° inclination's latitude band, one Earth angle (the error moves with longitude, which
the uniform points already cover).

    python campaigns/adcs/dipole_vs_igrf.py [--points N] [--seed S]

Prints the median, p95 and max angle (deg) between the two fields.
"""

from __future__ import annotations

import argparse
import math
import random
import statistics

from detumble.control.geomagnetic import dipole_field_N
from detumble.sim.igrf import IgrfField

RADIUS_M = 6378137.0 + 420e3


def angles_deg(points: int, seed: int) -> list[float]:
    field = IgrfField(2025.0)
    rng = random.Random(seed)
    band = math.sin(math.radians(51.6))
    out = []
    while len(out) < points:
        v = [rng.gauss(0.0, 1.0) for _ in range(3)]
        n = math.sqrt(sum(x * x for x in v))
        if abs(v[2] / n) > band:
            continue
        r = tuple(RADIUS_M * x / n for x in v)
        b, d = field.b_N(0.0, r), dipole_field_N(r, field.theta0_rad)
        c = sum(x * y for x, y in zip(b, d, strict=True)) / math.sqrt(sum(x * x for x in b) * sum(x * x for x in d))
        out.append(math.degrees(math.acos(max(-1.0, min(1.0, c)))))
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--points", type=int, default=5000)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args(argv)
    a = sorted(angles_deg(args.points, args.seed))
    print(f"{len(a)} points: median {statistics.median(a):.1f}, p95 {a[int(math.ceil(0.95 * len(a))) - 1]:.1f}, "
          f"max {a[-1]:.1f} deg")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
