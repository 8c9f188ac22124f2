/* e-puck library API, the LEDs of the fast agenda's variant (library/
 * motor_led/advance_one_timer/fast_agenda/e_led.h): the same functions as
 * the agenda variant's, which drive the same simulated LEDs (see
 * ../../../README.md). */
#ifndef EPUCK_API_FAST_AGENDA_E_LED_H
#define EPUCK_API_FAST_AGENDA_E_LED_H

#include "motor_led/advance_one_timer/e_led.h"

#endif
