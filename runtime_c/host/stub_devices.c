/*
 * stub_devices.c - the host's provider of libIrcom's API (IR messages,
 * as the e-puck2 firmware's src/ircom declares it) and of the e-puck2's
 * VL53L0X time-of-flight sensor, over a virtual robot: what the runtime's
 * rt_comm.c and rt_tof.c call.  On the stub harness alone nobody hears a
 * send and nothing is in the ToF's range; in an Enki world
 * (enki/robot_glue.c) the world takes the values sent and hands over the
 * messages its channel model delivered and the ToF ray's distance.
 * The camera (e_poxxxx, as the e-puck library declares it) sees what
 * stub_set_camera last gave it (grey on the harness alone), as one line of
 * RGB565 pixels, a capture ready at once.
 */
#include <stdio.h>
#include <string.h>

#include "ircom/ircom.h"
#include "ircom/ircomSend.h"
#include "ircom/ircomReceive.h"
#include "ircom/ircomMessages.h"
#include "sensors/VL53L0X/VL53L0X.h"
#include "leds.h"
#include "camera/fast_2_timer/e_poxxxx.h"
#include "motor_led/advance_one_timer/e_agenda.h"
#include "epuck_stub.h"

#define STUB_SENT_MAX 16

static IrcomMessage inbox[IRCOM_MESSAGES_MAX];
static int in_begin, in_count;
static int frame_ms = STUB_IRCOM_FRAME_MS;
static int on_air_ms;               /* what remains of the frame being sent */
static long sent[STUB_SENT_MAX];
static int n_sent;
static char json[256];
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
    value &= 0xFFL;     /* one byte: IRCOM_WORDSIZE bits */
    on_air_ms = frame_ms;
    if (n_sent < STUB_SENT_MAX)
        sent[n_sent++] = value;
    snprintf(json, sizeof json, ", \"value\": %ld", value);
    stub_observe("send", json, (int)value);
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
    stub_input_set();
    IrcomMessage *m;
    double bearing;
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
    stub_observe("message", json, (int)value);
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

/* ---- the camera ---------------------------------------------------------- */

#define STUB_CAMERA_PIXELS 60

static unsigned char camera_rgb[3 * STUB_CAMERA_PIXELS] = {0};
static char *capture;

void stub_set_camera(const unsigned char *rgb, int pixels)
{
    stub_input_set();
    if (pixels > STUB_CAMERA_PIXELS)
        pixels = STUB_CAMERA_PIXELS;
    memcpy(camera_rgb, rgb, (size_t)(3 * pixels));
}

int e_poxxxx_init_cam(void)
{
    return 0;
}

int e_poxxxx_config_cam(unsigned int sensor_x1, unsigned int sensor_y1,
                        unsigned int sensor_width, unsigned int sensor_height,
                        unsigned int zoom_fact_width, unsigned int zoom_fact_height,
                        int color_mode)
{
    /* the runtime asks for one row of STUB_CAMERA_PIXELS in RGB565 */
    return sensor_width / zoom_fact_width == STUB_CAMERA_PIXELS
           && sensor_height / zoom_fact_height == 1 && color_mode == RGB_565_MODE
           && sensor_x1 + sensor_width <= ARRAY_WIDTH
           && sensor_y1 + sensor_height <= ARRAY_HEIGHT ? 0 : -1;
}

void e_poxxxx_write_cam_registers(void)
{
}

void e_poxxxx_launch_capture(char *buf)
{
    capture = buf;
}

/* The capture is taken now: the pixels as RGB565, big-endian. */
int e_poxxxx_is_img_ready(void)
{
    int i;
    if (capture == NULL)
        return 0;
    for (i = 0; i < STUB_CAMERA_PIXELS; i++) {
        unsigned r = camera_rgb[3 * i], g = camera_rgb[3 * i + 1], b = camera_rgb[3 * i + 2];
        unsigned v = ((r & 0xF8u) << 8) | ((g & 0xFCu) << 3) | (b >> 3);
        capture[2 * i] = (char)(v >> 8);
        capture[2 * i + 1] = (char)(v & 0xFFu);
    }
    capture = NULL;
    return 1;
}

/* ---- the e-puck2's RGB LEDs: each change of a colour is traced ---------------- */

void set_rgb_led(rgb_led_name_t led_number, uint8_t red_val, uint8_t green_val,
                 uint8_t blue_val)
{
    static long shown[NUM_RGB_LED];
    long colour = ((long)red_val << 16) | ((long)green_val << 8) | blue_val;

    if ((int)led_number < 0 || led_number >= NUM_RGB_LED || shown[led_number] == colour + 1)
        return;
    shown[led_number] = colour + 1;
    snprintf(json, sizeof json, ", \"led\": \"led%d\", \"red\": %d, \"green\": %d, "
             "\"blue\": %d", 2 * (int)led_number + 1, red_val, green_val, blue_val);
    stub_observe("rgb", json, (int)led_number);
}
