"""Environment and actuator torque models (reference formulas, plain floats, SI).

All vectors in the body frame B. The integrator in :mod:`.attitude` evaluates the same formulas
inline at every RK4 stage; these functions are the readable definitions and are what the tests
compare it against.
"""

from __future__ import annotations

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
