/*
 * rt_idle.c - idle polls in bulk, for a platform that simulates time (the
 * host harness and the robots of Enki worlds: platform/platform_host.c).  At
 * the start of each poll cycle such a platform asks how many of the coming
 * polls are known to change nothing but time, and advances its virtual time
 * over them at once (docs/runtime.md, "Idle polls in bulk").  A robot's
 * platform never asks: there the poll waits for the real clock anyway, and
 * this file is not in its build.  Part of the runtime behind epuckrt.h; see
 * epuckrt.c.
 *
 * Why it is exact.  A poll that fired no event, ran no step of a sequence,
 * ended no motion and changed no hold (rt_stir as it was) leaves every
 * event's memory, every condition's latch and the program's variables as
 * the next poll will find them, since nothing else changes them.  The next
 * polls can then differ from it only by what they read that is not the
 * program's: the inputs (the platform knows when they change: the
 * scenario's next line, the world's next step), the clock (the timers'
 * deadlines, computed here from the same fields their event functions
 * read) and the wheels (the motion's end, which the platform watches in
 * steps; when the program reads the odometry, which sums each poll's
 * steps, the skipped polls still measure them ms by ms: rt_idle_ms).
 * Anything this file does not know (a user's event function, a condition
 * that reads the odometry or random numbers, the accelerometer's taps, a
 * device whose poll has work) is polled at every ms, as before.
 */
#include "rt_modes.h"

#define NEVER 0x7FFFFFFFL           /* ms: only after a change */
/* At most this many ms at once: the next poll measures the wheels' progress
 * over them from 16-bit counters, which hold at most 32767 steps of it (a
 * wheel makes at most 1000 steps a second). */
#define RT_IDLE_MAX_MS 10000L

static int primed;                  /* a poll cycle began under mainloop */
static unsigned stir_seen;          /* rt_stir when the last poll cycle began */
static unsigned long polls_seen;    /* rt_poll_count then */

static long abs_l(long v)
{
    return v < 0 ? -v : v;
}

/* The compiled conditions read only the proximity readings (without
 * RT_CONDITIONS_ALWAYS, as register_program's contract says) or what
 * RT_CONDITIONS_ON_CHANGE promises. */
static int conditions_on_change(void)
{
    unsigned s = rt_prog->sensors;
    return !(s & RT_CONDITIONS_ALWAYS) || (s & RT_CONDITIONS_ON_CHANGE);
}

/* The ms until event_timer on p can occur, as event_timer computes it. */
static long timer_due(const param_event_timer *p, long memory, long now)
{
    long base = 0;

    if (p == NULL || !rt_timer_running)
        return NEVER;           /* until set_timer runs: an action */
    if (p->time <= 0)
        return 1;               /* at every poll */
    if (memory != 0 && memory - 1 >= rt_timer_start) {
        long since = memory - 1 - rt_timer_start;
        base = since - since % p->time;
    }
    /* elapsed - base >= time, elapsed = now - start (0 <= both < 2^30) */
    return p->time - ((now - rt_timer_start) - base);
}

/* The ms from now until an armed event can occur if nothing but time
 * passes: NEVER when only a change of the inputs or of the program's state
 * can make it occur, 1 when it must be polled at the next ms (unknown). */
static long due(event_func f, const void *param, long memory, unsigned flags, long now)
{
    if (f == NULL)
        return conditions_on_change() ? NEVER : 1;
    if ((flags & RT_WAKE_ON_CHANGE) || f == event_stop_motor || f == event_sensor || f == sensor
            || f == event_ambient || f == event_selector || f == event_clap || f == event_remote)
        return NEVER;
    if (f == event_enter_mode)
        return memory != 0 ? NEVER : 1;
    if ((flags & RT_WAKE_AT_DEADLINE) || f == event_every || f == event_after)
        return memory != 0 ? memory - 1 - now : 1;
    if ((flags & RT_WAKE_AS_TIMER) || f == event_timer || f == timer)
        return timer_due((const param_event_timer *)param, memory, now);
    return 1;
}

static int mode_ok(int mode)
{
    return mode == 0 || mode == rt_current_mode;
}

/* The earliest due() of the events the next poll would poll, and of those
 * that hold the motors by their condition (a one-shot rule that fired and
 * disarmed is still read at each poll, by the walk's holds_update: when its
 * condition can change is when its event could occur). */
static long events_due(long now)
{
    long n = NEVER, d;
    int k;

    for (k = 0; k < rt_s_events && n > 1; k++) {
        const rt_event *e = &rt_prog->events[k];
        if (!(BIT_GET(rt_ev_armed, k) && mode_ok(e->mode)) && !BIT_GET(rt_ev_hold, k))
            continue;
        d = due(e->event_function, e->event_param,
                e->memory != RT_NO_MEMORY ? rt_prog->memory[e->memory] : 0, e->flags, now);
        n = d < n ? d : n;
    }
    for (k = 0; k < rt_n_events && n > 1; k++) {
        const event *e = &rt_events[k];
        if (e->event_function == NULL
                || (!(e->valid_flag && mode_ok(rt_event_ext[k].mode)) && !rt_event_ext[k].hold))
            continue;
        d = due(e->event_function, e->event_param, e->status.memory, 0u, now);
        n = d < n ? d : n;
    }
    return n;
}

/* events_due as long as nothing changed (rt_stir): the same clock time.
 * Only a time after the next ms is kept: what gives an earlier one (an
 * `every` armed but not polled yet, a memory of 0) may change without a
 * stir, what gives a later one (a deadline, a timer's start, which events
 * are armed or hold the motors, the mode) only with one. */
static long events_due_cached(long now)
{
    static int known;
    static unsigned stir;
    static long at;             /* clock time, or NEVER */
    long d;

    if (known && stir == rt_stir)
        return at == NEVER ? NEVER : at - now;
    d = events_due(now);
    known = d > 1;
    stir = rt_stir;
    at = d >= NEVER ? NEVER : now + d;
    return d;
}

/* The steps each watched wheel may still make before the motion can end:
 * it ends when max(|left|, |right|) (or the watched wheel's) reaches its
 * target, and |a + d| <= |a| + |d|, so no poll before these steps ends it.
 * 0 when it ends at the next poll. */
static int motion_room(long *left, long *right)
{
    long l = rt_motion.target - abs_l(rt_motion.left);
    long r = rt_motion.target - abs_l(rt_motion.right);

    if (rt_motion.watch != WATCH_RIGHT) {
        if (l < 1)
            return 0;
        *left = l;
    }
    if (rt_motion.watch != WATCH_LEFT) {
        if (r < 1)
            return 0;
        *right = r;
    }
    return 1;
}

long rt_idle_horizon(long *left, long *right)
{
    long now, n;
    int quiet = primed && rt_looping && rt_stir == stir_seen && rt_poll_count == polls_seen + 1UL;

    primed = rt_looping;
    stir_seen = rt_stir;
    polls_seen = rt_poll_count;
    *left = *right = 0;
    /* the poll before changed something, or the next one has work of its
     * own (a pending start, a stop_motor sample, a value waiting for the
     * transmitter), or per-poll work this file does not model (the
     * accelerometer's samples, whose tap compares two polls) */
    if (!quiet || rt_accel_wanted
            || (rt_device_poll != NULL && (rt_device_idle == NULL || !rt_device_idle()))
            || rt_sensors_starting || rt_mode_arm_pending || rt_mode_entry_pending
            || rt_seen_moving != rt_motion.active || rt_exit_requested)
        return 1;
    now = rt_millis();
    n = RT_IDLE_MAX_MS;
    if (rt_seq != NULL) {
        if (!rt_seq_waiting)
            return 1;
        if (rt_seq_delay) {
            long d = rt_seq_until - now;
            n = d < n ? d : n;
        } else if (!rt_motion.active || rt_motion.endless) {
            return 1;       /* it goes on at the next poll */
        }
    }
    if (rt_motion.active && !rt_motion.endless && !motion_room(left, right))
        return 1;
    if (n > 1) {
        long d = events_due_cached(now);
        n = d < n ? d : n;
    }
    return n < 1 ? 1 : n;
}

/* The odometry sums each poll's steps along the heading of that poll:
 * skipped polls still measure the wheels, one ms at a time. */
int rt_idle_each_ms(void)
{
    return rt_odometry_used;
}

int rt_idle_ms(void)
{
    return rt_motion_idle();
}

void rt_idle_skipped(long polls)
{
    rt_poll_count += (unsigned long)polls;
    polls_seen += (unsigned long)polls;
}
