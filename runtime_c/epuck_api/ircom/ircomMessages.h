/* libIrcom (e-puck2_main-processor src/ircom/ircomMessages.h): declarations only. */
#ifndef IRCOM_MESSAGES_H
#define IRCOM_MESSAGES_H
#include "ircom.h"
void ircomPopMessage(IrcomMessage *msg);
#endif
