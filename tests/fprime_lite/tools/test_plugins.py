"""Application verbs and bench pieces reach the tools through entry points."""
from __future__ import annotations

import importlib.metadata

import pytest

from fprime_lite.tools import plugins
from fprime_lite.tools.cli import main
from fprime_lite.tools.plugins import PluginError, Verb


class _EntryPoint:
    def __init__(self, name, obj=None, error=None):
        self.name, self.value, self._obj, self._error = name, f"fake.module:{name}", obj, error

    def load(self):
        if self._error:
            raise self._error
        return self._obj


def _fake_group(monkeypatch, found):
    monkeypatch.setattr(plugins, "entry_points", lambda group: found if group == plugins.VERBS_GROUP else [])


def test_an_installed_verb_is_run_with_its_own_arguments(monkeypatch):
    """PLUG-001: `fprime-lite NAME ARGS` calls the verb an entry point provides, with ARGS."""
    seen = []
    _fake_group(monkeypatch, [_EntryPoint("hello", Verb("hello", "say hello", lambda argv: seen.append(argv) or 7))])
    assert main(["hello", "--loud", "x"]) == 7
    assert seen == [["--loud", "x"]]


def test_a_broken_plug_in_is_named_with_what_to_do(monkeypatch):
    """PLUG-002: a plug-in that fails to import, or is not a Verb, is reported by name."""
    _fake_group(monkeypatch, [_EntryPoint("broken", error=ImportError("no module named fake"))])
    with pytest.raises(PluginError, match=r"'broken' .*cannot be loaded: no module named fake — reinstall"):
        plugins.verbs()
    _fake_group(monkeypatch, [_EntryPoint("odd", obj=42)])
    with pytest.raises(PluginError, match=r"'odd' .* is a int, not a Verb"):
        plugins.verbs()


def test_the_detumble_application_provides_sim():
    """PLUG-004: the installed package declares `sim` as an application verb (not a built-in)."""
    names = {ep.name for ep in importlib.metadata.entry_points(group=plugins.VERBS_GROUP)}
    assert "sim" in names
    from fprime_lite.tools.cli import BUILT_IN
    assert "sim" not in BUILT_IN
