/* e-puck library API, the two UARTs (library/uart/e_uart_char.h),
 * declarations only (see ../README.md; host/epuck_more.c).  What is sent
 * goes out at the UART's baud rate, to the trace (a "uart" record a burst)
 * and to the terminal; nothing is ever received (e_ischar_uart* is 0). */
#ifndef _UART_TXRX_CHAR
#define _UART_TXRX_CHAR

#define BAUD115200 7
#define BAUD230400 3
#define BAUD460800 1
#define BAUD921600 0

void e_init_uart1(void);
int  e_ischar_uart1();
int  e_getchar_uart1(char *car);
void e_send_uart1_char(const char * buff, int length);
int  e_uart1_sending(void);

void e_init_uart2(int);
int  e_ischar_uart2();
int  e_getchar_uart2(char *car);
void e_send_uart2_char(const char * buff, int length);
int  e_uart2_sending(void);

extern void *e_uart1_int_clr_addr;
extern int e_uart1_int_clr_mask;
extern void *e_uart2_int_clr_addr;
extern int e_uart2_int_clr_mask;

#endif
