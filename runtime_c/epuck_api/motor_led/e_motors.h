/* e-puck library API, the motors' timer variant (library/motor_led/
 * e_motors.h), declarations only (see ../README.md).  The same functions
 * as the agenda variant; on the simulated robot both drive the same
 * stepper motors. */
#ifndef EPUCK_API_E_MOTORS_TIMER_H
#define EPUCK_API_E_MOTORS_TIMER_H

#include "motor_led/advance_one_timer/e_motors.h"

#endif
