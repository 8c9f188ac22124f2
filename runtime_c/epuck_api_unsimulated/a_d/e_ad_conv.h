/* e-puck library API: a_d/e_ad_conv.h, which the simulated e-puck does not
 * model (the timer-driven A/D): the library's declarations, so that a program
 * that includes it builds and links; a call of one of its functions
 * ends the run with a message naming the timer-driven A/D (host/unsimulated.c;
 * docs/runtime.md, "What is not simulated"). */
#ifndef _AD_CONV
#define _AD_CONV
void e_init_ad(void);
int e_read_ad(unsigned int channel);
#endif
