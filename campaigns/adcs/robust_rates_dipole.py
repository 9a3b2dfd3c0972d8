"""The residual dipole in the rate observer (docs/studies/robust_rates.md, "The residual dipole in the observer"):
the figures the page gives beside its campaign, flown plant-only.

    python campaigns/adcs/robust_rates_dipole.py draws      # the gate campaign's three misses, T 0/10/20/40 s
    python campaigns/adcs/robust_rates_dipole.py targets    # pointing_targets.md's nadir and station pass, 0 and 20 s
    python campaigns/adcs/robust_rates_dipole.py blocks 26  # one draw's error in 20 s blocks, 0 and 20 s
    python campaigns/adcs/robust_rates_dipole.py auto       # the adcs scenario's own orbit (AUTO), 0 and 20 s
    python campaigns/adcs/robust_rates_dipole.py learn      # when that orbit's observer learns, at the defaults
    python campaigns/adcs/robust_rates_dipole.py estimators # the single-run slew with each ESTIMATOR, 0 and 20 s
    python campaigns/adcs/robust_rates_dipole.py along      # that orbit's estimate error, along and across the field

``draws``: the robust-rates campaign's draws 3, 0 and 77 (the three the default gate misses) flown as the gate
campaign flies them (``robust_rates_tail.fly`` with INTEGRAL_RATE_GATE 0.05 °/s) with the estimate's time constant
at 0 (off), 10, 20 and 40 s: honest-window p95 (deg), seconds above 0.05° in the hold of the attitude of entry and
after the slew's settle. ``targets``: pointing_targets.md's default cases (adcs scenario, seed 1, from rest, FORCE_MODE
POINTING at 1 s: nadir over one orbit, the ground-station pass over 1900 s) with the estimate off and at 20 s:
acquisition (s) and steady median / p95 / max (deg) per active reference. ``blocks N``: the campaign's draw N flown
as ``draws`` does with the estimate off and at 20 s: the true error's p95 / median (deg) in each 20 s block from the
slew's command (60 s) on, and the dipole estimate (A·m², B) just before the slew's stretch is one time constant old.
``auto``: the adcs scenario as it is (a tumble, AUTO through detumble and spin into POINTING, which holds the attitude
of entry to the end of the orbit) with the estimate off and at 20 s: the pointing statistics after acquisition (deg).
``learn``: the same orbit at the controller's defaults (the estimate on, 20 s since issue 27): when POINTING is
entered and acquired, the calm stretches in which the observer learns the dipole (s; those under 1 s only counted),
when its estimate first differs from zero (s), and the estimate at the end against the plant's dipole (A·m², B).
``estimators``: the robust-rates single-run geometry (``robust_rates_table``, the plant's inertia exact, 400 s) with
ESTIMATOR COMPLEMENTARY and MEKF, the estimate off and at 20 s: the slew's settle below 0.1° (s), median / p95 from
120 s (deg), and the dipole estimate when POINTING is entered (30 s) and at the end (A·m², B).
``along``: the ``learn`` orbit again; at twenty evenly spaced learning cycles and the last, the estimate's error
against the plant's dipole split into its part along the field the observer was given that cycle (which gives no
torque) and the part across it (A·m², B), the torque error that part makes and the plant dipole's own torque
``|m × B|`` (nN·m).
"""

from __future__ import annotations

import json
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
DRAWS = (3, 0, 77)
TIMES_S = (0.0, 10.0, 20.0, 40.0)


def draws() -> None:
    import pandas as pd

    sys.path.insert(0, str(ROOT / "campaigns" / "adcs"))
    from robust_rates_tail import CAMPAIGN, fly

    df = pd.read_parquet(CAMPAIGN).set_index("seed_index")
    for i in DRAWS:
        for t in TIMES_S:
            r = fly(json.loads(df.loc[i, "requested"]), int(df.loc[i, "seed"]),
                    ["control.adcs.INTEGRAL_RATE_GATE=0.05", f"control.adcs.RATE_OBSERVER_DIPOLE_TIME={t:g}"])
            print(f"draw {i:3d}  T {t:4.0f} s  p95 {r['p95_deg']:.4f}°  entry above 0.05° {r['entry_above_s']:4.1f} s  "
                  f"after the settle {r['after_settle_above_s']:4.1f} s  settle {r['settle_s']:.1f} s", flush=True)


def targets() -> None:
    sys.path.insert(0, str(ROOT / "campaigns" / "adcs"))
    from targets_study import CASES

    from detumble.sim.runner import run
    from detumble.sim.scenario import load_scenario

    for case in ("nadir", "ground station"):
        target, duration = CASES[case]
        for t in (0.0, 20.0):
            settings = ["initial.rate.magnitude_deg_s=0", "control.adcs.force_mode=POINTING",
                        "control.adcs.force_at_s=1", f"control.adcs.target_changes=[[0.5, {target}]]",
                        f"control.adcs.RATE_OBSERVER_DIPOLE_TIME={t:g}"]
            s = run(load_scenario("adcs", settings=settings), law="adcs", duration_s=duration).summary
            for label, st in s["pointing_error_by_target_deg"].items():
                acq = [i["acquisition_s"] for i in s["pointing_intervals"] if i["target"] == label]
                figures = "none" if st is None else f"{st['median']:.4f} / {st['p95']:.4f} / {st['max']:.3f}"
                print(f"{case:15s} T {t:4.0f} s  {label:17s} acquisitions {acq}  median / p95 / max {figures}",
                      flush=True)


def auto() -> None:
    from detumble.sim.runner import run
    from detumble.sim.scenario import load_scenario

    for t in (0.0, 20.0):
        s = run(load_scenario("adcs", settings=[f"control.adcs.RATE_OBSERVER_DIPOLE_TIME={t:g}"]), law="adcs").summary
        e = s["pointing_error_deg"]
        entries = [i["t_s"] for i in s["pointing_intervals"]]
        print(f"adcs T {t:4.0f} s  POINTING from {entries} s  acquisition {e['acquisition_s']} s  median / p95 / max "
              f"{e['median']:.4f} / {e['p95']:.4f} / {e['max']:.3f}  samples {e['samples']}", flush=True)


def blocks(index: int) -> None:
    import numpy as np
    import pandas as pd

    sys.path.insert(0, str(ROOT / "campaigns" / "adcs"))
    from robust_rates_tail import CAMPAIGN

    from detumble.control.rate_observer import RateObserver
    from detumble.sim.runner import run
    from detumble.sim.scenario import load_scenario
    from fprime_lite.tools.campaign.values import yaml_text

    df = pd.read_parquet(CAMPAIGN).set_index("seed_index")
    requested = json.loads(df.loc[index, "requested"])
    settings = [f"{k[9:]}={yaml_text(v)}" for k, v in sorted(requested.items()) if k.startswith("scenario.")]
    scenario = ROOT / "campaigns" / "adcs" / "scenarios" / "robust_rates_gate.yaml"
    learn = RateObserver.learn_dipole
    for t in (0.0, 20.0):
        seen: list = []

        def spy(self, *args, seen=seen):
            seen.append(self.dipole)
            return learn(self, *args)

        RateObserver.learn_dipole = spy  # type: ignore[method-assign]
        try:
            r = run(load_scenario(str(scenario), seed=int(df.loc[index, "seed"]),
                                  settings=settings + [f"control.adcs.RATE_OBSERVER_DIPOLE_TIME={t:g}"]),
                    law="adcs", duration_s=330.0)
        finally:
            RateObserver.learn_dipole = learn  # type: ignore[method-assign]
        assert r.adcs_header is not None and r.adcs_rows is not None
        k = r.adcs_header.index("pointing_error_deg")
        trace = np.array([(row[0], float(a[k])) for row, a in zip(r.rows, r.adcs_rows, strict=True)
                          if a[k] not in ("", None)])
        cells = []
        for t0 in range(80, 330, 20):
            e = trace[(trace[:, 0] >= t0) & (trace[:, 0] < t0 + 20), 1]
            cells.append(f"{t0}-{t0 + 20} s {np.percentile(e, 95):.4f} / {np.median(e):.4f}")
        print(f"draw {index} T {t:g} s: " + ", ".join(cells), flush=True)
        changes = [i for i in range(1, len(seen)) if seen[i] != seen[i - 1]]
        if changes:
            print("  dipole estimates taken (A·m²): " + ", ".join(
                f"({', '.join(f'{x:.2e}' for x in seen[i])})" for i in changes[::max(1, len(changes) // 6)]))


def _fly_auto_orbit():
    """The adcs scenario's AUTO orbit at the defaults, plant-only: ``(scenario, result, cycle_s, calm)`` with
    ``calm`` the ``(cycle, estimate after it, field given)`` of every control cycle in which the observer learned."""
    from detumble.control.rate_observer import RateObserver
    from detumble.sim.runner import run
    from detumble.sim.scenario import load_scenario

    fit, update = RateObserver.learn_dipole, RateObserver.update
    cycles: list[int] = [0]
    calm: list[tuple[int, tuple, tuple]] = []

    def counted(self, *args, **kwargs):
        cycles[0] += 1
        return update(self, *args, **kwargs)

    def learned(self, omega, torque, momentum, b_tesla, dt, time_s):
        calm.append((cycles[0], fit(self, omega, torque, momentum, b_tesla, dt, time_s), b_tesla))
        return self.dipole

    RateObserver.learn_dipole, RateObserver.update = learned, counted  # type: ignore[method-assign]
    try:
        sc = load_scenario("adcs")
        r = run(sc, law="adcs")
    finally:
        RateObserver.learn_dipole, RateObserver.update = fit, update  # type: ignore[method-assign]
    return sc, r, r.rows[-1][0] / cycles[0], calm


def learn() -> None:
    sc, r, cycle_s, calm = _fly_auto_orbit()
    stretches: list[list[int]] = []
    for n, _, _ in calm:
        if stretches and n == stretches[-1][1] + 1:
            stretches[-1][1] = n
        else:
            stretches.append([n, n])
    long = [(a * cycle_s, b * cycle_s) for a, b in stretches if (b - a + 1) * cycle_s >= 1.0]
    e = r.summary["pointing_error_deg"]
    first = next((n * cycle_s for n, m, _ in calm if any(x != 0.0 for x in m)), None)
    print(f"POINTING from {[i['t_s'] for i in r.summary['pointing_intervals']]} s, acquisition {e['acquisition_s']} s; "
          f"{len(stretches)} calm stretches, {len(stretches) - len(long)} under 1 s; the others (s): "
          + ", ".join(f"{a:.1f}-{b:.1f}" for a, b in long))
    when = "never" if first is None else f"{first:.1f}"
    end = ", ".join(f"{x:.2e}" for x in calm[-1][1])
    print(f"estimate first non-zero at {when} s; at the end ({end}) A·m², the plant's "
          f"{sc.spacecraft.residual_dipole_am2}")


def estimators() -> None:
    sys.path.insert(0, str(ROOT / "campaigns" / "adcs"))
    from robust_rates_table import BASE

    from detumble.control.rate_observer import RateObserver
    from detumble.sim.runner import run
    from detumble.sim.scenario import load_scenario

    fit, update = RateObserver.learn_dipole, RateObserver.update
    for estimator in ("COMPLEMENTARY", "MEKF"):
        for t in (0.0, 20.0):
            cycles, seen = [0], []  # control cycles so far; (cycle, estimate) of each cycle that learned

            def counted(self, *args, cycles=cycles, **kwargs):
                cycles[0] += 1
                return update(self, *args, **kwargs)

            def learned(self, *args, cycles=cycles, seen=seen):
                seen.append((cycles[0], fit(self, *args)))
                return self.dipole

            RateObserver.learn_dipole, RateObserver.update = learned, counted  # type: ignore[method-assign]
            try:
                r = run(load_scenario("adcs", settings=BASE + [f"control.adcs.ESTIMATOR={estimator}",
                                                               f"control.adcs.RATE_OBSERVER_DIPOLE_TIME={t:g}"]),
                        law="adcs", duration_s=400.0)
            finally:
                RateObserver.learn_dipole, RateObserver.update = fit, update  # type: ignore[method-assign]
            assert r.adcs_header is not None and r.adcs_rows is not None
            k = r.adcs_header.index("pointing_error_deg")
            steady = sorted(float(a[k]) for row, a in zip(r.rows, r.adcs_rows, strict=True) if row[0] >= 120.0)
            cycle_s = r.rows[-1][0] / cycles[0]
            entry = [m for n, m in seen if n * cycle_s <= 30.0]
            vec = lambda m: "(" + ", ".join(f"{x:.1e}" for x in m) + ")"  # noqa: E731
            text = f"at 30 s {vec(entry[-1])}, at the end {vec(seen[-1][1])}" if entry else "none"
            print(f"{estimator:13s} T {t:2.0f} s  settle {r.summary['slews'][0]['settle_below_0p1_deg_s']} s  "
                  f"median / p95 {steady[len(steady) // 2]:.4f} / {steady[int(round(0.95 * (len(steady) - 1)))]:.4f}"
                  f"  dipole estimate {text}", flush=True)


def along() -> None:
    import math

    sc, _, cycle_s, seen = _fly_auto_orbit()
    true = sc.spacecraft.residual_dipole_am2

    def dot(a, b):
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]

    def cross_norm(a, b):
        return math.sqrt(max(dot(a, a) * dot(b, b) - dot(a, b) ** 2, 0.0))

    n = len(seen)
    for k in [*range(n // 20, n, n // 20)][:19] + [n - 1]:
        cycle, m, b = seen[k]
        e = (m[0] - true[0], m[1] - true[1], m[2] - true[2])
        b_norm = math.sqrt(dot(b, b))
        along_b = dot(e, b) / b_norm
        across = math.sqrt(max(dot(e, e) - along_b ** 2, 0.0))
        print(f"t {cycle * cycle_s:7.1f} s  error along B {along_b * 1e3:+.3f}e-3, across {across * 1e3:.3f}e-3 A·m²  "
              f"torque error {across * b_norm * 1e9:.1f} nN·m of the dipole's {cross_norm(true, b) * 1e9:.1f}",
              flush=True)


if __name__ == "__main__":
    command = sys.argv[1] if len(sys.argv) > 1 else "draws"
    if command == "blocks":
        blocks(int(sys.argv[2]))
    else:
        {"draws": draws, "targets": targets, "auto": auto, "learn": learn, "estimators": estimators,
         "along": along}[command]()
