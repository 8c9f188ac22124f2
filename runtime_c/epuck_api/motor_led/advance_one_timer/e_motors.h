/* e-puck library API, agenda variant of the motors, declarations only
 * (see ../../README.md).  Speeds in steps/s, clamped to -1000..1000 by the
 * library; the step counters are 16 bits and wrap. */
#ifndef EPUCK_API_E_MOTORS_H
#define EPUCK_API_E_MOTORS_H

void e_init_motors(void);
void e_set_speed_left(int motor_speed);
void e_set_speed_right(int motor_speed);
void e_set_speed(int linear_speed, int angular_speed);
int e_get_steps_left(void);
int e_get_steps_right(void);
void e_set_steps_left(int set_steps);
void e_set_steps_right(int set_steps);

#endif
