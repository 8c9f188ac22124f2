/*
 * epuckrt.h - the event-driven runtime of Ochiai et al., "Event-driven
 * library for the autonomous robot e-Puck" (Shonan Institute of Technology),
 * as used by epuckc and by hand-written C.
 *
 * The paper's API (its table 1) is kept exactly; everything else is marked
 * "extension".  Units of the paper's parameter structs: speeds in motor steps
 * per second (signed, |speed| <= 1000), distances and radii in millimetres,
 * angles in degrees (positive turns left), times in milliseconds.
 *
 * Correct where int is 16 bits (dsPIC30F, XC16): anything that can pass 32767
 * is long.
 */
#ifndef EPUCKRT_H
#define EPUCKRT_H

#include <stddef.h>

/* Capacities of the two arrays (paper section 4.1).  Set with -D when the
 * runtime itself is compiled; the program does not depend on them. */
#ifndef MAX_ACTIONS
#define MAX_ACTIONS 32
#endif
#ifndef MAX_EVENTS
#define MAX_EVENTS 32
#endif

/* Default geometry used to convert the paper's millimetres and degrees into
 * motor steps.  Micrometres, so that integer arithmetic is exact enough. */
#ifndef EPUCK_WHEEL_CIRCUMFERENCE_UM
#define EPUCK_WHEEL_CIRCUMFERENCE_UM 128805L   /* pi * 41 mm */
#endif
#ifndef EPUCK_AXLE_UM
#define EPUCK_AXLE_UM 53000L
#endif
#ifndef EPUCK_STEPS_PER_REV
#define EPUCK_STEPS_PER_REV 1000L
#endif
#define EPUCK_MAX_SPEED 1000                   /* steps/s, the library clamps */
/* Largest geometry set_robot_geometry accepts (100 m wheels and axle, a
 * million steps per turn): within these the conversions cannot overflow. */
#define EPUCK_MAX_GEOMETRY_UM 100000000L
#define EPUCK_MAX_STEPS_PER_REV 1000000L

/* Function types.  The paper declares the registration arguments as void *;
 * ISO C cannot convert function pointers to void *, so they are typed. */
typedef void (*action_func)(void *action_param);
typedef void (*event_func)(void *event_param, void *status);

/* What an event function reports (its second argument points to one). */
typedef struct {
    int occurred;   /* set to 1 when the event happened at this poll */
    long memory;    /* private to the event function, kept between polls,
                       0 when the event is registered */
} event_status;

/* Paper figure 3: the elements of the two arrays. */
typedef struct {
    void (*action_function)(void *a);
    void *action_param;
} action;

typedef struct {
    void (*event_function)(void *a, void *b);
    void *event_param;
    int action_id;
    int valid_flag;
    /* extensions */
    int repeat_flag;        /* 1: stays armed after firing */
    event_status status;    /* passed as the event function's 2nd argument */
} event;

/* ---- Paper table 1 ---------------------------------------------------- */
/* Returns the new id (the array index), or -1 when the array is full or
 * action_func is NULL.  Slots are never reused: ids stay unique. */
int register_action(action_func f, void *action_param);
/* Returns the new id, armed, or -1 when the array is full, event_func is
 * NULL, or action_id is not a registered, uncancelled action. */
int register_event(event_func f, void *event_param, int action_id);
/* Unknown or already cancelled ids are ignored.  An event whose action was
 * cancelled still fires and disarms, but runs nothing. */
void cancel_action(int action_id);
void cancel_event(int event_id);
/* Polls until exit_main runs (paper figure 4).  Initialises the hardware on
 * first use, as the paper's figure 2 calls no init function. */
void mainloop(void);

/* ---- Extensions to table 1 -------------------------------------------- */
void set_event_repeat(int event_id, int repeat);   /* unknown ids ignored */
/* The robot's geometry, replacing the EPUCK_* defaults above for the
 * conversion of millimetres and degrees and for the host's odometry.
 * Ignored unless every value is positive and at most EPUCK_MAX_GEOMETRY_UM
 * (lengths) or EPUCK_MAX_STEPS_PER_REV.  epuckc calls it for a `robot { }`
 * block. */
void set_robot_geometry(long wheel_circumference_um, long axle_um, long steps_per_rev);
/* Names shown in the host harness's trace; ignored on the robot.  With
 * EPUCKRT_NO_NAMES defined (epuckc's robot builds; automatic with XC16)
 * they are macros that drop the name, so the labels are not even stored. */
void name_action(int action_id, const char *name);
void name_event(int event_id, const char *name);
/* The texts of the `count` steps of the sequence that action `action_id`
 * runs, for the trace ("step 2 of 3: start_curve(...)"); `names` is kept,
 * not copied.  Generated programs guard their arrays of step names with
 * EPUCKRT_NAMES_DROPPED. */
void name_steps(int action_id, const char *const *names, int count);
#if defined(EPUCKRT_NO_NAMES) || (defined(__XC16__) && !defined(EPUCKRT_NAMES))
#define EPUCKRT_NAMES_DROPPED 1
#define name_action(action_id, name) ((void)(action_id))
#define name_event(event_id, name) ((void)(event_id))
#define name_steps(action_id, names, count) ((void)(action_id))
#endif

/* ---- Extension: static registration ------------------------------------
 * A compiled program (epuckc's output) gives its actions and events as const
 * tables, which XC16 keeps in program memory, and registers them at once with
 * register_program; only what changes while it runs is in RAM (a few bits an
 * event, a long per event that keeps a memory).  The tables' ids are their
 * indices; register_action/register_event still work afterwards and their
 * ids follow the tables'.  mainloop polls the table's events first, in index
 * order, then the registered ones, with the same semantics (docs/runtime.md). */
typedef struct {
    action_func action_function;
    const void *action_param;   /* passed as the function's void *; the
                                   standard actions only read it */
} rt_action;

#define RT_REPEAT 1u            /* rt_event.flags: stays armed after firing */
/* rt_event.flags: how the rule holds the motors it commanded (docs/runtime.md,
 * "Holding the motors"); without either, until its action or sequence ends */
#define RT_HOLD_WHILE 2u        /* a condition (`when`, `sensor`, `ambient`):
                                   also while it stays true; implied by a NULL
                                   function, event_sensor and event_ambient */
#define RT_HOLD_GUARD 4u        /* a guarded periodic rule (`every D if G`):
                                   until a period whose guard is false */
/* rt_event.flags: when the event can occur, if nothing but time passes
 * (a host that simulates time polls in bulk what cannot: docs/runtime.md,
 * "Idle polls in bulk"); without any, at any poll.  The runtime knows the
 * standard event functions by themselves; these say it of a program's own
 * (a guard's, a `when`'s). */
#define RT_WAKE_ON_CHANGE 8u    /* only at a poll after the inputs or the
                                   program's state (its variables, a mode,
                                   the motion) changed; not occurring, it
                                   changes nothing but its memory */
#define RT_WAKE_AT_DEADLINE 16u /* as event_every: not before the clock
                                   reaches its memory - 1 (memory 0: at its
                                   next poll) */
#define RT_WAKE_AS_TIMER 32u    /* as event_timer on its event_param */
#define RT_NO_MEMORY (-1)       /* rt_event.memory: the function gets 0 */
#define RT_CONDITIONS_ALWAYS 0x100u   /* rt_program.sensors: see conditions */
#define RT_CONDITIONS_ON_CHANGE 0x200u    /* rt_program.sensors: see conditions */

typedef struct {
    event_func event_function;  /* NULL: the event is the program's compiled
                                   sensor condition (rt_program.conditions) */
    const void *event_param;
    int action_id;              /* an index in the program's actions */
    unsigned char flags;        /* RT_REPEAT, RT_HOLD_WHILE, RT_HOLD_GUARD,
                                   RT_WAKE_* */
    int memory;                 /* index in rt_program.memory of the status's
                                   memory, kept between polls (0 at the
                                   start), or RT_NO_MEMORY */
    int priority;               /* the rule's priority (set_event_priority's
                                   for a table event), 0 by default */
    int mode;                   /* its mode: 0 none, always armed; > 0 armed
                                   only while that mode is current */
} rt_event;

typedef struct {
    const rt_action *actions;
    int n_actions;
    const rt_event *events;
    int n_events;
    /* The compiled sensor conditions, or NULL: for each event k with a NULL
     * function, sets bit k % 16 of bits[k / 16] to its condition, from the
     * proximity readings ir[0..7] of this poll (the other bits are not
     * read).  Called at most once per poll, while the sensors are on; the
     * event occurs when its condition becomes true, as event_sensor's. */
    void (*conditions)(const int *ir, unsigned *bits);
    unsigned sensors;           /* bit n: conditions reads ir[n]; and
                                   RT_CONDITIONS_ALWAYS: some conditions are
                                   not the sensors' (the rule language's
                                   `when`): conditions is then called at
                                   every poll, with ir NULL while the
                                   sensors are off (the sensor conditions
                                   are then false); RT_CONDITIONS_ON_CHANGE
                                   with it: they read nothing but the
                                   inputs and the program's variables (no
                                   odometry, no random numbers) */
    unsigned *state;            /* RAM, RT_STATE_WORDS(n_actions, n_events) */
    long *memory;               /* RAM, one per memory index used, or NULL */
    /* The events' ids (n_events of them) by priority, highest first, in id
     * order within a priority, or NULL: with priorities, mainloop then
     * polls the table in one pass over it instead of one pass per
     * priority level. */
    const int *order;
} rt_program;

/* The state is bit planes of 16-bit words (unsigned is at least 16 bits). */
#define RT_WORDS(n) (((n) + 15) / 16)
#define RT_STATE_WORDS(n_actions, n_events) (RT_WORDS(n_actions) + 7 * RT_WORDS(n_events))

/* Registers a program's tables (before mainloop; tables registered by an
 * action are polled from the next poll): its actions get ids
 * 0..n_actions-1, its events 0..n_events-1, all armed.  Returns 0, or -1 (and registers
 * nothing) when a program or anything else was registered before, or a
 * table is inconsistent (an action_id out of range, a NULL action function,
 * a NULL event function without conditions, a NULL state, a negative
 * mode, an order that is not the events by priority then id). */
int register_program(const rt_program *program);

/* ---- Paper table 2: standard actions and their parameters -------------- */
/* The paper's structs, exactly (figure 2 writes `{250, 100}`). */
typedef struct {
    int speed;      /* steps/s; negative drives backwards */
    int distance;   /* mm; negative drives backwards */
} param_start_straight;

typedef struct {
    int radius;     /* mm, from the robot's centre to the circle's centre, >= 0 */
    int degrees;    /* arc angle; positive turns left, negative right */
    int speed;      /* steps/s of the outer wheel; negative drives backwards */
} param_start_curve;

void action_start_straight(void *param);   /* param_start_straight * */
void action_start_curve(void *param);      /* param_start_curve * */
void action_stop_motor(void *param);       /* NULL */
void action_set_timer(void *param);        /* NULL: (re)start the timer at 0 */
void action_reset_timer(void *param);      /* NULL: stop the timer */
void action_start_sensor(void *param);     /* NULL: start proximity polling */
void action_stop_sensor(void *param);      /* NULL */
void action_exit_main(void *param);        /* NULL: mainloop returns */
/* the paper's short spellings (figure 2) */
void start_straight(void *param);
void start_curve(void *param);
void stop_motor(void *param);
void set_timer(void *param);
void reset_timer(void *param);
void start_sensor(void *param);
void stop_sensor(void *param);
void exit_main(void *param);

/* Extension: motions given in exact motor steps, as epuckc compiles them
 * (no conversion of millimetres or degrees, so nothing depends on the
 * geometry at run time).  The actions only read their struct, so it may be
 * const. */
typedef struct {
    int speed;      /* steps/s; negative drives backwards */
    int steps;      /* motor steps each wheel turns; negative drives backwards;
                       0 is a motion of no steps */
} param_straight_steps;

typedef struct {
    int left_speed;     /* steps/s of each wheel, signed */
    int right_speed;
    int steps;          /* steps the faster wheel turns (either wheel when
                           both are as fast), >= 0 */
} param_curve_steps;

void action_straight_steps(void *param);   /* param_straight_steps * */
void action_curve_steps(void *param);      /* param_curve_steps * */
void straight_steps(void *param);
void curve_steps(void *param);

/* Extension: a sequence of steps ("A then B then C").  Each step starts when
 * the motion started by the step before it has finished, at once if that
 * step started no motion. */
typedef struct {
    const action *steps;   /* run in order; {function, param} pairs */
    int count;
} param_sequence;
void action_run_sequence(void *param);     /* param_sequence * */
void run_sequence(void *param);

/* ---- Paper table 3: standard events and their parameters --------------- */
#define SENSOR_OFF (-1)
typedef struct {
    int sensef[8];        /* threshold per IR sensor 0..7 (0..4095), or
                             SENSOR_OFF for a sensor not watched */
    unsigned char below;  /* extension: bit n set: sensor n fires when its
                             reading < sensef[n]; clear: when > sensef[n] */
} param_event_sensor;

typedef struct {
    long time;            /* ms since set_timer */
} param_event_timer;

typedef param_event_sensor param_sensor;
typedef param_event_timer param_timer;

void event_sensor(void *param, void *status);      /* param_event_sensor * */
void event_timer(void *param, void *status);       /* param_event_timer * */
void event_immediate(void *param, void *status);   /* NULL */
void event_stop_motor(void *param, void *status);  /* NULL */
/* short spellings; the stop_motor event keeps its long name because
 * stop_motor is the action */
void sensor(void *param, void *status);
void timer(void *param, void *status);
void immediate(void *param, void *status);

/* ---- Extension: priorities and modes ------------------------------------- */
/* Priority of an event's rule (default 0).  Within a poll, events are
 * polled and their actions run highest priority first, then in index
 * order.  The motors belong to the event whose action started the motion
 * in progress: while it runs, motor commands (start_straight, start_curve,
 * stop_motor) from the action of an event of lower priority are suppressed
 * (and traced), and so is a run_sequence that would replace a sequence in
 * progress of an event of higher priority.  All priorities equal: the
 * paper's behaviour.  Unknown ids ignored, and so are a program's table
 * ids (register_program): a table event's priority is its rt_event's. */
void set_event_priority(int event_id, int priority);
/* The mode an event belongs to: 0 (the default) none, always armed; a
 * positive number: polled only while that mode is the current one.  As
 * set_event_priority, for registered events only (a table event's mode is
 * its rt_event's). */
void set_event_mode(int event_id, int mode);
/* Makes `mode` (> 0) the current mode.  Its events are re-armed with their
 * state reset as at registration (one-shot ones that fired and disarmed
 * ones included; not those cancelled with cancel_event); no event of any
 * mode fires in the rest of this poll.  A sequence started by an event of
 * the mode left is abandoned and a motion it owns stopped (without a
 * stop_motor event).  Before
 * mainloop: sets the initial mode (traced when mainloop starts). */
void enter_mode(int mode);
/* Disarms an event until its mode is entered again (cancel_event is
 * forever).  Unknown ids ignored. */
void disarm_event(int event_id);
/* The name of a mode in the host trace; ignored on the robot, and a macro
 * that drops the name with EPUCKRT_NO_NAMES (as name_action). */
void name_mode(int mode, const char *name);
#if defined(EPUCKRT_NO_NAMES) || (defined(__XC16__) && !defined(EPUCKRT_NAMES))
#define name_mode(mode, name) ((void)(mode))
#endif

typedef struct {
    int mode;               /* > 0 */
} param_enter_mode;
void action_enter_mode(void *param);         /* param_enter_mode * */
/* Occurs at the first poll after its mode was entered (an event in no mode:
 * at the first poll, like immediate). */
void event_enter_mode(void *param, void *status);   /* NULL */

/* ---- Extension: the rest of the robot -------------------------------------- */
/* LEDs (e_set_led, e_set_body_led, e_set_front_led). */
#define SET_LED_ALL 8       /* led: 0..7 one ring LED, or one of these */
#define SET_LED_BODY 9
#define SET_LED_FRONT 10
#define SET_LED_OFF 0       /* value */
#define SET_LED_ON 1
#define SET_LED_TOGGLE 2
typedef struct {
    int led;
    int value;
} param_set_led;
void action_set_led(void *param);            /* param_set_led * */
/* A number on the ring: LEDs 0..count-1 on and the others off (count
 * clamped to 0..8), or LED k on where bit k of bits is 1 (bits 0..255). */
typedef struct {
    int count;
} param_led_ring;
void action_led_ring(void *param);           /* param_led_ring * */
typedef struct {
    int bits;
} param_led_bits;
void action_led_bits(void *param);           /* param_led_bits * */
/* The e-puck2's RGB LEDs (rt_rgb.c, over the firmware's set_rgb_led): led
 * 0..3 (LED2, LED4, LED6, LED8), red, green, blue in percent (clamped to
 * 0..100). */
typedef struct {
    int led;
    int red;
    int green;
    int blue;
} param_led_rgb;
void action_led_rgb(void *param);            /* param_led_rgb * */

/* The five samples of the library (e_play_sound; e_init_sound at the first
 * play). */
#define SOUND_HAA 0
#define SOUND_SPAAH 1
#define SOUND_OUAH 2
#define SOUND_YAOUH 3
#define SOUND_WOUAAAAAAAAH 4
typedef struct {
    int sound;
} param_play_sound;
void action_play_sound(void *param);         /* param_play_sound * */

/* Occurs when the selector (getselector(), 0..15) is at `position` at the
 * event's first poll, or moves to it. */
typedef struct {
    int position;
} param_event_selector;
void event_selector(void *param, void *status);

/* Occurs when some microphone's volume (e_get_micro_volume) goes over
 * `volume` (rising edge). */
typedef struct {
    int volume;
} param_event_clap;
void event_clap(void *param, void *status);

/* Accelerometer (e_get_acc, raw units).  tap: some axis changed by more
 * than `threshold` since the previous poll; tilt: x or y differs from its
 * reading at the first poll by more than `threshold`.  Both on the rising
 * edge. */
typedef struct {
    int threshold;
} param_event_accel;
void event_tap(void *param, void *status);
void event_tilt(void *param, void *status);

/* Occurs when a key of the RC5 remote control is pressed (e_get_check
 * toggled) and it is `key` (e_get_data: 0..9 digits, 12 standby, 13 mute,
 * 16/17 volume up/down, 32/33 channel up/down). */
typedef struct {
    int key;
} param_event_remote;
void event_remote(void *param, void *status);

/* Like event_sensor, on the ambient light readings (e_get_ambient_light);
 * works without start_sensor. */
void event_ambient(void *param, void *status);   /* param_event_sensor * */

/* ---- Extension: the rule language's state and continuous control ---------
 * What epuckc's expressions, variables, `when`, `every`, `after`,
 * `set_speed` and `wait` compile to (runtime_c/rt_lang.c).  Inside an
 * expression a value is exact while it fits 32 bits: generated C computes
 * in int where the checker proved the result fits 16 bits, in long where it
 * fits 32, and calls these functions where it may not: each saturates at
 * -2147483648..2147483647 (never overflows, on any int or long width).
 * Division truncates, and division or % by 0 gives 0.  A value is stored
 * (a variable, an argument) saturated to 16 bits: rt_sat16. */
#define RT_INT_MIN (-32767 - 1)
#define RT_INT_MAX 32767
#define RT_LONG_MIN (-2147483647L - 1)
#define RT_LONG_MAX 2147483647L
int rt_sat16(long v);
long rt_add(long a, long b);
long rt_sub(long a, long b);
long rt_mul(long a, long b);
long rt_div(long a, long b);
long rt_mod(long a, long b);
/* the language's `<<` and `>>` of a 16-bit value, for every count */
int rt_shl(int a, int n);
int rt_shr(int a, int n);
long rt_neg(long a);
long rt_abs(long a);
long rt_min(long a, long b);
long rt_max(long a, long b);
long rt_clamp(long x, long lo, long hi);    /* lo when x < lo, else hi when x > hi */
/* Integer math, no floating point, the same on every target (rt_math.c;
 * docs/runtime.md gives each one's error bound): atan2 in whole degrees
 * -180..180 counter-clockwise (atan2(0, 0) is 0), hypot and sqrt rounded to
 * nearest (sqrt of v <= 0 is 0), sin and cos of whole degrees in thousandths
 * -1000..1000. */
/* Arrays: an index outside 0..n-1 is taken as the nearest end (never out
 * of bounds); the index (the first of equals) of the smallest or largest of
 * n values. */
int rt_index(long i, int n);
int rt_argmin(const long *values, int n);
int rt_argmax(const long *values, int n);
int rt_argmin_int(const int *values, int n);      /* the same over ints */
int rt_argmax_int(const int *values, int n);
int rt_atan2(long y, long x);
long rt_hypot(long x, long y);
long rt_sqrt(long v);
int rt_sin(long deg);
int rt_cos(long deg);
/* A uniform random whole number in lo..hi (lo when hi < lo), from a 32-bit
 * generator that gives the same sequence on every target for a seed. */
int rt_random(int lo, int hi);
void rt_seed(unsigned long seed);
/* Readings, each read from the library at most once per poll (proximity
 * readings need no start_sensor): proximity 0..7, ambient light 0..7,
 * microphone volume 0..2, accelerometer axis 0..2, selector 0..15; the
 * odometry of the wheels' steps since the start pose: x forward and y to
 * the left in mm, heading in degrees counter-clockwise, -180..179. */
int rt_ir(int sensor);
/* The proximity readings of this poll, the sensors of `mask` (bit n:
 * sensor n) read if they were not yet: a `when` rule's conditions read
 * them with one call. */
const int *rt_proximity(unsigned mask);
int rt_ambient(int sensor);
int rt_mic(int micro);
int rt_acc(int axis);
int rt_selector(void);
int rt_x_mm(void);
int rt_y_mm(void);
int rt_heading_deg(void);
/* The odometry is kept only for a program that reads it: it calls this
 * before mainloop (its integer arithmetic costs every poll). */
void rt_use_odometry(void);
/* `NAME = value`: stores it in *var and traces the change (variable number
 * id, named with name_var). */
void rt_assign(int *var, int id, int value);
/* `fill(a, v)`: every element of the variable array a (count elements,
 * the first traced as variable number id) gets value, each traced where it
 * changes. */
typedef struct {
    int *array;
    int id;
    int count;
    int value;
} param_fill;
void action_fill(void *param);               /* param_fill * */
void name_var(int id, const char *name);
#if defined(EPUCKRT_NO_NAMES) || (defined(__XC16__) && !defined(EPUCKRT_NAMES))
#define name_var(id, name) ((void)(id))
#endif
/* The event function of a `when` rule calls rt_when with its condition: it
 * occurs when the condition becomes true (status->memory: the condition at
 * the previous poll, 0 when the rule is armed).  A guard (`if COND`) is
 * evaluated only when the rule's event occurred (rt_occurred), and rt_guard
 * with a false guard makes the event not occur (and ends the hold of an
 * RT_HOLD_GUARD event on the motors: its guard was false at a period). */
void rt_when(void *status, int condition);
int rt_occurred(void *status);          /* the event occurred in this poll */
void rt_guard(void *status, int guard);
/* `every` and `after`: their own timers, from when the rule is armed
 * (registration or its mode's entry); status->memory holds the next firing
 * time + 1 (0: just armed). */
typedef struct {
    long period;    /* ms, > 0 */
} param_event_every;
void event_every(void *param, void *status);
void event_after(void *param, void *status);
/* set_speed: the wheels at these speeds (clamped to EPUCK_MAX_SPEED) until
 * the next motor command; a motion without an end, arbitrated as the
 * others (a `then` sequence goes on at once). */
typedef struct {
    int left;
    int right;
} param_set_speed;
void action_set_speed(void *param);
/* wait: a step of a sequence; the next step starts `time` ms later (and
 * not before the motion in progress has ended).  Outside a sequence it
 * does nothing. */
typedef struct {
    long time;
} param_wait;
void action_wait(void *param);

/* ---- Extension: IR messages between robots (runtime_c/rt_comm.c) --------
 * Over libIrcom's API (ircomSend, ircomPopMessage: the e-puck2 firmware's
 * src/ircom; the host's stub and Enki provide the same).  send: broadcasts
 * the low 8 bits of `value`; while a message is on the air the newest
 * value waits and goes when it is free (one waits; a later send replaces
 * it).  Messages received are queued by the runtime (RT_MESSAGE_QUEUE; a
 * message that comes when it is full drops the oldest); event_message
 * occurs at a poll when it takes one from the queue (one per poll), and
 * until it takes the next rt_message* read that one: its value 0..255,
 * where it came from (degrees counter-clockwise from the heading,
 * -180..179, the direction of the sensor that received it) and how far
 * its sender was (mm, estimated). */
#define RT_MESSAGE_QUEUE 8
typedef struct {
    int value;
} param_send;
void action_send(void *param);
void event_message(void *param, void *status);
int rt_message(void);
int rt_message_bearing(void);
int rt_message_range(void);
/* Messages dropped because the queue was full, since the start. */
unsigned long rt_messages_dropped(void);

/* ---- Extension: the e-puck2's time-of-flight sensor (runtime_c/rt_tof.c) -
 * rt_distance: mm ahead (VL53L0X_get_dist_mm), RT_DISTANCE_MAX when
 * nothing is in range; the sensor is started at the first reading. */
#define RT_DISTANCE_MAX 2000
int rt_distance(void);

/* ---- Extension: GCtronic's ground-sensor module (runtime_c/rt_ground.c) --
 * rt_ground: the light the floor reflects under sensor 0 (left), 1 (centre)
 * or 2 (right) (get_ground_prox), 0..RT_GROUND_MAX; the module is started
 * at the first reading. */
#define RT_GROUND_MAX 4095
int rt_ground(int sensor);

/* ---- Extension: the colour camera (runtime_c/rt_camera.c) ----------------
 * One subsampled row of RT_CAMERA_PIXELS pixels over 60 degrees, read at
 * most once a poll.  rt_seen: the width in pixels of the widest run of
 * `colour` in it; rt_bearing: the degrees of that run's centre, 0 straight
 * ahead, positive to the left (0 when not seen).  rt_colour: the one
 * classifier of 8-bit r, g, b (docs/runtime.md). */
#define RT_CAMERA_PIXELS 60
#define RT_NO_COLOUR 0
#define RT_RED 1
#define RT_YELLOW 2
#define RT_GREEN 3
#define RT_CYAN 4
#define RT_BLUE 5
#define RT_MAGENTA 6
int rt_seen(int colour);
int rt_bearing(int colour);
int rt_colour(int r, int g, int b);

#endif /* EPUCKRT_H */
