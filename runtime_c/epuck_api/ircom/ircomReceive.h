/* libIrcom (e-puck2_main-processor src/ircom/ircomReceive.h): declarations only. */
#ifndef IRCOM_RECEIVE_H
#define IRCOM_RECEIVE_H
void ircomListen(void);
#endif
