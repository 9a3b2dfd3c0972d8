"""The PROVES detumble application.

Layers, lowest first (docs/architecture.md; import what you need, this package imports nothing itself):

* :mod:`detumble.control` and :mod:`detumble.analysis` — control laws, flight arithmetic and metrics on
  sampled series, plain Python with no framework import;
* :mod:`detumble.sim` — the plant of the simulated spacecraft (no framework import);
* :mod:`detumble.components` — the flight components (DetumbleManager, BDotDetumble, AttitudeController,
  CourseworkController) and their F´ types (:mod:`detumble.components.types`);
* :mod:`detumble.drivers` — the simulated drivers and the spacecraft they drive;
* :mod:`detumble.proves` — the PROVES flight components as flown (mode manager, IMU, power, housekeeping);
* :mod:`detumble.reports` — run reports, plots, the power budget and campaign metrics;
* :mod:`detumble.tools` — the ``sim`` verb and the bench pieces of ``fprime-lite``;
* :mod:`detumble.errors` — ``DetumbleError``, the root of the application's errors (imports nothing).
"""
