"""Figures of docs/studies/magnetic_pointing.md.

    python campaigns/adcs/magnetic_pointing_figures.py floquet --out docs/img/magnetic_pointing
    python campaigns/adcs/magnetic_pointing_figures.py runs \
        "SEED_PD, K_D 4e-4=RUN1" "FIELD_STEERING, K_D 4e-5=RUN2" "FIELD_STEERING (default)=RUN3" --out DIR

``floquet``: the Floquet growth rate (1/s, one orbit of the adcs_ref field toward its start-up target) of
seed 003's projected PD over (K_P, K_D), and of the steering law over (ρ, K_D); printed as tables too.
``runs``: the true pointing error against time of ``fprime-lite run`` output folders (their attitude.csv).
"""

from __future__ import annotations

import argparse
import csv
import pathlib
import sys

import numpy as np

from detumble.analysis.magnetic_floquet import averaged_projection, field_line_along_orbit, floquet_rate
from detumble.sim.plant import Plant
from detumble.sim.scenario import load_scenario

TARGET = (0.9238795325112867, 0.0, 0.3826834323650898, 0.0)


def floquet(out: pathlib.Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plant = Plant(load_scenario("adcs"))
    period, b, bd = field_line_along_orbit(plant, TARGET, samples=400)
    inertia = np.array(plant.scenario.spacecraft.inertia_kg_m2)
    print(f"orbit {period:.0f} s; field line rate |db/dt|: mean {np.linalg.norm(bd, axis=1).mean():.2e} /s, "
          f"min {np.linalg.norm(bd, axis=1).min():.2e}, max {np.linalg.norm(bd, axis=1).max():.2e}; "
          f"eig(averaged projection) {np.round(np.linalg.eigvalsh(averaged_projection(b[:-1])), 3)}")
    kps = np.logspace(-10, -5, 11)
    kds = np.logspace(-6, -3, 10)
    seed = np.array([[floquet_rate("seed_pd", period, b, bd, inertia, kp, kd) for kp in kps] for kd in kds])
    rhos = np.array([0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0])
    kds2 = np.array([2e-5, 4e-5, 1e-4, 2e-4, 4e-4])
    steer = np.array([[floquet_rate("field_steering", period, b, bd, inertia, 1e-6, kd, rho=rho) for rho in rhos]
                      for kd in kds2])
    print("seed_pd Floquet rate (1/s); rows K_D, columns K_P", " ".join(f"{k:.0e}" for k in kps))
    for kd, row in zip(kds, seed, strict=True):
        print(f"  K_D {kd:.1e}: " + " ".join(f"{v:+.1e}" for v in row))
    print("field_steering (K_P 1e-6) Floquet rate (1/s); rows K_D, columns rho", " ".join(f"{r:g}" for r in rhos))
    for kd, row in zip(kds2, steer, strict=True):
        print(f"  K_D {kd:.1e}: " + " ".join(f"{v:+.1e}" for v in row))
    out.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
    lim = 2.5e-3
    for ax, data, x, y, xl, title in (
            (axes[0], seed, np.log10(kps), np.log10(kds), "log10 K_P (N·m)",
             "seed 003 PD projected perpendicular to B"),
            (axes[1], steer, rhos, np.log10(kds2), "ρ (K_P 1e-6 N·m)", "field steering")):
        im = ax.pcolormesh(x, y, np.clip(data, -lim, lim), cmap="RdBu_r", vmin=-lim, vmax=lim, shading="nearest")
        ax.set_xlabel(xl)
        ax.set_ylabel("log10 K_D (N·m·s)")
        ax.set_title(title)
        fig.colorbar(im, ax=ax, label="Floquet rate, 1/s (red: diverges)")
    axes[0].plot(np.log10(2e-6), np.log10(4e-4), "k*", ms=14, label="old defaults")
    axes[0].legend(loc="lower left")
    axes[1].plot(2.0, np.log10(1e-4), "k*", ms=14, label="defaults")
    axes[1].legend(loc="lower left")
    fig.tight_layout()
    fig.savefig(out / "floquet.png", dpi=90)
    print(f"wrote {out / 'floquet.png'}")


def runs(out: pathlib.Path, specs: list[str]) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(10, 4.5))
    for spec in specs:
        label, _, folder = spec.rpartition("=")
        t, e = [], []
        with open(pathlib.Path(folder) / "attitude.csv", newline="") as f:
            for row in csv.DictReader(f):
                if row["mode"] == "POINTING" and row["pointing_error_deg"] not in ("", "nan"):
                    t.append(float(row["t_s"]))
                    e.append(float(row["pointing_error_deg"]))
        ax.plot(t, e, lw=1, label=label)
    ax.axhline(5.0, color="k", ls="--", lw=0.8)
    ax.axhline(15.0, color="k", ls=":", lw=0.8)
    ax.set_yscale("log")
    ax.set_ylim(0.5, 200)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("pointing error (deg, truth)")
    ax.set_title("adcs_ref, magnetorquers only, POINTING forced at 5 s "
                 "(0.5 deg/s start 45 deg off, or at rest on target)")
    ax.legend()
    fig.tight_layout()
    out.mkdir(parents=True, exist_ok=True)
    fig.savefig(out / "pointing_error_runs.png", dpi=90)
    print(f"wrote {out / 'pointing_error_runs.png'}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("what", choices=("floquet", "runs"))
    ap.add_argument("specs", nargs="*", help="runs: LABEL=FOLDER of fprime-lite run outputs")
    ap.add_argument("--out", default="docs/img/magnetic_pointing")
    a = ap.parse_args(argv)
    if a.what == "floquet":
        floquet(pathlib.Path(a.out))
    else:
        runs(pathlib.Path(a.out), a.specs)
    return 0


if __name__ == "__main__":
    sys.exit(main())
