"""Devices a target lacks: a standard action, event or reading that needs
a device (stdlib/table.py, `device`) the program's target does not have
is an error naming the target [E070], so that a build never fails at the
link. The simulation (`host`: the stub harness and Enki worlds) has every
device; the checker is told the target by `epuckc build --target` and
`epuckc check --target`.

On the host, three of them come from a world only: without one (`epuckc
run` alone, `world=False`) nobody hears a message sent and none arrives,
the camera sees nothing and the ToF sensor nothing in its range. The
program runs, but the first use of each is a warning naming the device
and how to give it one [W070]."""
from __future__ import annotations

from ..stdlib.table import DEVICES, TARGET_DEVICES, TARGET_NAMES

_OTHERS = {"messages": "build it for the e-puck2 (`--target epuck2`) or run it in a world",
           "tof": "build it for the e-puck2 (`--target epuck2`), or read the proximity "
                  "sensors (`ir0`, `ir7`) for what is close ahead"}


# Each of a world's devices: what it is, what it does in a run without a
# world, and what world gives it.
_WITHOUT_WORLD = {
    "messages": ("IR messages", "no robot hears what it sends and no message arrives",
                 "a world with other robots"),
    "camera": ("the camera", "it sees nothing (no coloured box, cylinder or robot)",
               "a world with coloured things (`cylinder at ... colour red`)"),
    "tof": ("the ToF distance sensor", "it has nothing in its range (it reads 2000 mm)",
            "a world with walls or obstacles"),
}


def _alone(checker, device: str, what: str, span) -> None:
    """W070, once per device: the run has no world to give the device."""
    if checker.world or device not in _WITHOUT_WORLD or device in checker.device_reported:
        return
    checker.device_reported.add(device)
    name, without, world = _WITHOUT_WORLD[device]
    checker.diags.warning("W070", span,
                          f"`{what}` uses {name}, which only a world gives: in this run "
                          f"without one {without}",
                          help=f"run it in {world}: `epuckc run FILE --world W.world` "
                               f"(docs/world.md)")


def require(checker, device: str, what: str, span) -> bool:
    """False (after reporting once per name) when `what` (an action, event
    or reading named in the text at `span`) needs `device` and the
    checker's target lacks it."""
    if not device:
        return True
    if device in TARGET_DEVICES.get(checker.target, DEVICES):
        checker.devices_used.add(device)
        _alone(checker, device, what, span)
        return True
    key = (device, what)
    if key not in checker.device_reported:
        checker.device_reported.add(key)
        checker.diags.error("E070", span,
                            f"`{what}` needs {DEVICES[device]}, which "
                            f"{TARGET_NAMES[checker.target]} does not have",
                            help=_OTHERS.get(device, "remove it, or build for a target that "
                                                     "has it"))
    return False
