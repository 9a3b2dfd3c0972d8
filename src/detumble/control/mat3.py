"""3-vector and 3×3 matrix helpers on nested tuples/lists of plain floats (no numpy in the per-tick path)."""

from __future__ import annotations

__all__ = ["cross", "det3", "inv3"]


def cross(a, b) -> tuple[float, float, float]:
    """``a × b`` of two 3-vectors (any frame, both in the same one)."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def det3(m) -> float:
    a, b, c = m[0]
    d, e, f = m[1]
    g, h, i = m[2]
    return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)


def inv3(m, tiny: float = 0.0):
    """The inverse by cofactors; ValueError when ``|det| <= tiny`` (the caller says what that means)."""
    a, b, c = m[0]
    d, e, f = m[1]
    g, h, i = m[2]
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    if not abs(det) > tiny:
        raise ValueError(f"singular 3x3 matrix (det {det:g})")
    s = 1.0 / det
    return ((s * (e * i - f * h), s * (c * h - b * i), s * (b * f - c * e)),
            (s * (f * g - d * i), s * (a * i - c * g), s * (c * d - a * f)),
            (s * (d * h - e * g), s * (b * g - a * h), s * (a * e - b * d)))
