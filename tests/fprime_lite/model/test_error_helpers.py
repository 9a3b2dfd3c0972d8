"""The message helpers every reader shares (fprime_lite.model.errors)."""

import pathlib

from fprime_lite.model.errors import closest, did_you_mean

SRC = pathlib.Path(__file__).resolve().parents[3] / "src" / "fprime_lite"


def test_did_you_mean_fills_the_template_with_the_closest_choice_or_says_otherwise():
    assert did_you_mean("GAINN", ["GAIN", "RATE"], "none") == "did you mean 'GAIN'?"
    assert did_you_mean("zzz", ["GAIN", "RATE"], "allowed: GAIN, RATE") == "allowed: GAIN, RATE"
    assert did_you_mean(12, ["12x"], "-", " — did you mean params.{}?") == " — did you mean params.12x?"
    assert did_you_mean("a", {}, "nothing to choose") == "nothing to choose"
    assert closest("--duraton", ["--duration", "--seed"]) == "--duration" and closest("x", ["--seed"]) is None


def test_the_framework_suggests_names_in_one_place():
    """Every did-you-mean of the topology, campaign and command-line readers comes from closest /
    did_you_mean (the plant's scenario reader, which may not import the framework, suggests none)."""
    users = sorted(str(p.relative_to(SRC)) for p in SRC.rglob("*.py") if "get_close_matches" in p.read_text())
    assert users == ["model/errors.py"]
