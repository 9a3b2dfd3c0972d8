"""``fprime-lite-app``: the program ``fprime-gds --app`` launches.

fprime-gds runs its app as ``PROGRAM -p PORT -a ADDRESS`` from the program's own folder (the
virtual environment's ``bin``), so everything else comes from options or environment variables:

=========================  ===================================  ===================================
option                     environment variable                 default
=========================  ===================================  ===================================
``--framing``              ``FPRIME_LITE_FRAMING``              ``ccsds`` (fprime-gds's default)
``--topology``             ``FPRIME_LITE_TOPOLOGY``             the reference deployment
``--out``                  ``FPRIME_LITE_OUT``                  the system's temporary folder
``--seq``                  ``FPRIME_LITE_SEQ``                  the topology's start-up sequence
``--duration``             ``FPRIME_LITE_DURATION``             864000 s (ten days: until stopped)
=========================  ===================================  ===================================

The run is ``fprime-lite run TOPOLOGY --realtime --gds ADDRESS:PORT --framing F`` (an address of
``0.0.0.0``, fprime-gds's default ``--ip-address``, means the local host). Each launch writes its outputs
to a new ``fprime-lite-app-*`` folder inside ``--out`` (printed to the app's log, which fprime-gds
keeps in its logs folder). SIGTERM from fprime-gds ends the run and the outputs are written. Start
fprime-gds with the framing the app uses.
"""

from __future__ import annotations

import argparse
import os
import pathlib
import sys
import tempfile

__all__ = ["main", "reference_topology"]

DEFAULT_DURATION_S = 864000.0


def reference_topology() -> pathlib.Path | None:
    """``deployments/proves_ref/topology.yaml`` of the source tree this package runs from, if any."""
    here = pathlib.Path(__file__).resolve()
    for parent in here.parents:
        candidate = parent / "deployments" / "proves_ref" / "topology.yaml"
        if candidate.is_file():
            return candidate
    return None


def build_parser() -> argparse.ArgumentParser:
    env = os.environ.get
    p = argparse.ArgumentParser(prog="fprime-lite-app", description="Fly an fprime-lite deployment for "
                                "fprime-gds --app (connects to the GDS at ADDRESS:PORT).")
    p.add_argument("-p", "--port", type=int, default=50000, help="the GDS's --ip-port (default 50000)")
    p.add_argument("-a", "--address", default="127.0.0.1", help="the GDS's --ip-address (default 127.0.0.1)")
    p.add_argument("--framing", choices=("ccsds", "fprime"), default=env("FPRIME_LITE_FRAMING", "ccsds"),
                   help="ground-link framing (env FPRIME_LITE_FRAMING; default ccsds)")
    p.add_argument("--topology", default=env("FPRIME_LITE_TOPOLOGY"),
                   help="topology YAML (env FPRIME_LITE_TOPOLOGY; default: the reference deployment)")
    p.add_argument("--out", default=env("FPRIME_LITE_OUT"),
                   help="folder in which each launch makes its output folder (env FPRIME_LITE_OUT)")
    p.add_argument("--seq", default=env("FPRIME_LITE_SEQ"), help="start-up sequence (env FPRIME_LITE_SEQ)")
    p.add_argument("--duration", type=float, default=float(env("FPRIME_LITE_DURATION", DEFAULT_DURATION_S)),
                   help="simulated seconds to fly (env FPRIME_LITE_DURATION; default ten days)")
    return p


def main(argv: list[str] | None = None) -> int:
    from fprime_lite.tools.cli import main as cli_main

    args = build_parser().parse_args(argv)
    topology = args.topology or reference_topology()
    if topology is None:
        print("fprime-lite-app: no topology — set FPRIME_LITE_TOPOLOGY or pass --topology", file=sys.stderr)
        return 2
    if args.out:
        os.makedirs(args.out, exist_ok=True)
    out = tempfile.mkdtemp(prefix="fprime-lite-app-", dir=args.out)
    address = "127.0.0.1" if args.address in ("", "0.0.0.0") else args.address
    run = ["run", str(topology), "--realtime", "--gds", f"{address}:{args.port}", "--framing", args.framing,
           "--duration", str(args.duration), "--out", str(out), "--no-plots", "--no-progress"]
    if args.seq:
        run += ["--seq", args.seq]
    print("fprime-lite-app: fprime-lite " + " ".join(run), flush=True)
    return cli_main(run)


if __name__ == "__main__":
    sys.exit(main())
