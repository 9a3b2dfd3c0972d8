"""BDotDetumble through its ports (seed 002 requirements BDot-001…004, detumble.md §6).

Fields in gauss, timestamps from the harness's test time, gain in A·m²·s, dipole in A·m².
"""

import math

import pytest

from detumble.components.bdot_detumble import BDotDetumble
from detumble.components.types import DipoleMoment, MagneticField, Result, Success
from fprime_lite import CmdResponse, Time, TimeBase

BASE = 0x10060000
T0 = Time(TimeBase.TB_WORKSTATION_TIME, 0, 500, 0)


class Magnetometer:
    """Returns the queued fields, stamped with the harness time at the read."""

    def __init__(self, h):
        self.h = h
        self.fields = []
        self.ok = True
        self.stamp = None  # override timestamp

    def __call__(self):
        x, y, z = self.fields.pop(0)
        stamp = self.stamp if self.stamp is not None else self.h.test_time
        return Result(MagneticField(x=x, y=y, z=z, timestamp=stamp),
                      Success.SUCCESS if self.ok else Success.FAILURE)


@pytest.fixture
def h(fprime_harness):
    harness = fprime_harness(BDotDetumble("bdotDetumble", base_id=BASE), test_time=T0)
    mag = Magnetometer(harness)
    harness.set_port_handler("magneticFieldGet", mag)
    harness.load_parameters()
    harness.mag = mag
    return harness


def get(h):
    return h.invoke("dipoleMomentGet")


def primed(h, first=(0.3, 0.0, 0.4)):
    h.mag.fields.append(first)
    reply = get(h)
    assert reply.condition == Success.FAILURE
    return reply


def test_first_call_primes_and_fails(h):
    """BDot-003 Robustness: the first call only stores the reading and answers FAILURE with a zero dipole."""
    reply = primed(h)
    assert reply.value == DipoleMoment(x=0.0, y=0.0, z=0.0)
    assert not reply.ok
    h.assert_tlm_size(0)


def test_bdot_law_hand_computed_with_damping_sign(h):
    """BDot-001 B-dot Law / DEVIATION (sign): B goes (0.3, 0, 0.4) → (0.3, 0.01, 0.4) G in 0.1 s:
    Ḃ = (0, 0.1, 0) G/s, |B| = 0.5000999900 G; with Gain 1.0, m = −Ḃ/|B| = (0, −0.19996, 0) A·m²
    (the seed's m = +k·Ḃ/|B| would pump energy in)."""
    primed(h)
    h.advance_time(useconds=100_000)
    h.mag.fields.append((0.3, 0.01, 0.4))
    reply = get(h)
    assert reply.condition == Success.SUCCESS
    magnitude = math.sqrt(0.3 ** 2 + 0.01 ** 2 + 0.4 ** 2)
    assert magnitude == pytest.approx(0.50009999, rel=1e-7)
    assert reply.value.x == 0.0 and reply.value.z == 0.0
    assert reply.value.y == pytest.approx(-0.1 / magnitude, rel=1e-12)
    assert reply.value.y == pytest.approx(-0.19996, rel=1e-4)


def test_consecutive_calls_use_the_previous_reading(h):
    """BDot-001 B-dot Law: each success becomes the next call's previous reading."""
    primed(h, (0.0, 0.0, 0.5))
    for step, bx in enumerate((0.01, 0.03), start=1):
        h.advance_time(useconds=50_000)
        h.mag.fields.append((bx, 0.0, 0.5))
        reply = get(h)
        assert reply.ok
        prev_bx = 0.0 if step == 1 else 0.01
        magnitude = math.hypot(bx, 0.5)
        assert reply.value.x == pytest.approx(-(bx - prev_bx) / 0.05 / magnitude, rel=1e-12)


def test_gain_parameter_scales_the_dipole(h):
    """BDot-002 Gain Param: Gain set by command scales the returned dipole proportionally."""
    primed(h)
    h.advance_time(useconds=100_000)
    h.mag.fields.append((0.31, 0.0, 0.4))
    m1 = get(h).value.x
    h.param_set("Gain", 2.5)
    h.param_send("Gain", cmd_seq=3)
    h.assert_cmd_response(0, "GAIN_PRM_SET", CmdResponse.OK, cmd_seq=3)
    h.advance_time(useconds=100_000)
    h.mag.fields.append((0.32, 0.0, 0.4))  # same Ḃ again
    m2 = get(h).value.x
    mag1, mag2 = math.hypot(0.31, 0.4), math.hypot(0.32, 0.4)
    assert m2 == pytest.approx(2.5 * m1 * mag1 / mag2, rel=1e-9)
    assert m1 < 0 and m2 < 0


def test_gain_telemetered_on_each_computation(h):
    """BDot-004 Telemetry: the Gain in use is telemetered on every computation (not on failures)."""
    primed(h)
    for gain in (1.0, 4.0):
        h.component.Gain.set(gain)
        h.advance_time(useconds=20_000)
        h.mag.fields.append((0.3, 0.0, 0.4))
        assert get(h).ok
    assert h.tlm_values("GainParam") == [1.0, 4.0]
    h.mag.fields.append((0.3, 0.0, 0.4))  # same timestamp: Δt = 0, no computation
    assert not get(h).ok
    assert h.tlm_values("GainParam") == [1.0, 4.0]


def test_default_gain_is_one(h):
    """BDot-002 Gain Param: the Gain parameter defaults to 1.0 A·m²·s."""
    assert h.component.Gain.value == 1.0


def test_tiny_field_fails_with_zero_dipole(h):
    """BDot-003 Robustness: |B| < 1e-6 G answers FAILURE with a zero dipole."""
    primed(h)
    h.advance_time(useconds=20_000)
    h.mag.fields.append((5e-7, 0.0, 5e-7))
    reply = get(h)
    assert reply.condition == Success.FAILURE and reply.value == DipoleMoment()
    # The previous reading is kept: the next good read differentiates against the primed one.
    h.advance_time(useconds=20_000)
    h.mag.fields.append((0.3, 0.0, 0.404))
    reply = get(h)
    assert reply.ok and reply.value.z == pytest.approx(-(0.004 / 0.04) / math.hypot(0.3, 0.404))


def test_zero_dt_fails_with_zero_dipole(h):
    """BDot-003 Robustness: two readings with the same timestamp (Δt = 0) answer FAILURE, zero dipole."""
    primed(h)
    h.mag.fields.append((0.3, 0.1, 0.4))
    reply = get(h)
    assert reply.condition == Success.FAILURE and reply.value == DipoleMoment()


def test_clock_going_backwards_fails_then_recovers(h):
    """BDot-003 Robustness: a reading older than the previous one fails and re-primes, no exception."""
    primed(h)
    h.mag.stamp = Time(TimeBase.TB_WORKSTATION_TIME, 0, 100, 0)
    h.mag.fields.append((0.3, 0.0, 0.4))
    assert not get(h).ok
    h.mag.stamp = Time(TimeBase.TB_WORKSTATION_TIME, 0, 100, 20_000)
    h.mag.fields.append((0.3, 0.002, 0.4))
    reply = get(h)
    assert reply.ok and reply.value.y == pytest.approx(-0.1 / math.hypot(0.3, 0.002, 0.4))


def test_failed_magnetometer_read_fails_without_priming(h):
    """BDot-003 Robustness: a FAILURE from the magnetometer is passed on and does not prime."""
    h.mag.ok = False
    h.mag.fields.append((0.3, 0.0, 0.4))
    assert not get(h).ok
    assert h.component.previous_field is None


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_field_fails_without_raising(h, bad):
    """BDot-003 Robustness: NaN/inf field components answer FAILURE with a zero dipole, never raise,
    and never become the previous reading."""
    primed(h)
    previous = h.component.previous_field
    h.advance_time(useconds=20_000)
    h.mag.fields.append((0.3, bad, 0.4))
    reply = get(h)
    assert reply.condition == Success.FAILURE and reply.value == DipoleMoment()
    assert h.component.previous_field is previous


def test_unconnected_magnetometer_fails(fprime_harness):
    """BDot-003 Robustness: without a magnetometer connection the answer is FAILURE."""
    harness = fprime_harness(BDotDetumble("bdotDetumble", base_id=BASE), test_time=T0)
    harness.component.output_port("magneticFieldGet").disconnect(0)
    assert harness.invoke("dipoleMomentGet").condition == Success.FAILURE
