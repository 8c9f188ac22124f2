/* e-puck library API: a_d/e_prox.h, which the simulated e-puck does not
 * model (the timer-driven A/D): the library's declarations, so that a program
 * that includes it builds and links; a call of one of its functions
 * ends the run with a message naming the timer-driven A/D (host/unsimulated.c;
 * docs/runtime.md, "What is not simulated"). */
#ifndef _PROX
#define _PROX
void e_init_prox(void);
void e_stop_prox(void);
int e_get_prox(unsigned int sensor_number);
int e_get_ambient_light(unsigned int sensor_number);
#endif
