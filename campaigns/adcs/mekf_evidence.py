"""The MEKF's evidence table of docs/studies/attitude_knowledge.md: the figures its unit tests measure.

``tests/detumble/control/test_mekf.py`` flies the plant's own sensor models (LSM6DSO gyro, star tracker) read the
way the AttitudeController reads them, against an RK4 truth, and asserts bounds (MEKF-001…004). This script flies
the same flights with that module's own harness (its ``fly``, ``make_mekf`` and sensor specs, loaded from the test
file, so the figures are those of the flights the tests assert on) and records what they measure:

* ``nees``: the attitude NEES (3 dof; truth from RK4), sampled every 2 s after 100 s of 700 s (300 samples), its
  mean per seed (3, 4, 5; the test flies seed 3), the bias-only NEES (3 dof) beside it, and the NIS of the tracker
  updates (3 dof), each with its two-sided 95 % χ² band (normal approximation of the mean);
* ``nees_no_quantisation``: the same with the gyro's quantisation off: the 6-dof NEES mean (the test asserts it is
  at most its band's upper end) and its bias part (3 dof);
* ``bias``: from b̂ = 0 against the gyro's (0.3, −0.2, 0.1) °/s, after 120 s: the error per axis and its σ (°/s);
* ``covariance``: over 200 s, P symmetric at every cycle and its smallest eigenvalue (Cholesky every cycle);
* ``rms``: 400 s from a zero bias, over the last 300 s, the RMS attitude error per axis (″, body frame B) and the
  RMS bias error (°/s) of the MEKF and of the complementary filter (k_p 0.5 /s, k_i 0.02 /s²).

    python campaigns/adcs/mekf_evidence.py [--json FILE]

A few CPU-seconds.
"""

from __future__ import annotations

import importlib.util
import json
import math
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
TEST_MODULE = ROOT / "tests" / "detumble" / "control" / "test_mekf.py"
SEEDS = (3, 4, 5)


def harness():
    """tests/detumble/control/test_mekf.py as a module (its flight harness and specs)."""
    spec = importlib.util.spec_from_file_location("mekf_test_harness", TEST_MODULE)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _mean(values: list[float]) -> float:
    return sum(values) / len(values)


def _consistency(h, gyro_spec, sigma_g: float, seed: int) -> dict:
    """The test's consistency flight (700 s, sampled after 100 s): mean NEES (attitude 3 dof, bias 3 dof, 6 dof)
    every 2 s and mean NIS of every tracker update, with the sample counts."""
    att, bias, full, nis = h._consistency(gyro_spec, sigma_g, seed)
    return {"seed": seed, "samples": len(att), "updates": len(nis), "nees_attitude": _mean(att),
            "nees_bias": _mean(bias), "nees_6": _mean(full), "nis": _mean(nis),
            "band_3": list(h._band(3, len(att))), "band_6": list(h._band(6, len(full))),
            "band_nis": list(h._band(3, len(nis)))}


def _bias(h) -> dict:
    f = h.make_mekf()
    h.fly([f], 120.0)
    return {"error_deg_s": [math.degrees(t - e) for t, e in zip(h.BIAS, f.bias, strict=True)],
            "sigma_deg_s": [math.degrees(s) for s in f.bias_sigma_rad_s]}


def _covariance(h) -> dict:
    import numpy as np

    symmetric, smallest, cycles = True, [], [0]

    def on_cycle(t, state, filters):
        if filters[0].q is None:
            return
        p = np.asarray(filters[0].P)
        nonlocal symmetric
        symmetric = symmetric and bool(np.array_equal(p, p.T))
        np.linalg.cholesky(p)
        smallest.append(float(np.linalg.eigvalsh(p).min()))
        cycles[0] += 1

    h.fly([h.make_mekf()], 200.0, on_cycle=on_cycle)
    return {"symmetric": symmetric, "cycles": cycles[0], "smallest_eigenvalue": min(smallest)}


def _rms(h) -> dict:
    rms, brms = h.rms_errors()
    return {name: {"attitude_arcsec": rms[key], "bias_deg_s": brms[key]}
            for name, key in (("mekf", "mekf"), ("complementary", "cf"))}


def evidence() -> dict:
    """Every flight of the table (see the module's docstring)."""
    h = harness()
    no_quant = h.GyroSpec(bias_dps=h.GYRO.bias_dps, full_scale_dps=2000.0, resolution_dps=0.0)
    return {"test_module": str(TEST_MODULE.relative_to(ROOT)),
            "nees": [_consistency(h, h.GYRO, h.SIGMA_G, s) for s in SEEDS],
            "nees_no_quantisation": [_consistency(h, no_quant, math.radians(no_quant.noise_std_dps), s)
                                     for s in SEEDS],
            "bias": _bias(h), "covariance": _covariance(h), "rms": _rms(h)}


def _span(values: list[float], digits: int = 2) -> str:
    lo, hi = min(values), max(values)
    return f"{lo:.{digits}f}–{hi:.{digits}f}"


def _join(runs: list[dict], key: str) -> str:
    return ", ".join(f"{n[key]:.2f}" for n in runs)


def markdown(table: dict) -> str:
    """The page's check | result | bound table, and the bias-only NEES line under it."""
    nees, off = table["nees"], table["nees_no_quantisation"]
    b, p, r = table["bias"], table["covariance"], table["rms"]
    band, band_nis = nees[0]["band_3"], nees[0]["band_nis"]
    seeds = ", ".join(str(n["seed"]) for n in nees)
    rows = [
        "| check | result | bound |", "|---|---|---|",
        f"| attitude NEES (3 dof), mean over {nees[0]['samples']} samples (seeds {seeds}) | "
        f"{_join(nees, 'nees_attitude')} | 95 % χ² band {band[0]:.2f}–{band[1]:.2f} "
        f"(MEKF-001 asserts it on seed {nees[0]['seed']}) |",
        f"| innovation NIS (3 dof), mean over {', '.join(str(n['updates']) for n in nees)} updates | "
        f"{_join(nees, 'nis')} | 95 % χ² band {band_nis[0]:.2f}–{band_nis[1]:.2f} "
        f"(asserted on seed {nees[0]['seed']}) |",
        f"| 6-dof NEES with quantisation off (seeds {seeds}) | {_join(off, 'nees_6')}; "
        f"its bias part (3 dof) {_span([n['nees_bias'] for n in off])}: conservative, since σ_u > 0 and the "
        f"plant's bias is constant | ≤ {off[0]['band_6'][1]:.2f} (asserted on seed {off[0]['seed']}) |",
        f"| bias from b̂ = 0 (true 0.3/−0.2/0.1 °/s) after 120 s | error "
        f"{' / '.join(f'{e:.1e}' for e in b['error_deg_s'])} °/s, σ {' / '.join(f'{s:.1e}' for s in b['sigma_deg_s'])}"
        f" °/s | < 0.003 °/s per axis and within 3σ; σ < 0.003 °/s (asserted) |",
        f"| P symmetric and positive definite at every cycle | "
        f"{'yes' if p['symmetric'] else '**no**'} ({p['cycles']} cycles of 200 s, Cholesky each; smallest "
        f"eigenvalue {p['smallest_eigenvalue']:.1e}) | asserted |",
        f"| RMS attitude error x / y / z (″), 100–400 s, same seed | **MEKF "
        f"{' / '.join(f'{v:.1f}' for v in r['mekf']['attitude_arcsec'])}**, complementary "
        f"{' / '.join(f'{v:.1f}' for v in r['complementary']['attitude_arcsec'])} | MEKF smaller on every axis "
        f"(asserted) |",
        f"| RMS bias error (°/s) | MEKF {r['mekf']['bias_deg_s']:.2e}, complementary "
        f"{r['complementary']['bias_deg_s']:.2e} | MEKF smaller (asserted) |",
        "",
        f"With quantisation on, the bias-only NEES (3 dof) is {_join(nees, 'nees_bias')} "
        f"(seeds {seeds}; band {band[0]:.2f}–{band[1]:.2f}).",
    ]
    return "\n".join(rows) + "\n"


def differences(now, then, where: str = "") -> list[str]:
    """Where ``now`` differs from ``then`` (nested dicts and lists compared to the float), one line each."""
    if isinstance(then, dict) and isinstance(now, dict):
        keys = sorted(set(now) | set(then))
        return [d for k in keys for d in differences(now.get(k), then.get(k), f"{where}.{k}" if where else k)]
    if isinstance(then, list) and isinstance(now, list) and len(now) == len(then):
        return [d for i, (a, b) in enumerate(zip(now, then, strict=True)) for d in differences(a, b, f"{where}[{i}]")]
    return [] if now == then else [f"{where}: {now!r} now, {then!r} committed"]


def probe(committed: dict) -> list[str]:
    """Every flight again (a few CPU-seconds), compared with the committed file to the float."""
    return differences(json.loads(json.dumps(evidence())), committed)


def main(argv: list[str] | None = None) -> int:
    from detumble.reports.study_table import table_script_main

    return table_script_main(argv, __doc__.split("\n\n")[0], lambda args: evidence(), markdown)


if __name__ == "__main__":
    sys.exit(main())
