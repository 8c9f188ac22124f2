"""The e-puck project keeps matching GCtronic's e-puck library (the
`library/` of github.com/gctronic/e-puck-library, where EPUCK_LIB names a
checkout, as the generated Makefile reads it): every library source the
dspic Makefile lists exists there, every header the runtime includes is
there at the same path, and the runtime, the robot layer and every
example's program compile against the library's own headers (avr-gcc:
16-bit int, -Werror) instead of runtime_c/epuck_api's declarations."""
import re
import subprocess

import pytest

from conftest import REPO, require_epuck_library, require_tool
from epuckc.base.resources import RUNTIME_CORE, RUNTIME_DSPIC_DEVICES
from epuckc.build.common import ROBOT_COPIES
from tests.support.programs import epuckc

RUNTIME = REPO / "runtime_c"
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-Os", "-DEPUCKRT_NO_NAMES"]


@pytest.fixture(scope="module")
def library():
    return require_epuck_library("library") / "library"


def test_every_library_source_the_makefile_lists_exists(library):
    makefile = (REPO / "templates" / "dspic.mk.j2").read_text()
    listed = re.findall(r"\$\(LIB\)/([\w/]+\.[cs])\b", makefile)
    assert len(listed) >= 11
    missing = [rel for rel in listed if not (library / rel).is_file()]
    assert not missing, f"the dspic Makefile lists files the library does not have: {missing}"


def test_every_header_the_runtime_includes_is_the_librarys(library):
    text = (RUNTIME / "rt_internal.h").read_text()
    text = re.sub(r"#ifdef EPUCKRT_EPUCK2.*?#else", "", text, flags=re.S)   # the e-puck's branch
    headers = re.findall(r'#include "([\w/]+\.h)"', text)
    ours = {"epuckrt.h", "rt_platform.h"}
    assert [h for h in headers if h not in ours and not (library / h).is_file()] == []


def test_the_runtime_and_every_program_compile_against_the_library(library, tmp_path):
    avr = require_tool("avr-gcc")
    # the headers the project has at other paths than runtime_c/ (sensors/ground.h)
    for rel, source in ROBOT_COPIES.items():
        (tmp_path / "copies" / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / "copies" / rel).write_bytes((RUNTIME / source).read_bytes())
    # (the chip's register header, XC16's p30F6014A.h, which the library's I2C header
    # includes, from runtime_c/epuck_api, the last place looked in)
    flags = [f"-mmcu=atmega128", *STRICT, f"-I{RUNTIME}", f"-I{tmp_path / 'copies'}",
             f"-I{library}", f"-I{RUNTIME / 'epuck_api'}"]
    # the camera (rt_camera.c) against the library's camera/fast_2_timer/e_poxxxx.h, the
    # ground-sensor module (ground_i2c.c) against its I2C/e_I2C_master_module.h
    for source in [*(RUNTIME / n for n in (*RUNTIME_CORE, *RUNTIME_DSPIC_DEVICES)),
                   RUNTIME / "platform" / "platform_robot.c"]:
        subprocess.run([avr, *flags, "-c", str(source), "-o", str(tmp_path / "x.o")], check=True)
    for example in sorted((REPO / "examples").glob("*.epk")):
        c = tmp_path / f"{example.stem}.c"
        epuckc("compile", example, "-o", c, check=True)
        subprocess.run([avr, *flags, f"-I{tmp_path}", "-c", str(c), "-o", str(tmp_path / "x.o")],
                       check=True)
