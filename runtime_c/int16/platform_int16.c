/*
 * platform_int16.c - the runtime's platform layer for `epuckc run --int16`:
 * the program, its extern C and the runtime built for an ATmega1284P (16-bit
 * int, like the dsPIC) over the host's virtual robot (host/epuck_stub.c,
 * EPUCK_STUB_NO_POSE), run on simavr (simavr_run.c).  Each ms: the wheels
 * move, the scenario's lines due apply (int16_scenario, written by
 * epuckc/sim/int16.py from the scenario file), the agendas run.  The trace
 * goes out byte by byte through GPIOR0, one line a record:
 *     E t id left right        an event fired (steps of each wheel since start)
 *     A t id step steps left right
 *                              an action ran (step -1: not a sequence's)
 *     S t var value            a variable changed
 *     U t id left right        a motor command of event id suppressed
 *     M t mode left right      the current mode changed
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

static volatile long now_ms;

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

/* kind, the time, then the `count` numbers of v */
static void numbers(char kind, int count, const long *v)
{
    int i;
    put_char(kind);
    put_char(' ');
    put_long(now_ms);
    for (i = 0; i < count; i++) {
        put_char(' ');
        put_long(v[i]);
    }
    put_char('\n');
}

/* kind, the time, then `count` of a, b, c */
static void line(char kind, int count, long a, long b, long c)
{
    long v[3];
    v[0] = a;
    v[1] = b;
    v[2] = c;
    numbers(kind, count, v);
}

/* kind, the time, a, then the steps of each wheel since the start (the
   host's trace gives them with every record) */
static void with_steps(char kind, long a)
{
    line(kind, 3, a, stub_total_steps_left(), stub_total_steps_right());
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

#ifdef INT16_C_MAIN
/*
 * A C program with its own main (INT16_C_MAIN): main runs at the AVR's own
 * speed and the simulator's millisecond is Timer1's interrupt, every 16000
 * cycles (1 ms at 16 MHz), as the agendas' timer interrupt on the dsPIC:
 * the wheels move, the scenario applies, the LED pins are read, the agendas
 * run, inside the interrupt.  wait(n) and e_calibrate_ir's busy loops
 * last what they last on the dsPIC (n turns of 6 cycles at 14.7456 MHz).
 */
#include <util/atomic.h>

#include "utility/utility.h"

#define AVR_CYCLES_PER_MS 16000UL

/* AVR cycles since start */
static unsigned long long now_cycles(void)
{
    unsigned long long c;
    ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
        unsigned int counter = TCNT1;
        long ms = now_ms;
        if (TIFR1 & _BV(OCF1A))         /* a tick is due, not yet counted */
            ms++, counter = TCNT1;
        c = (unsigned long long)ms * AVR_CYCLES_PER_MS + counter;
    }
    return c;
}

/* n times `cycles_each` dsPIC cycles, in AVR cycles (16 / 14.7456 = 625 / 576) */
static void busy(long count, int cycles_each)
{
    unsigned long long end;
    if (count <= 1)
        return;                 /* one call: the AVR's own time for it */
    end = now_cycles() + (unsigned long long)count * (unsigned long long)cycles_each * 625ULL
          / 576ULL;
    while (now_cycles() < end) {
    }
}

ISR(TIMER1_COMPA_vect)
{
    if (now_ms >= INT16_LIMIT_MS) {
        line('T', 2, stub_total_steps_left(), stub_total_steps_right(), 0);
        stop();
    }
    stub_motors_1ms();
    now_ms++;
    int16_scenario(now_ms);
    stub_sync_led_ports();
    stub_agendas_1ms();
}

/* before main: the harness starts, then Timer1 (CTC, no prescaler) */
void int16_start(void) __attribute__((naked, used, section(".init8")));
void int16_start(void)
{
    rt_platform_init();
    stub_cost_hook = busy;
    OCR1A = (unsigned int)(AVR_CYCLES_PER_MS - 1UL);
    TCCR1A = 0;
    TCCR1B = _BV(WGM12) | _BV(CS10);
    TIMSK1 = _BV(OCIE1A);
    sei();
}

/* what epuck_more.c reports (the UART): R t kind name extra */
void host_record(const char *kind, const char *name, const char *extra, const char *text)
{
    (void)text;
    put_text("R ");
    put_long(now_ms);
    put_char(' ');
    put_text(kind);
    put_char(' ');
    put_text(name);
    put_char(' ');
    put_text(extra);
    put_char('\n');
}

/* utility.h's timing: the A/D interrupt's ticks (1/16384 s), 0.061 ms each */
static unsigned long long reset_at;

void resetTime(void)
{
    reset_at = now_cycles();
}

float getDiffTimeMs(void)
{
    unsigned long long ticks = (now_cycles() - reset_at) * 16384ULL / 16000000ULL;
    return (float)ticks * 0.061f;
}

float getDiffTimeMsAndReset(void)
{
    float v = getDiffTimeMs();
    resetTime();
    return v;
}

double stub_turn_rate_dps(void)
{
    return 0.0;                 /* no pose on the 16-bit path */
}
#endif

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
    long v[5];
    v[0] = action_id;
    v[1] = step;
    v[2] = steps;
    v[3] = stub_total_steps_left();
    v[4] = stub_total_steps_right();
    numbers('A', 5, v);
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
    with_steps('U', event_id);
}

void rt_trace_mode(int mode)
{
    with_steps('M', mode);
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
