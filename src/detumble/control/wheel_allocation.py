"""Torque allocation to reaction wheels with their limits (plain floats; no framework import).

A wheel ``i`` with unit spin axis ``g_i`` (body frame) and motor torque ``u_i`` (N·m, positive
spins the wheel up along ``g_i``) puts ``−u_i g_i`` on the body, and its momentum obeys
``ḣ_i = u_i`` (``/work/shared/spec/control.md``). So a requested body torque ``τ`` needs
``G u = −τ`` with ``G = [g_1 … g_N]``; the minimum-norm solution is ``u = −Gᵀ (G Gᵀ)⁻¹ τ``.

With more than three wheels the torques ``u`` in the null space of ``G`` (``G u = 0``) move momentum between the
wheels without touching the body: ``P = I − Gᵀ (G Gᵀ)⁻¹ G`` projects onto it, and ``u_n = −k P h`` drives the
wheels' null-space momentum ``P h`` to zero at the rate ``k`` (``d(P h)/dt = −k P h``: ``P`` is idempotent) —
momentum management that spreads the wheels' momentum evenly (the minimum-norm set of momenta for the body
momentum they hold) and keeps them away from their limits, with no attitude disturbance.
"""

from __future__ import annotations

from typing import Sequence

from detumble.control.mat3 import inv3

Vec3 = tuple[float, float, float]

__all__ = ["WheelAllocator"]


def _inv3(m):
    try:
        return inv3(m, 1e-12)
    except ValueError:
        raise ValueError("the wheel axes do not span three dimensions; the body torque cannot be allocated") from None


class WheelAllocator:
    """Splits body torques over wheels and applies their torque and momentum limits.

    Args:
        axes: unit spin axes ``g_i`` in B (at least three, spanning space).
        max_torque: ``u_max`` per wheel, N·m.
        max_momentum: ``h_max`` per wheel, N·m·s.
        momentum_margin: a wheel within this fraction of ``h_max`` gets no torque that would push it
            further (so the plant's own cut-off is never reached).
    """

    def __init__(self, axes: Sequence[Vec3], max_torque: float, max_momentum: float,
                 momentum_margin: float = 0.02) -> None:
        g = [tuple(float(x) for x in a) for a in axes]
        if len(g) < 3:
            raise ValueError(f"need at least three wheels to allocate a 3-axis torque, got {len(g)}")
        for a in g:
            n = (a[0] ** 2 + a[1] ** 2 + a[2] ** 2) ** 0.5
            if abs(n - 1.0) > 1e-6:
                raise ValueError(f"wheel axis {a} is not a unit vector")
        self.axes = g
        self.max_torque = float(max_torque)
        self.max_momentum = float(max_momentum)
        self.momentum_margin = float(momentum_margin)
        ggt = tuple(tuple(sum(a[r] * a[c] for a in g) for c in range(3)) for r in range(3))
        inv = _inv3(ggt)
        #: rows of −Gᵀ (G Gᵀ)⁻¹, one per wheel
        self._rows = [tuple(-sum(a[k] * inv[k][c] for k in range(3)) for c in range(3)) for a in g]
        #: the null-space projector P = I − Gᵀ (G Gᵀ)⁻¹ G (None with three wheels: G is square, P = 0)
        self.null_projector: tuple[tuple[float, ...], ...] | None = None
        if len(g) > 3:
            self.null_projector = tuple(
                tuple((1.0 if i == j else 0.0) + sum(self._rows[i][c] * g[j][c] for c in range(3))
                      for j in range(len(g))) for i in range(len(g)))

    def null_space_torques(self, momenta: Sequence[float], gain: float) -> tuple[float, ...]:
        """``u_n = −gain · P h`` (N·m per wheel; ``gain`` 1/s, ``momenta`` N·m·s): zero body torque; all zeros
        with three wheels."""
        p = self.null_projector
        if p is None or gain == 0.0:
            return (0.0,) * len(self.axes)
        return tuple(-gain * sum(row[j] * momenta[j] for j in range(len(row))) for row in p)

    def allocate(self, tau_B: Vec3, momenta: Sequence[float] | None = None,
                 null_gain: float = 0.0) -> tuple[tuple[float, ...], bool]:
        """``(u per wheel N·m, limited)`` for the body torque ``tau_B``.

        With more than three wheels, ``momenta`` given and ``null_gain`` (1/s) > 0, the null-space
        torques :meth:`null_space_torques` are added (no body torque). The whole vector is scaled down
        when a wheel would exceed ``max_torque`` (the body torque keeps its direction); a wheel whose
        momentum is near ``max_momentum`` and would be pushed further gets zero. ``limited`` says whether
        either limit acted.
        """
        u = [r[0] * tau_B[0] + r[1] * tau_B[1] + r[2] * tau_B[2] for r in self._rows]
        if null_gain > 0.0 and momenta is not None and self.null_projector is not None:
            un = self.null_space_torques(momenta, null_gain)
            u = [a + b for a, b in zip(u, un, strict=True)]
        limited = False
        peak = max(abs(x) for x in u)
        if peak > self.max_torque:
            s = self.max_torque / peak
            u = [x * s for x in u]
            limited = True
        if momenta is not None:
            edge = self.max_momentum * (1.0 - self.momentum_margin)
            for i, h in enumerate(momenta):
                if abs(h) >= edge and u[i] * h > 0.0:
                    u[i] = 0.0
                    limited = True
        return tuple(u), limited

    def body_momentum(self, momenta: Sequence[float]) -> Vec3:
        """``Σ h_i g_i``: the wheels' momentum in B, N·m·s."""
        x = y = z = 0.0  # summed in wheel order, as sum() does
        for h, a in zip(momenta, self.axes, strict=True):
            x += h * a[0]
            y += h * a[1]
            z += h * a[2]
        return (x, y, z)
