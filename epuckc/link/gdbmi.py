"""GDB driven through its machine interface (GDB/MI, `--interpreter=mi`):
each command is sent with a token and its result record (`^done`,
`^error,msg="..."`) is waited for with a bound, so a command that fails is
known as soon as it fails and a debugger or probe that hangs is stopped;
what the commands print comes back as the console (`~`), target (`@`) and
log (`&`) streams, and `-target-download` reports its progress in
`+download` records. (The GDB manual, "The GDB/MI Interface".)"""
from __future__ import annotations

import queue
import re
import subprocess
import threading
import time
from typing import Callable, Optional

from ..base.records import field, record


class GdbStopped(Exception):
    """GDB ended (or had to be stopped) before the command's result came:
    `output` is what it printed last, `timed_out` says whether it was the
    bound that ran out."""

    def __init__(self, output: str, timed_out: bool):
        super().__init__(output)
        self.output = output
        self.timed_out = timed_out


@record
class Result:
    """A command's result: `kind` is done, connected, error, ...; `message`
    the error's text; `console` what it printed (console and target
    streams), `log` GDB's own log stream (warnings)."""
    kind: str
    message: str = ""
    console: list = field(default_factory=list)
    log: list = field(default_factory=list)

    @property
    def text(self) -> str:
        return "".join(self.console)


_C_ESCAPES = {"n": 10, "t": 9, "r": 13, '"': 34, "\\": 92, "a": 7, "b": 8, "f": 12, "v": 11,
              "e": 27}


def c_string(text: str) -> str:
    """The text of an MI c-string's inside (escapes and octal bytes)."""
    out, i = bytearray(), 0
    while i < len(text):
        ch = text[i]
        if ch == "\\" and i + 1 < len(text):
            nxt = text[i + 1]
            octal = re.match(r"[0-7]{1,3}", text[i + 1:])
            if octal:
                out.append(int(octal.group(0), 8) & 0xFF)
                i += 1 + len(octal.group(0))
                continue
            out.append(_C_ESCAPES.get(nxt, ord(nxt)) if ord(nxt) < 128 else ord("?"))
            i += 2
            continue
        out += ch.encode("utf-8")
        i += 1
    return out.decode("utf-8", "replace")


def _field(body: str, name: str) -> Optional[str]:
    found = re.search(name + r'="((?:[^"\\]|\\.)*)"', body)
    return c_string(found.group(1)) if found else None


class Gdb:
    """One GDB process with a program loaded. `on_download(section, sent)`
    is told of each +download record: the section's name and the bytes of
    the whole download sent so far (GDB's own count)."""

    def __init__(self, gdb: str, program: str, on_download: Optional[Callable] = None):
        self._on_download = on_download
        self._token = 0
        self._lines: queue.Queue = queue.Queue()
        self._recent: list = []
        self._process = subprocess.Popen(
            [gdb, "-nx", "-q", "--interpreter=mi", program], stdin=subprocess.PIPE,
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self):
        for raw in self._process.stdout:
            self._lines.put(raw.decode("utf-8", "replace").rstrip("\r\n"))
        self._lines.put(None)

    def command(self, text: str, timeout_s: float) -> Result:
        """Send one MI command and wait at most timeout_s for its result;
        GdbStopped if GDB ends first or the time runs out (GDB is then
        stopped)."""
        self._token += 1
        token = str(self._token)
        try:
            self._process.stdin.write(f"{token}{text}\n".encode("utf-8"))
            self._process.stdin.flush()
        except OSError:
            raise GdbStopped(self._output(), timed_out=False) from None
        console, log = [], []
        deadline = time.monotonic() + timeout_s
        while True:
            try:
                line = self._lines.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                self.stop()
                raise GdbStopped(self._output(), timed_out=True) from None
            if line is None:
                self._wait()
                raise GdbStopped(self._output(), timed_out=False)
            self._recent = (self._recent + [line])[-40:]
            if line.startswith(("~", "@")):
                console.append(c_string(line[2:-1]) if line.endswith('"') else line[1:])
                continue
            if line.startswith("&"):
                log.append(c_string(line[2:-1]) if line.endswith('"') else line[1:])
                continue
            mark = re.match(r"(\d*)([\^+*=])(.*)", line)
            if not mark:
                continue                # the prompt, or text from a program
            given, kind, body = mark.groups()
            if kind == "+" and body.startswith("download") and self._on_download:
                self._download(body)
            if kind == "^" and given == token:
                name, _, rest = body.partition(",")
                return Result(name, _field(rest, "msg") or "", console, log)

    def _download(self, body: str):
        section = _field(body, "section") or ""
        sent = _field(body, "total-sent")
        self._on_download(section, int(sent) if sent and sent.isdigit() else None)

    def _output(self) -> str:
        """What GDB printed last, as text (streams decoded)."""
        shown = []
        for line in self._recent:
            if line.startswith(("~", "@", "&")) and line.endswith('"'):
                shown.append(c_string(line[2:-1]))
            elif not line.startswith("(gdb)"):
                shown.append(line + "\n")
        return "".join(shown)

    def _wait(self):
        try:
            self._process.wait(timeout=5)
        except subprocess.TimeoutExpired:
            self.stop()

    def stop(self):
        """End GDB at once (it may be waiting on a probe that hangs)."""
        if self._process.poll() is None:
            self._process.kill()
        try:
            self._process.wait(timeout=5)
        except subprocess.TimeoutExpired:
            pass

    def close(self, timeout_s: float = 5.0):
        """`-gdb-exit`, waited for a few seconds, then stopped anyway."""
        if self._process.poll() is None:
            try:
                self._process.stdin.write(b"-gdb-exit\n")
                self._process.stdin.flush()
                self._process.stdin.close()
            except OSError:
                pass
            try:
                self._process.wait(timeout=timeout_s)
            except subprocess.TimeoutExpired:
                self.stop()
        self._reader.join(timeout=1)

    @property
    def returncode(self) -> Optional[int]:
        return self._process.poll()
