"""`epuckc monitor`: the robot's trace read live from a serial port (or a
file of bytes captured from one, or the 16-bit simulator's UART), decoded
(stream.py) and shown as `epuckc run` shows a run: the readable trace on
stdout as it comes, the JSON lines on the side (or on stdout with `-`),
the page that replays the run at the end. Every record is written and
flushed as it comes, into `OUT.jsonl.part` beside the file named, which
becomes OUT.jsonl at the end (also after Ctrl-C): an interrupted monitor
leaves whole lines, a refused stream leaves an earlier OUT.jsonl as it
was."""
from __future__ import annotations

import errno
import json
import os
import sys
from pathlib import Path
from typing import Optional, TextIO

from ..base.output import write_atomic
from ..sim.readable import readable_line, summary_line
from .stream import TraceDecoder, TraceError

BAUD = 115200
# bytes without a single whole frame before the monitor says what may be wrong
NO_FRAME_BYTES = 256


class MonitorError(Exception):
    """The monitor cannot go on; the message says why and what to do."""


class Session:
    """One run's trace: bytes in (`feed`), and at the end `finish()`, which
    returns the exit status as `epuckc run` gives it: 0 after exit_main, 3
    after a time limit, 0 when the stream ended first (interrupted, the
    port closed) with what came written."""

    def __init__(self, table: Optional[dict], trace: Optional[str] = None,
                 html: Optional[str] = None, title: str = "robot", variables=None,
                 time_limit_ms: Optional[int] = None, out: TextIO = sys.stdout,
                 err: TextIO = sys.stderr):
        self.table, self.out, self.err = table, out, err
        self.decoder = TraceDecoder(table, on_note=self.note)
        self.json_to_stdout = trace == "-"
        self.trace_path = Path(trace) if trace and trace != "-" else None
        self.trace_file = None
        if self.trace_path is not None:
            self.part = self.trace_path.with_name(self.trace_path.name + ".part")
            self.trace_file = open(self.part, "w", encoding="utf-8")
        self.html, self.title, self.variables = html, title, variables
        self.time_limit_ms = time_limit_ms
        self.records: list = []
        self.bytes_seen = 0
        self.warned_no_frame = False

    def note(self, text: str) -> None:
        print(f"epuckc monitor: {text}", file=self.err, flush=True)

    def _steps(self, action_id: int) -> list:
        return self.decoder.step_names(action_id)

    @property
    def done(self) -> bool:
        """The run ended (exit_main or its time limit), or the robot began
        another one, or the monitor's time limit passed."""
        if self.decoder.ended or self.decoder.restarted:
            return True
        return self.time_limit_ms is not None and self.decoder.t_ms >= self.time_limit_ms

    def feed(self, data: bytes) -> None:
        if self.done:
            return
        self.bytes_seen += len(data)
        try:
            records = self.decoder.feed(data)
        except TraceError:
            self.discard()
            raise
        self._write(records)
        if (not self.warned_no_frame and self.decoder.frames_decoded == 0
                and self.bytes_seen >= NO_FRAME_BYTES):
            self.warned_no_frame = True
            self.note(f"{self.bytes_seen} bytes and no whole frame of the robot's trace yet: "
                       f"is the program built with --trace, is this its port (the e-puck's "
                       f"Bluetooth port, the e-puck2's programmer's second port), at {BAUD} "
                       f"baud?")

    def _write(self, records: list) -> None:
        for r in records:
            if self.time_limit_ms is not None and r["t_ms"] > self.time_limit_ms:
                continue
            self.records.append(r)
            line = json.dumps(r)
            if self.trace_file is not None:
                self.trace_file.write(line + "\n")
                self.trace_file.flush()
            if self.json_to_stdout:
                print(line, file=self.out, flush=True)
            else:
                shown = readable_line(r, self._steps)
                if shown is not None:
                    print(shown, file=self.out, flush=True)

    def close_files(self) -> None:
        """The JSON lines so far become OUT.jsonl."""
        if self.trace_file is not None:
            self.trace_file.close()
            self.trace_file = None
            self.part.replace(self.trace_path)

    def discard(self) -> None:
        """A refused stream: OUT.jsonl is not touched."""
        if self.trace_file is not None:
            self.trace_file.close()
            self.trace_file = None
            self.part.unlink()

    def finish(self) -> int:
        if not self.decoder.restarted:
            self._write(self.decoder.close())
        if self.decoder.restarted:
            self.note("the robot started its program again (a reset, or another program "
                       "uploaded): this trace ends there; run the monitor again for the new run")
        end = summary_line(self.records)
        if end is not None and not self.json_to_stdout:
            print(end, file=self.out, flush=True)
        if self.decoder.frames_decoded == 0:
            self.discard()
            raise MonitorError(
                f"no frame of the robot's trace in {self.bytes_seen} bytes: build the program "
                f"with `epuckc build --trace`, upload it, and give the robot's trace port "
                f"(docs/robots.md, \"Watching the robot\")" if self.bytes_seen else
                "nothing came from the robot: is its program running, built with --trace?")
        self.close_files()
        if self.html:
            self._replay()
        if self.records and self.records[-1]["kind"] == "timeout":
            return 3
        return 0

    def _replay(self) -> None:
        from ..sim.plot import PlotError
        from ..sim.replay import replay_html
        text = "".join(json.dumps(r) + "\n" for r in self.records)
        try:
            page = replay_html(text, title=self.title, source="the robot's trace",
                               variables={"": self.variables} if self.variables else None)
        except PlotError as exc:
            raise MonitorError(f"--html: {exc}") from None
        write_atomic(Path(self.html), page)


def serial_failure(port: str, exc: Exception) -> str:
    """One line: why the port cannot be opened, and what to do (the flash's
    reasons, ports.py, for the same ports)."""
    from .ports import open_error
    number = getattr(exc, "errno", None)
    if number == errno.ENOENT:
        return (f"cannot open {port}: there is no such port. Is the robot on? e-puck: paired "
                f"and bound (`rfcomm bind`, /dev/rfcommN); e-puck2: its USB cable in, and "
                f"the programmer's second port (`epuckc flash --list` shows the robots' ports)")
    if number is not None:
        return open_error(port, exc)
    return f"cannot open {port}: {exc}"


def gdb_port_problem(port: str) -> Optional[str]:
    """The e-puck2 programmer's GDB port given: the trace is not there."""
    from .ports import epuck2_programmers, system_ports
    try:
        programmers = epuck2_programmers(system_ports())
    except Exception:           # a system whose list pyserial cannot read: no check
        return None
    real = os.path.realpath(port)
    if any(os.path.realpath(p.device) == real for p in programmers):
        return (f"{port} is the e-puck2 programmer's GDB port (its first), which flashes; the "
                f"robot's trace comes on its serial monitor, the second port (or with "
                f"--trace-link usb on the robot's own USB port)")
    return None


def read_serial(port: str, session: Session, baud: int = BAUD, chunk_s: float = 0.05) -> None:
    """Read the port into the session until its run is done, the port goes
    away (MonitorError) or the user interrupts (KeyboardInterrupt, with
    what came kept)."""
    try:
        import serial
    except ImportError:
        raise MonitorError("epuckc monitor needs pyserial: pip install pyserial") from None
    problem = gdb_port_problem(port)
    if problem:
        raise MonitorError(problem)
    try:
        link = serial.Serial(port, baud, timeout=chunk_s)   # DTR high: the e-puck2's
    except (serial.SerialException, OSError, ValueError) as exc:   # monitor port needs it
        raise MonitorError(serial_failure(port, exc)) from None
    session.note(f"reading {port} at {baud} baud (Ctrl-C stops, keeping what came)")
    try:
        while not session.done:
            try:
                data = link.read(4096)
            except (serial.SerialException, OSError) as exc:
                raise MonitorError(f"{port} went away while reading ({exc}): the robot was "
                                   f"switched off, out of range or unplugged; the trace up to "
                                   f"there is kept") from None
            if data:
                session.feed(data)
    finally:
        link.close()


def read_file(path: str, session: Session) -> None:
    """A file of the link's bytes (a capture), as if they came now."""
    try:
        data = Path(path).read_bytes()
    except OSError as exc:
        raise MonitorError(f"cannot read {path}: {exc.strerror or exc}") from None
    for at in range(0, len(data), 4096):
        if session.done:
            break
        session.feed(data[at:at + 4096])
