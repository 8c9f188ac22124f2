/*
 * trace_cost.c - the robot's tracer (runtime_c/rt_trace.c) alone on the
 * AVR, for bench/trace_bench.py: each hook called once, timed by
 * simavr_cycles.c (GPIOR1 = 1; call; GPIOR1 = 2), with the bytes it puts
 * on the wire.  Three rounds: with the link busy sending (the record
 * queued: what a poll pays, as on a robot whose link has frames in
 * flight), then the link free, one poll framing and handing it every
 * record queued (the framing's cost, paid at the link's pace), then with
 * the ring full (the record dropped and counted).  The clock and the
 * wheels' counters are plain variables; output lines on GPIOR0:
 *     NAME @CYCLES BYTES        (framing: "framed-N @CYCLES BYTES", N records)
 */
#include <avr/io.h>
#include <avr/interrupt.h>
#include <avr/sleep.h>

#include "rt_platform.h"

static volatile unsigned long clock_ms = 1234;
static unsigned long taken;
static int busy = 1, taking = 1;

long rt_millis(void) { return (long)clock_ms; }
int e_get_steps_left(void) { return 1200; }
int e_get_steps_right(void) { return -800; }
void rt_trace_port_start(void) {}
int rt_trace_port_busy(void) { return busy; }
int rt_trace_port_send(const unsigned char *bytes, int n)
{
    (void)bytes;
    if (!taking)
        return 0;
    taken += (unsigned long)n;
    return n;
}
void rt_trace_port_wait(void) {}

static void out(const char *s)
{
    while (*s != '\0')
        GPIOR0 = (unsigned char)*s++;
}

static void out_number(unsigned long v)
{
    char digits[12];
    int n = 0;
    do {
        digits[n++] = (char)('0' + (int)(v % 10UL));
        v /= 10UL;
    } while (v != 0UL);
    while (n > 0)
        GPIOR0 = (unsigned char)digits[--n];
}

static void t_event(void) { rt_trace_event(5); }
static void t_action(void) { rt_trace_action(5, -1, 0); }
static void t_step(void) { rt_trace_action(5, 1, 3); }
static void t_set(void) { rt_trace_set(3, 1234); }
static void t_suppressed(void) { rt_trace_suppressed(4, 0, 2, 1, "start_curve"); }
static void t_mode(void) { rt_trace_mode(2); }
static void t_motors(void) { rt_trace_motors(1, 5); }
static void t_led(void) { rt_tracer_led(9, 1); }
static void t_sound(void) { rt_tracer_sound(2); }
static void t_poll(void) { rt_tracer_poll(); }

static const struct {
    const char *name;
    void (*call)(void);
} hooks[] = {
    {"event", t_event}, {"action", t_action}, {"step", t_step}, {"set", t_set},
    {"suppressed", t_suppressed}, {"mode", t_mode}, {"motors", t_motors}, {"led", t_led},
    {"sound", t_sound}, {"poll", t_poll},
};

static void round_of(const char *prefix)
{
    unsigned k;
    for (k = 0; k < sizeof hooks / sizeof hooks[0]; k++) {
        out(prefix);
        out(hooks[k].name);
        GPIOR1 = 1;
        hooks[k].call();
        GPIOR1 = 2;
        out("\n");
    }
}

int main(void)
{
    unsigned long before;
    int k;

    rt_tracer_poll();           /* the hello goes out; the link is busy with it */
    round_of("");
    busy = 0;                   /* the link is free: a poll frames what waits */
    before = taken;
    out("framed-");
    out_number(sizeof hooks / sizeof hooks[0] - 1u);      /* the poll queues nothing */
    GPIOR1 = 1;
    rt_tracer_poll();
    GPIOR1 = 2;
    out(" ");
    out_number(taken - before);
    out("\n");
    busy = 1;
    taking = 0;
    for (k = 0; k < 200; k++)   /* the ring fills */
        rt_trace_set(1, k);
    round_of("dropped-");
    cli();
    sleep_cpu();
    return 0;
}
