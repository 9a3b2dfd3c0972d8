"""The PROVES detumble application.

Modules (import what you need; this package imports nothing itself):

* :mod:`detumble.components.types` — F´ enums, structs and port types (Components / Drv / Fw namespaces).
* :mod:`detumble.control.bdot`, :mod:`detumble.control.strategy_selector`, :mod:`detumble.control.magnetorquer` — the
  control-law helpers, plain Python with no framework import.
* :mod:`detumble.components.detumble_manager` — the DetumbleManager component.
* :mod:`detumble.components.bdot_detumble` — the BDotDetumble dipole provider component.
* :mod:`detumble.sim` — the simulated spacecraft.
"""
