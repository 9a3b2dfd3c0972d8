"""The study scripts' shared command line (detumble.reports.study_table)."""

import json

from detumble.reports.study_table import table_script_main


def test_the_table_is_printed_and_kept_with_the_scripts_own_options(tmp_path, capsys):
    """STUDYCLI-001: the script's own option reaches its results, the table is printed, and --json keeps the figures
    (exit 0); without --json nothing is written."""
    def options(parser):
        parser.add_argument("--rows", type=int, default=1)

    results = lambda args: {"rows": list(range(args.rows))}  # noqa: E731 - a one-line stand-in for a study
    markdown = lambda table: f"{len(table['rows'])} rows\n"  # noqa: E731
    out = tmp_path / "sub" / "table.json"
    assert table_script_main(["--rows", "3", "--json", str(out)], "a study", results, markdown, options) == 0
    assert capsys.readouterr().out == "3 rows\n"
    assert json.loads(out.read_text(encoding="utf-8")) == {"rows": [0, 1, 2]}
    assert table_script_main([], "a study", results, markdown, options) == 0
    assert capsys.readouterr().out == "1 rows\n"
    assert sorted(p.name for p in tmp_path.rglob("*.json")) == ["table.json"]


def test_a_flying_script_takes_its_runs_folder_and_a_sibling_script_imports(tmp_path, capsys):
    """STUDYCLI-002: runs_table_script_main hands ``--runs DIR`` (default: the script's own) to the flights, and
    sibling_script imports a study script of a folder that is not a package, leaving sys.path as it was."""
    import sys

    from detumble.reports.study_table import runs_table_script_main, sibling_script

    seen = []

    def results(runs):
        seen.append(runs)
        return {"rows": [str(runs)]}

    default = tmp_path / "default_runs"
    assert runs_table_script_main([], "a study", results, lambda t: t["rows"][0] + "\n", default) == 0
    assert runs_table_script_main(["--runs", str(tmp_path / "mine")], "a study", results, lambda t: "x\n",
                                  default) == 0
    assert seen == [default, tmp_path / "mine"]
    (tmp_path / "scripts").mkdir()
    (tmp_path / "scripts" / "study_sibling_probe.py").write_text("VALUE = 41 + 1\n", encoding="utf-8")
    before = list(sys.path)
    assert sibling_script(tmp_path / "scripts", "study_sibling_probe").VALUE == 42
    assert sys.path == before
