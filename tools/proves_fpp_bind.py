"""Bind PROVES's own component FPP files to fprime-lite's implementations and list what differs.

Run: ``python tools/proves_fpp_bind.py CHECKOUT`` where CHECKOUT is a clone of
Open-Source-Space-Foundation/proves-core-reference (not fetched here: CI has no network). Prints
the number of refusals, per component, and each refusal (FPP file:line: what differs — Python
file:line); exit 0 when everything binds, 1 otherwise. docs/fpp.md "PROVES's own component FPP"
gives the result measured for issue 30.
"""

from __future__ import annotations

import argparse
import collections
import os
import sys
import time

from fprime_lite.deploy.fpp.loader import FppError, check_components

#: PROVES FPP file (under PROVESFlightControllerReference/Components) -> fprime-lite's implementation
BINDINGS = {
    "DetumbleManager/DetumbleManager.fpp": ("Components.DetumbleManager",
                                            "detumble.components.detumble_manager.DetumbleManager"),
    "ImuManager/ImuManager.fpp": ("Components.ImuManager", "detumble.proves.imu_manager.ImuManager"),
    "ModeManager/ModeManager.fpp": ("Components.ModeManager", "detumble.proves.mode_manager.ModeManager"),
    "LoadSwitch/LoadSwitch.fpp": ("Components.LoadSwitch", "detumble.proves.load_switch.LoadSwitch"),
    "PowerMonitor/PowerMonitor.fpp": ("Components.PowerMonitor", "detumble.proves.power_monitor.PowerMonitor"),
    "ResetManager/ResetManager.fpp": ("Components.ResetManager", "detumble.proves.reset_manager.ResetManager"),
    "StartupManager/StartupManager.fpp": ("Components.StartupManager",
                                          "detumble.proves.startup_manager.StartupManager"),
    "Watchdog/Watchdog.fpp": ("Components.Watchdog", "detumble.proves.watchdog.Watchdog"),
    "Drv/Ina219Manager/Ina219Manager.fpp": ("Drv.Ina219Manager", "detumble.proves.ina219_manager.Ina219Manager"),
    "Drv/RtcManager/RtcManager.fpp": ("Drv.RtcManager", "detumble.proves.rtc_manager.RtcManager"),
}
#: read for their definitions only (the Drv types; the magnetorquer ports are in Drv2605Manager.fpp)
SOURCES_TOO = ["Drv/Types/Types.fpp"]
IMPORTS = ["Drv/Drv2605Manager/Drv2605Manager.fpp"]


def _class(dotted: str) -> type:
    import importlib

    module, _, name = dotted.rpartition(".")
    return getattr(importlib.import_module(module), name)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("checkout", help="a clone of proves-core-reference")
    args = parser.parse_args()
    folder = os.path.join(args.checkout, "PROVESFlightControllerReference", "Components")
    files = [os.path.join(folder, f) for f in list(BINDINGS) + SOURCES_TOO]
    implementations = {fpp: _class(py) for fpp, py in BINDINGS.values()}
    start = time.perf_counter()
    try:
        bound = check_components(files, imports=[os.path.join(folder, f) for f in IMPORTS],
                                 implementations=implementations)
    except FppError as exc:
        print(f"{len(exc.problems)} refusals ({time.perf_counter() - start:.2f} s)")
        per = collections.Counter(p.split(": ")[1] for p in exc.problems if ": " in p)
        for name, count in per.most_common():
            print(f"  {name}: {count}")
        for problem in exc.problems:
            print(problem)
        return 1
    print(f"all {len(bound)} components bind ({time.perf_counter() - start:.2f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
