/* e-puck library API, the two UARTs (library/uart/e_uart_char.h),
 * declarations only (see ../README.md).  On the simulated robot what is
 * sent goes to the trace (a "uart" record) and to the terminal; nothing is
 * ever received (e_ischar_uart* is 0). */
#ifndef EPUCK_API_E_UART_CHAR_H
#define EPUCK_API_E_UART_CHAR_H

#define BAUD115200 7
#define BAUD230400 3
#define BAUD460800 1
#define BAUD921600 0

void e_init_uart1(void);
int  e_ischar_uart1(void);
int  e_getchar_uart1(char *car);
void e_send_uart1_char(const char *buff, int length);
int  e_uart1_sending(void);
void e_init_uart2(int baud);
int  e_ischar_uart2(void);
int  e_getchar_uart2(char *car);
void e_send_uart2_char(const char *buff, int length);
int  e_uart2_sending(void);

#endif
