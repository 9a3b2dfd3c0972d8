"""A run's outputs written by a second process: the flight's core only hands over raw bytes and numbers.

``fprime-lite run`` flies on one core. With ``--writer process`` (the default ``auto`` picks it when
the machine has more than one core and nothing else runs in the process, see :func:`choose_writer`)
the formatting of its largest outputs moves to a **writer process** forked when the run starts:

- the ground recorder's telemetry part — decoding every downlinked telemetry packet and writing
  ``channels.csv`` and ``channels_wide.csv`` (:class:`~fprime_lite.ground.downlink.GroundRecorder`,
  the same code in the child, so the same bytes);
- row streams a run report opens with :func:`open_row_stream` (the detumble report's ``truth.csv``):
  the row's values (floats and texts, pickled exactly) go over, the child writes the line;
- ``dictionary.json`` (:meth:`OutputWriter.write_dictionary`): the child builds and writes it from its
  copy of the topology while the flight starts (the topology's dictionary does not change after the fork).

The flight's side appends each packet (its bytes and reception time in µs) or row to a list and,
every :data:`BATCH_ITEMS` items, sends the list through a pipe in one ``send``; a full pipe makes the
flight wait for the child (memory stays flat). The child runs as ``SCHED_BATCH`` (Linux): woken by a
send, it does not preempt the flight on the flight's core (measured: the flight's sends took 0.27 s of
an orbit's 7.5 s without it, 0.05 s with it, at load 6). Events, downlinked files and every counter the summary
reads stay with the flight (the reports and ``stop_on_events`` see each event at its tick).

Files are still written under a temporary name and renamed into place: a row stream when its report
closes it (before the plots read it), the recorder's files at :meth:`OutputWriter.close`. The child
ignores SIGINT and SIGTERM (a Ctrl-C reaches the whole process group): it finishes when the flight
sends the end of the stream, so an interrupted run keeps its outputs up to the stop as inline. If the
flight's process dies, the child sees the pipe close without an end and leaves its temporary files
for the next run to remove (as a killed inline run does). A failure in the child — a full disk, any
exception, the child killed — is sent back (or seen as the pipe breaking): the flight is stopped
(``on_failure``) and :meth:`OutputWriter.close` raises :class:`OutputWriterError` (an ``OSError``,
with the child's errno, file name and text when it had them), so the run fails with the reason
instead of leaving a file short.
"""

from __future__ import annotations

import multiprocessing
import os
import pathlib
import signal
import threading
import traceback
from typing import Any, Callable

from fprime_lite.deploy.dictionary import write_dictionary
from fprime_lite.ground.downlink import GroundRecorder, StreamedFile

__all__ = ["OutputWriter", "OutputWriterError", "open_row_stream", "choose_writer", "WRITER_MODES",
           "BATCH_ITEMS"]

#: ``--writer`` values: ``process`` (a writer process), ``inline`` (everything in the flight's process),
#: ``auto`` (:func:`choose_writer`).
WRITER_MODES = ("auto", "process", "inline")

#: Items (packets and rows) gathered before one send to the writer process.
BATCH_ITEMS = 256

_RECORDER = 0  # the stream id of the ground recorder's packets


class OutputWriterError(OSError):
    """The writer process failed (its errno, file name and text when it was an ``OSError``)."""


def choose_writer(mode: str, *, realtime: bool = False) -> str:
    """``"process"`` or ``"inline"`` for ``--writer MODE``. ``auto`` is ``process`` when this process may
    use more than one core, fork is available, only the main thread runs (a fork copies no other thread)
    and the run is not paced to the wall clock (``realtime``: there the outputs' cost does not matter);
    else ``inline``. Library callers (campaign workers, ``fprime_lite.run``) get ``inline`` unless they
    ask: a campaign's workers already use every core."""
    if mode not in WRITER_MODES:
        raise ValueError(f"writer must be one of {', '.join(WRITER_MODES)}, got {mode!r}")
    if mode != "auto":
        return mode
    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        cores = os.cpu_count() or 1
    forks = "fork" in multiprocessing.get_all_start_methods()
    alone = threading.active_count() == 1
    return "process" if cores > 1 and forks and alone and not realtime else "inline"


class _InlineRows(StreamedFile):
    """A row stream written here: ``factory(file).writerow`` into a temporary file, renamed on close."""

    def __init__(self, path: pathlib.Path, factory: Callable[[Any], Any]):
        super().__init__(path, newline="")
        self.writerow = factory(self.file).writerow


class _RemoteRows:
    """A row stream the writer process writes: ``writerow`` hands the row over."""

    def __init__(self, writer: "OutputWriter", stream: int):
        self._writer = writer
        self._stream = stream
        self._append = writer._items.append

    def writerow(self, row) -> None:
        self._append((self._stream, row))
        if len(self._writer._items) >= BATCH_ITEMS:
            self._writer._send_items()

    def close(self) -> None:
        self._writer._request(("close", self._stream))


def open_row_stream(deployment, path, factory: Callable[[Any], Any]):
    """A stream of CSV rows into ``path``: an object with ``writerow(row)`` and ``close()`` (the file
    is renamed into place on ``close``). ``factory(text_file)`` makes the row writer (a class such as
    ``csv.writer`` or ``detumble.reports.csv_rows.FastCsvWriter``; for the writer process it must be
    picklable by reference: a module-level class or function). Written by the run's writer process
    when it has one (``deployment.output_writer``), else here."""
    writer = getattr(deployment, "output_writer", None)
    if writer is None:
        return _InlineRows(pathlib.Path(path), factory)
    return writer.open_rows(pathlib.Path(path), factory)


class OutputWriter:
    """The flight's end of a writer process (see the module docstring).

    ``topology`` and ``out_dir``: the recorder's, as :class:`~fprime_lite.ground.downlink.GroundRecorder`
    takes them; ``start_us``: the reception time (µs in the clock's time base) the wide table's ``t_s``
    counts from; ``on_failure()`` is called once when the child fails (the run stops the flight).
    """

    def __init__(self, topology, out_dir, start_us: int, on_failure: Callable[[], None] | None = None):
        context = multiprocessing.get_context("fork")
        self._conn, child_conn = context.Pipe(duplex=True)
        self._items: list = []
        self._streams = 0
        self._failure: BaseException | None = None
        self._on_failure = on_failure
        self.stats: dict[str, int] = {}
        self._process = context.Process(target=_child_main, name="fprime-lite output writer",
                                        args=(child_conn, topology, pathlib.Path(out_dir), start_us), daemon=True)
        self._process.start()
        child_conn.close()
        self.pid = self._process.pid

    # --- the flight's side --------------------------------------------------------------------------

    def packet(self, data: bytes, reception_us: int) -> None:
        """A downlinked telemetry packet for the recorder, received at ``reception_us``."""
        items = self._items
        items.append((_RECORDER, (data, reception_us)))
        if len(items) >= BATCH_ITEMS:
            self._send_items()

    def open_rows(self, path: pathlib.Path, factory: Callable[[Any], Any]) -> _RemoteRows:
        """A row stream into ``path`` the child writes (see :func:`open_row_stream`)."""
        self._streams += 1
        self._send_items()
        self._send(("open", self._streams, path, factory))
        return _RemoteRows(self, self._streams)

    def write_dictionary(self, path: pathlib.Path) -> None:
        """Have the child write the topology's dictionary to ``path`` (atomically, as
        :func:`~fprime_lite.deploy.dictionary.write_dictionary` does): done before the items that follow."""
        self._send_items()
        self._send(("dictionary", pathlib.Path(path)))

    def _send_items(self) -> None:
        if not self._items:
            return
        items = self._items[:]
        self._items.clear()  # the same list: the row streams hold its append
        self._send(("items", items))

    def _send(self, message) -> None:
        if self._failure is not None:
            return  # the child failed: nothing more is written (close() raises)
        try:
            if self._conn.poll():  # the child only speaks first to say it failed
                self._fail(self._conn.recv())
                return
            self._conn.send(message)
        except (OSError, EOFError):
            self._fail(None)

    def _request(self, message) -> dict:
        """Send ``message`` (after the items gathered) and wait for the child's answer."""
        self._send_items()
        self._send(message)
        if self._failure is None:
            try:
                answer = self._conn.recv()
            except (OSError, EOFError):
                answer = None
            if answer is None or answer[0] != "ok":
                self._fail(answer)
            else:
                return answer[1]
        raise self._failure  # type: ignore[misc]

    def _fail(self, answer) -> None:
        """Record the child's failure (``("error", errno, filename, text)``, or None: it died)."""
        if self._failure is not None:
            return
        if answer is not None and answer[0] == "error":
            _, errno, filename, text = answer
            self._failure = OutputWriterError(errno, f"in the output writer process: {text}", filename)
        else:
            self._process.join(timeout=5)
            code = self._process.exitcode
            self._failure = OutputWriterError(
                f"the output writer process (pid {self.pid}) ended unexpectedly (exit code {code}); the outputs "
                "it was writing (channels.csv, channels_wide.csv, truth.csv, dictionary.json) were not finished")
        if self._on_failure is not None:
            self._on_failure()

    @property
    def failed(self) -> bool:
        return self._failure is not None

    def close(self) -> dict[str, int]:
        """Finish: the child writes what is left, closes and renames its files and exits. Returns the
        recorder's counters (``undecodable``, ``channel_updates``); raises :class:`OutputWriterError`
        when the child failed."""
        try:
            self.stats = self._request(("end",))
        finally:
            self._conn.close()
            self._process.join(timeout=60)
            if self._process.is_alive():
                self._process.kill()
                self._process.join()
        return self.stats

    def abandon(self) -> None:
        """End the child without finishing (the flight failed): its temporary files stay for the next run."""
        self._conn.close()
        self._process.join(timeout=10)
        if self._process.is_alive():
            self._process.kill()
            self._process.join()


class _ReceptionClock:
    """The child's stand-in for the deployment's clock: ``now()`` is the packet's reception time."""

    def __init__(self, us: int):
        from fprime_lite.model.time import Time

        self._time = Time.__new__(Time)
        self._time.time_base = 0
        self._time.context = 0
        self.set_us(us)

    def set_us(self, us: int) -> None:
        self._time.total_us = us

    def now(self):
        return self._time


def _child_main(conn, topology, out_dir: pathlib.Path, start_us: int) -> None:
    """The writer process: record packets and write row streams until the flight says ``end``."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # a Ctrl-C reaches the whole group: finish on "end"
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    try:  # a throughput task: woken by the flight's send, it must not preempt the flight on its core
        os.sched_setscheduler(0, os.SCHED_BATCH, os.sched_param(0))
    except (AttributeError, OSError):  # not on Linux
        pass

    failed: tuple | None = None
    recorder = None
    streams: dict[int, _InlineRows] = {}
    clock = _ReceptionClock(start_us)
    while True:
        try:
            message = conn.recv()
        except (EOFError, OSError):  # the flight's process is gone without an end: leave the temporaries
            os._exit(1)
        kind = message[0]
        if failed is not None:  # keep draining so the flight never blocks; answer requests with the failure
            if kind in ("close", "end"):
                conn.send(failed)
            if kind == "end":
                break
            continue
        try:
            if kind == "items":
                if recorder is None:
                    recorder = GroundRecorder(topology, out_dir, clock=clock, telemetry_only=True)
                receive, set_us = recorder.receive, clock.set_us
                for stream, payload in message[1]:
                    if stream == _RECORDER:
                        set_us(payload[1])
                        receive(payload[0])
                    else:
                        streams[stream].writerow(payload)
            elif kind == "dictionary":
                write_dictionary(topology, message[1])
            elif kind == "open":
                _, stream, path, factory = message
                streams[stream] = _InlineRows(path, factory)
            elif kind == "close":
                streams.pop(message[1]).close()
                conn.send(("ok", {}))
            elif kind == "end":
                if recorder is None:
                    recorder = GroundRecorder(topology, out_dir, clock=clock, telemetry_only=True)
                recorder.close()
                for rows in streams.values():
                    rows.close()
                conn.send(("ok", {"undecodable": recorder.undecodable, "channel_updates": recorder.channel_updates}))
                break
        except BaseException as exc:  # noqa: BLE001 - every failure goes back to the flight
            errno = exc.errno if isinstance(exc, OSError) else None
            filename = exc.filename if isinstance(exc, OSError) else None
            text = (exc.strerror if isinstance(exc, OSError) and exc.strerror else
                    "".join(traceback.format_exception_only(type(exc), exc)).strip())
            failed = ("error", errno, filename, text)
            try:
                conn.send(failed)
            except OSError:
                os._exit(1)
            if kind == "end":
                break
    conn.close()
