/*
 * rt_motion.c - motion control (start_straight, start_curve, their exact-step
 * forms, stop_motor, motor arbitration under priorities) and the sequencer
 * (`then`), with the paper's short spellings of their actions.  A layer of
 * the core on rt_registry.c and rt_odometry.c (rt_motion.h); part of the
 * runtime behind epuckrt.h.
 */
#include "rt_motion.h"

/* The motion in progress (rt_motion.h). */
struct rt_motion rt_motion = { 0, 0, 0, 0, 0, -1, 0 };
static int last_left;           /* raw counters at the previous poll */
static int last_right;
static unsigned motion_starts;  /* incremented at every motion start */
static int traced_active;       /* who holds the motors, as last traced */
static int traced_owner = -1;

/* stop_motor event latch: see event_stop_motor (rt_sensors.c). */
int rt_seen_moving;

/* Sequencer: the sequence in progress, if any. */
const param_sequence *rt_seq;   /* NULL: none */
static int seq_next;                /* index of the next step to run */
static int seq_action_id;           /* id used in the trace of its steps */
static int seq_event_id;            /* the event whose action started it */
int rt_seq_waiting;             /* a step's motion is under way */
static unsigned seq_generation;     /* changes when a sequence replaces one */
static int in_step;                 /* > 0 while a step's function runs */
int rt_seq_delay;               /* a wait step runs: go on at rt_seq_until */
long rt_seq_until;

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

/* ---- who holds the motors, for the trace ---------------------------------- */

static int holder_over(int level);

/* Called where the motion changes and once per poll (holds by a condition
 * or a sequence end there): traces the event of highest priority that holds
 * the motors (as arbitration sees it), main for a bounded motion that main
 * started, or nothing (a `set_speed` that no event holds: free). */
void rt_motors_changed(void)
{
    int owner = holder_over(-1);
    int active = owner >= 0 || (rt_motion.active && !rt_motion.endless);

    if (active == traced_active && owner == traced_owner)
        return;
    traced_active = active;
    traced_owner = owner;
    rt_trace_motors(active, owner);
}

void rt_motors_retrace(void)
{
    if (traced_active)
        rt_trace_motors(traced_active, traced_owner);
}

/* ---- motion control -------------------------------------------------------- */

static void sequence_outside_command(void);

/* The event of highest priority above `level` that holds the motors, or -1. */
static int holder_over(int level)
{
    int best = -1, id, left = rt_holds;

    if (rt_motion.active && !rt_motion.endless && rt_motion.owner >= 0
            && rt_event_priority(rt_motion.owner) > level) {
        best = rt_motion.owner;
        level = rt_event_priority(best);
    }
    if (rt_seq != NULL && seq_event_id >= 0 && rt_event_priority(seq_event_id) > level) {
        best = seq_event_id;
        level = rt_event_priority(best);
    }
    for (id = left > 0 ? rt_next_holder(0) : -1; id >= 0; id = --left > 0 ? rt_next_holder(id + 1) : -1) {
        if (rt_event_priority(id) > level) {
            best = id;
            level = rt_event_priority(id);
        }
    }
    return best;
}

static int holder_above(int me)
{
    return holder_over(rt_event_priority(me));
}

/* Motor arbitration: 1 when the running action may not command the motors
 * because an event of higher priority holds them (the command is then
 * traced as suppressed and not carried out).  Commands from outside any
 * event's action (main, before mainloop) always pass.  A command carried
 * out by a condition or a guarded periodic rule as it fires starts its
 * hold. */
static int motors_refused(const char *command)
{
    int me = rt_current_event_id, holder;

    if (me < 0)
        return 0;
    holder = holder_above(me);
    if (holder >= 0) {
        rt_trace_suppressed(me, rt_event_priority(me), holder, rt_event_priority(holder),
                            command);
        return 1;
    }
    if (rt_firing_event == me && rt_hold_kind(me) != 0)
        rt_hold_put(me, 1);
    return 0;
}

void rt_wheels(int left, int right)
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
    rt_motion.active = 1;
    rt_motion.endless = 0;
    rt_motion.owner = rt_current_event_id;
    rt_motion.watch = watch;
    rt_motion.target = target;
    rt_motion.left = 0;
    rt_motion.right = 0;
    rt_wheels(left, right);
    /* steps made since this poll's measurement belong to the replaced motion */
    last_left = e_get_steps_left();
    last_right = e_get_steps_right();
    rt_seen_moving = 1;
    motion_starts++;
    rt_motors_changed();
}

/* Phase (2) of a poll: measure the wheels, end the motion at its target. */
/* The motion's progress after dl, dr more steps: the watched wheel's, or
 * the larger of the two. */
static long progress_after(long dl, long dr)
{
    long al = abs_l(rt_motion.left + dl), ar = abs_l(rt_motion.right + dr);

    if (rt_motion.watch == WATCH_LEFT)
        return al;
    if (rt_motion.watch == WATCH_RIGHT)
        return ar;
    return al > ar ? al : ar;
}

void rt_motion_update(void)
{
    int l = e_get_steps_left();
    int r = e_get_steps_right();
    long dl = wheel_delta(l, last_left);
    long dr = wheel_delta(r, last_right);
    long progress;

    last_left = l;
    last_right = r;
    rt_odometry(dl, dr);
    if (!rt_motion.active || rt_motion.endless)
        return;
    progress = progress_after(dl, dr);
    rt_motion.left += dl;
    rt_motion.right += dr;
    if (progress >= rt_motion.target) {
        rt_stir++;
        rt_motion.active = 0;
        rt_wheels(0, 0);
        rt_motors_changed();
    }
}

/* Phase (2) of a poll that rt_idle.c skips: the same measurement, unless
 * the motion would end in it; then it does nothing and returns 0 (that
 * poll must run). */
int rt_motion_idle(void)
{
    int l = e_get_steps_left();
    int r = e_get_steps_right();
    long dl = wheel_delta(l, last_left);
    long dr = wheel_delta(r, last_right);

    if (rt_motion.active && !rt_motion.endless) {
        if (progress_after(dl, dr) >= rt_motion.target)
            return 0;
        rt_motion.left += dl;
        rt_motion.right += dr;
    }
    last_left = l;
    last_right = r;
    rt_odometry(dl, dr);
    return 1;
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
    return muldiv_round(um, rt_geo_steps_per_rev, rt_geo_circumference_um);
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
    arc = (two_r + rt_geo_axle_um) * degrees * 355LL;
    outer_steps = muldiv_round(arc, rt_geo_steps_per_rev, 360LL * 113LL * rt_geo_circumference_um);
    inner = clamp_speed((long)div_round((long long)outer * (two_r - rt_geo_axle_um),
                                        two_r + rt_geo_axle_um));
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

void action_set_speed(void *param)
{
    const param_set_speed *p = (const param_set_speed *)param;
    int left, right;

    if (p == NULL || motors_refused("set_speed"))
        return;
    left = clamp_speed(p->left);
    right = clamp_speed(p->right);
    if (left == 0 && right == 0) {
        /* stopped: a motion of no steps, that ends (stop_motor) at the next poll */
        motion_begin(0, 0, 0, WATCH_BOTH);
        return;
    }
    motion_begin(left, right, LONG_MAX_STEPS, WATCH_BOTH);
    rt_motion.endless = 1;
}

void action_stop_motor(void *param)
{
    (void)param;
    if (motors_refused("stop_motor"))
        return;
    sequence_outside_command();
    rt_motion.active = 0;
    rt_wheels(0, 0);
    rt_motors_changed();
}

/* ---- sequencer -------------------------------------------------------------- */

/* A motion start or stop_motor from outside a step takes the wheels from a
 * waiting sequence: the sequence is abandoned. */
static void sequence_outside_command(void)
{
    if (rt_seq != NULL && in_step == 0) {
        rt_seq = NULL;
        rt_seq_waiting = 0;
        rt_seq_delay = 0;
    }
}

/* Motor arbitration of run_sequence: a sequence in progress belongs to the
 * event that started it; one of lower priority may not replace it (1: the
 * new sequence is suppressed and traced).  Otherwise the new sequence runs,
 * and each of its steps' motor commands is arbitrated on its own. */
static int sequence_refused(void)
{
    int owner = seq_event_id, me = rt_current_event_id;

    if (rt_seq == NULL || owner < 0 || me < 0 || owner == me)
        return 0;
    if (rt_event_priority(me) >= rt_event_priority(owner))
        return 0;
    rt_trace_suppressed(me, rt_event_priority(me), owner, rt_event_priority(owner),
                        "run_sequence");
    return 1;
}

/* Run steps from seq_next on, until one starts a motion (then wait for it
 * to end) or the sequence is over. */
static void sequence_run_steps(void)
{
    unsigned generation = seq_generation;

    while (rt_seq != NULL && seq_next < rt_seq->count) {
        const action *step = &rt_seq->steps[seq_next];
        unsigned starts_before = motion_starts;
        int index = seq_next++;

        rt_stir++;
        rt_trace_action(seq_action_id, index, rt_seq->count);
        if (step->action_function != NULL) {
            int previous = rt_current_action_id, previous_event = rt_current_event_id;
            /* a step that runs a sequence names it after this one; its
             * motor commands are those of the event that started it */
            rt_current_action_id = seq_action_id;
            rt_current_event_id = seq_event_id;
            in_step++;
            step->action_function(step->action_param);
            in_step--;
            rt_current_action_id = previous;
            rt_current_event_id = previous_event;
        }
        if (generation != seq_generation || rt_seq == NULL)
            return;     /* the step ran a sequence that replaced this one */
        if (rt_exit_requested) {
            rt_seq = NULL;
            return;
        }
        if ((motion_starts != starts_before && rt_motion.active && !rt_motion.endless)
                || rt_seq_delay) {
            rt_seq_waiting = 1;
            return;
        }
    }
    rt_seq = NULL;
}

void action_run_sequence(void *param)
{
    const param_sequence *p = (const param_sequence *)param;

    if (sequence_refused())
        return;
    seq_generation++;
    rt_seq = NULL;
    rt_seq_waiting = 0;
    rt_seq_delay = 0;
    if (p == NULL || p->steps == NULL || p->count <= 0)
        return;
    rt_seq = p;
    seq_next = 0;
    seq_action_id = rt_current_action_id;
    seq_event_id = rt_current_event_id;
    if (in_step > 0) {
        /* run by a step of a sequence: it starts at the next poll (once the
         * step's motion, if any, has ended), so a sequence that runs itself
         * loops once per poll instead of recursing */
        rt_seq_waiting = 1;
        return;
    }
    sequence_run_steps();
}

void action_wait(void *param)
{
    const param_wait *p = (const param_wait *)param;

    if (p == NULL || in_step == 0 || rt_seq == NULL)
        return;         /* not a step of a sequence: nothing to hold back */
    rt_seq_delay = 1;
    rt_seq_until = rt_millis() + (p->time > 0 ? p->time : 0);
}

/* Phase (3) of a poll: continue a sequence whose step's motion (and wait)
 * has ended. */
void rt_sequence_advance(void)
{
    if (rt_seq != NULL && rt_seq_waiting && (!rt_motion.active || rt_motion.endless)) {
        if (rt_seq_delay) {
            if (rt_millis() - rt_seq_until < 0)
                return;
            rt_seq_delay = 0;
        }
        rt_seq_waiting = 0;
        sequence_run_steps();
    }
}

/* ---- the walk's and the modes' ends of motion ------------------------------------ */

/* mainloop starts: the wheels' counters are where its first poll measures
 * from. */
void rt_motion_loop_start(void)
{
    last_left = e_get_steps_left();
    last_right = e_get_steps_right();
}

/* Phase (4) of a poll: 1 when the wheels went from moving to at rest since
 * the previous poll (the stop_motor event's condition). */
int rt_motion_stop_sample(void)
{
    int stopped = rt_seen_moving && !rt_motion.active;

    rt_seen_moving = rt_motion.active;
    return stopped;
}

/* exit_main: the motion and the sequence stop at once. */
void rt_motion_halt(void)
{
    rt_motion.active = 0;
    rt_wheels(0, 0);
    rt_seq = NULL;
    rt_seq_waiting = 0;
    rt_seq_delay = 0;
    rt_seen_moving = 0;
}

/* The mode `left` was left: what its rules were doing with the motors ends
 * (their sequence; their motion, stopped without a stop_motor event: the
 * motion did not end, its mode did, and the new mode's stop_motor rules
 * must not take it for the end of a motion of theirs). */
void rt_motion_leave_mode(int left)
{
    if (rt_seq != NULL && seq_event_id >= 0 && rt_event_mode(seq_event_id) == left) {
        seq_generation++;
        rt_seq = NULL;
        rt_seq_waiting = 0;
        rt_seq_delay = 0;
    }
    if (rt_motion.active && rt_motion.owner >= 0 && rt_event_mode(rt_motion.owner) == left) {
        rt_motion.active = 0;
        rt_seen_moving = 0;
        rt_wheels(0, 0);
        rt_motors_changed();
    }
}

/* ---- the paper's short spellings -------------------------------------------- */

void start_straight(void *param) { action_start_straight(param); }
void start_curve(void *param) { action_start_curve(param); }
void straight_steps(void *param) { action_straight_steps(param); }
void curve_steps(void *param) { action_curve_steps(param); }
void stop_motor(void *param) { action_stop_motor(param); }
void run_sequence(void *param) { action_run_sequence(param); }
