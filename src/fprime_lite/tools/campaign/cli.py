"""``fprime-lite campaign FILE [--workers N | --scheduler ADDR] [--out DIR] [--resume] [--retry-failed]
[--force] [--rerun RUN_ID] [--tls-ca-file F --tls-cert F --tls-key F | --dask-config F]``."""

from __future__ import annotations

import argparse
import shlex
import sys

__all__ = ["main", "build_parser"]


def build_parser(prog: str = "fprime-lite campaign") -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog=prog, description="Run a campaign (gain sweep or Monte Carlo) on Dask: "
                                "an embedded cluster by default, or an existing cluster.")
    p.add_argument("file", help="campaign YAML file (see docs/campaigns.md; examples in campaigns/)")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, metavar="N",
                       help="worker processes of the embedded cluster (default: one per core)")
    where.add_argument("--scheduler", metavar="tcp://HOST:PORT", help="use an existing Dask scheduler (tcp:// or tls://)")
    p.add_argument("--out", metavar="DIR", help="campaign folder (default: runs/campaign-NAME-TIMESTAMP)")
    p.add_argument("--resume", action="store_true", help="continue the campaign in --out: skip finished runs")
    p.add_argument("--retry-failed", action="store_true",
                   help="with --resume (implied): also run again the runs recorded as failed or timeout")
    p.add_argument("--force", action="store_true",
                   help="with --resume: continue in a folder that holds another campaign's runs")
    p.add_argument("--rerun", metavar="RUN_ID",
                   help="fly one run again in this process (same seed and values), keeping its files in "
                        "--out/runs/RUN_ID; the results are not changed")
    tls = p.add_argument_group("a TLS scheduler (tls://HOST:PORT)")
    tls.add_argument("--tls-ca-file", metavar="FILE", help="the CA certificate that signed the cluster's")
    tls.add_argument("--tls-cert", metavar="FILE", help="this client's certificate")
    tls.add_argument("--tls-key", metavar="FILE", help="this client's private key")
    tls.add_argument("--dask-config", metavar="FILE",
                     help="a Dask config YAML file (e.g. distributed.comm.tls.* for a TLS cluster)")
    p.add_argument("--wait-for-workers", type=float, metavar="S", default=60.0,
                   help="how long to wait for a worker on a scheduler that has none (default 60 s)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument("--no-plots", action="store_true", help="do not draw the PNG plots")
    return p


def _rerun(args) -> int:
    from fprime_lite.tools.campaign.engine import rerun

    if not args.out:
        print("fprime-lite campaign: --rerun needs --out: the campaign's folder", file=sys.stderr)
        return 2
    row, differences = rerun(args.file, args.rerun, args.out)
    print(f"run {args.rerun}: {row['status']}" + (f" ({row['error']})" if row["error"] else "")
          + f"; its files are in {args.out}/runs/{args.rerun}")
    for key, (before, now) in differences.items():
        print(f"  {key}: journaled {before!r}, now {now!r}")
    if not differences:
        print("  every metric and read-back value as journaled (or not journaled yet)")
    return 0 if row["status"] == "ok" and not differences else 1


def resume_command(argv: list[str], out) -> str:
    """The command that continues an interrupted campaign: the same one, with ``--out`` the folder it
    wrote into and ``--resume`` (unless it had them, or ``--retry-failed``, already)."""
    args = list(argv)
    if not any(a == "--out" or a.startswith("--out=") for a in args):
        args += ["--out", str(out)]
    if not any(a in ("--resume", "--retry-failed") for a in args):
        args.append("--resume")
    return shlex.join(["fprime-lite", "campaign", *args])


def main(argv: list[str] | None = None) -> int:
    from fprime_lite.model.errors import FprimeLiteError, FwAssertionError
    from fprime_lite.tools.campaign.cluster import security_from
    from fprime_lite.tools.campaign.engine import default_out_dir, run_campaign
    from fprime_lite.tools.campaign.errors import CampaignInterrupted
    from fprime_lite.tools.campaign.spec import load_campaign
    from fprime_lite.tools.interrupt import exit_status

    argv = sys.argv[1:] if argv is None else list(argv)

    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:
        return int(exc.code or 0)
    out = args.out
    try:
        if args.rerun:
            return _rerun(args)
        campaign = load_campaign(args.file)
        resume = args.resume or args.retry_failed
        out = args.out or (None if resume else default_out_dir(campaign))
        security = security_from(args.tls_ca_file, args.tls_cert, args.tls_key, args.dask_config)
        df = run_campaign(campaign, workers=args.workers, scheduler=args.scheduler, out=out, resume=resume,
                          retry_failed=args.retry_failed, force=args.force, security=security,
                          wait_for_workers_s=args.wait_for_workers,
                          progress=not args.no_progress and sys.stderr.isatty(), plots=not args.no_plots,
                          interruptible=True)
    except FwAssertionError:
        raise  # a broken framework invariant is a bug: its traceback is what to report
    except FprimeLiteError as exc:
        print(f"fprime-lite campaign: {exc}", file=sys.stderr)
        return 2
    except CampaignInterrupted as stop:
        print(f"fprime-lite campaign: interrupted by {stop.signal} after {stop.done} of {stop.planned} runs (kept "
              f"in {stop.out}); continue with: {resume_command(argv, stop.out)}", file=sys.stderr)
        return exit_status(stop.signal)
    except KeyboardInterrupt:  # before the runs started (the checks, the probe flight)
        print("fprime-lite campaign: interrupted before any run was submitted"
              + (f"; continue with: {resume_command(argv, out)}" if out is not None else ""), file=sys.stderr)
        return 130
    print(f"results in {out}/results.parquet ({len(df)} runs)")
    bad = int((df["status"] != "ok").sum()) if len(df) else 0
    if bad:
        print(f"fprime-lite campaign: {bad} of {len(df)} runs did not finish ok (column 'error'; "
              f"--retry-failed runs them again)", file=sys.stderr)
        return 1
    return 0
