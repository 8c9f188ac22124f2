/*
 * platform_robot.c - the runtime's platform layer on the e-puck itself.
 *
 * The core (epuckrt.c) already initialises the e-puck library in the
 * agenda variant's order (e_init_port, e_start_agendas_processing,
 * e_init_motors, e_init_ad_scan(ALL_ADC)) and starts the 1 ms clock agenda,
 * so that the robot and the host harness share one code path.  What is left
 * here is waiting for the clock, and trace hooks that do nothing: without
 * `--trace` a robot build has no trace; with it (EPUCKRT_TRACE) the hooks
 * are the tracer's (rt_trace.c) and these are not compiled.  The e-puck2
 * shares the hooks and the seed; its wait for the clock is
 * platform_epuck2.c's (EPUCKRT_EPUCK2).
 */
#include "rt_platform.h"
#include "a_d/advance_ad_scan/e_prox.h"

#ifndef EPUCKRT_EPUCK2
void rt_platform_init(void)
{
}

/* One poll cycle per millisecond: wait until the clock agenda has ticked. */
void rt_platform_idle(void)
{
    long start = rt_millis();
    while (rt_millis() == start) {
        /* busy wait; the agenda runs in the Timer2 interrupt */
    }
}
#endif

#ifndef EPUCKRT_TRACE
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

void rt_trace_motors(int active, int owner_event_id)
{
    (void)active;
    (void)owner_event_id;
}
#endif

void rt_name_var(int id, const char *name)
{
    (void)id;
    (void)name;
}

/* The seed of `random`: the low bits of the sensors' noise at start. */
unsigned long rt_platform_seed(void)
{
    unsigned long seed = 0;
    unsigned n;

    for (n = 0; n < 8; n++)
        seed = (seed << 4) ^ (seed >> 28) ^ (unsigned long)e_get_ambient_light(n)
               ^ ((unsigned long)e_get_prox(n) << 12);
    return seed;
}

void rt_name_mode(int mode, const char *name)
{
    (void)mode;
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

/* The robot needs no odometry: the core converts with the geometry itself. */
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

void rt_name_event(int event_id, const char *name)
{
    (void)event_id;
    (void)name;
}

void rt_name_steps(int action_id, const char *const *names, int count)
{
    (void)action_id;
    (void)names;
    (void)count;
}
