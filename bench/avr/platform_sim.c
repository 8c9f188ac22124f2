/*
 * platform_sim.c - the runtime's platform layer (rt_platform.h) for the
 * AVR runs of bench/robot_bench.py under simavr.  Like platform_robot.c,
 * with two differences: the millisecond is advanced by calling the
 * agendas (epuck_avr_tick) instead of waiting for the timer interrupt, and
 * every poll is marked on port B so that the simavr harness
 * (simavr_polls.c) can count its cycles:
 *     PORTB = 2  a poll starts (rt_platform_idle returns)
 *     PORTB = 1  a poll has ended (rt_platform_idle is entered)
 */
#include <avr/io.h>

#include "rt_platform.h"
#include "epuck_avr.h"

void rt_platform_init(void)
{
    DDRB = 0xFF;
}

void rt_platform_idle(void)
{
    PORTB = 1;
    epuck_avr_tick();
    PORTB = 2;
}

void rt_trace_event(int event_id) { (void)event_id; }
void rt_trace_action(int action_id, int step, int steps)
{
    (void)action_id;
    (void)step;
    (void)steps;
}
void rt_trace_exit(void) {}
void rt_new_action(int action_id, action_func f) { (void)action_id; (void)f; }
void rt_new_event(int event_id, event_func f) { (void)event_id; (void)f; }
void rt_geometry(long wheel_circumference_um, long axle_um, long steps_per_rev)
{
    (void)wheel_circumference_um;
    (void)axle_um;
    (void)steps_per_rev;
}
void rt_name_action(int action_id, const char *name) { (void)action_id; (void)name; }
void rt_name_event(int event_id, const char *name) { (void)event_id; (void)name; }
void rt_name_steps(int action_id, const char *const *names, int count)
{
    (void)action_id;
    (void)names;
    (void)count;
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
void rt_trace_mode(int mode) { (void)mode; }
void rt_name_mode(int mode, const char *name) { (void)mode; (void)name; }
void rt_trace_set(int id, int value) { (void)id; (void)value; }
void rt_trace_motors(int active, int owner_event_id) { (void)active; (void)owner_event_id; }
void rt_name_var(int id, const char *name) { (void)id; (void)name; }
unsigned long rt_platform_seed(void) { return 1UL; }
