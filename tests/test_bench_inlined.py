"""benchmarks/bench_inlined.py keeps working (each case runs once, with tiny loops; no timing is asserted)."""
import importlib.util
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[1]


def test_every_case_of_the_inlined_copies_benchmark_runs(capsys):
    """BENCH-INL-001: every case builds both variants (the written-out code is still where the case
    looks for it) and prints one line."""
    spec = importlib.util.spec_from_file_location("bench_inlined", ROOT / "benchmarks/bench_inlined.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert module.main(["--repeat", "1", "--scale", "1000"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert [line.split()[0] for line in lines] == list(module.CASES)
