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
 *     L t name state           an LED changed (name: led0..led7, all, body, front)
 *     X t left right           exit_main
 *     T t left right           the time limit (INT16_LIMIT_MS) was reached
 * After X or T the AVR stops (cli; sleep), which ends the simulation.
 *
 * With the robot's tracer (EPUCKRT_TRACE: `epuckc run --int16
 * --robot-trace`) the trace is rt_trace.c's instead, its frames on the
 * USART0 (uart1_avr.c, the e-puck library's UART1 there), which simavr_run
 * writes to a file for the monitor's decoder; the hooks above are not
 * compiled (INT16_ROBOT_TIME without EPUCKRT_TRACE: the robot's time and no
 * trace at all, the hooks doing nothing as platform_robot.c's: what the
 * tracer's cost is measured against, bench/trace_bench.py).  Time is then
 * the robot's: a ms is 16000 cycles of Timer1 (1 ms at 16 MHz), and the
 * poll waits for its end asleep (simavr skips the cycles), as
 * platform_robot.c's waits for the agenda's tick, while the UART's
 * interrupt sends at its own pace; each poll's cycles are measured on
 * Timer1 (from the start of its ms: the virtual robot's ms included); at
 * the end one more line goes out on GPIOR0:
 *     P polls max_cycles overruns max_ms total_cycles
 * (overruns: polls longer than their ms; max_ms: the ms of the longest).
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

__attribute__((noreturn)) static void stop(void)
{
    cli();
    sleep_cpu();
    for (;;) {
    }
}

#if defined(EPUCKRT_TRACE) && !defined(INT16_ROBOT_TIME)
#define INT16_ROBOT_TIME 1
#endif
#if defined(INT16_ROBOT_TIME) && defined(INT16_C_MAIN)
#error "the robot's time on the 16-bit path takes a rule program, not a C main"
#endif

#ifndef INT16_ROBOT_TIME
/* kind, the time, then the `count` numbers of v (the LEDs first, when
 * they changed: host/outputs.c) */
static void numbers(char kind, int count, const long *v)
{
    int i;
    stub_outputs_flush();
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

/* The simulator's ms ends (a rule program's poll cycle, a C main's Timer1
 * interrupt): its LEDs, the end of the time, then the next ms as the
 * host's platform makes it. */
static void pass_ms(void)
{
    stub_outputs_ms_end();
    if (now_ms >= INT16_LIMIT_MS) {
        stub_outputs_end();
        line('T', 2, stub_total_steps_left(), stub_total_steps_right(), 0);
        stop();
    }
    stub_motors_1ms();
    now_ms++;
    int16_scenario(now_ms);
    stub_devices_ms(now_ms, 1);
    stub_agendas_1ms();
}
#endif

#ifdef INT16_C_MAIN
/*
 * A C program with its own main (INT16_C_MAIN): main runs at the AVR's own
 * speed and the simulator's millisecond is Timer1's interrupt, every 16000
 * cycles (1 ms at 16 MHz), as the agendas' timer interrupt on the dsPIC:
 * the wheels move, the scenario applies, the LED pins are read, the agendas
 * run, inside the interrupt, in none of main's time (it sets Timer1 back).
 * wait(n) and e_calibrate_ir's busy loops
 * last what they last on the dsPIC (n turns of 6 cycles at 14.7456 MHz).
 */
#include <util/atomic.h>

#include "utility/utility.h"

#define AVR_CYCLES_PER_MS 16000UL

/* the ms and the AVR cycles into it, now */
static void now_parts(unsigned long *ms, unsigned int *counter)
{
    ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
        *counter = TCNT1;
        *ms = (unsigned long)now_ms;
        if (TIFR1 & _BV(OCF1A))         /* a tick is due, not yet counted */
            ++*ms, *counter = TCNT1;
    }
}

/* AVR cycles since start */
static unsigned long long now_cycles(void)
{
    unsigned long ms;
    unsigned int counter;
    now_parts(&ms, &counter);
    return (unsigned long long)ms * AVR_CYCLES_PER_MS + counter;
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

/* The simulator's ms.  Its work (the devices, the LEDs' records, the
 * agendas) takes none of main's time, as on the host: Timer1 is set back
 * to where it was when the interrupt began, so each ms gives main its
 * 16000 cycles however long the simulation took over it. */
ISR(TIMER1_COMPA_vect)
{
    unsigned int began = TCNT1;
    pass_ms();
    TCNT1 = began;
    TIFR1 = _BV(OCF1A);         /* a match during the work: not main's */
}

/* the dsPIC's cycles of main's clock (AVR cycles x 14.7456 / 16 = x 576 /
 * 625), without a 64-bit division (stub_outputs_ms_end calls it in the
 * interrupt, which must leave main most of each ms): 5 ms are 73728
 * cycles exactly, the rest (< 80000 AVR cycles) in 32 bits */
static unsigned long long dspic_cycles(void)
{
    unsigned long ms;
    unsigned int counter;
    now_parts(&ms, &counter);
    return (unsigned long long)(ms / 5UL) * 73728ULL
           + ((ms % 5UL) * AVR_CYCLES_PER_MS + counter) * 576UL / 625UL;
}

/* before main: the harness starts, then Timer1 (CTC, no prescaler) */
void int16_start(void) __attribute__((naked, used, section(".init8")));
void int16_start(void)
{
    rt_platform_init();
    stub_cost_hook = busy;
    stub_clock_hook = dspic_cycles;
    stub_main_hook = dspic_cycles;
    OCR1A = (unsigned int)(AVR_CYCLES_PER_MS - 1UL);
    TCCR1A = 0;
    TCCR1B = _BV(WGM12) | _BV(CS10);
    TIMSK1 = _BV(OCIE1A);
    sei();
}

#endif

#ifndef INT16_ROBOT_TIME
/* what epuck_more.c reports (the UART): R t kind name extra */
void host_record(const char *kind, const char *name, const char *extra, const char *text)
{
    (void)text;
    stub_outputs_flush();
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

/* the run ends with `status`: the record, then the AVR stops */
void host_stop(const char *kind, const char *name, const char *extra, const char *text,
               int status)
{
    (void)status;
    stub_outputs_end();
    host_record(kind, name, extra, text);
    line('T', 2, stub_total_steps_left(), stub_total_steps_right(), 0);
    stop();
}

void stub_unsimulated(const char *function, const char *device)
{
    (void)device;
    host_stop("unsimulated", function, "", "", 6);
}
#endif

#ifndef INT16_ROBOT_TIME
void rt_platform_idle(void)
{
    pass_ms();
}
#endif

#ifdef INT16_ROBOT_TIME
/*
 * The robot's time and the tracer (see the top of the file).  Timer1 counts
 * the 16000 cycles of each ms (CTC, no prescaler); its interrupt only
 * counts the periods.  The poll waits asleep for the end of its ms, then
 * the ms passes as on the host (the wheels, the scenario, the agendas: the
 * clock ticks) and the next poll starts.  A poll that took longer than its
 * ms is an overrun: its ms is stretched to the poll's end, so that the
 * trace stays the host's, and it is counted (the robot would have skipped
 * a ms there: platform_robot.c waits for the next tick).
 */
#include <avr/sleep.h>

#define CYCLES_PER_MS 16000U

static volatile unsigned char periods;  /* Timer1 periods since this ms began */
static unsigned long polls, overruns, max_cycles, total_cycles;
static long max_at;                     /* the ms of the longest poll */

ISR(TIMER1_COMPA_vect)
{
    if (periods < 255u)
        periods++;
}

static void poll_stats(void)
{
    put_text("P ");
    put_long((long)polls);
    put_char(' ');
    put_long((long)max_cycles);
    put_char(' ');
    put_long((long)overruns);
    put_char(' ');
    put_long(max_at);
    put_char(' ');
    put_long((long)total_cycles);
    put_char('\n');
}

/* main returned (after exit_main and the tracer's flush): stop */
void int16_end(void) __attribute__((naked, used, section(".fini8")));
void int16_end(void)
{
    poll_stats();
    stop();
}

static unsigned long long robot_cycles(void);

void rt_platform_init(void)
{
    stub_clock_hook = robot_cycles;
    int16_scenario(0L);
    OCR1A = (unsigned int)(CYCLES_PER_MS - 1U);
    TCCR1A = 0;
    TCNT1 = 0;
    TCCR1B = _BV(WGM12) | _BV(CS10);
    TIMSK1 = _BV(OCIE1A);
    sei();
}

void rt_platform_idle(void)
{
    unsigned long cycles;
    unsigned char late;

    cli();
    late = periods;
    cycles = (unsigned long)late * CYCLES_PER_MS + TCNT1;
    sei();
    if (now_ms > 0) {           /* the ms that ends now: its poll's cycles */
        polls++;
        total_cycles += cycles;
        if (cycles > max_cycles) {
            max_cycles = cycles;
            max_at = now_ms;
        }
    }
    if (now_ms >= INT16_LIMIT_MS) {
#ifdef EPUCKRT_TRACE
        rt_tracer_timeout();
#endif
        poll_stats();
        stop();
    }
    if (late > 0 && now_ms > 0) {
        overruns++;             /* the next ms starts now */
        cli();
        TCNT1 = 0;
        TIFR1 = _BV(OCF1A);
        periods = 0;
        sei();
    } else {
        for (;;) {              /* asleep until the ms ends */
            cli();
            if (periods > 0)
                break;
            sleep_enable();
            sei();
            sleep_cpu();        /* sei; sleep: no interrupt comes between them */
            sleep_disable();
        }
        periods = 0;
        sei();
    }
    stub_motors_1ms();
    now_ms++;
    int16_scenario(now_ms);
    stub_agendas_1ms();
}

/* The library's clock, the robot's ms in dsPIC cycles (FCY 14.7456 MHz: 5
 * ms are 73728 cycles exactly; no 64-bit division).  Its devices are not
 * stepped each ms here (stub_devices_ms: their work took over a third of the
 * poll's 16000 cycles on the AVR, and on the robot it is the hardware's,
 * not the CPU's): what a rule program reads of them (the accelerometer)
 * the library's simulation works out from this clock when it is read. */
static unsigned long long robot_cycles(void)
{
    unsigned long ms = (unsigned long)now_ms;
    return (unsigned long long)(ms / 5UL) * 73728ULL + (ms % 5UL) * 73728UL / 5UL;
}

/* The library's simulation reports nothing here (the trace is the
 * tracer's, or none); a call of what it does not simulate (not in a rule
 * program's runtime) stops the run as the end of the time does. */
void host_record(const char *kind, const char *name, const char *extra, const char *text)
{
    (void)kind;
    (void)name;
    (void)extra;
    (void)text;
}

void host_stop(const char *kind, const char *name, const char *extra, const char *text,
               int status)
{
    (void)kind;
    (void)name;
    (void)extra;
    (void)text;
    (void)status;
    poll_stats();
    stop();
}

void stub_unsimulated(const char *function, const char *device)
{
    (void)device;
    host_stop("unsimulated", function, "", "", 6);
}

#ifndef EPUCKRT_TRACE
/* no trace at all, as on a robot built without --trace */
void rt_trace_event(int event_id) { (void)event_id; }
void rt_trace_action(int action_id, int step, int steps)
{
    (void)action_id;
    (void)step;
    (void)steps;
}
void rt_trace_exit(void) {}
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
void rt_trace_set(int id, int value) { (void)id; (void)value; }
void rt_trace_motors(int active, int owner_event_id) { (void)active; (void)owner_event_id; }
#endif
#else
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
    stub_outputs_end();
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
#endif
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
