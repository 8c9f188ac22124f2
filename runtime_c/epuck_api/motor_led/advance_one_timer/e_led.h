/* e-puck library API, LEDs with the agenda's effects (library/motor_led/
 * advance_one_timer/e_led.h), declarations only (see ../../README.md).
 * The effects (flow_led, k2000_led, ...) are agenda callbacks, one step
 * each call, as the library's. */
#ifndef EPUCK_API_E_LED_ADV_H
#define EPUCK_API_E_LED_ADV_H

#include "motor_led/e_led.h"

void e_blink_led(void);
void e_blink_led0(void);
void e_blink_led1(void);
void e_blink_led2(void);
void e_blink_led3(void);
void e_blink_led4(void);
void e_blink_led5(void);
void e_blink_led6(void);
void e_blink_led7(void);
void e_start_led_blinking(int cycle);
void e_stop_led_blinking(void);
void e_set_blinking_cycle(int cycle);
void flow_led(void);
void snake_led(void);
void k2000_led(void);
void right_led(void);
void left_led(void);

#endif
