"""``fprime-lite campaign FILE [--workers N | --scheduler tcp://HOST:PORT] [--out DIR] [--resume]
[--retry-failed]``."""

from __future__ import annotations

import argparse
import sys

__all__ = ["main", "build_parser"]


def build_parser(prog: str = "fprime-lite campaign") -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog=prog, description="Run a campaign (gain sweep or Monte Carlo) on Dask: "
                                "an embedded LocalCluster by default, or an existing cluster.")
    p.add_argument("file", help="campaign YAML file (see docs/campaigns.md; examples in campaigns/)")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, metavar="N",
                       help="worker processes of the embedded LocalCluster (default: one per core)")
    where.add_argument("--scheduler", metavar="tcp://HOST:PORT", help="use an existing Dask scheduler")
    p.add_argument("--out", metavar="DIR", help="campaign folder (default: runs/campaign-NAME-TIMESTAMP)")
    p.add_argument("--resume", action="store_true", help="continue the campaign in --out: skip finished runs")
    p.add_argument("--retry-failed", action="store_true",
                   help="with --resume (implied): also run again the runs recorded as failed or timeout")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument("--no-plots", action="store_true", help="do not draw the PNG plots")
    return p


def main(argv: list[str] | None = None) -> int:
    from fprime_lite.model.errors import FprimeLiteError, FwAssertionError
    from fprime_lite.tools.campaign.engine import default_out_dir, run_campaign
    from fprime_lite.tools.campaign.spec import load_campaign

    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:
        return int(exc.code or 0)
    try:
        campaign = load_campaign(args.file)
        resume = args.resume or args.retry_failed
        out = args.out or (None if resume else default_out_dir(campaign))
        df = run_campaign(campaign, workers=args.workers, scheduler=args.scheduler, out=out, resume=resume,
                          retry_failed=args.retry_failed,
                          progress=not args.no_progress and sys.stderr.isatty(), plots=not args.no_plots)
    except FwAssertionError:
        raise  # a broken framework invariant is a bug: its traceback is what to report
    except FprimeLiteError as exc:
        print(f"fprime-lite campaign: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"fprime-lite campaign: interrupted — the finished runs are in {out}; continue with "
              f"--out {out} --resume", file=sys.stderr)
        return 130
    print(f"results in {out}/results.parquet ({len(df)} runs)")
    return 0 if len(df) == 0 or (df["status"] == "ok").any() else 1
