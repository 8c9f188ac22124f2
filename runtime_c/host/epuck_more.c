/*
 * epuck_more.c - more of the e-puck library's simulation: the UARTs, the
 * A/D scan's timing (utility.h's resetTime/getDiffTimeMs, its flags), the
 * battery.  Written from the library's documented behaviour; none of its
 * code.
 *
 * UARTs.  What a program sends goes out at the UART's baud rate (uart1 at
 * 115200, uart2 at what e_init_uart2 sets: FCY / 16 / (BRG + 1)), ten bits
 * a byte: e_uartN_sending() is true meanwhile, and a send waits, as the
 * library's does, for the one before to be out.  A UART that was not
 * initialised sends nothing (and says so once on stderr): the robot's
 * stays off.  The trace gets a "uart" record per burst of text: up to a
 * newline, or what went out before the line stayed quiet for UART_QUIET_MS,
 * or UART_LINE bytes; nothing is ever received.  With
 * EPUCK_STUB_UART1_ELSEWHERE the UART1's sending is another file's (the
 * 16-bit path's robot tracer sends on the AVR's USART0, int16/uart1_avr.c).
 */
#include <stdio.h>
#include <string.h>

#include "epuck_stub.h"
#include "library_sim.h"
#include "p30F6014A.h"
#include "uart/e_uart_char.h"
#include "utility/utility.h"
#include "a_d/advance_ad_scan/e_ad_conv.h"

/* ---- the A/D scan: its ticks (16384 a second) -------------------------------------- */

int e_mic_scan[3][MIC_SAMP_NB];
int e_acc_scan[3][ACC_SAMP_NB];
unsigned int e_last_mic_scan_id;
unsigned int e_last_acc_scan_id;
int e_ambient_ir[10];
int e_ambient_and_reflected_ir[10];
unsigned char updateAccI2CCounter;
unsigned int tickAdcIsr;

#define AD_TICKS_PER_S 16384ULL

static unsigned long long ticks_before;     /* of the scan's earlier runs */
static unsigned long long started_at;       /* cycles; the run going on */
static int running;
static unsigned long long reset_at;         /* resetTime's tick */

static unsigned long long ticks_at(unsigned long long cycles)
{
    return cycles * AD_TICKS_PER_S / STUB_FCY;
}

unsigned long long stub_ad_ticks(void)
{
    unsigned long long t = ticks_before;
    if (running)
        t += ticks_at(stub_now_cycles()) - ticks_at(started_at);
    return t;
}

void stub_ad_scan_changed(int on)
{
    if (on && !running)
        started_at = stub_now_cycles();
    else if (!on && running)
        ticks_before = stub_ad_ticks();
    running = on;
}

/* the library's counters, as its A/D interrupt leaves them: tickAdcIsr up
 * to 65535 ticks (4 s) since resetTime, updateAccI2CCounter up to 64 (the
 * accelerometer's refresh, imu.c), the buffers' positions */
static void ad_counters(void)
{
    unsigned long long t = stub_ad_ticks(), since = t - reset_at;
    tickAdcIsr = since > 65535ULL ? 65535u : (unsigned int)since;
    e_last_mic_scan_id = (unsigned int)(t % MIC_SAMP_NB);
    e_last_acc_scan_id = (unsigned int)(t / 64ULL % ACC_SAMP_NB);
}

void resetTime(void)
{
    reset_at = stub_ad_ticks();
    tickAdcIsr = 0;
}

float getDiffTimeMs(void)
{
    if (stub_cost_hook != NULL)
        stub_cost_hook(1L, STUB_CALL_CYCLES);
    ad_counters();
    return (float)tickAdcIsr * (float)ADC_ISR_PERIOD_MS;
}

float getDiffTimeMsAndReset(void)
{
    float v = getDiffTimeMs();
    resetTime();
    return v;
}

/* the scan has filled the microphones' buffer once / taken all its channels */
unsigned char e_ad_is_array_filled(void)
{
    return stub_ad_ticks() >= MIC_SAMP_NB;
}

unsigned char e_ad_is_acquisition_completed(void)
{
    return stub_ad_ticks() >= 64ULL;
}

/* ---- UARTs ---------------------------------------------------------------------------- */

void *e_uart1_int_clr_addr;
int e_uart1_int_clr_mask;
void *e_uart2_int_clr_addr;
int e_uart2_int_clr_mask;
/* the receivers' buffers and counts (nothing is ever received here) */
char U1RXBuf[64], U2RXBuf[64];
int U1RXRcvCnt, U1RXReadCnt, U2RXRcvCnt, U2RXReadCnt;

#ifdef __AVR__
#define UART_LINE 64            /* emit's buffers fit the AVR's 16 KB (--int16) */
#else
#define UART_LINE 512
#endif
#define UART_QUIET_MS 10

typedef struct {
    const char *name;
    int on;                     /* initialised */
    int warned;
    unsigned long brg;          /* FCY / 16 / (brg + 1) baud */
    unsigned long long busy_until;     /* cycles: the last byte is out */
    char text[UART_LINE];
    int used;
} uart;

static uart uarts[2] = { { "uart1", 0, 0, 7, 0, {0}, 0 }, { "uart2", 0, 0, 7, 0, {0}, 0 } };

/* The bytes as JSON string text (controls as \uXXXX, \r \n \t by name). */
static void escape(char *out, size_t size, const char *buff, int length)
{
    size_t used = 0;
    int i;
    for (i = 0; i < length && used + 8 < size; i++) {
        unsigned char c = (unsigned char)buff[i];
        if (c == '"' || c == '\\')
            used += (size_t)snprintf(out + used, size - used, "\\%c", c);
        else if (c == '\n' || c == '\r' || c == '\t')
            used += (size_t)snprintf(out + used, size - used, "\\%c",
                                     c == '\n' ? 'n' : c == '\r' ? 'r' : 't');
        else if (c < 0x20 || c == 0x7f)
            used += (size_t)snprintf(out + used, size - used, "\\u%04x", c);
        else
            out[used++] = (char)c;
    }
    out[used] = '\0';
}

/* the first `n` bytes of the line: a record; the rest stays */
static void emit(uart *u, int n)
{
    /* a byte escapes to at most 6 (\u00XX); on the stack, not in the
     * program's state: a world's robots sharing the object swap their
     * state at every step (runtime_c/enki/robot_loader.h) */
    char text[6 * UART_LINE + 8], extra[6 * UART_LINE + 32], line[6 * UART_LINE + 32];
    if (n <= 0)
        return;
    escape(text, sizeof text, u->text, n);
    snprintf(extra, sizeof extra, ", \"text\": \"%s\"", text);
    snprintf(line, sizeof line, "%-9s %s", u->name, text);
    host_record("uart", u->name, extra, line);
    memmove(u->text, u->text + n, (size_t)(u->used - n));
    u->used -= n;
}

static void send(uart *u, const char *buff, int length)
{
    unsigned long long now;
    int i;
    if (stub_cost_hook != NULL)
        stub_cost_hook(1L, STUB_CALL_CYCLES);
    if (buff == NULL || length <= 0)
        return;
    if (!u->on) {
        if (!u->warned)
            fprintf(stderr, "epuckc: note: e_send_%s_char before e_init_%s: the robot's UART "
                    "is off and sends nothing\n", u->name, u->name);
        u->warned = 1;
        return;
    }
    now = stub_now_cycles();
    if (u->busy_until > now) {          /* the library waits for the one before */
        stub_wait_cycles((long)(u->busy_until - now));
        now = stub_now_cycles();
    }
    u->busy_until = (u->busy_until > now ? u->busy_until : now)
                    + (unsigned long long)length * 10ULL * 16ULL * (u->brg + 1ULL);
    for (i = 0; i < length; i++) {
        if (u->used == UART_LINE)
            emit(u, u->used);
        u->text[u->used++] = buff[i];
        if (buff[i] == '\n')
            emit(u, u->used);
    }
}

static int sending(uart *u)
{
    if (stub_cost_hook != NULL)
        stub_cost_hook(1L, STUB_CALL_CYCLES);
    return u->on && u->busy_until > stub_now_cycles();
}

#ifndef EPUCK_STUB_UART1_ELSEWHERE
void e_init_uart1(void) { uarts[0].on = 1; uarts[0].brg = 7; }
#endif
void e_init_uart2(int baud) { uarts[1].on = 1; uarts[1].brg = (unsigned long)baud & 0xFFFFu; }
int e_ischar_uart1(void) { return 0; }
int e_ischar_uart2(void) { return 0; }
int e_getchar_uart1(char *car) { (void)car; return 0; }
int e_getchar_uart2(char *car) { (void)car; return 0; }
#ifndef EPUCK_STUB_UART1_ELSEWHERE
int e_uart1_sending(void) { return sending(&uarts[0]); }
void e_send_uart1_char(const char *buff, int length) { send(&uarts[0], buff, length); }
#endif
int e_uart2_sending(void) { return sending(&uarts[1]); }
void e_send_uart2_char(const char *buff, int length) { send(&uarts[1], buff, length); }

/* the lines quiet for long enough; at the end (n < 0) every line's rest */
static void quiet_lines(int end)
{
    int k;
    unsigned long long now = stub_now_cycles();
    for (k = 0; k < 2; k++) {
        uart *u = &uarts[k];
        if (u->used > 0 && (end || now > u->busy_until
                                   + (unsigned long long)UART_QUIET_MS * STUB_FCY / 1000ULL))
            emit(u, u->used);
    }
}

void stub_uart_end(void)
{
    quiet_lines(1);
}

/* ---- each ms, and a reset ------------------------------------------------------------ */

void stub_more_ms(long now_ms, long n)
{
    (void)now_ms;
    (void)n;
    ad_counters();
    quiet_lines(0);
}

void stub_more_reset(void)
{
    int k;
    quiet_lines(1);
    for (k = 0; k < 2; k++) {
        uarts[k].on = 0;
        uarts[k].busy_until = 0;
    }
    ticks_before = 0;
    running = 0;
    reset_at = 0;
    tickAdcIsr = 0;
    updateAccI2CCounter = 0;
}

/* ---- battery: full ----------------------------------------------------------------------- */

unsigned int getBatteryValueRaw(void)
{
    return 2560;        /* the library's MAX_BATT_VALUE, 4.2 V */
}

unsigned int getBatteryValuePercentage(void)
{
    return 100;
}
