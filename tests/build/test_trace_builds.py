"""`epuckc build --trace` (the robot's tracer, docs/runtime.md "The robot's
trace") on both robots: the dspic project with the tracer on the
Bluetooth UART1 (GCtronic's UART1 files in its Makefile, the runtime and
the program compiled against the library's own headers where int is 16
bits, as the other dspic tests check it: there is no XC16 here), the
e-puck2 project with it on UART3 or the USB serial port linked into the
real firmware, the table beside the program with its fingerprint compiled
in; --trace where it means nothing refused; and, without --trace, the
runtime exactly what it was without a tracer: its objects are the bytes of
the same sources with the tracer's hooks taken out."""
import json
import re
import subprocess
from pathlib import Path

import pytest

from conftest import REPO, require_checkout, require_tool
from epuckc.base.resources import (RUNTIME_CORE, RUNTIME_DEVICES, RUNTIME_DSPIC_DEVICES,
                                   RUNTIME_TRACE, RUNTIME_TRACE_CHIBIOS, RUNTIME_TRACE_UART1)
from tests.support.programs import epuckc

EXAMPLES = REPO / "examples"
RUNTIME = REPO / "runtime_c"
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-Os"]


def _dspic(tmp_path, example="bump_counter.epk", *more):
    out = tmp_path / "proj"
    r = epuckc("build", EXAMPLES / example, "--target", "dspic", "--trace", *more, "-o", out,
               env={"XC16_DIR": "", "PATH": "/usr/bin:/bin"})
    assert r.returncode == 3, r.stderr      # written, not built: no XC16 here
    return out


def _defines(makefile: str) -> dict:
    return dict(re.findall(r"-D(\w+)(?:=(\S+))?", makefile))


def test_the_dspic_project_has_the_tracer_its_link_and_its_table(tmp_path):
    out = _dspic(tmp_path)
    for name in (*RUNTIME_TRACE, *RUNTIME_TRACE_UART1):
        assert (out / "runtime" / name).is_file()
    table = json.loads((out / "bump_counter.trace.json").read_text())
    makefile = (out / "Makefile").read_text()
    defines = _defines(makefile)
    assert "EPUCKRT_TRACE" in defines and "EPUCKRT_NO_NAMES" in defines
    assert defines["EPUCKRT_TRACE_ID"] == f"0x{table['fingerprint']}UL"
    assert defines["EPUCKRT_TRACE_BUFFER"] == "256"
    for part in ("e_init_uart1.s", "e_uart1_tx_char.s", "e_uart1_rx_char.s"):
        assert f"$(LIB)/uart/{part}" in makefile
    assert "runtime/rt_trace.c runtime/rt_trace_uart1.c" in makefile
    assert table["events"][1].startswith("bump_counter.epk:13 rule bump")
    assert table["steps"]["0"] == ["stop_motor, led_on(body)", "wait(500 ms)", "exit_main"]


def test_without_trace_the_projects_have_none_of_it(tmp_path):
    for target in ("dspic", "epuck2"):
        out = tmp_path / target
        epuckc("build", EXAMPLES / "square.epk", "--target", target, "-o", out,
               env={"XC16_DIR": "", "EPUCK2_FIRMWARE": "", "PATH": "/usr/bin:/bin"})
        makefile = (out / "Makefile").read_text()
        assert "TRACE" not in makefile and "uart" not in makefile
        assert not list(out.rglob("rt_trace*")) and not list(out.glob("*.trace.json"))


def test_the_dspic_projects_sources_compile_against_the_library_with_16_bit_int(tmp_path):
    """As tests/build/test_epuck_library.py: the runtime with the tracer,
    its UART1 link and the program against GCtronic's own headers
    (uart/e_uart_char.h among them), with avr-gcc, -Werror."""
    library = require_checkout("EPUCK_LIB", "library",
                               "EPUCK_LIB does not name GCtronic's e-puck library") / "library"
    avr = require_tool("avr-gcc")
    out = _dspic(tmp_path)
    defines = [f"-D{k}" + (f"={v}" if v else "") for k, v in
               _defines((out / "Makefile").read_text()).items()]
    for source in [out / "bump_counter.c", *(out / "runtime" / n for n in (
            *RUNTIME_CORE, *RUNTIME_DSPIC_DEVICES, "platform_robot.c", *RUNTIME_TRACE,
            *RUNTIME_TRACE_UART1))]:
        subprocess.run([avr, "-mmcu=atmega128", *STRICT, *defines, f"-I{out}",
                        f"-I{out / 'runtime'}", f"-I{library}",
                        # XC16's p30F6014A.h, which the library's I2C header (ground_i2c.c)
                        # includes, from runtime_c/epuck_api, the last place looked in
                        f"-I{RUNTIME / 'epuck_api'}", "-c", str(source), "-o",
                        str(tmp_path / "x.o")], check=True)
    for part in ("e_init_uart1.s", "e_uart1_tx_char.s", "e_uart1_rx_char.s"):
        assert (library / "uart" / part).is_file()


def test_the_dspic_makefile_assembles_the_uart_with_its_include(tmp_path):
    make = require_tool("make")
    out = _dspic(tmp_path)
    lib = tmp_path / "lib"
    for rel in re.findall(r"\$\(LIB\)/([\w/.]+\.[cs])\b", (out / "Makefile").read_text()):
        (lib / "library" / rel).parent.mkdir(parents=True, exist_ok=True)
        (lib / "library" / rel).write_text("")
    dry = subprocess.run([make, "-n", "-C", str(out), f"EPUCK_LIB={lib}"], capture_output=True,
                         text=True, check=True).stdout
    assert re.search(r"xc16-gcc -mcpu=30F6014A -omf=elf -I\S+/codec -I\S+/uart -c "
                     r"\S+/uart/e_uart1_tx_char.s", dry)
    assert "-DEPUCKRT_TRACE " in dry and "runtime/rt_trace.c" in dry


@pytest.mark.parametrize("more, why", [
    (["--target", "host", "--trace"], "--trace is for the robots' builds"),
    (["--target", "dspic", "--trace-link", "usb"], "give --trace with it"),
    (["--target", "dspic", "--trace", "--trace-link", "usb"], "is the e-puck2's"),
])
def test_trace_where_it_means_nothing_is_refused(tmp_path, more, why):
    r = epuckc("build", EXAMPLES / "square.epk", *more, "-o", tmp_path / "p")
    assert r.returncode == 2 and why in r.stderr and "Traceback" not in r.stderr
    assert not (tmp_path / "p").exists()


@pytest.mark.parametrize("link", ["uart", "usb"])
def test_the_e_puck2_build_with_the_tracer_links_into_the_firmware(tmp_path, link):
    firmware = str(require_checkout(
        "EPUCK2_FIRMWARE", "src", "EPUCK2_FIRMWARE is not set: the full e-puck2 link needs "
        "the firmware (git clone --recursive https://github.com/e-puck2/e-puck2_main-processor)"))
    require_tool("arm-none-eabi-gcc")
    out = tmp_path / "proj"
    r = epuckc("build", EXAMPLES / "bump_counter.epk", "--target", "epuck2", "--trace",
               "--trace-link", link, "-o", out, "--firmware", firmware)
    assert r.returncode == 0, r.stdout + r.stderr
    makefile = (out / "Makefile").read_text()
    for name in (*RUNTIME_TRACE, *RUNTIME_TRACE_CHIBIOS):
        assert f"./runtime/{name} \\" in makefile
    assert ("-DEPUCKRT_TRACE_USB" in makefile) == (link == "usb")
    assert "-DEPUCKRT_TRACE_BUFFER=1024" in makefile
    symbols = subprocess.run(["arm-none-eabi-nm", str(out / "build" / "bump_counter.elf")],
                             capture_output=True, text=True, check=True).stdout
    assert re.search(r" T rt_tracer_poll$", symbols, re.M)
    assert re.search(r" T (usb_start|sdStart)$", symbols, re.M)
    assert (out / "bump_counter.trace.json").is_file()


def _text_of(obj, tmp_path) -> bytes:
    binary = tmp_path / "text.bin"
    subprocess.run(["avr-objcopy", "-O", "binary", "-j", ".text", "-j", ".data", str(obj),
                    str(binary)], check=True)
    return binary.read_bytes()


def test_without_trace_the_runtime_is_the_same_bytes_as_without_its_hooks(tmp_path):
    """The tracer costs nothing off: each runtime file compiled without
    EPUCKRT_TRACE gives the same code and data, byte for byte, as the file
    with every RT_TRACE_* hook line deleted, and references nothing of
    the tracer."""
    avr = require_tool("avr-gcc")
    require_tool("avr-objcopy")
    flags = ["-mmcu=atmega1284p", *STRICT, "-DEPUCKRT_NO_NAMES", f"-I{RUNTIME}",
             f"-I{RUNTIME / 'epuck_api'}"]
    hooked = 0
    for name in (*RUNTIME_CORE, *RUNTIME_DEVICES, "platform/platform_robot.c"):
        source = (RUNTIME / name).read_text()
        stripped = re.sub(r"^[ \t]*RT_TRACE_\w+\(.*\);[^\n]*\n", "", source, flags=re.M)
        hooked += source != stripped
        plain, without = tmp_path / "plain.o", tmp_path / "without.o"
        subprocess.run([avr, *flags, "-c", str(RUNTIME / name), "-o", str(plain)], check=True)
        copy = tmp_path / Path(name).name
        copy.write_text(stripped)
        subprocess.run([avr, *flags, "-c", str(copy), "-o", str(without)],
                       check=True)
        assert _text_of(plain, tmp_path) == _text_of(without, tmp_path), name
        symbols = subprocess.run(["avr-nm", str(plain)], capture_output=True, text=True,
                                 check=True).stdout
        assert "rt_tracer" not in symbols and "rt_trace_port" not in symbols, name
    assert hooked >= 3          # the poll's, the LEDs' and sounds', the messages'
