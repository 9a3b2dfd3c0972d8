"""Campaigns: gain sweeps and Monte Carlo of the flight software on Dask (``docs/campaigns.md``).

``run_campaign(FILE, workers=N | scheduler=ADDR, out=DIR, resume=False)`` returns the results as a
pandas DataFrame; ``read_results(DIR)`` reads a finished (or interrupted) campaign folder.
"""

from fprime_lite.tools.campaign.engine import run_campaign
from fprime_lite.tools.campaign.errors import CampaignError, CampaignInterrupted, MetricUnavailable, RunSetupError
from fprime_lite.tools.campaign.kinds import Metric, Prepared, RunKind, RunOutput, RunRequest
from fprime_lite.tools.campaign.results import read_results
from fprime_lite.tools.campaign.spec import load_campaign

__all__ = ["run_campaign", "read_results", "load_campaign", "CampaignError", "CampaignInterrupted", "RunSetupError",
           "MetricUnavailable", "RunKind", "RunRequest", "Prepared", "RunOutput", "Metric"]
