"""`epuckc flash` of the e-puck: the tinybld Bluetooth bootloader's protocol
against a fake robot on a pty (tests/support/fake_tinybld.py) that checks
each packet and rebuilds the program memory. The hex files are written
from known instructions (tests/support/xc16_hex.py, with type-04 records,
configuration words and EEPROM data to skip), and what the robot must hold
is computed from those instructions and the bootloader's layout in
../shared/reference/robot-link.md (xc16_hex.expected_memory), never
through the code under test."""
import pytest

from tests.support.fake_tinybld import FakeTinybld
from tests.support.flash import flash
from tests.support.xc16_hex import (BOOTLOADER_ROW, CONFIG, EEPROM, example_words,
                                    expected_memory, write_program)

OLD = {0x100 + 2 * i: 0x0A0B0C for i in range(3000)}       # a longer program before


@pytest.fixture
def hexfile(tmp_path):
    words = example_words()
    return write_program(tmp_path / "prog.hex", words, CONFIG, EEPROM), words


def test_the_robot_holds_the_programs_memory_with_the_reset_vector_patched(hexfile):
    path, words = hexfile
    with FakeTinybld(old=OLD) as robot:
        r = flash(path, "--port", robot.port, "--robot-id", "3112")
        assert r.returncode == 0, r.stderr
        assert robot.finished.is_set()               # the end packet came
        assert robot.errors == []                    # every packet's layout was right
        assert robot.flash == expected_memory(words, 3112, OLD)
        # the first 64 KB of the file (the reset vector's) last, after the
        # bootloader's row; the chunk past it first
        order = robot.rows_written
        assert order.index(BOOTLOADER_ROW) == len([a for a in order if a >= 0x8000]) - 1
        assert all(a < 0x8000 for a in order[order.index(BOOTLOADER_ROW) + 1:])
        assert len(order) == len(set(order)) == len({a - a % 64 for a in words}) + 1
    assert r.stdout.startswith(f"flashed {path} to the e-puck 3112 on {robot.port} (")
    assert f"the e-puck 3112 on {robot.port}: press the robot's reset button now (you have " \
           "30 s)" in r.stderr
    assert "has EEPROM data, which the bootloader does not write" in r.stderr


def test_a_packet_refused_for_a_changed_byte_is_sent_again(hexfile):
    path, words = hexfile
    with FakeTinybld(corrupt={1, 4}) as robot:
        r = flash(path, "--port", robot.port, "--robot-id", "7")
        assert r.returncode == 0, r.stderr
        assert robot.answers.count(b"N") == 2
        assert robot.flash == expected_memory(words, 7, {})


def test_a_packet_refused_every_time_is_given_up_after_five_sends(hexfile):
    path, _ = hexfile
    with FakeTinybld(refuse_all=True) as robot:
        r = flash(path, "--port", robot.port, "--robot-id", "7")
        assert robot.received_packets == 5 and robot.flash == {}
    assert r.returncode == 1
    assert r.stderr.splitlines()[-1] == (
        f"epuckc: error: the e-puck 7 on {robot.port}: packet 1 of 29 (address 0x008000) was "
        "refused 5 times (checksum errors: the Bluetooth link changes bytes): move the robot "
        "closer to the computer, away from other radios, and flash again")


def test_a_byte_lost_on_the_way_stops_the_upload_with_its_fix(hexfile):
    path, _ = hexfile
    with FakeTinybld(drop_packet_byte=3) as robot:
        r = flash(path, "--port", robot.port, "--robot-id", "7")
    assert r.returncode == 1
    assert (f"the e-puck 7 on {robot.port}: the robot stopped answering at packet 3 of 29 "
            "(address 0x008080): bytes were lost on the Bluetooth link and the bootloader gave "
            "up; flash again and press the reset button when asked") in r.stderr


def test_a_reset_never_pressed_ends_with_the_window(hexfile):
    path, _ = hexfile
    with FakeTinybld(reset_after=None) as robot:
        r = flash(path, "--port", robot.port, "--robot-id", "7", "--reset-window", "1.5s")
        assert robot.handshakes == 0
    assert r.returncode == 1
    assert "press the robot's reset button now (you have 2 s)" in r.stderr
    assert "no answer from the bootloader in 1.5 s: press the robot's reset button" in r.stderr


def test_sercoms_reset_command_starts_the_bootloader(hexfile):
    """GCtronic's sercom resets on `R\\n`: no button needed."""
    path, words = hexfile
    with FakeTinybld(reset_after=None, sercom=True) as robot:
        r = flash(path, "--port", robot.port, "--robot-id", "9")
        assert r.returncode == 0, r.stderr
        assert robot.flash == expected_memory(words, 9, {})
        assert robot.answers[0].startswith(b"v\r\nVersion")      # V's answer, ignored


def test_a_call_lost_on_the_way_is_made_again(hexfile):
    path, words = hexfile
    with FakeTinybld(drop_first_call=True) as robot:
        r = flash(path, "--port", robot.port, "--robot-id", "9")
        assert r.returncode == 0, r.stderr
        assert robot.flash == expected_memory(words, 9, {})


def test_several_robots_at_once_each_with_its_number_one_failing(hexfile):
    path, words = hexfile
    with FakeTinybld() as a, FakeTinybld(refuse_all=True) as b, FakeTinybld() as c:
        r = flash(path, "--port", a.port, "--port", b.port, "--port", c.port,
                  "--robot-id", "101", "--robot-id", "102", "--robot-id", "103")
        assert a.flash == expected_memory(words, 101, {})
        assert c.flash == expected_memory(words, 103, {})
    assert r.returncode == 1
    assert sorted(line.split(" (")[0] for line in r.stdout.splitlines()) == [
        f"flashed {path} to the e-puck 101 on {a.port}",
        f"flashed {path} to the e-puck 103 on {c.port}"]
    assert r.stderr.splitlines()[-1] == (f"epuckc: error: 1 of 3 robots was not flashed: the "
                                         f"e-puck 102 on {b.port}")


def test_the_robots_number_is_read_from_its_ports_name(hexfile, tmp_path):
    """macOS names the port after the robot (cu.e-puck_3112-COM1); a udev
    rule can too."""
    path, words = hexfile
    with FakeTinybld() as robot:
        named = tmp_path / "cu.e-puck_3112-COM1"
        named.symlink_to(robot.port)
        r = flash(path, "--port", named)
        assert r.returncode == 0, r.stderr
        assert robot.flash == expected_memory(words, 3112, {})


def test_a_port_without_a_number_asks_for_it(hexfile):
    path, _ = hexfile
    with FakeTinybld() as robot:
        r = flash(path, "--port", robot.port)
        assert robot.received_packets == 0
    assert r.returncode == 2
    assert (f"which e-puck is on {robot.port}? give --robot-id N (the number on its sticker, "
            "its Bluetooth PIN): the bootloader keeps it in the robot") in r.stderr


@pytest.mark.parametrize("change, says", [
    ("no-goto", "does not start with a jump (GOTO) at its reset vector"),
    ("bootloader", "has code at 0x017f10, where the e-puck's bootloader lives (0x017f00 and "
                   "above): the program is too big"),
    ("checksum", "is not an Intel HEX file the bootloader can take"),
    ("eeprom-only", "holds no program memory"),
])
def test_a_hex_the_bootloader_cannot_take_is_refused_before_the_robot_is_touched(
        tmp_path, change, says):
    words = example_words()
    if change == "no-goto":
        words[0] = 0x123456
    elif change == "bootloader":
        words[0x17F10] = 0x000000
    path = write_program(tmp_path / "bad.hex", {} if change == "eeprom-only" else words,
                         CONFIG, EEPROM)
    if change == "checksum":
        lines = path.read_text().splitlines()
        lines[3] = lines[3][:-2] + ("00" if lines[3][-2:] != "00" else "01")
        path.write_text("\n".join(lines) + "\n")
    with FakeTinybld() as robot:
        r = flash(path, "--port", robot.port, "--robot-id", "5")
        assert robot.answers == [] and robot.received_packets == 0
    assert r.returncode == 2
    assert says in r.stderr and len(r.stderr.splitlines()) == 1, r.stderr
