/*
 * outputs.c - the robot's LEDs, as the e-puck library drives them
 * (motor_led/e_led.h and advance_one_timer/e_led.h's effects, written from
 * the library's documented behaviour; none of its code): the latches of
 * their pins (LED0 is _LATA6, ../epuck_api/motor_led/e_epuck_ports.h),
 * which a program writes through the library or itself; and the records
 * the trace gets of the robot's outputs.
 *
 * Records on change.  The observer (the platform's trace) is told of the
 * LEDs when they differ from what it was last told: before any other
 * record is written, as they are then (stub_outputs_flush, which the
 * platforms' record writers call first), and when a simulated ms ends, as
 * the eye saw them in it (stub_outputs_ms_end: by main's clock, a LED on
 * for at least a tenth of the ms was lit, if dimmer: a program that clears
 * and sets its LEDs in every turn of a loop leaves them lit, and the trace
 * has nothing to say).  The devices' records (sounds, IR messages, RGB LEDs)
 * are told as they happen (stub_observe), after the LEDs.
 */
#include <stddef.h>

#include "epuck_stub.h"
#include "library_sim.h"
#include "p30F6014A.h"
#include "motor_led/e_epuck_ports.h"
#include "motor_led/e_led.h"
#include "motor_led/advance_one_timer/e_led.h"
#include "motor_led/advance_one_timer/e_agenda.h"

/* ---- the pins -------------------------------------------------------------------
 * A write to an output pin's PORT bit is a write to its latch, as on the
 * chip; an output pin's PORT bit reads its latch, an input's what the
 * simulation put there (the selector's, dspic.c's idle levels). */
typedef struct {
    volatile unsigned int *port, *lat, *tris;
    unsigned int shown;     /* the PORT word as last put there */
} port_view;

static port_view ports[] = {
    { &PORTA, &LATA, &TRISA, 0u }, { &PORTB, &LATB, &TRISB, 0u }, { &PORTC, &LATC, &TRISC, 0u },
    { &PORTD, &LATD, &TRISD, 0u }, { &PORTF, &LATF, &TRISF, 0x0040u }, { &PORTG, &LATG, &TRISG, 0u },
};

static void sync_ports(void)
{
    size_t i;
    for (i = 0; i < sizeof ports / sizeof ports[0]; i++) {
        port_view *p = &ports[i];
        unsigned int outputs = ~*p->tris & 0xFFFFu;
        unsigned int written = (*p->port ^ p->shown) & outputs;
        if (written != 0u)
            *p->lat = (*p->lat & ~written) | (*p->port & written);
        *p->port = (*p->port & ~outputs) | (*p->lat & outputs);
        p->shown = *p->port;
    }
}

static int pin(int n)
{
    switch (n) {
    case 0: return LED0;
    case 1: return LED1;
    case 2: return LED2;
    case 3: return LED3;
    case 4: return LED4;
    case 5: return LED5;
    case 6: return LED6;
    case 7: return LED7;
    case 9: return BODY_LED;
    case 10: return FRONT_LED;
    default: return 0;
    }
}

static int shown[11];           /* what the observer was last told, by stub_led's number */

/* LED n as the trace has it */
int stub_led(int n)
{
    return n >= 0 && n < 11 ? shown[n] : 0;
}

/* ---- each LED's time on in the ms going on ---------------------------------------- */

static int level[11];                   /* as last marked */
static int at_end[11];                  /* the pins when the last ms ended */
static unsigned long long marked;       /* main's clock then */
static unsigned long long on_for[11], ms_began;

/* main's clock: the time the LEDs were as they were */
static unsigned long long main_now(void)
{
    return stub_main_hook != NULL ? stub_main_hook() : 0ULL;
}

/* The LEDs' levels up to now were what they were when last marked: now by
 * main's clock, but not past the ms going on (main's clock runs ahead of
 * the simulation's in a long call, wait(15000) say, whose ms are taken
 * one by one after it). */
static void mark(void)
{
    unsigned long long now = main_now(),
        ms_end = stub_ms_began_cycles() + (unsigned long long)STUB_FCY / 1000ULL;
    int n;
    if (now > ms_end)
        now = ms_end;
    if (now < marked)
        now = marked;
    sync_ports();
    for (n = 0; n < 11; n++) {
        if (level[n] && now > marked)
            on_for[n] += now - marked;
        level[n] = pin(n);
    }
    marked = now;
}

/* ---- the records ------------------------------------------------------------------- */

static stub_observer observer;
static int flushing;

void stub_set_observer(stub_observer f)
{
    observer = f;
}

void stub_observe(const char *device, const char *name, int value)
{
    stub_outputs_flush();
    if (observer != NULL)
        observer(device, name, value);
}

/* The observer told of the LEDs that differ from what it was last told. */
static void tell(const int now[11])
{
    static const char *const names[11] = {
        "led0", "led1", "led2", "led3", "led4", "led5", "led6", "led7", "all", "body", "front"
    };
    int n, k = 0, changed[11], ring_changed = 0;
    if (flushing)
        return;
    flushing = 1;
    for (n = 0; n < 8; n++)
        if (now[n] != shown[n])
            ring_changed++;
    for (n = 0; n < 11; n++)
        if (n != 8 && now[n] != shown[n] && !(n < 8 && ring_changed == 8))
            changed[k++] = n;
    for (n = 0; n < 11; n++)
        if (n != 8)
            shown[n] = now[n];          /* every record shows the LEDs as they are now */
    if (ring_changed == 8 && observer != NULL)      /* the whole ring: one record */
        observer("led", "all", now[0]);
    for (n = 0; n < k; n++)
        if (observer != NULL)
            observer("led", names[changed[n]], now[changed[n]]);
    flushing = 0;
}

/* what changed since the last ms's end (else what it decided stands) */
static void changes(void)
{
    int now[11], n;
    sync_ports();
    for (n = 0; n < 11; n++) {
        now[n] = pin(n) != at_end[n] ? pin(n) : shown[n];
        at_end[n] = pin(n);
    }
    tell(now);
}

/* before another record: the LEDs as they are, when nothing of main's
 * clock went by in the ms so far (a poll of the rules, an agenda: the
 * record of a change comes before the next record, in order); else at the
 * ms's end, as the eye saw them (not a moment between two calls of main's) */
void stub_outputs_flush(void)
{
    if (flushing || main_now() > stub_ms_began_cycles())
        return;
    changes();
}

/* the ms ends: the LEDs that were on for a tenth of it at least; when it
 * took no time of main's clock (a poll of the rules), as they are */
void stub_outputs_ms_end(void)
{
    int now[11], n;
    unsigned long long length;
    if (flushing)
        return;
    mark();
    length = marked - ms_began;
    if (length == 0) {
        changes();
        return;
    }
    for (n = 0; n < 11; n++) {
        now[n] = 10ULL * on_for[n] >= length;
        on_for[n] = 0;
        at_end[n] = level[n];
    }
    ms_began = marked;
    tell(now);
}

/* the run ends: the UARTs' last words, the LEDs as they are */
void stub_outputs_end(void)
{
    stub_uart_end();
    stub_outputs_ms_end();
}

/* the library's own writes to the pins (e_display_angle); a program's
 * (LED3 = 1) count from its next call of the library (cmain.c), or the
 * ms's end */
void stub_outputs_mark(void)
{
    mark();
}

/* a reset clears the latches (dspic.c); the trace learns it at the next flush */
void stub_outputs_reset(void)
{
    size_t i;
    for (i = 0; i < sizeof ports / sizeof ports[0]; i++)
        ports[i].shown = *ports[i].port;
}

/* ---- the library's LED functions ---------------------------------------------------- */

#define COST() do { if (stub_cost_hook != NULL) stub_cost_hook(1L, STUB_CALL_CYCLES); } while (0)

/* 0 off, 1 on, more: toggled; a led_number other than 0..7 sets all eight
 * to the value's low bit, as the library's assignment to each pin does */
void e_set_led(unsigned int led_number, unsigned int value)
{
    COST();
    mark();
    switch (led_number) {
    case 0: LED0 = value > 1 ? LED0 ^ 1u : value; break;
    case 1: LED1 = value > 1 ? LED1 ^ 1u : value; break;
    case 2: LED2 = value > 1 ? LED2 ^ 1u : value; break;
    case 3: LED3 = value > 1 ? LED3 ^ 1u : value; break;
    case 4: LED4 = value > 1 ? LED4 ^ 1u : value; break;
    case 5: LED5 = value > 1 ? LED5 ^ 1u : value; break;
    case 6: LED6 = value > 1 ? LED6 ^ 1u : value; break;
    case 7: LED7 = value > 1 ? LED7 ^ 1u : value; break;
    default:
        value &= 1u;
        LED0 = value; LED1 = value; LED2 = value; LED3 = value;
        LED4 = value; LED5 = value; LED6 = value; LED7 = value;
        break;
    }
    mark();
}

/* the eight ring LEDs off (not the body's nor the front's) */
void e_led_clear(void)
{
    COST();
    mark();
    LED0 = 0; LED1 = 0; LED2 = 0; LED3 = 0; LED4 = 0; LED5 = 0; LED6 = 0; LED7 = 0;
    mark();
}

void e_set_body_led(unsigned int value)
{
    COST();
    mark();
    BODY_LED = value > 1 ? BODY_LED ^ 1u : value;
    mark();
}

void e_set_front_led(unsigned int value)
{
    COST();
    mark();
    FRONT_LED = value > 1 ? FRONT_LED ^ 1u : value;
    mark();
}

/* ---- the effects: agenda callbacks, one step a call -------------------------------- */

#define TOGGLE 2

void e_blink_led(void)
{
    mark();
    LED0 = ~LED0; LED1 = ~LED1; LED2 = ~LED2; LED3 = ~LED3;
    LED4 = ~LED4; LED5 = ~LED5; LED6 = ~LED6; LED7 = ~LED7;
    mark();
}

void e_blink_led0(void) { e_set_led(0, TOGGLE); }
void e_blink_led1(void) { e_set_led(1, TOGGLE); }
void e_blink_led2(void) { e_set_led(2, TOGGLE); }
void e_blink_led3(void) { e_set_led(3, TOGGLE); }
void e_blink_led4(void) { e_set_led(4, TOGGLE); }
void e_blink_led5(void) { e_set_led(5, TOGGLE); }
void e_blink_led6(void) { e_set_led(6, TOGGLE); }
void e_blink_led7(void) { e_set_led(7, TOGGLE); }

void e_start_led_blinking(int cycle)
{
    e_activate_agenda(e_blink_led, cycle);
}

void e_stop_led_blinking(void)
{
    e_destroy_agenda(e_blink_led);
}

void e_set_blinking_cycle(int cycle)
{
    if (cycle >= 0)
        e_set_agenda_cycle(e_blink_led, cycle);
}

/* Toggle the LEDs of `pair` (-1: none). */
static void toggle_pair(const int pair[2])
{
    if (pair[0] >= 0)
        e_set_led((unsigned int)pair[0], TOGGLE);
    if (pair[1] >= 0)
        e_set_led((unsigned int)pair[1], TOGGLE);
}

/* A wave from the front to the back along both sides, on then off. */
void flow_led(void)
{
    static const int wave[5][2] = { {0, -1}, {1, 7}, {2, 6}, {3, 5}, {4, -1} };
    static int step;
    toggle_pair(wave[step]);
    step = (step + 1) % 5;
}

/* One light around the ring. */
void snake_led(void)
{
    static int lit;
    e_set_led((unsigned int)((lit + 7) % 8), 0);
    e_set_led((unsigned int)lit, 1);
    lit = (lit + 1) % 8;
}

/* One light swinging over the front LEDs: 1, 0, 7, 0, 1 ... */
void k2000_led(void)
{
    static const int swing[4] = {1, 0, 7, 0};
    static int lit, step;
    e_set_led((unsigned int)lit, 0);
    lit = swing[step];
    e_set_led((unsigned int)lit, 1);
    step = (step + 1) % 4;
}

/* A wave over one side, then all off: right (1, 2, 3 with 0 and 4), left
 * (7, 6, 5). */
static void side_wave(const int steps[3][2], int *step)
{
    if (*step < 3)
        toggle_pair(steps[*step]);
    else
        e_led_clear();
    *step = (*step + 1) % 4;
}

void right_led(void)
{
    static const int steps[3][2] = { {0, 4}, {1, 3}, {2, -1} };
    static int step;
    side_wave(steps, &step);
}

void left_led(void)
{
    static const int steps[3][2] = { {0, 4}, {7, 5}, {6, -1} };
    static int step;
    side_wave(steps, &step);
}
