"""A magnetorquer-only hold scheduled on the on-board field model: a finite-horizon LQR of the linearised hold over the
field predicted along the coming orbit (plain floats; no framework import).

Why. The field-steering law (``control.magnetic_pointing``) knows the field only as it is now (the reading and the
rate of its direction); along the field line it cannot do better than a pair at ``ζ ρ r``. A law that knows ``B(t)``
ahead can: the periodic LQR bound of ``docs/studies/magnetorquer_hold_after_acquisition.md`` ("Can any linear coil law
do it?") brings a 30° error along the field line to 15° in ≈ 200 s with ``B(t)`` known, its dipole scaled to the
coils' capacity. On board, ``B(t)`` ahead is the on-board field model (``control.geomagnetic``, the tilted dipole)
along the orbit propagated from the ephemeris, turned into the target frame T (an inertial target).

The model (as ``detumble.analysis.magnetic_periodic_lqr``, rewritten here in plain floats): small errors about an
inertial target, ``θ̇ = ω``, ``J ω̇ = m × B(t)`` in T, the dipole held over each step ``h`` and the field held at the
step's start, so the step is exact: ``A = [[I, hI], [0, I]]``, ``B_k = [h²/2 G_k; h G_k]``, ``G_k = −J⁻¹ [B_k×]``.
The Riccati recursion with the α-shift (``Â = e^{αh} A``, ``B̂ = e^{αh} B``)

    ``K_k = (R h + B̂ᵀ P B̂)⁻¹ B̂ᵀ P Â``,  ``P ← Q h + Âᵀ P Â − Âᵀ P B̂ K_k``

runs backward from the end of the horizon (``P = Q h`` there) to its start; ``m = −K_k x``, ``x = (θ, ω)`` in T.
Weights as the bound's: ``Q = diag(I/θ_s², I/ω_s²)``, ``R = r diag(1/m_max²)``.

Orbit: the ephemeris' position turned on its circle at the angular rate ``|r × v| / |r|²`` (a circular two-body
orbit; the J2 drift over an orbit, ~0.3° of node, is left out). Earth angle: ``θ_E + ω_E t``.

Units: s, m, T, A·m², rad, rad/s; ``q`` scalar first, ``q_BN`` / ``q_TN``; inertia kg·m² (3×3).
"""

from __future__ import annotations

import math
from array import array
from collections.abc import Sequence

from detumble.control.geomagnetic import dipole_field_N
from detumble.control.mat3 import inv3
from detumble.control.quaternion import Quat, Vec3, rotate_b_to_n, rotate_n_to_b

__all__ = ["EARTH_ROTATION_RATE_RAD_S", "SAMPLE_UNITS", "RICCATI_STEP_UNITS", "circular_position_N", "hold_gains",
           "HoldGainTable", "HoldGainTableBuilder", "hold_gain_table", "lqr_dipole_B"]

#: rad/s: the Earth's rotation rate (the on-board model's)
EARTH_ROTATION_RATE_RAD_S = 7.2921159e-5

Mat = list[list[float]]
#: a gain ``K`` (3×6) as the table gives it: its 18 floats row by row (``K[i][k]`` at ``6 i + k``), a slice of the
#: table's one ``array('d')``. A table of 7,972 gains kept as Python lists or tuples is ~32,000 objects: freeing them
#: took 2.4 ms (and made the interpreter's full collections longer); one array is freed at once and never tracked.
Gain = Sequence[float]


def circular_position_N(r_N: Vec3, v_N: Vec3, t_s: float) -> Vec3:
    """The position (m, N) ``t_s`` seconds after ``(r_N, v_N)`` on the circle of radius ``|r|`` in the orbit plane,
    turned at ``|r × v| / |r|²`` rad/s. ValueError without a plane (``r × v`` = 0)."""
    hx = r_N[1] * v_N[2] - r_N[2] * v_N[1]
    hy = r_N[2] * v_N[0] - r_N[0] * v_N[2]
    hz = r_N[0] * v_N[1] - r_N[1] * v_N[0]
    hn = math.sqrt(hx * hx + hy * hy + hz * hz)
    r2 = r_N[0] * r_N[0] + r_N[1] * r_N[1] + r_N[2] * r_N[2]
    if not (hn > 0.0 and r2 > 0.0):
        raise ValueError("no orbit plane: r × v is zero")
    rate = hn / r2
    # ĥ × r: the in-plane direction 90° ahead of r, with |r|
    ux, uy, uz = hx / hn, hy / hn, hz / hn
    ax, ay, az = uy * r_N[2] - uz * r_N[1], uz * r_N[0] - ux * r_N[2], ux * r_N[1] - uy * r_N[0]
    c, s = math.cos(rate * t_s), math.sin(rate * t_s)
    return (c * r_N[0] + s * ax, c * r_N[1] + s * ay, c * r_N[2] + s * az)


def _mul(a: Mat, b: Mat) -> Mat:
    bt = list(zip(*b, strict=True))
    return [[sum(x * y for x, y in zip(row, col, strict=True)) for col in bt] for row in a]


def _t(a: Mat) -> Mat:
    return [list(col) for col in zip(*a, strict=True)]


#: work units (:class:`HoldGainTableBuilder`): one field-model sample, one backward Riccati step. Measured on the
#: development machine (``time.thread_time``, 2,000 of each): a sample 2 µs (dipole), 16 µs (IGRF degree 6), 44 µs
#: (degree 13); a Riccati step 120 µs. A step counts three samples, so a budget of units bounds the CPU of a call by
#: about 44 µs a unit whatever the degree.
SAMPLE_UNITS = 1
RICCATI_STEP_UNITS = 3


class _RiccatiRecursion:
    """The backward Riccati recursion of :func:`hold_gains`, one step per :meth:`step` (the state between steps:
    ``P`` and the index of the next step, counting down to 0)."""

    def __init__(self, fields_t: array, inertia, step_s: float, m_max: Vec3, theta_scale_rad: float,
                 rate_scale_rad_s: float, r_weight: float, alpha: float) -> None:
        h = self.h = float(step_s)
        self.fields = fields_t
        self.j_inv = inv3(inertia)
        self.s = math.exp(alpha * h)
        qt, qw = h / theta_scale_rad ** 2, h / rate_scale_rad_s ** 2
        self.q_h = [[(qt if i < 3 else qw) if i == k else 0.0 for k in range(6)] for i in range(6)]
        self.r_h = [[r_weight * h / m_max[i] ** 2 if i == k else 0.0 for k in range(3)] for i in range(3)]
        self.p = [row[:] for row in self.q_h]
        n = len(fields_t) // 3
        self.gains = array("d", bytes(8 * 18 * n))  # gain k at [18 k, 18 k + 18), row by row
        self.idx = n  # the next step computes gain idx - 1; 0: done

    def step(self) -> None:
        """One step backward: ``K`` at ``idx − 1`` and the ``P`` before it. ArithmeticError if it overflows."""
        idx = self.idx - 1
        h, s, j_inv, p, q_h, r_h = self.h, self.s, self.j_inv, self.p, self.q_h, self.r_h
        bx, by, bz = self.fields[3 * idx:3 * idx + 3]
        skew = ((0.0, -bz, by), (bz, 0.0, -bx), (-by, bx, 0.0))
        g = [[-sum(j_inv[i][n] * skew[n][k] for n in range(3)) for k in range(3)] for i in range(3)]
        # Â = s [[I, hI], [0, I]], B̂ = s [h²/2 G; h G]
        b_hat = [[s * 0.5 * h * h * g[i][k] for k in range(3)] for i in range(3)] + \
                [[s * h * g[i][k] for k in range(3)] for i in range(3)]
        # P Â: columns 0-2 are s P[:, :3], columns 3-5 are s (h P[:, :3] + P[:, 3:])
        pa = [[s * row[k] for k in range(3)] + [s * (h * row[k] + row[k + 3]) for k in range(3)] for row in p]
        pb = _mul(p, b_hat)  # 6×3
        bt = _t(b_hat)
        m3 = _mul(bt, pb)
        for i in range(3):
            m3[i][i] += r_h[i][i]
        try:
            m3_inv = inv3(m3)
        except ValueError as exc:
            raise ArithmeticError("the Riccati step's input weight is singular") from exc
        gain = _mul(m3_inv, _mul(bt, pa))  # 3×6: (R h + B̂ᵀPB̂)⁻¹ B̂ᵀ P Â
        # Âᵀ P Â
        apa = [[s * pa[n][k] for k in range(6)] for n in range(3)]
        apa += [[s * (h * pa[n][k] + pa[n + 3][k]) for k in range(6)] for n in range(3)]
        # Âᵀ P B̂ K = (P Â)ᵀ B̂ K
        bk = _mul(b_hat, gain)  # 6×6
        pat = _t(pa)
        corr = _mul(pat, bk)
        p = [[q_h[i][k] + apa[i][k] - corr[i][k] for k in range(6)] for i in range(6)]
        p = [[0.5 * (p[i][k] + p[k][i]) for k in range(6)] for i in range(6)]
        if not all(math.isfinite(x) for row in p for x in row):
            raise ArithmeticError("the Riccati recursion overflowed")
        self.p = p
        self.gains[18 * idx:18 * idx + 18] = array("d", gain[0] + gain[1] + gain[2])
        self.idx = idx


def hold_gains(fields_t: Sequence[Vec3], inertia, step_s: float, m_max: Vec3, theta_scale_rad: float,
               rate_scale_rad_s: float, r_weight: float, alpha: float) -> list[Gain]:
    """The gains ``K_k`` (3×6 each as 18 floats row by row, :data:`Gain`; ``m = −K_k (θ, ω)``, A·m² per rad and per
    rad/s) of the finite-horizon LQR over the fields ``fields_t`` (T, target frame, one per step of ``step_s`` s; the
    horizon is their count × the step), backward from ``P = Q h`` at its end. ``inertia``: 3×3 kg·m² (the coils' duty
    folded in by the caller); ``m_max``: the per-axis dipole capacity (A·m²) in R's weights. ArithmeticError if the
    recursion overflows."""
    recursion = _RiccatiRecursion(array("d", [c for b in fields_t for c in b]), inertia, step_s, m_max,
                                  theta_scale_rad, rate_scale_rad_s, r_weight, alpha)
    while recursion.idx:
        recursion.step()
    g = recursion.gains
    return [g[18 * k:18 * k + 18] for k in range(len(fields_t))]


class HoldGainTable:
    """The gains of :func:`hold_gains` for the target ``q_tn`` from ``t0_s`` (s, the controller's clock) on, one per
    ``step_s``; :meth:`gain` at a time within ``use_s`` of the start, else None (time to compute a new table)."""

    def __init__(self, q_tn: Quat, t0_s: float, step_s: float, use_s: float, gains: array) -> None:
        self.q_tn, self.t0_s, self.step_s, self.use_s, self.gains = q_tn, t0_s, step_s, use_s, gains

    def gain(self, t_s: float) -> Gain | None:
        dt = t_s - self.t0_s
        if not 0.0 <= dt < self.use_s:
            return None
        k = int(dt / self.step_s)
        return self.gains[18 * k:18 * k + 18] if 18 * k < len(self.gains) else None


class HoldGainTableBuilder:
    """:func:`hold_gain_table` a bounded piece at a time: :meth:`advance` does at most ``budget`` work units
    (:data:`SAMPLE_UNITS` a field-model sample, then :data:`RICCATI_STEP_UNITS` a backward Riccati step) and returns
    the finished :class:`HoldGainTable` (the same floats as :func:`hold_gain_table`, which is this builder run to
    completion) once the last step is done, else None. Arguments as :func:`hold_gain_table`'s; ``t0_s`` is the time
    of the ephemeris ``(r_N, v_N, earth_angle_rad)``, so the table's gains are for the times from ``t0_s`` on whenever
    it finishes. ValueError (no orbit plane, a singular inertia) or ArithmeticError (the recursion overflows) from
    the :meth:`advance` that meets it."""

    def __init__(self, q_tn: Quat, t0_s: float, r_N: Vec3, v_N: Vec3, earth_angle_rad: float, inertia,  # noqa: N803
                 m_max: Vec3, step_s: float, use_s: float, extra_s: float, theta_scale_rad: float,
                 rate_scale_rad_s: float, r_weight: float, alpha: float, field_N=dipole_field_N) -> None:  # noqa: N803
        self.q_tn, self.t0_s, self.step_s, self.use_s = q_tn, t0_s, step_s, use_s
        self._orbit = (r_N, v_N, earth_angle_rad, field_N)
        self._weights = (inertia, step_s, m_max, theta_scale_rad, rate_scale_rad_s, r_weight, alpha)
        self.samples = int(math.ceil((use_s + extra_s) / step_s))
        self.fields = array("d")  # the samples (T, in T), three floats each
        self._recursion: _RiccatiRecursion | None = None
        #: work units done so far, of :attr:`units_total`
        self.units_done = 0
        self.units_total = self.samples * (SAMPLE_UNITS + RICCATI_STEP_UNITS)

    def advance(self, budget: int) -> HoldGainTable | None:
        """At most ``budget`` work units (at least :data:`RICCATI_STEP_UNITS`, else ValueError); the table when done."""
        if budget < RICCATI_STEP_UNITS:
            raise ValueError(f"a budget below {RICCATI_STEP_UNITS} units cannot take a Riccati step")
        left = budget
        fields, n = self.fields, self.samples
        if len(fields) < 3 * n:
            r_N, v_N, angle, field_N = self._orbit
            q_tn, h = self.q_tn, self.step_s
            while left >= SAMPLE_UNITS and len(fields) < 3 * n:
                t = (len(fields) // 3) * h
                b_N = field_N(circular_position_N(r_N, v_N, t), angle + EARTH_ROTATION_RATE_RAD_S * t)
                fields.extend(rotate_n_to_b(q_tn, b_N))
                left -= SAMPLE_UNITS
                self.units_done += SAMPLE_UNITS
            if len(fields) < 3 * n:
                return None
        recursion = self._recursion
        if recursion is None:
            recursion = self._recursion = _RiccatiRecursion(fields, *self._weights)
        while left >= RICCATI_STEP_UNITS and recursion.idx:
            recursion.step()
            left -= RICCATI_STEP_UNITS
            self.units_done += RICCATI_STEP_UNITS
        if recursion.idx:
            return None
        return HoldGainTable(self.q_tn, self.t0_s, self.step_s, self.use_s, recursion.gains)


def hold_gain_table(q_tn: Quat, t0_s: float, r_N: Vec3, v_N: Vec3, earth_angle_rad: float, inertia, m_max: Vec3,
                    step_s: float, use_s: float, extra_s: float, theta_scale_rad: float, rate_scale_rad_s: float,
                    r_weight: float, alpha: float, field_N=dipole_field_N) -> HoldGainTable:  # noqa: N803
    """The table for ``use_s`` seconds from ``t0_s``: the on-board field model ``field_N(r_N, earth_angle)`` (T, N;
    the tilted dipole by default, ``control.geomagnetic.OnboardField``) along the circular propagation of
    ``(r_N, v_N)`` (the ephemeris at ``t0_s``, Earth angle ``earth_angle_rad`` then), turned into T by ``q_tn``,
    over ``use_s + extra_s`` (the extra backward horizon lets the gains at the start settle): a
    :class:`HoldGainTableBuilder` run to completion in one call (about 1 s of CPU for an orbit plus an orbit at
    1.4 s; a flight builds it over many control cycles instead)."""
    builder = HoldGainTableBuilder(q_tn, t0_s, r_N, v_N, earth_angle_rad, inertia, m_max, step_s, use_s, extra_s,
                                   theta_scale_rad, rate_scale_rad_s, r_weight, alpha, field_N)
    table = builder.advance(builder.units_total + RICCATI_STEP_UNITS)
    assert table is not None  # the whole budget finishes it
    return table


def lqr_dipole_B(gain: Gain, q_err: Quat, omega_B: Vec3) -> Vec3:
    """``m = −K (θ, ω)`` (A·m², in B) for the error ``q_err`` = ``q_BT`` (``θ = 2 q_err.v``, the same in B and T) and
    the rate ``omega_B`` (rad/s, B); the gain acts in T."""
    th = (2.0 * q_err[1], 2.0 * q_err[2], 2.0 * q_err[3])
    w_t = rotate_b_to_n(q_err, omega_B)
    x = th + w_t
    m_t = tuple(-sum(gain[6 * i + k] * x[k] for k in range(6)) for i in range(3))
    return rotate_n_to_b(q_err, (m_t[0], m_t[1], m_t[2]))
