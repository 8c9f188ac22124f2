/* libIrcom (e-puck2_main-processor src/ircom/ircomSend.h): declarations only. */
#ifndef IRCOM_SEND_H
#define IRCOM_SEND_H
void ircomSend(long int value);
int ircomIsSending(void);
#endif
