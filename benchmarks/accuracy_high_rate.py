"""Torque-free RK4 accuracy at high body rates: energy, |H| and attitude drift over one orbit.

Run: ``python benchmarks/accuracy_high_rate.py [--orbit-s 5833]``. Prints one line per case:
relative energy and |H| change after one coursework orbit, and (isotropic body, where the exact
solution is a constant-rate rotation) the attitude error against the closed form.
"""

from __future__ import annotations

import argparse
import math

from detumble.sim.attitude import RigidBody
from detumble.sim.frames import attitude_error_rad
from detumble.sim.vec import quat_from_axis_angle

DEFAULT_J = ((2.20e-3, 2.0e-5, -1.5e-5), (2.0e-5, 2.15e-3, 1.0e-5), (-1.5e-5, 1.0e-5, 2.05e-3))
ISO_J = ((1.67e-3, 0, 0), (0, 1.67e-3, 0), (0, 0, 1.67e-3))
#: the strongly asymmetric body of tests/detumble/sim/test_attitude.py (principal moments 2-4e-3)
ASYM_J = ((2.0e-3, 1.0e-4, -5.0e-5), (1.0e-4, 3.0e-3, 8.0e-5), (-5.0e-5, 8.0e-5, 4.0e-3))


def run(inertia, w0, dt, duration, substeps=1):
    body = RigidBody(inertia)
    s = (1.0, 0.0, 0.0, 0.0) + tuple(w0)
    e0, h0 = body.kinetic_energy(s), math.sqrt(sum(x * x for x in body.angular_momentum_B(s)))
    h = dt / substeps
    for _ in range(int(round(duration / dt)) * substeps):
        s = body.step(s, h)
    e1, h1 = body.kinetic_energy(s), math.sqrt(sum(x * x for x in body.angular_momentum_B(s)))
    return s, (e1 - e0) / e0, (h1 - h0) / h0


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--orbit-s", type=float, default=5833.0)
    a = p.parse_args()
    w0 = (1.0, 2.0, 3.0)  # rad/s, 214 deg/s
    wn = math.sqrt(14.0)
    w20 = tuple(x * math.radians(20.0) / wn for x in w0)
    print("case, dt_s, rate_deg_s, rel_energy_change, rel_H_change, attitude_error_rad")
    for dt in (0.05, 0.02, 0.01, 0.005):
        _, de, dh = run(DEFAULT_J, w20, dt, a.orbit_s)
        print(f"default J, {dt}, 20, {de:.3e}, {dh:.3e}, -")
    for dt in (0.05, 0.02, 0.01, 0.005):
        _, de, dh = run(DEFAULT_J, w0, dt, a.orbit_s)
        print(f"default J, {dt}, 214, {de:.3e}, {dh:.3e}, -")
    for dt in (0.01,):
        _, de, dh = run(ASYM_J, w20, dt, a.orbit_s)
        print(f"asymmetric J, {dt}, 20, {de:.3e}, {dh:.3e}, -")
    for dt in (0.05, 0.02, 0.01, 0.005):
        _, de, dh = run(ASYM_J, w0, dt, a.orbit_s)
        print(f"asymmetric J, {dt}, 214, {de:.3e}, {dh:.3e}, -")
    w30 = tuple(x * math.radians(30.0) / wn for x in w0)
    s, de, dh = run(ISO_J, w30, 0.05, a.orbit_s)
    exact = quat_from_axis_angle(w0, math.radians(30.0) * a.orbit_s)
    print(f"isotropic (case A rate), 0.05, 30, {de:.3e}, {dh:.3e}, {attitude_error_rad(s[:4], exact):.3e}")
    for dt in (0.05, 0.02, 0.01, 0.005):
        s, de, dh = run(ISO_J, w0, dt, a.orbit_s)
        exact = quat_from_axis_angle(w0, wn * a.orbit_s)
        print(f"isotropic (surrey), {dt}, 214, {de:.3e}, {dh:.3e}, {attitude_error_rad(s[:4], exact):.3e}")


if __name__ == "__main__":
    main()
