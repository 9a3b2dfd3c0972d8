"""The ``fprime-lite`` command line.

    fprime-lite run [TOPOLOGY]          fly a deployment (default ./topology.yaml)
    fprime-lite dict [TOPOLOGY] -o F    write the F´ JSON dictionary
    fprime-lite check [TOPOLOGY]        validate a topology
    fprime-lite graph [TOPOLOGY]        print the topology as DOT or Mermaid
    fprime-lite params [TOPOLOGY] -o F  write a parameter file holding every parameter's default
                                        (--list: print them with their ids, types and units)
    fprime-lite plot RUN_DIR            draw the plots of a finished run again
    fprime-lite new component|deployment NAME   write a skeleton that passes its own test
    fprime-lite bench                   measure speed and memory
    fprime-lite campaign FILE           run a gain sweep / Monte Carlo on Dask (docs/campaigns.md)
    fprime-lite conformance TESTS_DIR   run an fprime-gds integration suite against the flying deployment

Applications add verbs of their own through the ``fprime_lite.verbs`` entry points
(:mod:`fprime_lite.tools.plugins`); the detumble application adds ``sim``.

User mistakes (a missing file, bad YAML, an unknown scenario) are reported on stderr with a non-zero
exit status, never with a traceback.
"""

from __future__ import annotations

import argparse
import json
import logging
import math
import os
import pathlib
import sys
import threading

from fprime_lite.model.errors import FprimeLiteError, FwAssertionError

__all__ = ["main"]

EXIT_USAGE = 2
EXIT_FAILED = 1


class UserError(FprimeLiteError):
    """A mistake the user can fix; printed without a traceback."""


def _topology_arg(p: argparse.ArgumentParser) -> None:
    p.add_argument("topology", nargs="?", default="topology.yaml",
                   help="topology YAML file (default: ./topology.yaml)")


def _model_arg(p: argparse.ArgumentParser) -> None:
    p.add_argument("topology", nargs="*", default=["topology.yaml"], metavar="MODEL",
                   help="topology YAML file (default: ./topology.yaml), or FPP files of one topology and its "
                   "components (docs/fpp.md)")
    p.add_argument("-i", "--imports", default="", metavar="FILE,FILE",
                   help="FPP files that only resolve references, as fpp-to-dict -i")
    p.add_argument("--no-framework-fpp", action="store_true",
                   help="FPP only: leave out fprime-lite's framework definitions (give your F´ checkout's "
                   "FPP files with -i instead)")


def _load_model(args):
    """The FPP model (:class:`~fprime_lite.deploy.fpp.loader.FppModel`) the verb's files name, or the
    YAML deployment; ``args.topology`` is left as one string for the messages."""
    paths = list(args.topology)
    fpp_files = [p for p in paths if p.endswith(".fpp")]
    imports = [p for p in args.imports.split(",") if p]
    if fpp_files or imports:
        from fprime_lite.deploy.fpp.loader import check_components, load_fpp

        if len(fpp_files) != len(paths):
            raise UserError(f"{' '.join(paths)}: give either FPP files or one topology YAML, not both")
        args.topology = " ".join(paths)
        framework = not args.no_framework_fpp
        if args.command == "check" and not _defines_topology(fpp_files):
            return check_components(fpp_files, imports=imports, framework=framework), None
        return load_fpp(fpp_files, imports=imports, framework=framework), None
    if len(paths) != 1:
        raise UserError(f"{' '.join(paths)}: give one topology YAML (several files are FPP files only)")
    args.topology = paths[0]
    loaded = _load(args.topology)
    return loaded.topology, loaded


def _defines_topology(paths: list[str]) -> bool:
    """Whether one of the FPP files defines a topology (else ``check`` binds its components alone)."""
    import re

    pattern = re.compile(r"^\s*topology\s+\$?\w+\s*\{", re.MULTILINE)
    return any(pattern.search(pathlib.Path(p).read_text(encoding="utf-8", errors="replace"))
               for p in paths if pathlib.Path(p).is_file())


def _parse(parser: argparse.ArgumentParser, argv) -> argparse.Namespace:
    """``parser.parse_args(argv)``, with a did-you-mean for a misspelt option of the chosen verb
    (``--duraton`` → ``--duration``)."""
    from fprime_lite.model.errors import closest

    parsed, extras = parser.parse_known_args(argv)
    if not extras:
        return parsed
    verbs = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    chosen = verbs[0].choices.get(str(parsed.command)) if verbs else None
    options = [o for a in (chosen or parser)._actions for o in a.option_strings]
    hints = []
    for token in extras:
        name = token.split("=", 1)[0]
        guess = closest(name, options) if name.startswith("--") else None
        if guess is not None:
            hints.append(guess if len(extras) == 1 else f"{guess} for {name}")
    hint = f" — did you mean {', '.join(hints)}?" if hints else ""
    (chosen or parser).error(f"unrecognized arguments: {' '.join(extras)}{hint}")
    raise AssertionError("argparse's error() exits")  # pragma: no cover


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="fprime-lite", description="F´ components in Python: run, check and "
                                     "inspect deployments; fly the simulated spacecraft.")
    parser.add_argument("--version", action="version", version=f"fprime-lite {_version()}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True

    run = sub.add_parser("run", help="run a deployment", description="Run a deployment in simulated time and write "
                         "summary.json, events.log, channels.csv, channels_wide.csv, truth.csv, dictionary.json and "
                         "plots "
                         "(docs/outputs.md). Exits 1 when the flight had faults, cycle slips or WARNING_HI/FATAL "
                         "events (--allow-warnings accepts them), 2 for a mistake in the inputs.")
    _model_arg(run)
    run.add_argument("--run-file", metavar="FILE", help="FPP only: the constructor arguments, rate-group divisors "
                     "and resources an FPP topology does not say (default: run.yaml beside the FPP files; "
                     "docs/fpp.md)")
    run.add_argument("--duration", type=float, default=None, metavar="SECONDS",
                     help="simulated seconds to run (default: the topology's run.duration_s, else 600)")
    run.add_argument("--stop-when", action="append", default=[], metavar="'KEY OP VALUE'",
                     help="end the run early once every such condition holds on the reports' progress values, "
                          "e.g. 'spin_settled_for_s >= 300' or 'mode == POINTING' (repeatable; checked once per "
                          "simulated second)")
    run.add_argument("--scenario", metavar="NAME|FILE", help="simulation scenario (packaged name or YAML file)")
    run.add_argument("--seed", type=int, help="seed of the sensor noise (overrides the scenario's)")
    run.add_argument("--set", action="append", default=[], metavar="KEY.PATH=VALUE",
                     help="override one scenario value, e.g. sensors.magnetometer.noise_std_gauss=0 (repeatable)")
    run.add_argument("--params", metavar="FILE", help="parameter file for PrmDb (overrides the topology's)")
    run.add_argument("--seq", metavar="FILE", help="start-up sequence (.seq text or binary; overrides the topology's)")
    run.add_argument("--out", metavar="DIR", help="output folder (default: a new runs/<timestamp>)")
    run.add_argument("--no-progress", action="store_true", help="no progress bar")
    run.add_argument("--no-plots", action="store_true", help="do not draw the PNG plots")
    run.add_argument("--writer", choices=("auto", "process", "inline"), default="auto",
                     help="who formats channels.csv, channels_wide.csv and truth.csv: a writer process on another "
                          "core, or this one (auto: a process when there is a second core and the run is not "
                          "paced; the same bytes either way)")
    run.add_argument("--truth-interval", type=float, metavar="SECONDS",
                     help="sampling interval of the truth log (default: the topology's)")
    run.add_argument("--allow-warnings", action="store_true", help="exit 0 even when the flight had handler "
                     "faults, cycle slips or WARNING_HI/FATAL events (the summary still lists them)")
    run.add_argument("-v", "--verbose", action="store_true", help="log framework warnings to stderr")
    run.add_argument("--force", action="store_true", help="fly a run longer than 6 h even when its outputs would "
                     "not fit the disk or exceed 10 GB (estimated from a 60 s probe flight; docs/outputs.md)")
    run.add_argument("--realtime", action="store_true", help="pace the run to the wall clock (simulated time "
                     "never runs ahead of it); Ctrl-C stops the run and still writes the outputs")
    run.add_argument("--gds", nargs="?", const="127.0.0.1:50000", metavar="HOST:PORT",
                     help="fly the deployment with a ground link to a running fprime-gds (default "
                     "127.0.0.1:50000); implies --realtime; see docs/ground.md")
    run.add_argument("--framing", choices=("ccsds", "fprime"), default="ccsds",
                     help="ground-link framing, as fprime-gds --framing-selection: ccsds = "
                     "space-packet-space-data-link (the GDS's default), fprime = fprime (default: ccsds)")
    run.add_argument("--file-root", metavar="DIR", help="confine the file services (fileUplink, fileDownlink, "
                     "fileManager) to DIR instead of the output folder, with relative paths resolved against the "
                     "working directory (which must be inside DIR) and uplinked or moved files replacing existing "
                     "ones, as F´'s do; F´'s own integration tests use /tmp and 'conformance' passes --file-root /tmp")
    run.add_argument("--board-root", metavar="DIR", help="DIR stands in for the board's / for the file services "
                     "and the command sequencers: an absolute path such as /seq/a.bin names DIR/seq/a.bin, relative "
                     "paths resolve against DIR, nothing outside DIR is reachable, and uplinked or moved files replace "
                     "existing ones (PROVES's suite uplinks to /seq; 'conformance --board-root' passes it); DIR is "
                     "also the simulated flash, so fsFormat's FORMAT erases it all, as on the board; not with "
                     "--file-root")
    run.add_argument("--no-startup", action="store_true", help="fly without the topology's start-up sequence, as "
                     "a board whose file system holds none (PROVES's CI formats it before its suite); not with --seq")

    dic = sub.add_parser("dict", help="write the F´ JSON dictionary")
    _model_arg(dic)
    dic.add_argument("-o", "--output", required=True, metavar="FILE",
                     help="where to write the dictionary ('-' for standard output)")
    dic.add_argument("--force", action="store_true", help="replace FILE even when it is not an F´ dictionary")
    dic.add_argument("--gds", action="store_true", help="include the ground link that 'run --gds' adds (the "
                     "dictionary to start fprime-gds with)")

    check = sub.add_parser("check", help="validate a topology")
    _model_arg(check)

    graph = sub.add_parser("graph", help="print the topology as DOT or Mermaid")
    _model_arg(graph)
    graph.add_argument("--format", choices=("dot", "mermaid"), default="dot")
    graph.add_argument("--patterns", action="store_true", help="include pattern connections (command, event, …)")

    params = sub.add_parser("params", help="write a parameter file with every parameter's default; list them",
                            description="Write F´'s PrmDb file holding every parameter's default (or the value "
                            "--set gives it) with -o FILE, and/or print every parameter of the topology with its "
                            "id, type, value and units with --list.")
    _topology_arg(params)
    params.add_argument("-o", "--output", metavar="FILE", help="the parameter file to write ('-' for standard output)")
    params.add_argument("--force", action="store_true", help="replace FILE even when it is not a parameter file")
    params.add_argument("--list", action="store_true",
                        help="print a table of the parameters: name, id, type, value (the default or --set) "
                             "and units")
    params.add_argument("--set", action="append", default=[], metavar="Module.inst.PARAM=VALUE",
                        help="write VALUE instead of the default, e.g. ReferenceDeployment.detumbleManager.GAIN=2.5 "
                             "(repeatable; enum values by name)")

    plot = sub.add_parser("plot", help="draw the plots of a finished run again", description="Draw the PNG "
                          "plots of a finished run from the files in its folder, with the plotters the "
                          "installed applications provide (entry points fprime_lite.plots).")
    plot.add_argument("run_dir", metavar="RUN_DIR", help="a folder 'fprime-lite run' wrote")
    plot.add_argument("-o", "--output", metavar="DIR", help="where to write the PNGs (default: RUN_DIR)")

    new = sub.add_parser("new", help="write a component or deployment skeleton that passes its own test",
                         description="Write a skeleton: 'new component NAME' writes NAME's module, its "
                         "harness test and a docs stub into --dir; 'new deployment NAME' creates the folder "
                         "NAME with a component, topology.yaml, tests and a README. Run python -m pytest "
                         "there.")
    new.add_argument("kind", choices=("component", "deployment"))
    new.add_argument("name", metavar="NAME", help="a class-style name, e.g. MyHeater")
    new.add_argument("--dir", default=".", metavar="DIR", help="the folder to write into (default: .)")
    new.add_argument("--component", default="Counter", metavar="NAME",
                     help="deployment only: the name of its component (default: Counter)")
    new.add_argument("--fpp", action="store_true", help="component only: write its interface as NAME.fpp and "
                     "a Python class with the handlers only (docs/fpp.md)")

    bench = sub.add_parser("bench", help="measure speed and memory", add_help=False)
    bench.add_argument("args", nargs=argparse.REMAINDER)
    campaign = sub.add_parser("campaign", help="run a gain sweep or Monte Carlo campaign on Dask", add_help=False)
    campaign.add_argument("args", nargs=argparse.REMAINDER)
    conformance = sub.add_parser("conformance", help="run an fprime-gds integration suite against the flying "
                                 "deployment (docs/ground.md)", add_help=False)
    conformance.add_argument("args", nargs=argparse.REMAINDER)
    for verb in _application_verbs().values():
        plug = sub.add_parser(verb.name, help=verb.help, add_help=False)
        plug.add_argument("args", nargs=argparse.REMAINDER)
    return parser


def _application_verbs() -> dict:
    from fprime_lite.tools.plugins import PluginError, verbs

    try:
        return {name: verb for name, verb in verbs().items() if name not in BUILT_IN}
    except PluginError as exc:
        print(f"fprime-lite: {exc}", file=sys.stderr)
        return {}


def _version() -> str:
    from fprime_lite import __version__
    return __version__


def _load(path: str):
    from fprime_lite.tools.api import load

    return load(path)


def cmd_check(args) -> int:
    from fprime_lite.deploy.preflight import topology_file_problems, topology_warnings
    from fprime_lite.deploy.topology import TopologyError

    topo, loaded = _load_model(args)
    if isinstance(topo, dict):
        print(f"{args.topology}: OK — {len(topo)} FPP component(s) bound to their Python implementations: "
              + ", ".join(f"{name} → {cls.__module__}.{cls.__qualname__}" for name, cls in topo.items()))
        return 0
    if loaded is None:
        print(f"{args.topology}: OK — FPP topology {topo.deployment}: {len(topo.instances)} instances bound to their "
              f"Python implementations, {len(topo.connections)} connections")
        return 0
    problems = topology_file_problems(loaded)
    if problems:
        raise TopologyError(problems)
    for warning in topology_warnings(loaded):
        print(warning, file=sys.stderr)
    print(f"{args.topology}: OK — deployment {topo.deployment}: {len(topo.instances)} instances, "
          f"{len(topo.connections)} connections")
    return 0


def cmd_dict(args) -> int:
    from fprime_lite.deploy.dictionary import build_dictionary, write_dictionary

    topology, loaded = _load_model(args)
    if args.gds and loaded is None:
        raise UserError("--gds adds the ground link to a YAML deployment; an FPP topology wires its own")
    if args.gds:
        from fprime_lite.deploy.com_stack import add_ground_link

        add_ground_link(topology)
    if args.output == "-":
        d = build_dictionary(topology)
        sys.stdout.write(json.dumps(d, indent=2) + "\n")
        return 0
    _replaceable_output(args.output, "-o", _is_dictionary, "an F´ JSON dictionary", args.force)
    d = write_dictionary(topology, args.output)
    print(f"wrote {args.output}: {len(d['commands'])} commands, {len(d['events'])} events, "
          f"{len(d['telemetryChannels'])} channels, {len(d['parameters'])} parameters")
    return 0


def _is_dictionary(path: pathlib.Path) -> bool:
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError):
        return False
    return isinstance(data, dict) and isinstance(data.get("metadata"), dict) and "commands" in data


def _is_param_file(path: pathlib.Path) -> bool:
    from fprime_lite.svc.prm_db import ParamFileError, decode_param_file

    try:
        decode_param_file(path.read_bytes())
    except (OSError, ParamFileError):
        return False
    return True


def _replaceable_output(path: str, option: str, is_ours, what: str, force: bool) -> pathlib.Path:
    """An output file the user named (see :func:`_output_file`) that may replace an existing file only when
    that file is ``what`` the verb writes (``is_ours(path)``) or ``force``: a typo such as ``params -o
    topology.yaml`` must not destroy the user's own file."""
    p = _output_file(path, option)
    if p.exists() and not force and not is_ours(p):
        raise UserError(f"{option} {path}: the file exists and is not {what} — choose another name, or add "
                        f"--force to replace it")
    return p


def cmd_graph(args) -> int:
    topo, loaded = _load_model(args)
    if loaded is None:
        sys.stdout.write(topo.to_dot() if args.format == "dot" else topo.to_mermaid())
        return 0
    sys.stdout.write(topo.to_dot(args.patterns) if args.format == "dot" else topo.to_mermaid(args.patterns))
    return 0


def cmd_params(args) -> int:
    from fprime_lite.model.params import ParamValid
    from fprime_lite.svc.prm_db import encode_param_file
    from fprime_lite.osal.atomic import atomic_write_bytes

    if args.output is None and not args.list:
        raise UserError("give -o FILE (write the parameter file), --list (print the parameters) or both")
    if args.output == "-" and args.list:
        raise UserError("-o - writes the parameter file to standard output: leave out --list")
    if args.output not in (None, "-"):
        _replaceable_output(args.output, "-o", _is_param_file, "a parameter file (F´ PrmDb)", args.force)
    topo = _load(args.topology).topology
    declared = {}
    for instance in topo.instances.values():
        comp = instance.component
        for p in comp.spec.params:
            declared[f"{instance.qualified_name}.{p.name}"] = (comp.base_id + p.local_id, p)
    values = {name: p.default for name, (_, p) in declared.items() if p.has_default}
    for setting in args.set:
        name, value = _param_setting(setting, declared)
        values[name] = value
    if args.list:
        sys.stdout.write(_param_table(declared, values))
    if args.output is None:
        return 0
    records = sorted((name, declared[name][0], declared[name][1].type.serialize(value))
                     for name, value in values.items())  # by full name, as fprime-prm-write orders them
    data = encode_param_file([(pid, data) for _, pid, data in records])
    changed = f"; {len(args.set)} set on the command line" if args.set else ""
    if args.output == "-":
        sys.stdout.buffer.write(data)
        sys.stdout.flush()
        return 0
    atomic_write_bytes(args.output, data)
    print(f"wrote {args.output}: {len(records)} parameters ({ParamValid.DEFAULT.name} values of the "
          f"topology{changed})")
    return 0


def _param_table(declared: dict, values: dict) -> str:
    """``params --list``: one row a parameter, in id order — full name, id, F´ type, the value the file
    holds (enum constants by name; ``—`` for a parameter without default, which the file leaves
    out) and the declared units (``—`` when none)."""
    rows = [("parameter", "id", "type", "value", "units")]
    for name, (pid, p) in sorted(declared.items(), key=lambda item: item[1][0]):
        if name in values:
            value = p.type.json_value(values[name])
            text = value.rsplit(".", 1)[1] if p.type.kind == "enum" else json.dumps(value, ensure_ascii=False)
        else:
            text = "—"
        rows.append((name, f"0x{pid:X}", p.type.name, text, p.units or "—"))
    widths = [max(len(row[i]) for row in rows) for i in range(4)]
    return "".join("  ".join(cell.ljust(w) for cell, w in zip(row[:4], widths, strict=True)) + f"  {row[4]}\n"
                   for row in rows)


def _param_setting(setting: str, declared: dict) -> tuple[str, object]:
    """``Module.inst.PARAM=VALUE`` → (name, value checked against the parameter's F´ type)."""
    import yaml

    from fprime_lite.model.errors import SerializationError, did_you_mean

    name, sep, text = setting.partition("=")
    name = name.strip()
    if not sep or not name:
        raise UserError(f"--set {setting!r}: expected Module.inst.PARAM=VALUE")
    if name not in declared:
        hint = did_you_mean(name, declared, " (fprime-lite dict lists them)", " — did you mean {}?")
        raise UserError(f"--set {setting!r}: the topology has no parameter {name}{hint}")
    try:
        value = yaml.safe_load(text)
    except yaml.YAMLError:
        value = text
    param = declared[name][1]
    ptype = param.type
    if getattr(ptype, "kind", None) == "float" and isinstance(value, str):
        value = _float_text(setting, text.strip(), ptype.name)
    try:
        value = ptype.check(value)
    except (SerializationError, ValueError, TypeError) as exc:
        raise UserError(f"--set {setting!r}: not a valid {ptype.name}: {exc}") from None
    problem = param.invalid_reason(value)
    if problem is not None:  # the component would refuse it at load and use its default
        raise UserError(f"--set {setting!r}: {problem}; {name} would load its default instead")
    return name, value


def _float_text(setting: str, text: str, type_name: str):
    """A float written as text YAML does not read as a number (``1e400``, ``1e5``): its value, or
    an out-of-range error when it overflows."""
    import math

    try:
        value = float(text)
    except ValueError:
        return text  # not a number: the type's own check says so
    if math.isinf(value) and "inf" not in text.lower():
        raise UserError(f"--set {setting!r}: {text} is out of range for {type_name} "
                        f"(|x| ≤ {sys.float_info.max:.6g})")
    return value


def _run_topology(args) -> None:
    """``args.topology`` as one topology YAML path: the given YAML, or the YAML written (into a
    temporary folder removed at exit) that flies the given FPP topology with its run file."""
    paths = list(args.topology)
    if not any(p.endswith(".fpp") for p in paths) and not args.imports:
        if args.run_file is not None:
            raise UserError("--run-file applies to an FPP topology: give its .fpp files")
        if len(paths) != 1:
            raise UserError(f"{' '.join(paths)}: give one topology YAML (several files are FPP files only)")
        args.topology = paths[0]
        return
    import atexit
    import shutil
    import tempfile

    from fprime_lite.deploy.fpp.run import write_topology_yaml

    if not all(p.endswith(".fpp") for p in paths):
        raise UserError(f"{' '.join(paths)}: give either FPP files or one topology YAML, not both")
    folder = pathlib.Path(tempfile.mkdtemp(prefix="fprime-lite-fpp-"))
    atexit.register(shutil.rmtree, folder, ignore_errors=True)
    args.topology = str(write_topology_yaml(paths, folder, imports=[p for p in args.imports.split(",") if p],
                                            framework=not args.no_framework_fpp, run_file=args.run_file))


def cmd_run(args) -> int:
    from fprime_lite.deploy.preflight import check_run_files
    from fprime_lite.tools import disk_estimate
    from fprime_lite.tools.api import claim_run_folder, load
    from fprime_lite.tools.interrupt import exit_status
    from fprime_lite.tools.runner import run_deployment, run_duration
    from fprime_lite.tools.stop_condition import StopConditionError, parse_stop_condition

    _checked_settings(args.set)
    _run_topology(args)
    if args.duration is not None and not 0 < args.duration < math.inf:
        raise UserError(f"--duration must be a positive, finite number of seconds, got {args.duration}")
    try:
        args.stop_when = [parse_stop_condition(text) for text in args.stop_when]
    except StopConditionError as exc:
        raise UserError(f"--stop-when {exc}") from None
    for option, value in (("--params", args.params), ("--seq", args.seq), ("--scenario", args.scenario)):
        if value is not None and pathlib.Path(value).is_dir():
            raise UserError(f"{option} {value}: is a folder — give a file")
        if option != "--scenario" and value is not None and not pathlib.Path(value).is_file():
            raise UserError(f"{option} {value}: no such file")
    realtime = args.realtime or args.gds is not None
    address = None
    if args.gds is not None:
        from fprime_lite.svc.ground_link import parse_address

        try:
            address = parse_address(args.gds)
        except ValueError as exc:
            raise UserError(f"--gds {exc}") from None
    elif args.framing != "ccsds":
        raise UserError("--framing applies to the ground link: add --gds")
    loaded = load(args.topology, scenario=args.scenario, seed=args.seed, settings=args.set,
                  truth_interval_s=args.truth_interval, scheduler_factory=_paced if realtime else None)
    check_run_files(loaded, parameter_file=args.params, sequence=args.seq)
    args.duration = run_duration(loaded, args.duration)  # the topology's own run length when not given
    _check_file_root(args.file_root)
    if args.board_root is not None:
        if args.file_root is not None:
            raise UserError("--board-root and --file-root: give one (a board root is the file services' whole root)")
        if not pathlib.Path(args.board_root).is_dir():
            raise UserError(f"--board-root {args.board_root}: not an existing folder")
        from fprime_lite.tools.runner import use_board_as_flash

        use_board_as_flash(loaded, args.board_root)
    if args.no_startup:
        if args.seq is not None:
            raise UserError("--no-startup and --seq: give one")
        loaded.startup_sequence = None
    if args.duration > disk_estimate.CHECK_ABOVE_S and not args.force and not realtime:
        def fly(folder: pathlib.Path, seconds: float) -> None:
            probe = load(args.topology, scenario=args.scenario, seed=args.seed, settings=args.set,
                         truth_interval_s=args.truth_interval)
            run_deployment(probe, folder, duration_s=seconds, parameter_file=args.params, sequence=args.seq,
                           plots=False, quiet=True)
        disk_estimate.check_disk(disk_estimate.estimate_output_bytes(fly), args.duration,
                                 pathlib.Path(args.out or "runs"))
    out = claim_run_folder(args.out)
    if not realtime:
        summary = run_deployment(loaded, out, duration_s=args.duration, parameter_file=args.params,
                                 sequence=args.seq, progress=not args.no_progress and sys.stderr.isatty(),
                                 plots=not args.no_plots, allow_warnings=args.allow_warnings,
                                 stop_when=args.stop_when, interruptible=True, file_root=args.file_root,
                                 board_root=args.board_root, writer=args.writer)
    else:
        summary = _run_realtime(loaded, out, args, address)
    print(f"outputs in {out}/")
    if summary.get("stopped_by") == "interrupted" and not realtime:
        print(f"fprime-lite run: interrupted by {summary['signal']} at t = {summary['sim_seconds']:.3f} s; the "
              f"outputs up to then are in {out}/", file=sys.stderr)
        return exit_status(summary["signal"])  # 130 for SIGINT, 143 for SIGTERM, as a shell says
    if summary.get("stop_reason"):  # the simulation itself ended the run (a diverged plant)
        print(f"fprime-lite run: stopped: {summary['stop_reason']}", file=sys.stderr)
        return EXIT_FAILED
    if not summary["ok"]:
        print(f"fprime-lite run: the flight reported problems: {'; '.join(summary['problems'])} "
              f"(--allow-warnings accepts them)", file=sys.stderr)
        return EXIT_FAILED
    return 0


def _check_file_root(file_root: str | None) -> None:
    """``--file-root DIR``: an existing folder that holds the working directory."""
    from fprime_lite.tools.runner import file_root_problem

    problem = file_root_problem(file_root)
    if problem is not None:
        raise UserError(f"--file-root {file_root}: {problem}")


def _output_file(path: str, option: str) -> pathlib.Path:
    """An output file the user named: refused when it is a folder or its folder does not exist
    (nothing is created that the user did not ask for)."""
    p = pathlib.Path(path)
    if p.is_dir():
        raise UserError(f"{option} {path}: is a folder — give a file name")
    parent = p.parent
    if not parent.is_dir():
        raise UserError(f"{option} {path}: folder {parent} does not exist — create it first or choose another")
    if not os.access(parent, os.W_OK):
        raise UserError(f"{option} {path}: cannot write in {parent} (permission denied)")
    return p


def _paced(clock):
    from fprime_lite.deploy.scheduler import PacedScheduler

    return PacedScheduler(clock)


def _run_realtime(loaded, out: pathlib.Path, args, address) -> dict:
    """Run paced to the wall clock, with the ground link when ``address`` is given; SIGINT and
    SIGTERM end the run early and the outputs are still written (the way a paced run is ended, by the
    user or by fprime-gds: exit status 0 unless the flight reported problems)."""
    from fprime_lite.tools.runner import run_deployment

    link = None
    if address is not None:
        from fprime_lite.deploy.com_stack import add_ground_link

        link = add_ground_link(loaded.topology, host=address[0], port=address[1], framing=args.framing)
        print(f"ground link: {args.framing} framing, connecting to {link.host}:{link.port} "
              f"(instance {loaded.topology.deployment}.{link.name})", flush=True)
    scheduler = loaded.scheduler
    try:
        if link is not None:
            link.start_socket_task()
            threading.Thread(target=_announce_connection, args=(link,), name="announce-connection",
                             daemon=True).start()
        summary = run_deployment(loaded, out, duration_s=args.duration, parameter_file=args.params,
                                 sequence=args.seq, progress=False, plots=not args.no_plots,
                                 allow_warnings=args.allow_warnings, stop_when=args.stop_when, interruptible=True,
                                 file_root=args.file_root, board_root=args.board_root)
    finally:
        if link is not None:
            link.close()
    print(f"realtime: largest lag behind the wall clock {scheduler.max_lag_s * 1e3:.1f} ms")
    if link is not None:
        print(f"ground link: {link.connections} connection(s), {link.commands_forwarded} command(s) "
              f"forwarded, {link.downlink_frames} frame(s) / {link.downlink_bytes} bytes sent")
    return summary


def _announce_connection(link) -> None:
    """Print one line when the ground link first connects (``fprime-lite conformance`` waits for it)."""
    while not link.wait_connected(1.0):
        pass
    print(f"ground link: connected to {link.host}:{link.port}", flush=True)


def _checked_settings(settings: list[str]) -> list[str]:
    """``--set`` values, refused early when one is not ``KEY.PATH=VALUE``."""
    for setting in settings:
        path, sep, _ = setting.partition("=")
        if not sep or not path.strip():
            raise UserError(f"--set {setting!r}: expected KEY.PATH=VALUE, e.g. sensors.magnetometer.noise_std_gauss=0")
    return settings


def cmd_plot(args) -> int:
    from fprime_lite.tools.api import plot_run_dir

    written = plot_run_dir(args.run_dir, args.output)
    print(f"wrote {len(written)} plot(s): " + ", ".join(str(p) for p in written))
    return 0


def cmd_new(args) -> int:
    from fprime_lite.tools.skeleton import SkeletonError, new_component, new_deployment

    try:
        if args.kind == "component":
            written = new_component(args.name, args.dir, fpp=args.fpp)
        elif args.fpp:
            raise UserError("--fpp applies to 'new component'; a deployment's topology is YAML")
        else:
            written = new_deployment(args.name, args.dir, component=args.component)
    except SkeletonError as exc:
        raise UserError(str(exc)) from None
    folder = written[0].parent
    print(f"wrote {', '.join(str(p) for p in written)}\nnext: cd {folder} && python -m pytest")
    return 0


def cmd_bench(args) -> int:
    from fprime_lite.tools.bench import main as bench_main

    return bench_main(args.args)


def cmd_conformance(args) -> int:
    from fprime_lite.tools.conformance import main as conformance_main

    return conformance_main(args.args)


def cmd_campaign(args) -> int:
    from fprime_lite.tools.campaign.cli import main as campaign_main

    return campaign_main(args.args)


COMMANDS = {"run": cmd_run, "dict": cmd_dict, "check": cmd_check, "graph": cmd_graph,
            "params": cmd_params, "bench": cmd_bench, "campaign": cmd_campaign, "plot": cmd_plot, "new": cmd_new,
            "conformance": cmd_conformance}
BUILT_IN = set(COMMANDS)

#: Verbs that parse their own options (application verbs do too).
PASS_THROUGH = {"bench", "campaign", "conformance"}


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] in PASS_THROUGH:
        args = argparse.Namespace(command=argv[0], args=argv[1:], verbose=False)
    elif argv and argv[0] not in BUILT_IN and not argv[0].startswith("-") and argv[0] in _application_verbs():
        return _application_verbs()[argv[0]].main(argv[1:])
    else:
        args = _parse(build_parser(), argv)
    logging.basicConfig(level=logging.INFO if getattr(args, "verbose", False) else logging.ERROR,
                        format="%(levelname)s %(name)s: %(message)s")
    try:
        return COMMANDS[args.command](args)
    except FwAssertionError:
        raise  # a broken framework invariant is a bug: its traceback is what to report
    except FprimeLiteError as exc:  # UserError and every other mistake the message explains
        print(f"fprime-lite {args.command}: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        print(f"fprime-lite {args.command}: interrupted", file=sys.stderr)
        return 130
    except OSError as exc:  # an output the system refuses (disk full, permissions …)
        where = f" {exc.filename}" if exc.filename else ""
        print(f"fprime-lite {args.command}: cannot write or read{where}: {exc.strerror or exc}", file=sys.stderr)
        return EXIT_FAILED


if __name__ == "__main__":
    sys.exit(main())
