"""`epuckc build --target epuck2`: the project on GCtronic's e-puck2 firmware
(as its Project_template), the exit status and next command when the
toolchain or the firmware is missing, and every example, the runtime and
the ChibiOS platform layer compiled for the Cortex-M4 with the firmware's
warning flags; the full build where the firmware is (EPUCK2_FIRMWARE)."""
import os
import subprocess
from pathlib import Path

import pytest

from conftest import REPO, require_checkout, require_tool
from epuckc.base.resources import RUNTIME_CORE, RUNTIME_DEVICES
from epuckc.build.epuck2 import EPUCK2_SOURCES, make_command
from tests.support.programs import epuckc

EXAMPLES = sorted((REPO / "examples").glob("*.epk"))
RUNTIME = REPO / "runtime_c"
# the firmware's Makefile: CWARN, the Cortex-M4 with its FPU; -Werror: no
# warning from the project's own files
ARM_FLAGS = ["-mcpu=cortex-m4", "-mthumb", "-mfloat-abi=hard", "-mfpu=fpv4-sp-d16",
             "-std=gnu99", "-Os", "-Wall", "-Wextra", "-Wundef", "-Wstrict-prototypes",
             "-Wno-implicit-fallthrough", "-Werror", "-DEPUCKRT_EPUCK2", "-DEPUCKRT_NO_NAMES"]
API = [f"-I{RUNTIME / 'epuck2_api'}", f"-I{RUNTIME / 'epuck_api'}"]


def _env_without(tool: str) -> dict:
    """PATH without the folders that hold `tool`."""
    env = dict(os.environ)
    env["PATH"] = os.pathsep.join(p for p in env.get("PATH", "").split(os.pathsep)
                                  if p and not (Path(p) / tool).exists())
    env.pop("EPUCK2_FIRMWARE", None)
    return env


def test_project_is_the_firmwares_project_template(tmp_path):
    out = tmp_path / "proj"
    r = epuckc("build", "--target", "epuck2", REPO / "examples" / "braitenberg.epk", "-o", out,
               env={"EPUCK2_FIRMWARE": ""})
    assert r.returncode == 3, r.stderr
    makefile = (out / "Makefile").read_text()
    assert "GLOBAL_PATH = $(EPUCK2_FIRMWARE)" in makefile
    assert "include $(GLOBAL_PATH)/Makefile" in makefile
    assert "$(GLOBAL_PATH)/src/epuck1x" in makefile and "-DEPUCKRT_EPUCK2" in makefile
    for name in [*RUNTIME_CORE, "platform_robot.c", "platform_epuck2.c", "newlib_stubs.c"]:
        assert f"./runtime/{name} \\" in makefile
        assert (out / "runtime" / name).is_file()
    assert "./program_main.c" in makefile and "./braitenberg.c" not in makefile
    assert '#include "braitenberg.c"' in (out / "program_main.c").read_text()
    main = (out / "main.c").read_text()
    for call in ("halInit();", "chSysInit();", "mpu_init();", "messagebus_init(&bus",
                 "parameter_namespace_declare(&parameter_root", "motors_init();",
                 "proximity_start(", "epk_program_main();"):
        assert call in main
    assert "extern messagebus_t bus;" in (out / "main.h").read_text()
    # the next command, and no traceback
    assert "git clone --recursive https://github.com/e-puck2/e-puck2_main-processor" in r.stderr
    assert f"make -C {out} EPUCK2_FIRMWARE=" in r.stderr and "Traceback" not in r.stderr


def test_without_the_arm_toolchain_it_says_how_to_get_it(tmp_path):
    r = epuckc("build", "--target", "epuck2", REPO / "examples" / "square.epk", "-o",
               tmp_path / "p", env=_env_without("arm-none-eabi-gcc"))
    assert r.returncode == 3
    assert "apt-get install gcc-arm-none-eabi libnewlib-arm-none-eabi" in r.stderr


def test_a_folder_that_is_not_the_firmware_is_named(tmp_path):
    require_tool("arm-none-eabi-gcc")
    r = epuckc("build", "--target", "epuck2", REPO / "examples" / "square.epk", "-o",
               tmp_path / "p", "--firmware", tmp_path)
    assert r.returncode == 3
    assert f"{tmp_path} is not the firmware's folder" in r.stderr


@pytest.mark.parametrize("example", EXAMPLES, ids=lambda p: p.stem)
def test_every_example_compiles_for_the_cortex_m4(tmp_path, example):
    """The generated C, through program_main.c (main renamed), with the
    firmware's warnings as errors, against the project's API headers."""
    gcc = require_tool("arm-none-eabi-gcc")
    out = tmp_path / "proj"
    r = epuckc("build", "--target", "epuck2", example, "-o", out, env={"EPUCK2_FIRMWARE": ""})
    assert r.returncode == 3, r.stderr
    sources = [out / "program_main.c"] + sorted((out / "user").glob("*.c"))
    for source in sources:
        subprocess.run([gcc, *ARM_FLAGS, f"-I{out}", f"-I{out / 'runtime'}", *API, "-c",
                        str(source), "-o", str(tmp_path / "x.o")], check=True)


def test_the_runtime_and_the_platform_layer_compile_for_the_cortex_m4(tmp_path):
    gcc = require_tool("arm-none-eabi-gcc")
    for source in [*(RUNTIME / n for n in (*RUNTIME_CORE, *RUNTIME_DEVICES)),
                   RUNTIME / "platform" / "platform_robot.c",
                   RUNTIME / "platform" / "platform_epuck2.c", RUNTIME / "epuck2" / "newlib_stubs.c"]:
        subprocess.run([gcc, *ARM_FLAGS, f"-I{RUNTIME}", *API, "-c", str(source), "-o",
                        str(tmp_path / "x.o")], check=True)


def test_the_platform_layer_sleeps_and_never_spins():
    """Under ChibiOS a busy wait would starve the firmware's sensor and motor
    threads: the poll waits in chThdSleepUntilWindowed, and the millisecond
    clock is counted from the system time."""
    text = (RUNTIME / "platform" / "platform_epuck2.c").read_text()
    idle = text[text.index("void rt_platform_idle(void)"):]
    idle = idle[:idle.index("\n}\n")]
    assert "chThdSleepUntilWindowed(" in idle and "rt_clock_tick()" in idle
    assert "while (rt_millis() ==" not in idle


def _firmware() -> str:
    """The firmware's folder (EPUCK2_FIRMWARE), with arm-none-eabi-gcc."""
    firmware = str(require_checkout(
        "EPUCK2_FIRMWARE", "src",
        "EPUCK2_FIRMWARE is not set: the full e-puck2 link needs the firmware "
        "(git clone --recursive https://github.com/e-puck2/e-puck2_main-processor)"))
    require_tool("arm-none-eabi-gcc")
    return firmware


@pytest.mark.parametrize("example", EXAMPLES + ["every_feature"],
                         ids=lambda p: getattr(p, "stem", p))
def test_a_full_build_with_the_firmware(tmp_path, example):
    """Needs the firmware tree with its submodules (ChibiOS, ...): where
    EPUCK2_FIRMWARE names it, every example and the language's
    every-feature program link into an .elf and a .bin."""
    firmware = _firmware()
    if example == "every_feature":
        from tests.runtime.test_language import EVERY_FEATURE
        example = tmp_path / "every_feature.epk"
        example.write_text(EVERY_FEATURE, encoding="utf-8")
    out = tmp_path / "proj"
    r = epuckc("build", "--target", "epuck2", example, "-o", out, "--firmware", firmware)
    assert r.returncode == 0, r.stdout + r.stderr
    assert (out / "build" / f"{example.stem}.elf").is_file()
    assert (out / "build" / f"{example.stem}.bin").is_file()


def _fake_tool(folder: Path, name: str, body: str = "exit 0") -> Path:
    folder.mkdir(exist_ok=True)
    tool = folder / name
    tool.write_text(f"#!/bin/sh\n{body}\n")
    tool.chmod(0o755)
    return tool


def test_make_runs_on_every_core_through_ccache_when_it_is_there(tmp_path):
    ccache = _fake_tool(tmp_path / "bin", "ccache")
    command, env, used = make_command("make", tmp_path / "p", tmp_path / "fw",
                                      {"PATH": str(ccache.parent)})
    assert used == str(ccache)
    assert command[:4] == ["make", f"-j{os.cpu_count() or 1}", "-C", str(tmp_path / "p")]
    assert f"EPUCK2_FIRMWARE={tmp_path / 'fw'}" in command
    assert f"CC={ccache} arm-none-eabi-gcc" in command
    # one project's firmware objects serve the next, whatever its folder
    assert env["CCACHE_NOHASHDIR"] == "1"
    # the user's own choice of ccache's hash_dir is kept
    _, env, _ = make_command("make", tmp_path / "p", tmp_path / "fw",
                             {"PATH": str(ccache.parent), "CCACHE_HASHDIR": "1"})
    assert "CCACHE_NOHASHDIR" not in env


@pytest.mark.parametrize("no_ccache, on_path", [(True, True), (False, False)],
                         ids=["EPUCKC_NO_CCACHE", "no ccache on PATH"])
def test_without_ccache_make_calls_the_firmwares_compiler(tmp_path, no_ccache, on_path):
    folder = _fake_tool(tmp_path / "bin", "ccache").parent
    environ = {"PATH": str(folder if on_path else tmp_path / "empty")}
    if no_ccache:
        environ["EPUCKC_NO_CCACHE"] = "1"
    command, env, used = make_command("make", tmp_path / "p", tmp_path / "fw", environ)
    assert used is None
    assert not any(arg.startswith("CC=") for arg in command)
    assert "CCACHE_NOHASHDIR" not in env


def test_a_ccache_that_fails_is_named_with_the_way_around_it(tmp_path):
    """A ccache that cannot work (here one that always fails, as one with an
    unwritable cache folder does) fails the build with its own message,
    and the error says how to build without it."""
    firmware = _firmware()
    broken = _fake_tool(tmp_path / "bin", "ccache",
                        "echo 'ccache: error: Failed to create directory' >&2\nexit 1")
    path = f"{broken.parent}{os.pathsep}{os.environ['PATH']}"
    r = epuckc("build", "--target", "epuck2", EXAMPLES[0], "-o", tmp_path / "p",
               "--firmware", firmware, env={"PATH": path})
    assert r.returncode != 0 and "Traceback" not in r.stderr
    assert "ccache: error: Failed to create directory" in r.stderr
    assert f"through {broken}" in r.stderr and "EPUCKC_NO_CCACHE=1" in r.stderr
    r = epuckc("build", "--target", "epuck2", EXAMPLES[0], "-o", tmp_path / "p",
               "--firmware", firmware, env={"PATH": path, "EPUCKC_NO_CCACHE": "1"})
    assert r.returncode == 0, r.stdout + r.stderr


def _ccache_stats(ccache: str) -> dict:
    out = subprocess.run([ccache, "--print-stats"], capture_output=True, text=True,
                         check=True).stdout
    return {key: int(value) for key, value in
            (line.split("\t") for line in out.splitlines() if "\t" in line)}


def test_a_second_project_compiles_only_its_own_files(tmp_path):
    """The firmware's files compile once: a second program, in another
    folder, gets their objects from ccache and compiles only the program,
    main.c and the runtime (a full build of the firmware is ~200 files)."""
    firmware = _firmware()
    ccache = require_tool("ccache")
    first, second = EXAMPLES[0], EXAMPLES[-1]
    r = epuckc("build", "--target", "epuck2", first, "-o", tmp_path / "one",
               "--firmware", firmware)
    assert r.returncode == 0, r.stdout + r.stderr
    before = _ccache_stats(ccache)
    r = epuckc("build", "--target", "epuck2", second, "-o", tmp_path / "two",
               "--firmware", firmware)
    assert r.returncode == 0, r.stdout + r.stderr
    assert (tmp_path / "two" / "build" / f"{second.stem}.elf").is_file()
    after = _ccache_stats(ccache)
    hits = sum(after.get(k, 0) - before.get(k, 0)
               for k in ("direct_cache_hit", "preprocessed_cache_hit"))
    misses = after.get("cache_miss", 0) - before.get("cache_miss", 0)
    # the project's own files: main.c, program_main.c, the runtime, the user's C
    own = len(list((tmp_path / "two").rglob("*.c")))
    assert own >= len(EPUCK2_SOURCES) + 2
    assert misses <= own, (misses, own)
    assert hits >= 150, hits


DEVICES = """# messages, the camera, the ToF sensor and the RGB LEDs in one program
var turn = 0 steps/s
rule chase: every 50 ms if seen(red) > 0 and distance > 50 mm do
    turn = bearing(red) / 1 deg * 10 steps/s, set_speed(300 steps/s - turn, 300 steps/s + turn)
rule tell: every 200 ms do send(clamp(distance / 10 mm, 0, 255))
rule hear: on message repeat do turn = message_bearing / 1 deg * 1 steps/s,
    led_rgb(led3, clamp(distance / 20 mm, 0, 100), 0, 100 - clamp(distance / 20 mm, 0, 100))
on immediate do led_rgb(led1, 100, 0, 0)
"""


def test_a_full_build_with_messages_the_camera_and_the_tof_sensor(tmp_path):
    """Issue 27: messages (the firmware's src/ircom), the camera (its
    epuck1x e_poxxxx over po8030 and dcmi, started as its main starts it)
    and the VL53L0X link into the firmware, each from the runtime's own file;
    and issue 25's RGB LEDs (its src/leds.c's set_rgb_led)."""
    firmware = _firmware()
    nm = require_tool("arm-none-eabi-nm")
    program = tmp_path / "devices.epk"
    program.write_text(DEVICES, encoding="utf-8")
    out = tmp_path / "proj"
    r = epuckc("build", "--target", "epuck2", program, "-o", out, "--firmware", firmware)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "cam_start();" in (out / "main.c").read_text()
    symbols = subprocess.run([nm, str(out / "build" / "devices.elf")], capture_output=True,
                             text=True, check=True).stdout
    defined = {line.split()[-1] for line in symbols.splitlines() if " T " in line}
    assert {"action_send", "event_message", "rt_seen", "rt_bearing", "rt_distance",
            "ircomSend", "ircomPopMessage", "e_poxxxx_launch_capture",
            "VL53L0X_get_dist_mm", "action_led_rgb", "set_rgb_led"} <= defined


def test_a_program_without_the_camera_does_not_start_it(tmp_path):
    out = tmp_path / "proj"
    r = epuckc("build", "--target", "epuck2", EXAMPLES[0], "-o", out,
               env={"EPUCK2_FIRMWARE": ""})
    assert r.returncode == 3, r.stderr
    assert "cam_start" not in (out / "main.c").read_text()
