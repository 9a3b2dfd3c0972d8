"""benchmarks/bench_power_step.py keeps working and times the same work both ways (no timing is asserted)."""
import importlib.util
import pathlib

import pytest

from detumble.sim import plant_kernel

ROOT = pathlib.Path(__file__).resolve().parents[1]


def _bench():
    spec = importlib.util.spec_from_file_location("bench_power_step", ROOT / "benchmarks/bench_power_step.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _state(eps, thermal):
    return [repr(v) for obj in (eps, eps.battery, thermal) for k, v in vars(obj).items() if k not in ("cfg", "battery")]


def test_both_variants_of_the_power_step_benchmark_do_the_same_steps():
    """BENCH-034: the Python and the compiled step the benchmark times leave their models in the same state
    after the same number of steps, and the state moved (the timed calls integrate, from where the last left)."""
    if plant_kernel.load().module is None:
        pytest.skip("no compiled kernel on this machine")
    python_step, compiled_step, (py, c) = _bench().steppers()
    start = _state(*py)
    for _ in range(50):
        python_step()
        compiled_step()
    assert _state(*py) == _state(*c) != start
    assert py[0].solar_j > 0.0 and py[0].coil_j > 0.0


def test_the_power_step_benchmark_prints_both_figures(capsys):
    """BENCH-035: ``main`` with tiny loops prints a line a variant and the saving (the kernel built here)."""
    if plant_kernel.load().module is None:
        pytest.skip("no compiled kernel on this machine")
    best = _bench().main(["--repeat", "1", "--number", "10"])
    assert set(best) == {"python", "compiled"} and all(0.0 < v < float("inf") for v in best.values())
    assert [line.split()[0] for line in capsys.readouterr().out.splitlines()] == ["python", "compiled", "saved"]
