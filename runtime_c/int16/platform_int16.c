/*
 * platform_int16.c - the runtime's platform layer for `epuckc run --int16`:
 * the program, its extern C and the runtime built for an ATmega1284P (16-bit
 * int, like the dsPIC) over the host's virtual robot (host/epuck_stub.c,
 * EPUCK_STUB_NO_POSE), run on simavr (simavr_run.c).  Each ms: the wheels
 * move, the scenario's lines due apply (int16_scenario, written by
 * epuckc/sim/int16.py from the scenario file), the agendas run.  The trace
 * goes out byte by byte through GPIOR0, one line a record:
 *     E t id left right        an event fired (steps of each wheel since start)
 *     A t id step steps        an action ran (step -1: not a sequence's)
 *     S t var value            a variable changed
 *     U t id                   a motor command of event id suppressed
 *     M t mode                 the current mode changed
 *     L t name state           an LED command (name: led0..led7, all, body, front)
 *     X t left right           exit_main
 *     T t left right           the time limit (INT16_LIMIT_MS) was reached
 * After X or T the AVR stops (cli; sleep), which ends the simulation.
 */
#include <avr/io.h>
#include <avr/interrupt.h>
#include <avr/sleep.h>

#include "rt_platform.h"
#include "epuck_stub.h"

#ifndef INT16_LIMIT_MS
#define INT16_LIMIT_MS 60000L
#endif

void int16_scenario(long t_ms);     /* the scenario's lines due at t_ms */

static long now_ms;

static void put_char(char c)
{
    GPIOR0 = (unsigned char)c;
}

static void put_text(const char *s)
{
    while (*s != '\0')
        put_char(*s++);
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

/* kind, the time, then `count` numbers */
static void line(char kind, int count, long a, long b, long c)
{
    long v[3];
    int i;
    v[0] = a;
    v[1] = b;
    v[2] = c;
    put_char(kind);
    put_char(' ');
    put_long(now_ms);
    for (i = 0; i < count; i++) {
        put_char(' ');
        put_long(v[i]);
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

static void observe(const char *device, const char *name, int value)
{
    if (device[0] != 'l')
        return;                 /* sounds: not traced here */
    put_text("L ");
    put_long(now_ms);
    put_char(' ');
    put_text(name);
    put_char(' ');
    put_long(value);
    put_char('\n');
}

void rt_platform_init(void)
{
    stub_set_observer(observe);
    int16_scenario(0L);
}

void rt_platform_idle(void)
{
    if (now_ms >= INT16_LIMIT_MS) {
        line('T', 2, stub_total_steps_left(), stub_total_steps_right(), 0);
        stop();
    }
    stub_motors_1ms();
    now_ms++;
    int16_scenario(now_ms);
    stub_agendas_1ms();
}

void rt_trace_event(int event_id)
{
    line('E', 3, event_id, stub_total_steps_left(), stub_total_steps_right());
}

void rt_trace_action(int action_id, int step, int steps)
{
    line('A', 3, action_id, step, steps);
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
unsigned long rt_platform_seed(void)
{
#ifdef INT16_SEED
    return INT16_SEED;
#else
    return 1UL;
#endif
}
