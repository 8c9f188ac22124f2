"""The one table of the standard actions and events.

Each entry says what the language accepts (its parameters in the paper's
order, which is the order of positional arguments, with their kinds and
ranges), what it means (one line of documentation) and what it becomes
(the runtime call). The checker, lowering, the language reference
(docs/language.md section 3, kept equal to `reference_markdown()` by a test)
and the editor's hover and completion all read this table; none keeps a
list of its own.
"""
from __future__ import annotations

from typing import Optional

from ..base.records import record
from .units import ANGLE, DISTANCE, DURATION, INT, NATURAL_UNIT, SPEED

SENSOR_COUNT = 8
THRESHOLD_MAX = 4095
CHOICE = "choice"           # the kind of a parameter that names one of its Choices


@record(frozen=True)
class Choice:
    """One value of an enumerated parameter: its name in rule files, the C
    expression it becomes, and what it means."""
    name: str
    c: str
    doc: str


@record(frozen=True)
class Choices:
    """The values an enumerated parameter takes (an LED, a sound, a key).
    `numbers`: whole numbers lo..hi accepted as themselves as well (the
    remote control's digit keys)."""
    what: str
    values: tuple
    numbers: Optional[tuple] = None

    def names(self) -> list:
        return [c.name for c in self.values]

    def get(self, name: str) -> Optional[Choice]:
        return next((c for c in self.values if c.name == name), None)

    def describe(self) -> str:
        names = [c.name for c in self.values]
        text = ", ".join(f"`{n}`" for n in names)
        if self.numbers is not None:
            text = f"{self.numbers[0]}..{self.numbers[1]}, " + text
        return text


@record(frozen=True)
class Param:
    """A parameter: its name, its kind (units.py, or CHOICE), and for the
    standard ones a short description and the range the checker enforces,
    in words with the codes that enforce it. `choices` lists the values of
    a CHOICE parameter; `lo`..`hi` bound a whole-number one (`range_code`
    reports a value outside)."""
    name: str
    kind: str
    doc: str = ""
    range: str = ""
    choices: Optional[Choices] = None
    lo: Optional[int] = None
    hi: Optional[int] = None
    range_code: str = "E042"


@record(frozen=True)
class ActionSpec:
    name: str
    params: tuple
    doc: str
    runtime: str              # the runtime's action function the call becomes
    motion: bool = False      # starts a motion (ends with a `stop_motor` event)
    motors: bool = False      # commands the motors (a motion, or stopping one)
    runtime_param: Optional[str] = None   # its parameter struct, when not the paper's
    fields: tuple = ()        # the struct's initialisers: C text, `{param}` is a value
    # for an action without parameters given arguments [E016]: where what the
    # user meant goes instead (`set_timer(2 s)`: the time goes on `timer`)
    misuse: str = ""
    # what a call whose arguments are expressions (computed while the program
    # runs) becomes: (function, struct, fields) with the values in their
    # natural units (mm, steps/s, deg); None: its arguments must be fixed
    dynamic: Optional[tuple] = None
    device: str = ""          # the device it needs (DEVICES); "": every e-puck has it

    @property
    def signature(self) -> str:
        return signature(self.name, self.params)


@record(frozen=True)
class EventSpec:
    name: str
    params: Optional[tuple]   # None: takes conditions (`sensor(ir0 > 300)`)
    doc: str
    runtime: str              # the runtime's event function
    runtime_param: Optional[str] = None   # its parameter struct, if any
    fields: tuple = ()        # as ActionSpec.fields, for the structs not the paper's
    in_mode: bool = False     # only inside a mode (`enter`)
    conditions_doc: str = ""  # for params None: its conditions, when not the sensor's
    # the function keeps status->memory between polls: a compiled program
    # gives the rule a long of RAM for it (False: the function never reads it)
    memory: bool = True
    # written as a rule's head of its own (`when COND`, `every D`, `after D`),
    # not `on NAME(...)`
    head: bool = False
    device: str = ""          # the device it needs (DEVICES)
    # when it can occur if nothing but time passes (a host skips the polls
    # that cannot see it occur: docs/runtime.md, "Idle polls in bulk"):
    # "change" only after the inputs or the program's state changed,
    # "deadline" when the clock reaches the time in its memory (its own
    # timer), "timer" as `timer` on its parameter; "": at any poll
    wake: str = ""

    @property
    def signature(self) -> str:
        if self.head:
            return f"{self.name} {self.params[0].name.upper()}"
        if self.params is None:
            return f"{self.name}(irN > T, irM < T, ...)"
        return signature(self.name, self.params)


# The devices not every target has, what they are in words, and the targets
# that have each: the checker reports a standard name that needs a device
# its target lacks [E070] (never a link error). `host` is the simulation
# (the stub harness and Enki worlds), which models them all.
DEVICES = {
    "messages": "IR messages between robots (libIrcom: `ircomSend`, `ircomPopMessage`)",
    "tof": "the time-of-flight distance sensor (VL53L0X)",
    "camera": "the colour camera (`e_poxxxx`; the e-puck2's po8030 through `dcmi`)",
    "rgb_leds": "RGB LEDs (the e-puck2's four, `set_rgb_led`)",
    "ground": "GCtronic's ground-sensor module (three IR sensors under the front, "
              "`get_ground_prox`)",
}
TARGET_DEVICES = {
    "host": frozenset(DEVICES),
    # the e-puck library the dspic project builds with has no IR messaging
    # (libIrcom is a library apart) and the e-puck has no ToF sensor; the
    # ground module is read over its I2C protocol (runtime_c/ground_i2c.c)
    "dspic": frozenset({"camera", "ground"}),
    "epuck2": frozenset({"messages", "tof", "camera", "rgb_leds", "ground"}),
}
TARGET_NAMES = {"host": "the simulation (host)", "dspic": "the e-puck (dspic)",
                "epuck2": "the e-puck2 (epuck2)"}
MESSAGE_MAX = 255           # ircomSend carries one byte (IRCOM_WORDSIZE 8)

_SPEED_RANGE = "-max_speed..max_speed (1000 steps/s on the e-puck) [E030]"
_STEPS_RANGE = "a 16-bit int of motor steps [E034]"

LEDS = Choices("LED", tuple(
    [Choice(f"led{i}", str(i), f"ring LED {i}" + (" (front; numbered clockwise seen from "
                                                   "above: led2 right, led4 back, led6 left)"
                                                   if i == 0 else ""))
     for i in range(8)]
    + [Choice("all", "SET_LED_ALL", "the eight ring LEDs"),
       Choice("body", "SET_LED_BODY", "the green body LED"),
       Choice("front", "SET_LED_FRONT", "the red front LED")]))
# The e-puck2's four RGB LEDs, between the red ones of the ring (the
# firmware's LED2, LED4, LED6, LED8: rgb_led_name_t 0..3).
RGB_LEDS = Choices("RGB LED", tuple(
    Choice(f"led{i}", str(k), f"the RGB LED at ring position {i} (the firmware's LED{i + 1})")
    for k, i in enumerate((1, 3, 5, 7))))
RGB_MAX = 100               # the firmware's RGB_MAX_INTENSITY: percent
SOUNDS = Choices("sound", (
    Choice("haa", "SOUND_HAA", "a short \"haa\""),
    Choice("spaah", "SOUND_SPAAH", "\"spaah\""),
    Choice("ouah", "SOUND_OUAH", "\"ouah\""),
    Choice("yaouh", "SOUND_YAOUH", "\"yaouh\""),
    Choice("wouaaaaaaaah", "SOUND_WOUAAAAAAAAH", "the long \"wouaaaaaaaah\""),
))
# RC5 codes of a TV remote control (e_get_data); digits are 0..9 themselves.
KEYS = Choices("key", (
    Choice("standby", "12", "the standby (power) key"),
    Choice("mute", "13", "mute"),
    Choice("vol_up", "16", "volume up"),
    Choice("vol_down", "17", "volume down"),
    Choice("chan_up", "32", "channel up"),
    Choice("chan_down", "33", "channel down"),
), numbers=(0, 9))
# The colours the camera tells apart (runtime_c/rt_camera.c, rt_colour: one
# classifier on every target; docs/runtime.md gives its thresholds).
COLOURS = Choices("colour", (
    Choice("red", "RT_RED", "hue 330..30 degrees"),
    Choice("yellow", "RT_YELLOW", "hue 30..90"),
    Choice("green", "RT_GREEN", "hue 90..150"),
    Choice("cyan", "RT_CYAN", "hue 150..210"),
    Choice("blue", "RT_BLUE", "hue 210..270"),
    Choice("magenta", "RT_MAGENTA", "hue 270..330"),
))
CAMERA_PIXELS = 60
CHOICES = (LEDS, SOUNDS, KEYS, COLOURS)

SENSOR_NAMES_DOC = ("ir0", f"ir{SENSOR_COUNT - 1}")
_LED = Param("led", CHOICE, "which LED", "one of " + LEDS.describe() + " [E041]", choices=LEDS)
_READING_RANGE = f"a whole number 0..{THRESHOLD_MAX} [E032]"

ACTIONS = (
    ActionSpec("start_straight",
               (Param("speed", SPEED, "wheel speed; negative drives backwards", _SPEED_RANGE),
                Param("distance", DISTANCE, "how far; negative drives backwards", _STEPS_RANGE)),
               "drives straight; backwards when exactly one of them is negative (both: forward [W012])",
               # compiled to exact steps: the runtime's extension, so the
               # paper's param_start_straight stays the paper's
               "straight_steps", motion=True, motors=True, runtime_param="param_straight_steps",
               dynamic=("action_start_straight", "param_start_straight",
                        ("{speed}", "{distance}"))),
    ActionSpec("start_curve",
               (Param("radius", DISTANCE, "from the robot's centre to the circle's centre",
                      ">= 0 [E036], a 16-bit int of mm [E034]"),
                Param("degrees", ANGLE, "arc angle; positive turns left, negative right",
                      "the outer wheel's steps fit a 16-bit int [E034]"),
                Param("speed", SPEED, "the outer wheel's speed; negative drives backwards",
                      _SPEED_RANGE)),
               "drives an arc through the robot's centre; positive degrees turn left, negative "
               "right; `speed` is the outer wheel's; radius 0 turns on the spot",
               "curve_steps", motion=True, motors=True, runtime_param="param_curve_steps",
               dynamic=("action_start_curve", "param_start_curve",
                        ("{radius}", "{degrees}", "{speed}"))),
    ActionSpec("set_speed",
               (Param("left", SPEED, "the left wheel's speed; negative turns it backwards",
                      _SPEED_RANGE),
                Param("right", SPEED, "the right wheel's speed", _SPEED_RANGE)),
               "drives the wheels at these speeds until the next motor command (no "
               "`stop_motor` event: it has no end)",
               "action_set_speed", motors=True, runtime_param="param_set_speed",
               fields=("{left}", "{right}"),
               dynamic=("action_set_speed", "param_set_speed", ("{left}", "{right}"))),
    ActionSpec("wait",
               (Param("time", DURATION, "how long the sequence waits",
                      "> 0 [E033], at most 2147483647 ms [E034]"),),
               "a step of a `then` sequence: the next step starts `time` later (and not "
               "before the motion of the step before has ended)",
               "action_wait", runtime_param="param_wait", fields=("{time}L",)),
    ActionSpec("stop_motor", (), "stops the wheels; the current motion ends", "stop_motor",
               misuse="it stops the wheels at once; to stop after a distance or an angle, give "
                      "it to the motion (`start_straight(300, 10 cm)`) and use `on stop_motor`",
               motors=True),
    ActionSpec("set_timer", (), "(re)starts the one timer at 0", "set_timer",
               misuse="it starts the timer at 0; the time goes on the rule that waits for it: "
                      "`on immediate do set_timer` and `on timer(2 s) do ...`"),
    ActionSpec("reset_timer", (), "stops the timer", "reset_timer",
               misuse="it stops the timer; a time goes on a `timer(...)` event"),
    ActionSpec("start_sensor", (), "starts polling the proximity sensors, from the next poll",
               "start_sensor",
               misuse="it starts all eight sensors; the sensor and its threshold go on the rule "
                      "that waits for them: `on sensor(ir0 > 300) do ...`"),
    ActionSpec("stop_sensor", (), "stops it; sensor conditions are then false", "stop_sensor",
               misuse="it stops all eight sensors"),
    ActionSpec("exit_main", (), "ends the main loop", "exit_main",
               misuse="it ends the program at once; to end it later: "
                      "`on timer(10 s) do exit_main` (after `set_timer`)"),
    ActionSpec("led_on", (_LED,), "switches an LED on (`e_set_led`, `e_set_body_led`, "
               "`e_set_front_led`)", "action_set_led", runtime_param="param_set_led",
               fields=("{led}", "SET_LED_ON")),
    ActionSpec("led_off", (_LED,), "switches an LED off", "action_set_led",
               runtime_param="param_set_led", fields=("{led}", "SET_LED_OFF")),
    ActionSpec("led_toggle", (_LED,), "switches an LED on if it is off, off if it is on",
               "action_set_led", runtime_param="param_set_led",
               fields=("{led}", "SET_LED_TOGGLE")),
    # `fill(a, v)` is `a = [v, v, ...]` (check/arrays.py), v computed once
    ActionSpec("fill",
               (Param("array", "array", "a variable array", "declared `var a = [...]` [E062]"),
                Param("value", "value", "what every element gets, computed once",
                      "of the array's kind [E048]")),
               "gives every element of a variable array one value (`a = [v, v, ...]`)",
               "action_fill", runtime_param="param_fill",
               dynamic=("action_fill", "param_fill", ("{array}", "{id}", "{count}", "{value}"))),
    ActionSpec("led_ring",
               (Param("count", INT, "how many ring LEDs to light, from LED 0 (the front) "
                      "clockwise", "0..8 [E042]; a value computed outside is taken as the "
                      "nearest end", lo=0, hi=8),),
               "shows a number on the ring: LEDs 0..count-1 on, the others off",
               "action_led_ring", runtime_param="param_led_ring", fields=("{count}",),
               dynamic=("action_led_ring", "param_led_ring", ("{count}",))),
    ActionSpec("led_bits",
               (Param("bits", INT, "bit k lights ring LED k",
                      "0..255 [E042]; a value computed is taken modulo 256", lo=0, hi=255),),
               "shows a bit pattern on the ring: LED k on where bit k of `bits` is 1",
               "action_led_bits", runtime_param="param_led_bits", fields=("{bits}",),
               dynamic=("action_led_bits", "param_led_bits", ("{bits}",))),
    ActionSpec("play_sound",
               (Param("sound", CHOICE, "one of the library's five samples",
                      "one of " + SOUNDS.describe() + " [E041]", choices=SOUNDS),),
               "plays a built-in sample on the speaker (`e_play_sound`); the program goes on "
               "at once", "action_play_sound", runtime_param="param_play_sound",
               fields=("{sound}",)),
    ActionSpec("send",
               (Param("value", INT, "the value the message carries",
                      f"a whole number 0..{MESSAGE_MAX} [E042] (one byte, as `ircomSend`); an "
                      "expression that can leave it is warned [W030] and sent modulo 256",
                      lo=0, hi=MESSAGE_MAX),),
               "broadcasts `value` over the IR sensors (`ircomSend`) to the robots in range; "
               "a send while one is still on the air replaces the value waiting to go",
               "action_send", runtime_param="param_send", fields=("{value}",),
               dynamic=("action_send", "param_send", ("{value}",)), device="messages"),
    ActionSpec("led_rgb",
               (Param("led", CHOICE, "which RGB LED", "one of " + RGB_LEDS.describe() + " [E041]",
                      choices=RGB_LEDS),)
               + tuple(Param(colour, INT, f"its {colour} in percent",
                             f"0..{RGB_MAX} [E042]; a value computed outside is taken as the "
                             f"nearest end", lo=0, hi=RGB_MAX)
                       for colour in ("red", "green", "blue")),
               "sets the colour of one of the e-puck2's RGB LEDs (`set_rgb_led`); 0, 0, 0 "
               "switches it off", "action_led_rgb", runtime_param="param_led_rgb",
               fields=("{led}", "{red}", "{green}", "{blue}"),
               dynamic=("action_led_rgb", "param_led_rgb",
                        ("{led}", "{red}", "{green}", "{blue}")), device="rgb_leds"),
)

EVENTS = (
    EventSpec("when",
              (Param("condition", "condition", "a condition on variables and readings",
                     "comparisons joined with `and`, `or`, `not` [E050]"),),
              "when the condition becomes true (and, with `repeat`, every time it becomes "
              "true again)", "rt_when", head=True, wake="change"),
    EventSpec("every",
              (Param("period", DURATION, "time between two firings",
                     "> 0 [E033], at most 2147483647 ms [E034]"),),
              "every `period`, counted from when the rule is armed (start, or its mode's "
              "entry); its own timer", "event_every", "param_event_every",
              fields=("{period}L",), head=True, wake="deadline"),
    EventSpec("after",
              (Param("delay", DURATION, "time from when the rule is armed",
                     "> 0 [E033], at most 2147483647 ms [E034]"),),
              "once, `delay` after the rule is armed (start, or its mode's entry); its own "
              "timer", "event_after", "param_event_every", fields=("{delay}L",), head=True,
              wake="deadline"),
    EventSpec("immediate", (), "at the first poll", "immediate", memory=False),
    EventSpec("stop_motor", (),
              "when a motion has ended (reached its distance or stopped by `stop_motor`)",
              "event_stop_motor", memory=False, wake="change"),
    EventSpec("timer",
              (Param("time", DURATION, "time since `set_timer`",
                     "> 0 [E033], at most 2147483647 ms [E034]"),),
              "when the timer has run `time` since `set_timer`",
              "timer", "param_event_timer", wake="timer"),
    EventSpec("sensor", None,
              "when some listed sensor's reading passes its threshold",
              "sensor", "param_event_sensor", wake="change"),
    EventSpec("enter", (), "at the first poll after its mode was entered; only inside a "
              "mode [E044]", "event_enter_mode", in_mode=True, wake="change"),
    EventSpec("selector",
              (Param("position", INT, "a position of the 16-position selector",
                     "a whole number 0..15 [E042]", lo=0, hi=15),),
              "when the selector (`getselector()`) is at `position` at start, or turns to it",
              "event_selector", "param_event_selector", fields=("{position}",), wake="change"),
    EventSpec("clap",
              (Param("volume", INT, "microphone volume (peak to peak, raw)", _READING_RANGE,
                     lo=0, hi=THRESHOLD_MAX, range_code="E032"),),
              "when some microphone's volume (`e_get_micro_volume`) goes over `volume`",
              "event_clap", "param_event_clap", fields=("{volume}",), wake="change"),
    EventSpec("tap",
              (Param("threshold", INT, "change of a raw accelerometer axis in one poll",
                     _READING_RANGE, lo=0, hi=THRESHOLD_MAX, range_code="E032"),),
              "when an accelerometer axis (`e_get_acc_filtered(axis, 1)`) jumps by more than "
              "`threshold` "
              "between two polls (a knock on the robot)",
              "event_tap", "param_event_accel", fields=("{threshold}",)),
    EventSpec("tilt",
              (Param("threshold", INT, "raw accelerometer units away from rest",
                     _READING_RANGE, lo=0, hi=THRESHOLD_MAX, range_code="E032"),),
              "when the x or y acceleration differs from its reading at start by more than "
              "`threshold` (the robot tilted or lifted)",
              "event_tilt", "param_event_accel", fields=("{threshold}",)),
    EventSpec("remote",
              (Param("key", CHOICE, "a key of an RC5 (TV) remote control",
                     "a digit 0..9 [E042] or one of " + ", ".join(f"`{n}`" for n in KEYS.names())
                     + " [E041]", choices=KEYS),),
              "when that key of the remote control is pressed (`e_get_check`, `e_get_data`)",
              "event_remote", "param_event_remote", fields=("{key}",), wake="change"),
    EventSpec("ambient", None,
              "when some listed sensor's ambient light reading (`e_get_ambient_light`) passes "
              "its threshold; needs no `start_sensor`",
              "event_ambient", "param_event_sensor", wake="change",
              conditions_doc=f"`{SENSOR_NAMES_DOC[0]}`..`{SENSOR_NAMES_DOC[1]}` `>` or `<` a "
              f"whole threshold in 0..{THRESHOLD_MAX} [E032] (raw ambient light readings)"),
    EventSpec("message", (),
              "for each message received (`ircomPopMessage`), one per poll, in the order they "
              "came; while its action runs, `message`, `message_bearing` and `message_range` "
              "describe it (the runtime queues 8; when full, the oldest is dropped)",
              "event_message", memory=False, device="messages", wake="change"),
)

STANDARD_ACTIONS = {spec.name: spec for spec in ACTIONS}
MOTOR_ACTIONS = frozenset(spec.name for spec in ACTIONS if spec.motors)
STANDARD_EVENTS = {spec.name: spec for spec in EVENTS}
MOTION_ACTIONS = frozenset(spec.name for spec in ACTIONS if spec.motion)

# The paper's long spellings are accepted too (`action_start_straight`,
# `event_timer`), so that its tables can be copied as they are.
ACTION_ALIASES = {f"action_{name}": name for name in STANDARD_ACTIONS}
# (`enter` is written as its keyword only: it has no long spelling)
EVENT_ALIASES = {f"event_{spec.name}": spec.name for spec in EVENTS
                 if not spec.in_mode and not spec.head}

SENSOR_NAMES = tuple(f"ir{i}" for i in range(SENSOR_COUNT))
SENSOR_CONDITION_DOC = (f"`{SENSOR_NAMES[0]}`..`{SENSOR_NAMES[-1]}` `>` or `<` a whole "
                        f"threshold in 0..{THRESHOLD_MAX} [E032] (0: nothing near, "
                        f"{THRESHOLD_MAX}: touching)")

EXTERN_TYPES = ("int", "distance", "speed", "angle", "duration")


@record(frozen=True)
class Reading:
    """A value of the robot that expressions read: its kind (units.py), the
    interval the checker assumes, the runtime call that reads it, and what
    it is."""
    name: str
    kind: str
    lo: int
    hi: int
    c: str
    doc: str
    device: str = ""          # the device it needs (DEVICES)
    # a reading of one of several things, written `name(CHOICE)`: `c` has
    # `{choice}` where the choice's C goes (`seen(red)`: `rt_seen(RT_RED)`)
    param: Optional[Param] = None

    @property
    def signature(self) -> str:
        return f"{self.name}({self.param.choices.what.upper()})" if self.param else self.name


_COLOUR = Param("colour", CHOICE, "a colour the camera tells apart",
                "one of " + COLOURS.describe() + " [E041]", choices=COLOURS)

READINGS = tuple(
    [Reading(f"ir{i}", INT, 0, THRESHOLD_MAX, f"rt_ir({i})",
             f"proximity sensor {i} (`e_get_prox`; 0: nothing near, {THRESHOLD_MAX}: touching)")
     for i in range(SENSOR_COUNT)]
    + [Reading(f"ambient{i}", INT, 0, THRESHOLD_MAX, f"rt_ambient({i})",
               f"ambient light at sensor {i} (`e_get_ambient_light`, raw)")
       for i in range(SENSOR_COUNT)]
    + [Reading(f"mic{i}", INT, 0, THRESHOLD_MAX, f"rt_mic({i})",
               f"volume of microphone {i} (`e_get_micro_volume`, peak to peak)")
       for i in range(3)]
    + [Reading(f"ground{i}", INT, 0, THRESHOLD_MAX, f"rt_ground({i})",
               f"ground sensor {i}, {side} (`get_ground_prox`: light reflected by the floor, "
               f"about 1000 on white paper, near 0 on black)", device="ground")
       for i, side in enumerate(("left", "centre", "right"))]
    + [Reading(f"acc_{axis}", INT, 0, THRESHOLD_MAX, f"rt_acc({i})",
               f"accelerometer axis {axis} (`e_get_acc_filtered({i}, 1)`: 2048 no acceleration, "
               f"768 a g)")
       for i, axis in enumerate("xyz")]
    + [Reading("selector", INT, 0, 15, "rt_selector()",
               "the 16-position selector (`getselector()`)"),
       Reading("x", DISTANCE, -32768, 32767, "rt_x_mm()",
               "odometry: mm forward of the start pose (along its heading)"),
       Reading("y", DISTANCE, -32768, 32767, "rt_y_mm()",
               "odometry: mm to the left of the start pose"),
       Reading("heading", ANGLE, -180, 179, "rt_heading_deg()",
               "odometry: degrees turned since the start, counter-clockwise, -180..179"),
       Reading("message", INT, 0, MESSAGE_MAX, "rt_message()",
               "the value of the message `on message` received (0 before any)",
               device="messages"),
       Reading("message_bearing", ANGLE, -180, 179, "rt_message_bearing()",
               "where that message came from: degrees counter-clockwise from the robot's "
               "heading, -180..179, the direction of the sensor that received it best",
               device="messages"),
       Reading("message_range", DISTANCE, 0, 1000, "rt_message_range()",
               "how far its sender was: mm, estimated from the signal's strength",
               device="messages"),
       Reading("distance", DISTANCE, 0, 2000, "rt_distance()",
               "the time-of-flight sensor's distance ahead (mm; 2000: nothing in range)",
               device="tof"),
       Reading("seen", INT, 0, CAMERA_PIXELS, "rt_seen({choice})",
               f"the width in pixels (0..{CAMERA_PIXELS}) of the widest run of that colour in "
               f"the camera's line of {CAMERA_PIXELS} pixels over 60 degrees", device="camera",
               param=_COLOUR),
       Reading("bearing", ANGLE, -30, 30, "rt_bearing({choice})",
               "where the centre of that run is: degrees, 0 straight ahead, positive to the "
               "left (0 when the colour is not seen)", device="camera", param=_COLOUR)])
# by name; a reading of a choice once for each (`seen(red)`), as the checker
# names the Expr that reads it
STANDARD_READINGS = {r.name: r for r in READINGS if r.param is None}
STANDARD_READINGS.update(
    (f"{r.name}({c.name})", Reading(f"{r.name}({c.name})", r.kind, r.lo, r.hi,
                                    r.c.format(choice=c.c), r.doc, r.device))
    for r in READINGS if r.param is not None for c in r.param.choices.values)
CHOICE_READINGS = {r.name: r for r in READINGS if r.param is not None}

# The readings of several sensors as arrays: `ir[3]` is `ir3`; name ->
# (the readings in order, the runtime call that reads element i).
READING_ARRAYS = {
    "ir": (tuple(f"ir{i}" for i in range(SENSOR_COUNT)), "rt_ir"),
    "ambient": (tuple(f"ambient{i}" for i in range(SENSOR_COUNT)), "rt_ambient"),
    "mic": (tuple(f"mic{i}" for i in range(3)), "rt_mic"),
    "ground": (tuple(f"ground{i}" for i in range(3)), "rt_ground"),
    "acc": (tuple(f"acc_{axis}" for axis in "xyz"), "rt_acc"),
}
# Functions of a whole array (`min` and `max` of one argument too).
AGGREGATES = {
    "sum": (("a",), "the sum of the elements of the array `a`, exact up to 32 bits"),
    "argmin": (("a",), "the index of the smallest element of `a` (the first one of equals)"),
    "argmax": (("a",), "the index of the largest element of `a` (the first one of equals)"),
    "dot": (("a", "b"), "the sum of the products of the elements of `a` and `b` (arrays of "
            "one size), exact up to 32 bits"),
}

# The functions of expressions: name -> (arguments, doc).
FUNCTIONS = {
    "abs": (("x",), "the absolute value of `x`"),
    "min": (("a", "b"), "the smaller of `a` and `b`; `min(a)`: the smallest element of the "
            "array `a`"),
    "max": (("a", "b"), "the larger of `a` and `b`; `max(a)`: the largest element of the "
            "array `a`"),
    "clamp": (("x", "lo", "hi"), "`x` kept within `lo`..`hi`"),
    "random": (("lo", "hi"), "a random whole number in `lo`..`hi` (both included), new at each "
               "evaluation"),
    "atan2": (("y", "x"), "the angle (deg, -180..180, counter-clockwise from the x axis) of the "
              "point (`x`, `y`), two values of one kind; within 0.51 deg"),
    "hypot": (("x", "y"), "the length `sqrt(x * x + y * y)` of (`x`, `y`), two values of one "
              "kind, rounded"),
    "sqrt": (("v",), "the square root of a plain number, rounded (0 for `v` <= 0)"),
    "sin": (("a",), "the sine of the angle `a` in thousandths, -1000..1000, rounded"),
    "cos": (("a",), "the cosine of the angle `a` in thousandths, -1000..1000, rounded"),
}


def _reference_functions_defined_below():     # READINGS, FUNCTIONS: see the end
    pass


def signature(name: str, params) -> str:
    if not params:
        return name
    return f"{name}({', '.join(f'{p.name}: {kind_name(p)}' for p in params)})"


def kind_name(p: Param) -> str:
    """The kind of a parameter in words: `distance`, `LED`, ..."""
    return p.choices.what if p.choices is not None else p.kind


def describe_param(p: Param) -> str:
    """`speed` (speed, RANGE): a parameter in the reference's tables."""
    return f"`{p.name}` ({kind_name(p)}{', ' + p.range if p.range else ''})"


def bare_unit(p: Param) -> str:
    """What a bare number means for this parameter (`steps/s`, `mm`, ...)."""
    return NATURAL_UNIT.get(p.kind, "a plain number")


def reference_markdown() -> str:
    """The tables of docs/language.md section 3, from this table."""
    lines = ["### 3.1 Actions", "", "| action | parameters | does |", "|---|---|---|"]
    for a in ACTIONS:
        params = ", ".join(describe_param(p) for p in a.params) or "-"
        lines.append(f"| `{a.name}` | {params} | {a.doc} |")
    lines += ["", "### 3.2 Events", "", "| event | parameters | occurs |", "|---|---|---|"]
    for e in EVENTS:
        params = ("conditions: " + (e.conditions_doc or SENSOR_CONDITION_DOC) if e.params is None
                  else ", ".join(describe_param(p) for p in e.params) or "-")
        lines.append(f"| `{e.signature if e.head else e.name}` | {params} | {e.doc} |")
    lines += ["", "Rules headed `when`, `every` and `after` are written `when COND do ...`, "
              "`every D do ...`, `after D do ...` (section 2.10).",
              "", "### 3.3 Readings", "", "| reading | kind | interval | is |", "|---|---|---|---|"]
    lines += [f"| `{r.signature}` | {r.kind} | {r.lo}..{r.hi} | {r.doc} |" for r in READINGS]
    lines += ["", "### 3.4 Functions", "", "| function | gives |", "|---|---|"]
    lines += [f"| `{name}({', '.join(params)})` | {doc} |"
              for name, (params, doc) in {**FUNCTIONS, **AGGREGATES}.items()]
    lines += ["", "The readings of several sensors are arrays too: "
              + ", ".join(f"`{name}` (`{names[0]}`..`{names[-1]}`)"
                          for name, (names, _) in READING_ARRAYS.items()) + "."]
    for choices in CHOICES:
        lines += ["", f"The {choices.what} values"
                  + (f" (besides the numbers {choices.numbers[0]}..{choices.numbers[1]})"
                     if choices.numbers else "") + ":", "",
                  f"| {choices.what} | means | C |", "|---|---|---|"]
        lines += [f"| `{c.name}` | {c.doc} | `{c.c}` |" for c in choices.values]
    lines += ["", "Devices not every robot has: a name that needs one is an error [E070] when "
              "the target (`epuckc check/build --target`) lacks it.", "",
              "| device | names | " + " | ".join(TARGET_NAMES[t] for t in TARGET_DEVICES) + " |",
              "|---|---|" + "---|" * len(TARGET_DEVICES)]
    for device, what in DEVICES.items():
        names = [("on " + x.name if isinstance(x, EventSpec) else
                  x.signature if isinstance(x, Reading) else x.name)
                 for x in (*ACTIONS, *EVENTS, *READINGS) if x.device == device]
        lines.append(f"| {what} | {', '.join(f'`{n}`' for n in names)} | "
                     + " | ".join("yes" if device in TARGET_DEVICES[t] else "no"
                                  for t in TARGET_DEVICES) + " |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":      # python3 -m epuckc.stdlib > section 3's tables
    print(reference_markdown(), end="")
