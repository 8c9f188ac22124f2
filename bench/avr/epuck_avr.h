/* epuck_avr.h - the bench's AVR e-puck API (epuck_avr.c): one simulated
 * millisecond of the agendas. */
#ifndef EPUCK_AVR_H
#define EPUCK_AVR_H
void epuck_avr_tick(void);
#endif
