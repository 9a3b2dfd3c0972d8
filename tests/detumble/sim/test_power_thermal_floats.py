"""The electrical and thermal models' per-step arithmetic, written for speed (issue 32), gives the same
floats as the plain formulas: each face's sunlit cosine as ``max(0.0, ±s)`` and the closed face switches
as ``sum()`` (EPS-FLT-001/002), and the thermal step's face loop (THM-FLT-001), bit for bit.
"""

import math
import random

from detumble.sim.epoch import julian_date
from detumble.sim.orbit import R_EARTH_EQ
from detumble.sim.plant import build_orbit
from detumble.sim.power import FACE_SWITCHES, SWITCH_NAMES, ElectricalSystem
from detumble.sim.scenario import load_scenario
from detumble.sim.sun import SOLAR_CONSTANT_W_M2, in_umbra
from detumble.sim.thermal import STEFAN_BOLTZMANN, ThermalConfig, ThermalModel
from detumble.control.quaternion import rotate_n_to_b

SCENARIO = load_scenario("default")
ORBIT = build_orbit(SCENARIO)


def _reference_solar(eps, t_s, q, r):
    """solar_power_w and face_flux_w_m2 as max(0.0, ±s) gives them (the formula before issue 32)."""
    s_N, d_au = eps.sun(t_s)
    if in_umbra(r, s_N, eps.earth_radius_m):
        return 0.0, (0.0,) * 6
    s = rotate_n_to_b(q, s_N)
    flux = SOLAR_CONSTANT_W_M2 / (d_au * d_au)
    faces = (flux * max(0.0, s[0]), flux * max(0.0, -s[0]), flux * max(0.0, s[1]),
             flux * max(0.0, -s[1]), flux * max(0.0, s[2]), flux * max(0.0, -s[2]))
    a = eps._areas
    lit = (a[0] * max(0.0, s[0]) + a[1] * max(0.0, -s[0]) + a[2] * max(0.0, s[1]) + a[3] * max(0.0, -s[1])
           + a[4] * max(0.0, s[2]) + a[5] * max(0.0, -s[2]))
    return flux * eps.cfg.solar.efficiency * lit, faces


def _same(x, y):
    return x == y and math.copysign(1.0, x) == math.copysign(1.0, y) or (math.isnan(x) and math.isnan(y))


def test_eps_flt_001_sunlit_faces_are_the_max_formula_bit_for_bit():
    """EPS-FLT-001: 3000 random attitudes around an orbit, plus attitudes that put the Sun exactly on a
    face normal and in a face plane (zero cosines of either sign): the array power and every face's
    flux equal max(0.0, ±s)'s, bit for bit and sign of zero included."""
    eps = ElectricalSystem(SCENARIO.power, julian_date(SCENARIO.epoch), R_EARTH_EQ)
    rng = random.Random(5)
    period = 2 * math.pi / ORBIT.arg_latitude_rate
    cases = []
    for _ in range(3000):
        q = [rng.gauss(0.0, 1.0) for _ in range(4)]
        n = math.sqrt(sum(x * x for x in q))
        cases.append((rng.uniform(0.0, period), tuple(x / n for x in q)))
    h = math.sqrt(0.5)
    for q in [(1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (h, h, 0.0, 0.0), (h, 0.0, h, 0.0), (h, 0.0, 0.0, h),
              (0.5, 0.5, 0.5, 0.5), (-1.0, 0.0, 0.0, 0.0)]:
        cases += [(t, q) for t in (0.0, period / 3, period / 2)]
    lit = 0
    for t, q in cases:
        r = ORBIT.position_N(t)
        want_w, want_faces = _reference_solar(eps, t, q, r)
        got_w = eps.solar_power_w(t, q, r)
        assert _same(got_w, want_w), (t, q)
        assert all(_same(g, w) for g, w in zip(eps.face_flux_w_m2, want_faces, strict=True)), (t, q)
        lit += got_w > 0.0
    assert 0 < lit < len(cases)  # both sunlit and eclipsed attitudes were checked
    # the Sun exactly along a body axis: the other axes' cosines are zeros (of either sign)
    r = (0.0, 0.0, 7.0e6)  # off the Earth's shadow for a Sun in the x-y plane
    for s_N in ((1.0, 0.0, 0.0), (-1.0, 0.0, 0.0), (0.0, 1.0, -0.0), (0.0, -1.0, 0.0), (-0.0, 0.6, 0.8)):
        eps.sun = lambda t, s_N=s_N: (s_N, 1.0)
        for q in ((1.0, 0.0, 0.0, 0.0), (-1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0)):
            want_w, want_faces = _reference_solar(eps, 0.0, q, r)
            got_w = eps.solar_power_w(0.0, q, r)
            assert got_w > 0.0 and _same(got_w, want_w), (s_N, q)
            assert all(_same(g, w) for g, w in zip(eps.face_flux_w_m2, want_faces, strict=True)), (s_N, q)


def test_eps_flt_002_switched_load_counts_closed_face_switches_as_sum_does():
    """EPS-FLT-002: every one of the 256 switch settings gives the load that sum() over the closed face
    switches gives."""
    eps = ElectricalSystem(SCENARIO.power, julian_date(SCENARIO.epoch), R_EARTH_EQ)
    loads = eps.cfg.loads
    for bits in range(256):
        for k, name in enumerate(SWITCH_NAMES):
            eps.set_switch(name, bool(bits >> k & 1))
        sw = eps.switches
        want = loads.avionics_w + loads.face_board_w * sum(sw[name] for name in FACE_SWITCHES)
        if sw["payloadPower"]:
            want += loads.payload_power_w
        if sw["payloadBattery"]:
            want += loads.payload_battery_w
        assert _same(eps.switched_load_w(), want), bits


def _reference_thermal_step(model, dt, flux, load_w):
    cfg = model.cfg
    n = max(1, int(dt / cfg.max_substep_s + 0.999999))
    h = dt / n
    a, g = cfg.face_area_m2, cfg.face_interior_w_k
    absorbed = [cfg.absorptivity * a * q for q in flux]
    rad = cfg.emissivity * STEFAN_BOLTZMANN * a
    for _ in range(n):
        ti = model.interior_k
        to_interior = 0.0
        faces = model.face_k
        for f in range(6):
            tf = faces[f]
            cond = g * (tf - ti)
            to_interior += cond
            faces[f] = tf + h * (absorbed[f] - rad * tf ** 4 - cond) / cfg.face_capacity_j_k
        model.interior_k = ti + h * (load_w + to_interior) / cfg.interior_capacity_j_k


def test_thm_flt_001_thermal_step_is_the_face_loop_bit_for_bit():
    """THM-FLT-001: 2000 steps of random length (sub-stepped or not), sunlight and load: every node's
    temperature equals the plain face loop's, bit for bit."""
    rng = random.Random(11)
    a, b = ThermalModel(ThermalConfig()), ThermalModel(ThermalConfig())
    for _ in range(2000):
        dt = rng.choice((0.1, 0.02, 1.0, 2.5, rng.uniform(0.0, 3.0)))
        flux = tuple(rng.choice((0.0, rng.uniform(0.0, 1400.0))) for _ in range(6))
        load = rng.uniform(0.0, 5.0)
        a.step(dt, flux, load)
        _reference_thermal_step(b, dt, flux, load)
        assert a.face_k == b.face_k and a.interior_k == b.interior_k
