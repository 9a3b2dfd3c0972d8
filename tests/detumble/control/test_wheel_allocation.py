"""Torque allocation to reaction wheels with their limits (N·m, N·m·s)."""

import math

import pytest

from detumble.control.wheel_allocation import WheelAllocator

ORTHO = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


def body_torque(alloc, u):
    """What the wheels put on the body: −Σ u_i g_i."""
    return tuple(-sum(ui * g[k] for ui, g in zip(u, alloc.axes, strict=True)) for k in range(3))


def test_orthogonal_wheels_give_the_requested_torque():
    """ADCS-009: with three orthogonal wheels u = −τ and the body receives τ exactly."""
    a = WheelAllocator(ORTHO, 2e-3, 4e-3)
    u, limited = a.allocate((1e-4, -2e-4, 3e-5))
    assert u == (-1e-4, 2e-4, -3e-5) and not limited


def test_four_wheel_pyramid_minimum_norm():
    """ADCS-009: a 4-wheel pyramid reproduces the body torque to 1e-18 N·m with the minimum-norm split."""
    s = 1 / math.sqrt(3)
    axes = ((s, s, s), (-s, s, s), (-s, -s, s), (s, -s, s))
    a = WheelAllocator(axes, 2e-3, 4e-3)
    tau = (1e-4, -5e-5, 2e-4)
    u, _ = a.allocate(tau)
    assert all(abs(x - y) < 1e-18 for x, y in zip(body_torque(a, u), tau, strict=True))
    assert abs(sum(u[0:1]) - u[0]) == 0.0  # exercised
    # minimum norm: adding a null-space vector (1, −1, 1, −1) only increases |u|
    n2 = sum(x * x for x in u)
    assert all(sum((x + e * d) ** 2 for x, d in zip(u, (1, -1, 1, -1), strict=True)) > n2 for e in (1e-5, -1e-5))


def test_torque_limit_scales_the_whole_command():
    """ADCS-009: a request beyond u_max is scaled so the largest wheel sits at u_max; direction kept."""
    a = WheelAllocator(ORTHO, 2e-3, 4e-3)
    u, limited = a.allocate((4e-3, 1e-3, 0.0))
    assert limited and abs(abs(u[0]) - 2e-3) < 1e-18 and abs(u[1] / u[0] - 0.25) < 1e-12


def test_momentum_limit_stops_a_wheel_pushed_further():
    """ADCS-009: a wheel within 2 % of h_max gets no torque that would push it further, but may unload."""
    a = WheelAllocator(ORTHO, 2e-3, 4e-3)
    u, limited = a.allocate((-1e-4, 1e-4, 0.0), momenta=(3.95e-3, 3.95e-3, 0.0))
    assert limited and u[0] == 0.0  # u = +1e-4 would push h = +3.95e-3 beyond
    assert u[1] == -1e-4  # unloads: allowed


def test_bad_axes_are_refused():
    """ADCS-009: fewer than three wheels, non-unit or coplanar axes are refused with a message."""
    with pytest.raises(ValueError, match="at least three"):
        WheelAllocator(ORTHO[:2], 1e-3, 1e-3)
    with pytest.raises(ValueError, match="not a unit vector"):
        WheelAllocator(((2.0, 0, 0), (0, 1.0, 0), (0, 0, 1.0)), 1e-3, 1e-3)
    with pytest.raises(ValueError, match="span"):
        WheelAllocator(((1.0, 0, 0), (0, 1.0, 0), (1 / math.sqrt(2), 1 / math.sqrt(2), 0)), 1e-3, 1e-3)
