"""Environment and actuator torque models (reference formulas, plain floats, SI).

All vectors in the body frame B. Drag and solar radiation pressure (:class:`BoxSurfaces`, with the
atmosphere of :func:`atmosphere_density`) are evaluated by :class:`~.plant.Plant` once per dynamics step at
the step's start and held over it (the attitude moves < 0.01 deg in a 20 ms step at the pointing rates).
The integrator in :mod:`.attitude` evaluates the same formulas
inline at every RK4 stage; these functions are the readable definitions and are what the tests
compare it against.
"""

from __future__ import annotations

import math

from detumble.sim.vec import Mat3, Vec3, add, cross, mat_vec, norm, scale


def magnetic_torque(m_B: Vec3, b_B: Vec3) -> Vec3:
    """Torque of a dipole ``m_B`` (A m^2) in a field ``b_B`` (T): ``m x B`` in N m."""
    return cross(m_B, b_B)


def gravity_gradient_torque(mu: float, r_B: Vec3, inertia: Mat3) -> Vec3:
    """Gravity-gradient torque ``3 mu / r^3 * r_hat x (J r_hat)`` in N m.

    ``mu`` in m^3/s^2, ``r_B`` the spacecraft position from the Earth's centre expressed in B
    (m), ``inertia`` in kg m^2. Equal to ``3 n^2 r_hat x (J r_hat)`` on a circular orbit.
    """
    r = norm(r_B)
    r_hat = scale(1.0 / r, r_B)
    return scale(3.0 * mu / r**3, cross(r_hat, mat_vec(inertia, r_hat)))


def residual_dipole_torque(m_res_B: Vec3, b_B: Vec3) -> Vec3:
    """Torque of the spacecraft's own residual (uncommanded) dipole, N m."""
    return cross(m_res_B, b_B)


def total_magnetic_torque(m_coils_B: Vec3, m_res_B: Vec3, b_B: Vec3) -> Vec3:
    """Coils plus residual dipole in the same field, N m."""
    return cross(add(m_coils_B, m_res_B), b_B)


# --- drag and solar radiation pressure -------------------------------------------------------------------

#: Piecewise-exponential atmosphere: (base altitude km, density at the base kg/m^3, scale height km), the
#: CIRA-72 based table of Vallado, "Fundamentals of Astrodynamics and Applications" (4th ed., table 8-4),
#: 150-1000 km. A mean-solar-activity model: the real density at 400 km varies ~10x over the solar cycle.
ATMOSPHERE_TABLE = (
    (150.0, 2.070e-9, 22.523), (180.0, 5.464e-10, 29.740), (200.0, 2.789e-10, 37.105),
    (250.0, 7.248e-11, 45.546), (300.0, 2.418e-11, 53.628), (350.0, 9.518e-12, 53.298),
    (400.0, 3.725e-12, 58.515), (450.0, 1.585e-12, 60.828), (500.0, 6.967e-13, 63.822),
    (600.0, 1.454e-13, 71.835), (700.0, 3.614e-14, 88.667), (800.0, 1.170e-14, 124.64),
    (900.0, 5.245e-15, 181.05), (1000.0, 3.019e-15, 268.00),
)
#: Solar radiation pressure at 1 AU on an absorbing surface, N/m^2 (1361 W/m^2 / c).
SOLAR_PRESSURE_N_M2 = 1361.0 / 299792458.0


def atmosphere_density(altitude_m: float) -> float:
    """Density ``ρ0 exp(−(h − h0)/H)`` (kg/m^3) of :data:`ATMOSPHERE_TABLE` at ``altitude_m`` above the
    reference sphere; the lowest band below 150 km, the highest above 1000 km."""
    h = altitude_m / 1000.0
    row = ATMOSPHERE_TABLE[0]
    for r in ATMOSPHERE_TABLE:
        if h >= r[0]:
            row = r
    return row[1] * math.exp(-(h - row[0]) / row[2])


class BoxSurfaces:
    """A box-shaped spacecraft's six faces for drag and solar-radiation-pressure torques (flat plates).

    ``size_m`` the box's edges along B's x, y, z (m); ``cp_offset_m`` the box's geometric centre minus the
    centre of mass (m, B): the lever arm the forces act through. Face ``±i`` (outward normal ``±e_i``) has the
    area of the other two edges and its centre at ``cp_offset ± size_i/2 e_i``. Drag: each face facing the flow
    (``c = n · v̂ > 0``) takes ``F = −½ ρ C_D A c |v|² v̂`` (momentum of the particles it stops). Solar pressure:
    each lit face (``c = n · ŝ > 0``) takes ``F = −P A c [(1 − ε) ŝ + 2 ε c n]`` (ε the specular reflectivity,
    the rest absorbed). The torque is the sum of ``r_face × F``; forces in N, torques in N m, B frame.
    """

    def __init__(self, size_m: Vec3, cp_offset_m: Vec3, drag_coefficient: float = 2.2,
                 specular_reflectivity: float = 0.0) -> None:
        self.size_m = tuple(float(x) for x in size_m)
        self.cp_offset_m = tuple(float(x) for x in cp_offset_m)
        self.drag_coefficient = float(drag_coefficient)
        self.specular_reflectivity = float(specular_reflectivity)
        a, b, c = self.size_m
        areas = (b * c, a * c, a * b)
        o = self.cp_offset_m
        faces = []
        for i in range(3):
            for sign in (1.0, -1.0):
                n = [0.0, 0.0, 0.0]
                n[i] = sign
                centre = list(o)
                centre[i] += sign * 0.5 * self.size_m[i]
                faces.append(((n[0], n[1], n[2]), areas[i], (centre[0], centre[1], centre[2])))
        self.faces = tuple(faces)

    def drag_torque(self, v_rel_B: Vec3, density: float) -> Vec3:
        """Drag torque (N m, B) for the air's velocity relative to the body ``v_rel_B`` (m/s: the body's
        velocity through the air) and ``density`` (kg/m^3)."""
        speed = norm(v_rel_B)
        if speed == 0.0 or density == 0.0:
            return (0.0, 0.0, 0.0)
        vh = scale(1.0 / speed, v_rel_B)
        q = 0.5 * density * self.drag_coefficient * speed * speed
        tx = ty = tz = 0.0
        for n, area, r in self.faces:
            c = n[0] * vh[0] + n[1] * vh[1] + n[2] * vh[2]
            if c <= 0.0:
                continue
            f = -q * area * c
            fx, fy, fz = f * vh[0], f * vh[1], f * vh[2]
            tx += r[1] * fz - r[2] * fy
            ty += r[2] * fx - r[0] * fz
            tz += r[0] * fy - r[1] * fx
        return (tx, ty, tz)

    def solar_torque(self, sun_B: Vec3, pressure: float) -> Vec3:
        """Solar-radiation-pressure torque (N m, B) for the unit Sun direction ``sun_B`` and the pressure
        (N/m^2; 0 in eclipse)."""
        eps = self.specular_reflectivity
        tx = ty = tz = 0.0
        if pressure == 0.0:
            return (0.0, 0.0, 0.0)
        for n, area, r in self.faces:
            c = n[0] * sun_B[0] + n[1] * sun_B[1] + n[2] * sun_B[2]
            if c <= 0.0:
                continue
            k = -pressure * area * c
            a, s = k * (1.0 - eps), k * 2.0 * eps * c
            fx, fy, fz = a * sun_B[0] + s * n[0], a * sun_B[1] + s * n[1], a * sun_B[2] + s * n[2]
            tx += r[1] * fz - r[2] * fy
            ty += r[2] * fx - r[0] * fz
            tz += r[0] * fy - r[1] * fx
        return (tx, ty, tz)
