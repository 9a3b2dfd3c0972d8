"""CameraHandler as flown: takes an image with the payload camera and saves it to the flash.

TAKE_IMAGE sends ``snap`` to the camera (:class:`detumble.drivers.camera.SimulatedCamera`, powered
from face 4's load switch); PING sends ``ping``; SEND_COMMAND(cmd) sends ``cmd``. A command the camera
does not take (unpowered, unknown) logs CommandError(cmd) and answers EXECUTION_ERROR; one it takes
logs CommandSuccess(cmd). A command while an image is arriving logs FailedCommandCurrentlyReceiving
and answers BUSY. Every ``schedIn`` tick (10 Hz) reads up to ``bytes_per_tick`` from the camera (the
UART's pace: 11 520 B/s at 115200 baud, 1152 B a tick): the image header starts a transfer
(ImageTransferStarted(size)), progress is logged at 25, 50 and 75 % (ImageTransferProgress), and
the complete image is written atomically to ``images/img_NNNN.jpg`` on the simulated flash
(ImageTransferComplete(path, size); ImagesSaved). A reply ``PONG`` logs PongReceived (BadPongReceived
when no ping was sent). The camera losing power mid-transfer leaves the transfer open; the next
TAKE_IMAGE is refused (BUSY) until the flight software resets.

Ground interface (flight ``Components.CameraHandler``, base id 0x1002B000): commands TAKE_IMAGE (0),
PING (1), SEND_COMMAND(cmd) (2); the flight events in order; channels BytesReceived, ExpectedSize,
IsReceiving, FileOpen, FileErrorCount, ImagesSaved. Deviation: PayloadCom and its UART are folded
into the camera model.
"""

from __future__ import annotations

import os
from typing import Annotated

from fprime_lite import (BOOL, U8, U32, Channel, CmdResponse, Event, PassiveComponent, Sched, Severity, String,
                         sync_command, sync_input)
from fprime_lite.osal.atomic import atomic_write_bytes

from detumble.drivers.camera import IMAGE_HEADER, PONG, SimulatedCamera
from detumble.drivers.spacecraft import SimulatedSpacecraft

__all__ = ["CameraHandler", "IMAGE_DIR"]

IMAGE_DIR = "images"
_HEADER_LEN = len(IMAGE_HEADER) + 4


class CameraHandler(PassiveComponent):
    """Takes images with the simulated camera of ``spacecraft`` (instance ``cameraHandler``)."""

    # Instance state, set in __init__ (declared here: the handlers above it use it).
    receiving: bool
    expected: int
    _milestone: int
    _ping_pending: bool
    _buffer: bytearray

    @sync_command()
    def TAKE_IMAGE(self):
        """Take an image (``snap``)."""
        return self._send("snap")

    @sync_command()
    def PING(self):
        """Ping the camera (``ping``)."""
        return self._send("ping")

    @sync_command()
    def SEND_COMMAND(self, cmd: Annotated[str, String(40)]):
        """Send ``cmd`` to the camera."""
        return self._send(cmd)

    CommandError = Event(Severity.WARNING_HI, "Failed to send {} command", cmd=String(40))
    CommandSuccess = Event(Severity.ACTIVITY_HI, "Command {} sent successfully", cmd=String(40))
    ImageTransferStarted = Event(Severity.ACTIVITY_HI, "Image transfer started, expecting {} bytes", size=U32)
    ImageTransferProgress = Event(Severity.ACTIVITY_HI, "Image transfer {}% complete ({}/{} bytes)",
                                  percent=U8, received=U32, expected=U32)
    ImageTransferComplete = Event(Severity.ACTIVITY_HI, "Image saved: {} ({} bytes)", path=String(100), size=U32)
    FailedCommandCurrentlyReceiving = Event(Severity.WARNING_LO, "Cannot send command while image is receiving!")
    PongReceived = Event(Severity.ACTIVITY_HI, "Ping Received")
    BadPongReceived = Event(Severity.WARNING_HI, "Ping Received when we did not expect it!")
    FileWriteError = Event(Severity.WARNING_HI, "File write error occurred during image transfer")
    FileReadError = Event(Severity.WARNING_HI, "File read error occurred during image transfer")

    BytesReceived = Channel(U32)
    ExpectedSize = Channel(U32)
    IsReceiving = Channel(BOOL)
    FileOpen = Channel(BOOL)
    FileErrorCount = Channel(U32)
    ImagesSaved = Channel(U32)

    @sync_input(Sched)
    def schedIn(self, context: int) -> None:
        """10 Hz: take what the camera sent since the last tick."""
        data = self.camera.read(self.bytes_per_tick)
        if not data:
            return
        self._buffer += data
        if not self.receiving:
            if self._buffer.startswith(PONG):
                del self._buffer[:len(PONG)]
                (self.PongReceived if self._ping_pending else self.BadPongReceived)()
                self._ping_pending = False
            if len(self._buffer) >= _HEADER_LEN and self._buffer.startswith(IMAGE_HEADER):
                self.expected = int.from_bytes(self._buffer[len(IMAGE_HEADER):_HEADER_LEN], "little")
                del self._buffer[:_HEADER_LEN]
                self.receiving, self._milestone = True, 0
                self.ImageTransferStarted(self.expected)
                self.ExpectedSize.write(self.expected)
                self.IsReceiving.write(True)
        if self.receiving:
            got = min(len(self._buffer), self.expected)
            self.BytesReceived.write(got)
            while self._milestone < 3 and got * 4 >= (self._milestone + 1) * self.expected:
                self._milestone += 1
                self.ImageTransferProgress(25 * self._milestone, got, self.expected)
            if got >= self.expected:
                self._save(bytes(self._buffer[:self.expected]))
                del self._buffer[:self.expected]

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0, bytes_per_tick: int = 1152,
                 image_bytes: int = 20_000):
        super().__init__(name, base_id=base_id)
        self.spacecraft = spacecraft
        self.camera = SimulatedCamera(spacecraft, image_bytes=image_bytes)
        self.bytes_per_tick = int(bytes_per_tick)
        self.receiving = False
        self.expected = 0
        self.images_saved = 0
        self.file_errors = 0
        self._milestone = 0
        self._ping_pending = False
        self._buffer = bytearray()

    def _send(self, cmd: str):
        if self.receiving:
            self.FailedCommandCurrentlyReceiving()
            return CmdResponse.BUSY
        if not self.camera.command(cmd):
            self.CommandError(cmd)
            return CmdResponse.EXECUTION_ERROR
        self._ping_pending = self._ping_pending or cmd.strip().lower() == "ping"
        self.CommandSuccess(cmd)
        return CmdResponse.OK

    def _save(self, image: bytes) -> None:
        self.receiving = False
        self.IsReceiving.write(False)
        rel = os.path.join(IMAGE_DIR, f"img_{self.images_saved:04d}.jpg")
        path = os.path.join(self.spacecraft.flash_dir, rel)
        try:
            os.makedirs(os.path.dirname(path), exist_ok=True)
            atomic_write_bytes(path, image)
        except OSError:
            self.file_errors += 1
            self.FileWriteError()
            self.FileErrorCount.write(self.file_errors)
            return
        self.images_saved += 1
        self.ImageTransferComplete("/" + rel.replace(os.sep, "/"), len(image))
        self.ImagesSaved.write(self.images_saved)
