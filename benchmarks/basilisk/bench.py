"""fprime-lite against Basilisk, side by side in one sitting (issue #19): what
``benchmarks/bench_vs_basilisk.py`` and the ``basilisk`` piece of ``fprime-lite bench``
(:mod:`detumble.tools.bench_basilisk`, which finds this folder in a checkout) measure.

Four kinds of run, each in a fresh child process, interleaved round by round so that every kind
sees the same load on a shared machine:

1. ``basilisk_20hz``: Basilisk, case A, dynamics and its Python B-dot at 20 Hz (0.05 s)
   (:mod:`basilisk.case_a`);
2. ``fprime_lite_plant_20hz``: the plant-only runner, case A, kopt law, 20 Hz (what
   ``fprime-lite sim case_a --law kopt`` flies);
3. ``basilisk_50hz``: Basilisk, case A at 50 Hz (0.02 s);
4. ``basilisk_lean_50hz``: the same case as a performance-minded Basilisk user writes it
   (``case_a --lean``: Basilisk's C++ magnetometer feeding the Python B-dot, the Earth-rotation
   ephemeris on a 1 s task, a 1 s rate recorder);
5. ``fprime_lite_deployment_50hz``: the whole F´ deployment of the topology at 50 Hz (every
   component, rate group, channel and event; ``fprime-lite run`` without its output files);
6. ``fprime_lite_run_50hz``: ``fprime-lite run --no-plots`` as users run it: topology loaded,
   flown, and its outputs written (events.log, channels.csv, channels_wide.csv, truth.csv,
   summary.json, dictionary.json), timed from the load to the last file written.

Issue 32's goal for proves_ref is ``run_50hz_over_fastest_basilisk`` (≥ 2.0): the ``run`` kind
against the faster of the two Basilisk 50 Hz kinds in each round's best.

The newer deployments have their own cases (:func:`measure_case`, ``--case`` of the benchmark
script; definitions in :mod:`basilisk.side_by_side`):

* ``adcs_ref``: the pointing case, ``basilisk_adcs_c_50hz`` (every law in Basilisk's C modules,
  :mod:`basilisk.adcs`), ``basilisk_adcs_python_50hz`` (the project's laws in one
  Python module), ``fprime_lite_adcs_ref_50hz`` (the whole adcs_ref deployment flying the same
  sequence) and ``fprime_lite_adcs_plant_50hz`` (the same flight software without the framework: the
  plant-only ``adcs`` law on :func:`~basilisk.side_by_side.plant_only_settings`, the deployment's
  flight to the last bit: its ratio to Basilisk is context, the bound a framework cannot beat, and its
  ratio to the deployment is the deployment's tick over the plant-only tick on this case);
* ``coursework``: WHEELS_PD, ``basilisk_coursework_100hz`` (:mod:`basilisk.coursework`)
  and ``fprime_lite_coursework_100hz`` (the whole coursework deployment as shipped).

Each child times only its run proper (set-up excluded; the ``run`` kind from before its imports)
and reports the real-time factor. The children run with Python's bytecode cache on, as a user's
install does (``_child_env``: the build machines set ``PYTHONDONTWRITEBYTECODE``). The
figures are the fastest round of each kind, the ratios are formed from them, and the median
round's ratios are reported beside them. Both case-A runs report when |ω| < 1 °/s, a check that
the two sides simulate the same thing. Basilisk is optional: ``pip install -e '.[bsk]'`` (PyPI
name ``bsk``); without it the piece says so and measures nothing.
"""
from __future__ import annotations

import argparse
import importlib.util
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile

__all__ = ["measure", "measure_cases", "case_of", "plausibility_text", "CASES", "GOALS", "basilisk_installed",
           "piece_figures", "piece_rows", "INSTALL_HINT"]

ORBIT_S = 5578.0  #: one case-A orbit (420 km), simulated seconds
BENCHMARKS = pathlib.Path(__file__).resolve().parents[1]  #: benchmarks/, where the package ``basilisk`` is
DEPLOYMENTS = BENCHMARKS.parent / "deployments"
INSTALL_HINT = "pip install -e '.[bsk]'  (Basilisk from PyPI, package bsk)"

_PLANT = """
import json
from detumble.sim.runner import run
from detumble.sim.scenario import load_scenario
s = run(load_scenario("case_a"), law="kopt", duration_s={duration}).summary
print(json.dumps({{"sim_seconds": s["sim_seconds"], "wall_s": s["wall_seconds"],
                  "real_time_factor": s["sim_seconds"] / s["wall_seconds"],
                  "time_below_1_deg_s": s["time_below_1_deg_s"], "final_rate_deg_s": s["final_rate_deg_s"]}}))
"""

_DEPLOYMENT = """
import json, time
from fprime_lite.deploy.deployment import Deployment
from fprime_lite.deploy.topology_loader import load_topology
loaded = load_topology({topology!r})
deployment = Deployment(loaded)
deployment.start()
t0 = time.perf_counter()
deployment.run_for({duration})
wall = time.perf_counter() - t0
craft = loaded.resources.get("spacecraft")
rate = craft.truth().rate_deg_s if craft is not None else None
print(json.dumps({{"sim_seconds": {duration}, "wall_s": wall, "real_time_factor": {duration} / wall,
                  "final_rate_deg_s": rate}}))
"""


# fprime-lite run as users run it (no plots, no progress bar): load, fly, write every output file, the
# telemetry files and truth rows by the writer process where `fprime-lite run`'s default (--writer auto) has one.
_RUN = """
import json, tempfile, time
t0 = time.perf_counter()
from fprime_lite.deploy.topology_loader import load_topology
from fprime_lite.tools.runner import run_deployment
loaded = load_topology({topology!r})
with tempfile.TemporaryDirectory() as out:
    s = run_deployment(loaded, out, duration_s={duration}, plots=False, quiet=True, allow_warnings=True,
                       writer="auto")
    wall = time.perf_counter() - t0
print(json.dumps({{"sim_seconds": s["sim_seconds"], "wall_s": wall, "real_time_factor": s["sim_seconds"] / wall,
                  "flight_wall_s": s["wall_seconds"]}}))
"""


# The adcs_ref deployment flying the pointing case (side_by_side's sequence and settings), its truth
# sampled every TRACE_INTERVAL_S as the Basilisk side records it.
_ADCS = """
import json, os, tempfile, time
from fprime_lite.deploy.deployment import Deployment
from fprime_lite.tools.api import load
from basilisk import side_by_side as case
loaded = load({topology!r}, settings=list(case.SETTINGS))
craft = loaded.resources["spacecraft"]
trace = []
with tempfile.TemporaryDirectory() as folder:
    seq = os.path.join(folder, "pointing.seq")
    with open(seq, "w") as f:
        f.write(case.sequence_text())
    deployment = Deployment(loaded)
    deployment.start(sequence=seq)
    craft.set_trace(lambda s: trace.append((s.t_s, s.q_BN, s.wheel_momenta)), round(case.TRACE_INTERVAL_S * 1e6))
    t0 = time.perf_counter()
    deployment.run_for({duration})
    wall = time.perf_counter() - t0
print(json.dumps({{"sim_seconds": {duration}, "wall_s": wall, "real_time_factor": {duration} / wall,
                  **case.plausibility(trace)}}))
"""

# The same flight without the framework: the plant-only adcs law with the sequence's commands as settings.
_ADCS_PLANT = """
import json
from detumble.sim.runner import run
from detumble.sim.scenario import load_scenario
from basilisk import side_by_side as case
r = run(load_scenario(case.SCENARIO, settings=case.plant_only_settings()), law="adcs", duration_s={duration})
s, cols = r.summary, r.adcs_header
q, h = [cols.index(f"q{{i}}") for i in range(4)], [i for i, c in enumerate(cols) if c.endswith("_Nms")]
trace = [(row[0], [extra[i] for i in q], [extra[i] for i in h]) for row, extra in zip(r.rows, r.adcs_rows)]
print(json.dumps({{"sim_seconds": s["sim_seconds"], "wall_s": s["wall_seconds"],
                  "real_time_factor": s["sim_seconds"] / s["wall_seconds"], **case.plausibility(trace)}}))
"""

_COURSEWORK = """
import json, time
from fprime_lite.deploy.deployment import Deployment
from fprime_lite.tools.api import load
from basilisk import side_by_side as case
loaded = load({topology!r})
craft = loaded.resources["spacecraft"]
trace = []
deployment = Deployment(loaded)
deployment.start()
craft.set_trace(lambda s: trace.append((s.t_s, s.q_BO, s.omega_BN_B, s.wheel_momenta)),
                round(case.TRACE_INTERVAL_S * 1e6))
t0 = time.perf_counter()
deployment.run_for({duration})
wall = time.perf_counter() - t0
print(json.dumps({{"sim_seconds": {duration}, "wall_s": wall, "real_time_factor": {duration} / wall,
                  **case.coursework_plausibility(trace)}}))
"""

#: case -> (its deployment, [(ratio name, fprime-lite kind, Basilisk kind or kinds)]); with several
#: Basilisk kinds the ratio is taken against the fastest of them.
CASES: dict[str, tuple[pathlib.Path, list[tuple[str, str, str | tuple[str, ...]]]]] = {
    "proves_ref": (DEPLOYMENTS / "proves_ref" / "topology.yaml",
                   [("run_50hz_over_fastest_basilisk", "fprime_lite_run_50hz", ("basilisk_50hz", "basilisk_lean_50hz")),
                    ("plant_20hz_over_basilisk", "fprime_lite_plant_20hz", "basilisk_20hz"),
                    ("deployment_50hz_over_basilisk", "fprime_lite_deployment_50hz", "basilisk_50hz"),
                    ("deployment_50hz_over_basilisk_lean", "fprime_lite_deployment_50hz", "basilisk_lean_50hz")]),
    "adcs_ref": (DEPLOYMENTS / "adcs_ref" / "topology.yaml",
                 [("adcs_ref_over_basilisk_c", "fprime_lite_adcs_ref_50hz", "basilisk_adcs_c_50hz"),
                  ("adcs_ref_over_basilisk_python", "fprime_lite_adcs_ref_50hz", "basilisk_adcs_python_50hz"),
                  ("adcs_laws_alone_over_basilisk_c", "fprime_lite_adcs_plant_50hz", "basilisk_adcs_c_50hz"),
                  # plant-only real-time factor over the deployment's: the deployment's tick over the plant-only tick
                  ("adcs_ref_tick_over_plant_only_tick", "fprime_lite_adcs_plant_50hz", "fprime_lite_adcs_ref_50hz")]),
    "coursework": (DEPLOYMENTS / "coursework" / "topology.yaml",
                   [("coursework_over_basilisk", "fprime_lite_coursework_100hz", "basilisk_coursework_100hz")]),
}
#: ratio -> issue 32's goal; the others are context (issue 19's goals, which issue 32 replaced, are
#: in docs/performance.md; adcs_laws_alone_*: the flight software without the framework)
GOALS = {"run_50hz_over_fastest_basilisk": "≥ 2.0", "adcs_ref_over_basilisk_python": "≥ 1.0"}


def _kinds(case: str, topology: str, duration_s: float) -> dict[str, list[str]]:
    """The child command of every kind of run of ``case`` (in the order they are flown)."""
    py = sys.executable
    d = str(duration_s)
    if case == "proves_ref":
        case_a = [py, "-m", "basilisk.case_a", "--duration", d]
        return {
            "basilisk_20hz": case_a + ["--step", "0.05"],
            "fprime_lite_plant_20hz": [py, "-c", _PLANT.format(duration=duration_s)],
            "basilisk_50hz": case_a + ["--step", "0.02"],
            "basilisk_lean_50hz": case_a + ["--step", "0.02", "--lean"],
            "fprime_lite_deployment_50hz": [py, "-c", _DEPLOYMENT.format(topology=topology, duration=duration_s)],
            "fprime_lite_run_50hz": [py, "-c", _RUN.format(topology=topology, duration=duration_s)],
        }
    if case == "adcs_ref":
        adcs = [py, "-m", "basilisk.adcs", "--duration", d, "--step", "0.02"]
        return {
            "basilisk_adcs_c_50hz": adcs + ["--control", "c"],
            "basilisk_adcs_python_50hz": adcs + ["--control", "python"],
            "fprime_lite_adcs_ref_50hz": [py, "-c", _ADCS.format(topology=topology, duration=duration_s)],
            "fprime_lite_adcs_plant_50hz": [py, "-c", _ADCS_PLANT.format(duration=duration_s)],
        }
    if case == "coursework":
        return {
            "basilisk_coursework_100hz": [py, "-m", "basilisk.coursework", "--duration", d],
            "fprime_lite_coursework_100hz": [py, "-c", _COURSEWORK.format(topology=topology, duration=duration_s)],
        }
    raise ValueError(f"no side-by-side case {case!r}; choose one of {', '.join(CASES)}")


def basilisk_installed() -> bool:
    return importlib.util.find_spec("Basilisk") is not None


def _child_env() -> dict[str, str]:
    """The children's environment: this package on the path, and Python's bytecode cache on.

    A user's installed fprime-lite runs from compiled bytecode (pip compiles what it installs; an
    editable install writes ``__pycache__`` on its first run). With ``PYTHONDONTWRITEBYTECODE`` set,
    as on the shared build machines, every child would compile the ~140 modules it imports from
    source, about 0.3-0.4 s of CPU a run that no user pays: the children keep their bytecode in
    a cache of their own (``PYTHONPYCACHEPREFIX``, the source tree untouched), filled by
    :func:`_warm_bytecode` before the first round.
    """
    # the children import this package (``-m basilisk.case_a``, ``from basilisk import side_by_side``)
    path = os.pathsep.join(p for p in (str(BENCHMARKS), os.environ.get("PYTHONPATH", "")) if p)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env["PYTHONPATH"] = path
    env.setdefault("PYTHONPYCACHEPREFIX", str(_BYTECODE_CACHE))
    return env


#: Where the children keep their compiled bytecode (see :func:`_child_env`).
_BYTECODE_CACHE = pathlib.Path(tempfile.gettempdir()) / "fprime-lite-bench-pycache"


def _warm_bytecode() -> None:
    """Compile the sources the children import into their bytecode cache (quietly; a failure only
    leaves the children to compile what they import, as before)."""
    roots = [str(BENCHMARKS / "basilisk")]
    for package in ("fprime_lite", "detumble"):
        spec = importlib.util.find_spec(package)
        if spec is not None and spec.submodule_search_locations:
            roots.extend(spec.submodule_search_locations)
    subprocess.run([sys.executable, "-m", "compileall", "-q", *roots], capture_output=True, check=False,
                   env=_child_env())


def _child(argv: list[str]) -> dict:
    done = subprocess.run(argv, capture_output=True, text=True, check=False, env=_child_env())
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(argv[:3])}…: failed\n{done.stderr[-2000:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def measure_cases(cases, duration_s: float = ORBIT_S, rounds: int = 3, topologies=None, progress=None) -> dict:
    """Fly every kind of every case in ``cases`` ``rounds`` times, all interleaved in each round.

    ``topologies`` maps a case to the deployment it flies (default: the case's own). Returns
    ``{case: figures}``; a case's figures hold its runs, the fastest and the median round of each
    kind, its ratios (fastest rounds, and median rounds) and, for the newer cases, both sides'
    plausibility figures (the first round's).
    """
    topologies = dict(topologies or {})
    plan: dict[str, tuple[str, list[str]]] = {}
    for case in cases:
        if case not in CASES:
            raise ValueError(f"no side-by-side case {case!r}; choose one of {', '.join(CASES)}")
        topology = str(pathlib.Path(topologies.get(case, CASES[case][0])).resolve())
        topologies[case] = topology
        for kind, argv in _kinds(case, topology, duration_s).items():
            plan[kind] = (case, argv)
    runs: dict[str, list[dict]] = {k: [] for k in plan}
    _warm_bytecode()
    for r in range(rounds):
        for kind, (_, argv) in plan.items():
            runs[kind].append(_child(argv))
            if progress is not None:
                progress(f"round {r + 1}/{rounds} {kind}: {runs[kind][-1]['real_time_factor']:.0f}× real time")
    out: dict[str, dict] = {}
    for case in cases:
        mine = {k: v for k, v in runs.items() if plan[k][0] == case}
        best = {k: max(x["real_time_factor"] for x in v) for k, v in mine.items()}
        median = {k: statistics.median(x["real_time_factor"] for x in v) for k, v in mine.items()}
        figures = {"installed": True, "case": case, "topology": topologies[case], "sim_seconds": duration_s,
                   "rounds": rounds, "runs": mine, "best_real_time_factor": best,
                   "median_real_time_factor": median}
        for name, ours, theirs in CASES[case][1]:
            figures[name] = best[ours] / _fastest(best, theirs)
            figures[f"median_{name}"] = median[ours] / _fastest(median, theirs)
        if case != "proves_ref":
            skip = ("sim_seconds", "wall_s", "real_time_factor", "step_s", "control")
            figures["plausibility"] = {k: {f: x for f, x in v[0].items() if f not in skip} for k, v in mine.items()}
        out[case] = figures
    return out


def _fastest(factors: dict[str, float], kinds: str | tuple[str, ...]) -> float:
    """The real-time factor of ``kinds`` (one kind's, or the largest of several)."""
    return factors[kinds] if isinstance(kinds, str) else max(factors[k] for k in kinds)


def _label(kinds: str | tuple[str, ...]) -> str:
    return kinds if isinstance(kinds, str) else "fastest of " + " / ".join(kinds)


def measure(topology, duration_s: float = ORBIT_S, rounds: int = 3, progress=None) -> dict:
    """Fly proves_ref's four kinds ``rounds`` times, interleaved; figures and ratios (see the module doc)."""
    d = measure_cases(["proves_ref"], duration_s, rounds, {"proves_ref": topology}, progress)["proves_ref"]
    runs = d["runs"]
    d["case_a_time_below_1_deg_s"] = {"basilisk": runs["basilisk_20hz"][0]["time_below_1_deg_s"],
                                      "basilisk_lean": runs["basilisk_lean_50hz"][0]["time_below_1_deg_s"],
                                      "fprime_lite": runs["fprime_lite_plant_20hz"][0]["time_below_1_deg_s"]}
    return d


def plausibility_text(figures: dict) -> str:
    """One line of a run's plausibility figures (``name value, ...``)."""
    return ", ".join(f"{k} {v:.4g}" if isinstance(v, float) else f"{k} {v}" for k, v in figures.items())


def case_of(topology) -> str:
    """The side-by-side case of a deployment: the case whose own topology file it is (adcs_ref,
    coursework), else proves_ref (Basilisk's case A against whatever deployment is given)."""
    path = pathlib.Path(topology).resolve()
    for case, (own, _) in CASES.items():
        if path == own.resolve():
            return case
    return "proves_ref"


def piece_rows(d: dict) -> list[tuple[str, str, str]]:
    """The ``fprime-lite bench`` table rows of :func:`piece_figures`' figures."""
    if not d.get("installed"):
        return [("Basilisk side by side", f"not measured: Basilisk is not installed — {INSTALL_HINT}", "")]
    b = d["best_real_time_factor"]
    if d.get("case", "proves_ref") != "proves_ref":
        rows = [(f"{d['case']}, {d['sim_seconds']:.0f} s: {ours} / {_label(theirs)} (real-time factors, "
                 f"best of {d['rounds']})",
                 f"{b[ours]:,.0f} / {_fastest(b, theirs):,.0f} = {d[name]:.2f} "
                 f"(median rounds {d['median_' + name]:.2f})",
                 GOALS.get(name, "context"))
                for name, ours, theirs in CASES[d["case"]][1]]
        for kind, figures in d["plausibility"].items():
            rows.append((f"{kind}: plausibility", plausibility_text(figures), ""))
        return rows
    t = d["case_a_time_below_1_deg_s"]
    fastest = _fastest(b, ("basilisk_50hz", "basilisk_lean_50hz"))
    return [
        (f"50 Hz, {d['sim_seconds']:.0f} s: fprime-lite run (outputs, no plots) / fastest Basilisk case A "
         f"(real-time factors, best of {d['rounds']})",
         f"{b['fprime_lite_run_50hz']:,.0f} / {fastest:,.0f} = {d['run_50hz_over_fastest_basilisk']:.2f} "
         f"(median rounds {d['median_run_50hz_over_fastest_basilisk']:.2f})", GOALS["run_50hz_over_fastest_basilisk"]),
        ("50 Hz Basilisk case A: as first written / lean",
         f"{b['basilisk_50hz']:,.0f} / {b['basilisk_lean_50hz']:,.0f}", ""),
        ("50 Hz: whole deployment without outputs / Basilisk case A, lean",
         f"{b['fprime_lite_deployment_50hz']:,.0f} / {b['basilisk_lean_50hz']:,.0f} = "
         f"{d['deployment_50hz_over_basilisk_lean']:.2f}", "context"),
        ("case A 20 Hz: fprime-lite plant-only / Basilisk",
         f"{b['fprime_lite_plant_20hz']:,.0f} / {b['basilisk_20hz']:,.0f} = {d['plant_20hz_over_basilisk']:.2f} "
         f"(median rounds {d['median_plant_20hz_over_basilisk']:.2f})", "context"),
        ("case A |ω| < 1 °/s at: fprime-lite / Basilisk / Basilisk lean",
         f"{t['fprime_lite']} s / {t['basilisk']} s / {t['basilisk_lean']} s", ""),
    ]


def piece_figures(options: argparse.Namespace) -> dict:
    """What the ``basilisk`` bench piece measures with ``fprime-lite bench``'s options: the case of
    ``options.topology`` (:func:`case_of`), three rounds of ``options.duration`` (default one orbit)."""
    if not basilisk_installed():
        return {"installed": False, "how_to_install": INSTALL_HINT}
    duration = options.duration if options.duration is not None else ORBIT_S
    def progress(line: str) -> None:
        print(line, file=sys.stderr, flush=True)

    case = case_of(options.topology)
    if case != "proves_ref":
        return measure_cases([case], duration, 3, {case: options.topology}, progress)[case]
    return measure(options.topology, duration, progress=progress)

