"""pytest plugin (entry point ``fprime_lite``): the ``fprime_harness`` fixture.

    def test_run(fprime_harness):
        h = fprime_harness(MyComponent("comp", base_id=0x100))
        h.invoke("run", 0)

Harnesses made by the fixture are closed (active threads stopped) when the test ends.
"""

from __future__ import annotations

import pytest

from fprime_lite.testing.harness import ComponentHarness


@pytest.fixture
def fprime_harness():
    """A factory: ``fprime_harness(component, test_time=None) -> ComponentHarness``."""
    made: list[ComponentHarness] = []

    def make(component, **kwargs) -> ComponentHarness:
        harness = ComponentHarness(component, **kwargs)
        made.append(harness)
        return harness

    yield make
    for harness in made:
        harness.close()
