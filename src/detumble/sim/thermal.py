"""A lumped thermal model of the 1U spacecraft: one node per face panel and one for the interior.

Pure physics (no framework import). It gives the simulated temperature sensors (the TMP112s on the
faces and battery cells, the RP2350's die sensor) something physical to read; it is not a design
tool (no Earth IR or albedo, no conduction between neighbouring faces).

Model (SI, temperatures in kelvin inside, °C at the interface)::

    C_f dT_f/dt = α A_f q_f − ε σ A_f T_f⁴ − G (T_f − T_i)          (each face f; q_f its sunlight, W/m²)
    C_i dT_i/dt = P_el − Σ_f G (T_i − T_f)                            (interior; P_el the electrical load)

Every watt the loads draw ends as heat in the interior, which only loses it through the faces.
At equilibrium the absorbed and dissipated power equals the radiated power:
``Σ α A_f q_f + P_el = Σ ε σ A_f T_f⁴`` (``tests/detumble/sim/test_thermal.py`` checks it, and the
closed-form single-face balance). Integrated with explicit Euler in sub-steps of at most
``max_substep_s`` (the shortest time constant, ``C_f / (G + 4 ε σ A T³)``, is about 29 s with the
defaults, so 1 s sub-steps are stable). With the defaults a tumbling 1U cube in sunlight averages
about 14 °C (``Σ`` absorbed ≈ α S · 0.015 m², the mean projected area of a cube of 0.06 m²).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["ThermalConfig", "ThermalModel", "STEFAN_BOLTZMANN", "KELVIN"]

STEFAN_BOLTZMANN = 5.670374419e-8   #: W m⁻² K⁻⁴
KELVIN = 273.15                      #: 0 °C in K


@dataclass(frozen=True)
class ThermalConfig:
    face_area_m2: float = 0.01               #: each face panel, 10 cm x 10 cm
    absorptivity: float = 0.9                #: solar absorptivity of the cell side
    emissivity: float = 0.85                 #: infrared emissivity
    face_capacity_j_k: float = 60.0          #: a face board with its cells (about 70 g of FR4 and glass)
    interior_capacity_j_k: float = 400.0     #: battery, boards and frame inside
    face_interior_w_k: float = 2.0           #: each face bolted to the frame, W/K (an assumption)
    initial_c: float = 20.0                  #: every node at plant t = 0, °C
    max_substep_s: float = 1.0


class ThermalModel:
    """Six face nodes and an interior node; :meth:`step` integrates with the inputs held."""

    def __init__(self, cfg: ThermalConfig = ThermalConfig()) -> None:
        if cfg.max_substep_s <= 0.0:
            raise ValueError(f"max_substep_s must be positive, got {cfg.max_substep_s}")
        self.cfg = cfg
        self.face_k = [cfg.initial_c + KELVIN] * 6
        self.interior_k = cfg.initial_c + KELVIN

    def face_c(self, face: int) -> float:
        """Face ``face`` (0 X+ … 5 Z−) in °C."""
        return self.face_k[face] - KELVIN

    @property
    def interior_c(self) -> float:
        """The interior (battery, flight computer) in °C."""
        return self.interior_k - KELVIN

    def step(self, dt: float, face_flux_w_m2, load_w: float) -> None:
        """Advance ``dt`` s with sunlight ``face_flux_w_m2`` (6 values, W/m²) and electrical load ``load_w`` (W)."""
        if dt <= 0.0:
            return
        cfg = self.cfg
        n = max(1, int(dt / cfg.max_substep_s + 0.999999))
        h = dt / n
        a, g = cfg.face_area_m2, cfg.face_interior_w_k
        absorbed = [cfg.absorptivity * a * q for q in face_flux_w_m2]
        rad = cfg.emissivity * STEFAN_BOLTZMANN * a
        c_face, c_interior = cfg.face_capacity_j_k, cfg.interior_capacity_j_k
        faces = self.face_k
        for _ in range(n):
            ti = self.interior_k
            to_interior = 0.0
            for f, tf in enumerate(faces):  # the list is only written at the index just read
                cond = g * (tf - ti)
                to_interior += cond
                faces[f] = tf + h * (absorbed[f] - rad * tf ** 4 - cond) / c_face
            self.interior_k = ti + h * (load_w + to_interior) / c_interior
