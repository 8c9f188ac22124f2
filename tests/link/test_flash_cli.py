"""`epuckc flash`'s refusals, each one line naming what is wrong and what to
do, with status 2 (a bad request) before any robot or build is touched;
1 when no robot is found; the progress bar on a terminal."""
import os
import pty
import re
import select
import subprocess
import sys
import time

import pytest

from conftest import REPO
from epuckc.cli import main
from tests.support.fake_tinybld import FakeTinybld
from tests.support.xc16_hex import example_words, write_program

RULES = "on immediate do led_on(front), exit_main\n"


def run(capsys, *args):
    status = main(["flash", *map(str, args)])
    out, err = capsys.readouterr()
    return status, out, err


@pytest.fixture
def files(tmp_path):
    (tmp_path / "prog.epk").write_text(RULES)
    (tmp_path / "prog.elf").write_bytes(b"\x7fELF")
    write_program(tmp_path / "prog.hex", example_words())
    (tmp_path / "prog.bin").write_bytes(b"\0" * 16)
    return tmp_path


@pytest.mark.parametrize("args, says", [
    (["prog.bin"], "prog.bin: flash takes a rule file (.epk), a C program (.c), or a built "
                   "program: .hex for the e-puck, .elf for the e-puck2 (give the .elf beside it"),
    (["prog.epk"], "which robot is prog.epk for? give --target epuck or --target epuck2"),
    (["prog.hex", "--target", "epuck2"], "prog.hex is built for the e-puck (.hex), not the "
                                         "e-puck2: leave out --target"),
    (["prog.elf", "--target", "dspic"], "prog.elf is built for the e-puck2 (.elf), not the "
                                        "e-puck"),
    (["prog.elf", "--port", "/dev/x", "--robot-id", "3"], "--robot-id is the e-puck's number "
                                                          "for its bootloader; the e-puck2 has none"),
    (["prog.hex", "--port", "/dev/x", "--port", "/dev/y", "--robot-id", "3"],
     "1 --robot-id for 2 ports: give one robot number per --port, in the same order"),
    (["prog.hex", "--port", "/dev/x", "--port", "/dev/x"], "a port is given twice with --port"),
    (["prog.hex", "--port", "/dev/x", "--all"], "--all flashes every robot found: give either "
                                               "--port or --all"),
    ([], "give the program to flash: epuckc flash PROG"),
])
def test_a_request_that_cannot_be_carried_out(capsys, files, monkeypatch, args, says):
    monkeypatch.chdir(files)
    status, out, err = run(capsys, *args)
    assert status == 2
    assert err == f"epuckc: error: {says}" + err[len("epuckc: error: ") + len(says):]
    assert len(err.splitlines()) == 1 and out == ""


@pytest.mark.parametrize("value", ["5", "0s", "2h", "-1s"])
def test_durations_need_their_unit_and_a_range(capsys, files, monkeypatch, value):
    monkeypatch.chdir(files)
    with pytest.raises(SystemExit) as caught:
        main(["flash", "prog.hex", "--timeout", value])
    assert caught.value.code == 2
    assert "--timeout" in capsys.readouterr().err


def test_a_robot_number_is_a_16_bit_number(capsys, files, monkeypatch):
    monkeypatch.chdir(files)
    with pytest.raises(SystemExit):
        main(["flash", "prog.hex", "--robot-id", "70000"])
    assert "is not a robot number: give the e-puck's number, 0 to 65535" in \
        capsys.readouterr().err


def test_without_a_port_and_no_robot_connected(capsys, files, monkeypatch):
    from epuckc.link.ports import robot_ports
    if robot_ports("epuck2"):
        pytest.skip("an e-puck2 is connected to this machine")
    monkeypatch.chdir(files)
    status, out, err = run(capsys, "prog.elf")
    assert status == 1
    assert err.startswith("epuckc: error: no e-puck2 is connected: plug the robot's USB cable "
                          "in (a data cable, not a charge-only one)")


def test_a_port_that_is_not_there_fails_that_robot(capsys, files, monkeypatch):
    monkeypatch.chdir(files)
    status, out, err = run(capsys, "prog.hex", "--port", "/dev/rfcomm-not-here",
                           "--robot-id", "12")
    assert status == 1
    assert err.startswith("epuckc: error: the e-puck 12 on /dev/rfcomm-not-here: cannot open "
                          "/dev/rfcomm-not-here") or "there is no port" in err
    assert len(err.splitlines()) == 1


def test_list_shows_ports_and_flashes_nothing(capsys):
    assert main(["flash", "--list"]) == 0


def test_a_terminal_gets_a_progress_bar_that_ends_as_the_robots_line(files):
    """stderr on a pty: the bar is drawn and redrawn in place, and gone at
    the end; the result is one line."""
    with FakeTinybld(answer_delay=0.03) as robot:
        leader, follower = pty.openpty()
        env = dict(os.environ, TERM="xterm",
                   PYTHONPATH=str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", ""))
        process = subprocess.Popen(
            [sys.executable, "-m", "epuckc", "flash", str(files / "prog.hex"), "--port",
             robot.port, "--robot-id", "4"], stdout=subprocess.PIPE, stderr=follower, env=env)
        os.close(follower)
        shown = bytearray()
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            ready, _, _ = select.select([leader], [], [], 0.2)
            if ready:
                try:
                    chunk = os.read(leader, 4096)
                except OSError:
                    break
                if not chunk:
                    break
                shown += chunk
            elif process.poll() is not None:
                break
        out = process.communicate(timeout=30)[0].decode()
        os.close(leader)
    assert process.returncode == 0
    text = shown.decode()
    assert f"e-puck 4 on {robot.port} [" in text and "press the robot's reset button now (" in text
    # (each packet's answer takes 30 ms: over 0.8 s of packets, redrawn every 0.1 s)
    drawn = [int(p) for p in re.findall(r"\] +(\d+)% packet", text)]
    assert len(drawn) >= 2 and drawn == sorted(drawn) and drawn[-1] > 50
    assert "\x1b[" in text and text.rstrip().endswith("\x1b[J")      # the block cleared
    assert out.startswith(f"flashed {files / 'prog.hex'} to the e-puck 4 on {robot.port} (")
