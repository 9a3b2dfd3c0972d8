"""Version: tells the ground which framework, project, library and custom versions are flying.

F´'s ``Svc.Version`` (a *passive* component; instance ``version`` in F´'s CdhCore subtopology).
It knows three kinds of fixed version string, given when the deployment is built, and up to
:data:`NUM_CUSTOM_VERSIONS` custom versions that other components set at run time:

- the framework version (by default the installed fprime-lite's version);
- the project version (the topology's, by default ``"unknown"``);
- the library versions, any number: each one is an event, the first
  :data:`NUM_LIBRARY_CHANNELS` also have a channel (``LibraryVersion01`` …);
- custom versions, one slot per ``Svc.VersionCfg.VersionEnum`` constant, written through the
  ``setVersion`` port and read back through ``getVersion``.

Reporting a version means emitting its event and writing its channel. At start-up (the
``parameters_loaded`` hook, once) the framework, project and library versions are reported, as
F´'s ``start()`` does. The ``VERSION`` command reports one kind (or ``ALL``: project, framework,
libraries, custom, in that order). ``setVersion`` reports the slot it wrote. A custom version is
always reported by event; its ``CustomVersionNN`` channel is written only while verbosity is on
(``ENABLE`` command, or :meth:`Version.config` / ``startup_verbose=``, F´'s ``config(enable)``).
Strings longer than F´'s bounds (40 bytes for events and string channels, 80 for the custom
version value) are truncated, never refused.

Ports, commands, events, channels and types carry F´ v4's names, opcodes, ids, severities, formats
and namespaces (``Svc/Version/Version.fpp``, ``Svc/Ports/VersionPorts``, ``VersionCfg.fpp``) —
including the ``LibraryVersions`` format's spelling ``"Libary Versions: [{}]"``, which is F´'s.

Differences from F´:

- The ``Svc.Version`` port's two ``ref`` arguments (``version_string``, ``status``) come back as
  the call's return value ``(version_string, status)``: ``getVersion`` returns the slot's value
  and status; ``setVersion`` returns its arguments unchanged.
- A ``version_id`` that is not a ``VersionEnum`` constant, a ``status`` that is not a
  ``VersionStatus`` or a ``version_string`` that is not text makes F´ assert; here the call is
  logged, counted in :attr:`Version.rejected_calls`, changes nothing and answers
  ``(…, VersionStatus.FAILURE)``.
- A custom slot counts as set once ``setVersion`` has written it. F´ marks unset slots with the
  value ``"no_ver"``, so a version set to that literal text is treated as unset there.
- Truncation keeps whole UTF-8 characters (F´ cuts at the byte bound and may split one); text
  that is not valid UTF-8 (lone surrogates) has those characters replaced by ``?``.
- The versions are constructor arguments; F´ compiles them in from a generated ``version.hpp``.
  The framework version defaults to fprime-lite's own version (F´: F´'s git version).
- Start-up reporting runs in the ``parameters_loaded`` hook — after parameters load, before the
  rate groups start — and only once per instance (later ``load_parameters()`` calls do not
  repeat it); ``report_at_startup=False`` skips it, as a topology that never calls F´'s
  ``start()``. F´ v4 reports in ``start()`` (startTasks phase); older F´ reported inside
  ``config()``.
- Verbosity defaults to on (``startup_verbose=True``), what F´'s CdhCore configures with
  ``config(true)``; F´'s own constructor default is off.
- No ``prmGetOut``/``prmSetOut`` ports: F´ declares them but the component has no parameters.

Python note: F´ names an event and a channel ``FrameworkVersion`` (and ``ProjectVersion``). The
channels are declared with ``Channel(..., name="FrameworkVersion")`` under the attributes
``FrameworkVersion_channel`` / ``ProjectVersion_channel``; the dictionary, the harness and
``version.channels`` use the F´ names.
"""

from __future__ import annotations

import importlib.metadata
import logging
from collections.abc import Sequence
from typing import Annotated

from fprime_lite.model.commands import guarded_command
from fprime_lite.model.component import PassiveComponent
from fprime_lite.model.errors import SerializationError
from fprime_lite.model.events import Event, Severity
from fprime_lite.model.ports import PortType, guarded_input
from fprime_lite.model.telemetry import Channel
from fprime_lite.model.types import U32, FwEnum, String, Struct, fit_utf8, fw_type

__all__ = [
    "CUSTOM_VERSION_SIZE",
    "NO_VERSION",
    "NUM_CUSTOM_VERSIONS",
    "NUM_LIBRARY_CHANNELS",
    "VERSION_STRING_SIZE",
    "CustomVersionDb",
    "Version",
    "VersionEnabled",
    "VersionEnum",
    "VersionPort",
    "VersionStatus",
    "VersionType",
    "installed_framework_version",
]

log = logging.getLogger("fprime_lite")

#: Bound in bytes of the version strings of events and string channels (FPP ``string size 40``).
VERSION_STRING_SIZE = 40
#: Bound in bytes of a custom version value (``CustomVersionDb.version_value: string size 80``).
CUSTOM_VERSION_SIZE = 80
#: Number of custom version slots (constants of ``Svc.VersionCfg.VersionEnum``).
NUM_CUSTOM_VERSIONS = 10
#: Library versions that also get a channel (``LibraryVersion01`` … ``LibraryVersion10``).
NUM_LIBRARY_CHANNELS = 10
#: Value of a custom slot nobody has set (F´'s marker).
NO_VERSION = "no_ver"


class VersionEnabled(FwEnum, namespace="Svc"):
    """Verbosity of custom versions (F´ ``Svc.VersionEnabled``)."""

    DISABLED = 0
    ENABLED = 1


class VersionType(FwEnum, namespace="Svc"):
    """Which versions the ``VERSION`` command reports (F´ ``Svc.VersionType``)."""

    PROJECT = 0
    FRAMEWORK = 1
    LIBRARY = 2
    CUSTOM = 3
    ALL = 4


class VersionStatus(FwEnum, namespace="Svc"):
    """Whether a custom version is good (F´ ``Svc.VersionStatus``)."""

    OK = 0
    FAILURE = 1


class VersionEnum(FwEnum, namespace="Svc.VersionCfg", rep=U32):
    """The custom version slots (F´'s default ``Svc.VersionCfg.VersionEnum``)."""

    PROJECT_VERSION_00 = 0
    PROJECT_VERSION_01 = 1
    PROJECT_VERSION_02 = 2
    PROJECT_VERSION_03 = 3
    PROJECT_VERSION_04 = 4
    PROJECT_VERSION_05 = 5
    PROJECT_VERSION_06 = 6
    PROJECT_VERSION_07 = 7
    PROJECT_VERSION_08 = 8
    PROJECT_VERSION_09 = 9


class CustomVersionDb(Struct, namespace="Svc"):
    """One custom version as its ``CustomVersionNN`` channel carries it (F´ ``Svc.CustomVersionDb``)."""

    version_enum: VersionEnum
    version_value: Annotated[str, String(80)]
    version_status: VersionStatus


#: Set or get one custom version (F´ ``Svc.Version``). F´'s ``ref`` arguments ``version_string``
#: and ``status`` are returned as ``(version_string, status)``.
VersionPort = PortType("Svc.Version", returns=tuple, version_id=VersionEnum, version_string=str,
                       status=VersionStatus)

_VERSION_ENUM = fw_type(VersionEnum)
_VERSION_STATUS = fw_type(VersionStatus)



def installed_framework_version() -> str:
    """The installed fprime-lite distribution's version, or ``"unknown"`` when it is not installed."""
    try:
        return importlib.metadata.version("fprime-lite")
    except importlib.metadata.PackageNotFoundError:
        return "unknown"


class Version(PassiveComponent):
    """F´'s version reporter (``Svc.Version``).

    Args:
        name: instance name (``version`` in F´'s CdhCore).
        framework_version: the framework's version; None means the installed fprime-lite's.
        project_version: the project's version.
        library_versions: one string per library, reported in this order.
        startup_verbose: F´'s ``config(enable)``: whether custom versions are also written to their
            channels (events are always emitted).
        report_at_startup: report the framework, project and library versions once at start-up
            (F´'s ``start()``).
        base_id: added to the local opcodes (0–1), event ids (0–3) and channel ids (0–21).
    """

    @guarded_input(VersionPort)
    def getVersion(self, version_id, version_string, status):
        """Read custom slot ``version_id``: returns ``(value, status)``; ``("no_ver", FAILURE)`` if unset."""
        slot = self._slot(version_id, "getVersion")
        if slot is None:
            return "", VersionStatus.FAILURE
        entry = self._custom[slot]
        return entry.version_value, entry.version_status

    @guarded_input(VersionPort)
    def setVersion(self, version_id, version_string, status):
        """Write custom slot ``version_id`` and report it; returns the arguments as F´ leaves them."""
        slot = self._slot(version_id, "setVersion")
        if slot is None:
            return version_string, VersionStatus.FAILURE
        if not isinstance(version_string, str):
            return self._reject("setVersion", f"version_string must be text, got {version_string!r}",
                                version_string)
        try:
            status = _VERSION_STATUS.check(status)
        except SerializationError as exc:
            return self._reject("setVersion", str(exc), version_string)
        self._custom[slot] = CustomVersionDb(VersionEnum(slot), fit_utf8(version_string, CUSTOM_VERSION_SIZE), status)
        self._custom_set[slot] = True
        self._report_custom(slot)
        return version_string, status

    @guarded_command(opcode=0)
    def ENABLE(self, enable: VersionEnabled):
        """Turn custom-version telemetry on (ENABLED) or off (DISABLED)."""
        self.verbose = enable == VersionEnabled.ENABLED

    @guarded_command(opcode=1)
    def VERSION(self, version_type: VersionType):
        """Report the versions of one type, or ALL of them."""
        if version_type in (VersionType.PROJECT, VersionType.ALL):
            self._report_project()
        if version_type in (VersionType.FRAMEWORK, VersionType.ALL):
            self._report_framework()
        if version_type in (VersionType.LIBRARY, VersionType.ALL):
            self._report_libraries()
        if version_type in (VersionType.CUSTOM, VersionType.ALL):
            for slot in range(NUM_CUSTOM_VERSIONS):
                self._report_custom(slot)

    FrameworkVersion = Event(Severity.ACTIVITY_LO, "Framework Version: [{}]", id=0,
                             args=[("version", String(40))])
    ProjectVersion = Event(Severity.ACTIVITY_LO, "Project Version: [{}]", id=1,
                           args=[("version", String(40))])
    LibraryVersions = Event(Severity.ACTIVITY_LO, "Libary Versions: [{}]", id=2,
                            args=[("version", String(40))])
    CustomVersions = Event(Severity.ACTIVITY_LO, "Custom Versions: [{}] [{}]", id=3,
                           args=[("version_enum", VersionEnum), ("version_value", String(40))])

    # F´ gives these channels the names of the events above; their attributes differ.
    FrameworkVersion_channel = Channel(String(40), id=0, name="FrameworkVersion")
    ProjectVersion_channel = Channel(String(40), id=1, name="ProjectVersion")
    CustomVersion01 = Channel(CustomVersionDb, id=2)
    CustomVersion02 = Channel(CustomVersionDb, id=3)
    CustomVersion03 = Channel(CustomVersionDb, id=4)
    CustomVersion04 = Channel(CustomVersionDb, id=5)
    CustomVersion05 = Channel(CustomVersionDb, id=6)
    CustomVersion06 = Channel(CustomVersionDb, id=7)
    CustomVersion07 = Channel(CustomVersionDb, id=8)
    CustomVersion08 = Channel(CustomVersionDb, id=9)
    CustomVersion09 = Channel(CustomVersionDb, id=10)
    CustomVersion10 = Channel(CustomVersionDb, id=11)
    LibraryVersion01 = Channel(String(40), id=12)
    LibraryVersion02 = Channel(String(40), id=13)
    LibraryVersion03 = Channel(String(40), id=14)
    LibraryVersion04 = Channel(String(40), id=15)
    LibraryVersion05 = Channel(String(40), id=16)
    LibraryVersion06 = Channel(String(40), id=17)
    LibraryVersion07 = Channel(String(40), id=18)
    LibraryVersion08 = Channel(String(40), id=19)
    LibraryVersion09 = Channel(String(40), id=20)
    LibraryVersion10 = Channel(String(40), id=21)

    def __init__(self, name: str = "version", framework_version: str | None = None,
                 project_version: str = "unknown", library_versions: Sequence[str] = (), *,
                 startup_verbose: bool = True, report_at_startup: bool = True, base_id: int = 0):
        if framework_version is None:
            framework_version = installed_framework_version()
        for what, value in (("framework_version", framework_version), ("project_version", project_version)):
            if not isinstance(value, str):
                raise TypeError(f"{name}: {what} must be a str, got {value!r}")
        if isinstance(library_versions, (str, bytes)) or not all(isinstance(v, str) for v in library_versions):
            raise TypeError(f"{name}: library_versions must be a sequence of str, got {library_versions!r}")
        super().__init__(name, base_id=base_id)
        self._framework_tlm = self._channels["FrameworkVersion"]
        self._project_tlm = self._channels["ProjectVersion"]
        self._library_tlm = [self._channels[f"LibraryVersion{i:02d}"] for i in range(1, NUM_LIBRARY_CHANNELS + 1)]
        self._custom_tlm = [self._channels[f"CustomVersion{i:02d}"] for i in range(1, NUM_CUSTOM_VERSIONS + 1)]
        self.framework_version = framework_version
        self.project_version = project_version
        self.library_versions = tuple(library_versions)
        self.verbose = bool(startup_verbose)
        self.report_at_startup = report_at_startup
        #: Port calls refused for a bad version id, status or value (F´ asserts on those).
        self.rejected_calls = 0
        self.started = False
        self._custom = [CustomVersionDb(VersionEnum.PROJECT_VERSION_00, NO_VERSION, VersionStatus.FAILURE)
                        for _ in range(NUM_CUSTOM_VERSIONS)]
        self._custom_set = [False] * NUM_CUSTOM_VERSIONS

    # --- configuration and start-up ----------------------------------------------------------------

    def config(self, enable: bool) -> None:
        """Set custom-version verbosity (F´ ``config(enable)``)."""
        with self._lock:
            self.verbose = bool(enable)

    def start(self) -> None:
        """Report the framework, project and library versions (F´ ``start()``)."""
        with self._lock:
            self.started = True
            self._report_framework()
            self._report_project()
            self._report_libraries()

    def parameters_loaded(self) -> None:
        """Start-up hook: report once, unless ``report_at_startup`` is off."""
        if self.report_at_startup and not self.started:
            self.start()

    # --- custom versions ---------------------------------------------------------------------------

    def custom_version(self, version_id) -> CustomVersionDb:
        """The stored entry of a custom slot (``version_value`` is ``"no_ver"`` while unset)."""
        return self._custom[int(_VERSION_ENUM.check(version_id))]

    def _slot(self, version_id, port: str) -> int | None:
        try:
            return int(_VERSION_ENUM.check(version_id))
        except SerializationError as exc:
            self._reject(port, str(exc), None)
            return None

    def _reject(self, port: str, why: str, version_string):
        self.rejected_calls += 1
        log.warning("%s: %s call refused: %s", self.name, port, why)
        return version_string, VersionStatus.FAILURE

    # --- reporting ---------------------------------------------------------------------------------

    def _report_framework(self) -> None:
        text = fit_utf8(self.framework_version, VERSION_STRING_SIZE)
        self.FrameworkVersion(text)
        self._framework_tlm.write(text)

    def _report_project(self) -> None:
        text = fit_utf8(self.project_version, VERSION_STRING_SIZE)
        self.ProjectVersion(text)
        self._project_tlm.write(text)

    def _report_libraries(self) -> None:
        for index, library in enumerate(self.library_versions):
            text = fit_utf8(library, VERSION_STRING_SIZE)
            self.LibraryVersions(text)
            if index < NUM_LIBRARY_CHANNELS:
                self._library_tlm[index].write(text)

    def _report_custom(self, slot: int) -> None:
        if not self._custom_set[slot]:
            return
        entry = self._custom[slot]
        self.CustomVersions(entry.version_enum, fit_utf8(entry.version_value, VERSION_STRING_SIZE))
        if self.verbose:
            self._custom_tlm[slot].write(entry)

