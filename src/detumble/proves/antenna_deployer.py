"""AntennaDeployer as flown: deploys the antenna by burning its restraint, with retries.

DEPLOY starts attempt 1 (DeployAttempt(1), ``burnStart`` to the burnwire) unless the persisted
deployed flag is set (DeploymentAlreadyComplete, OK, nothing else) or a deployment is running (BUSY).
Every ``schedIn`` tick (1 Hz) of a burn counts; after ``BURN_DURATION_SEC`` ticks it calls
``burnStop`` and logs AntennaBurnSignalCount(ticks). With attempts left it waits ``RETRY_DELAY_SEC``
ticks (0: the next tick) and starts the next attempt; after ``MAX_DEPLOY_ATTEMPTS`` it finishes with
DEPLOY_RESULT_FAILED. DEPLOY_STOP aborts (DEPLOY_RESULT_ABORT). A deployment that finishes
SUCCESS *or FAILED* logs DeploySuccess and sets the deployed flag (the flight code does so: the
burn is assumed to have done its work), then DeployFinish(result, attempts).

The deployed flag is one byte, ``antenna/antenna_deployer.bin`` on the simulated flash
(``spacecraft.flash_dir``), written atomically; SET_DEPLOYMENT_STATE(b) and RESET_DEPLOYMENT_STATE
set it for ground tests. A file that cannot be written or read logs FileOperationError(path, op).

Ground interface (flight ``Components.AntennaDeployer``, base id 0x10022000): commands DEPLOY (0),
DEPLOY_STOP (1), RESET_DEPLOYMENT_STATE (2), SET_DEPLOYMENT_STATE (3); channel DeployAttemptCount;
events DeployAttempt, DeploySuccess, DeployFinish, AntennaBurnSignalCount, DeploymentAlreadyComplete,
FileOperationError; parameters RETRY_DELAY_SEC (30 s), MAX_DEPLOY_ATTEMPTS (3), BURN_DURATION_SEC (8 s).
The flight component (at the commit the suite was copied from) has no distance-sensor input: it
never reports DEPLOY_RESULT_SUCCESS, and neither does this one (``docs/components/antenna_deployer.md``).
"""

from __future__ import annotations

import enum
import os

from fprime_lite import (BOOL, U32, Channel, CmdResponse, Event, FwEnum, OutputPort, Param, PassiveComponent,
                         Sched, Severity, String, sync_command, sync_input)
from fprime_lite.osal.atomic import atomic_write_bytes

from detumble.drivers.ports import Signal
from detumble.drivers.spacecraft import SimulatedSpacecraft, require_spacecraft

__all__ = ["AntennaDeployer", "DeployResult", "STATE_FILE"]

#: The deployed flag's path in the simulated flash (flight ``//antenna/antenna_deployer.bin``).
STATE_FILE = os.path.join("antenna", "antenna_deployer.bin")


class DeployResult(FwEnum, namespace="Components"):
    """How a deployment ended (flight ``Components.DeployResult``)."""

    DEPLOY_RESULT_SUCCESS = 0
    DEPLOY_RESULT_ABORT = 1
    DEPLOY_RESULT_FAILED = 2


class _State(enum.Enum):
    IDLE = 0
    BURNING = 1
    RETRY_WAIT = 2


class AntennaDeployer(PassiveComponent):
    """Deploys the antenna of ``spacecraft`` through the burnwire (instance ``antennaDeployer``)."""

    # Instance state, set in __init__ (declared here: the handlers above it use it).
    state: _State
    attempt: int
    total_attempts: int
    ticks: int
    burn_ticks: int
    stop_requested: bool

    @sync_command()
    def DEPLOY(self):
        """Start the deployment (skipped when the deployed flag is set)."""
        if self.deployed():
            self.DeploymentAlreadyComplete()
            return CmdResponse.OK
        if self.state != _State.IDLE:
            return CmdResponse.BUSY
        self._reset()
        self._start_attempt()
        return CmdResponse.OK

    @sync_command()
    def DEPLOY_STOP(self):
        """Abort a running deployment."""
        if self.state != _State.IDLE:
            self.stop_requested = True
            self._finish(DeployResult.DEPLOY_RESULT_ABORT)
        return CmdResponse.OK

    @sync_command()
    def RESET_DEPLOYMENT_STATE(self):
        """Clear the deployed flag."""
        self._write_deployed(False)

    @sync_command()
    def SET_DEPLOYMENT_STATE(self, deployed: BOOL):
        """Set or clear the deployed flag."""
        self._write_deployed(bool(deployed))

    DeployAttemptCount = Channel(U32)

    DeployAttempt = Event(Severity.ACTIVITY_HI, "Antenna deployment attempt {} started", attempt=U32)
    DeploySuccess = Event(Severity.ACTIVITY_HI, "Antenna deployment succeeded on attempt {}", attempt=U32)
    DeployFinish = Event(Severity.ACTIVITY_HI, "Antenna deployment finished with result {} after {} attempts",
                         result=DeployResult, attempts=U32)
    AntennaBurnSignalCount = Event(Severity.ACTIVITY_LO, "Burn signal active for {} scheduler ticks", ticks=U32)
    DeploymentAlreadyComplete = Event(Severity.ACTIVITY_HI, "Antenna deployment skipped - antenna already deployed")
    FileOperationError = Event(Severity.WARNING_HI, "File operation failed: {} on file {}",
                               filePath=String(200), operation=String(40))

    @sync_input(Sched)
    def schedIn(self, context: int) -> None:
        """1 Hz: advance the burn or the wait between attempts."""
        if self.state == _State.BURNING:
            self._burning_tick()
        elif self.state == _State.RETRY_WAIT:
            self._retry_tick()

    burnStart = OutputPort(Signal)
    burnStop = OutputPort(Signal)

    RETRY_DELAY_SEC = Param(U32, default=30, units="s")
    MAX_DEPLOY_ATTEMPTS = Param(U32, default=3)
    BURN_DURATION_SEC = Param(U32, default=8, units="s")

    def __init__(self, name: str, spacecraft: SimulatedSpacecraft, *, base_id: int = 0):
        super().__init__(name, base_id=base_id)
        require_spacecraft(name, spacecraft)
        self.spacecraft = spacecraft
        self.total_attempts = 0
        self._reset()

    @property
    def state_path(self) -> str:
        return os.path.join(self.spacecraft.flash_dir, STATE_FILE)

    def deployed(self) -> bool:
        """The persisted deployed flag (a missing file is "not deployed")."""
        try:
            with open(self.state_path, "rb") as fh:
                return fh.read(1) == b"\x01"
        except FileNotFoundError:
            return False
        except OSError:
            self.FileOperationError(self.state_path, "open_read")
            return False

    # --- behaviour ------------------------------------------------------------------------------

    def _reset(self) -> None:
        self.state = _State.IDLE
        self.attempt = 0
        self.ticks = 0
        self.burn_ticks = 0
        self.stop_requested = False

    def _start_attempt(self) -> None:
        self.attempt += 1
        self.ticks = 0
        self.DeployAttempt(self.attempt)
        self.DeployAttemptCount.write(self.total_attempts)   # before the increment, as flown
        self.total_attempts += 1
        self.burn_ticks = 0
        if self.is_connected("burnStart", 0):
            self.burnStart[0]()
        self.state = _State.BURNING

    def _burning_tick(self) -> None:
        self.ticks += 1
        self.burn_ticks = self.ticks
        if self.ticks >= self.BURN_DURATION_SEC.value:
            self._stop_burn()
            if self.attempt >= self.MAX_DEPLOY_ATTEMPTS.value:
                self._finish(DeployResult.DEPLOY_RESULT_FAILED)
                return
            self.state = _State.RETRY_WAIT
            self.ticks = 0

    def _retry_tick(self) -> None:
        self.ticks += 1
        delay = self.RETRY_DELAY_SEC.value
        if delay == 0 or self.ticks >= delay:
            if self.attempt >= self.MAX_DEPLOY_ATTEMPTS.value:
                self._finish(DeployResult.DEPLOY_RESULT_FAILED)
            else:
                self._start_attempt()

    def _stop_burn(self) -> None:
        if self.is_connected("burnStop", 0):
            self.burnStop[0]()
        if self.burn_ticks > 0:
            self.AntennaBurnSignalCount(self.burn_ticks)
            self.burn_ticks = 0

    def _finish(self, result: DeployResult) -> None:
        if self.state == _State.IDLE:
            return
        self._stop_burn()
        if result in (DeployResult.DEPLOY_RESULT_SUCCESS, DeployResult.DEPLOY_RESULT_FAILED):
            self.DeploySuccess(self.attempt)
            self._write_deployed(True)
        self.DeployFinish(result, self.attempt)
        self._reset()

    def _write_deployed(self, deployed: bool) -> None:
        path = self.state_path
        try:
            os.makedirs(os.path.dirname(path), exist_ok=True)
            atomic_write_bytes(path, b"\x01" if deployed else b"\x00")
        except OSError:
            self.FileOperationError(path, "write")
