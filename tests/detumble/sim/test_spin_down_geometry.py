"""The field geometry of the coils' spin-down (detumble.sim.spin_down_geometry)."""

from __future__ import annotations

import math

import pytest

from detumble.sim import spin_down_geometry as sdg


def test_windows_and_reach_count_only_open_seconds_after_the_start():
    """SUNSAFE-031: on a made-up β(t) (1 s samples) with the gate open 10–19 s and 40–59 s, ``windows`` gives those
    stretches (cut to the range asked), and ``reach_time`` the instant the open seconds since the start add up: 15 s
    of open gate from 0 s at 45 s (10 in the first window, 5 in the second), from 15 s at 50 s."""
    t = [float(k) for k in range(80)]
    beta = [85.0 if 10 <= k < 20 or 40 <= k < 60 else 30.0 for k in range(80)]
    geo = {"t": t, "beta_deg": beta, "eclipse": [False] * 80}
    assert sdg.windows(geo, 80.0) == [(10.0, 20.0), (40.0, 60.0)]
    assert sdg.windows(geo, 80.0, 15.0, 50.0) == [(15.0, 20.0), (40.0, 50.0)]
    assert sdg.windows(geo, 90.0) == []
    assert sdg.reach_time(geo, 80.0, 0.0, 15.0) == 45.0
    assert sdg.reach_time(geo, 80.0, 15.0, 15.0) == 50.0
    assert sdg.reach_time(geo, 80.0, 0.0, 31.0) is None  # only 30 s open in the samples


def test_beta_is_the_field_against_the_sun_line_folded():
    """SUNSAFE-032: ``geometry``'s β is the angle between the scenario's field and the Sun line folded to 0–90°
    (the gate looks at |cos|): at three instants it equals the angle worked out from the plant's own field and
    orbit and the ephemeris, and over an orbit it spans nearly 0–90° (the dipole turns through the Sun line)."""
    from detumble.sim.epoch import julian_date
    from detumble.sim.plant import build_field, build_orbit
    from detumble.sim.scenario import load_scenario
    from detumble.sim.sun import sun_direction_N

    geo = sdg.geometry("adcs", duration_s=600.0, step_s=100.0)
    sc = load_scenario("adcs")
    orbit = build_orbit(sc)
    field = build_field(sc, orbit)
    for k in (0, 3, 6):
        t = geo["t"][k]
        b = field.b_N(t, orbit.position_N(t))
        s = sun_direction_N(julian_date(sc.epoch) + t / 86400.0)[0]
        c = abs(sum(x * y for x, y in zip(b, s, strict=True))) / math.sqrt(sum(x * x for x in b))
        assert geo["beta_deg"][k] == pytest.approx(math.degrees(math.acos(c)), abs=1e-9)
    full = sdg.geometry("adcs", step_s=10.0)
    assert min(full["beta_deg"]) < 5.0 and max(full["beta_deg"]) > 85.0
