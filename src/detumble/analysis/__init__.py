"""Post-processing of runs: settling and detumble metrics on sampled time series (numpy; no
framework import)."""
