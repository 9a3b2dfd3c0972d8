"""Scenario keys of the electrical power system (``power:``) and the accelerometer
(``sensors.accelerometer:``); called by :mod:`detumble.sim.scenario` with its validating section
reader, so errors read ``FILE:LINE: power.battery.capacity_wh: …`` like every other key."""

from __future__ import annotations

from detumble.sim.accelerometer import AccelerometerSpec
from detumble.sim.power import (SWITCH_NAMES, BatteryConfig, LoadConfig, PowerConfig, SolarConfig)

__all__ = ["parse_power", "parse_accelerometer", "POWER_SCHEMA", "ACCELEROMETER_SCHEMA"]

#: The keys of ``power:`` and ``sensors.accelerometer:`` for ``--set`` (sections dicts, leaves None).
POWER_SCHEMA = {
    "enabled": None, "switches_on": None,
    "battery": dict.fromkeys(("capacity_wh", "initial_soc", "internal_resistance_ohm", "cells_in_series")),
    "solar": dict.fromkeys(("panel_area_m2", "efficiency")),
    "loads": dict.fromkeys(("avionics_w", "face_board_w", "payload_power_w", "payload_battery_w", "burnwire_w")),
}
ACCELEROMETER_SCHEMA = dict.fromkeys(("ideal", "bias_mps2", "noise_std_mps2", "lsb_mps2", "full_scale_mps2",
                                      "lever_arm_m"))


def parse_accelerometer(s) -> AccelerometerSpec:
    d = AccelerometerSpec()
    spec = AccelerometerSpec(
        ideal=s.boolean("ideal", d.ideal),
        bias_mps2=s.vec3("bias_mps2", d.bias_mps2),
        noise_std_mps2=s.number("noise_std_mps2", d.noise_std_mps2, nonneg=True),
        lsb_mps2=s.number("lsb_mps2", d.lsb_mps2, nonneg=True),
        full_scale_mps2=s.number("full_scale_mps2", d.full_scale_mps2, positive=True),
        lever_arm_m=s.vec3("lever_arm_m", d.lever_arm_m),
    )
    s.finish()
    return spec


def parse_power(s) -> PowerConfig:
    d = PowerConfig()
    enabled = s.boolean("enabled", d.enabled)

    b = s.section("battery")
    db = d.battery
    soc = b.number("initial_soc", db.initial_soc, nonneg=True)
    if soc > 1.0:
        b.fail("initial_soc", f"state of charge is a fraction 0..1, got {soc}")
    cells = b.integer("cells_in_series", db.cells_in_series)
    if cells < 1:
        b.fail("cells_in_series", f"needs at least one cell, got {cells}")
    battery = BatteryConfig(capacity_wh=b.number("capacity_wh", db.capacity_wh, positive=True), initial_soc=soc,
                            internal_resistance_ohm=b.number("internal_resistance_ohm", db.internal_resistance_ohm,
                                                             nonneg=True),
                            cells_in_series=cells)
    b.finish()

    p = s.section("solar")
    dp = d.solar
    areas = p.raw("panel_area_m2", list(dp.panel_area_m2))
    if not isinstance(areas, (list, tuple)) or len(areas) != 6:
        p.fail("panel_area_m2", f"expected 6 areas in m² (X+, X-, Y+, Y-, Z+, Z-), got {areas!r}")
    areas = tuple(p.ctx.number(p.path + ("panel_area_m2", i), a, nonneg=True) for i, a in enumerate(areas))
    eff = p.number("efficiency", dp.efficiency, nonneg=True)
    if eff > 1.0:
        p.fail("efficiency", f"efficiency is a fraction 0..1, got {eff}")
    solar = SolarConfig(panel_area_m2=areas, efficiency=eff)
    p.finish()

    lo = s.section("loads")
    dl = d.loads
    loads = LoadConfig(avionics_w=lo.number("avionics_w", dl.avionics_w, nonneg=True),
                       face_board_w=lo.number("face_board_w", dl.face_board_w, nonneg=True),
                       payload_power_w=lo.number("payload_power_w", dl.payload_power_w, nonneg=True),
                       payload_battery_w=lo.number("payload_battery_w", dl.payload_battery_w, nonneg=True),
                       burnwire_w=lo.number("burnwire_w", dl.burnwire_w, nonneg=True))
    lo.finish()

    on = s.raw("switches_on", list(d.switches_on))
    if not isinstance(on, (list, tuple)) or any(name not in SWITCH_NAMES for name in on):
        s.fail("switches_on", f"expected a list of switch names from {list(SWITCH_NAMES)}, got {on!r}")
    s.finish()
    return PowerConfig(enabled=enabled, battery=battery, solar=solar, loads=loads, switches_on=tuple(on))
