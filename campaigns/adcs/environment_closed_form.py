"""The closed-form figures of docs/studies/environment_torques.md (no flight: arithmetic on the adcs scenario and
the flight software's defaults, and twelve Floquet maps of 16000 samples, about 8 CPU-s in all).

    python campaigns/adcs/environment_closed_form.py                                                        # printed
    python campaigns/adcs/environment_closed_form.py --json docs/studies/environment_torques/closed_form.json  # kept

``nadir``: with +Z to nadir (r̂_B = (0, 0, −1)) on the adcs orbit (circular, the scenario's altitude, μ of the
scenario), the gravity-gradient torque the wheel law's feed-forward models (``detumble.control.pointing``:
``3 μ/r³ r̂ × (I r̂)``), the gyroscopic torque ``ω × I ω`` of the body turning at the orbit rate n about its y axis,
the offset a PD with the default K_P (``detumble.control.attitude_defaults``) holds that gravity gradient at
(``|τ| / (K_P/2)``), and the libration stiffness ``3 n² |I_zz − I_yy|`` against the PD's ``K_P/2``.
``surfaces``: drag and solar pressure on the adcs box (``detumble.sim.torques.BoxSurfaces``, the scenario's size and
drag coefficient; density of ``atmosphere_density`` at the scenario's altitude), the flow (7.4 km/s relative to
the air, the figure the page uses) or the Sun square on one 0.1 × 0.1135 m face, per centimetre of centre-of-pressure
offset across it; the momentum a centimetre's drag torque stores over one orbit, against one wheel's capacity.
``floquet_bias``: the magnetorquer hold's slowest Floquet rate (1/s; the present coil gains K_P_MAG, K_D_MAG, ρ, ζ of
``attitude_defaults``, inertia × 1.25 for the coils' duty) with the law seeing the field through k × the scenario's
LIS2MDL bias, k = 0 … 2, in the tilted dipole and in IGRF-14 (``campaigns/adcs/magnetic_pointing_tables.py``'s map).
``igrf_table``: how far adcs_ref's field table (IGRF-14 tabulated every ``field.table_step_s``, linearly interpolated)
is from the exact field along two orbits: the largest |B̈| per component (central differences of the exact field,
δ = 5 s, at every interval's midpoint), the interpolation bound ``h²/8 · |max B̈|`` and the largest error measured at
those midpoints (T), against the LIS2MDL's quantisation step.
``tools/studies.py --only environment_closed_form`` renders the page's blocks from the JSON file.
"""

from __future__ import annotations

import math
import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
#: the flow speed relative to the air the page quotes (m/s): the orbit's 7.66 km/s less the co-rotating air
FLOW_M_S = 7400.0
OFFSET_M = 0.01
BIAS_FACTORS = (0.0, 1.0, 1.25, 1.5, 1.75, 2.0)


def _tables():
    from detumble.reports.study_table import sibling_script

    return sibling_script(HERE, "magnetic_pointing_tables")


def nadir() -> dict:
    from detumble.control import attitude_defaults
    from detumble.control.pointing import gravity_gradient_torque, gyroscopic_torque
    from detumble.sim.scenario import load_scenario

    sc = load_scenario("adcs")
    inertia = [list(row) for row in sc.spacecraft.inertia_kg_m2]
    r = sc.orbit.earth_radius_m + 1e3 * sc.orbit.altitude_km
    mu = sc.orbit.mu_m3_s2
    n = math.sqrt(mu / r ** 3)
    gg = gravity_gradient_torque(inertia, (0.0, 0.0, -r), mu)
    gyro = gyroscopic_torque(inertia, (0.0, n, 0.0), (0.0, 0.0, 0.0))
    spring = attitude_defaults.K_P / 2.0
    libration = 3.0 * n * n * abs(inertia[2][2] - inertia[1][1])
    offset = math.hypot(*gg) / spring
    return {"altitude_km": sc.orbit.altitude_km, "three_n2": 3.0 * n * n, "n2": n * n,
            "products": {"xy": inertia[0][1], "xz": inertia[0][2], "yz": inertia[1][2]},
            "gravity_gradient_nm": list(gg), "gyroscopic_nm": list(gyro), "k_p": attitude_defaults.K_P,
            "offset_rad": offset, "offset_deg": math.degrees(offset), "libration_nm_per_rad": libration,
            "spring_over_libration": spring / libration}


def surfaces() -> dict:
    from detumble.sim.scenario import load_scenario
    from detumble.sim.torques import SOLAR_PRESSURE_N_M2, BoxSurfaces, atmosphere_density

    sc = load_scenario("adcs")
    cfg = sc.spacecraft.surfaces
    density = atmosphere_density(1e3 * sc.orbit.altitude_km)
    box = BoxSurfaces(cfg.size_m, (0.0, 0.0, OFFSET_M), cfg.drag_coefficient, cfg.specular_reflectivity)
    area = cfg.size_m[1] * cfg.size_m[2]
    drag = math.hypot(*box.drag_torque((FLOW_M_S, 0.0, 0.0), density))
    solar = math.hypot(*box.solar_torque((1.0, 0.0, 0.0), SOLAR_PRESSURE_N_M2))
    period = 2.0 * math.pi * math.sqrt((sc.orbit.earth_radius_m + 1e3 * sc.orbit.altitude_km) ** 3
                                       / sc.orbit.mu_m3_s2)
    capacity = sc.spacecraft.reaction_wheels[0].max_momentum_nms
    return {"density_kg_m3": density, "face_m2": area, "flow_m_s": FLOW_M_S, "offset_m": OFFSET_M,
            "drag_force_n": 0.5 * density * cfg.drag_coefficient * area * FLOW_M_S ** 2,
            "drag_torque_nm": drag, "solar_force_n": SOLAR_PRESSURE_N_M2 * area, "solar_torque_nm": solar,
            "orbit_period_s": period, "drag_momentum_per_orbit_nms": drag * period,
            "wheel_capacity_nms": capacity, "drag_momentum_fraction": drag * period / capacity}


def igrf_table() -> dict:
    from detumble.sim.plant import build_field, build_orbit
    from detumble.sim.scenario import load_scenario

    sc = load_scenario("adcs")
    orbit = build_orbit(sc)
    table = build_field(sc, orbit)
    h, d = table.table_step_s, 5.0
    period = 2.0 * math.pi / orbit.mean_motion

    def exact(t: float):
        return table.model.b_N(t, orbit.position_N(t))

    curvature, worst = [0.0, 0.0, 0.0], 0.0
    for k in range(int(2.0 * period / h)):
        t = h * k + 0.5 * h  # an interval's midpoint: the nodes are at multiples of h
        a, b, c = exact(t - d), exact(t), exact(t + d)
        curvature = [max(m, abs(a[i] - 2.0 * b[i] + c[i]) / (d * d)) for i, m in enumerate(curvature)]
        worst = max(worst, math.dist(table.b_N(t), b))
    bound = h * h / 8.0 * math.sqrt(sum(m * m for m in curvature))
    return {"model": sc.field.model, "table_step_s": h, "orbits": 2, "bddot_max_t_s2": curvature, "bound_t": bound,
            "worst_midpoint_t": worst, "magnetometer_step_t": 1e-4 * sc.magnetometer.resolution_gauss}


def floquet_bias() -> dict:
    from detumble.control import attitude_defaults as d

    tables = _tables()
    gains = (d.K_P_MAG, d.K_D_MAG, d.MAG_STEER_RHO, d.MAG_STEER_ZETA)
    return {"gains": list(gains), "factors": list(BIAS_FACTORS),
            "rates": {field: tables.floquet_row(field, *gains, factors=BIAS_FACTORS) for field in tables.FIELDS}}


def results() -> dict:
    return {"script": "campaigns/adcs/environment_closed_form.py", "nadir": nadir(), "surfaces": surfaces(),
            "floquet_bias": floquet_bias(), "igrf_table": igrf_table()}


def probe(committed: dict) -> list[str]:
    """Compute every figure again (about 8 CPU-s) and compare with the committed file to the float."""
    import json

    again = json.loads(json.dumps(results()))
    return [f"{key} is {json.dumps(again.get(key))} now, {json.dumps(committed.get(key))} committed"
            for key in sorted(set(again) | set(committed)) if again.get(key) != committed.get(key)]


def _e(x: float, digits: int = 1) -> str:
    """``x`` in e-notation without the exponent's leading zero (3.8e-11)."""
    mantissa, exponent = f"{x:.{digits}e}".split("e")
    return f"{mantissa}e{int(exponent)}".replace("-", "−", 1) if x < 0 else f"{mantissa}e{int(exponent)}"


def _vec(v) -> str:
    return "(" + ", ".join("0" if x == 0 else _e(x) for x in v) + ")"


def nadir_markdown(table: dict) -> str:
    t = table["nadir"]
    p = t["products"]
    rows = [
        ("3 n² at the scenario's altitude", f"{t['altitude_km']:g} km: {_e(t['three_n2'], 2)} s⁻²"),
        ("products of inertia I_xy, I_xz, I_yz (kg·m²)", f"{_e(p['xy'])}, {_e(p['xz'])}, {_e(p['yz'])}"),
        ("gravity gradient, +Z to nadir: 3 n² (−I_yz, I_xz, 0)", f"{_vec(t['gravity_gradient_nm'])} N·m"),
        ("gyroscopic, turning at n about y: n² (I_yz, 0, −I_xy)", f"{_vec(t['gyroscopic_nm'])} N·m"),
        ("PD offset holding that gravity gradient, \\|τ\\| / (K_P/2)",
         f"{_e(t['offset_rad'])} rad = **{_e(t['offset_deg'])}°** (K_P {_e(t['k_p'])} N·m)"),
        ("libration stiffness 3 n² \\|I_zz − I_yy\\| against K_P/2",
         f"{_e(t['libration_nm_per_rad'])} N·m/rad, {_e(t['spring_over_libration'])} times weaker"),
    ]
    lines = ["| closed form (adcs body, nadir hold) | value |", "|---|---|"]
    return "\n".join(lines + [f"| {a} | {b} |" for a, b in rows]) + "\n"


def surfaces_markdown(table: dict) -> str:
    s = table["surfaces"]
    cm = s["offset_m"] * 100
    rows = [
        ("air density (CIRA-72 table, mean activity)", f"{_e(s['density_kg_m3'], 2)} kg/m³"),
        (f"drag force on the {s['face_m2']:.5f} m² face at {s['flow_m_s'] / 1e3:g} km/s", f"{_e(s['drag_force_n'])} N"),
        (f"drag torque per {cm:g} cm of offset", f"**{_e(s['drag_torque_nm'])} N·m**"),
        ("solar pressure force on that face (absorbed)", f"{_e(s['solar_force_n'])} N"),
        (f"solar pressure torque per {cm:g} cm of offset", f"**{_e(s['solar_torque_nm'])} N·m**"),
        (f"momentum the {cm:g} cm drag torque stores in an orbit ({s['orbit_period_s']:.0f} s)",
         f"{_e(s['drag_momentum_per_orbit_nms'])} N·m·s, {100 * s['drag_momentum_fraction']:.1f} % of a wheel's "
         f"{_e(s['wheel_capacity_nms'], 0)} N·m·s"),
    ]
    lines = ["| drag and solar pressure, adcs body at the scenario's altitude | value |", "|---|---|"]
    return "\n".join(lines + [f"| {a} | {b} |" for a, b in rows]) + "\n"


def floquet_bias_markdown(table: dict) -> str:
    f = table["floquet_bias"]
    names = {"dipole": "dipole", "igrf14": "IGRF-14"}
    lines = ["| k | " + " | ".join(f"{k:g}" for k in f["factors"]) + " |", "|---|" + "---|" * len(f["factors"])]
    for field, rates in f["rates"].items():
        cells = [f"−{_e(-x, 2)}" if x < 0 else f"**+{_e(x)}**" for x in rates]
        lines.append(f"| {names.get(field, field)} (1/s) | " + " | ".join(cells) + " |")
    kp, kd, rho, zeta = f["gains"]
    return "\n".join(lines) + (f"\n\nGains K_P_MAG {_e(kp, 0)} N·m, K_D_MAG {_e(kd, 0)} N·m·s, ρ {rho:g}, ζ {zeta:g} "
                               "(the defaults), inertia × 1.25.\n")


def igrf_table_markdown(table: dict) -> str:
    g = table["igrf_table"]
    nt = [1e9 * x for x in g["bddot_max_t_s2"]]
    bound, worst, step = 1e9 * g["bound_t"], 1e9 * g["worst_midpoint_t"], 1e9 * g["magnetometer_step_t"]
    return (f"Along {g['orbits']} adcs orbits ({g['model']} on a {g['table_step_s']:g} s table): |B̈| at most "
            f"{nt[0]:.2f}, {nt[1]:.2f}, {nt[2]:.2f} nT/s² (x, y, z), so the table is within **{bound:.1f} nT** "
            f"of the exact field (h²/8 · |max B̈|); the worst interval midpoint measured is {worst:.1f} nT, "
            f"1/{step / bound:.0f} of the LIS2MDL's {step:.0f} nT step.\n")


def markdown(table: dict) -> str:
    return "\n".join(f(table) for f in (nadir_markdown, surfaces_markdown, floquet_bias_markdown, igrf_table_markdown))


def main(argv: list[str] | None = None) -> int:
    from detumble.reports.study_table import table_script_main

    return table_script_main(argv, __doc__.split("\n\n")[0], lambda args: results(), markdown)


if __name__ == "__main__":
    sys.exit(main())
