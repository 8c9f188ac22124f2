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
# epuckrt.h; rt_internal.h is what they share. Every build (host, Enki, the
# robot's projects), cache key and test takes the list from here;
# runtime_c/Makefile repeats it (CORE), and a test keeps the two equal.
RUNTIME_CORE = ("epuckrt.c", "rt_motion.c", "rt_sensors.c", "rt_modes.c", "rt_lang.c",
                "rt_math.c")
# The runtime's device files (IR messages, the ToF sensor, the camera, the
# e-puck2's RGB LEDs): in
# the builds of the targets that have the devices (host, Enki worlds, the
# e-puck2); the e-puck's (dspic) takes only the camera (RUNTIME_DSPIC_DEVICES),
# and its checker refuses the others' names (E070); the core never calls
# them, so it links without them.
RUNTIME_DEVICES = ("rt_comm.c", "rt_tof.c", "rt_camera.c", "rt_rgb.c")
RUNTIME_DSPIC_DEVICES = ("rt_camera.c",)
# What only a platform that simulates time links with the core (the host
# harness, the robots of Enki worlds): rt_idle.c tells host/platform_host.c
# which polls it may run in bulk. A robot polls in real time: not in its builds.
RUNTIME_SIMULATED = ("rt_idle.c",)
RUNTIME_CORE_HEADERS = ("epuckrt.h", "rt_internal.h", "rt_platform.h", "utility.h")


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
