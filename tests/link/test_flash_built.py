"""`epuckc flash PROG.epk`: the rule file is built by `epuckc build`'s own
command, then flashed. The e-puck2: a real example linked into GCtronic's
firmware (EPUCK2_FIRMWARE) and loaded by the real gdb-multiarch into the
fake programmer, which must hold exactly the .elf's loadable sections (one
firmware build, the dearest test here). The e-puck: XC16 is not free to
install, so `make` is a stand-in that leaves a known hex where the
project's Makefile would; without XC16 the build's message and the next
command are given."""
import json
import os
import sys
from pathlib import Path

import pytest

from conftest import REPO, require_checkout, require_tool
from tests.support.arm_elf import flash_image, received
from tests.support.fake_probe import FakeProbe
from tests.support.fake_tinybld import FakeTinybld
from tests.support.flash import flash
from tests.support.xc16_hex import example_words, expected_memory, write_program

EXAMPLE = REPO / "examples" / "braitenberg.epk"


def test_a_rule_file_built_into_the_firmware_and_flashed_to_the_e_puck2(tmp_path):
    firmware = require_checkout(
        "EPUCK2_FIRMWARE", "src",
        "EPUCK2_FIRMWARE is not set: the e-puck2 build needs the firmware "
        "(git clone --recursive https://github.com/e-puck2/e-puck2_main-processor)")
    require_tool("arm-none-eabi-gcc")
    require_tool("gdb-multiarch")
    objcopy = require_tool("arm-none-eabi-objcopy")
    out = tmp_path / "proj"
    with FakeProbe() as probe:
        r = flash(EXAMPLE, "--target", "epuck2", "--port", probe.port, "-o", out,
                  "--firmware", firmware, timeout=900)
        assert r.returncode == 0, r.stdout + r.stderr
        elf = out / "build" / "braitenberg.elf"
        image = flash_image(elf, objcopy)
        assert received(probe) == image
        assert all(probe.flash_bytes(a, 1)[0] == b for a, b in image.items())
        assert probe.errors == [] and probe.killed
    lines = r.stdout.splitlines()
    assert lines[0] == f"built {elf} and .bin"
    assert lines[1].startswith(f"flashed {elf} to the e-puck2 on {probe.port} ("
                               f"{len(image):,} bytes in ")


def _fake_xc16(tmp_path: Path, hexfile: Path) -> dict:
    """An environment where xc16-gcc is found and `make` leaves `hexfile`
    as the project's NAME.hex (the name read from its Makefile)."""
    tools = tmp_path / "tools"
    tools.mkdir()
    (tools / "xc16-gcc").write_text("#!/bin/sh\nexit 0\n")
    (tools / "make").write_text(
        f"#!{sys.executable}\n"
        "import os, re, shutil, sys, pathlib\n"
        "folder = pathlib.Path(sys.argv[sys.argv.index('-C') + 1])\n"
        "name = re.search(r'^PROGRAM = (\\S+)\\.c', (folder / 'Makefile').read_text(), re.M)\n"
        f"shutil.copy({str(hexfile)!r}, folder / (name.group(1) + '.hex'))\n")
    for tool in tools.iterdir():
        tool.chmod(0o755)
    return {"PATH": str(tools) + os.pathsep + os.environ.get("PATH", ""),
            "EPUCK_LIB": str(tmp_path), "XC16_DIR": ""}


def test_a_rule_file_built_for_the_e_puck_and_flashed_over_its_bootloader(tmp_path):
    words = example_words(seed=3)
    env = _fake_xc16(tmp_path, write_program(tmp_path / "made.hex", words))
    out = tmp_path / "proj"
    with FakeTinybld() as robot:
        r = flash(EXAMPLE, "--target", "epuck", "-o", out, "--port", robot.port,
                  "--robot-id", "2024", env=env)
        assert r.returncode == 0, r.stdout + r.stderr
        assert robot.flash == expected_memory(words, 2024, {})
    lines = r.stdout.splitlines()
    assert lines[0] == f"built {out / 'braitenberg.hex'}"
    assert lines[1].startswith(f"flashed {out / 'braitenberg.hex'} to the e-puck 2024 on "
                               f"{robot.port} (")


def test_without_xc16_the_project_is_written_and_the_next_commands_given(tmp_path):
    out = tmp_path / "proj"
    path = os.pathsep.join(p for p in os.environ.get("PATH", "").split(os.pathsep)
                           if p and not (Path(p) / "xc16-gcc").exists())
    with FakeTinybld() as robot:
        r = flash(EXAMPLE, "--target", "dspic", "-o", out, "--port", robot.port,
                  "--robot-id", "1", env={"PATH": path, "XC16_DIR": ""})
        assert robot.answers == []
    assert r.returncode == 3
    assert f"the project was written to {out}, but it was not built: xc16-gcc" in r.stderr
    assert (f"epuckc: note: once the .hex is built, flash it with: epuckc flash "
            f"{out / 'braitenberg.hex'} --port {robot.port} --robot-id 1") in r.stderr


def test_flash_with_trace_builds_the_tracer_in_and_says_how_to_watch_it(tmp_path):
    """`epuckc flash PROG.epk --trace` builds as `epuckc build --trace`
    does (the options are build's, add_build_options): the project has the
    tracer on UART1 with the table's fingerprint compiled in, the table is
    beside it, and the command that watches the trace is given."""
    words = example_words(seed=5)
    env = _fake_xc16(tmp_path, write_program(tmp_path / "made.hex", words))
    out = tmp_path / "proj"
    with FakeTinybld() as robot:
        r = flash(EXAMPLE, "--target", "epuck", "--trace", "-o", out, "--port", robot.port,
                  "--robot-id", "77", env=env)
        assert r.returncode == 0, r.stdout + r.stderr
        assert robot.flash == expected_memory(words, 77, {})
    makefile = (out / "Makefile").read_text()
    table = out / "braitenberg.trace.json"
    fingerprint = json.loads(table.read_text())["fingerprint"]
    assert f"-DEPUCKRT_TRACE_ID=0x{fingerprint}UL" in makefile
    assert "runtime/rt_trace.c runtime/rt_trace_uart1.c" in makefile
    assert (out / "runtime" / "rt_trace.c").is_file()
    assert (f"epuckc: note: the robot sends its trace: epuckc monitor {robot.port} "
            f"--program {table}") in r.stderr
    # without --trace, the same flash builds none of it
    plain = tmp_path / "plain"
    with FakeTinybld() as robot:
        r = flash(EXAMPLE, "--target", "epuck", "-o", plain, "--port", robot.port,
                  "--robot-id", "77", env=env)
        assert r.returncode == 0, r.stdout + r.stderr
    assert "TRACE" not in (plain / "Makefile").read_text()
    assert not list(plain.glob("*.trace.json")) and "epuckc monitor" not in r.stderr


@pytest.mark.parametrize("given, more, why", [
    ("prog.hex", ["--trace"], "is built already, so --trace cannot build the robot's tracer"),
    ("prog.epk", ["--target", "epuck", "--trace", "--trace-link", "usb"], "is the e-puck2's"),
    ("prog.epk", ["--target", "epuck", "--trace-link", "usb"], "give --trace with it"),
])
def test_trace_options_that_cannot_be_are_refused_before_any_robot_is_touched(
        tmp_path, given, more, why):
    program = tmp_path / given
    if given.endswith(".hex"):
        write_program(program, example_words(seed=1))
    else:
        program.write_text(EXAMPLE.read_text())
    with FakeTinybld() as robot:
        r = flash(program, *more, "-o", tmp_path / "p", "--port", robot.port,
                  "--robot-id", "1")
        assert robot.answers == [] and robot.calls == 0
    assert r.returncode == 2 and why in r.stderr and "Traceback" not in r.stderr, r.stderr
    assert not (tmp_path / "p").exists()
