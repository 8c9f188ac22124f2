/*
 * platform_trace.c - the runtime's platform layer for running a program on
 * simavr (ATmega1284P: 16-bit int) over the host's virtual robot
 * (runtime_c/host/epuck_stub.c, built with EPUCK_STUB_NO_POSE) and printing
 * its trace, so that the trace of the 16-bit build can be compared with the
 * host's (tests/runtime/test_avr_trace.py).  One line per record, written
 * byte by byte to GPIOR0, which simavr_trace.c prints:
 *     E t id left right     an event fired (steps of each wheel since start)
 *     S t var value         a variable changed (var: its number)
 *     U t id                a motor command of event id suppressed
 *     M t mode              the current mode changed
 *     X t left right        exit_main
 *     T t left right        the time limit (TRACE_LIMIT_MS) was reached
 * After X or T the AVR stops (cli; sleep), which ends the simulation.
 */
#include <avr/io.h>
#include <avr/interrupt.h>
#include <avr/sleep.h>

#include "rt_platform.h"
#include "epuck_stub.h"

#ifndef TRACE_LIMIT_MS
#define TRACE_LIMIT_MS 5000L
#endif

static long now_ms;

static void put_char(char c)
{
    GPIOR0 = (unsigned char)c;
}

static void put_long(long v)
{
    char digits[12];
    int n = 0;
    unsigned long u = v < 0 ? 0UL - (unsigned long)v : (unsigned long)v;

    if (v < 0)
        put_char('-');
    do {
        digits[n++] = (char)('0' + (int)(u % 10UL));
        u /= 10UL;
    } while (u != 0UL);
    while (n > 0)
        put_char(digits[--n]);
}

static void line(char kind, int count, long a, long b, long c)
{
    put_char(kind);
    put_char(' ');
    put_long(now_ms);
    if (count > 0) {
        put_char(' ');
        put_long(a);
    }
    if (count > 1) {
        put_char(' ');
        put_long(b);
    }
    if (count > 2) {
        put_char(' ');
        put_long(c);
    }
    put_char('\n');
}

static void stop(void)
{
    cli();
    sleep_cpu();
    for (;;) {
    }
}

void rt_platform_init(void)
{
}

void rt_platform_idle(void)
{
    if (now_ms >= TRACE_LIMIT_MS) {
        line('T', 2, stub_total_steps_left(), stub_total_steps_right(), 0);
        stop();
    }
    stub_motors_1ms();
    now_ms++;
    stub_agendas_1ms();
}

void rt_trace_event(int event_id)
{
    line('E', 3, event_id, stub_total_steps_left(), stub_total_steps_right());
}

void rt_trace_action(int action_id, int step, int steps)
{
    (void)action_id;
    (void)step;
    (void)steps;
}

void rt_trace_exit(void)
{
    line('X', 2, stub_total_steps_left(), stub_total_steps_right(), 0);
    stop();
}

void rt_trace_suppressed(int event_id, int priority, int owner_event_id,
                         int owner_priority, const char *command)
{
    (void)priority;
    (void)owner_event_id;
    (void)owner_priority;
    (void)command;
    line('U', 1, event_id, 0, 0);
}

void rt_trace_mode(int mode)
{
    line('M', 1, mode, 0, 0);
}

void rt_trace_set(int id, int value)
{
    line('S', 2, id, value, 0);
}

/* who holds the motors: not compared with the host's trace */
void rt_trace_motors(int active, int owner_event_id) { (void)active; (void)owner_event_id; }

void rt_new_action(int action_id, action_func f) { (void)action_id; (void)f; }
void rt_new_event(int event_id, event_func f) { (void)event_id; (void)f; }
void rt_geometry(long wheel_circumference_um, long axle_um, long steps_per_rev)
{
    stub_set_geometry(wheel_circumference_um, axle_um, steps_per_rev);
}
void rt_name_action(int action_id, const char *name) { (void)action_id; (void)name; }
void rt_name_event(int event_id, const char *name) { (void)event_id; (void)name; }
void rt_name_steps(int action_id, const char *const *names, int count)
{
    (void)action_id;
    (void)names;
    (void)count;
}
void rt_name_mode(int mode, const char *name) { (void)mode; (void)name; }
void rt_name_var(int id, const char *name) { (void)id; (void)name; }
unsigned long rt_platform_seed(void) { return 1UL; }    /* as the host's default */
