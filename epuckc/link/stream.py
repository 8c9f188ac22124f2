"""The records of the robot's trace (runtime_c/rt_trace.c, docs/runtime.md
"The robot's trace"), decoded into the host trace's JSON records with the
program's table (build/trace_table.py): the same kinds, names and fields
as `epuckc run --trace` writes, the wheels' steps unwrapped into totals
since the start, the time from the robot's ms clock, the pose from the
odometry of the steps (odometry.py). What did not arrive is a record of
its own, never silence: `lost` (frames that came damaged or cut, the
reader resynchronised at the next whole frame) and `dropped` (records the
robot could not queue, counted there and sent). A stream whose hello
names another table than the one given is refused (TableMismatch)."""
from __future__ import annotations

from typing import Callable, Optional

from ..build.trace_table import DEFAULT_GEOMETRY, FORMAT
from .frames import Damage, FrameReader
from .odometry import Odometry

# the payloads' kinds (rt_trace.c's K_*)
HELLO, TICK, DROPPED = 1, 2, 3
EVENT, ACTION, SET, SUPPRESSED, MODE, MOTORS, LED, SOUND, SEND, MESSAGE, EXIT, TIMEOUT = \
    range(16, 28)
# rt_trace.c's commands[], the names rt_motion.c gives rt_trace_suppressed
COMMANDS = ("start_straight", "start_curve", "set_speed", "stop_motor", "run_sequence")
# the library's samples (host/epuck_stub.c e_play_sound): name, length in words
SOUNDS = (("haa", 2112), ("spaah", 1760), ("ouah", 3412), ("yaouh", 3732),
          ("wouaaaaaaaah", 8016))
LED_NAMES = [f"led{n}" for n in range(8)] + ["all", "body", "front"]


class TraceError(Exception):
    """A stream that must not be decoded: the message says why and what to do."""


class TableMismatch(TraceError):
    """The robot runs a program whose table is not the one given."""


class _Payload:
    """Reading one payload's fields in order; IndexError past its end."""

    def __init__(self, data: bytes):
        self.data, self.at = data, 0

    def u8(self) -> int:
        self.at += 1
        return self.data[self.at - 1]

    def u16(self) -> int:
        return self.u8() | self.u8() << 8

    def u32(self) -> int:
        return self.u16() | self.u16() << 16

    def uvar(self) -> int:
        value, shift = 0, 0
        while True:
            byte = self.u8()
            value |= (byte & 0x7F) << shift
            if byte < 0x80:
                return value
            shift += 7
            if shift > 35:
                raise IndexError("varint too long")

    def svar(self) -> int:
        v = self.uvar()
        return -(v >> 1) - 1 if v & 1 else v >> 1

    def id(self) -> int:            # rt_trace.c put_id: -1 as 0
        return self.uvar() - 1

    def more(self) -> bool:
        return self.at < len(self.data)


def _signed16(v: int) -> int:
    v &= 0xFFFF
    return v - 0x10000 if v >= 0x8000 else v


class TraceDecoder:
    """Bytes of the robot's link in, JSON trace records out (`feed`, then
    `close` at the end of the stream). `table`: the program's (None: any
    program, its records named by number). `on_note(text)` hears what is
    worth a line on stderr (a table-less stream's fingerprint, a join in
    the middle of a run)."""

    def __init__(self, table: Optional[dict] = None,
                 on_note: Optional[Callable[[str], None]] = None):
        self.table = table
        self.on_note = on_note or (lambda text: None)
        self.frames = FrameReader()
        self.odometry = Odometry((table or {}).get("geometry") or DEFAULT_GEOMETRY)
        self.synced = False         # a hello was seen
        self.t_ms = 0
        self.raw = [0, 0]           # the wheels' counters at the last record
        self.total = [0, 0]
        self.dropped_total = None   # as the robot last told it
        self.unsynced_frames = 0    # whole frames before the first hello
        self.damage: Optional[Damage] = None
        self.sequence: Optional[int] = None     # the next frame's number
        self.restarted = False      # a second start: the robot began again
        self.ended = False          # exit or timeout seen
        self.frames_decoded = 0

    # ---- names ----------------------------------------------------------------------
    def _name(self, kind: str, index: int, fallback: str) -> str:
        names = (self.table or {}).get(kind, [])
        if isinstance(names, dict):
            found = names.get(str(index))
        else:
            found = names[index] if 0 <= index < len(names) else None
        return found if found is not None else f"{fallback}#{index}"

    def event_name(self, i: int) -> str:
        return self._name("events", i, "event")

    def step_names(self, action_id: int) -> list:
        return list(((self.table or {}).get("steps") or {}).get(str(action_id), []))

    # ---- the stream ------------------------------------------------------------------
    def feed(self, data: bytes) -> list:
        out = []
        for item in self.frames.feed(data):
            if isinstance(item, Damage):
                self.damage = item if self.damage is None else Damage(
                    self.damage.frames + item.frames, self.damage.size + item.size)
                continue
            out += self._payload(item)
        return out

    def close(self) -> list:
        """The end of the stream: damage since the last whole frame (an
        unfinished one at the end with it) as a last `lost` record."""
        damage = self.frames.close()
        if damage is not None:
            self.damage = damage if self.damage is None else Damage(
                self.damage.frames + damage.frames, self.damage.size + damage.size)
        return self._lost(None)

    def _lost(self, until_ms: Optional[int], missing: Optional[int] = None,
              at_ms: Optional[int] = None) -> list:
        """The `lost` record of what came between two whole frames:
        `missing` frames by their sequence numbers (None: not known, at the
        end of the stream: the damaged pieces counted), the damage's bytes."""
        damage, self.damage = self.damage, None
        if not missing and damage is None:
            return []
        if not self.synced:
            self.unsynced_frames += damage.frames if damage else 0
            return []
        frames = missing if missing is not None else damage.frames
        record = {"t_ms": self.t_ms if at_ms is None else at_ms, "kind": "lost", "name": "lost",
                  "id": -1, "frames": frames, "bytes": damage.size if damage else 0}
        if until_ms is not None:
            record["until_ms"] = until_ms
        return [record]

    def _missing(self, number: int) -> int:
        """Frames lost before this one, by the sequence numbers."""
        missing = 0 if self.sequence is None else (number - self.sequence) & 0xFF
        self.sequence = (number + 1) & 0xFF
        return missing

    def _time(self, low: int) -> int:
        return self.t_ms + ((low - self.t_ms) & 0xFFFF)

    def _payload(self, data: bytes) -> list:
        kind = data[0]
        if not self.synced and kind != HELLO:
            self.unsynced_frames += 1
            return []
        try:
            p = _Payload(data)
            p.u8()
            number = p.u8()
            if kind == HELLO:
                return self._hello(p, number)
            t = self._time(p.u16())
            last_ms = self.t_ms
            records = self._record(kind, p, t)
        except IndexError:
            # a whole frame (its CRC holds) that is no record of this format
            self.damage = Damage((self.damage.frames if self.damage else 0) + 1,
                                 (self.damage.size if self.damage else 0) + len(data))
            return []
        self.frames_decoded += 1
        before = self._lost(t, self._missing(number), last_ms)
        self.t_ms = max(self.t_ms, t)
        return before + records

    def _hello(self, p: _Payload, number: int) -> list:
        form, first, fingerprint, t = p.u8(), p.u8(), p.u32(), p.u32()
        dropped = p.uvar()
        raw = (p.u16(), p.u16())
        if form != FORMAT:
            raise TraceError(f"the robot's trace is of format {form}; this epuckc reads format "
                             f"{FORMAT}: build the program with this epuckc (epuckc build "
                             f"--trace) and upload it again")
        self._check_table(fingerprint)
        out = []
        if self.synced and first:
            self.restarted = True
            return []
        if not self.synced:
            self.synced = True
            self.sequence = (number + 1) & 0xFF
            self.t_ms = t
            self.raw = list(raw)
            self.total = [_signed16(raw[0]), _signed16(raw[1])] if first else [0, 0]
            self.odometry.left, self.odometry.right = self.total
            if not first:
                self.on_note(f"joined a run in progress at {t} ms: the trace starts there, "
                             f"the wheels' steps and the pose count from there")
                self.dropped_total = dropped
            if self.unsynced_frames or self.damage is not None:
                frames = self.unsynced_frames + (self.damage.frames if self.damage else 0)
                size = self.damage.size if self.damage else 0
                self.damage = None
                out.append({"t_ms": t, "kind": "lost", "name": "lost", "id": -1,
                            "frames": frames, "bytes": size, "before_start": True})
                self.unsynced_frames = 0
        else:
            out += self._lost(t, self._missing(number))
            self.t_ms = max(self.t_ms, t)
            self._steps(*raw)
        out += self._dropped(dropped)
        self.frames_decoded += 1
        return out

    def _check_table(self, fingerprint: int) -> None:
        if self.table is None:
            if not self.synced:
                self.on_note(f"no table given (--program): the robot's program has the table "
                             f"{fingerprint:08x}; its rules, actions and variables are shown by "
                             f"number")
            return
        mine = int(self.table["fingerprint"], 16)
        if fingerprint != mine:
            raise TableMismatch(
                f"the robot runs a program whose trace table is {fingerprint:08x}, not "
                f"{self.table.get('program', 'the program')}'s ({mine:08x}): it was built from "
                f"another program or another version of it, and its records would be "
                f"named wrongly. Give --program the program the robot runs (or its "
                f"NAME.trace.json), or build this one with --trace and upload it again")

    def _dropped(self, total: int) -> list:
        if self.dropped_total is None:
            self.dropped_total = 0
        if total <= self.dropped_total:
            return []
        count, self.dropped_total = total - self.dropped_total, total
        return [{"t_ms": self.t_ms, "kind": "dropped", "name": "dropped", "id": -1,
                 "count": count, "total": total}]

    def _steps(self, left: int, right: int) -> None:
        for wheel, raw in ((0, left), (1, right)):
            self.total[wheel] += _signed16(raw - self.raw[wheel])
            self.raw[wheel] = raw
        self.odometry.move_to(*self.total)

    def _base(self, t: int, kind: str, name: str, number: int, steps: tuple) -> dict:
        """t_ms .. heading_deg of a record with the wheels' steps."""
        self._steps(*steps)
        x, y, h = self.odometry.pose()
        return {"t_ms": t, "kind": kind, "name": name, "id": number,
                "left_steps": self.total[0], "right_steps": self.total[1],
                "x_mm": x, "y_mm": y, "heading_deg": h}

    def _record(self, kind: int, p: _Payload, t: int) -> list:
        """The records of one payload: its fields are all read (IndexError
        for a payload of another shape) before anything of the decoder's
        state changes."""
        def steps():
            return p.u16(), p.u16()

        def done():
            if p.more():
                raise IndexError("a payload longer than its kind's")

        if kind == TICK:
            wheels = steps()
            done()
            return [self._base(t, "pose", "pose", -1, wheels)]
        if kind == DROPPED:
            total = p.uvar()
            done()
            self.t_ms = max(self.t_ms, t)
            return self._dropped(total)
        if kind == EVENT:
            i, wheels = p.uvar(), steps()
            done()
            return [self._base(t, "event", self.event_name(i), i, wheels)]
        if kind == ACTION:
            i, wheels = p.uvar(), steps()
            sequence = (p.uvar(), p.uvar()) if p.more() else None
            done()
            record = self._base(t, "action", self._name("actions", i, "action"), i, wheels)
            if sequence is not None:
                record.update(step=sequence[0] + 1, steps=sequence[1])
            return [record]
        if kind == SET:
            i, value = p.uvar(), p.svar()
            done()
            return [{"t_ms": t, "kind": "set", "var": self._name("variables", i, "var"),
                     "value": value}]
        if kind == SUPPRESSED:
            me, priority, owner, owner_priority = p.id(), p.svar(), p.id(), p.svar()
            command, wheels = p.u8(), steps()
            done()
            record = self._base(t, "suppressed", self.event_name(me), me, wheels)
            record.update(command=COMMANDS[command] if command < len(COMMANDS)
                          else f"command#{command}", priority=priority, owner=owner,
                          owner_name=self.event_name(owner), owner_priority=owner_priority)
            return [record]
        if kind == MODE:
            i, wheels = p.uvar(), steps()
            done()
            return [self._base(t, "mode", self._name("modes", i, "mode"), i, wheels)]
        if kind == MOTORS:
            active, owner, wheels = p.u8(), p.id(), steps()
            done()
            name = "free" if not active else "main" if owner < 0 else self.event_name(owner)
            return [self._base(t, "motors", name, owner if active else -1, wheels)]
        if kind == LED:
            packed, ring, wheels = p.u8(), p.u8(), steps()
            done()
            if (packed & 0x0F) >= len(LED_NAMES):
                raise IndexError("no such LED")
            record = self._base(t, "led", LED_NAMES[packed & 0x0F], -1, wheels)
            record.update(state=packed >> 4 & 1,
                          ring="".join("1" if ring >> n & 1 else "0" for n in range(8)),
                          body=packed >> 5 & 1, front=packed >> 6 & 1)
            return [record]
        if kind == SOUND:
            sound, wheels = p.u8(), steps()
            done()
            name, length = SOUNDS[sound] if sound < len(SOUNDS) else (f"sound#{sound}", 0)
            record = self._base(t, "sound", name, -1, wheels)
            record["length"] = length
            return [record]
        if kind == SEND:
            value, wheels = p.u8(), steps()
            done()
            record = self._base(t, "send", "send", -1, wheels)
            record["value"] = value
            return [record]
        if kind == MESSAGE:
            value, bearing, distance, wheels = p.u8(), p.svar(), p.uvar(), steps()
            done()
            record = self._base(t, "message", "message", -1, wheels)
            record.update(value=value, bearing_deg=float(bearing), range_mm=float(distance))
            return [record]
        if kind in (EXIT, TIMEOUT):
            wheels = steps()
            done()
            self.ended = True
            return [self._base(t, "exit" if kind == EXIT else "timeout",
                               "exit_main" if kind == EXIT else "timeout", -1, wheels)]
        raise IndexError(f"no payload of kind {kind}")
