"""Compile a copy of the unchanged framework and flight software with mypyc, check it flies the same
flight, and time it against the pure-Python tree (issue #19; measured, not adopted: docs/performance.md
"Compiling the framework with mypyc").

    python benchmarks/bench_mypyc_build.py build    [--out DIR] [--tiers framework,flight,sitl] [--exclude MOD,...]
    python benchmarks/bench_mypyc_build.py identity [--out DIR] [--duration S] [--topology FILE]
    python benchmarks/bench_mypyc_build.py measure  [--out DIR ...] [--deployments adcs_ref,proves_ref]
                                                    [--duration S] [--rounds N]

``build`` copies ``src/`` to ``DIR/src`` (default ``/tmp/fprime-lite-mypyc``) and compiles the chosen
tiers' modules there with mypyc (``mypycify`` + ``build_ext --inplace``, the C compiler Python was built
with, ``-ffp-contract=off`` so that no multiply-add is fused). Nothing in the repository is written.
A module mypyc refuses is left interpreted and the build is tried again without it; then every compiled
module is imported in a child process, and one that fails to import is left out too. What was
compiled and what was left out (with mypyc's or the import's first error) is written to
``DIR/build.json``.

``identity`` flies the deployment (default adcs_ref, 400 s) with the pure tree and with ``DIR/src``
first on ``PYTHONPATH`` and compares every output file byte for byte (a second pure run tells which
files differ between any two runs: wall-clock times in summary.json).

``measure`` times the per-tick CPU of the deployments with each tree (pure, then every ``--out``),
tree after tree, round after round, with the child of ``bench_tick_ab.py`` (thread CPU time, the
fastest of four pieces, the plant-only counterpart timed beside it). Timings are never asserted.
"""

from __future__ import annotations

import argparse
import csv
import filecmp
import io
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import time
import tomllib

ROOT = pathlib.Path(__file__).resolve().parents[1]
DEFAULT_OUT = pathlib.Path("/tmp/fprime-lite-mypyc")

#: tier -> module globs under src/. framework: the F´ model, the services and the scheduler the tick
#: goes through; flight: the flight components and the control laws; sitl: the simulated drivers, the
#: spacecraft and the Python side of the plant (not asked for by #19's question, measured as a bound).
TIERS = {
    "framework": ["fprime_lite/model/*.py", "fprime_lite/svc/*.py", "fprime_lite/deploy/scheduler.py",
                  "fprime_lite/deploy/deployment.py", "fprime_lite/deploy/topology.py"],
    "flight": ["detumble/components/*.py", "detumble/control/*.py"],
    "sitl": ["detumble/proves/imu_manager.py", "detumble/proves/ina219_manager.py", "detumble/proves/load_switch.py",
             "detumble/drivers/magnetorquer_driver.py", "detumble/proves/mode_manager.py",
             "detumble/proves/power_monitor.py", "detumble/drivers/reaction_wheel_driver.py",
             "detumble/proves/reset_manager.py", "detumble/proves/rtc_manager.py", "detumble/drivers/spacecraft.py",
             "detumble/drivers/star_tracker.py", "detumble/proves/startup_manager.py",
             "detumble/drivers/torque_rod_driver.py", "detumble/proves/watchdog.py", "detumble/drivers/ports.py",
             "detumble/sim/plant.py", "detumble/sim/sensors.py", "detumble/sim/coils.py", "detumble/sim/wheels.py",
             "detumble/sim/power.py", "detumble/sim/star_tracker.py", "detumble/sim/accelerometer.py",
             "detumble/sim/attitude.py", "detumble/sim/orbit.py", "detumble/sim/field.py", "detumble/sim/vec.py",
             "detumble/sim/torques.py", "detumble/sim/frames.py", "detumble/sim/sun.py",
             "detumble/sim/truth.py", "detumble/sim/readback.py", "detumble/sim/adcs_law.py",
             "detumble/sim/laws.py"],
}

#: modules mypyc compiles and that import, but that break the flight at run time: left interpreted by
#: default (found by flying adcs_ref with the compiled copy; ``--keep-runtime-breaks`` compiles them anyway)
RUNTIME_BREAKS = {
    "fprime_lite.model.queues": "`self.on_put = None` unannotated: mypyc infers the attribute's type as None and "
                                "refuses the scheduler's functools.partial (TypeError at Deployment.start)",
    "fprime_lite.svc.file_root": "FileRoot becomes a native class; the interpreted FileUplink/FileDownlink/"
                                 "FileManager subclass it (interpreted classes cannot inherit from compiled)",
    "detumble.control.strategy_selector": "the method alias `select = from_angular_velocity_magnitude` in the "
                                          "class body: SystemError (KeyError) when StrategySelector() is built",
    "detumble.sim.sensors": "`sample_gauss = property(_held_gauss, ...)` in the class body: SystemError (KeyError "
                            "'_held_gauss') when the magnetometer is built",
    "detumble.control.coursework": "segmentation fault in WheelsPd.__init__ (assigning its `inertia`/`target` "
                                   "properties there); the coursework deployment crashes when its parameters load",
    "detumble.sim.wheels": "a behaviour change: compiled, WheelAssembly.set_torque takes True/False/1.0 as a wheel "
                           "index instead of refusing them (WHL-102); WheelAssembly is not deep-copyable either",
    "detumble.sim.laws": "the runner sets `law.limit = clip_to_limits` on a law object; a native class takes no "
                         "undeclared attribute (AttributeError for clip saturation, the surrey scenario)",
    "detumble.sim.coils": "CoilSpec becomes a native dataclass without __dict__; scenario.py merges "
                          "`CoilSpec(**{**base.__dict__, **kw})`",
}

_SETUP = """
import sys
from setuptools import setup
from mypyc.build import mypycify
paths = sys.argv.pop(1).split(",")
setup(name="fprime_lite_mypyc", ext_modules=mypycify(paths, opt_level="3", multi_file=True))
"""

#: mypyc's errors, and its internal errors (an assertion with the line it was compiling)
_ERROR = re.compile(r"^(?P<path>[\w/]+\.py):(?P<line>\d+): (?:error: )?(?P<msg>(?:\w+Error: )?.*)$", re.M)


def _module(path: str) -> str:
    return path[:-3].replace("/", ".").removesuffix(".__init__")


def _copy_src(out: pathlib.Path) -> pathlib.Path:
    dest = out / "src"
    if dest.exists():
        shutil.rmtree(dest)
    shutil.copytree(ROOT / "src", dest, ignore=shutil.ignore_patterns("__pycache__", "*.so", "build", "*.egg-info"))
    link = out / "deployments"  # what code that finds the reference deployments beside src/ looks for
    if not link.exists():
        link.symlink_to(ROOT / "deployments", target_is_directory=True)
    return dest


def _mypy_ini() -> str:
    """The repository's ``[tool.mypy]`` settings as a mypy.ini for the copy (mypyc reads its cwd's)."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["mypy"]
    lines = ["[mypy]"]
    for key, value in config.items():
        if key == "overrides":
            continue
        if key == "mypy_path":
            value = "."
        lines.append(f"{key} = {str(value).lower() if isinstance(value, bool) else value}")
    for override in config.get("overrides", []):
        lines.append(f"[mypy-{','.join(override['module'])}]")
        lines += [f"{k} = {str(v).lower() if isinstance(v, bool) else v}" for k, v in override.items() if k != "module"]
    return "\n".join(lines) + "\n"


def _mypyc(src: pathlib.Path, paths: list[str]) -> subprocess.CompletedProcess[str]:
    (src / "setup_mypyc.py").write_text(_SETUP)
    (src / "mypy.ini").write_text(_mypy_ini())
    env = dict(os.environ, CFLAGS="-ffp-contract=off", MYPY_FORCE_COLOR="0")
    return subprocess.run([sys.executable, "setup_mypyc.py", ",".join(paths), "build_ext", "--inplace", "-j", "2"],
                          cwd=src, env=env, capture_output=True, text=True, check=False)


def _import_failures(src: pathlib.Path, modules: list[str]) -> dict[str, str]:
    """Each compiled module that fails to import, blamed on the innermost compiled module of the traceback
    (a module that only imports a broken one is not blamed), with the first line of the error."""
    probe = ("import importlib, json, sys, traceback\nbad = {}\nfor m in sys.argv[1:]:\n"
             "    try:\n        mod = importlib.import_module(m)\n"
             "        assert not mod.__file__.endswith('.py'), 'imported the .py, not the extension'\n"
             "    except BaseException as e:\n"
             "        files = [f.filename for f in traceback.extract_tb(e.__traceback__)]\n"
             "        bad[m] = [files, f'{type(e).__name__}: {e}'.splitlines()[0][:200]]\n"
             "print(json.dumps(bad))")
    done = subprocess.run([sys.executable, "-c", probe, *modules], env=dict(os.environ, PYTHONPATH=str(src)),
                          capture_output=True, text=True, check=False)
    if done.returncode:
        raise SystemExit(f"bench_mypyc_build: the import probe failed:\n{done.stderr[-2000:]}")
    by_file = {}  # a compiled module's frames name its path as mypyc was given it: relative to src
    for m in modules:
        rel = m.replace(".", "/") + ".py"
        by_file[rel] = by_file[str(src / rel)] = m
    blamed: dict[str, str] = {}
    for m, (files, error) in json.loads(done.stdout.strip().splitlines()[-1]).items():
        culprit = next((by_file[f] for f in reversed(files) if f in by_file), m)
        blamed.setdefault(culprit, error)
    return blamed


def _clean_build(src: pathlib.Path) -> None:
    for so in src.rglob("*.so"):
        if so.name != "_plant_kernel.so":
            so.unlink()
    shutil.rmtree(src / "build", ignore_errors=True)


def build(out: pathlib.Path, tiers: list[str], exclude: set[str], keep_runtime_breaks: bool = False) -> dict:
    src = _copy_src(out)
    chosen: list[str] = []
    for tier in tiers:
        for pattern in TIERS[tier]:
            for p in sorted(src.glob(pattern)):
                rel = p.relative_to(src).as_posix()
                if p.name != "__init__.py" and rel not in chosen:
                    chosen.append(rel)
    left_out = {p: "excluded on the command line" for p in chosen if _module(p) in exclude}
    if not keep_runtime_breaks:
        left_out.update({p: "run time: " + RUNTIME_BREAKS[_module(p)] for p in chosen if _module(p) in RUNTIME_BREAKS})
    t0 = time.monotonic()
    attempts = 0
    while True:
        paths = [p for p in chosen if p not in left_out]
        attempts += 1
        print(f"bench_mypyc_build: mypyc on {len(paths)} modules (attempt {attempts})", file=sys.stderr)
        done = _mypyc(src, paths)
        if done.returncode == 0:
            bad = _import_failures(src, [_module(p) for p in paths])
            if not bad:
                break
            for p in paths:
                if _module(p) in bad:
                    left_out[p] = "import: " + bad[_module(p)]
            _clean_build(src)
            continue
        errors: dict[str, str] = {}
        for m in _ERROR.finditer(done.stdout + done.stderr):
            if m["path"] in paths and not m["msg"].startswith(("note:", "warning:")):
                errors.setdefault(m["path"], f"line {m['line']}: {m['msg']}")
        if not errors:
            raise SystemExit(f"bench_mypyc_build: the build failed without a module to blame:\n"
                             f"{(done.stdout + done.stderr)[-4000:]}")
        left_out.update(errors)
        _clean_build(src)
    report = {"tiers": tiers, "src": str(src), "compiled": [_module(p) for p in paths],
              "left_out": {_module(p): why for p, why in left_out.items()},
              "attempts": attempts, "build_s": round(time.monotonic() - t0, 1)}
    (out / "build.json").write_text(json.dumps(report, indent=2) + "\n")
    return report


_RUN = ("import sys\nfrom fprime_lite.tools.cli import main\nsys.exit(main(sys.argv[1:]))")


def _fly(src: pathlib.Path, topology: str, duration: float, dest: pathlib.Path) -> None:
    done = subprocess.run([sys.executable, "-c", _RUN, "run", topology, "--duration", str(duration), "--no-plots",
                           "--no-progress", "--allow-warnings", "--out", str(dest)],
                          env=dict(os.environ, PYTHONPATH=str(src)), capture_output=True, text=True, check=False)
    if done.returncode:
        raise SystemExit(f"bench_mypyc_build: the run with {src} failed:\n{done.stderr[-3000:]}")


def _fields(path: pathlib.Path) -> dict[str, list[str]]:
    """A run's output as named fields: a long CSV (time,channel,value) by channel, a wide CSV by column,
    a JSON object by top-level key, anything else as one field of lines."""
    text = path.read_text(errors="replace")
    if path.suffix == ".csv":
        rows = list(csv.reader(io.StringIO(text)))
        header, body = rows[0], rows[1:]
        if header[:2] == ["time", "channel"]:
            by_channel: dict[str, list[str]] = {}
            for row in body:
                by_channel.setdefault(row[1], []).append(",".join(row))
            return by_channel
        return {name: [row[i] if i < len(row) else "" for row in body] for i, name in enumerate(header)}
    if path.suffix == ".json":
        data = json.loads(text)
        if isinstance(data, dict):
            return {k: [json.dumps(v, sort_keys=True)] for k, v in data.items()}
    return {"": text.splitlines()}


def identity(out: pathlib.Path, topology: str, duration: float) -> dict[str, str]:
    """Per output file: identical, identical but for the fields that also differ between two pure runs
    (wall-clock times), or where it differs."""
    runs = out / "identity"
    shutil.rmtree(runs, ignore_errors=True)
    for name, src in (("pure", ROOT / "src"), ("pure2", ROOT / "src"), ("compiled", out / "src")):
        _fly(src, topology, duration, runs / name)
    result: dict[str, str] = {}
    for path in sorted(p for p in (runs / "pure").rglob("*") if p.is_file()):
        rel = path.relative_to(runs / "pure").as_posix()
        other = runs / "compiled" / rel
        if not other.is_file():
            result[rel] = "MISSING from the compiled run"
        elif filecmp.cmp(path, other, shallow=False):
            result[rel] = "byte-identical"
        else:
            a, b, c = _fields(path), _fields(runs / "pure2" / rel), _fields(other)
            noisy = {k for k in a.keys() | b.keys() if a.get(k) != b.get(k)}
            bad = sorted(k for k in a.keys() | c.keys() if k not in noisy and a.get(k) != c.get(k))
            result[rel] = (f"DIFFERS in {', '.join(bad[:8])}" if bad else
                           f"identical but for {', '.join(sorted(noisy))} (differ between two pure runs too)")
    return result


def measure(outs: list[pathlib.Path], deployments: list[str], duration: float, rounds: int) -> dict:
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_tick_ab import _CHILD, DEPLOYMENTS  # the child of the A/B bench, reused
    trees = {"pure": ROOT / "src", **{o.name: o / "src" for o in outs}}
    best: dict[str, dict[str, list[float]]] = {}
    for _ in range(rounds):
        for name in deployments:
            law, group, tick_s = DEPLOYMENTS[name]
            topology = ROOT / "deployments" / name / "topology.yaml"
            for label, src in trees.items():
                done = subprocess.run(
                    [sys.executable, "-c", _CHILD, str(topology), str(duration), law, group, str(tick_s)],
                    env=dict(os.environ, PYTHONPATH=str(src)), capture_output=True, text=True, check=False)
                if done.returncode:
                    raise SystemExit(f"bench_mypyc_build: {name} with {label} failed:\n{done.stderr[-2000:]}")
                figures = json.loads(done.stdout.strip().splitlines()[-1])
                mins = best.setdefault(name, {}).setdefault(label, [float("inf"), float("inf")])
                mins[0] = min(mins[0], figures["deployment_us"])
                mins[1] = min(mins[1], figures["plant_only_us"])
                print(f"  {name:10s} {label:24s} {figures['deployment_us']:6.1f} / {figures['plant_only_us']:6.1f}",
                      file=sys.stderr)
    for name, per_tree in best.items():
        pure_dep = per_tree["pure"][0]
        for label, (dep, plant) in per_tree.items():
            print(f"{name:11s} {label:24s} deployment {dep:6.1f} µs / plant-only ({DEPLOYMENTS[name][0]}) "
                  f"{plant:6.1f} µs a tick "
                  f"= {dep / plant:.2f}; pure/this {pure_dep / dep:.2f}x")
    return best


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="verb", required=True)
    b = sub.add_parser("build", help="copy src/ and compile the tiers' modules with mypyc")
    b.add_argument("--out", type=pathlib.Path, default=DEFAULT_OUT)
    b.add_argument("--tiers", default="framework,flight", help="comma-separated, from " + ", ".join(TIERS))
    b.add_argument("--exclude", default="", help="comma-separated module names to leave interpreted")
    b.add_argument("--keep-runtime-breaks", action="store_true", help="compile RUNTIME_BREAKS' modules too")
    i = sub.add_parser("identity", help="fly the deployment pure and compiled, compare the outputs")
    i.add_argument("--out", type=pathlib.Path, default=DEFAULT_OUT)
    i.add_argument("--topology", default=str(ROOT / "deployments" / "adcs_ref" / "topology.yaml"))
    i.add_argument("--duration", type=float, default=400.0)
    m = sub.add_parser("measure", help="per-tick CPU, pure tree and compiled trees interleaved")
    m.add_argument("--out", type=pathlib.Path, action="append", help="a built folder (repeatable)")
    m.add_argument("--deployments", default="adcs_ref,proves_ref")
    m.add_argument("--duration", type=float, default=300.0)
    m.add_argument("--rounds", type=int, default=3)
    m.add_argument("--json", type=pathlib.Path)
    args = parser.parse_args(argv)
    if args.verb == "build":
        tiers = [t for t in args.tiers.split(",") if t]
        unknown = [t for t in tiers if t not in TIERS]
        if unknown:
            parser.error(f"unknown tier(s) {', '.join(unknown)}")
        report = build(args.out, tiers, {m for m in args.exclude.split(",") if m}, args.keep_runtime_breaks)
        print(json.dumps(report, indent=2))
    elif args.verb == "identity":
        for f, verdict in identity(args.out, args.topology, args.duration).items():
            print(f"{f:24s} {verdict}")
    else:
        best = measure(args.out or [DEFAULT_OUT], [d for d in args.deployments.split(",") if d], args.duration,
                       args.rounds)
        if args.json:
            args.json.write_text(json.dumps(best, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
