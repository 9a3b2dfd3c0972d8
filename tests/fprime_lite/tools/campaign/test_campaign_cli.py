"""`fprime-lite campaign`: user mistakes give a message and exit status 2, never a traceback."""

from __future__ import annotations

from fprime_lite.tools.cli import main


def test_bad_campaign_file_is_reported_without_a_traceback(write_campaign, capsys):
    """CAMP-070: an unknown key exits 2 with the file:line message on stderr and no traceback."""
    path = write_campaign("campaign: x\nrun: {kind: plant, scenario: default}\nsedes: 2\n")
    assert main(["campaign", str(path), "--workers", "1"]) == 2
    err = capsys.readouterr().err
    assert f"{path}:3: unknown key 'sedes' in the campaign file — did you mean 'seeds'?" in err
    assert "Traceback" not in err


def test_missing_file_and_conflicting_options(tmp_path, capsys, write_campaign):
    """CAMP-071: a missing file, --resume without --out, and --workers with --scheduler are refused."""
    assert main(["campaign", str(tmp_path / "nope.yaml")]) == 2
    assert "no such campaign file" in capsys.readouterr().err
    path = write_campaign("campaign: x\nrun: {kind: plant, scenario: default}\n")
    assert main(["campaign", str(path), "--resume"]) == 2
    assert "--resume needs --out" in capsys.readouterr().err
    assert main(["campaign", str(path), "--workers", "1", "--scheduler", "tcp://127.0.0.1:1"]) == 2
    assert "not allowed with argument" in capsys.readouterr().err
