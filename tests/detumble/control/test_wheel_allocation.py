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


def test_a_fourth_wheel_s_null_space_manages_momentum_without_body_torque():
    """ADCS-098: four wheels in a pyramid: the null-space torques ``−k P h`` put no torque on the body (G u = 0
    to 1e-18 N·m), P is the idempotent projector, and integrating ``ḣ = u_n`` keeps the wheels' body momentum
    ``G h`` while their null-space momentum decays as ``e^(−k t)``; with three wheels there is no null space and
    the allocation is the plain one; the body torque of ``allocate`` is unchanged by the null-space term."""
    import math

    from detumble.control.wheel_allocation import WheelAllocator

    c, s = math.sqrt(2.0 / 3.0), math.sqrt(1.0 / 3.0)
    axes = ((c, 0.0, s), (0.0, c, s), (-c, 0.0, s), (0.0, -c, s))
    alloc = WheelAllocator(axes, 2e-3, 4e-3)
    p = alloc.null_projector
    assert p is not None
    for i in range(4):
        for j in range(4):
            assert sum(p[i][k] * p[k][j] for k in range(4)) == pytest.approx(p[i][j], abs=1e-15)
    h = [2.0e-3, -1.0e-3, 5.0e-4, 1.5e-3]
    body0 = alloc.body_momentum(h)
    null0 = math.sqrt(sum(x * x for x in (sum(p[i][j] * h[j] for j in range(4)) for i in range(4))))
    assert null0 > 5e-4
    k, dt = 2e-3, 0.1
    for _ in range(5000):  # 500 s
        un = alloc.null_space_torques(h, k)
        assert max(abs(x) for x in alloc.body_momentum(un)) < 1e-18
        h = [hi + ui * dt for hi, ui in zip(h, un, strict=True)]
    assert alloc.body_momentum(h) == pytest.approx(body0, abs=1e-15)
    null1 = math.sqrt(sum(x * x for x in (sum(p[i][j] * h[j] for j in range(4)) for i in range(4))))
    assert null1 / null0 == pytest.approx((1.0 - k * dt) ** 5000, rel=1e-9)
    tau = (1e-4, -2e-4, 5e-5)
    u, _ = alloc.allocate(tau, h, null_gain=k)
    assert alloc.body_momentum(u) == pytest.approx(tuple(-x for x in tau), abs=1e-15)
    three = WheelAllocator(((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)), 2e-3, 4e-3)
    assert three.null_projector is None and three.null_space_torques([1e-3, 0.0, 0.0], k) == (0.0, 0.0, 0.0)
    assert three.allocate(tau, [1e-3, 0.0, 0.0], null_gain=k) == three.allocate(tau, [1e-3, 0.0, 0.0])
