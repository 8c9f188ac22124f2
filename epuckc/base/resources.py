"""Where the grammar, templates and C runtime are.

In a checkout they sit at the top of the repository; an installed wheel
carries them inside the package (see pyproject.toml), so both places are
tried, the package first.
"""
from __future__ import annotations

import os
from pathlib import Path

_PACKAGE = Path(__file__).resolve().parent.parent   # epuckc/

# The runtime's own sources, one file per concern (docs/runtime.md), behind
# epuckrt.h, bottom layer first (rt_internal.h shows the layers; each file
# calls only the files before it, tests/test_architecture.py). Every build (host, Enki, the
# robot's projects), cache key and test takes the list from here;
# runtime_c/Makefile repeats it (CORE), and a test keeps the two equal.
RUNTIME_CORE = ("rt_math.c", "rt_clock.c", "rt_sensors.c", "rt_registry.c", "rt_odometry.c",
                "rt_motion.c", "rt_lang.c", "rt_modes.c", "epuckrt.c")
# The runtime's device files (IR messages, the ToF sensor, the camera, the
# e-puck2's RGB LEDs, the ground-sensor module): in
# the builds of the targets that have the devices (host, Enki worlds, the
# e-puck2); the e-puck's (dspic) takes only the camera (RUNTIME_DSPIC_DEVICES),
# and its checker refuses the others' names (E070); the core never calls
# them, so it links without them.
RUNTIME_DEVICES = ("rt_comm.c", "rt_tof.c", "rt_camera.c", "rt_rgb.c", "rt_ground.c")
# the e-puck's: the camera, and GCtronic's ground-sensor module with the
# e-puck2 firmware's API to it that ground_i2c.c provides over the e-puck
# library's I2C bus
RUNTIME_DSPIC_DEVICES = ("rt_camera.c", "rt_ground.c", "ground_i2c.c")
# What only a platform that simulates time links with the core (the host
# harness, the robots of Enki worlds): rt_idle.c tells platform/platform_host.c
# which polls it may run in bulk. A robot polls in real time: not in its builds.
RUNTIME_SIMULATED = ("rt_idle.c",)
RUNTIME_CORE_HEADERS = ("epuckrt.h", "rt_internal.h", "rt_clock.h", "rt_sensors.h",
                        "rt_registry.h", "rt_odometry.h", "rt_motion.h", "rt_modes.h",
                        "rt_platform.h", "utility.h")
# The robot's trace (`build --trace`, docs/runtime.md "The robot's trace"):
# the tracer, and its link on each robot: the e-puck library's UART1 (the
# e-puck, and the 16-bit simulator's model of it), ChibiOS's serial drivers
# (the e-puck2). In no build without --trace; runtime_c/Makefile's TRACE is
# the tracer and the UART1 link (its 16-bit check).
RUNTIME_TRACE = ("rt_trace.c",)
RUNTIME_TRACE_UART1 = ("rt_trace_uart1.c",)
RUNTIME_TRACE_CHIBIOS = ("rt_trace_chibios.c",)
# The e-puck library's simulation, below the runtime on the host, in Enki
# worlds and on the 16-bit path (runtime_c/host/epuck_stub.h says what each
# file simulates), with the e-puck2 firmware's ground-sensor API
# (host/stub_ground.c); the host's platform files (platform_host.c,
# scenario.c, cmain.c) and the 16-bit path's are apart.
LIBRARY_SIMULATION = ("host/epuck_stub.c", "host/outputs.c", "host/sound.c", "host/imu.c",
                      "host/camera.c", "host/stub_devices.c", "host/stub_ground.c",
                      "host/epuck_more.c", "host/dspic.c", "host/unsimulated.c")


def resource_dir(name: str) -> Path:
    for candidate in (_PACKAGE / name, _PACKAGE.parent / name):
        if candidate.is_dir() and any(candidate.iterdir()):
            return candidate
    raise FileNotFoundError(f"epuckc is installed without its {name}/ directory")


def grammar_path() -> Path:
    return resource_dir("grammar") / "epuck.lark"


def templates_dir() -> Path:
    return resource_dir("templates")


def runtime_dir() -> Path:
    return resource_dir("runtime_c")


def cache_dir() -> Path:
    """Where epuckc keeps what it can rebuild (parse tables, host builds):
    $EPUCKC_CACHE_DIR, else $XDG_CACHE_HOME/epuckc, else ~/.cache/epuckc."""
    if os.environ.get("EPUCKC_CACHE_DIR"):
        return Path(os.environ["EPUCKC_CACHE_DIR"])
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "epuckc"
