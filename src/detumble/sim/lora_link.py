"""The LoRa link's timing: how long a packet occupies the air (Semtech's time-on-air formula).

Pure arithmetic (no framework import). For spreading factor SF, bandwidth BW (Hz), coding rate
4/(4+CR), preamble ``n_preamble`` symbols, explicit header and CRC on, low-data-rate optimisation DE
when a symbol lasts 16 ms or more (SX127x/SX126x datasheets, AN1200.13)::

    T_sym = 2^SF / BW
    n_payload = 8 + max(ceil((8 PL − 4 SF + 28 + 16 CRC − 20 IH) / (4 (SF − 2 DE))) (CR + 4), 0)
    T_packet = (n_preamble + 4.25) T_sym + n_payload T_sym

``tests/detumble/sim/test_lora_link.py`` checks it against values from Semtech's LoRa calculator.
"""

from __future__ import annotations

import math

__all__ = ["time_on_air_s", "MAX_PAYLOAD"]

#: The largest LoRa payload, bytes.
MAX_PAYLOAD = 255


def time_on_air_s(payload_bytes: int, sf: int, bw_hz: float, cr: int = 1, *, n_preamble: int = 8,
                  crc: bool = True, implicit_header: bool = False) -> float:
    """Seconds on air of one packet of ``payload_bytes`` at spreading factor ``sf`` (6…12), bandwidth
    ``bw_hz`` and coding rate 4/(4+``cr``) (``cr`` 1…4)."""
    if not 0 <= payload_bytes <= MAX_PAYLOAD:
        raise ValueError(f"a LoRa payload is 0..{MAX_PAYLOAD} bytes, got {payload_bytes}")
    if sf not in range(6, 13) or cr not in range(1, 5) or bw_hz <= 0:
        raise ValueError(f"sf must be 6..12, cr 1..4 and bw positive; got sf={sf}, cr={cr}, bw={bw_hz}")
    t_sym = (1 << sf) / bw_hz
    de = 1 if t_sym >= 0.016 else 0
    num = 8 * payload_bytes - 4 * sf + 28 + (16 if crc else 0) - (20 if implicit_header else 0)
    n_payload = 8 + max(math.ceil(num / (4 * (sf - 2 * de))) * (cr + 4), 0)
    return (n_preamble + 4.25) * t_sym + n_payload * t_sym
