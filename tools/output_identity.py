#!/usr/bin/env python3
"""Do two revisions of fprime-lite fly the same flights? ("outputs identical", as a command.)

    python tools/output_identity.py [BASE [OTHER]] [--cases NAME,...] [--quick] [--ignore-json-key KEY]
                                    [--keep DIR] [--list]

BASE and OTHER are each a git revision of this repository (``main``, ``HEAD~3``, a hash) or a folder
holding a checkout (a work tree, another clone). The defaults compare ``HEAD`` with the work tree, which
is what to run before a refactoring commit; ``main .`` from a branch's work tree compares the branch's
state with main.

Each side flies the same fixed set of cases with its own ``src/`` (``PYTHONPATH``, the Python that runs
this script), its own deployments and campaign files: the reference deployments through ``fprime-lite
run`` (B-dot detumble, the three attitude modes, magnetorquer pointing with the residual-dipole
estimate, the coursework controllers), the plant-only laws through ``python -m detumble.sim``, and each
deployment's parameter file through ``fprime-lite params``. Then every output file of every case is
compared byte for byte; a file that differs is read again as CSV, JSON or lines to say where (the first
differing row, column or key and both values). The only things left out of the comparison are the
measurements of wall-clock time, which differ between two runs of the same tree: the summaries'
``wall_seconds`` and ``real_time_factor`` (and any key with ``wall`` in it) and the rate groups'
``RgMaxTime`` channel — and the JSON keys named with ``--ignore-json-key``, for what a change adds on
purpose (it is then identical but for those keys).

Exit status: 0 when every file is identical, 1 when one differs or is missing on one side, 2 when a
side could not be set up or a case failed to fly (its output is shown).
"""

from __future__ import annotations

import argparse
import concurrent.futures
import csv
import dataclasses
import filecmp
import io
import json
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

REPO = pathlib.Path(__file__).resolve().parents[1]

#: 10° from the hold campaign's target at 0.04 °/s (tests/test_adcs_plant_only_vs_deployment.py, ADCS-076)
_HOLD_START = ("initial.rate.magnitude_deg_s=0.04", "initial.rate.axis=[0.6, 0.0, 0.8]",
               "initial.attitude.quaternion=[0.9659258262890683, 0.0, 0.25881904510252074, 0.0]")
_HOLD_FORCED = ("control.adcs.POINTING_ACTUATOR=MAGNETORQUERS", "control.adcs.force_mode=POINTING",
                "control.adcs.force_at_s=5.0",
                "control.adcs.target_q_bn=[0.9238795325112867, 0, 0.3826834323650898, 0]")
_SLOW_TUMBLE = ("initial.rate.magnitude_deg_s=1.2",)  # DETUMBLE → SPIN_STABLE at 51 s → POINTING at 334 s


@dataclasses.dataclass(frozen=True)
class Case:
    """One flight (or file) each side produces into its own folder.

    ``kind``: ``run`` (``fprime-lite run TARGET``), ``sim`` (``python -m detumble.sim TARGET``) or
    ``params`` (``fprime-lite params TARGET -o params.dat``). ``target`` is a path inside the checkout
    (a topology) or a packaged scenario name; ``duration_s`` simulated seconds (``quick_s`` with
    ``--quick``); ``settings`` ``--set`` overrides; ``extra`` further arguments, paths inside the checkout.
    """

    name: str
    kind: str
    target: str
    duration_s: float = 0.0
    quick_s: float = 0.0
    settings: tuple[str, ...] = ()
    extra: tuple[str, ...] = ()


CASES = (
    Case("proves_ref", "run", "deployments/proves_ref/topology.yaml", 600, 30),
    Case("proves_ref_bdot", "run", "deployments/proves_ref/topology_bdot_detumble.yaml", 300, 30),
    Case("adcs_ref_detumble", "run", "deployments/adcs_ref/topology.yaml", 300, 30),
    Case("adcs_ref_modes", "run", "deployments/adcs_ref/topology.yaml", 500, 60, _SLOW_TUMBLE),
    Case("adcs_ref_magnetorquer_hold", "run", "deployments/adcs_ref/topology.yaml", 700, 30, _HOLD_START,
         ("--seq", "campaigns/adcs/pointing_magnetorquers.seq")),
    Case("coursework", "run", "deployments/coursework/topology.yaml", 120, 20),
    Case("coursework_cross_product", "run", "deployments/coursework/topology.yaml", 300, 20, (),
         ("--seq", "deployments/coursework/cross_product.seq")),
    Case("coursework_beta_pd", "run", "deployments/coursework/topology.yaml", 300, 20, (),
         ("--seq", "deployments/coursework/beta_pd.seq")),
    Case("sim_adcs_modes", "sim", "adcs", 500, 60, _SLOW_TUMBLE, ("--law", "adcs")),
    Case("sim_adcs_magnetorquer_hold", "sim", "adcs", 700, 30, (*_HOLD_START, *_HOLD_FORCED), ("--law", "adcs")),
    Case("sim_kopt", "sim", "default", 600, 30, (), ("--law", "kopt")),
    Case("sim_bdot", "sim", "case_a", 600, 30, (), ("--law", "bdot")),
    Case("sim_cross_product", "sim", "surrey", 600, 30, (), ("--law", "cross_product", "--gain", "500")),
    Case("sim_beta_pd", "sim", "surrey", 300, 30, (), ("--law", "beta_pd")),
    Case("sim_wheels_pd", "sim", "surrey", 120, 20, (), ("--law", "wheels_pd")),
    Case("params_proves_ref", "params", "deployments/proves_ref/topology.yaml"),
    Case("params_adcs_ref", "params", "deployments/adcs_ref/topology.yaml"),
    Case("params_coursework", "params", "deployments/coursework/topology.yaml"),
)

#: Channels and summary keys that measure wall-clock time, not the flight.
WALL_CHANNEL_SUFFIXES = (".RgMaxTime",)
WALL_KEYS = ("real_time_factor",)

_CLI = "import sys; from fprime_lite.tools.cli import main; sys.exit(main(sys.argv[1:]))"


class SetupError(Exception):
    """A side that cannot be checked out or a case that does not fly."""


#: What a flight reads of a checkout; a folder side is copied so that both sides fly from folders of the same
#: length (a path in an event is cut at the string's declared size, so it must be cut at the same place).
CHECKOUT_PARTS = ("src", "deployments", "campaigns", "examples")


def _checkout(spec: str, scratch: pathlib.Path, label: str) -> pathlib.Path:
    """``scratch/label``, holding the checkout ``spec`` names: a folder's flight inputs copied, or the git
    revision exported."""
    target = scratch / label
    shutil.rmtree(target, ignore_errors=True)
    folder = pathlib.Path(spec)
    if folder.is_dir():
        if not (folder / "src" / "fprime_lite").is_dir():
            raise SetupError(f"{spec}: a folder, but not a checkout of fprime-lite (no src/fprime_lite)")
        ignore = shutil.ignore_patterns("__pycache__", "*.pyc", "*.so", ".venv", "runs")
        for part in CHECKOUT_PARTS:
            if (folder / part).is_dir():
                shutil.copytree(folder / part, target / part, ignore=ignore)
        return target
    found = subprocess.run(["git", "-C", str(REPO), "rev-parse", "--verify", "--quiet", f"{spec}^{{commit}}"],
                           capture_output=True, text=True, check=False)
    if found.returncode:
        raise SetupError(f"{spec}: neither a folder nor a git revision of {REPO}")
    commit = found.stdout.strip()
    target.mkdir(parents=True)
    archive = subprocess.run(["git", "-C", str(REPO), "archive", "--format=tar", commit, "--", *CHECKOUT_PARTS],
                             capture_output=True, check=False)
    if archive.returncode:
        raise SetupError(f"{spec}: git archive failed: {archive.stderr.decode(errors='replace')}")
    subprocess.run(["tar", "-x", "-C", str(target)], input=archive.stdout, check=True)
    return target


def _command(case: Case, tree: pathlib.Path, out: pathlib.Path, quick: bool) -> list[str]:
    duration = str(case.quick_s if quick and case.quick_s else case.duration_s)
    extra = list(case.extra)  # paths relative to the checkout, which is the flight's working folder
    sets = [f"--set={s}" for s in case.settings]
    if case.kind == "run":
        return [sys.executable, "-c", _CLI, "run", case.target, "--duration", duration, "--no-plots",
                "--no-progress", "--allow-warnings", "--out", str(out), *sets, *extra]
    if case.kind == "sim":
        return [sys.executable, "-m", "detumble.sim", case.target, "--duration", duration, "--out", str(out), *sets,
                *extra]
    if case.kind == "params":
        out.mkdir(parents=True, exist_ok=True)
        return [sys.executable, "-c", _CLI, "params", case.target, "-o", str(out / "params.dat")]
    raise ValueError(f"case {case.name}: unknown kind {case.kind!r}")


def _fly(case: Case, tree: pathlib.Path, out: pathlib.Path, quick: bool) -> None:
    env = dict(os.environ, PYTHONPATH=str(tree / "src"), MPLBACKEND="Agg")
    done = subprocess.run(_command(case, tree, out, quick), cwd=str(tree), env=env, capture_output=True,
                          text=True, check=False)
    if done.returncode not in (0,):
        raise SetupError(f"case {case.name} failed with {tree} (exit {done.returncode}):\n"
                         f"{(done.stdout + done.stderr)[-3000:]}")


def _is_wall_key(key: str) -> bool:
    return "wall" in key or key in WALL_KEYS


def _strip_wall(value, ignored: frozenset[str] = frozenset()):
    """``value`` without its wall-clock keys and the ``ignored`` ones, at any depth."""
    if isinstance(value, dict):
        return {k: _strip_wall(v, ignored) for k, v in value.items() if not _is_wall_key(k) and k not in ignored}
    if isinstance(value, list):
        return [_strip_wall(v, ignored) for v in value]
    return value


def _first_json_difference(a, b, path: str = "") -> str | None:
    if isinstance(a, dict) and isinstance(b, dict):
        for key in sorted(a.keys() | b.keys()):
            if key not in a or key not in b:
                return f"key {path}{key} only in {'OTHER' if key in b else 'BASE'}"
            found = _first_json_difference(a[key], b[key], f"{path}{key}.")
            if found:
                return found
        return None
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return f"{path.rstrip('.')}: {len(a)} items against {len(b)}"
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            found = _first_json_difference(x, y, f"{path}{i}.")
            if found:
                return found
        return None
    return None if a == b else f"{path.rstrip('.')}: {a!r} against {b!r}"


def _csv_rows(text: str) -> list[tuple[int, list[str]]]:
    """``(line number, fields)`` of a CSV file without its wall-clock channels: their rows in channels.csv
    (one row per channel write), their columns in the wide tables."""
    rows = list(enumerate(csv.reader(io.StringIO(text)), start=1))
    if not rows:
        return rows
    header = rows[0][1]
    if len(header) >= 3 and header[1] == "channel":
        return [rows[0]] + [(n, r) for n, r in rows[1:] if not (len(r) > 1 and r[1].endswith(WALL_CHANNEL_SUFFIXES))]
    keep = [i for i, name in enumerate(header) if not name.rsplit("[", 1)[0].strip().endswith(WALL_CHANNEL_SUFFIXES)]
    if len(keep) == len(header):
        return rows
    return [(n, [r[i] if i < len(r) else "" for i in keep]) for n, r in rows]


def _first_csv_difference(a: list[tuple[int, list[str]]], b: list[tuple[int, list[str]]]) -> str | None:
    if a and b and a[0][1] != b[0][1]:
        only_a = [c for c in a[0][1] if c not in b[0][1]]
        only_b = [c for c in b[0][1] if c not in a[0][1]]
        return f"header differs (only in BASE: {only_a[:5]}, only in OTHER: {only_b[:5]}, or in another order)"
    header = a[0][1] if a else []
    for (n, x), (_, y) in zip(a, b, strict=False):
        if x != y:
            for i, (u, v) in enumerate(zip(x, y, strict=False)):
                if u != v:
                    column = header[i] if i < len(header) else f"column {i + 1}"
                    return f"line {n}, {column}: {u!r} against {v!r}"
            return f"line {n}: {len(x)} fields against {len(y)}"
    if len(a) != len(b):
        return f"{len(a)} rows against {len(b)}"
    return None


def _text(path: pathlib.Path, root: pathlib.Path | None) -> str:
    """The file's text with its checkout's folder written ``<checkout>`` (events name the sequence files
    they load by their path)."""
    text = path.read_text()
    return text.replace(str(root), "<checkout>") if root is not None else text


def compare_file(base: pathlib.Path, other: pathlib.Path, roots: tuple[pathlib.Path, pathlib.Path] | None = None,
                 ignored_keys: frozenset[str] = frozenset()) -> str | None:
    """None when the two files fly the same (identical, or identical but for wall-clock measurements, the
    folders of the two checkouts, ``roots``, and JSON keys named in ``ignored_keys``); otherwise where they
    first differ."""
    if filecmp.cmp(base, other, shallow=False):
        return None
    root_a, root_b = roots if roots is not None else (None, None)
    try:
        ta, tb = _text(base, root_a), _text(other, root_b)
    except UnicodeDecodeError:
        return f"binary files differ ({base.stat().st_size} and {other.stat().st_size} bytes)"
    if ta == tb:
        return None
    if base.suffix == ".json":
        try:
            a, b = json.loads(ta), json.loads(tb)
        except ValueError as exc:
            return f"not JSON on one side: {exc}"
        return _first_json_difference(_strip_wall(a, ignored_keys), _strip_wall(b, ignored_keys))
    if base.suffix == ".csv":
        return _first_csv_difference(_csv_rows(ta), _csv_rows(tb))
    la, lb = ta.splitlines(), tb.splitlines()
    for n, (x, y) in enumerate(zip(la, lb, strict=False)):
        if x != y:
            return f"line {n + 1}: {x[:160]!r} against {y[:160]!r}"
    return f"{len(la)} lines against {len(lb)}"


def compare_cases(base_out: pathlib.Path, other_out: pathlib.Path, cases,
                  roots: tuple[pathlib.Path, pathlib.Path] | None = None,
                  ignored_keys: frozenset[str] = frozenset()) -> list[tuple[str, str, str | None]]:
    """``(case, file, difference or None)`` for every output file of every case on either side (``roots``: the
    two checkouts' folders, which the outputs may name)."""
    rows: list[tuple[str, str, str | None]] = []
    for case in cases:
        a, b = base_out / case.name, other_out / case.name
        files = sorted({p.relative_to(a).as_posix() for p in a.rglob("*") if p.is_file()}
                       | {p.relative_to(b).as_posix() for p in b.rglob("*") if p.is_file()})
        if not files:
            rows.append((case.name, "(no output)", "neither side wrote anything"))
        for rel in files:
            if not (a / rel).is_file() or not (b / rel).is_file():
                rows.append((case.name, rel, f"only in {'BASE' if (a / rel).is_file() else 'OTHER'}"))
            else:
                rows.append((case.name, rel, compare_file(a / rel, b / rel, roots, ignored_keys)))
    return rows


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="output_identity", description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("base", nargs="?", default="HEAD", help="git revision or checkout folder (default HEAD)")
    parser.add_argument("other", nargs="?", default=str(REPO),
                        help="git revision or checkout folder (default: this work tree)")
    parser.add_argument("--cases", help="comma-separated case names (default: all; --list shows them)")
    parser.add_argument("--quick", action="store_true", help="fly each case for a few tens of seconds only")
    parser.add_argument("--keep", type=pathlib.Path, help="keep the checkouts and outputs in this folder")
    parser.add_argument("--list", action="store_true", help="list the cases and exit")
    parser.add_argument("--ignore-json-key", action="append", default=[], metavar="KEY",
                        help="leave JSON keys named KEY out of the comparison, at any depth (repeatable): what a "
                             "change adds on purpose, e.g. the parameters' 'annotation' when units are declared")
    parser.add_argument("-j", "--jobs", type=int, default=min(2, os.cpu_count() or 1), help="flights at once")
    args = parser.parse_args(argv)
    if args.list:
        for c in CASES:
            print(f"{c.name:28s} {c.kind:6s} {c.target} {c.duration_s:g} s (quick {c.quick_s:g} s) "
                  f"{' '.join((*c.settings, *c.extra))}")
        return 0
    cases = list(CASES)
    if args.cases:
        names = [n.strip() for n in args.cases.split(",") if n.strip()]
        unknown = [n for n in names if n not in {c.name for c in CASES}]
        if unknown:
            print(f"output_identity: unknown case(s) {', '.join(unknown)}; --list shows them", file=sys.stderr)
            return 2
        cases = [c for c in CASES if c.name in names]
    scratch = pathlib.Path(tempfile.mkdtemp(prefix="output-identity-")) if args.keep is None else args.keep
    scratch.mkdir(parents=True, exist_ok=True)
    try:
        try:
            trees = {"base": _checkout(args.base, scratch, "base"), "other": _checkout(args.other, scratch, "othr")}
            outs = {side: scratch / f"{side}-out" for side in trees}  # outputs beside, not inside, the trees
            for o in outs.values():
                shutil.rmtree(o, ignore_errors=True)
            with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
                jobs = [pool.submit(_fly, c, trees[s], outs[s] / c.name, args.quick) for c in cases for s in trees]
                for job in jobs:
                    job.result()
        except SetupError as exc:
            print(f"output_identity: {exc}", file=sys.stderr)
            return 2
        rows = compare_cases(outs["base"], outs["other"], cases, (trees["base"], trees["other"]),
                             frozenset(args.ignore_json_key))
    finally:
        if args.keep is None:
            shutil.rmtree(scratch, ignore_errors=True)
    print(f"BASE  {args.base}\nOTHER {args.other}{'  (quick)' if args.quick else ''}")
    width = max(len(f"{c}/{f}") for c, f, _ in rows)
    for case, rel, diff in rows:
        print(f"{case + '/' + rel:{width}s}  {'identical' if diff is None else 'DIFFERS: ' + diff}")
    differing = [r for r in rows if r[2] is not None]
    print(f"{len(rows) - len(differing)} of {len(rows)} files identical"
          + (f"; {len(differing)} differ" if differing else ""))
    return 1 if differing else 0


if __name__ == "__main__":
    sys.exit(main())
