"""A pytest plugin that lets the test API's ZMQ link to the ground system settle before the first test.

``fprime-lite conformance`` loads it (``-p fprime_lite.testing.link_settle``). fprime-gds's test API
publishes what it sends (commands, file-uplink packets) on a ZMQ PUB socket that *connects* to the
ground system's bound SUB socket. A PUB socket drops every message published before the
subscriber's subscription has reached it (ZMQ's "slow joiner"), so a suite whose first test sends
within milliseconds of the API's creation — F´'s FileHandling suite uplinks a file first — can lose
its first packets and wait for a completion that never comes. A person at the GDS's browser
never sends that fast; a suite does. The plugin waits ``--fprime-lite-link-settle`` seconds
(default 1.0) once, after the session's API is built and before its first test; it sends nothing,
so no suite's command counts or histories change.
"""

from __future__ import annotations

import time

import pytest

OPTION = "--fprime-lite-link-settle"


def pytest_addoption(parser):
    parser.addoption(OPTION, type=float, default=1.0, metavar="SECONDS",
                     help="seconds to wait after the test API connects, before the first test (default 1.0)")


@pytest.fixture(scope="session", autouse=True)
def _fprime_lite_link_settled(request):
    """Once a session: build the API (fprime-gds's session fixture), then give its PUB socket time to
    learn the ground system's subscription."""
    if not _suite_uses_the_api(request):
        return
    request.getfixturevalue("fprime_test_api_session")
    time.sleep(max(0.0, request.config.getoption(OPTION)))


def _suite_uses_the_api(request) -> bool:
    return any("fprime_test_api" in getattr(item, "fixturenames", ()) for item in request.session.items)
