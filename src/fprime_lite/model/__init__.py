"""The F´ component model: types, time, ports, components, commands, events, telemetry, parameters."""
