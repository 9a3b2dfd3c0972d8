"""BDotDetumble: a dipole-moment provider from two consecutive magnetometer readings (seed 002).

Behaviour, requirements and deviations: ``docs/components/bdot_detumble.md``.
Each ``dipoleMomentGet`` call reads the magnetometer once and returns::

    m = −Gain · Ḃ / |B|        Ḃ = (B_now − B_prev) / Δt

with B in gauss (body frame), Δt in seconds from the two readings' timestamps, Gain in A·m²·s
(``Gain`` parameter, default 1.0) and m in A·m² (body frame). DEVIATION: the seed writes
m = k·Ḃ/|B|; a positive gain must damp, as the flight code's own comment (m = −k·Ḃ/|B|) says.

The reply is a :class:`~detumble.components.types.Result` ``(DipoleMoment, Success)``. FAILURE (with a zero
dipole) on: the first call (it only primes the previous reading), a failed or non-finite
magnetometer read, |B| < 1e-6 G, or a zero Δt. A negative Δt (the clock went backwards) or a change
of time base also fails and re-primes with the new reading so the provider recovers.

Telemetry: the seed's channel ``Gain`` is named ``GainParam`` here, because fprime_lite cannot give
a parameter and a channel the same name (see the component doc page).
"""

from __future__ import annotations

import math

from fprime_lite import F64, Channel, OutputPort, Param, PassiveComponent, sync_input

from detumble.control.attitude_defaults import BDOT_MIN_FIELD_GAUSS, BDOT_PROVIDER_GAIN
from detumble.control.magnetic import normalised_bdot_dipole
from detumble.components.types import DipoleMoment, DipoleMomentGet, MagneticField, MagneticFieldGet, Result, Success
from detumble.components.types import new_result as _new_result  # Result(...) without its Python frame

__all__ = ["BDotDetumble", "MIN_FIELD_MAGNITUDE_GAUSS"]

#: Below this |B| (gauss) no dipole is computed (the plant-only law's provider uses the same value).
MIN_FIELD_MAGNITUDE_GAUSS = BDOT_MIN_FIELD_GAUSS
_SUCCESS = Success.SUCCESS  # read once: an enum class attribute costs a metaclass lookup; once a control cycle


def _zero_failure() -> Result:
    return Result(DipoleMoment(x=0.0, y=0.0, z=0.0), Success.FAILURE)


class BDotDetumble(PassiveComponent):
    """Computes a damping dipole moment on request (F´ namespace ``Drv``)."""

    #: B-dot gain, A·m²·s (m = −Gain·Ḃ/|B|); a negative gain would spin the spacecraft up, NaN or
    #: inf would make every dipole non-finite.
    Gain = Param(F64, default=BDOT_PROVIDER_GAIN, low=0.0, high=1000.0, units="A·m²·s")

    magneticFieldGet = OutputPort(MagneticFieldGet)

    #: The gain used by the latest computation (seed channel ``Gain``), A·m²·s.
    GainParam = Channel(F64)

    def __init__(self, name: str, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        self._field_port = self.output_port("magneticFieldGet")  # looked up once: read every control cycle
        #: The last reading used (or primed with); None until the first good read.
        self.previous_field: MagneticField | None = None

    @sync_input(DipoleMomentGet)
    def dipoleMomentGet(self):
        """Read the magnetometer and return ``Result(DipoleMoment A·m², Success)``."""
        port = self._field_port  # is_connected("magneticFieldGet", 0), on the port looked up once
        if port.targets[0] is None:
            return _zero_failure()
        field, condition = port.calls[0]()
        if condition != _SUCCESS or not _finite_field(field):
            return _zero_failure()
        previous = self.previous_field
        if previous is None:
            self.previous_field = field  # prime
            return _zero_failure()
        magnitude = math.sqrt(field.x * field.x + field.y * field.y + field.z * field.z)
        if magnitude < MIN_FIELD_MAGNITUDE_GAUSS:
            return _zero_failure()
        if field.timestamp.time_base != previous.timestamp.time_base:
            self.previous_field = field
            return _zero_failure()
        dt_us = field.timestamp.total_us - previous.timestamp.total_us
        if dt_us == 0:
            return _zero_failure()
        if dt_us < 0:
            self.previous_field = field
            return _zero_failure()
        dt = dt_us / 1e6
        gain = self.Gain.value
        self.GainParam.write(gain)
        x, y, z = normalised_bdot_dipole((previous.x, previous.y, previous.z), (field.x, field.y, field.z), dt, gain,
                                         magnitude)
        moment = DipoleMoment(x, y, z)
        self.previous_field = field
        if not (math.isfinite(moment.x) and math.isfinite(moment.y) and math.isfinite(moment.z)):
            return _zero_failure()
        return _new_result(Result, (moment, _SUCCESS))


def _finite_field(field) -> bool:
    try:
        return math.isfinite(field.x) and math.isfinite(field.y) and math.isfinite(field.z)
    except (AttributeError, TypeError):
        return False
