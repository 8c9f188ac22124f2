/* e-puck library API, the robot's pins (library/motor_led/e_epuck_ports.h),
 * declarations only (see ../README.md).  As in the library, LED0..LED7,
 * FRONT_LED and BODY_LED are one-bit lvalues (`LED3 = 1;`, `LED0 = ~LED0;`):
 * here bits of `e_epuck_ports`, which the simulated robot reads each
 * simulated millisecond (a change is traced like e_set_led's); e_set_led and
 * friends write them too.  SELECTOR0..SELECTOR3 read the bits of the
 * simulated selector.  The clock constants are the e-puck 1's. */
#ifndef EPUCK_API_E_EPUCK_PORTS_H
#define EPUCK_API_E_EPUCK_PORTS_H

#include "utility/utility.h"

#define FOSC   7.3728e6
#define PLL    8.0
#define FCY     ((FOSC*PLL)/(4.0))
#define MILLISEC  (FCY/1.0e3)
#define MICROSEC  (FCY/1.0e6)
#define NANOSEC   (FCY/1.0e9)
#define TCY_PIC   (1e9/FCY)
#define INTERRUPT_DELAY (10*TCY_PIC)

#define TRUE    1
#define FALSE   0
#define OUTPUT_PIN 0
#define INPUT_PIN 1

typedef struct {
    unsigned int led0 : 1, led1 : 1, led2 : 1, led3 : 1,
                 led4 : 1, led5 : 1, led6 : 1, led7 : 1,
                 body : 1, front : 1;
} e_epuck_port_bits;
extern volatile e_epuck_port_bits e_epuck_ports;

#define LED0 (e_epuck_ports.led0)
#define LED1 (e_epuck_ports.led1)
#define LED2 (e_epuck_ports.led2)
#define LED3 (e_epuck_ports.led3)
#define LED4 (e_epuck_ports.led4)
#define LED5 (e_epuck_ports.led5)
#define LED6 (e_epuck_ports.led6)
#define LED7 (e_epuck_ports.led7)
#define BODY_LED (e_epuck_ports.body)
#define FRONT_LED (e_epuck_ports.front)

#define SELECTOR0 (getselector() & 1)
#define SELECTOR1 ((getselector() >> 1) & 1)
#define SELECTOR2 ((getselector() >> 2) & 1)
#define SELECTOR3 ((getselector() >> 3) & 1)

#define IR0 8
#define IR1 9
#define IR2 10
#define IR3 11
#define IR4 12
#define IR5 13
#define IR6 14
#define IR7 15
#define MIC1 2
#define MIC2 3
#define MIC3 4
#define ACCX 5
#define ACCY 6
#define ACCZ 7

/* the library's one-instruction macros: nothing to do on the simulated
 * robot (interrupts are the agendas, which the simulator runs between
 * two steps of main) */
#define NOP() ((void)0)
#define CLRWDT() ((void)0)
#define INTERRUPT_OFF() ((void)0)
#define INTERRUPT_ON() ((void)0)

#endif
