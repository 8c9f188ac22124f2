/*
 * epuck_stub.c - the e-puck library's simulation for the host harness (the
 * prototypes of ../epuck_api/ over a virtual robot): the ports, agendas,
 * motors, odometry, proximity sensors, remote control and selector; the
 * simulation's time and its reset.  The other devices are in outputs.c
 * (LEDs and the trace's output records), sound.c (the codec and the
 * microphones), imu.c (the accelerometer and the gyroscope), camera.c,
 * stub_devices.c (IR messages, ToF), epuck_more.c (UARTs, battery, the A/D
 * scan's timing), dspic.c (the chip's registers, EEPROM, instructions).
 *
 * Motors: speeds clamped to +-1000 steps/s like the library; each wheel
 * steps whole steps (one every 1000/|speed| ms, phase restarted when the
 * speed changes), counted in a 16-bit counter that wraps like the real one,
 * and in an unwrapped total for the trace.  Odometry from the steps with the
 * default geometry of epuckrt.h.  Proximity: values set by the scenario.
 * Agendas: a fixed table, run by the host platform once per virtual ms.
 *
 * Deterministic: no real time, no randomness; the trigonometry is computed
 * here (Taylor series) so that no libm is needed and results do not depend
 * on the C library.
 */
#include <stdint.h>
#include <stddef.h>

#include "epuckrt.h"
#include "epuck_stub.h"
#include "motor_led/e_init_port.h"
#include "motor_led/advance_one_timer/e_motors.h"
#include "motor_led/advance_one_timer/e_agenda.h"
#include "a_d/advance_ad_scan/e_prox.h"
#include "a_d/advance_ad_scan/e_ad_conv.h"
#include "motor_led/e_epuck_ports.h"
#include "motor_led/advance_one_timer/e_remote_control.h"
#include "utility/utility.h"
#include "library_sim.h"

#define STUB_PI 3.14159265358979323846
static double mm_per_step = (double)EPUCK_WHEEL_CIRCUMFERENCE_UM / 1000.0 / (double)EPUCK_STEPS_PER_REV;
static double axle_mm = (double)EPUCK_AXLE_UM / 1000.0;

void stub_set_geometry(long wheel_circumference_um, long axle_um, long steps_per_rev)
{
    mm_per_step = (double)wheel_circumference_um / 1000.0 / (double)steps_per_rev;
    axle_mm = (double)axle_um / 1000.0;
}

/* ---- the C main model: what main's calls cost (cmain.c on the host) ------- */

void (*stub_cost_hook)(long count, int cycles_each);
unsigned long long (*stub_clock_hook)(void);
unsigned long long (*stub_main_hook)(void);

#define COST(cycles) do { if (stub_cost_hook != NULL) stub_cost_hook(1L, cycles); } while (0)

/* the library's busy loop, `for (i = 0; i < num; i++);` over a long */
void wait(long num)
{
    if (stub_cost_hook != NULL && num > 0)
        stub_cost_hook(num, STUB_WAIT_LOOP_CYCLES);
}

void stub_wait_cycles(long cycles)
{
    if (stub_cost_hook != NULL && cycles > 0)
        stub_cost_hook(cycles, 1);
}

/* ---- the simulation's time --------------------------------------------------- */

static long devices_ms;             /* the last ms stub_devices_ms was told of */

/* ms * STUB_FCY / 1000 exactly, without a 64-bit division (the AVR's
 * each-ms interrupt calls it: --int16): ms = 1000 s + r */
unsigned long long stub_ms_cycles(long ms)
{
    unsigned long m = ms > 0 ? (unsigned long)ms : 0UL, s = m / 1000UL, r = m % 1000UL;
    return (unsigned long long)s * STUB_FCY + r * (STUB_FCY / 1000UL)
           + r * (STUB_FCY % 1000UL) / 1000UL;
}

unsigned long long stub_now_cycles(void)
{
    if (stub_clock_hook != NULL)
        return stub_clock_hook();
    return stub_ms_cycles(devices_ms);
}

unsigned long long stub_ms_began_cycles(void)
{
    return stub_ms_cycles(devices_ms);
}

void stub_devices_ms(long now_ms, long n)
{
    devices_ms = now_ms;
    stub_sound_ms(now_ms, n);
    stub_more_ms(now_ms, n);
    stub_imu_ms(now_ms, n);
    stub_camera_ms(now_ms, n);
}

long stub_devices_next_ms(void)
{
    return stub_camera_next_ms();
}

/* ---- reset and sleep: the library's state as at the chip's reset ------------- */

void stub_reset_library(void)
{
    stub_dspic_reset_registers();
    stub_motors_reset();
    stub_outputs_reset();
    stub_sound_reset();
    stub_imu_reset();
    stub_camera_reset();
    stub_more_reset();
}

/* sleep: the system clock stops, and with it Timer2 (the agendas, which
 * step the motors on the robot) */
void stub_sleep_library(void)
{
    e_end_agendas_processing();
    e_set_speed_left(0);
    e_set_speed_right(0);
}

/* ---- ports ---------------------------------------------------------------- */

unsigned char isPresentFlag = 1;    /* the e-puck 1.3's I2C devices answered */

/* As the library: the LEDs, the IR emitters, the audio and the camera's
 * reset are outputs, off; the selector, the remote and the battery inputs. */
void e_init_port(void)
{
    COST(STUB_CALL_CYCLES);
    LED0 = 0; LED1 = 0; LED2 = 0; LED3 = 0; LED4 = 0; LED5 = 0; LED6 = 0; LED7 = 0;
    LED0_DIR = OUTPUT_PIN; LED1_DIR = OUTPUT_PIN; LED2_DIR = OUTPUT_PIN; LED3_DIR = OUTPUT_PIN;
    LED4_DIR = OUTPUT_PIN; LED5_DIR = OUTPUT_PIN; LED6_DIR = OUTPUT_PIN; LED7_DIR = OUTPUT_PIN;
    FRONT_LED = 0;
    FRONT_LED_DIR = OUTPUT_PIN;
    BODY_LED = 0;
    BODY_LED_DIR = OUTPUT_PIN;
    PULSE_IR0 = 0; PULSE_IR1 = 0; PULSE_IR2 = 0; PULSE_IR3 = 0;
    PULSE_IR0_DIR = OUTPUT_PIN; PULSE_IR1_DIR = OUTPUT_PIN;
    PULSE_IR2_DIR = OUTPUT_PIN; PULSE_IR3_DIR = OUTPUT_PIN;
    AUDIO_ON = 0;
    AUDIO_ON_DIR = OUTPUT_PIN;
    CAM_RESET = 0;
    CAM_RESET_DIR = OUTPUT_PIN;
    SELECTOR0_DIR = INPUT_PIN; SELECTOR1_DIR = INPUT_PIN;
    SELECTOR2_DIR = INPUT_PIN; SELECTOR3_DIR = INPUT_PIN;
    REMOTE_DIR = INPUT_PIN;
    BATT_LOW_DIR = INPUT_PIN;
}

unsigned char isEpuckVersion1_3(void)
{
    return 1;
}

/* ---- agendas ---------------------------------------------------------------- */

#define STUB_MAX_AGENDAS 16

static struct {
    void (*func)(void);
    int cycle;      /* 0.1 ms; 0 = inactive */
    long count;     /* 0.1 ms ticks since the last call */
    int paused;
    int counter;    /* the stub's own, which only counts (stub_activate_counter) */
} agendas[STUB_MAX_AGENDAS];
static int agendas_running;
static int agendas_changed = 1;     /* stub_agendas_count_only looks again */
static int agendas_used;            /* the slots ever used: the loops stop there */

static int agenda_find(void (*func)(void))
{
    int i;
    for (i = 0; i < STUB_MAX_AGENDAS; i++)
        if (agendas[i].func != NULL && agendas[i].func == func)
            return i;
    return -1;
}

/* As the library: Timer2's interrupt runs them (STOP_TMR2, which clears
 * its enable bit, stops them as on the robot). */
void e_start_agendas_processing(void)
{
    agendas_changed = 1;
    agendas_running = 1;
    IEC0bits.T2IE = 1;
}

void e_end_agendas_processing(void)
{
    agendas_changed = 1;
    agendas_running = 0;
    IEC0bits.T2IE = 0;
}

int stub_agendas_running(void)
{
    return agendas_running && IEC0bits.T2IE;
}

/* Returns 0 on success, 1 when func already has an agenda or none is free. */
int e_activate_agenda(void (*func)(void), int cycle)
{
    int i;
    if (func == NULL || agenda_find(func) >= 0)
        return 1;
    for (i = 0; i < STUB_MAX_AGENDAS; i++) {
        if (agendas[i].func == NULL) {
            agendas[i].func = func;
            agendas[i].cycle = cycle < 0 ? 0 : cycle;
            agendas[i].count = 0;
            agendas[i].paused = 0;
            agendas[i].counter = 0;
            agendas_changed = 1;
            if (i >= agendas_used)
                agendas_used = i + 1;
            return 0;
        }
    }
    return 1;
}

int e_destroy_agenda(void (*func)(void))
{
    int i = agenda_find(func);
    if (i < 0)
        return 1;
    agendas[i].func = NULL;
    agendas_changed = 1;
    return 0;
}

int e_set_agenda_cycle(void (*func)(void), int cycle)
{
    int i = agenda_find(func);
    if (i < 0)
        return 1;
    agendas[i].cycle = cycle < 0 ? 0 : cycle;
    agendas_changed = 1;
    return 0;
}

int e_reset_agenda(void (*func)(void))
{
    int i = agenda_find(func);
    if (i < 0)
        return 1;
    agendas[i].count = 0;
    return 0;
}

int e_pause_agenda(void (*func)(void))
{
    int i = agenda_find(func);
    if (i < 0)
        return 1;
    agendas[i].paused = 1;
    agendas_changed = 1;
    return 0;
}

int e_restart_agenda(void (*func)(void))
{
    int i = agenda_find(func);
    if (i < 0)
        return 1;
    agendas[i].paused = 0;
    agendas_changed = 1;
    return 0;
}

int stub_activate_counter(void (*func)(void), int cycle)
{
    if (e_activate_agenda(func, cycle) != 0)
        return 1;
    agendas[agenda_find(func)].counter = 1;
    return 0;
}

/* Every agenda that processing would call is `clock` or a counter of the
 * stub's own (and processing runs); counted again after the table changed. */
int stub_agendas_count_only(void (*clock)(void))
{
    static int only;
    static void (*seen)(void);
    int i;
    static unsigned int enabled;
    if (agendas_changed || clock != seen || enabled != IEC0bits.T2IE) {
        agendas_changed = 0;
        seen = clock;
        enabled = IEC0bits.T2IE;
        only = stub_agendas_running();
        for (i = 0; i < agendas_used && only; i++) {
            if (agendas[i].func != NULL && agendas[i].cycle > 0 && !agendas[i].paused
                    && agendas[i].func != clock && !agendas[i].counter)
                only = 0;
        }
    }
    return only;
}

void stub_agendas_1ms(void)
{
    int i;
    if (!stub_agendas_running())
        return;
    for (i = 0; i < agendas_used; i++) {
        if (agendas[i].func == NULL || agendas[i].cycle <= 0 || agendas[i].paused)
            continue;
        agendas[i].count += 10;     /* 1 ms = 10 ticks of 0.1 ms */
        while (agendas[i].func != NULL && agendas[i].count >= agendas[i].cycle) {
            agendas[i].count -= agendas[i].cycle;
            agendas[i].func();
        }
    }
}

void stub_agendas_ms(long n, void (*clock)(void), void (*clock_ticks)(long))
{
    int i;
    if (!stub_agendas_count_only(clock)) {
        while (n-- > 0)
            stub_agendas_1ms();
        return;
    }
    /* agendas that only count: each one's calls of the n ms in a row */
    for (i = 0; i < agendas_used; i++) {
        if (agendas[i].func == NULL || agendas[i].cycle <= 0 || agendas[i].paused)
            continue;
        agendas[i].count += 10L * n;
        if (agendas[i].func == clock && agendas[i].count >= agendas[i].cycle) {
            long calls = agendas[i].count / agendas[i].cycle;
            agendas[i].count -= calls * agendas[i].cycle;
            clock_ticks(calls);
            continue;
        }
        while (agendas[i].func != NULL && agendas[i].count >= agendas[i].cycle) {
            agendas[i].count -= agendas[i].cycle;
            agendas[i].func();
        }
    }
}

/* ---- motors ------------------------------------------------------------------ */

typedef struct {
    int speed;          /* steps/s, clamped */
    long phase;         /* thousandths of a step towards the next step */
    uint16_t counter;   /* what e_get_steps_* reports, wraps */
    long total;         /* unwrapped, for the trace */
} wheel;

static wheel left_wheel, right_wheel;
static double pose_x, pose_y;

static int clamp(int s)
{
    return s > 1000 ? 1000 : s < -1000 ? -1000 : s;
}

static void wheel_set_speed(wheel *w, int speed)
{
    speed = clamp(speed);
    if (speed != w->speed) {
        w->speed = speed;
        w->phase = 0;
    }
}

/* Returns the step made in this ms: -1, 0 or 1 (|speed| <= 1000). */
static int wheel_1ms(wheel *w)
{
    if (w->speed == 0)
        return 0;
    w->phase += w->speed > 0 ? w->speed : -w->speed;
    if (w->phase < 1000)
        return 0;
    w->phase -= 1000;
    if (w->speed > 0) {
        w->counter = (uint16_t)(w->counter + 1u);
        w->total++;
        return 1;
    }
    w->counter = (uint16_t)(w->counter - 1u);
    w->total--;
    return -1;
}

static int counter_value(uint16_t c)
{
    return c >= 0x8000u ? (int)((long)c - 65536L) : (int)c;
}

void e_init_motors(void)
{
}

void e_set_speed_left(int motor_speed)
{
    COST(STUB_CALL_CYCLES);
    wheel_set_speed(&left_wheel, motor_speed);
}

void e_set_speed_right(int motor_speed)
{
    COST(STUB_CALL_CYCLES);
    wheel_set_speed(&right_wheel, motor_speed);
}

/* as the agenda variant of the library: linear +- angular */
void e_set_speed(int linear_speed, int angular_speed)
{
    long l = (long)linear_speed - angular_speed;
    long r = (long)linear_speed + angular_speed;
    e_set_speed_left(l > 1000 ? 1000 : l < -1000 ? -1000 : (int)l);
    e_set_speed_right(r > 1000 ? 1000 : r < -1000 ? -1000 : (int)r);
}

int e_get_steps_left(void)
{
    COST(STUB_CALL_CYCLES);
    return counter_value(left_wheel.counter);
}

int e_get_steps_right(void)
{
    COST(STUB_CALL_CYCLES);
    return counter_value(right_wheel.counter);
}

void e_set_steps_left(int set_steps)
{
    COST(STUB_CALL_CYCLES);
    left_wheel.counter = (uint16_t)(unsigned)set_steps;
}

void e_set_steps_right(int set_steps)
{
    COST(STUB_CALL_CYCLES);
    right_wheel.counter = (uint16_t)(unsigned)set_steps;
}

long stub_total_steps_left(void)
{
    return left_wheel.total;
}

int stub_speed_left(void)
{
    return left_wheel.speed;
}

int stub_speed_right(void)
{
    return right_wheel.speed;
}

void stub_geometry(double *mm, double *axle)
{
    *mm = mm_per_step;
    *axle = axle_mm;
}

/* ---- odometry ------------------------------------------------------------------ */

/* a reduced to (-pi, pi] */
static double wrap_pi(double a)
{
    long n = (long)(a / (2.0 * STUB_PI));
    a -= (double)n * 2.0 * STUB_PI;
    if (a > STUB_PI)
        a -= 2.0 * STUB_PI;
    else if (a <= -STUB_PI)
        a += 2.0 * STUB_PI;
    return a;
}

#ifndef EPUCK_STUB_NO_POSE
/* Taylor series on (-pi, pi]; 20 terms leave an error far below 1e-12. */
static double stub_sin(double a)
{
    double x = wrap_pi(a), term = x, sum = x;
    int k;
    for (k = 1; k < 20; k++) {
        term *= -x * x / (double)((2 * k) * (2 * k + 1));
        sum += term;
    }
    return sum;
}

static double stub_cos(double a)
{
    double x = wrap_pi(a), term = 1.0, sum = 1.0;
    int k;
    for (k = 1; k < 20; k++) {
        term *= -x * x / (double)((2 * k - 1) * (2 * k));
        sum += term;
    }
    return sum;
}
#endif

/* Heading in radians, exact from the step totals (no drift). */
static double heading_rad(void)
{
    return (double)(right_wheel.total - left_wheel.total) * mm_per_step / axle_mm;
}

void stub_motors_1ms(void)
{
#ifdef EPUCK_STUB_NO_POSE
    /* the steps alone (the 16-bit trace check on simavr, which compares
     * the steps, not the pose) */
    (void)wheel_1ms(&left_wheel);
    (void)wheel_1ms(&right_wheel);
#else
    double before = heading_rad();
    int dl = wheel_1ms(&left_wheel);
    int dr = wheel_1ms(&right_wheel);
    if (dl + dr != 0) {
        /* move along the mean heading of this ms */
        double mid = (before + heading_rad()) / 2.0;
        double ds = (double)(dl + dr) * 0.5 * mm_per_step;
        pose_x += ds * stub_cos(mid);
        pose_y += ds * stub_sin(mid);
    }
#endif
}

/* The ms a wheel needs to make `steps` (>= 1) more steps; -1: never. */
static long wheel_ms_for(const wheel *w, long steps)
{
    long s = w->speed < 0 ? -(long)w->speed : w->speed;
    if (s == 0)
        return -1;
    if (steps > 1000000L)
        return 1000000L;        /* beyond any bulk of ms (rt_idle.c) */
    /* after m ms it has made (phase + m s) / 1000 steps; phase < 1000 */
    return (steps * 1000L - w->phase + s - 1) / s;
}

#ifdef EPUCK_STUB_NO_POSE
/* n ms of wheel_1ms at once */
static void wheel_ms(wheel *w, long n)
{
    long s = w->speed < 0 ? -(long)w->speed : w->speed, k;
    if (s == 0 || n <= 0)
        return;
    k = (w->phase + n * s) / 1000L;
    w->phase = (w->phase + n * s) % 1000L;
    if (w->speed > 0) {
        w->counter = (uint16_t)(w->counter + (unsigned)(k & 0xFFFFL));
        w->total += k;
    } else {
        w->counter = (uint16_t)(w->counter - (unsigned)(k & 0xFFFFL));
        w->total -= k;
    }
}
#endif

void stub_motors_ms_end(void)
{
}

long stub_motors_ms(long n, long left, long right)
{
    long m;
    if (left > 0 && (m = wheel_ms_for(&left_wheel, left)) >= 0 && m < n)
        n = m;
    if (right > 0 && (m = wheel_ms_for(&right_wheel, right)) >= 0 && m < n)
        n = m;
    if (n < 1)
        n = 1;
#ifdef EPUCK_STUB_NO_POSE
    wheel_ms(&left_wheel, n);
    wheel_ms(&right_wheel, n);
#else
    /* the pose moves along each ms's mean heading */
    for (m = 0; m < n; m++)
        stub_motors_1ms();
#endif
    return n;
}

void stub_pose(double *x_mm, double *y_mm, double *heading_deg)
{
    *x_mm = pose_x;
    *y_mm = pose_y;
    *heading_deg = wrap_pi(heading_rad()) * 180.0 / STUB_PI;
}

/* ---- proximity ---------------------------------------------------------------- */

static int prox[8];
enum { AD_OFF, AD_ALL, AD_MICRO };
static int ad_scan;         /* e_init_ad_scan: all the channels, or the microphones only */
static int ad_scan_mode = AD_ALL;   /* what e_ad_scan_on starts again */
static int ir_offset[8];    /* e_calibrate_ir's, what e_get_calibrated_prox subtracts */
static int remote_on;
static unsigned char remote_check = 2, remote_data;

int stub_ad_scan_running(void)
{
    return ad_scan != AD_OFF;
}

/* ---- the inputs' epoch: each setter counts ---------------------------------- */

static unsigned long inputs_set;

unsigned long stub_inputs_epoch(void)
{
    return inputs_set;
}

void stub_input_set(void)
{
    inputs_set++;
}

void stub_set_prox(int n, int value)
{
    inputs_set++;
    if (n >= 0 && n < 8)
        prox[n] = value;
}

void e_init_ad_scan(unsigned char only_micro)
{
    /* MICRO_ONLY scans the microphones only: no proximity readings */
    ad_scan = only_micro == MICRO_ONLY ? AD_MICRO : AD_ALL;
    ad_scan_mode = ad_scan;
    stub_ad_scan_changed(1);
}

/* the scan stops, and starts again as it was configured (the buffers as
 * they are) */
void e_ad_scan_off(void)
{
    ad_scan = AD_OFF;
    stub_ad_scan_changed(0);
}

void e_ad_scan_on(void)
{
    ad_scan = ad_scan_mode;
    stub_ad_scan_changed(1);
}

/* As the library: 100 rounds of the ten channels, each reading followed by
 * a busy loop of 1000; the offset of a sensor is the mean of its readings
 * (the robot must see nothing meanwhile). */
void e_calibrate_ir(void)
{
    long sum[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    int round, n;
    for (round = 0; round < 100; round++)
        for (n = 0; n < 10; n++) {
            if (n < 8)
                sum[n] += e_get_prox((unsigned int)n);
            if (stub_cost_hook != NULL)
                stub_cost_hook(1000L, STUB_WAIT_LOOP_CYCLES);
        }
    for (n = 0; n < 8; n++)
        ir_offset[n] = (int)(sum[n] / 100);
}

int e_get_prox(unsigned int sensor_number)
{
    COST(STUB_CALL_CYCLES);
    if (ad_scan != AD_ALL || sensor_number > 7)
        return 0;
    return prox[sensor_number];
}

/* the reading less e_calibrate_ir's offset, never below 0 (0 offsets
 * before any calibration) */
int e_get_calibrated_prox(unsigned int sensor_number)
{
    int v = e_get_prox(sensor_number);
    if (sensor_number > 7)
        return 0;
    v -= ir_offset[sensor_number];
    return v > 0 ? v : 0;
}

static int ambient[8];

void stub_set_ambient(int n, int value)
{
    inputs_set++;
    if (n >= 0 && n < 8)
        ambient[n] = value;
}

int e_get_ambient_light(unsigned int sensor_number)
{
    COST(STUB_CALL_CYCLES);
    if (ad_scan != AD_ALL || sensor_number > 7)
        return 0;
    return ambient[sensor_number];
}

/* ---- IR remote control (RC5) ------------------------------------------------------- */

void e_init_remote_control(void)
{
    remote_on = 1;
}

/* the library's agenda that decodes the receiver's pulses: here the keys
 * arrive decoded (stub_press_key) */
void e_read_remote_control(void)
{
}

void stub_press_key(int key)
{
    inputs_set++;
    if (!remote_on)
        return;     /* the receiver is not initialised: the press is lost */
    remote_check = (unsigned char)!remote_check;
    remote_data = (unsigned char)key;
}

unsigned char e_get_check(void)
{
    return remote_check;
}

unsigned char e_get_address(void)
{
    return 0;
}

unsigned char e_get_data(void)
{
    return remote_data;
}

/* ---- selector: its four pins RG6..RG9 ------------------------------------------------ */

int selector;       /* the library's global (a_d/advance_ad_scan/e_ad_conv.c), for programs */

void stub_set_selector(int position)
{
    inputs_set++;
    PORTGbits.RG6 = (unsigned)position & 1u;
    PORTGbits.RG7 = ((unsigned)position >> 1) & 1u;
    PORTGbits.RG8 = ((unsigned)position >> 2) & 1u;
    PORTGbits.RG9 = ((unsigned)position >> 3) & 1u;
}

int getselector(void)
{
    COST(STUB_CALL_CYCLES);
    return SELECTOR0 + 2 * SELECTOR1 + 4 * SELECTOR2 + 8 * SELECTOR3;
}

/* ---- reset -------------------------------------------------------------------------- */

/* A reset: the motors stop, their counters start again (the library's
 * RAM), the agendas are gone; the wheels' totals and the pose (the
 * world's) stay. */
void stub_motors_reset(void)
{
    int i;
    left_wheel.speed = right_wheel.speed = 0;
    left_wheel.phase = right_wheel.phase = 0;
    left_wheel.counter = right_wheel.counter = 0;
    for (i = 0; i < STUB_MAX_AGENDAS; i++)
        agendas[i].func = NULL;
    agendas_used = 0;
    agendas_running = 0;
    agendas_changed = 1;
    ad_scan = AD_OFF;
    ad_scan_mode = AD_ALL;
    for (i = 0; i < 8; i++)
        ir_offset[i] = 0;
    remote_on = 0;
    remote_check = 2;
    remote_data = 0;
}

long stub_total_steps_right(void)
{
    return right_wheel.total;
}
