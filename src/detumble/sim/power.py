"""The spacecraft's electrical power system: solar panels per face, a Li-ion battery, switched loads.

Pure physics (no framework import). One :class:`ElectricalSystem` is stepped with the plant; the
simulated INA219 monitors read its bus and array figures, and the simulated load switches open and
close its switched loads.

Model
-----
* **Solar array** — a panel per face ``i`` with area ``A_i`` (m²) and cell efficiency ``η``:
  ``P_sol = S/d² · η · Σ A_i · max(0, n_i · s_B)`` outside the Earth's cylindrical shadow, 0 inside
  (``S`` the solar constant, ``d`` the Earth–Sun distance in AU, ``s_B`` the Sun direction in body
  axes, ``n_i`` the face's outward normal). The array feeds the bus directly; when the battery is
  full the charge regulator shunts what the loads do not take (counted as ``shunted``).
* **Loads** — an always-on avionics baseline ``avionics_w``; per face board ``face_board_w`` while its
  load switch is on; the payload loads while theirs are on; the antenna burnwire ``burnwire_w`` while
  its GPIOs are high; every coil's supply power
  ``|V_applied · I|`` (``V²/R`` at a steady level) while driven. A coil on a face whose switch is
  off cannot be driven (the spacecraft bridge enforces it).
* **Battery** — ``cells_in_series`` Li-ion cells; stored energy ``E = SoC · capacity_wh``; open-circuit
  voltage ``OCV(SoC)`` from a typical NMC cell curve (3.0 V empty … 4.2 V full) times the cell count;
  internal resistance ``R``. For a net discharge power ``P = P_load − P_sol`` the battery current
  solves ``(OCV − I R) I = P``; the bus (terminal) voltage is ``OCV − I R``; the chemical energy
  changes by ``−OCV · I · dt`` and ``I² R · dt`` is lost as heat. An empty battery (SoC 0) delivers
  nothing: the loads it cannot serve are counted as ``unserved``.

Energy bookkeeping (J), exact over any interval::

    solar − shunted = loads − unserved + loss + ΔE_battery

Frames: body B (faces X+ 0, X− 1, Y+ 2, Y− 3, Z+ 4, Z− 5), inertial N. Units SI unless named.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field as _dc_field

from detumble.sim.sun import SOLAR_CONSTANT_W_M2, in_umbra, sun_direction_N
from detumble.sim.vec import rotate_n_to_b

__all__ = ["BatteryConfig", "SolarConfig", "LoadConfig", "PowerConfig", "Battery", "ElectricalSystem",
           "SWITCH_NAMES", "FACE_SWITCHES", "cell_ocv", "coil_supply_power_w"]

#: The load switches of the PROVES flight controller board, by flight instance stem.
FACE_SWITCHES = ("face0", "face1", "face2", "face3", "face4", "face5")
SWITCH_NAMES = FACE_SWITCHES + ("payloadPower", "payloadBattery")

_FACE_NORMALS = ((1.0, 0.0, 0.0), (-1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, -1.0, 0.0), (0.0, 0.0, 1.0),
                 (0.0, 0.0, -1.0))

# A typical NMC 18650 open-circuit curve: SoC 0, 0.1, …, 1.0 -> cell volts.
_OCV_TABLE = (3.00, 3.45, 3.58, 3.66, 3.72, 3.78, 3.86, 3.94, 4.02, 4.10, 4.20)


def cell_ocv(soc: float) -> float:
    """Open-circuit voltage of one cell (V) at state of charge ``soc`` (0…1, clamped)."""
    if soc <= 0.0:
        return _OCV_TABLE[0]
    if soc >= 1.0:
        return _OCV_TABLE[-1]
    x = soc * 10.0
    k = int(x)
    return _OCV_TABLE[k] + (x - k) * (_OCV_TABLE[k + 1] - _OCV_TABLE[k])


@dataclass(frozen=True)
class BatteryConfig:
    capacity_wh: float = 20.0             #: energy between empty and full, Wh (2S 18650 pack)
    initial_soc: float = 0.9              #: state of charge at plant t = 0 (0…1)
    internal_resistance_ohm: float = 0.15  #: pack series resistance, Ω
    cells_in_series: int = 2


@dataclass(frozen=True)
class SolarConfig:
    #: cell area per face X+, X−, Y+, Y−, Z+, Z− (m²); two 26.6 cm² cells on each 1U face
    panel_area_m2: tuple = (0.0053, 0.0053, 0.0053, 0.0053, 0.0053, 0.0053)
    efficiency: float = 0.25              #: cell efficiency at the panel's operating point


@dataclass(frozen=True)
class LoadConfig:
    avionics_w: float = 0.9               #: flight controller, radio receive, IMU: always on
    face_board_w: float = 0.03            #: sensors and DRV2605 standby on a powered face board
    payload_power_w: float = 1.2          #: payload while payloadPower is on
    payload_battery_w: float = 0.0        #: payload battery line while payloadBattery is on
    #: the antenna burnwire while its GPIOs are high: two nichrome wires from the battery, ~0.8 A at
    #: 7.4 V (an assumption: the flight sources give no figure)
    burnwire_w: float = 6.0


@dataclass(frozen=True)
class PowerConfig:
    enabled: bool = True
    battery: BatteryConfig = _dc_field(default_factory=BatteryConfig)
    solar: SolarConfig = _dc_field(default_factory=SolarConfig)
    loads: LoadConfig = _dc_field(default_factory=LoadConfig)
    #: switches closed at plant t = 0 (the spacecraft was already flying in NORMAL mode)
    switches_on: tuple = FACE_SWITCHES


class Battery:
    """A Li-ion pack: state of charge, open-circuit voltage, internal resistance."""

    def __init__(self, cfg: BatteryConfig) -> None:
        self.cfg = cfg
        self.capacity_j = cfg.capacity_wh * 3600.0
        self.energy_j = cfg.initial_soc * self.capacity_j
        self.current_a = 0.0              #: positive = discharging
        self.terminal_v = self.ocv()

    @property
    def soc(self) -> float:
        return self.energy_j / self.capacity_j

    def ocv(self) -> float:
        """The pack's open-circuit voltage (V) at its present state of charge."""
        return cell_ocv(self.soc) * self.cfg.cells_in_series

    def current_for(self, power_w: float) -> float:
        """Battery current (A, + = discharge) delivering ``power_w`` at its terminals; at most the
        maximum-power current ``OCV/2R`` when the load asks for more than the pack can give."""
        return self.current_for_ocv(power_w, self.ocv())

    def current_for_ocv(self, power_w: float, ocv: float) -> float:
        """:meth:`current_for` with the pack's present open-circuit voltage ``ocv`` (V, what
        :meth:`ocv` returns now) given by a caller that has it."""
        r = self.cfg.internal_resistance_ohm
        if r <= 0.0:
            return power_w / ocv
        disc = ocv * ocv - 4.0 * r * power_w
        if disc < 0.0:
            return ocv / (2.0 * r)
        return (ocv - math.sqrt(disc)) / (2.0 * r)


def coil_supply_power_w(level: int, max_level: int, voltage_v: float, current_a: float) -> float:
    """Power a coil driver takes from the bus: applied voltage times coil current, W."""
    return abs(level / max_level * voltage_v * current_a)


class ElectricalSystem:
    """Battery, array and loads; :meth:`step` integrates one interval with the inputs held.

    Args:
        cfg: the scenario's :class:`PowerConfig`.
        epoch_jd: Julian date of plant t = 0 (for the Sun's position).
        earth_radius_m: radius of the shadow cylinder.
    """

    def __init__(self, cfg: PowerConfig, epoch_jd: float, earth_radius_m: float) -> None:
        unknown = set(cfg.switches_on) - set(SWITCH_NAMES)
        if unknown:
            raise ValueError(f"power.switches_on: unknown switch {sorted(unknown)}; switches are {list(SWITCH_NAMES)}")
        self.cfg = cfg
        self.epoch_jd = epoch_jd
        self.earth_radius_m = earth_radius_m
        self.battery = Battery(cfg.battery)
        self.switches = {name: name in cfg.switches_on for name in SWITCH_NAMES}
        self.burnwire_on = False          #: the burnwire GPIOs (not a load switch: fed from the battery)
        self._areas = tuple(float(a) for a in cfg.solar.panel_area_m2)
        # present (last step's) figures
        self.solar_w = 0.0
        self.load_w = 0.0
        self.coil_w = 0.0
        self.eclipse = False
        #: sunlight on each face (X+, X−, Y+, Y−, Z+, Z−), W/m², over the last step (0 in eclipse)
        self.face_flux_w_m2: tuple = (0.0,) * 6
        self.bus_v = self.battery.terminal_v
        # energy accumulators, J
        self.solar_j = 0.0
        self.shunted_j = 0.0
        self.load_j = 0.0
        self.coil_j = 0.0
        self.loss_j = 0.0
        self.unserved_j = 0.0
        self._sun_cache_t: int | None = None
        self._sun = ((1.0, 0.0, 0.0), 1.0)

    # --- switches ---------------------------------------------------------------------------------

    def set_switch(self, name: str, on: bool) -> None:
        if name not in self.switches:
            raise ValueError(f"no load switch {name!r}; switches are {list(SWITCH_NAMES)}")
        self.switches[name] = bool(on)

    def face_powered(self, face: int) -> bool:
        return self.switches[FACE_SWITCHES[face]]

    # --- physics ----------------------------------------------------------------------------------

    def sun(self, t_s: float) -> tuple[tuple[float, float, float], float]:
        """Sun direction in N and distance (AU) at plant time ``t_s``; recomputed once a minute
        (the Sun moves 0.04 deg/min)."""
        key = int(t_s // 60.0)
        if key != self._sun_cache_t:
            self._sun_cache_t = key
            self._sun = sun_direction_N(self.epoch_jd + key * 60.0 / 86400.0)
        return self._sun

    def solar_power_w(self, t_s: float, q_BN, r_N) -> float:
        """Array output (W) at plant time ``t_s`` for attitude ``q_BN`` at position ``r_N`` (m)."""
        s_N, d_au = self.sun(t_s)
        if in_umbra(r_N, s_N, self.earth_radius_m):
            self.eclipse = True
            self.face_flux_w_m2 = (0.0,) * 6
            return 0.0
        self.eclipse = False
        sx, sy, sz = rotate_n_to_b(q_BN, s_N)
        flux = SOLAR_CONSTANT_W_M2 / (d_au * d_au)
        # each face's sunlit cosine (X+, X-, Y+, Y-, Z+, Z-): the lit face of each axis gets its
        # cosine, the other 0.0 (what max(0.0, ±s) gives, a zero cosine included)
        c0, c1 = (sx, 0.0) if sx > 0.0 else (0.0, -sx if sx < 0.0 else 0.0)
        c2, c3 = (sy, 0.0) if sy > 0.0 else (0.0, -sy if sy < 0.0 else 0.0)
        c4, c5 = (sz, 0.0) if sz > 0.0 else (0.0, -sz if sz < 0.0 else 0.0)
        self.face_flux_w_m2 = (flux * c0, flux * c1, flux * c2, flux * c3, flux * c4, flux * c5)
        a = self._areas
        lit = a[0] * c0 + a[1] * c1 + a[2] * c2 + a[3] * c3 + a[4] * c4 + a[5] * c5
        return flux * self.cfg.solar.efficiency * lit

    def switched_load_w(self) -> float:
        loads = self.cfg.loads
        sw = self.switches
        # the closed face switches counted (an int, as sum() gives it)
        p = loads.avionics_w + loads.face_board_w * (sw["face0"] + sw["face1"] + sw["face2"] + sw["face3"]
                                                     + sw["face4"] + sw["face5"])
        if sw["payloadPower"]:
            p += loads.payload_power_w
        if sw["payloadBattery"]:
            p += loads.payload_battery_w
        if self.burnwire_on:
            p += loads.burnwire_w
        return p

    def step(self, dt: float, t_s: float, q_BN, r_N, coil_w: float) -> None:
        """Integrate ``dt`` s from plant time ``t_s`` with attitude, position and coil power held."""
        if dt <= 0.0:
            return
        solar = self.solar_power_w(t_s, q_BN, r_N)
        load = self.switched_load_w() + coil_w
        bat = self.battery
        net = load - solar                       # W the battery must deliver (< 0: charging)
        shunted = 0.0
        unserved = 0.0
        if net < 0.0 and bat.energy_j >= bat.capacity_j:
            shunted, net = -net, 0.0             # full: the regulator sheds the surplus
        ocv = bat.ocv()  # the pack's energy is that of the step's start until it is set below
        current = bat.current_for_ocv(net, ocv) if net != 0.0 else 0.0
        delivered = (ocv - current * bat.cfg.internal_resistance_ohm) * current
        if net > 0.0 and delivered < net:        # the pack cannot deliver it all (brown-out)
            unserved = net - delivered
        d_e = -ocv * current * dt
        loss = current * current * bat.cfg.internal_resistance_ohm * dt
        new_e = bat.energy_j + d_e
        if new_e > bat.capacity_j:               # the last partial step to full: shunt the rest
            excess = new_e - bat.capacity_j
            shunted += excess / dt
            new_e = bat.capacity_j
        elif new_e < 0.0:                        # empty: what was not there was not delivered
            unserved += -new_e / dt
            new_e = 0.0
        bat.energy_j = new_e
        bat.current_a = current
        bat.terminal_v = ocv - current * bat.cfg.internal_resistance_ohm if new_e > 0.0 else 0.0
        self.bus_v = bat.terminal_v
        self.solar_w, self.load_w, self.coil_w = solar, load, coil_w
        self.solar_j += solar * dt
        self.shunted_j += shunted * dt
        self.load_j += load * dt
        self.coil_j += coil_w * dt
        self.loss_j += loss
        self.unserved_j += unserved * dt

    # --- what the INA219 monitors see -------------------------------------------------------------

    def system_reading(self) -> tuple[float, float, float]:
        """``(V, A, W)`` of the system rail: bus voltage, load current, load power."""
        v = self.bus_v
        return (v, self.load_w / v if v > 0.0 else 0.0, self.load_w if v > 0.0 else 0.0)

    def solar_reading(self) -> tuple[float, float, float]:
        """``(V, A, W)`` of the array output: bus voltage while generating (else 0), current, power."""
        p = self.solar_w
        if p <= 0.0 or self.bus_v <= 0.0:
            return (0.0, 0.0, 0.0)
        return (self.bus_v, p / self.bus_v, p)
