"""Grid axes: the values one campaign key takes, and the points of a grid (their product).

An axis is written in the campaign file as

- a list: ``[0.5, 1.0, 2.0]`` (any YAML values, taken as they are);
- ``{range: [start, stop, step]}``: start, start + step, … up to and including ``stop`` when it
  falls on the grid (within 1e-9 of a step);
- ``{linspace: [start, stop, n]}``: ``n`` evenly spaced values, both ends included;
- ``{logrange: [start, stop, n]}``: ``n`` values evenly spaced in log10, both ends included
  (start and stop > 0).

A campaign's ``grid`` is one mapping of key → axis (their Cartesian product) or a list of such
mappings (the union of their products, in the order written: different keys per sub-grid).
"""

from __future__ import annotations

import itertools
import math

__all__ = ["AXIS_FORMS", "axis_values", "grid_points"]

AXIS_FORMS = ("range", "linspace", "logrange")


def _numbers(args, form: str) -> list[float]:
    if not (isinstance(args, list) and len(args) == 3
            and all(isinstance(a, (int, float)) and not isinstance(a, bool) for a in args)):
        raise ValueError(f"'{form}' takes three numbers [start, stop, {'step' if form == 'range' else 'n'}]")
    if not all(math.isfinite(a) for a in args):
        raise ValueError(f"'{form}' values must be finite")
    return list(args)


def _clean(x: float) -> float | int:
    """Round-off of an arithmetic grid removed (0.30000000000000004 → 0.3) for readable ids."""
    r = float(f"{x:.12g}")
    return int(r) if r.is_integer() and abs(r) < 2 ** 53 else r


def axis_values(spec) -> list:
    """The values of one axis written as a list or a ``{range|linspace|logrange: [...]}`` mapping;
    ``ValueError`` says what is wrong."""
    if isinstance(spec, list):
        if not spec:
            raise ValueError("an axis needs at least one value")
        return list(spec)
    if isinstance(spec, dict):
        if len(spec) != 1 or next(iter(spec)) not in AXIS_FORMS:
            raise ValueError(f"an axis mapping has exactly one of {', '.join(AXIS_FORMS)} "
                             f"(got {', '.join(map(str, spec)) or 'nothing'})")
        form, args = next(iter(spec.items()))
        start, stop, third = _numbers(args, form)
        if form == "range":
            if third == 0 or (stop - start) / third < -1e-9:
                raise ValueError(f"range [{start}, {stop}, {third}]: the step never reaches stop")
            n = int(math.floor((stop - start) / third + 1e-9)) + 1
            if n > 100_000:
                raise ValueError(f"range [{start}, {stop}, {third}] has {n} values; is the step right?")
            return [_clean(start + i * third) for i in range(n)]
        if not (float(third).is_integer() and third >= 1):
            raise ValueError(f"{form}: n must be a whole number >= 1, got {third}")
        n = int(third)
        if form == "logrange":
            if not (start > 0 and stop > 0):
                raise ValueError(f"logrange [{start}, {stop}, {n}]: start and stop must be > 0")
            lo, hi = math.log10(start), math.log10(stop)
            return [_clean(10 ** (lo + (hi - lo) * i / (n - 1))) if n > 1 else _clean(start) for i in range(n)]
        return [_clean(start + (stop - start) * i / (n - 1)) if n > 1 else _clean(start) for i in range(n)]
    raise ValueError("an axis is a list of values or {range|linspace|logrange: [a, b, c]}")


def grid_points(grids: list[dict[str, list]]) -> list[dict]:
    """Every point of a union of grids, in file order (the last key written varies fastest)."""
    points = []
    for grid in grids:
        keys = list(grid)
        for combo in itertools.product(*(grid[k] for k in keys)):
            points.append(dict(zip(keys, combo, strict=True)))
    return points or [{}]
