"""Testing support: the component port harness and its pytest fixture."""

from fprime_lite.testing.harness import (CommandResponseRecord, ComponentHarness, EventRecord, PortCall,
                      TelemetryRecord, TextEventRecord)

__all__ = ["ComponentHarness", "PortCall", "CommandResponseRecord", "EventRecord", "TextEventRecord",
           "TelemetryRecord"]
