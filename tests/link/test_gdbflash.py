"""`epuckc flash` of the e-puck2: the real gdb-multiarch (Debian's) against a
fake of the robot's on-board programmer that speaks the GDB remote protocol
as its Black Magic Probe firmware does (tests/support/fake_probe.py) on a
pty. The fake's flash must end up holding exactly what the ELF puts there
(binutils' objcopy says what that is), with the programmer's firmware of
2020 (no threads reported) and of today; each failure the fake stages is one
line with its fix and a non-zero status."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import require_tool
from tests.support.arm_elf import flash_image, received, small_elf
from tests.support.fake_probe import FakeProbe, gdb_crc32
from tests.support.flash import flash

@pytest.fixture(scope="module")
def elf(tmp_path_factory):
    require_tool("gdb-multiarch")
    gcc = require_tool("arm-none-eabi-gcc")
    return small_elf(tmp_path_factory.mktemp("elf"), gcc)


@pytest.fixture(scope="module")
def image(elf):
    return flash_image(elf, require_tool("arm-none-eabi-objcopy"))


def _holds(probe, image: dict):
    """The fake took exactly the ELF's bytes, and its flash keeps them."""
    got = received(probe)
    assert sorted(got) == sorted(image)
    assert got == image
    for address, byte in image.items():
        assert probe.flash_bytes(address, 1)[0] == byte, hex(address)
    assert probe.errors == []


@pytest.mark.parametrize("threads", [False, True], ids=["firmware-2020", "firmware-today"])
def test_the_flash_holds_exactly_the_elfs_loadable_sections(elf, image, threads):
    with FakeProbe(threads=threads) as probe:
        r = flash(elf, "--port", probe.port)
        assert r.returncode == 0, r.stderr
        _holds(probe, image)
        assert probe.killed                  # reset and let go: the program runs
        # the flash was erased in whole blocks of the memory map before it was written
        assert probe.erased and all(a % 0x4000 == 0 for a, _ in probe.erased)
        # escaped bytes (# $ } *) went through vFlashWrite's binary packets
        assert any(b"}" in data or b"#" in data for _, data in probe.written)
    assert r.stdout == (f"flashed {elf} to the e-puck2 on {probe.port} "
                        f"({len(image):,} bytes in 4 sections, verified)\n")


def test_gdbs_crc_is_the_manuals():
    """qCRC is CRC-32 of IEEE 802.3 taken most significant bit first, from
    0xffffffff, not inverted: its check value over "123456789" is
    CRC-32/MPEG-2's, 0x0376E6E7."""
    assert gdb_crc32(b"123456789") == 0x0376E6E7
    assert gdb_crc32(b"") == 0xFFFFFFFF


@pytest.mark.parametrize("stage, says", [
    (dict(no_target=True), "the programmer found no processor to flash (Target voltage: "
                           "0.0V; SW-DP scan failed!): switch the robot on with a charged "
                           "battery in place, then flash again"),
    (dict(bad_crc=True), "after the load, .vectors on the robot differs from {elf} "
                         "(compare-sections): flash again"),
    (dict(vanish_after=2), "the connection to the programmer was lost while it loaded the "
                           "program (Remote connection closed): check the USB cable"),
    (dict(attach_fails=True), "the programmer found STM32F40x M4 but could not attach to it "
                              "(it answered 'E01'): switch the robot off and on"),
    (dict(erase_fails=True), "the programmer could not write the flash (Error erasing flash "
                             "with vFlashErase packet): switch the robot off and on"),
], ids=["no-target", "bad-crc", "vanished-port", "attach-fails", "erase-fails"])
def test_each_failure_is_one_line_with_its_fix(elf, stage, says):
    with FakeProbe(**stage) as probe:
        r = flash(elf, "--port", probe.port)
    assert r.returncode == 1
    lines = r.stderr.splitlines()
    assert len(lines) == 1, r.stderr
    assert lines[0].startswith(f"epuckc: error: the e-puck2 on {probe.port}: "
                               + says.format(elf=elf))
    assert "Traceback" not in r.stderr and r.stdout == ""


def test_a_probe_that_stops_answering_is_given_up_on_in_time(elf):
    """The probe hangs in the middle of an erase (GDB itself would wait
    for it for 1000 s): --timeout bounds the whole flash."""
    with FakeProbe(mute_on=b"vFlashErase") as probe:
        r = flash(elf, "--port", probe.port, "--timeout", "3s", timeout=60)
    assert r.returncode == 1
    assert (f"the e-puck2 on {probe.port}: the programmer stopped answering (no answer for "
            in r.stderr)
    assert "while it loaded the program): unplug the robot's USB cable" in r.stderr


def test_a_port_that_is_not_a_gdb_server_is_named(elf, tmp_path):
    """A pty nobody answers on (say the robot's serial monitor port)."""
    master, slave = os.openpty()
    try:
        r = flash(elf, "--port", os.ttyname(slave), "--timeout", "2s", timeout=60)
    finally:
        os.close(master)
        os.close(slave)
    assert r.returncode == 1
    assert ("the port did not answer as a GDB server within 2 s: is it the programmer's GDB "
            "port (the first of the robot's two ports)?") in r.stderr


def test_several_robots_at_once_one_failing(elf, image):
    with FakeProbe() as a, FakeProbe(no_target=True) as b, FakeProbe(threads=True) as c:
        r = flash(elf, "--port", a.port, "--port", b.port, "--port", c.port)
        for probe in (a, c):
            _holds(probe, image)
        assert b.written == []
    assert r.returncode == 1
    assert sorted(r.stdout.splitlines()) == sorted(
        f"flashed {elf} to the e-puck2 on {p.port} ({len(image):,} bytes in 4 sections, "
        "verified)" for p in (a, c))
    assert r.stderr.splitlines()[-1] == (f"epuckc: error: 1 of 3 robots was not flashed: the "
                                         f"e-puck2 on {b.port}")


def _path_without(*tools) -> str:
    return os.pathsep.join(p for p in os.environ.get("PATH", "").split(os.pathsep)
                           if p and not any((Path(p) / t).exists() for t in tools))


def test_without_gdb_it_says_which_package_to_install(elf):
    with FakeProbe() as probe:
        r = flash(elf, "--port", probe.port,
                  env={"PATH": _path_without("gdb-multiarch", "arm-none-eabi-gdb")})
        assert probe.packets == []
    assert r.returncode == 3
    assert "neither gdb-multiarch nor arm-none-eabi-gdb is installed" in r.stderr
    assert "sudo apt-get install gdb-multiarch" in r.stderr


def test_arm_none_eabi_gdb_is_taken_when_gdb_multiarch_is_missing(elf, image, tmp_path):
    """The other debugger's name, on PATH (here the same GDB under it)."""
    tools = tmp_path / "bin"
    tools.mkdir()
    (tools / "arm-none-eabi-gdb").symlink_to(require_tool("gdb-multiarch"))
    with FakeProbe() as probe:
        r = flash(elf, "--port", probe.port,
                  env={"PATH": str(tools) + os.pathsep + _path_without("gdb-multiarch")})
        assert r.returncode == 0, r.stderr
        _holds(probe, image)


@pytest.mark.parametrize("make, says", [
    ("host", "is a program for X86_64, not for the e-puck2's ARM Cortex-M4"),
    ("text", "is not a program GDB can load (not an ELF file"),
    ("low", "puts .text at 0x00000000, outside the e-puck2's flash (0x08000000-0x080fffff)"),
], ids=["host-elf", "not-elf", "outside-flash"])
def test_a_file_that_is_no_e_puck2_program_is_refused_before_any_flash(tmp_path, make, says):
    target = tmp_path / "bad.elf"
    if make == "host":
        target.symlink_to(Path(sys.executable).resolve())
        if target.read_bytes()[18] != 0x3E:
            pytest.skip("this interpreter is not an x86-64 program")
    elif make == "text":
        target.write_text("not a program\n")
    else:
        gcc = require_tool("arm-none-eabi-gcc")
        (tmp_path / "p.c").write_text("void reset(void) { for (;;) ; }\n")
        subprocess.run([gcc, "-mcpu=cortex-m4", "-mthumb", "-nostdlib", "-Ttext=0", "-o",
                        str(target), str(tmp_path / "p.c")], check=True, capture_output=True)
    with FakeProbe() as probe:
        r = flash(target, "--port", probe.port)
        assert probe.packets == []
    assert r.returncode == 2
    assert says in r.stderr and len(r.stderr.splitlines()) == 1, r.stderr
