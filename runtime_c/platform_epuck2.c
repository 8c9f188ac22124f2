/*
 * platform_epuck2.c - the runtime's platform layer on the e-puck2
 * (STM32F407 under ChibiOS, GCtronic's e-puck2_main-processor firmware,
 * whose src/epuck1x layer offers the e-puck library's API).
 *
 * Two things differ from the e-puck (platform_robot.c):
 * - The poll is paced by ChibiOS: rt_platform_idle sleeps until the next
 *   1 ms deadline (chThdSleepUntilWindowed) and never spins, so that the
 *   firmware's threads that read the sensors and drive the motors run
 *   between two polls, whatever the runtime thread's priority.
 * - The epuck1x layer's agendas do nothing (there is no Timer2 to run
 *   them), so the runtime's millisecond clock is kept here: after each
 *   sleep, rt_clock_tick is called once for every millisecond of ChibiOS's
 *   system time since mainloop started (more than once after a poll that
 *   overran its millisecond).
 * There is no trace on the robot.
 */
#include "ch.h"
#include "rt_platform.h"
#include "a_d/advance_ad_scan/e_prox.h"

static systime_t counted;        /* system time the clock has counted up to */
static systime_t due;            /* the next poll's deadline */

void rt_platform_init(void)
{
    counted = chVTGetSystemTime();
    due = counted;
}

void rt_platform_idle(void)
{
    systime_t previous = due, now;
    unsigned long ms;

    due += MS2ST(1);
    /* sleeps until `due`; returns at once when `due` is already past */
    chThdSleepUntilWindowed(previous, due);
    now = chVTGetSystemTime();
    if ((systime_t)(now - due) >= (systime_t)MS2ST(1)
            && (systime_t)(now - due) < (systime_t)MS2ST(60000))
        due = now;          /* the poll overran: the next deadline counts from now */
    /* the clock: one tick per whole millisecond since it last counted
     * (differences of systime_t, so its wrapping does not matter) */
    ms = (unsigned long)((systime_t)(now - counted) / MS2ST(1));
    counted += (systime_t)(ms * MS2ST(1));
    while (ms-- > 0)
        rt_clock_tick();
}

void rt_trace_event(int event_id)
{
    (void)event_id;
}

void rt_trace_action(int action_id, int step, int steps)
{
    (void)action_id;
    (void)step;
    (void)steps;
}

void rt_trace_exit(void)
{
}

void rt_trace_suppressed(int event_id, int priority, int owner_event_id,
                         int owner_priority, const char *command)
{
    (void)event_id;
    (void)priority;
    (void)owner_event_id;
    (void)owner_priority;
    (void)command;
}

void rt_trace_mode(int mode)
{
    (void)mode;
}

void rt_trace_set(int id, int value)
{
    (void)id;
    (void)value;
}

void rt_name_mode(int mode, const char *name)
{
    (void)mode;
    (void)name;
}

void rt_name_var(int id, const char *name)
{
    (void)id;
    (void)name;
}

void rt_new_action(int action_id, action_func f)
{
    (void)action_id;
    (void)f;
}

void rt_new_event(int event_id, event_func f)
{
    (void)event_id;
    (void)f;
}

void rt_geometry(long wheel_circumference_um, long axle_um, long steps_per_rev)
{
    (void)wheel_circumference_um;
    (void)axle_um;
    (void)steps_per_rev;
}

void rt_name_action(int action_id, const char *name)
{
    (void)action_id;
    (void)name;
}

void rt_name_steps(int action_id, const char *const *names, int count)
{
    (void)action_id;
    (void)names;
    (void)count;
}

void rt_name_event(int event_id, const char *name)
{
    (void)event_id;
    (void)name;
}

/* The seed of `random`: the low bits of the sensors' noise at start, and
 * the system time. */
unsigned long rt_platform_seed(void)
{
    unsigned long seed = (unsigned long)chVTGetSystemTime();
    unsigned n;

    for (n = 0; n < 8; n++)
        seed = (seed << 4) ^ (seed >> 28) ^ (unsigned long)e_get_ambient_light(n)
               ^ ((unsigned long)e_get_prox(n) << 12);
    return seed;
}
