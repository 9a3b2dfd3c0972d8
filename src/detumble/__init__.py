"""The PROVES detumble application.

Modules (import what you need; this package imports nothing itself):

* :mod:`detumble.types` — F´ enums, structs and port types (Components / Drv / Fw namespaces).
* :mod:`detumble.bdot`, :mod:`detumble.strategy_selector`, :mod:`detumble.magnetorquer` — the
  control-law helpers, plain Python with no framework import.
* :mod:`detumble.detumble_manager` — the DetumbleManager component.
* :mod:`detumble.bdot_detumble` — the BDotDetumble dipole provider component.
* :mod:`detumble.sim` — the simulated spacecraft.
"""
