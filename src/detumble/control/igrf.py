"""IGRF-14 (International Geomagnetic Reference Field, 14th generation) to degree and order 13, epoch 2025.0.

The Gauss coefficients ``g_n^m``, ``h_n^m`` (nT) of the 2025.0 main field and their secular variation (nT/yr, the
predictive 2025–2030 model: the published 2030.0 column minus 2025.0, over 5 years), as published by IAGA
Working Group V-MOD (Alken et al. 2025, doi:10.5281/zenodo.14012302; the released ``IGRF14.shc``). Degree 1 is
the tilted dipole the plant's ``sim.field.DipoleField`` and the on-board ``control.geomagnetic`` use (g10 = −29350.0,
g11 = −1410.3, h11 = 4545.5).

:class:`IgrfField` evaluates the geocentric spherical-harmonic expansion (Schmidt semi-normalised associated
Legendre functions, reference radius 6371.2 km) at a position in N, tesla, in plain floats: about 195 terms, a few
hundred microseconds a call — the plant wraps it in ``sim.field.FieldAlongOrbit`` with a table step
(``field.table_step_s``, 1 s by default) as for the WMM. Valid 2025–2030; outside it the linear secular variation
extrapolates. Plain floats, no framework import: the plant's field (``sim.igrf`` re-exports it) and, truncated, the
flight software's on-board model (MAG_FIELD_MODEL_DEGREE, ``control.three_mode``).
"""

from __future__ import annotations

import math

__all__ = ["IGRF14_2025", "IgrfField"]

#: (n, m, g_n^m nT, h_n^m nT, dg/dt nT/yr, dh/dt nT/yr) at 2025.0, n = 1…13, m = 0…n (h_n^0 = 0)
IGRF14_2025: tuple[tuple[int, int, float, float, float, float], ...] = (
    (1, 0, -29350.0, 0.0, 12.6, 0.0),
    (1, 1, -1410.3, 4545.5, 10.0, -21.5),
    (2, 0, -2556.2, 0.0, -11.2, 0.0),
    (2, 1, 2950.9, -3133.6, -5.3, -27.3),
    (2, 2, 1648.7, -814.2, -8.3, -11.1),
    (3, 0, 1360.9, 0.0, -1.5, 0.0),
    (3, 1, -2404.2, -56.9, -4.4, 3.8),
    (3, 2, 1243.8, 237.6, 0.4, -0.2),
    (3, 3, 453.4, -549.6, -15.6, -3.9),
    (4, 0, 894.7, 0.0, -1.7, 0.0),
    (4, 1, 799.6, 278.6, -2.3, -1.3),
    (4, 2, 55.8, -134.0, -5.8, 4.1),
    (4, 3, -281.1, 212.0, 5.4, 1.6),
    (4, 4, 12.0, -375.4, -6.8, -4.1),
    (5, 0, -232.9, 0.0, 0.6, 0.0),
    (5, 1, 369.0, 45.3, 1.3, -0.5),
    (5, 2, 187.2, 220.0, 0.0, 2.1),
    (5, 3, -138.7, -122.9, 0.7, 0.5),
    (5, 4, -141.9, 42.9, 2.3, 1.7),
    (5, 5, 20.9, 106.2, 1.0, 1.9),
    (6, 0, 64.3, 0.0, -0.2, 0.0),
    (6, 1, 63.8, -18.4, -0.3, 0.3),
    (6, 2, 76.7, 16.8, 0.8, -1.6),
    (6, 3, -115.7, 48.9, 1.2, -0.4),
    (6, 4, -40.9, -59.8, -0.8, 0.8),
    (6, 5, 14.9, 10.9, 0.4, 0.7),
    (6, 6, -60.8, 72.8, 0.9, 0.9),
    (7, 0, 79.6, 0.0, -0.1, 0.0),
    (7, 1, -76.9, -48.9, -0.1, 0.6),
    (7, 2, -8.8, -14.4, -0.1, 0.5),
    (7, 3, 59.3, -1.0, 0.5, -0.7),
    (7, 4, 15.8, 23.5, -0.1, 0.0),
    (7, 5, 2.5, -7.4, -0.8, -0.9),
    (7, 6, -11.2, -25.1, -0.8, 0.5),
    (7, 7, 14.3, -2.2, 0.9, -0.3),
    (8, 0, 23.1, 0.0, -0.1, 0.0),
    (8, 1, 10.9, 7.2, 0.2, -0.3),
    (8, 2, -17.5, -12.6, 0.0, 0.4),
    (8, 3, 2.0, 11.5, 0.4, -0.3),
    (8, 4, -21.8, -9.7, -0.1, 0.4),
    (8, 5, 16.9, 12.7, 0.3, -0.5),
    (8, 6, 14.9, 0.7, 0.1, -0.6),
    (8, 7, -16.8, -5.2, 0.0, 0.3),
    (8, 8, 1.0, 3.9, 0.3, 0.2),
    (9, 0, 4.7, 0.0, 0.0, 0.0),
    (9, 1, 8.0, -24.8, 0.0, 0.0),
    (9, 2, 3.0, 12.1, 0.0, 0.0),
    (9, 3, -0.2, 8.3, 0.0, 0.0),
    (9, 4, -2.5, -3.4, 0.0, 0.0),
    (9, 5, -13.1, -5.3, 0.0, 0.0),
    (9, 6, 2.4, 7.2, 0.0, 0.0),
    (9, 7, 8.6, -0.6, 0.0, 0.0),
    (9, 8, -8.7, 0.8, 0.0, 0.0),
    (9, 9, -12.8, 9.8, 0.0, 0.0),
    (10, 0, -1.3, 0.0, 0.0, 0.0),
    (10, 1, -6.4, 3.3, 0.0, 0.0),
    (10, 2, 0.2, 0.1, 0.0, 0.0),
    (10, 3, 2.0, 2.5, 0.0, 0.0),
    (10, 4, -1.0, 5.4, 0.0, 0.0),
    (10, 5, -0.5, -9.0, 0.0, 0.0),
    (10, 6, -0.9, 0.4, 0.0, 0.0),
    (10, 7, 1.5, -4.2, 0.0, 0.0),
    (10, 8, 0.9, -3.8, 0.0, 0.0),
    (10, 9, -2.6, 0.9, 0.0, 0.0),
    (10, 10, -3.9, -9.0, 0.0, 0.0),
    (11, 0, 3.0, 0.0, 0.0, 0.0),
    (11, 1, -1.4, 0.0, 0.0, 0.0),
    (11, 2, -2.5, 2.8, 0.0, 0.0),
    (11, 3, 2.4, -0.6, 0.0, 0.0),
    (11, 4, -0.6, 0.1, 0.0, 0.0),
    (11, 5, 0.0, 0.5, 0.0, 0.0),
    (11, 6, -0.6, -0.3, 0.0, 0.0),
    (11, 7, -0.1, -1.2, 0.0, 0.0),
    (11, 8, 1.1, -1.7, 0.0, 0.0),
    (11, 9, -1.0, -2.9, 0.0, 0.0),
    (11, 10, -0.1, -1.8, 0.0, 0.0),
    (11, 11, 2.6, -2.3, 0.0, 0.0),
    (12, 0, -2.0, 0.0, 0.0, 0.0),
    (12, 1, -0.1, -1.2, 0.0, 0.0),
    (12, 2, 0.4, 0.6, 0.0, 0.0),
    (12, 3, 1.2, 1.0, 0.0, 0.0),
    (12, 4, -1.2, -1.5, 0.0, 0.0),
    (12, 5, 0.6, 0.0, 0.0, 0.0),
    (12, 6, 0.5, 0.6, 0.0, 0.0),
    (12, 7, 0.5, -0.2, 0.0, 0.0),
    (12, 8, -0.1, 0.8, 0.0, 0.0),
    (12, 9, -0.5, 0.1, 0.0, 0.0),
    (12, 10, -0.2, -0.9, 0.0, 0.0),
    (12, 11, -1.2, 0.1, 0.0, 0.0),
    (12, 12, -0.7, 0.2, 0.0, 0.0),
    (13, 0, 0.2, 0.0, 0.0, 0.0),
    (13, 1, -0.9, -0.9, 0.0, 0.0),
    (13, 2, 0.6, 0.7, 0.0, 0.0),
    (13, 3, 0.7, 1.2, 0.0, 0.0),
    (13, 4, -0.2, -0.3, 0.0, 0.0),
    (13, 5, 0.5, -1.3, 0.0, 0.0),
    (13, 6, 0.1, -0.1, 0.0, 0.0),
    (13, 7, 0.7, 0.2, 0.0, 0.0),
    (13, 8, 0.0, -0.2, 0.0, 0.0),
    (13, 9, 0.3, 0.5, 0.0, 0.0),
    (13, 10, 0.2, 0.6, 0.0, 0.0),
    (13, 11, 0.4, -0.6, 0.0, 0.0),
    (13, 12, -0.5, -0.3, 0.0, 0.0),
    (13, 13, -0.4, -0.5, 0.0, 0.0),
)

_REFERENCE_RADIUS_M = 6371200.0


class IgrfField:
    """IGRF-14 in the inertial frame N, tesla, rotating with the Earth as :class:`.field.DipoleField` does.

    ``year`` the decimal year at t = 0 (the coefficients are carried to it by their secular variation and held
    there for the run: 20 nT/yr at most, 1e-3 of the field over a year); ``max_degree`` truncates the expansion
    (1 gives the dipole); ``earth_rotation_rate`` rad/s and ``theta0_rad`` the Earth rotation angle at t = 0.
    """

    def __init__(self, year: float = 2025.0, max_degree: int = 13, earth_rotation_rate: float = 7.2921159e-5,
                 theta0_rad: float = 0.0) -> None:
        if not 1 <= int(max_degree) <= 13:
            raise ValueError(f"max_degree must be 1…13, got {max_degree}")
        self.year = float(year)
        self.max_degree = int(max_degree)
        self.earth_rotation_rate = float(earth_rotation_rate)
        self.theta0_rad = float(theta0_rad)
        dt = self.year - 2025.0
        self.g = [[0.0] * (n + 1) for n in range(self.max_degree + 1)]
        self.h = [[0.0] * (n + 1) for n in range(self.max_degree + 1)]
        for n, m, g, h, gd, hd in IGRF14_2025:
            if n <= self.max_degree:
                self.g[n][m] = g + gd * dt
                self.h[n][m] = h + hd * dt
        nmax = self.max_degree
        #: recursion constants of the Schmidt semi-normalised functions
        self._k1 = [[0.0] * (n + 1) for n in range(nmax + 1)]
        self._k2 = [[0.0] * (n + 1) for n in range(nmax + 1)]
        for n in range(2, nmax + 1):
            for m in range(0, n):
                s = math.sqrt(n * n - m * m)
                self._k1[n][m] = (2 * n - 1) / s
                self._k2[n][m] = math.sqrt((n - 1) * (n - 1) - m * m) / s
        self._kd = [0.0, 1.0] + [math.sqrt((2 * n - 1) / (2 * n)) for n in range(2, nmax + 1)]

    def b_ecef(self, r_E: tuple[float, float, float]) -> tuple[float, float, float]:  # noqa: N803 - frame suffix
        """The field (T) in Earth-fixed Cartesian axes at ``r_E`` (m, geocentric)."""
        x, y, z = r_E
        rho = math.hypot(x, y)
        r = math.hypot(rho, z)
        ct, st = z / r, max(rho / r, 1e-12)
        cp, sp = (x / rho, y / rho) if rho > 0.0 else (1.0, 0.0)
        nmax = self.max_degree
        # P_n^m(cos θ) and dP_n^m/dθ, Schmidt semi-normalised
        p = [[0.0] * (n + 1) for n in range(nmax + 1)]
        dp = [[0.0] * (n + 1) for n in range(nmax + 1)]
        p[0][0] = 1.0
        for n in range(1, nmax + 1):
            k = self._kd[n]
            p[n][n] = k * st * p[n - 1][n - 1]
            dp[n][n] = k * (ct * p[n - 1][n - 1] + st * dp[n - 1][n - 1])
            for m in range(0, n):
                if n == 1:  # m = 0
                    p[1][0], dp[1][0] = ct, -st
                    continue
                k1, k2 = self._k1[n][m], self._k2[n][m]
                pm2, dpm2 = (p[n - 2][m], dp[n - 2][m]) if m <= n - 2 else (0.0, 0.0)
                p[n][m] = k1 * ct * p[n - 1][m] - k2 * pm2
                dp[n][m] = k1 * (ct * dp[n - 1][m] - st * p[n - 1][m]) - k2 * dpm2
        # cos mφ, sin mφ
        cm, sm = [1.0], [0.0]
        for _ in range(nmax):
            cm.append(cm[-1] * cp - sm[-1] * sp)
            sm.append(sm[-1] * cp + cm[-2] * sp)
        br = bt = bp = 0.0
        ar = _REFERENCE_RADIUS_M / r
        f = ar * ar
        for n in range(1, nmax + 1):
            f *= ar  # (a/r)^(n+2)
            gn, hn, pn, dpn = self.g[n], self.h[n], p[n], dp[n]
            sr = st_ = sp_ = 0.0
            for m in range(n + 1):
                c = gn[m] * cm[m] + hn[m] * sm[m]
                sr += c * pn[m]
                st_ += c * dpn[m]
                sp_ += m * (gn[m] * sm[m] - hn[m] * cm[m]) * pn[m]
            br += (n + 1) * f * sr
            bt -= f * st_
            bp += f * sp_
        bp /= st
        e = (br * st + bt * ct) * 1e-9
        return (e * cp - bp * 1e-9 * sp, e * sp + bp * 1e-9 * cp, (br * ct - bt * st) * 1e-9)

    def b_N(self, t: float, r_N: tuple[float, float, float]) -> tuple[float, float, float]:
        """Field (T) in N at position ``r_N`` (m) and time ``t`` (s after epoch)."""
        return self.b_N_at_angle(r_N, self.theta0_rad + self.earth_rotation_rate * t)

    def b_N_at_angle(self, r_N: tuple[float, float, float], earth_angle_rad: float) -> tuple[float, float, float]:  # noqa: N802
        """Field (T) in N at position ``r_N`` (m) with the Earth turned ``earth_angle_rad`` (rad) from N to ECEF."""
        c, s = math.cos(earth_angle_rad), math.sin(earth_angle_rad)
        x, y, z = r_N
        bx, by, bz = self.b_ecef((c * x + s * y, -s * x + c * y, z))
        return (c * bx - s * by, s * bx + c * by, bz)
