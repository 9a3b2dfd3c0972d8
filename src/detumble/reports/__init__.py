"""What the application makes of a run: report resources, plots, the power budget and metrics.

* report resources (a topology's ``resources:``, role ``report``): :mod:`.detumble_report`
  (``truth.csv``, the detumble figures of ``summary.json``), :mod:`.attitude_report` (``attitude.csv``),
  :mod:`.coursework_report`;
* plots: :mod:`.plots` (``fprime-lite plot RUN_DIR``), :mod:`.power_budget` (``power.png`` and the
  ``power`` summary), :mod:`.figures` (what they share: ``truth.csv`` read for plotting, a PNG saved whole);
* campaign plug-ins: :mod:`.campaign` (the ``plant`` run kind and the detumble metrics),
  :mod:`.pointing_metrics` (the attitude-control metrics).
"""
