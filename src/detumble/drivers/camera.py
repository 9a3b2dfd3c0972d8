"""The simulated payload camera behind the CameraHandler: powered from face 4, it answers "snap".

A device of the simulated spacecraft: ``command(text)`` is what the flight software writes to the
camera's UART through PayloadCom. While face 4's load switch is closed the camera accepts ``snap``
(an image of ``image_bytes`` bytes, a deterministic test pattern with a JPEG start and end marker)
and ``ping`` (answers ``PONG``); unpowered, it accepts nothing. ``read(n)`` returns the next bytes it
sends back, at most ``n`` (the UART's pace is the caller's). Opening face 4's switch mid-transfer
cuts the stream.
"""

from __future__ import annotations

from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft

__all__ = ["SimulatedCamera", "IMAGE_HEADER", "PONG"]

#: The camera's image header: ``<IMG>`` then the size as 4 little-endian bytes.
IMAGE_HEADER = b"<IMG>"
PONG = b"PONG"


class SimulatedCamera:
    """The payload camera on face 4 of ``spacecraft``."""

    def __init__(self, spacecraft: SimulatedSpacecraft, *, image_bytes: int = 20_000, switch: str = "face4"):
        require_spacecraft("camera", spacecraft)
        if image_bytes < 4:
            raise ValueError(f"image_bytes must be at least 4 (JPEG markers), got {image_bytes}")
        self.spacecraft = spacecraft
        self.image_bytes = image_bytes
        self.switch = switch
        self.images_taken = 0
        self._out = bytearray()

    @property
    def powered(self) -> bool:
        return self.spacecraft.load_switch(self.switch)

    def command(self, text: str) -> bool:
        """The flight software writes ``text``; False when the camera is unpowered or does not know it."""
        if not self.powered:
            self._out.clear()
            return False
        word = text.strip().lower()
        if word == "snap":
            self.images_taken += 1
            n = self.image_bytes
            body = bytes((self.images_taken + i) & 0xFF for i in range(n - 4))
            self._out += IMAGE_HEADER + n.to_bytes(4, "little") + b"\xff\xd8" + body + b"\xff\xd9"
            return True
        if word == "ping":
            self._out += PONG
            return True
        return False

    def read(self, n: int) -> bytes:
        """Up to ``n`` bytes of what the camera sends back (nothing when unpowered)."""
        if not self.powered:
            self._out.clear()
            return b""
        chunk = bytes(self._out[:n])
        del self._out[:n]
        return chunk
