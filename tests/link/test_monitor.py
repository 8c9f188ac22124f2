"""`epuckc monitor` on a serial port: a pseudo-terminal stands for the
robot's port (the e-puck's /dev/rfcommN, the e-puck2's programmer port),
a fake robot on its other end sends the bytes the tracer sent on simavr,
in pieces over time; the monitor prints the trace as it comes and stops at
the program's exit. A port that is not there, a port that goes away in the
middle and a Ctrl-C each end it with one line and whole files."""
import json
import os
import signal
import subprocess
import sys
import threading
import time

import pytest

from conftest import REPO
from tests.support.programs import epuckc
from tests.support.serial_robot import FakeRobot

EXAMPLES = REPO / "examples"


class Monitor:
    """`epuckc monitor PORT ...` in the background; `listening()` waits
    until it has the port open (bytes sent before would be the flushed
    ones of a robot that ran before it came)."""

    def __init__(self, port, *more):
        env = dict(os.environ, PYTHONPATH=str(REPO))
        self.process = subprocess.Popen(
            [sys.executable, "-m", "epuckc", "monitor", port, *map(str, more)],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
        self.stderr, self.opened = [], threading.Event()
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self):
        for line in self.process.stderr:
            self.stderr.append(line)
            if "reading " in line:
                self.opened.set()

    def listening(self):
        assert self.opened.wait(120), "".join(self.stderr)

    def wait(self, timeout=120):
        stdout = self.process.stdout.read()
        self.process.wait(timeout)
        self.reader.join(10)
        return self.process.returncode, stdout, "".join(self.stderr)


def test_the_monitor_prints_the_trace_live_and_stops_at_the_exit(bump_stream, tmp_path):
    table, data, records = bump_stream
    robot = FakeRobot(data)
    out = tmp_path / "out.jsonl"
    try:
        monitor = Monitor(robot.port, "--program", EXAMPLES / "bump_counter.epk", "--trace", out)
        monitor.listening()
        robot.run()
        status, stdout, stderr = monitor.wait()
    finally:
        robot.close()
    assert status == 0, stderr
    assert [json.loads(line) for line in out.read_text().splitlines()] == records
    from epuckc.sim.readable import readable_trace
    assert stdout == readable_trace(records, lambda a: table["steps"].get(str(a), []))


def test_a_port_that_goes_away_keeps_what_came(bump_stream, tmp_path):
    _, data, records = bump_stream
    robot = FakeRobot(data, stop_after=len(data) // 2)
    out = tmp_path / "out.jsonl"
    try:
        monitor = Monitor(robot.port, "--program", EXAMPLES / "bump_counter.epk", "--trace", out)
        monitor.listening()
        robot.run(then_close=True)
        os.close(robot.slave)       # only the monitor holds the port now
        robot.slave = None
        status, _, stderr = monitor.wait()
    finally:
        robot.close()
    assert status == 2 and "went away while reading" in stderr, stderr
    kept = [json.loads(line) for line in out.read_text().splitlines()]
    assert kept and kept == records[:len(kept)] and kept[-1]["kind"] != "exit"


def test_ctrl_c_keeps_what_came(bump_stream, tmp_path):
    _, data, records = bump_stream
    robot = FakeRobot(data, stop_after=len(data) // 2)
    out = tmp_path / "out.jsonl"
    try:
        monitor = Monitor(robot.port, "--program", EXAMPLES / "bump_counter.epk", "--trace", out)
        monitor.listening()
        robot.run()
        assert robot.sent.wait(60)
        time.sleep(1.0)
        monitor.process.send_signal(signal.SIGINT)
        status, _, stderr = monitor.wait()
    finally:
        robot.close()
    assert status == 130, stderr
    kept = [json.loads(line) for line in out.read_text().splitlines()]
    assert kept and kept == records[:len(kept)]


@pytest.mark.parametrize("port, said", [("/dev/no-such-port", "there is no such port")])
def test_a_port_that_cannot_be_opened_is_one_line(port, said):
    r = epuckc("monitor", port)
    assert r.returncode == 2 and said in r.stderr and "Traceback" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


def test_the_e_puck2_programmers_gdb_port_is_refused_naming_the_right_one(monkeypatch):
    """The programmer's first port flashes; the trace is on its second."""
    from tests.link.test_ports import epuck2
    from epuckc.link import ports
    from epuckc.link.monitor import gdb_port_problem
    robot = FakeRobot(b"")
    try:
        monkeypatch.setattr(ports, "system_ports", lambda: [
            epuck2(robot.port, "1-1.2:1.0", "e-puck2 GDB Server"),
            epuck2("/dev/ttyACM9", "1-1.2:1.2", "e-puck2 Serial Monitor")])
        said = gdb_port_problem(robot.port)
        assert said and "GDB port" in said and "serial monitor, the second port" in said
        assert gdb_port_problem("/dev/ttyACM9") is None
    finally:
        robot.close()
