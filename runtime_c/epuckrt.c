/*
 * epuckrt.c - the core of the event-driven runtime (Ochiai et al., sections
 * 3-4): the two fixed arrays, registration, the polling main loop (figure 4),
 * the standard actions and events, motion control, the sequencer and the
 * millisecond clock.
 *
 * The hardware is reached only through the e-puck library API (the real
 * library on the robot, host/epuck_stub.c on a PC) and rt_platform.h.
 * Written for 16-bit int: every count of steps or milliseconds that can pass
 * 32767 is long; products that can pass 2^31 are long long.
 * docs/runtime.md describes the semantics implemented here.
 */
#include <stddef.h>

#include "epuckrt.h"
#include "rt_platform.h"

#include "motor_led/e_init_port.h"
#include "motor_led/advance_one_timer/e_motors.h"
#include "motor_led/advance_one_timer/e_agenda.h"
#include "a_d/advance_ad_scan/e_prox.h"
#include "a_d/advance_ad_scan/e_ad_conv.h"
#include "a_d/advance_ad_scan/e_micro.h"
#include "a_d/advance_ad_scan/e_acc.h"
#include "motor_led/e_led.h"
#include "motor_led/advance_one_timer/e_remote_control.h"
#include "codec/e_sound.h"
#include "utility/utility.h"

#if MAX_ACTIONS < 1 || MAX_EVENTS < 1
#error "MAX_ACTIONS and MAX_EVENTS must be at least 1"
#endif

/* ---- the two arrays (paper 4.1): ids are indices, slots never reused ---- */
static action actions[MAX_ACTIONS];
static event events[MAX_EVENTS];
static int n_actions;   /* slots used so far, cancelled ones included */
static int n_events;

/* Extension state of each event of the arrays, kept beside the paper's
 * struct: its priority (set_event_priority) and mode (set_event_mode, 0:
 * none).  A table event's are in its rt_event. */
static struct {
    int priority;
    int mode;
} event_ext[MAX_EVENTS];
/* 1 once any event has a priority or a mode: the walk then goes by
 * priority levels (poll_ranked); 0: every priority is 0 and there are no
 * modes, and the walk is the plain one in id order. */
static int ranked;

/* ---- the static tables (register_program) ----------------------------------
 * Ids 0..s_actions-1 and 0..s_events-1 are the program's table entries; the
 * arrays' ids follow (array index + s_actions / s_events).  The program's
 * RAM state is six bit planes of 16-bit words, bit k % 16 of word k / 16
 * for entry k: */
static const rt_program *prog;      /* NULL: none registered */
static int s_actions, s_events;     /* its table sizes, 0 without one */
static unsigned s_words;            /* RT_WORDS(s_events) */
static unsigned *action_off;        /* the action was cancelled */
static unsigned *ev_armed;          /* the event is armed (valid_flag) */
static unsigned *ev_repeat;         /* repeat_flag */
static unsigned *ev_latch;          /* compiled condition at its last poll */
static unsigned *ev_now;            /* compiled conditions of this poll */
static unsigned *ev_compiled;       /* the event is a compiled condition */
static unsigned *ev_dead;           /* cancel_event: not re-armed by enter_mode */
static int conditions_valid;        /* ev_now holds this poll's conditions */

#define WORD_MASK 0xFFFFu
#define BIT_OF(k) (1u << ((unsigned)(k) & 15u))
#define BIT_GET(plane, k) (((plane)[(k) >> 4] & BIT_OF(k)) != 0)
#define BIT_SET(plane, k) ((plane)[(k) >> 4] |= BIT_OF(k))
#define BIT_CLEAR(plane, k) ((plane)[(k) >> 4] &= ~BIT_OF(k))

/* An event's priority and mode, by id (table or array). */
static int event_priority(int id)
{
    return id < s_events ? prog->events[id].priority : event_ext[id - s_events].priority;
}

static int event_mode(int id)
{
    return id < s_events ? prog->events[id].mode : event_ext[id - s_events].mode;
}

/* ---- millisecond clock ---------------------------------------------------
 * A 1 ms e-puck agenda (cycle 10 x 0.1 ms) counts; it runs in the Timer2
 * interrupt on the robot, hence volatile.  Unsigned so that the increment
 * never overflows a signed type. */
static volatile unsigned long ms_ticks;

static void clock_tick(void)
{
    ms_ticks++;
}

long rt_millis(void)
{
    unsigned long a, b;
    /* A 32-bit read is two 16-bit reads on the dsPIC: the interrupt may
     * change the value in between, so read until two reads agree. */
    do {
        a = ms_ticks;
        b = ms_ticks;
    } while (a != b);
    /* 30 bits: callers may add 1 and subtract without overflowing a 32-bit
     * long.  Wraps after 12.4 days. */
    return (long)(a & 0x3FFFFFFFUL);
}

static int initialised;
static int remote_wanted;       /* an event_remote was registered */
static int remote_started;      /* e_init_remote_control() has run */
static int accel_wanted;        /* an event_tap or event_tilt was registered */

static void remote_start(void)
{
    if (remote_wanted && initialised && !remote_started) {
        remote_started = 1;
        e_init_remote_control();
    }
}

static void rt_init(void)
{
    if (initialised)
        return;
    initialised = 1;
    /* the agenda variant's start-up order, then the A/D scan (Webots'
     * e-puck cross-compilation layer does the same) */
    e_init_port();
    e_start_agendas_processing();
    e_init_motors();
    e_init_ad_scan(ALL_ADC);
    (void)e_activate_agenda(clock_tick, 10);
    rt_platform_init();
    remote_start();     /* only for programs that use the remote control */
}

/* ---- state of the standard actions and events --------------------------- */

static int exit_requested;      /* set by exit_main, checked by mainloop */
static int current_action_id = -1;  /* the action being run by mainloop */
static int current_event_id = -1;   /* the event whose action runs (-1: none) */

/* Modes: the current one (0: none), entries so far, and whether a mode was
 * entered during this poll's walk (then no mode's event fires until the
 * next poll). */
static int current_mode;
static int mode_entered_in_poll;
static int mode_trace_pending;      /* enter_mode before mainloop */

/* Timer (set_timer / reset_timer / event_timer). */
static int timer_running;
static long timer_start;        /* rt_millis() at set_timer */

/* Proximity polling (start_sensor / stop_sensor); off at start. */
static int sensors_on;

/* The proximity readings, read once per poll: bit n of prox_valid says
 * prox[n] was read in this poll (cleared at the start of each poll). */
static int prox[8];
static unsigned prox_valid;

static void read_prox(unsigned mask)
{
    unsigned n, todo = mask & ~prox_valid & 0xFFu;

    if (todo == 0)
        return;
    for (n = 0; todo != 0; n++, todo >>= 1) {
        if (todo & 1u)
            prox[n] = e_get_prox(n);
    }
    prox_valid |= mask & 0xFFu;
}

/* Motion: at most one at a time.  Progress is measured from the 16-bit step
 * counters at each poll and accumulated in long. */
enum { WATCH_BOTH, WATCH_LEFT, WATCH_RIGHT };
static struct {
    int active;     /* 1 from its start until its target is reached */
    int watch;      /* which wheel's progress ends it (BOTH: the larger) */
    long target;    /* steps, >= 0 */
    long left;      /* signed steps turned since the start */
    long right;
    int owner;      /* event whose action started it (-1: none); the
                       motors are its until the motion ends */
} motion = { 0, 0, 0, 0, 0, -1 };
static int last_left;           /* raw counters at the previous poll */
static int last_right;
static unsigned motion_starts;  /* incremented at every motion start */

/* stop_motor event latch: see event_stop_motor. */
static int seen_moving;
static int stop_sample;         /* the stop_motor condition of this poll */

/* Sequencer: the sequence in progress, if any. */
static const param_sequence *seq;   /* NULL: none */
static int seq_next;                /* index of the next step to run */
static int seq_action_id;           /* id used in the trace of its steps */
static int seq_event_id;            /* the event whose action started it */
static int seq_waiting;             /* a step's motion is under way */
static unsigned seq_generation;     /* changes when a sequence replaces one */
static int in_step;                 /* > 0 while a step's function runs */

/* ---- small arithmetic helpers ------------------------------------------- */

static long abs_l(long v)
{
    return v < 0 ? -v : v;
}

static int clamp_speed(long s)
{
    if (s > EPUCK_MAX_SPEED)
        return EPUCK_MAX_SPEED;
    if (s < -EPUCK_MAX_SPEED)
        return -EPUCK_MAX_SPEED;
    return (int)s;
}

/* n / d rounded half away from zero; d > 0. */
static long long div_round(long long n, long long d)
{
    if (n >= 0)
        return (n + d / 2) / d;
    return -((-n + d / 2) / d);
}

/* Signed progress of a 16-bit wrapping counter between two reads, portable
 * to any int width >= 16 (no signed overflow). */
static long wheel_delta(int now, int last)
{
    unsigned d = ((unsigned)now - (unsigned)last) & 0xFFFFu;
    return d >= 0x8000u ? (long)d - 0x10000L : (long)d;
}

/* ---- paper table 1 -------------------------------------------------------- */

static int action_ok(int id)
{
    if (id >= 0 && id < s_actions)
        return !BIT_GET(action_off, id);
    id -= s_actions;
    return id >= 0 && id < n_actions && actions[id].action_function != NULL;
}

/* A registered event that was not cancelled (it may have fired and disarmed). */
static int event_ok(int id)
{
    if (id >= 0 && id < s_events)
        return 1;   /* table events stay registered: cancel_event disarms them */
    id -= s_events;
    return id >= 0 && id < n_events && events[id].event_function != NULL;
}

int register_action(action_func f, void *action_param)
{
    int id;
    if (f == NULL || n_actions >= MAX_ACTIONS)
        return -1;
    id = n_actions++;
    actions[id].action_function = f;
    actions[id].action_param = action_param;
    rt_new_action(s_actions + id, f);
    return s_actions + id;
}

int register_event(event_func f, void *event_param, int action_id)
{
    int id;
    event *e;
    if (f == NULL || n_events >= MAX_EVENTS || !action_ok(action_id))
        return -1;
    id = n_events++;
    e = &events[id];
    e->event_function = f;
    e->event_param = event_param;
    e->action_id = action_id;
    e->valid_flag = 1;
    e->repeat_flag = 0;
    e->status.occurred = 0;
    e->status.memory = 0;
    event_ext[id].priority = 0;
    event_ext[id].mode = 0;
    if (f == event_remote) {
        remote_wanted = 1;
        remote_start();
    }
    if (f == event_tap || f == event_tilt)
        accel_wanted = 1;
    rt_new_event(s_events + id, f);
    return s_events + id;
}

void cancel_action(int action_id)
{
    if (!action_ok(action_id))
        return;
    if (action_id < s_actions) {
        BIT_SET(action_off, action_id);
        return;
    }
    /* A NULL function marks the slot cancelled; it is never reused. */
    action_id -= s_actions;
    actions[action_id].action_function = NULL;
    actions[action_id].action_param = NULL;
}

void cancel_event(int event_id)
{
    if (!event_ok(event_id))
        return;
    if (event_id < s_events) {
        BIT_CLEAR(ev_armed, event_id);
        BIT_SET(ev_dead, event_id);
        return;
    }
    event_id -= s_events;
    events[event_id].valid_flag = 0;
    events[event_id].event_function = NULL;
}

void set_event_repeat(int event_id, int repeat)
{
    if (!event_ok(event_id))
        return;
    if (event_id < s_events) {
        if (repeat)
            BIT_SET(ev_repeat, event_id);
        else
            BIT_CLEAR(ev_repeat, event_id);
        return;
    }
    events[event_id - s_events].repeat_flag = repeat != 0;
}

/* Priorities and modes of the arrays' events; a table event's are in its
 * rt_event (these ignore table ids). */
void set_event_priority(int event_id, int priority)
{
    if (event_id >= s_events && event_ok(event_id)) {
        event_ext[event_id - s_events].priority = priority;
        if (priority != 0)
            ranked = 1;
    }
}

void set_event_mode(int event_id, int mode)
{
    if (event_id >= s_events && event_ok(event_id) && mode >= 0) {
        event_ext[event_id - s_events].mode = mode;
        if (mode != 0)
            ranked = 1;
    }
}

void disarm_event(int event_id)
{
    if (!event_ok(event_id))
        return;
    if (event_id < s_events)
        BIT_CLEAR(ev_armed, event_id);
    else
        events[event_id - s_events].valid_flag = 0;
}

void (name_mode)(int mode, const char *name)
{
    if (mode > 0)
        rt_name_mode(mode, name);
}

/* Parenthesised: epuckrt.h may define them as macros (EPUCKRT_NO_NAMES). */
void (name_action)(int action_id, const char *name)
{
    if (action_id >= 0 && action_id < s_actions + n_actions)
        rt_name_action(action_id, name);
}

void (name_event)(int event_id, const char *name)
{
    if (event_id >= 0 && event_id < s_events + n_events)
        rt_name_event(event_id, name);
}

int register_program(const rt_program *p)
{
    int k, words_a, words_e;

    if (p == NULL || prog != NULL || n_actions != 0 || n_events != 0
            || p->n_actions < 0 || p->n_events < 0 || p->state == NULL
            || (p->n_actions > 0 && p->actions == NULL)
            || (p->n_events > 0 && p->events == NULL))
        return -1;
    for (k = 0; k < p->n_actions; k++) {
        if (p->actions[k].action_function == NULL)
            return -1;
    }
    for (k = 0; k < p->n_events; k++) {
        const rt_event *e = &p->events[k];
        if (e->action_id < 0 || e->action_id >= p->n_actions
                || (e->event_function == NULL && p->conditions == NULL)
                || (e->memory != RT_NO_MEMORY && (e->memory < 0 || p->memory == NULL))
                || e->mode < 0)
            return -1;
    }
    /* the order, strictly increasing by (priority downwards, id): then it
     * holds every event once */
    for (k = 0; p->order != NULL && k < p->n_events; k++) {
        int id = p->order[k], before;
        if (id < 0 || id >= p->n_events)
            return -1;
        if (k > 0) {
            before = p->order[k - 1];
            if (p->events[before].priority < p->events[id].priority
                    || (p->events[before].priority == p->events[id].priority && before >= id))
                return -1;
        }
    }
    words_a = RT_WORDS(p->n_actions);
    words_e = RT_WORDS(p->n_events);
    action_off = p->state;
    ev_armed = action_off + words_a;
    ev_repeat = ev_armed + words_e;
    ev_latch = ev_repeat + words_e;
    ev_now = ev_latch + words_e;
    ev_compiled = ev_now + words_e;
    ev_dead = ev_compiled + words_e;
    for (k = 0; k < words_a + 6 * words_e; k++)
        p->state[k] = 0;
    for (k = 0; k < p->n_actions; k++)
        rt_new_action(k, p->actions[k].action_function);
    for (k = 0; k < p->n_events; k++) {
        const rt_event *e = &p->events[k];
        BIT_SET(ev_armed, k);
        if (e->flags & RT_REPEAT)
            BIT_SET(ev_repeat, k);
        if (e->event_function == NULL)
            BIT_SET(ev_compiled, k);
        if (e->memory != RT_NO_MEMORY)
            p->memory[e->memory] = 0;
        if (e->priority != 0 || e->mode != 0)
            ranked = 1;
        if (e->event_function == event_remote)
            remote_wanted = 1;
        if (e->event_function == event_tap || e->event_function == event_tilt)
            accel_wanted = 1;
        rt_new_event(k, e->event_function);
    }
    remote_start();
    prog = p;
    s_actions = p->n_actions;
    s_events = p->n_events;
    s_words = (unsigned)words_e;
    return 0;
}

/* ---- motion control -------------------------------------------------------- */

static void sequence_outside_command(void);

/* Motor arbitration: 1 when the running action may not command the motors
 * because the motion in progress belongs to an event of higher priority
 * (the command is then traced as suppressed and not carried out).  Commands
 * from outside any event's action (main, before mainloop) always pass. */
static int motors_refused(const char *command)
{
    int owner = motion.owner, me = current_event_id;

    if (!motion.active || owner < 0 || me < 0 || owner == me)
        return 0;
    if (event_priority(me) >= event_priority(owner))
        return 0;
    rt_trace_suppressed(me, event_priority(me), owner, event_priority(owner),
                        command);
    return 1;
}

static void wheels(int left, int right)
{
    e_set_speed_left(left);
    e_set_speed_right(right);
}

/* Start a motion (replacing the current one): wheel speeds, and the number
 * of steps of the watched wheel after which it ends. */
static void motion_begin(int left, int right, long target, int watch)
{
    int watched_speed;

    sequence_outside_command();
    if (watch == WATCH_LEFT)
        watched_speed = left;
    else if (watch == WATCH_RIGHT)
        watched_speed = right;
    else
        watched_speed = left != 0 ? left : right;
    if (watched_speed == 0 || target <= 0) {
        /* nothing to drive: the motion ends at the next poll */
        target = 0;
        left = 0;
        right = 0;
    }
    motion.active = 1;
    motion.owner = current_event_id;
    motion.watch = watch;
    motion.target = target;
    motion.left = 0;
    motion.right = 0;
    wheels(left, right);
    /* steps made since this poll's measurement belong to the replaced motion */
    last_left = e_get_steps_left();
    last_right = e_get_steps_right();
    seen_moving = 1;
    motion_starts++;
}

/* Phase (2) of a poll: measure the wheels, end the motion at its target. */
static void motion_update(void)
{
    int l = e_get_steps_left();
    int r = e_get_steps_right();
    long dl = wheel_delta(l, last_left);
    long dr = wheel_delta(r, last_right);
    long progress;

    last_left = l;
    last_right = r;
    if (!motion.active)
        return;
    motion.left += dl;
    motion.right += dr;
    if (motion.watch == WATCH_LEFT) {
        progress = abs_l(motion.left);
    } else if (motion.watch == WATCH_RIGHT) {
        progress = abs_l(motion.right);
    } else {
        long al = abs_l(motion.left), ar = abs_l(motion.right);
        progress = al > ar ? al : ar;
    }
    if (progress >= motion.target) {
        motion.active = 0;
        wheels(0, 0);
    }
}

/* The geometry that converts millimetres and degrees (set_robot_geometry). */
static long geo_circumference_um = EPUCK_WHEEL_CIRCUMFERENCE_UM;
static long geo_axle_um = EPUCK_AXLE_UM;
static long geo_steps_per_rev = EPUCK_STEPS_PER_REV;

void set_robot_geometry(long wheel_circumference_um, long axle_um, long steps_per_rev)
{
    if (wheel_circumference_um <= 0 || wheel_circumference_um > EPUCK_MAX_GEOMETRY_UM
        || axle_um <= 0 || axle_um > EPUCK_MAX_GEOMETRY_UM
        || steps_per_rev <= 0 || steps_per_rev > EPUCK_MAX_STEPS_PER_REV)
        return;
    geo_circumference_um = wheel_circumference_um;
    geo_axle_um = axle_um;
    geo_steps_per_rev = steps_per_rev;
    rt_geometry(wheel_circumference_um, axle_um, steps_per_rev);
}

#define LONG_MAX_STEPS 0x7FFFFFFFL

/* a * b / d rounded half up, for a >= 0, b >= 0, d > 0, saturated to a
 * long.  Computed as (a / d) * b + (a % d) * b / d so that no product passes
 * 2^63 when b and d are within the geometry limits (b, d <= ~4 * 10^12 and
 * (d - 1) * b < 2^63). */
static long muldiv_round(long long a, long long b, long long d)
{
    long long q = a / d, r = a % d;
    long long whole, rest;

    if (q != 0 && b > LONG_MAX_STEPS / q)
        return LONG_MAX_STEPS;
    whole = q * b;
    rest = (r * b + d / 2) / d;
    if (whole > LONG_MAX_STEPS - rest)
        return LONG_MAX_STEPS;
    return (long)(whole + rest);
}

/* |distance| mm -> steps with the robot's geometry. */
static long mm_to_steps(int mm)
{
    long long um = 1000LL * (mm < 0 ? -(long long)mm : (long long)mm);
    return muldiv_round(um, geo_steps_per_rev, geo_circumference_um);
}

/* Drive both wheels at |speed| for `steps` (>= 0), backwards when asked. */
static void straight(int speed, long steps, int backwards)
{
    int s = clamp_speed(abs_l(speed));
    motion_begin(backwards ? -s : s, backwards ? -s : s, steps, WATCH_BOTH);
}

void action_start_straight(void *param)
{
    const param_start_straight *p = (const param_start_straight *)param;

    if (p == NULL || motors_refused("start_straight"))
        return;
    straight(p->speed, mm_to_steps(p->distance), (p->speed < 0) != (p->distance < 0));
}

void action_straight_steps(void *param)
{
    const param_straight_steps *p = (const param_straight_steps *)param;

    /* traced under the rule file's name of the motion it compiles */
    if (p == NULL || motors_refused("start_straight"))
        return;
    straight(p->speed, abs_l(p->steps), (p->speed < 0) != (p->steps < 0));
}

void action_start_curve(void *param)
{
    const param_start_curve *p = (const param_start_curve *)param;
    int outer, inner;
    long radius, degrees;
    long long two_r, arc;       /* um; um * degrees * 355 */
    long outer_steps;

    if (p == NULL || motors_refused("start_curve"))
        return;
    outer = clamp_speed(p->speed);
    /* within the robot's 16-bit int, so that a host with a wider int
     * computes what the robot would, without overflow */
    radius = abs_l(p->radius) > 32767L ? 32767L : abs_l(p->radius);
    degrees = abs_l(p->degrees) > 32767L ? 32767L : abs_l(p->degrees);
    two_r = 2LL * 1000LL * radius;
    /* outer arc = (r + axle/2) * |degrees| * pi / 180, pi = 355/113;
     * arc <= (6.6e7 + 1e8) * 32767 * 355 < 2^61 */
    arc = (two_r + geo_axle_um) * degrees * 355LL;
    outer_steps = muldiv_round(arc, geo_steps_per_rev, 360LL * 113LL * geo_circumference_um);
    inner = clamp_speed((long)div_round((long long)outer * (two_r - geo_axle_um),
                                        two_r + geo_axle_um));
    if (p->degrees >= 0)        /* left: the right wheel is outer */
        motion_begin(inner, outer, outer_steps, WATCH_RIGHT);
    else
        motion_begin(outer, inner, outer_steps, WATCH_LEFT);
}

void action_curve_steps(void *param)
{
    const param_curve_steps *p = (const param_curve_steps *)param;
    int left, right;
    long al, ar;

    /* traced under the rule file's name of the motion it compiles */
    if (p == NULL || motors_refused("start_curve"))
        return;
    left = clamp_speed(p->left_speed);
    right = clamp_speed(p->right_speed);
    al = abs_l(left);
    ar = abs_l(right);
    motion_begin(left, right, abs_l(p->steps),
                 al > ar ? WATCH_LEFT : ar > al ? WATCH_RIGHT : WATCH_BOTH);
}

void action_stop_motor(void *param)
{
    (void)param;
    if (motors_refused("stop_motor"))
        return;
    sequence_outside_command();
    motion.active = 0;
    wheels(0, 0);
}

/* ---- the other standard actions ------------------------------------------- */

void action_set_timer(void *param)
{
    (void)param;
    timer_running = 1;
    timer_start = rt_millis();
}

void action_reset_timer(void *param)
{
    (void)param;
    timer_running = 0;
}

void action_start_sensor(void *param)
{
    (void)param;
    sensors_on = 1;
}

void action_stop_sensor(void *param)
{
    (void)param;
    sensors_on = 0;
}

void action_exit_main(void *param)
{
    (void)param;
    exit_requested = 1;
}

/* ---- sequencer -------------------------------------------------------------- */

/* A motion start or stop_motor from outside a step takes the wheels from a
 * waiting sequence: the sequence is abandoned. */
static void sequence_outside_command(void)
{
    if (seq != NULL && in_step == 0) {
        seq = NULL;
        seq_waiting = 0;
    }
}

/* Motor arbitration of run_sequence: a sequence in progress belongs to the
 * event that started it; one of lower priority may not replace it (1: the
 * new sequence is suppressed and traced).  Otherwise the new sequence runs,
 * and each of its steps' motor commands is arbitrated on its own. */
static int sequence_refused(void)
{
    int owner = seq_event_id, me = current_event_id;

    if (seq == NULL || owner < 0 || me < 0 || owner == me)
        return 0;
    if (event_priority(me) >= event_priority(owner))
        return 0;
    rt_trace_suppressed(me, event_priority(me), owner, event_priority(owner),
                        "run_sequence");
    return 1;
}

/* Run steps from seq_next on, until one starts a motion (then wait for it
 * to end) or the sequence is over. */
static void sequence_run_steps(void)
{
    unsigned generation = seq_generation;

    while (seq != NULL && seq_next < seq->count) {
        const action *step = &seq->steps[seq_next];
        unsigned starts_before = motion_starts;
        int index = seq_next++;

        rt_trace_action(seq_action_id, index, seq->count);
        if (step->action_function != NULL) {
            int previous = current_action_id, previous_event = current_event_id;
            /* a step that runs a sequence names it after this one; its
             * motor commands are those of the event that started it */
            current_action_id = seq_action_id;
            current_event_id = seq_event_id;
            in_step++;
            step->action_function(step->action_param);
            in_step--;
            current_action_id = previous;
            current_event_id = previous_event;
        }
        if (generation != seq_generation || seq == NULL)
            return;     /* the step ran a sequence that replaced this one */
        if (exit_requested) {
            seq = NULL;
            return;
        }
        if (motion_starts != starts_before && motion.active) {
            seq_waiting = 1;
            return;
        }
    }
    seq = NULL;
}

void action_run_sequence(void *param)
{
    const param_sequence *p = (const param_sequence *)param;

    if (sequence_refused())
        return;
    seq_generation++;
    seq = NULL;
    seq_waiting = 0;
    if (p == NULL || p->steps == NULL || p->count <= 0)
        return;
    seq = p;
    seq_next = 0;
    seq_action_id = current_action_id;
    seq_event_id = current_event_id;
    if (in_step > 0) {
        /* run by a step of a sequence: it starts at the next poll (once the
         * step's motion, if any, has ended), so a sequence that runs itself
         * loops once per poll instead of recursing */
        seq_waiting = 1;
        return;
    }
    sequence_run_steps();
}

/* Phase (3) of a poll: continue a sequence whose step's motion has ended. */
static void sequence_advance(void)
{
    if (seq != NULL && seq_waiting && !motion.active) {
        seq_waiting = 0;
        sequence_run_steps();
    }
}

/* ---- standard events -------------------------------------------------------- */

void event_immediate(void *param, void *status)
{
    (void)param;
    ((event_status *)status)->occurred = 1;
}

/* "The wheels went from moving to at rest between two polls": stop_sample,
 * computed once per poll before the events are polled. */
void event_stop_motor(void *param, void *status)
{
    (void)param;
    ((event_status *)status)->occurred = stop_sample;
}

/* Occurs when the timer runs and has run >= time ms.  status->memory holds
 * 1 + the clock time of the last firing (0: never), so that a repeating
 * event fires at time, 2*time, ... of the timer, and a restarted timer
 * restarts the phase. */
void event_timer(void *param, void *status)
{
    const param_event_timer *p = (const param_event_timer *)param;
    event_status *st = (event_status *)status;
    long now, elapsed, base = 0;

    st->occurred = 0;
    if (p == NULL || !timer_running)
        return;
    now = rt_millis();
    elapsed = now - timer_start;
    if (p->time > 0 && st->memory != 0 && st->memory - 1 >= timer_start) {
        /* fired before in this run of the timer: the current period
         * starts at the last multiple of time not after that firing */
        long since = st->memory - 1 - timer_start;
        base = since - since % p->time;
    }
    if (elapsed - base >= p->time) {
        st->occurred = 1;
        st->memory = now + 1;
    }
}

/* Occurs when the condition becomes true (status->memory: the condition at
 * the previous poll, 0 before the first). */
static int thresholds_passed(const param_event_sensor *p, int (*reading)(unsigned int))
{
    unsigned n;

    for (n = 0; n < 8; n++) {
        int threshold = p->sensef[n];
        int value;
        if (threshold == SENSOR_OFF)
            continue;
        value = reading(n);
        if ((p->below >> n) & 1u ? value < threshold : value > threshold)
            return 1;
    }
    return 0;
}

/* Rising edge of cond: status->memory holds the condition at the previous
 * poll (0 before the first). */
static void edge(event_status *st, int cond)
{
    st->occurred = cond && st->memory == 0;
    st->memory = cond;
}

void event_sensor(void *param, void *status)
{
    const param_event_sensor *p = (const param_event_sensor *)param;

    event_status *st = (event_status *)status;
    int cond = 0;
    unsigned n;

    if (p != NULL && sensors_on) {
        if (prox_valid != 0xFFu)
            read_prox(0xFFu);       /* the first sensor event of this poll */
        for (n = 0; n < 8; n++) {
            int threshold = p->sensef[n];
            int value = prox[n];
            if (threshold == SENSOR_OFF)
                continue;
            if ((p->below >> n) & 1u ? value < threshold : value > threshold) {
                cond = 1;
                break;
            }
        }
    }
    edge(st, cond);
}

/* ---- extension: modes ---------------------------------------------------------- */

void enter_mode(int mode)
{
    int i, left = current_mode;

    if (mode <= 0)
        return;
    current_mode = mode;
    /* re-armed as at registration; cancel_event's are gone for good */
    for (i = 0; i < s_events; i++) {
        const rt_event *e = &prog->events[i];
        if (e->mode == mode && !BIT_GET(ev_dead, i)) {
            BIT_SET(ev_armed, i);
            BIT_CLEAR(ev_latch, i);
            if (e->memory != RT_NO_MEMORY)
                prog->memory[e->memory] = 0;
        }
    }
    for (i = 0; i < n_events; i++) {
        if (event_ext[i].mode == mode && events[i].event_function != NULL) {
            events[i].valid_flag = 1;
            events[i].status.occurred = 0;
            events[i].status.memory = 0;
        }
    }
    if (!initialised) {
        mode_trace_pending = 1;     /* traced when mainloop starts */
        return;
    }
    mode_entered_in_poll = 1;
    rt_trace_mode(mode);
    if (left == 0)
        return;
    /* what the rules of the mode left were doing with the motors ends */
    if (seq != NULL && seq_event_id >= 0 && event_mode(seq_event_id) == left) {
        seq_generation++;
        seq = NULL;
        seq_waiting = 0;
    }
    if (motion.active && motion.owner >= 0 && event_mode(motion.owner) == left) {
        /* stopped without a stop_motor event: the motion did not end, its
         * mode did (the new mode's stop_motor rules must not take it for
         * the end of a motion of theirs) */
        motion.active = 0;
        seen_moving = 0;
        wheels(0, 0);
    }
}

void action_enter_mode(void *param)
{
    const param_enter_mode *p = (const param_enter_mode *)param;

    if (p != NULL)
        enter_mode(p->mode);
}

/* Occurs at its first poll after it was (re-)armed: mode entries reset
 * status->memory to 0. */
void event_enter_mode(void *param, void *status)
{
    event_status *st = (event_status *)status;

    (void)param;
    st->occurred = st->memory == 0;
    st->memory = 1;
}

/* ---- extension: LEDs and sound --------------------------------------------------- */

void action_set_led(void *param)
{
    const param_set_led *p = (const param_set_led *)param;

    if (p == NULL || p->value < SET_LED_OFF || p->value > SET_LED_TOGGLE)
        return;
    if (p->led >= 0 && p->led <= SET_LED_ALL)
        e_set_led((unsigned)p->led, (unsigned)p->value);
    else if (p->led == SET_LED_BODY)
        e_set_body_led((unsigned)p->value);
    else if (p->led == SET_LED_FRONT)
        e_set_front_led((unsigned)p->value);
}

/* [offset, length] in words of the library's samples (codec/e_const_sound.s) */
static const int sound_samples[5][2] = {
    { 0, 2112 }, { 2116, 1760 }, { 3878, 3412 }, { 7294, 3732 }, { 11028, 8016 }
};
static int sound_ready;

void action_play_sound(void *param)
{
    const param_play_sound *p = (const param_play_sound *)param;

    if (p == NULL || p->sound < 0 || p->sound > SOUND_WOUAAAAAAAAH)
        return;
    if (!sound_ready) {
        sound_ready = 1;
        e_init_sound();
    }
    e_play_sound(sound_samples[p->sound][0], sound_samples[p->sound][1]);
}

/* ---- extension: selector, microphones, accelerometer, remote, ambient light ----- */

void event_selector(void *param, void *status)
{
    const param_event_selector *p = (const param_event_selector *)param;

    edge((event_status *)status, p != NULL && getselector() == p->position);
}

void event_clap(void *param, void *status)
{
    const param_event_clap *p = (const param_event_clap *)param;
    int cond = 0;
    unsigned m;

    if (p != NULL)
        for (m = 0; m < 3 && !cond; m++)
            cond = e_get_micro_volume(m) > p->volume;
    edge((event_status *)status, cond);
}

/* Accelerometer samples, taken once per poll (phase 4) when a tap or tilt
 * event is registered: this poll's, the previous poll's, and the first
 * (the robot at rest). */
static int acc_now[3], acc_prev[3], acc_rest[3];
static int acc_samples;

static void accel_sample(void)
{
    unsigned k;

    for (k = 0; k < 3; k++) {
        acc_prev[k] = acc_now[k];
        acc_now[k] = e_get_acc(k);
        if (acc_samples == 0) {
            acc_prev[k] = acc_now[k];
            acc_rest[k] = acc_now[k];
        }
    }
    acc_samples = 1;
}

static int differs(int a, int b, int threshold)
{
    long d = (long)a - b;
    return (d < 0 ? -d : d) > threshold;
}

void event_tap(void *param, void *status)
{
    const param_event_accel *p = (const param_event_accel *)param;
    int cond = 0;
    unsigned k;

    if (p != NULL && acc_samples)
        for (k = 0; k < 3 && !cond; k++)
            cond = differs(acc_now[k], acc_prev[k], p->threshold);
    edge((event_status *)status, cond);
}

void event_tilt(void *param, void *status)
{
    const param_event_accel *p = (const param_event_accel *)param;
    int cond = 0;
    unsigned k;

    if (p != NULL && acc_samples)
        for (k = 0; k < 2 && !cond; k++)
            cond = differs(acc_now[k], acc_rest[k], p->threshold);
    edge((event_status *)status, cond);
}

/* status->memory: 0 before the first poll, else 1 + the check bit seen at
 * the previous poll; a new press toggles the bit. */
void event_remote(void *param, void *status)
{
    const param_event_remote *p = (const param_event_remote *)param;
    event_status *st = (event_status *)status;
    int check;

    st->occurred = 0;
    if (p == NULL || !remote_started)
        return;
    check = e_get_check() != 0;
    st->occurred = st->memory != 0 && check != st->memory - 1 && e_get_data() == p->key;
    st->memory = check + 1;
}

static int ambient_reading(unsigned int n)
{
    return e_get_ambient_light(n);
}

void event_ambient(void *param, void *status)
{
    const param_event_sensor *p = (const param_event_sensor *)param;

    edge((event_status *)status, p != NULL && thresholds_passed(p, ambient_reading));
}

/* ---- the paper's short spellings -------------------------------------------- */

void start_straight(void *param) { action_start_straight(param); }
void start_curve(void *param) { action_start_curve(param); }
void straight_steps(void *param) { action_straight_steps(param); }
void curve_steps(void *param) { action_curve_steps(param); }
void stop_motor(void *param) { action_stop_motor(param); }
void set_timer(void *param) { action_set_timer(param); }
void reset_timer(void *param) { action_reset_timer(param); }
void start_sensor(void *param) { action_start_sensor(param); }
void stop_sensor(void *param) { action_stop_sensor(param); }
void exit_main(void *param) { action_exit_main(param); }
void run_sequence(void *param) { action_run_sequence(param); }
void sensor(void *param, void *status) { event_sensor(param, status); }
void timer(void *param, void *status) { event_timer(param, status); }
void immediate(void *param, void *status) { event_immediate(param, status); }

/* ---- main loop (paper figure 4) ---------------------------------------------- */

static void run_action(int action_id)
{
    int previous = current_action_id;
    action_func f;
    void *param;

    if (!action_ok(action_id))
        return;     /* cancelled: the event fires but runs nothing */
    if (action_id < s_actions) {
        f = prog->actions[action_id].action_function;
        param = (void *)prog->actions[action_id].action_param;
    } else {
        f = actions[action_id - s_actions].action_function;
        param = actions[action_id - s_actions].action_param;
    }
    rt_trace_action(action_id, -1, 0);
    current_action_id = action_id;
    f(param);
    current_action_id = previous;
}

/* A table event occurred: trace it, run its action, disarm it unless it
 * repeats. */
static void fire_static(int id)
{
    rt_trace_event(id);
    current_event_id = id;
    run_action(prog->events[id].action_id);
    current_event_id = -1;
    if (!BIT_GET(ev_repeat, id))
        BIT_CLEAR(ev_armed, id);
}

/* ~0u while the sensors are on (this poll's compiled conditions are then
 * in ev_now, computed at the first call of the poll), 0 while they are off:
 * a mask for ev_now. */
static unsigned conditions_mask(void)
{
    if (!sensors_on || prog->conditions == NULL)
        return 0;
    if (!conditions_valid) {
        read_prox(prog->sensors);
        prog->conditions(prox, ev_now);
        conditions_valid = 1;
    }
    return ~0u;
}

/* Polls a table event that is not a compiled condition. */
static void poll_static_function(int id)
{
    const rt_event *e = &prog->events[id];
    event_status st;

    st.occurred = 0;
    st.memory = e->memory != RT_NO_MEMORY ? prog->memory[e->memory] : 0;
    e->event_function((void *)e->event_param, &st);
    if (e->memory != RT_NO_MEMORY)
        prog->memory[e->memory] = st.memory;
    if (st.occurred)
        fire_static(id);
}

/* Phase (5) for the table's events, sixteen at a time: a word whose armed
 * events are all compiled conditions that do not become true only has its
 * latches updated; the others are polled one by one in index order, and
 * the word re-read after each, since an action may change the sensors or
 * cancel events.  Returns 1 when exit_main ran. */
static int poll_static(void)
{
    unsigned w;
    unsigned *armed = ev_armed, *latch = ev_latch, *compiled = ev_compiled, *now = ev_now;
    unsigned on = conditions_mask();

    for (w = 0; w < s_words; w++) {
        unsigned todo = armed[w];       /* armed and not polled yet */
        while (todo != 0) {
            unsigned comp = todo & compiled[w];
            unsigned cond = now[w] & comp & on;
            unsigned pick = (cond & ~latch[w]) | (todo & ~comp);
            unsigned low, below;
            int k;

            if (pick == 0) {
                /* no event of the word occurs: the latches follow */
                latch[w] = (latch[w] & ~comp) | cond;
                break;
            }
            for (k = 0; !((pick >> k) & 1u); k++)
                ;
            low = BIT_OF(k);
            below = low - 1u;
            latch[w] = (latch[w] & ~(comp & below)) | (cond & below);
            if (comp & low) {
                latch[w] |= low;        /* the condition became true */
                fire_static((int)(w * 16u) + k);
            } else {
                poll_static_function((int)(w * 16u) + k);
            }
            if (exit_requested)
                return 1;
            on = conditions_mask();     /* the action may have started the sensors */
            todo = armed[w] & ~(low | below) & WORD_MASK;
        }
    }
    return 0;
}

/* An array event occurred: trace it, run its action, disarm it unless it
 * repeats. */
static void fire_dynamic(int i)
{
    event *e = &events[i];

    rt_trace_event(s_events + i);
    current_event_id = s_events + i;
    run_action(e->action_id);
    current_event_id = -1;
    if (!e->repeat_flag)
        e->valid_flag = 0;
}

/* ---- the walk by priority levels (ranked: priorities or modes in use) ---- */

/* A mode's events are polled only while it is the current mode, and not in
 * the poll that entered it. */
static int mode_ok(int mode)
{
    return mode == 0 || (mode == current_mode && !mode_entered_in_poll);
}

static int static_armed(int k)
{
    return BIT_GET(ev_armed, k) && mode_ok(prog->events[k].mode);
}

static int dynamic_armed(int i)
{
    return events[i].valid_flag && events[i].event_function != NULL
           && mode_ok(event_ext[i].mode);
}

/* Polls one table event (the ranked walk's, one at a time). */
static void poll_static_one(int k)
{
    int cond, was;

    if (!BIT_GET(ev_compiled, k)) {
        poll_static_function(k);
        return;
    }
    cond = (conditions_mask() & ev_now[k >> 4] & BIT_OF(k)) != 0;
    was = BIT_GET(ev_latch, k);
    if (cond)
        BIT_SET(ev_latch, k);
    else
        BIT_CLEAR(ev_latch, k);
    if (cond && !was)
        fire_static(k);
}

/* The highest priority below `below` (any, when !bounded) among the armed
 * array events; 0 when there is none. */
static int next_dynamic_level(int bounded, int below, int *level)
{
    int i, found = 0;

    for (i = 0; i < n_events; i++) {
        int p = event_ext[i].priority;
        if ((bounded && p >= below) || !dynamic_armed(i))
            continue;
        if (!found || p > *level)
            *level = p;
        found = 1;
    }
    return found;
}

/* The same among all the armed events, the table's too. */
static int next_level(int bounded, int below, int *level)
{
    int i, found = next_dynamic_level(bounded, below, level);

    for (i = 0; i < s_events; i++) {
        int p = prog->events[i].priority;
        if ((bounded && p >= below) || !static_armed(i))
            continue;
        if (!found || p > *level)
            *level = p;
        found = 1;
    }
    return found;
}

/* Polls the armed array events of priority `level`, in id order. */
static int poll_dynamic_level(int level)
{
    int i;

    /* n_events is re-read: an action may register events, polled at once */
    for (i = 0; i < n_events; i++) {
        event *e = &events[i];
        if (event_ext[i].priority != level || !dynamic_armed(i))
            continue;
        e->status.occurred = 0;
        e->event_function(e->event_param, &e->status);
        if (e->status.occurred)
            fire_dynamic(i);
        if (exit_requested)
            return 1;
    }
    return 0;
}

/* The ranked walk over the table's order (rt_program.order): one pass
 * over the table, the array events of each level after the table's. */
static int poll_ordered(void)
{
    const int *order = prog->order;
    int j = 0, level = 0, bounded = 0;

    for (;;) {
        int dynamic = n_events > 0 && next_dynamic_level(bounded, level, &level);
        if (j < s_events && (!dynamic || prog->events[order[j]].priority > level))
            level = prog->events[order[j]].priority;
        else if (!dynamic)
            return 0;
        for (; j < s_events && prog->events[order[j]].priority == level; j++) {
            if (static_armed(order[j])) {
                poll_static_one(order[j]);
                if (exit_requested)
                    return 1;
            }
        }
        if (n_events > 0 && poll_dynamic_level(level))
            return 1;
        bounded = 1;
    }
}

/* Phase (5) with priorities or modes: the armed events (in no mode or in
 * the current one), highest priority first, in id order within a priority
 * (the table's, then the arrays'); the levels are re-read after each, since
 * an action may arm, disarm or register events.  Without the table's order
 * the table is scanned once per level.  Returns 1 when exit_main ran. */
static int poll_ranked(void)
{
    int i, level = 0, more;

    mode_entered_in_poll = 0;
    if (prog != NULL && prog->order != NULL)
        return poll_ordered();
    more = next_level(0, 0, &level);
    while (more) {
        for (i = 0; i < s_events; i++) {
            if (prog->events[i].priority == level && static_armed(i)) {
                poll_static_one(i);
                if (exit_requested)
                    return 1;
            }
        }
        if (poll_dynamic_level(level))
            return 1;
        more = next_level(1, level, &level);
    }
    return 0;
}

/* Phase (5): poll the armed events; without priorities and modes in index
 * order: the table's, then the registered ones.  Returns 1 when exit_main
 * ran. */
static int poll_events(void)
{
    int i;

    conditions_valid = 0;
    prox_valid = 0;
    if (ranked)
        return poll_ranked();
    if (prog != NULL && poll_static())
        return 1;
    /* n_events is re-read: an action may register events, polled at once */
    for (i = 0; i < n_events; i++) {
        event *e = &events[i];
        if (!e->valid_flag || e->event_function == NULL)
            continue;
        e->status.occurred = 0;
        e->event_function(e->event_param, &e->status);
        if (e->status.occurred)
            fire_dynamic(i);
        if (exit_requested)
            return 1;
    }
    return 0;
}

void mainloop(void)
{
    rt_init();
    exit_requested = 0;
    if (mode_trace_pending) {
        mode_trace_pending = 0;
        rt_trace_mode(current_mode);
    }
    last_left = e_get_steps_left();
    last_right = e_get_steps_right();
    for (;;) {
        rt_platform_idle();         /* (1) wait for / advance time by 1 ms */
        motion_update();            /* (2) */
        sequence_advance();         /* (3) */
        if (exit_requested)
            break;
        stop_sample = seen_moving && !motion.active;    /* (4) */
        seen_moving = motion.active;
        if (accel_wanted)
            accel_sample();
        if (poll_events())          /* (5) */
            break;
    }
    /* exit_main: stop at once */
    motion.active = 0;
    wheels(0, 0);
    seq = NULL;
    seq_waiting = 0;
    seen_moving = 0;
    exit_requested = 0;
    prox_valid = 0;
    rt_trace_exit();
}
