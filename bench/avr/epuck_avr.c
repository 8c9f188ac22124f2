/*
 * epuck_avr.c - a small e-puck library API for the AVR runs of
 * bench/robot_bench.py under simavr: the functions the runtime calls, over
 * plain variables.  The wheels do not move (the counters stay 0), the
 * proximity readings stay 0, agendas are run by epuck_avr_tick() (called by
 * platform_sim.c once per simulated millisecond) instead of a timer
 * interrupt, so that a poll's cycles are the runtime's alone.
 */
#include "motor_led/e_init_port.h"
#include "motor_led/advance_one_timer/e_motors.h"
#include "motor_led/advance_one_timer/e_agenda.h"
#include "a_d/advance_ad_scan/e_prox.h"
#include "a_d/advance_ad_scan/e_ad_conv.h"
#include "a_d/advance_ad_scan/e_acc.h"
#include "a_d/advance_ad_scan/e_micro.h"
#include "motor_led/e_led.h"
#include "motor_led/advance_one_timer/e_remote_control.h"
#include "codec/e_sound.h"
#include "utility/utility.h"
#include "epuck_avr.h"

#define MAX_AGENDAS 4

static struct {
    void (*func)(void);
    int cycle;      /* in 0.1 ms, as the library's */
    int count;
} agendas[MAX_AGENDAS];
static int agendas_on;
static volatile int speed_left, speed_right;
static volatile int steps_left, steps_right;
static volatile int prox[8];

void e_init_port(void) {}
void e_start_agendas_processing(void) { agendas_on = 1; }
void e_end_agendas_processing(void) { agendas_on = 0; }

int e_activate_agenda(void (*func)(void), int cycle)
{
    int i;
    for (i = 0; i < MAX_AGENDAS; i++) {
        if (agendas[i].func == func)
            return 1;
    }
    for (i = 0; i < MAX_AGENDAS; i++) {
        if (agendas[i].func == 0) {
            agendas[i].func = func;
            agendas[i].cycle = cycle;
            agendas[i].count = 0;
            return 0;
        }
    }
    return 1;
}

static int agenda_set(void (*func)(void), int cycle, int destroy)
{
    int i;
    for (i = 0; i < MAX_AGENDAS; i++) {
        if (agendas[i].func == func) {
            if (destroy)
                agendas[i].func = 0;
            else if (cycle >= 0)
                agendas[i].cycle = cycle;
            agendas[i].count = 0;
            return 0;
        }
    }
    return 1;
}

int e_destroy_agenda(void (*func)(void)) { return agenda_set(func, -1, 1); }
int e_set_agenda_cycle(void (*func)(void), int cycle) { return agenda_set(func, cycle, 0); }
int e_reset_agenda(void (*func)(void)) { return agenda_set(func, -1, 0); }
int e_pause_agenda(void (*func)(void)) { return agenda_set(func, -1, 0); }
int e_restart_agenda(void (*func)(void)) { return agenda_set(func, -1, 0); }

void epuck_avr_tick(void)
{
    int i, t;
    if (!agendas_on)
        return;
    for (t = 0; t < 10; t++) {      /* ten agenda cycles of 0.1 ms */
        for (i = 0; i < MAX_AGENDAS; i++) {
            if (agendas[i].func != 0 && agendas[i].cycle > 0
                    && ++agendas[i].count >= agendas[i].cycle) {
                agendas[i].count = 0;
                agendas[i].func();
            }
        }
    }
}

void e_init_motors(void) {}
void e_set_speed_left(int s) { speed_left = s; }
void e_set_speed_right(int s) { speed_right = s; }
void e_set_speed(int linear, int angular)
{
    speed_left = linear - angular;
    speed_right = linear + angular;
}
int e_get_steps_left(void) { return steps_left; }
int e_get_steps_right(void) { return steps_right; }
void e_set_steps_left(int s) { steps_left = s; }
void e_set_steps_right(int s) { steps_right = s; }

void e_init_ad_scan(unsigned char only_micro) { (void)only_micro; }
void e_calibrate_ir(void) {}
int e_get_prox(unsigned int n) { return n < 8 ? prox[n] : 0; }
int e_get_calibrated_prox(unsigned int n) { return e_get_prox(n); }
int e_get_ambient_light(unsigned int n) { (void)n; return 0; }

/* The rest of the robot (issue 9): quiet devices; the benched programs do
 * not use them, but the runtime links them. */
void e_set_led(unsigned int led_number, unsigned int value) { (void)led_number; (void)value; }
void e_led_clear(void) {}
void e_set_body_led(unsigned int value) { (void)value; }
void e_set_front_led(unsigned int value) { (void)value; }
void e_init_sound(void) {}
void e_play_sound(int sound_offset, int sound_length) { (void)sound_offset; (void)sound_length; }
void e_close_sound(void) {}
int e_get_acc(unsigned int captor) { (void)captor; return 0; }
int e_get_acc_filtered(unsigned int captor, unsigned int filter_size)
{
    (void)captor;
    (void)filter_size;
    return 0;
}
void e_acc_calibr(void) {}
int e_get_micro(unsigned int micro_id) { (void)micro_id; return 0; }
int e_get_micro_average(unsigned int micro_id, unsigned int filter_size)
{
    (void)micro_id;
    (void)filter_size;
    return 0;
}
int e_get_micro_volume(unsigned int micro_id) { (void)micro_id; return 0; }
void e_init_remote_control(void) {}
unsigned char e_get_check(void) { return 0; }
unsigned char e_get_address(void) { return 0; }
unsigned char e_get_data(void) { return 0; }
void wait(long num) { (void)num; }
int getselector(void) { return 0; }
