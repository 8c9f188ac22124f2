/*
 * uart1_avr.c - the e-puck library's UART1 (uart/e_uart_char.h: the calls
 * of rt_trace_uart1.c) on the ATmega1284P's USART0, for the 16-bit
 * simulator with the robot's tracer (`epuckc run --int16 --robot-trace`,
 * docs/runtime.md).  Interrupt driven as GCtronic's e_uart1_tx_char.s is:
 * e_send_uart1_char hands the buffer to the transmitter's interrupt (here
 * the data register empty interrupt, one byte each) and returns;
 * e_uart1_sending() is 1 until its last byte is in the transmitter.
 *
 * The speed: simavr sends one byte per 1000000 / (baud / 11) us (it counts
 * a parity bit that 8N1 does not have).  UBRR 15 with the double speed of
 * U2X at 16 MHz is 125000 baud, i.e. 88 us a byte: within 1.4 % of the 86.8
 * us of 115200 baud 8N1, the e-puck's Bluetooth link (11,520 bytes/s).
 */
#include <avr/io.h>
#include <avr/interrupt.h>

#include "uart/e_uart_char.h"

static const char *volatile next_byte;
static volatile int bytes_left;

void e_init_uart1(void)
{
    UCSR0A = _BV(U2X0);         /* before the rate: simavr reads U2X when UBRR is written */
    UCSR0C = _BV(UCSZ01) | _BV(UCSZ00);
    UBRR0H = 0;
    UBRR0L = 15;
    UCSR0B = _BV(TXEN0);
}

void e_send_uart1_char(const char *buff, int length)
{
    if (length <= 0)
        return;
    cli();
    next_byte = buff;
    bytes_left = length;
    UCSR0B |= _BV(UDRIE0);
    sei();
}

int e_uart1_sending(void)
{
    int sending;
    uint8_t sreg = SREG;
    cli();
    sending = bytes_left > 0;
    SREG = sreg;
    return sending;
}

ISR(USART0_UDRE_vect)
{
    if (bytes_left > 0) {
        UDR0 = (uint8_t)*next_byte++;
        bytes_left--;
    }
    if (bytes_left == 0)
        UCSR0B &= (uint8_t)~_BV(UDRIE0);
}
