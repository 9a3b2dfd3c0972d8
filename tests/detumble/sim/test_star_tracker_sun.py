"""STAR-SUN-001…003: the star tracker's Sun exclusion angle (issue 27: a tracker blinded by the Sun gives no
solution, which is the existing loss path into SUN_SAFE)."""

from __future__ import annotations

import math

import pytest

from detumble.sim.plant import Plant
from detumble.sim.scenario import ScenarioError, load_scenario
from detumble.sim.star_tracker import StarTracker, StarTrackerSpec

IDENTITY = (1.0, 0.0, 0.0, 0.0)


def test_the_sun_inside_the_exclusion_cone_blinds_the_tracker():
    """STAR-SUN-001: boresight +Z, exclusion 30°: the Sun 29° off the boresight gives no solution (the held attitude,
    counted in ``blinded`` and ``dropouts``), 31° off gives one; eclipsed (sun_N None) or with the angle 0 (off),
    the Sun never blinds."""
    st = StarTracker(StarTrackerSpec(sun_exclusion_deg=30.0, max_rate_deg_s=0.0), seed=1)
    for off, valid in ((29.0, False), (31.0, True)):
        sun = (math.sin(math.radians(off)), 0.0, math.cos(math.radians(off)))
        assert st.measure(IDENTITY, (0.0, 0.0, 0.0), sun)[1] is valid
    assert st.blinded == 1 and st.dropouts == 1
    assert st.measure(IDENTITY, (0.0, 0.0, 0.0), None)[1]
    off = StarTracker(StarTrackerSpec(max_rate_deg_s=0.0), seed=1)
    assert not off.needs_sun and off.measure(IDENTITY, (0.0, 0.0, 0.0), (0.0, 0.0, 1.0))[1]


def test_the_plant_feeds_the_sun_to_the_tracker():
    """STAR-SUN-002: the adcs scenario at rest: with ``sun_exclusion_deg`` 179.9 every sunlit sample is blinded
    (the Sun is somewhere in that cone), with the default 0 none is; the plant passes the Sun only when it is lit."""
    base = ["initial.rate.magnitude_deg_s=0"]
    for angle, valid in ((179.9, False), (0.0, True)):
        sc = load_scenario("adcs", seed=1, settings=base + [f"sensors.star_tracker.sun_exclusion_deg={angle}"])
        plant = Plant(sc, 1)
        plant.step(1.0)
        assert plant.star_tracker_reading()[4] is valid
        assert (plant.star_tracker.blinded > 0) is (not valid)


def test_a_full_sphere_exclusion_is_refused():
    """STAR-SUN-003: an exclusion of 180° or more would blind the tracker everywhere: refused by name."""
    with pytest.raises(ScenarioError, match="sun_exclusion_deg"):
        load_scenario("adcs", settings=["sensors.star_tracker.sun_exclusion_deg=180"])


def test_a_blinded_tracker_takes_pointing_into_sun_safe():
    """STAR-SUN-004 (closed loop, plant-only): adcs at rest, +Z 68° from the Sun, the tracker's exclusion 40°,
    POINTING (wheels, forced at 2 s) commanded to put +Z on the Sun: the slew carries the boresight into the cone,
    the tracker stops giving solutions, and after ATTITUDE_TIMEOUT the law goes POINTING → SUN_SAFE (ATTITUDE_LOST),
    the existing loss path. With the exclusion off the same flight stays in POINTING."""
    from detumble.sim.adcs_law import AdcsLaw, PlantIo
    from detumble.sim.epoch import julian_date
    from detumble.sim.orbit import R_EARTH_EQ
    from detumble.sim.sun_sensors import SunSensorModel
    from detumble.sim.vec import rotate_n_to_b

    def flight(exclusion: float):
        sc = load_scenario("adcs", seed=1, settings=["initial.rate.magnitude_deg_s=0",
                                                      f"sensors.star_tracker.sun_exclusion_deg={exclusion}"])
        plant = Plant(sc, 1)
        sensors = SunSensorModel(julian_date(sc.epoch), R_EARTH_EQ, seed=1)
        s_N = sensors.sun(0.0)[0]
        # q_BN with body +Z along s_N: the rotation taking s_N onto +Z (half-angle form), checked below
        c = s_N[2]
        axis = (s_N[1], -s_N[0], 0.0)  # s_N × ẑ
        n = math.hypot(axis[0], axis[1])
        half = math.acos(max(-1.0, min(1.0, c))) / 2.0
        q = (math.cos(half), *(math.sin(half) * a / n for a in axis))
        if rotate_n_to_b(q, s_N)[2] < 0.999:
            q = (q[0], -q[1], -q[2], -q[3])
        assert rotate_n_to_b(q, s_N)[2] > 0.999
        law = AdcsLaw(params={"POINTING_ACTUATOR": "WHEELS"}, target_q_bn=q, force_mode="POINTING", force_at_s=2.0)
        io = PlantIo(plant, sensors)
        dt = sc.dynamics_step_s
        every = int(round(law.tick_s / dt))
        for k in range(int(round(120.0 / dt))):
            if k % every == 0:
                law.tick(io)
            plant.step(dt)
        return law.transitions, plant

    transitions, plant = flight(40.0)
    assert [m for _, m, _ in transitions][:1] == ["POINTING"]
    assert ("SUN_SAFE", "ATTITUDE_LOST") in [(m, r) for _, m, r in transitions]
    assert plant.star_tracker.blinded > 0
    transitions, plant = flight(0.0)
    assert [m for _, m, _ in transitions] == ["POINTING"] and plant.star_tracker.blinded == 0
