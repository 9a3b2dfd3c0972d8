"""Figures of docs/studies/magnetic_pointing.md.

    python campaigns/adcs/magnetic_pointing_figures.py floquet --out docs/img/magnetic_pointing \
        --json docs/studies/magnetic_pointing/floquet_maps.json

``floquet``: the Floquet growth rate (1/s, one orbit of the adcs_ref field toward its start-up target) of
seed 003's projected PD over (K_P, K_D), and of the steering law over (ρ, K_D) at the first pass's K_P (ζ 0.7), in
the scenario's field; the figures the page quotes from them are printed (``maps_markdown``), and ``--json`` keeps
the maps, from which ``tools/studies.py --only magnetic_pointing_floquet_figure`` draws the figure and the page's
block again.
The error-vs-time figure of the single deployment runs is drawn by ``magnetic_pointing_runs.py``'s ``draw_errors``
from the error series its ``--json`` keeps (``tools/studies.py --only magnetic_pointing_runs``).
"""

from __future__ import annotations

import argparse
import math
import pathlib
import sys

import numpy as np

from detumble.analysis.magnetic_floquet import averaged_projection, field_line_along_orbit, floquet_rate
from detumble.sim.plant import Plant
from detumble.sim.scenario import load_scenario

TARGET = (0.9238795325112867, 0.0, 0.3826834323650898, 0.0)


KPS = [float(x) for x in np.logspace(-10, -5, 11)]
KDS = [float(x) for x in np.logspace(-6, -3, 10)]
RHOS = [0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0]
KDS_STEER = [2e-5, 4e-5, 1e-4, 2e-4, 4e-4]
OLD_GAINS = (2e-6, 4e-4)          # seed 003's PD: K_P_MAG, K_D_MAG
FIRST_PASS = (1e-6, 1e-4, 2.0)    # the steering law's first-pass K_P_MAG, K_D_MAG, ρ (ζ 0.7, the law's default)
#: samples of the orbit, one RK4 step each: magnetic_pointing_tables.py's FLOQUET_SAMPLES, the count its convergence
#: table justifies (400 samples × 8 sub-steps until 2026-12-04)
SAMPLES, SUBSTEPS = 16000, 1


def field_line(plant=None):
    """(period, b̂, ḃ) over one orbit of the adcs scenario toward the start-up target (:data:`SAMPLES`)."""
    plant = plant or Plant(load_scenario("adcs"))
    return plant, *field_line_along_orbit(plant, TARGET, samples=SAMPLES)


def floquet_maps() -> dict:
    """The two maps and the figures the page quotes from them (rates in 1/s, negative decays)."""
    plant, period, b, bd = field_line()
    inertia = np.array(plant.scenario.spacecraft.inertia_kg_m2)
    rate = np.linalg.norm(bd, axis=1)
    seed = [[floquet_rate("seed_pd", period, b, bd, inertia, kp, kd, substeps=SUBSTEPS) for kp in KPS] for kd in KDS]
    steer = [[floquet_rate("field_steering", period, b, bd, inertia, FIRST_PASS[0], kd, rho=rho,
                          substeps=SUBSTEPS) for rho in RHOS]
             for kd in KDS_STEER]
    return {"field_model": plant.scenario.field.model, "period_s": float(period),
            "mean_motion_rad_s": float(plant.orbit.mean_motion),
            "field_line_rate": {"min": float(rate.min()), "mean": float(rate.mean()), "max": float(rate.max())},
            "averaged_projection_eig": [float(x) for x in np.linalg.eigvalsh(averaged_projection(b[:-1]))],
            "old_gains_rate": float(floquet_rate("seed_pd", period, b, bd, inertia, *OLD_GAINS, substeps=SUBSTEPS)),
            "k_p": KPS, "k_d": KDS, "seed_pd": seed, "rho": RHOS, "k_d_steer": KDS_STEER, "field_steering": steer}


def _e(x: float, digits: int = 0) -> str:
    """``x`` in e-notation without the exponent's leading zero (3e-8, 4.8e-4)."""
    mantissa, exponent = f"{x:.{digits}e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def maps_markdown(maps: dict) -> str:
    """The figures the page quotes from the maps (markdown lines)."""
    seed = np.array(maps["seed_pd"])
    kps = np.array(maps["k_p"])
    # the K_P from which every K_P of the map diverges at every K_D of the map
    diverging = [kp for j, kp in enumerate(kps) if (seed[:, j:] > 0).all()]
    stable = seed < 0
    best = float(seed[stable].min()) if stable.any() else None
    corner = [kps[j] for j in range(len(kps)) if stable[:, j].any()]
    r = maps["field_line_rate"]
    eig = ", ".join(f"{x:.2f}" for x in maps["averaged_projection_eig"])
    old = ("+" if maps["old_gains_rate"] > 0 else "−") + _e(abs(maps["old_gains_rate"]), 1)
    lines = [f"- field ({maps['field_model']}): over the orbit ({maps['period_s']:.0f} s) b̂ turns at r = "
             f"{_e(r['min'], 1)}–{_e(r['max'], 1)} rad/s (mean {_e(r['mean'], 2)}, "
             f"{r['mean'] / maps['mean_motion_rad_s']:.1f} n); the averaged projection ⟨P⟩ has eigenvalues {eig}",
             f"- seed 003's PD with the old gains (K_P 2e-6, K_D 4e-4): **{old} /s** "
             f"(×{math.exp(maps['old_gains_rate'] * maps['period_s']):.0f} per orbit)",
             f"- seed 003's PD diverges at every K_P ≥ {_e(min(diverging))} N·m of the map, whatever K_D"
             if diverging else "- seed 003's PD: the map's largest K_P does not diverge at every K_D",
             (f"- its stable corner: K_P ≤ {_e(max(corner))} N·m, best decay {_e(-best, 1)} /s (e-folding "
              f"{-1.0 / best:.0f} s)") if best is not None else "- seed 003's PD: no stable point on the map"]
    return "\n".join(lines) + "\n"


def draw_floquet(maps: dict, out: pathlib.Path) -> pathlib.Path:
    """Draw the maps of ``maps`` (:func:`floquet_maps`) into ``out/floquet.png``."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
    lim = 2.5e-3
    for ax, data, x, y, xl, title in (
            (axes[0], maps["seed_pd"], np.log10(maps["k_p"]), np.log10(maps["k_d"]), "log10 K_P (N·m)",
             "seed 003 PD projected perpendicular to B"),
            (axes[1], maps["field_steering"], np.array(maps["rho"]), np.log10(maps["k_d_steer"]),
             f"ρ (K_P {FIRST_PASS[0]:g} N·m)", "field steering")):
        im = ax.pcolormesh(x, y, np.clip(np.array(data), -lim, lim), cmap="RdBu_r", vmin=-lim, vmax=lim,
                           shading="nearest")
        ax.set_xlabel(xl)
        ax.set_ylabel("log10 K_D (N·m·s)")
        ax.set_title(f"{title} ({maps['field_model']})")
        fig.colorbar(im, ax=ax, label="Floquet rate, 1/s (red: diverges)")
    axes[0].plot(np.log10(OLD_GAINS[0]), np.log10(OLD_GAINS[1]), "k*", ms=14, label="old defaults")
    axes[0].legend(loc="lower left")
    axes[1].plot(FIRST_PASS[2], np.log10(FIRST_PASS[1]), "k*", ms=14, label="first-pass defaults")
    axes[1].legend(loc="lower left")
    fig.tight_layout()
    fig.savefig(out / "floquet.png", dpi=90)
    plt.close(fig)
    return out / "floquet.png"


def probe(committed: dict) -> list[str]:
    """The field line's figures and the old gains' rate computed again (one Floquet map, a few CPU-s) against the
    committed ones, to the float."""
    plant, period, b, bd = field_line()
    inertia = np.array(plant.scenario.spacecraft.inertia_kg_m2)
    rate = np.linalg.norm(bd, axis=1)
    again = {"period_s": float(period), "field_line_rate": {"min": float(rate.min()), "mean": float(rate.mean()),
                                                            "max": float(rate.max())},
             "old_gains_rate": float(floquet_rate("seed_pd", period, b, bd, inertia, *OLD_GAINS, substeps=SUBSTEPS))}
    return [f"{key} is {value} now, {committed.get(key)} committed" for key, value in again.items()
            if committed.get(key) != value]


def floquet(out: pathlib.Path, json_path: pathlib.Path | None = None) -> None:
    maps = floquet_maps()
    if json_path is not None:
        from fprime_lite.osal.atomic import atomic_write_json

        atomic_write_json(json_path, maps)
    print(maps_markdown(maps), end="")
    print(f"wrote {draw_floquet(maps, out)}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("what", choices=("floquet",))
    ap.add_argument("--out", default="docs/img/magnetic_pointing")
    ap.add_argument("--json", type=pathlib.Path, metavar="FILE", help="also keep the maps in FILE (JSON)")
    a = ap.parse_args(argv)
    floquet(pathlib.Path(a.out), a.json)
    return 0


if __name__ == "__main__":
    sys.exit(main())
