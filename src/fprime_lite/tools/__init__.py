"""The tools around a deployment: the runner, the command line, the benchmark, the GDS app."""
