/*
 * rt_trace_uart1.c - the link of the robot's trace (rt_trace.c) on the
 * e-puck library's UART1: on the e-puck, the Bluetooth module (115200 baud
 * 8N1, the PC's /dev/rfcommN); in `epuckc run --int16 --robot-trace`, the
 * 16-bit simulator's model of the same library calls on the ATmega's USART0
 * (int16/uart1_avr.c).  GCtronic's e_send_uart1_char is interrupt driven:
 * it hands the buffer to the transmitter's interrupt and returns, and
 * e_uart1_sending() says whether it is still being read, so the tracer
 * gives it a piece of its ring and leaves it in place until then.  With
 * `--trace` the UART1 is the trace's: a program's own C should not use it.
 */
#include "rt_platform.h"
#include "uart/e_uart_char.h"

void rt_trace_port_start(void)
{
    e_init_uart1();
}

int rt_trace_port_busy(void)
{
    return e_uart1_sending();
}

int rt_trace_port_send(const unsigned char *bytes, int n)
{
    e_send_uart1_char((const char *)bytes, n);
    return n;
}

/* until the piece in flight is sent (bounded: about a second at most on
 * the dsPIC), then about a millisecond more for the transmitter's own
 * bytes; counted in loops, since the clock need not tick meanwhile */
void rt_trace_port_wait(void)
{
    static volatile unsigned long spin;

    for (spin = 0; e_uart1_sending() && spin < 1000000UL; spin++) {
    }
    for (spin = 0; spin < 2000UL; spin++) {
    }
}
