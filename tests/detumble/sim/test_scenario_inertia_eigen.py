"""The eigenvalues that check a scenario's inertia (``scenario.symmetric_eigenvalues``):
they match numpy's ``eigvalsh`` (the check's reference, which loading a scenario no longer imports)."""

from __future__ import annotations

import subprocess
import sys

import numpy as np

from detumble.sim.scenario import symmetric_eigenvalues


def _matrices():
    rng = np.random.default_rng(32)
    for i in range(600):
        a = rng.normal(size=(3, 3)) * 10 ** rng.uniform(-4, 1)
        if i % 3 == 0:
            m = a @ a.T
        elif i % 3 == 1:
            m = a + a.T
        else:
            m = np.diag(rng.uniform(1e-3, 3e-3, 3)) + 1e-6 * (a + a.T)
        yield tuple(tuple(float(x) for x in row) for row in m)
    yield ((2.2e-3, 1e-5, -2e-5), (1e-5, 2.1e-3, 3e-6), (-2e-5, 3e-6, 2.0e-3))  # a CubeSat's small products
    yield ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))                  # a triple eigenvalue
    yield ((2.0, 1.0, 0.0), (1.0, 2.0, 0.0), (0.0, 0.0, 3.0))                  # a double one, not diagonal


def test_jacobi_eigenvalues_match_numpy():
    """SCN-EIG-001: ascending, and within 1e-12 of the largest eigenvalue's magnitude of eigvalsh."""
    for j in _matrices():
        ours = symmetric_eigenvalues(j)
        ref = sorted(np.linalg.eigvalsh(np.array(j)).tolist())
        assert ours == sorted(ours), j
        scale = max(abs(x) for x in ref)
        assert max(abs(x - y) for x, y in zip(ours, ref, strict=True)) <= 1e-12 * scale, (j, ours, ref)


def test_a_diagonal_matrix_gives_its_diagonal_exactly():
    """SCN-EIG-002."""
    j = ((3.0e-3, 0.0, 0.0), (0.0, 1.0e-3, 0.0), (0.0, 0.0, 2.0e-3))
    assert symmetric_eigenvalues(j) == [1.0e-3, 2.0e-3, 3.0e-3]


def test_loading_the_default_scenario_imports_no_numpy():
    """SCN-EIG-003: what the check is for (numpy's import was ~0.1 s of every ``fprime-lite run``)."""
    code = ("import sys; from detumble.sim.scenario import load_scenario; load_scenario('default'); "
            "print('numpy' in sys.modules)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "False"
