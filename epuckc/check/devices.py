"""Devices a target lacks: a standard action, event or reading that needs
a device (stdlib/table.py, `device`) the program's target does not have
is an error naming the target [E070], so that a build never fails at the
link. The simulation (`host`: the stub harness and Enki worlds) has every
device; the checker is told the target by `epuckc build --target` and
`epuckc check --target`."""
from __future__ import annotations

from ..stdlib.table import DEVICES, TARGET_DEVICES, TARGET_NAMES

_OTHERS = {"messages": "build it for the e-puck2 (`--target epuck2`) or run it in a world",
           "tof": "build it for the e-puck2 (`--target epuck2`), or read the proximity "
                  "sensors (`ir0`, `ir7`) for what is close ahead"}


def require(checker, device: str, what: str, span) -> bool:
    """False (after reporting once per name) when `what` (an action, event
    or reading named in the text at `span`) needs `device` and the
    checker's target lacks it."""
    if not device:
        return True
    if device in TARGET_DEVICES.get(checker.target, DEVICES):
        checker.devices_used.add(device)
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
