/*
 * stub_devices.c - the host's provider of libIrcom's API (IR messages,
 * as the e-puck2 firmware's src/ircom declares it) and of the e-puck2's
 * VL53L0X time-of-flight sensor, over a virtual robot: what the runtime's
 * rt_comm.c and rt_tof.c call.  On the stub harness alone nobody hears a
 * send and nothing is in the ToF's range; in an Enki world
 * (enki/robot_glue.c) the world takes the values sent and hands over the
 * messages its channel model delivered and the ToF ray's distance.
 * The camera is camera.c's.
 */
#include <stdio.h>
#include <string.h>

#include "ircom/ircom.h"
#include "ircom/ircomSend.h"
#include "ircom/ircomReceive.h"
#include "ircom/ircomMessages.h"
#include "sensors/VL53L0X/VL53L0X.h"
#include "leds.h"
#include "motor_led/advance_one_timer/e_agenda.h"
#include "epuck_stub.h"

#define STUB_SENT_MAX 16

static IrcomMessage inbox[IRCOM_MESSAGES_MAX];
static int in_begin, in_count;
static int frame_ms = STUB_IRCOM_FRAME_MS;
static int on_air_ms;               /* what remains of the frame being sent */
static long sent[STUB_SENT_MAX];
static int n_sent;
static int distance_mm = STUB_DISTANCE_NONE;

/* 1 ms of the frame on the air: an agenda of 10 ticks of 0.1 ms */
static void on_air_1ms(void)
{
    if (on_air_ms > 0)
        on_air_ms--;
}

void ircomStart(void)
{
    stub_activate_counter(on_air_1ms, 10);
}

void ircomEnableContinuousListening(void)
{
}

void ircomEnableProximity(void)
{
}

void ircomListen(void)
{
}

void stub_ircom_set_frame_ms(int ms)
{
    frame_ms = ms > 0 ? ms : 1;
}

int ircomIsSending(void)
{
    return on_air_ms > 0;
}

void ircomSend(long int value)
{
    char json[256], line[160];      /* the record's JSON keys, its readable line */
    value &= 0xFFL;     /* one byte: IRCOM_WORDSIZE bits */
    on_air_ms = frame_ms;
    if (n_sent < STUB_SENT_MAX)
        sent[n_sent++] = value;
    snprintf(json, sizeof json, ", \"value\": %ld", value);
    snprintf(line, sizeof line, "send      %ld", value);
    host_record("send", "send", json, line);
}

int stub_ircom_take_sent(long *values, int max)
{
    int n = n_sent < max ? n_sent : max;
    memcpy(values, sent, (size_t)n * sizeof *values);
    n_sent = 0;
    return n;
}

void stub_ircom_receive(long value, double distance_cm, double direction_rad, int sensor,
                        const char *from, double from_x_mm, double from_y_mm)
{
    char json[256], line[160];
    IrcomMessage *m;
    double bearing;
    stub_input_set();
    if (in_count == IRCOM_MESSAGES_MAX) {     /* as libIrcom: the oldest goes */
        in_begin = (in_begin + 1) % IRCOM_MESSAGES_MAX;
        in_count--;
    }
    m = &inbox[(in_begin + in_count) % IRCOM_MESSAGES_MAX];
    in_count++;
    m->value = value;
    m->distance = (float)distance_cm;
    m->direction = (float)direction_rad;
    m->receivingSensor = sensor;
    m->error = 0;
    /* robot names are letters, digits, _ and - (epuckc/sim/world.py) */
    bearing = direction_rad * 180.0 / 3.14159265358979323846;
    if (bearing >= 180.0)       /* as message_bearing: -180..180 */
        bearing -= 360.0;
    snprintf(json, sizeof json, ", \"from\": \"%.32s\", \"value\": %ld, \"bearing_deg\": %.1f, "
             "\"range_mm\": %.1f, \"sensor\": %d, \"from_x_mm\": %.1f, \"from_y_mm\": %.1f",
             from, value, bearing, distance_cm * 10.0, sensor, from_x_mm, from_y_mm);
    snprintf(line, sizeof line, "message   %ld from %.32s, bearing %.1f deg, range %.1f mm "
             "(sensor %d)", value, from, bearing, distance_cm * 10.0, sensor);
    host_record("message", "message", json, line);
}

void ircomPopMessage(IrcomMessage *msg)
{
    if (in_count == 0) {
        msg->error = -1;
        return;
    }
    *msg = inbox[in_begin];
    in_begin = (in_begin + 1) % IRCOM_MESSAGES_MAX;
    in_count--;
}

void VL53L0X_start(void)
{
}

void stub_set_distance(int mm)
{
    stub_input_set();
    distance_mm = mm < 0 ? 0 : mm;
}

uint16_t VL53L0X_get_dist_mm(void)
{
    return (uint16_t)distance_mm;
}

/* ---- the e-puck2's RGB LEDs: each change of a colour is traced ---------------- */

void set_rgb_led(rgb_led_name_t led_number, uint8_t red_val, uint8_t green_val,
                 uint8_t blue_val)
{
    static long shown[NUM_RGB_LED];
    char json[256], line[160];
    long colour = ((long)red_val << 16) | ((long)green_val << 8) | blue_val;

    if ((int)led_number < 0 || led_number >= NUM_RGB_LED || shown[led_number] == colour + 1)
        return;
    shown[led_number] = colour + 1;
    snprintf(json, sizeof json, ", \"led\": \"led%d\", \"red\": %d, \"green\": %d, "
             "\"blue\": %d", 2 * (int)led_number + 1, red_val, green_val, blue_val);
    snprintf(line, sizeof line, "rgb       led%d red %d green %d blue %d",
             2 * (int)led_number + 1, red_val, green_val, blue_val);
    host_record("rgb", "rgb", json, line);
}
