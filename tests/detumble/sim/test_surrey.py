"""The coursework environment (seed 004) as the packaged scenario ``surrey``."""

import csv
import json
import math

import pytest

from detumble.control.coursework import dcm_ob
from detumble.sim.plant import Plant
from detumble.sim.runner import main
from detumble.sim.scenario import load_scenario

B_O = (3e-5, 3e-5, 3e-5)  # T, seed 004 eq. 8
N_SEED = math.sqrt(3.98e5 / 7000.0 ** 3)  # rad/s, the coursework's constant


def matvec(a, v):
    return tuple(sum(a[i][k] * v[k] for k in range(3)) for i in range(3))


def matTvec(a, v):
    return tuple(sum(a[k][i] * v[k] for k in range(3)) for i in range(3))


def closed_form_b_B(t):
    """Field in B for the torque-free isotropic coursework body, in the seed's own convention.

    omega = (1, 2, 3) rad/s stays constant (isotropic, no torque), so B(t) is B(0) turned by |w| t
    about w; O(t) is O(0) turned by n t about the orbit normal -y_O; B(0) = O(0). In scalar-last
    quaternions of 'frame turned by angle about axis' (eq. 11 is dcm_ob): b_B = A(q_B(t)B0) A(q_O(t)O0)^T B_O."""
    w = (1.0, 2.0, 3.0)
    wn = math.sqrt(14.0)
    s, c = math.sin(wn * t / 2), math.cos(wn * t / 2)
    q_b = (w[0] / wn * s, w[1] / wn * s, w[2] / wn * s, c)
    so, co = math.sin(N_SEED * t / 2), math.cos(N_SEED * t / 2)
    q_o = (0.0, -so, 0.0, co)
    return matvec(dcm_ob(q_b), matTvec(dcm_ob(q_o), B_O))


def test_surrey_is_the_coursework_environment():
    """SUR-001: orbit rate n = sqrt(3.98e5/7000^3) rad/s, isotropic 1.67e-3 kg m^2, omega0 =
    (1, 2, 3) rad/s, q_BO0 = identity so b_B(0) = B_O, wheels +-1 mN m / +-0.1 N m s, rods +-1 A m^2
    clipped per axis; a body at rest in O has omega_BN_B = (0, -n, 0) (synchronous rotation)."""
    sc = load_scenario("surrey")
    plant = Plant(sc)
    assert plant.orbit.mean_motion == pytest.approx(N_SEED, rel=1e-14)
    assert plant.omega_BN_B == (1.0, 2.0, 3.0)
    assert plant.q_BO == pytest.approx((1.0, 0.0, 0.0, 0.0), abs=1e-15)
    assert plant.b_B == pytest.approx(B_O, abs=1e-18)
    assert [plant.wheels.u_max, plant.wheels.h_max] == [(1e-3,) * 3, (0.1,) * 3]
    # the body without its wheel rotors is the report's isotropic I = 1.67e-3 kg m^2
    assert [c for row in plant.body.inertia for c in row] == pytest.approx(
        [1.67e-3, 0, 0, 0, 1.67e-3, 0, 0, 0, 1.67e-3], abs=1e-18)
    assert plant.max_dipole_per_axis() == (1.0, 1.0, 1.0)
    assert sc.spacecraft.actuator_saturation == "clip" and sc.control.saturation == "clip"
    assert plant.omega_BO_B == pytest.approx((1.0, 2.0 + N_SEED, 3.0), abs=1e-15)
    at_rest = Plant(load_scenario("surrey", settings=[f"initial.rate.omega_rad_s=[0, {-N_SEED!r}, 0]"]))
    at_rest.advance_to(600.0)
    assert at_rest.b_B == pytest.approx(B_O, abs=1e-15)  # T: the field never moves in B
    assert at_rest.q_BO == pytest.approx((1.0, 0.0, 0.0, 0.0), abs=1e-10)


def test_sim_surrey_truth_shows_the_orbit_field_turning_with_the_attitude(tmp_path):
    """SUR-002: ``fprime-lite sim surrey --law none --duration 600`` runs; in its rate.csv the
    body-frame field (i) equals [BO] B_O of the logged q_BO at every row (1e-6 uT), (ii) matches the
    closed-form torque-free rotation written in seed 004's own equations (eq. 11, scalar last) to
    0.002 uT after 600 s, (iii) keeps |B| = 3e-5 sqrt(3) T and really turns: B_O is 22 deg off the
    spin axis (1, 2, 3), so b_B sweeps a cone reaching 44 deg from b_B(0)."""
    out = tmp_path / "surrey"
    assert main(["surrey", "--law", "none", "--duration", "600", "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["scenario"] == "surrey" and summary["sim_seconds"] == 600.0
    rows = list(csv.DictReader((out / "rate.csv").open()))
    assert len(rows) == 601
    worst_logged = worst_closed = 0.0
    min_cos = 1.0
    for row in rows:
        t = float(row["time_s"])
        b = tuple(float(row[f"b_{a}_uT"]) for a in "xyz")
        qo = tuple(float(row[k]) for k in ("qo0", "qo1", "qo2", "qo3"))
        from_q = matvec(dcm_ob((qo[1], qo[2], qo[3], qo[0])), B_O)
        worst_logged = max(worst_logged, max(abs(b[i] - 1e6 * from_q[i]) for i in range(3)))
        expect = closed_form_b_B(t)
        worst_closed = max(worst_closed, max(abs(b[i] - 1e6 * expect[i]) for i in range(3)))
        assert math.sqrt(sum(x * x for x in b)) == pytest.approx(30 * math.sqrt(3), rel=1e-9)
        min_cos = min(min_cos, sum(b[i] * B_O[i] for i in range(3)) / (30 * math.sqrt(3) * 3e-5 * math.sqrt(3)))
        # 9 digits in the file
        assert float(row["rate_deg_s"]) == pytest.approx(math.degrees(math.sqrt(14.0)), rel=1e-8)
    assert worst_logged < 1e-6
    assert worst_closed < 2e-3
    assert math.degrees(math.acos(min_cos)) > 40.0
