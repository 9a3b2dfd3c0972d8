"""The README's code blocks run as written."""

import pathlib
import re
import sys
import types

from fprime_lite.testing import ComponentHarness

README = pathlib.Path(__file__).parents[1] / "README.md"


def python_blocks() -> list[str]:
    return re.findall(r"```python\n(.*?)```", README.read_text(), flags=re.S)


def test_readme_component_and_harness_example_work():
    blocks = python_blocks()
    assert len(blocks) >= 2
    module = types.ModuleType("readme_example")
    sys.modules[module.__name__] = module
    try:
        exec(compile("\n".join(blocks), str(README), "exec"), module.__dict__)  # noqa: S102 - our own README
        made = []
        module.test_too_cold(lambda comp, **kw: made.append(ComponentHarness(comp, **kw)) or made[-1])
        assert made and made[0].component.SETPOINT.value == 10.0
    finally:
        del sys.modules[module.__name__]
