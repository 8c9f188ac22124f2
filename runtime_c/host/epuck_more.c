/*
 * epuck_more.c - the rest of the e-puck library that programs written
 * against it use, over the simulated robot of epuck_stub.c: the LED effects
 * of motor_led/advance_one_timer/e_led.h (agenda callbacks, one step a
 * call), the UARTs (what is sent goes to the trace and the terminal;
 * nothing is received), the LSM330 accelerometer and gyroscope of
 * acc_gyro/e_lsm330.h (a flat floor: gravity only; the body's rotation
 * about z), and the battery (full).  Written from the library's
 * documented behaviour; none of its code.
 */
#include <stdio.h>
#include <string.h>

#include "epuck_stub.h"
#include "motor_led/advance_one_timer/e_led.h"
#include "motor_led/advance_one_timer/e_agenda.h"
#include "uart/e_uart_char.h"
#include "acc_gyro/e_lsm330.h"
#include "utility/utility.h"

/* ---- LED effects ----------------------------------------------------------- */

#define TOGGLE 2

void e_blink_led(void)
{
    e_set_led(8, (unsigned int)!stub_led(0));   /* the library inverts each; all follow led0 */
}

void e_blink_led0(void) { e_set_led(0, TOGGLE); }
void e_blink_led1(void) { e_set_led(1, TOGGLE); }
void e_blink_led2(void) { e_set_led(2, TOGGLE); }
void e_blink_led3(void) { e_set_led(3, TOGGLE); }
void e_blink_led4(void) { e_set_led(4, TOGGLE); }
void e_blink_led5(void) { e_set_led(5, TOGGLE); }
void e_blink_led6(void) { e_set_led(6, TOGGLE); }
void e_blink_led7(void) { e_set_led(7, TOGGLE); }

void e_start_led_blinking(int cycle)
{
    e_activate_agenda(e_blink_led, cycle);
}

void e_stop_led_blinking(void)
{
    e_destroy_agenda(e_blink_led);
}

void e_set_blinking_cycle(int cycle)
{
    if (cycle >= 0)
        e_set_agenda_cycle(e_blink_led, cycle);
}

/* Toggle the LEDs of `pair` (-1: none). */
static void toggle_pair(const int pair[2])
{
    if (pair[0] >= 0)
        e_set_led((unsigned int)pair[0], TOGGLE);
    if (pair[1] >= 0)
        e_set_led((unsigned int)pair[1], TOGGLE);
}

/* A wave from the front to the back along both sides, on then off. */
void flow_led(void)
{
    static const int wave[5][2] = { {0, -1}, {1, 7}, {2, 6}, {3, 5}, {4, -1} };
    static int step;
    toggle_pair(wave[step]);
    step = (step + 1) % 5;
}

/* One light around the ring. */
void snake_led(void)
{
    static int lit;
    e_set_led((unsigned int)((lit + 7) % 8), 0);
    e_set_led((unsigned int)lit, 1);
    lit = (lit + 1) % 8;
}

/* One light swinging over the front LEDs: 1, 0, 7, 0, 1 ... */
void k2000_led(void)
{
    static const int swing[4] = {1, 0, 7, 0};
    static int lit, step;
    e_set_led((unsigned int)lit, 0);
    lit = swing[step];
    e_set_led((unsigned int)lit, 1);
    step = (step + 1) % 4;
}

/* A wave over one side, then all off: right (1, 2, 3 with 0 and 4), left
 * (7, 6, 5). */
static void side_wave(const int steps[3][2], int *step)
{
    if (*step < 3)
        toggle_pair(steps[*step]);
    else
        e_led_clear();
    *step = (*step + 1) % 4;
}

void right_led(void)
{
    static const int steps[3][2] = { {0, 4}, {1, 3}, {2, -1} };
    static int step;
    side_wave(steps, &step);
}

void left_led(void)
{
    static const int steps[3][2] = { {0, 4}, {7, 5}, {6, -1} };
    static int step;
    side_wave(steps, &step);
}

/* ---- UARTs -------------------------------------------------------------------- */

void e_init_uart1(void) {}
void e_init_uart2(int baud) { (void)baud; }
int e_ischar_uart1(void) { return 0; }
int e_ischar_uart2(void) { return 0; }
int e_getchar_uart1(char *car) { (void)car; return 0; }
int e_getchar_uart2(char *car) { (void)car; return 0; }
int e_uart1_sending(void) { return 0; }
int e_uart2_sending(void) { return 0; }

/* The bytes as JSON string text (controls as \uXXXX, \r \n \t by name);
 * cut at `size`. */
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

static void send(const char *uart, const char *buff, int length)
{
    char text[1024], extra[1100], line[1100];
    if (stub_cost_hook != NULL)
        stub_cost_hook(1L, STUB_CALL_CYCLES);
    if (buff == NULL || length <= 0)
        return;
    escape(text, sizeof text, buff, length);
    snprintf(extra, sizeof extra, ", \"text\": \"%s\"", text);
    snprintf(line, sizeof line, "%-9s %s", uart, text);
    host_record("uart", uart, extra, line);
}

void e_send_uart1_char(const char *buff, int length) { send("uart1", buff, length); }
void e_send_uart2_char(const char *buff, int length) { send("uart2", buff, length); }

/* ---- LSM330 ------------------------------------------------------------------------ */

#define ACC_ONE_G 16384         /* +-2 g full scale, 16 bits */
#define GYRO_DPS_PER_UNIT 0.00875

void initAccAndGyro(void) {}
void calibrateGyroscope(void) {}
int getXAxisAcc(void) { return 0; }
int getYAxisAcc(void) { return 0; }
int getZAxisAcc(void) { return ACC_ONE_G; }
int getXAxisGyro(void) { return 0; }
int getYAxisGyro(void) { return 0; }
signed char getTemperature(void) { return 25; }

/* the body's rate of turn about z, from its heading over the last ms */
int getZAxisGyro(void)
{
    double rate = stub_turn_rate_dps();
    double raw = rate / GYRO_DPS_PER_UNIT;
    if (raw > 32767.0)
        return 32767;
    if (raw < -32768.0)
        return -32768;
    return (int)(raw < 0 ? raw - 0.5 : raw + 0.5);
}

void getAllAxesAcc(signed int *x, signed int *y, signed int *z)
{
    *x = getXAxisAcc();
    *y = getYAxisAcc();
    *z = getZAxisAcc();
}

void getAllAxesGyro(signed int *x, signed int *y, signed int *z)
{
    *x = getXAxisGyro();
    *y = getYAxisGyro();
    *z = getZAxisGyro();
}

/* little-endian pairs x, y, z as the sensor's registers */
static void raw_pairs(unsigned char *arr, int x, int y, int z)
{
    int v[3], i;
    v[0] = x;
    v[1] = y;
    v[2] = z;
    for (i = 0; i < 3; i++) {
        arr[2 * i] = (unsigned char)(v[i] & 0xFF);
        arr[2 * i + 1] = (unsigned char)((v[i] >> 8) & 0xFF);
    }
}

void getAllAxesAccRaw(unsigned char *arr)
{
    raw_pairs(arr, getXAxisAcc(), getYAxisAcc(), getZAxisAcc());
}

void getAllAxesGyroRaw(unsigned char *arr)
{
    raw_pairs(arr, getXAxisGyro(), getYAxisGyro(), getZAxisGyro());
}

float rawToDps(int value)
{
    return (float)value * 0.00875f;
}

float rawToDpms(int value)
{
    return (float)value * 0.00000875f;
}

/* ---- battery: full ------------------------------------------------------------------ */

unsigned int getBatteryValueRaw(void)
{
    return 2560;        /* the library's MAX_BATT_VALUE, 4.2 V */
}

unsigned int getBatteryValuePercentage(void)
{
    return 100;
}
