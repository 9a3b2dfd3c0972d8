"""Seed 004's own model, integrated the way its MATLAB does: an independent check of the figures.

The coursework report integrated ``attitude_model`` with ``ode45`` at MATLAB's default tolerances
(RelTol 1e-3, AbsTol 1e-6) and called its control law inside the right-hand side, at every stage
of every step (rejected ones included; ``magnetorquer2`` differences β between those calls through
globals). This script does the same with SciPy's RK45 (Dormand–Prince, ode45's method; its step
controller differs in detail), using the project's laws (:mod:`detumble.control.coursework`) in the
report's convention, and reports the report's settling times (``lsiminfo`` with the report's
``yfinal``/``yinit``) at the report's tolerances and at tight ones.

    pip install scipy
    python campaigns/coursework/report_replica.py cross_product --gain 146 --t-max 30000
    python campaigns/coursework/report_replica.py beta_pd --ks 990 --kd 0.06 --t-max 12000 --rtol 1e-6
    python campaigns/coursework/report_replica.py wheels_pd --t-max 60

Prints one JSON line.
"""
from __future__ import annotations

import argparse
import json
import math
import time

import numpy as np
from scipy.integrate import solve_ivp

from detumble.analysis.settling import settling_time
from detumble.control import coursework as cw

N = cw.REPORT_MEAN_MOTION
INERTIA = ((1.67e-3, 0.0, 0.0), (0.0, 1.67e-3, 0.0), (0.0, 0.0, 1.67e-3))
B_O = (3e-5, 3e-5, 3e-5)


def make_rhs(law: str, gain: float, ks: float, kd: float, kp_w: float, kd_w: float, switched: bool,
             normalize: bool = True):
    beta = cw.BetaPd(ks, kd, switched=switched)
    calls = {"n": 0}

    def control(t, q, w, h, b):
        if law == "cross_product":
            return cw.cross_product_dipole(gain, w, b), (0.0, 0.0, 0.0)
        if law == "beta_pd":
            return beta.dipole(t, w, b), (0.0, 0.0, 0.0)
        q_e = cw.error_quaternion((0.0, 0.0, 0.0, 1.0), q)
        w_o = cw.rate_relative_to_orbit(q, w)
        return (0.0, 0.0, 0.0), cw.wheel_torque(kp_w, kd_w, INERTIA, q_e, w_o, w, h)

    def rhs(t, x):
        calls["n"] += 1
        q = x[0:4]
        s = math.sqrt(q[0] ** 2 + q[1] ** 2 + q[2] ** 2 + q[3] ** 2) if normalize else 1.0
        a = cw.dcm_ob(q / s)
        b = tuple(sum(a[i][j] * B_O[j] for j in range(3)) for i in range(3))
        w, h = tuple(x[4:7]), tuple(x[7:10])
        m, torque = control(t, tuple(q / s), w, h, b)
        m = cw.clip_dipole(m)
        torque = cw.limit_wheel_torque(torque, h)
        n_mt = (m[1] * b[2] - m[2] * b[1], m[2] * b[0] - m[0] * b[2], m[0] * b[1] - m[1] * b[0])
        w_o = (w[0] + a[0][1] * N, w[1] + a[1][1] * N, w[2] + a[2][1] * N)
        iw = tuple(INERTIA[i][i] * w[i] for i in range(3))
        hw = (iw[0] + h[0], iw[1] + h[1], iw[2] + h[2])
        gyro = (w[1] * hw[2] - w[2] * hw[1], w[2] * hw[0] - w[0] * hw[2], w[0] * hw[1] - w[1] * hw[0])
        w_dot = [(n_mt[i] - torque[i] - gyro[i]) / INERTIA[i][i] for i in range(3)]
        o1, o2, o3 = w_o
        q1, q2, q3, q4 = q
        q_dot = (0.5 * (o3 * q2 - o2 * q3 + o1 * q4), 0.5 * (-o3 * q1 + o1 * q3 + o2 * q4),
                 0.5 * (o2 * q1 - o1 * q2 + o3 * q4), 0.5 * (-o1 * q1 - o2 * q2 - o3 * q3))
        return [*q_dot, *w_dot, *torque]

    return rhs, calls


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("law", choices=("cross_product", "beta_pd", "wheels_pd"))
    p.add_argument("--gain", type=float, default=146.0)
    p.add_argument("--ks", type=float, default=990.0)
    p.add_argument("--kd", type=float, default=0.06)
    p.add_argument("--kp-wheels", type=float, default=5.0)
    p.add_argument("--kd-wheels", type=float, default=9.0)
    p.add_argument("--switched", action="store_true")
    p.add_argument("--t-max", type=float, default=5833.0)
    p.add_argument("--rtol", type=float, default=1e-3, help="MATLAB ode45 default 1e-3")
    p.add_argument("--atol", type=float, default=1e-6, help="MATLAB ode45 default 1e-6")
    p.add_argument("--no-normalize", action="store_true",
                   help="form eq. 11's DCM from the integrated quaternion as it is (its norm drifts under ode45)")
    args = p.parse_args()
    rhs, calls = make_rhs(args.law, args.gain, args.ks, args.kd, args.kp_wheels, args.kd_wheels, args.switched,
                          normalize=not args.no_normalize)
    t0 = time.perf_counter()
    sol = solve_ivp(rhs, (0.0, args.t_max), [0, 0, 0, 1, 1, 2, 3, 0, 0, 0], method="RK45", rtol=args.rtol,
                    atol=args.atol)
    wall = time.perf_counter() - t0
    t, y = sol.t[1:], sol.y[:, 1:]
    finals, inits = (0.0, -N, 0.0), (1.0, 2.0, 3.0)
    axes = [settling_time(t, y[4 + i], finals[i], inits[i]) for i in range(3)]
    q4 = settling_time(t, y[3], -1.0, 1.0)
    out = {"law": args.law, "normalized": not args.no_normalize, "rtol": args.rtol, "atol": args.atol,
           "t_max_s": args.t_max, "steps": int(len(sol.t) - 1),
           "rhs_calls": calls["n"], "wall_s": wall, "settling_axes_s": axes,
           "settling_overall_s": None if None in axes else max(axes), "settling_q4_to_minus1_s": q4,
           "final_omega_rad_s": [float(v) for v in y[4:7, -1]], "final_q": [float(v) for v in y[0:4, -1]],
           "final_norm_q": float(np.linalg.norm(y[0:4, -1]))}
    print(json.dumps(out))


if __name__ == "__main__":
    main()
