/* e-puck library API, the motors of the fast agenda's variant (library/
 * motor_led/advance_one_timer/fast_agenda/e_motors.h): the same functions
 * as the agenda variant's, which drive the same simulated stepper motors
 * (see ../../../README.md). */
#ifndef EPUCK_API_FAST_AGENDA_E_MOTORS_H
#define EPUCK_API_FAST_AGENDA_E_MOTORS_H

#include "motor_led/advance_one_timer/e_motors.h"

#endif
