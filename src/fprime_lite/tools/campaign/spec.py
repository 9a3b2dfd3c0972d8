"""The campaign file: parsing and validation (``docs/campaigns.md`` gives the format).

Parsed with the topology loader's line-keeping SafeLoader; every problem is reported at once as
``file:line: what is wrong — what to do``, and unknown keys are refused (with a did-you-mean).
"""

from __future__ import annotations

import math
import pathlib
from dataclasses import dataclass, field

from fprime_lite.model.errors import did_you_mean
from fprime_lite.tools.campaign.dispersions import Dispersion, parse_dispersion
from fprime_lite.tools.campaign.errors import CampaignError
from fprime_lite.tools.campaign.grid import axis_values
from fprime_lite.tools.campaign.keep import KEEP_FIELDS, KEEP_MODES, KeepPolicy

__all__ = ["Campaign", "load_campaign", "TOP_KEYS", "PLOT_TYPES"]

TOP_KEYS = {"campaign", "description", "run", "grid", "dispersions", "seeds", "master_seed", "metrics",
            "timeout_s", "keep", "plots", "common_random_numbers"}
PLOT_TYPES = {"line": {"x", "metric"}, "heatmap": {"x", "y", "metric"}, "histogram": {"metric"},
              "cdf": {"metric"}}
PLOT_KEYS = {"type", "x", "y", "metric", "agg", "percentiles"}


@dataclass
class Campaign:
    """A validated campaign file."""

    path: pathlib.Path
    text: str
    name: str
    description: str
    kind: str
    run: dict
    grids: list[dict[str, list]]
    dispersions: dict[str, Dispersion]
    dispersion_specs: dict
    seeds: int
    master_seed: int
    metrics: list[str]
    timeout_s: float | None
    keep: KeepPolicy
    plots: list[dict]
    common_random_numbers: bool = False
    where: dict[str, str] = field(default_factory=dict)  # campaign key → "file:line"
    #: ``PREFIX.*`` entries of 'metrics' → the named metrics they stand for (already in ``metrics``)
    metric_groups: dict[str, list[str]] = field(default_factory=dict)

    @property
    def base_dir(self) -> pathlib.Path:
        return self.path.parent.resolve()

    @property
    def grid_keys(self) -> list[str]:
        keys: list[str] = []
        for g in self.grids:
            keys += [k for k in g if k not in keys]
        return keys

    @property
    def varied_keys(self) -> list[str]:
        return self.grid_keys + [k for k in self.dispersions if k not in self.grid_keys]


def _plain(value):
    """YAML nodes with line numbers → plain dicts, lists and scalars (picklable for workers)."""
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_plain(v) for v in value]
    return value


class _Checker:
    def __init__(self, path: pathlib.Path):
        self.path = path
        self.problems: list[str] = []

    def at(self, line) -> str:
        return f"{self.path}:{line if line is not None else '?'}"

    def problem(self, line, message: str) -> None:
        self.problems.append(f"{self.at(line)}: {message}")

    def keys(self, mapping, allowed, what: str) -> None:
        from fprime_lite.deploy.topology_yaml.problems import unknown_key_message

        for key in mapping:
            if key not in allowed:  # (named as text: a campaign quotes a number key too)
                self.problem(mapping.key_lines.get(key), unknown_key_message(str(key), allowed, what))


def _keep_policy(c: _Checker, raw, key_line, metric_names: list[str]) -> KeepPolicy:
    """``keep``: none / failed / all, or {best: N, worst: N, by: METRIC, order: min|max, failed: bool}."""
    from fprime_lite.deploy.topology_yaml.parse import YMap

    usage = (f"'keep' (per-run files kept) is one of {', '.join(KEEP_MODES)}, or a policy "
             f"{{best: N, worst: N, by: METRIC, order: min|max, failed: true|false, every: N}}")
    if isinstance(raw, str) and raw in KEEP_MODES:
        return KeepPolicy(mode=raw)
    if not isinstance(raw, YMap):
        c.problem(key_line, f"{usage}, got {raw!r}" + did_you_mean(str(raw), KEEP_MODES, "", " — did you mean '{}'?"))
        return KeepPolicy()
    c.keys(raw, KEEP_FIELDS, "'keep'")
    at = lambda k: raw.key_lines.get(k, raw.line)  # noqa: E731
    counts = {}
    for k in ("best", "worst", "every"):
        v = raw.get(k, 0)
        if k in raw and (isinstance(v, bool) or not isinstance(v, int) or v < 1):
            what = "keep one run in N" if k == "every" else "how many runs to keep"
            c.problem(at(k), f"'keep: {k}' is {what}, a whole number >= 1, got {v!r}")
            v = 0
        counts[k] = v
    failed = raw.get("failed", False)
    if not isinstance(failed, bool):
        c.problem(at("failed"), f"'keep: failed' is true or false, got {failed!r}")
        failed = False
    if not ({"best", "worst", "every"} & set(raw)) and failed is not True:
        c.problem(raw.line, f"a 'keep' policy needs 'best: N', 'worst: N', 'every: N' or 'failed: true' — {usage}")
    by = raw.get("by")
    ranked = bool({"best", "worst"} & set(raw))
    if by is None:
        if ranked:
            c.problem(raw.line, "a ranking 'keep' (best/worst) needs 'by: METRIC' (one of the campaign's 'metrics')")
    elif by not in metric_names:
        c.problem(at("by"), f"'keep: by' {by!r} is not in 'metrics'"
                  + did_you_mean(by, metric_names, f" ({', '.join(metric_names) or 'none given'})",
                                 " — did you mean '{}'?"))
    order = raw.get("order", "min")
    if order not in ("min", "max"):
        c.problem(at("order"), f"'keep: order' is min (smaller is better) or max (larger is better), got {order!r}")
        order = "min"
    return KeepPolicy(mode="ranked", best=counts["best"], worst=counts["worst"], by=by, order=order, failed=failed,
                      every=counts["every"])


def _numeric_axis(key: str, grids: list[dict[str, list]], dispersions: dict) -> str | None:
    """None when ``key`` takes numbers only (a grid axis, or a scalar dispersion), else why not."""
    values = [v for g in grids for v in g.get(key, [])]
    if key in dispersions:
        values = list(dispersions[key].nominals)
    if not values:
        return "is not a varied key of this campaign"
    bad = next((v for v in values if isinstance(v, bool) or not isinstance(v, (int, float))), None)
    if bad is not None:
        return f"takes the value {bad!r}, not a number: a plot axis needs numbers (group by it in pandas instead)"
    return None


def _check_plot(c: _Checker, p, grids, dispersions, metric_names) -> None:
    """One entry of 'plots': its type, axes (numeric varied keys; a heatmap's on the grid), metric,
    ``agg`` (heatmap) and ``percentiles`` (line: the band, two numbers 0–100)."""
    from fprime_lite.tools.campaign.plots import AGGREGATE_NAMES, aggregate

    c.keys(p, PLOT_KEYS, "a plot")
    at = lambda k: p.key_lines.get(k, p.line)  # noqa: E731
    ptype = p.get("type")
    if ptype not in PLOT_TYPES:
        c.problem(at("type"), f"plot type {ptype!r}: use one of {', '.join(PLOT_TYPES)}"
                  + did_you_mean(str(ptype), PLOT_TYPES, "", " — did you mean '{}'?"))
        return
    for k in sorted(PLOT_TYPES[ptype] - set(p)):
        c.problem(p.line, f"a {ptype} plot needs '{k}'")
    for k in ("x", "y"):
        if k not in p:
            continue
        if k not in PLOT_TYPES[ptype]:
            c.problem(at(k), f"a {ptype} plot has no '{k}' (it takes {', '.join(sorted(PLOT_TYPES[ptype]))})")
            continue
        varied = [key for g in grids for key in g] + list(dispersions)
        if p[k] not in varied:
            c.problem(at(k), f"plot {k} '{p[k]}' is not a varied key of this campaign"
                      + did_you_mean(str(p[k]), varied, "", " — did you mean '{}'?"))
            continue
        if ptype == "heatmap" and p[k] in dispersions:
            c.problem(at(k), f"heatmap {k} '{p[k]}' is dispersed: a heatmap's axes are grid keys")
            continue
        why = _numeric_axis(p[k], grids, dispersions)
        if why:
            c.problem(at(k), f"plot {k} '{p[k]}' {why}")
    if ptype == "heatmap" and p.get("x") is not None and p.get("x") == p.get("y"):
        c.problem(at("y"), "a heatmap's x and y must be two different keys")
    if "metric" in p and p["metric"] not in metric_names:
        c.problem(at("metric"), f"plot metric '{p['metric']}' is not in 'metrics'"
                  + did_you_mean(str(p["metric"]), metric_names, f" ({', '.join(metric_names) or 'none given'})",
                                 " — did you mean '{}'?"))
    if "agg" in p:
        if ptype != "heatmap":
            c.problem(at("agg"), f"'agg' is a heatmap's (a {ptype} plot has none)")
        elif aggregate(p["agg"]) is None:
            c.problem(at("agg"), f"heatmap agg {p['agg']!r}: use one of {', '.join(AGGREGATE_NAMES)} or pNN "
                                 "(a percentile, e.g. p90)"
                      + did_you_mean(str(p["agg"]), AGGREGATE_NAMES, "", " — did you mean '{}'?"))
    if "percentiles" in p:
        q = p["percentiles"]
        if ptype != "line":
            c.problem(at("percentiles"), f"'percentiles' is a line plot's band (a {ptype} plot has none)")
        elif not (isinstance(q, list) and len(q) == 2 and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                                for v in q) and 0 <= q[0] < q[1] <= 100):
            c.problem(at("percentiles"), f"'percentiles' is [low, high] with 0 <= low < high <= 100, got {q!r}")


def _expand_metric_groups(c: _Checker, names: list[str], at, named_metrics) -> tuple[list[str], dict[str, list[str]]]:
    """Replace each ``PREFIX.*`` entry of 'metrics' by the installed named metrics ``PREFIX.…``, in
    their registration order; return the expanded list and ``{entry: [names]}``."""
    if not any(n.endswith(".*") for n in names):
        return names, {}
    installed = list(named_metrics())
    expanded: list[str] = []
    groups: dict[str, list[str]] = {}
    for name in names:
        if not name.endswith(".*"):
            expanded.append(name)
            continue
        prefix = name[:-1]
        members = [m for m in installed if m.startswith(prefix)]
        if not members:
            roots = sorted({m.split(".")[0] + ".*" for m in installed if "." in m})
            c.problem(at, f"metric group '{name}' matches no installed named metric"
                          + (f" (groups: {', '.join(roots)})" if roots else ""))
            continue
        groups[name] = members
        expanded += members
    return expanded, groups


def load_campaign(path) -> Campaign:
    """Read and validate a campaign file; raise :class:`CampaignError` listing every problem."""
    from fprime_lite.deploy.topology import TopologyError
    from fprime_lite.deploy.topology_yaml.parse import YMap, parse_yaml
    from fprime_lite.tools.campaign.kinds import metrics as named_metrics
    from fprime_lite.tools.campaign.kinds import resolve_kind, run_kinds

    path = pathlib.Path(path)
    if not path.is_file():
        raise CampaignError([f"{path}: no such campaign file — give the path of a campaign YAML file "
                             f"(examples in campaigns/)"])
    try:
        doc = parse_yaml(path)
    except TopologyError as exc:
        raise CampaignError(exc.problems) from None
    c = _Checker(path)
    if not isinstance(doc, YMap):
        raise CampaignError([f"{path}:1: a campaign file is a mapping (campaign:, run:, grid:, ...)"])
    c.keys(doc, TOP_KEYS, "the campaign file")
    line = doc.key_lines.get

    name = doc.get("campaign")
    if not isinstance(name, str) or not name.strip():
        c.problem(line("campaign", doc.line), "'campaign' must name the campaign (a short string)")
        name = "campaign"
    description = doc.get("description", "")

    kinds = run_kinds()
    run = doc.get("run")
    kind_name, kind = None, None
    if not isinstance(run, YMap):
        c.problem(line("run", doc.line), "'run' must be a mapping with 'kind' (one of "
                                         f"{', '.join(sorted(kinds))}) and the kind's fields")
        run = YMap()
        run.key_lines = {}
    else:
        kind_name = run.get("kind")
        kind = kinds.get(kind_name) if isinstance(kind_name, str) else None
        if kind is None and isinstance(kind_name, str) and ":" in kind_name:
            try:
                kind = resolve_kind(kind_name)
            except LookupError as exc:
                c.problem(run.key_lines.get("kind", run.line), f"{exc} — give module.path:NAME of a RunKind "
                                                               f"importable on every worker")
        elif kind is None:
            hint = did_you_mean(kind_name, sorted(kinds), f"installed kinds: {', '.join(sorted(kinds))}")
            c.problem(run.key_lines.get("kind", run.line), f"unknown run kind {kind_name!r} — {hint}")
        else:
            c.keys(run, kind.fields | {"kind"}, f"the '{kind_name}' run section")
            for req in sorted(kind.required - set(run)):
                c.problem(run.line, f"the '{kind_name}' run section needs '{req}'")

    where: dict[str, str] = {"metrics": c.at(line("metrics", doc.line))}
    if isinstance(run, YMap):
        for key in run:  # a run-section field at fault (stop_on_events, topology…) is reported at its line
            where[str(key)] = c.at(run.key_lines.get(key, run.line))

    def check_varied(key, key_line) -> bool:
        where[str(key)] = c.at(key_line)
        if kind is None:
            return True
        problem = kind.check_key(str(key))
        if problem:
            c.problem(key_line, f"'{key}' cannot be varied: {problem}")
            return False
        return True

    grids: list[dict[str, list]] = []
    raw_grid = doc.get("grid")
    if raw_grid is not None:
        parts = raw_grid if isinstance(raw_grid, list) else [raw_grid]
        for part in parts:
            if not isinstance(part, YMap):
                c.problem(getattr(part, "line", line("grid")), "'grid' is a mapping of key: axis, or a list of them")
                continue
            grid = {}
            for key, axis in part.items():
                kl = part.key_lines.get(key)
                if not check_varied(key, kl):
                    continue
                try:
                    grid[str(key)] = _plain(axis_values(_plain(axis)))
                except ValueError as exc:
                    c.problem(kl, f"grid axis '{key}': {exc}")
            grids.append(grid)

    dispersions: dict[str, Dispersion] = {}
    dispersion_specs = {}
    raw_disp = doc.get("dispersions")
    if raw_disp is not None:
        if not isinstance(raw_disp, YMap):
            c.problem(line("dispersions"), "'dispersions' is a mapping of key: {dist: ..., ...}")
        else:
            grid_keys = {k for g in grids for k in g}
            for key, spec in raw_disp.items():
                kl = raw_disp.key_lines.get(key)
                if not check_varied(key, kl):
                    continue
                if key in grid_keys:
                    c.problem(kl, f"'{key}' is both on the grid and dispersed — choose one")
                    continue
                try:
                    dispersions[str(key)] = parse_dispersion(_plain(spec), str(key))
                    dispersion_specs[str(key)] = _plain(spec)
                except ValueError as exc:
                    c.problem(kl, f"dispersion '{key}': {exc}")

    def integer(key, default, minimum):
        value = doc.get(key, default)
        if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
            c.problem(line(key), f"'{key}' must be a whole number >= {minimum}, got {value!r}")
            return default
        return value

    seeds = integer("seeds", 1, 1)
    master_seed = integer("master_seed", 0, 0)

    metric_names = doc.get("metrics", [])
    if not (isinstance(metric_names, list) and all(isinstance(m, str) for m in metric_names)):
        c.problem(line("metrics"), "'metrics' is a list of names: run-summary keys or named metrics "
                                   f"({', '.join(sorted(named_metrics())) or 'none installed'})")
        metric_names = []
    metric_names, metric_groups = _expand_metric_groups(c, metric_names, line("metrics"), named_metrics)
    if len(set(metric_names)) != len(metric_names):
        c.problem(line("metrics"), "'metrics' names a metric twice")

    timeout = doc.get("timeout_s")
    if timeout is not None and not (isinstance(timeout, (int, float)) and not isinstance(timeout, bool)
                                    and math.isfinite(timeout) and timeout > 0):
        c.problem(line("timeout_s"), f"'timeout_s' must be a positive number of wall-clock seconds, got {timeout!r}")
        timeout = None
    crn = doc.get("common_random_numbers", False)
    if not isinstance(crn, bool):
        c.problem(line("common_random_numbers"), f"'common_random_numbers' is true or false, got {crn!r}")
        crn = False
    keep = _keep_policy(c, doc.get("keep", "none"), line("keep"), metric_names)

    plots = []
    raw_plots = doc.get("plots", [])
    if not isinstance(raw_plots, list):
        c.problem(line("plots"), "'plots' is a list of {type: line|heatmap|histogram|cdf, x:, y:, metric:}")
        raw_plots = []
    for p in raw_plots:
        if not isinstance(p, YMap):
            c.problem(getattr(p, "line", line("plots")), "a plot is a mapping {type: ..., metric: ...}")
            continue
        _check_plot(c, p, grids, dispersions, metric_names)
        plots.append(_plain(p))

    if c.problems:
        raise CampaignError(c.problems)
    return Campaign(path=path, text=path.read_text(encoding="utf-8"), name=name.strip(),
                    description=str(description or ""), kind=str(kind_name), run=_plain(run), grids=grids or [{}],
                    dispersions=dispersions, dispersion_specs=dispersion_specs, seeds=seeds,
                    master_seed=master_seed, metrics=list(metric_names), timeout_s=timeout, keep=keep,
                    plots=plots, common_random_numbers=crn, where=where,
                    metric_groups=metric_groups)
