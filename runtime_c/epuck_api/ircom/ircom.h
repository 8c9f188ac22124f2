/* Declarations of libIrcom's API as the e-puck2 firmware has it
 * (e-puck2_main-processor src/ircom/ircom.h), for the host build; the
 * stub (host/stub_devices.c) implements them.  A real e-puck2 build uses the
 * firmware's own headers. */
#ifndef IRCOM_H
#define IRCOM_H

#define IRCOM_MESSAGES_MAX 20

typedef struct
{
    long int value;
    float distance;         /* cm */
    float direction;        /* rad, counter-clockwise from the heading, 0..2 pi */
    int receivingSensor;
    int error;              /* -1 = inexistent msg, 0 = all is ok, 1 = error in transmission */
} IrcomMessage;

void ircomStart(void);
void ircomEnableContinuousListening(void);
void ircomEnableProximity(void);

#endif
