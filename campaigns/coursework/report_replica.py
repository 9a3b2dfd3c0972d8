"""Seed 004's own model, integrated the way its MATLAB does: an independent check of the figures.

The coursework report integrated ``attitude_model`` with ``ode45`` at MATLAB's default tolerances
(RelTol 1e-3, AbsTol 1e-6) and called its control law inside the right-hand side, at every stage
of every step (rejected ones included; ``magnetorquer2`` differences β between those calls through
globals). This script does the same with SciPy's RK45 (Dormand–Prince, ode45's method; its step
controller differs in detail), using the project's laws (:mod:`detumble.control.coursework`) in the
report's convention, and reports the report's settling times (``lsiminfo`` with the report's
``yfinal``/``yinit``) at the report's tolerances and at tight ones, read off the solver's dense output
every millisecond (``--sample``): read off its accepted steps alone, a figure is quantised by the step
(the wheel law at RelTol 1e-8: 11.94 s off its steps, as 12.02 s was in an earlier table; 11.916 s off
the dense output, at 1 ms and at 0.1 ms). The wheel law
is eq. 25 as the report writes it (this is the report's model); ``beta_pd`` is eq. 23 *or* 24 by
default, as the report's equations and figures, ``--listing`` its MATLAB listing.

    pip install scipy
    python campaigns/coursework/report_replica.py cross_product --gain 146 --t-max 30000
    python campaigns/coursework/report_replica.py beta_pd --ks 990 --kd 0.06 --t-max 9000 [--listing]
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

from detumble.analysis.settling import SettlingTracker, settling_time
from detumble.control import coursework as cw

N = cw.REPORT_MEAN_MOTION
INERTIA = ((1.67e-3, 0.0, 0.0), (0.0, 1.67e-3, 0.0), (0.0, 0.0, 1.67e-3))
B_O = (3e-5, 3e-5, 3e-5)


def make_rhs(law: str, gain: float, ks: float, kd: float, kp_w: float, kd_w: float, switched: bool = True,
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


def _settling_dense(dense, t_max: float, sample: float, channels, chunk: int = 200_000) -> list[float | None]:
    """:func:`settling_time` of each ``(state row, y_final, y_init)`` channel read off the dense
    output every ``sample`` s, a chunk at a time (a 30,000 s run at 1 ms is 3e7 samples)."""
    trackers = [SettlingTracker(final, init) for _, final, init in channels]
    count = int(round(t_max / sample))
    for start in range(1, count + 1, chunk):
        t = np.arange(start, min(start + chunk, count + 1)) * sample
        y = dense(t)
        for (row, _, _), tracker in zip(channels, trackers, strict=True):
            outside = np.abs(y[row] - tracker.y_final) > tracker.width
            if outside.any():
                last = int(np.flatnonzero(outside)[-1])
                tracker.update(float(t[last]), math.inf)
                if last + 1 < len(t):
                    tracker.update(float(t[last + 1]), tracker.y_final)
            else:
                tracker.update(float(t[0]), tracker.y_final)
    return [tracker.time for tracker in trackers]


def parse_args(argv=None) -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("law", choices=("cross_product", "beta_pd", "wheels_pd"))
    p.add_argument("--gain", type=float, default=146.0)
    p.add_argument("--ks", type=float, default=990.0)
    p.add_argument("--kd", type=float, default=0.06)
    p.add_argument("--kp-wheels", type=float, default=5.0)
    p.add_argument("--kd-wheels", type=float, default=9.0)
    p.add_argument("--listing", action="store_true",
                   help="beta_pd: both spin terms at once, as the report's MATLAB listing (default: eq. 23 or 24, "
                        "as its equations)")
    p.add_argument("--t-max", type=float, default=5833.0)
    p.add_argument("--rtol", type=float, default=1e-3, help="MATLAB ode45 default 1e-3")
    p.add_argument("--atol", type=float, default=1e-6, help="MATLAB ode45 default 1e-6")
    p.add_argument("--sample", type=float, default=0.001, metavar="S",
                   help="read the settling times off the solver's dense output every S seconds (default "
                        "0.001); 0: off its accepted steps only, whose spacing (up to seconds) then "
                        "quantises the figure")
    p.add_argument("--no-normalize", action="store_true",
                   help="form eq. 11's DCM from the integrated quaternion as it is (its norm drifts under ode45)")
    return p.parse_args(argv)


def run(args: argparse.Namespace) -> dict:
    """Integrate the report's model as ``args`` says; the figures as a dict (what ``main`` prints)."""
    rhs, calls = make_rhs(args.law, args.gain, args.ks, args.kd, args.kp_wheels, args.kd_wheels,
                          switched=not args.listing, normalize=not args.no_normalize)
    t0 = time.perf_counter()
    sol = solve_ivp(rhs, (0.0, args.t_max), [0, 0, 0, 1, 1, 2, 3, 0, 0, 0], method="RK45", rtol=args.rtol,
                    atol=args.atol, dense_output=args.sample > 0)
    wall = time.perf_counter() - t0
    finals, inits = (0.0, -N, 0.0), (1.0, 2.0, 3.0)
    channels = [(4, finals[0], inits[0]), (5, finals[1], inits[1]), (6, finals[2], inits[2]), (3, -1.0, 1.0)]
    if args.sample > 0:
        *axes, q4 = _settling_dense(sol.sol, args.t_max, args.sample, channels)
    else:
        t, y = sol.t[1:], sol.y[:, 1:]
        *axes, q4 = (settling_time(t, y[row], final, init) for row, final, init in channels)
    return {"law": args.law, "spin_terms": "listing" if args.listing else "equations",
            "normalized": not args.no_normalize, "rtol": args.rtol, "atol": args.atol,
            "t_max_s": args.t_max, "sample_s": args.sample, "steps": int(len(sol.t) - 1),
            "rhs_calls": calls["n"], "wall_s": wall, "settling_axes_s": axes,
            "settling_overall_s": None if None in axes else max(axes), "settling_q4_to_minus1_s": q4,
            "final_omega_rad_s": [float(v) for v in sol.y[4:7, -1]], "final_q": [float(v) for v in sol.y[0:4, -1]],
            "final_norm_q": float(np.linalg.norm(sol.y[0:4, -1]))}


def main(argv=None) -> None:
    print(json.dumps(run(parse_args(argv))))


if __name__ == "__main__":
    main()
