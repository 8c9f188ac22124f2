/*
 * camera.c - the e-puck's camera as the library's driver gives it
 * (camera/fast_2_timer/e_poxxxx.h; written from its documented behaviour,
 * none of its code): a PO3030K (e_poxxxx_init_cam returns 0x3030) mounted
 * as on GCtronic's first e-pucks, without rotation (the EEPROM's last word
 * says so: 0xFFFF, dspic.c): its image is 480 wide and 640 tall, the
 * sensor's 480 rows running across the field (e_poxxxx_get_orientation 0),
 * so a window one column wide and 480 rows tall is a line across the
 * world, the one GCtronic's camera demo reads.
 *
 * What it sees is what stub_set_camera last gave (Enki's camera in a
 * world: 60 pixels, a degree each, across 60 degrees; black on the harness
 * alone): the sensor's 480 rows are those 60 pixels, 8 rows to a pixel,
 * from the right (its row 0) to the left, the other way with the vertical
 * mirror (e_poxxxx_set_mirror(1, ...)); every column sees the same line
 * (the world is flat).
 *
 * e_poxxxx_config_cam takes the library's window, zoom and mode and
 * returns, as the PO3030K's driver, 0, or -1 when the window leaves the
 * sensor, its width or height is not a multiple of its zoom, a zoom is 0,
 * the mode is unknown or a line is too long for the driver's timer table
 * (330 entries: pixels x bytes a pixel x the zoom left after the sensor's
 * own subsampling).  A capture takes a pixel every `zoom` columns and rows
 * of the window (its middle one), in the mode's bytes: GREY_SCALE_MODE one
 * byte of luminance (0.299 r + 0.587 g + 0.114 b: white near 255),
 * RGB_565_MODE two bytes (high first), YUV_MODE two bytes a pixel as
 * U Y V Y pairs.  It is ready one frame after e_poxxxx_launch_capture, a
 * frame taking what the driver's clock divider makes it (the sensor
 * subsamples by 4, 2 or 1 as both zooms allow; grey divides by 2, 4, 8,
 * colour by 4, 8, 16): 8.6 frames a second in grey at a zoom of 4 or 8,
 * 4.3 in colour, as GCtronic measured for the e-puck.
 */
#include <stdio.h>
#include <string.h>

#include "epuck_stub.h"
#include "library_sim.h"
#include "camera/fast_2_timer/e_poxxxx.h"

#define COST() do { if (stub_cost_hook != NULL) stub_cost_hook(1L, STUB_CALL_CYCLES); } while (0)
#define CAMERA_VERSION 0x3030
#define LINE_CONF 330               /* the driver's timer table */
#define ROWS_A_PIXEL 8              /* of the sensor's 480 rows, to one of Enki's pixels */

static unsigned char seen[3 * STUB_CAMERA_PIXELS];

void stub_set_camera(const unsigned char *rgb, int pixels)
{
    stub_input_set();
    if (pixels > STUB_CAMERA_PIXELS)
        pixels = STUB_CAMERA_PIXELS;
    memcpy(seen, rgb, (size_t)(3 * pixels));
}

static struct {
    int configured;
    unsigned int x1, y1, zoom_w, zoom_h;
    int columns, rows, bpp, mode, divider;
    int mirror_v, mirror_h;
    char *buffer;                   /* the capture going on */
    unsigned long long ready_at;    /* cycles */
    int ready;
} cam;

int e_poxxxx_init_cam(void)
{
    COST();
    cam.mirror_v = cam.mirror_h = 0;    /* as the library's init of the PO3030K */
    return CAMERA_VERSION;
}

/* 0: vertical, 480 x 640 (the library's, from the EEPROM's last word) */
int e_poxxxx_get_orientation(void)
{
    return 0;
}

static int bytes_per_pixel(int mode)
{
    return mode == GREY_SCALE_MODE ? 1 : 2;
}

int e_poxxxx_apply_timer_config(int pixel_row, int pixel_col, int bpp, int pbp, int bbl)
{
    (void)bbl;
    if ((long)pixel_col * bpp * (1 + pbp) + 1 > LINE_CONF)
        return -1;
    cam.rows = pixel_row;
    cam.columns = pixel_col;
    cam.bpp = bpp;
    return 0;
}

int e_poxxxx_config_cam(unsigned int sensor_x1, unsigned int sensor_y1,
                        unsigned int sensor_width, unsigned int sensor_height,
                        unsigned int zoom_fact_width, unsigned int zoom_fact_height,
                        int color_mode)
{
    unsigned int sample;
    COST();
    cam.configured = 0;
    if (zoom_fact_height < 1 || zoom_fact_width < 1
            || sensor_x1 + sensor_width > ARRAY_WIDTH
            || sensor_y1 + sensor_height > ARRAY_HEIGHT
            || sensor_width % zoom_fact_width || sensor_height % zoom_fact_height
            || (color_mode != GREY_SCALE_MODE && color_mode != RGB_565_MODE
                && color_mode != YUV_MODE))
        return -1;
    /* the sensor subsamples by 4 or 2 where both zooms allow; the timers the rest */
    sample = zoom_fact_height % 4 == 0 && zoom_fact_width % 4 == 0 ? 4
             : zoom_fact_height % 2 == 0 && zoom_fact_width % 2 == 0 ? 2 : 1;
    if (e_poxxxx_apply_timer_config((int)(sensor_height / zoom_fact_height),
                                    (int)(sensor_width / zoom_fact_width),
                                    bytes_per_pixel(color_mode),
                                    (int)(zoom_fact_width / sample) - 1,
                                    (int)(zoom_fact_height / sample) - 1) != 0)
        return -1;
    cam.divider = (color_mode == GREY_SCALE_MODE ? 8 : 16) / (int)sample;
    cam.x1 = sensor_x1;
    cam.y1 = sensor_y1;
    cam.zoom_w = zoom_fact_width;
    cam.zoom_h = zoom_fact_height;
    cam.mode = color_mode;
    cam.configured = 1;
    return 0;
}

void e_poxxxx_write_cam_registers(void)
{
    COST();
}

void e_poxxxx_set_mirror(int vertical, int horizontal)
{
    COST();
    cam.mirror_v = vertical != 0;
    cam.mirror_h = horizontal != 0;
}

/* the sensor's own automatic white balance and exposure, its gains and
 * exposure time: taken, without effect on the simulated pixels (Enki's
 * colours, lit evenly) */
void e_poxxxx_set_awb_ae(int awb, int ae)
{
    (void)awb;
    (void)ae;
    COST();
}

void e_poxxxx_set_rgb_gain(unsigned char r, unsigned char g, unsigned char b)
{
    (void)r;
    (void)g;
    (void)b;
    COST();
}

void e_poxxxx_set_exposure(unsigned long exp)
{
    (void)exp;
    COST();
}

/* a frame's time, in cycles: 8.6 frames a second at the driver's clock
 * divided by 2 */
static unsigned long long frame_cycles(void)
{
    return (unsigned long long)((double)STUB_FCY * cam.divider / 17.2);
}

void e_poxxxx_launch_capture(char *buf)
{
    static int warned;
    COST();
    cam.ready = 0;
    cam.buffer = NULL;
    if (!cam.configured) {
        if (!warned)
            fprintf(stderr, "epuckc: note: e_poxxxx_launch_capture before a configuration "
                    "that e_poxxxx_config_cam took (it returns 0): the capture never ends\n");
        warned = 1;
        return;
    }
    cam.buffer = buf;
    cam.ready_at = stub_now_cycles() + frame_cycles();
}

/* what the sensor's row r sees: r, g, b (row 0 the rightmost, unless the
 * vertical mirror turns it) */
static void at_row(long r, unsigned int rgb[3])
{
    long p;
    int k;
    if (!cam.mirror_v)
        r = ARRAY_HEIGHT - 1 - r;
    p = r / ROWS_A_PIXEL;       /* from the left */
    for (k = 0; k < 3; k++)
        rgb[k] = p >= 0 && p < STUB_CAMERA_PIXELS ? seen[3 * p + k] : 0u;
}

static unsigned char luma(const unsigned int rgb[3])
{
    return (unsigned char)((77u * rgb[0] + 150u * rgb[1] + 29u * rgb[2] + 128u) >> 8);
}

static unsigned char chroma(const unsigned int a[3], const unsigned int b[3], int v)
{
    long r = (long)(a[0] + b[0]) / 2, g = (long)(a[1] + b[1]) / 2, bl = (long)(a[2] + b[2]) / 2;
    long c = v ? 128 + (128 * r - 107 * g - 21 * bl) / 256 : 128 + (-43 * r - 85 * g + 128 * bl) / 256;
    return (unsigned char)(c < 0 ? 0 : c > 255 ? 255 : c);
}

/* the frame into the program's buffer, line after line: the pixels of a
 * line are of one row of the sensor (every column sees the same) */
static void take(void)
{
    unsigned char *out = (unsigned char *)cam.buffer;
    unsigned int rgb[3], next[3];
    int i, line;
    for (line = 0; line < cam.rows; line++) {
        long r = (long)cam.y1 + (long)line * cam.zoom_h + cam.zoom_h / 2;
        at_row(r, rgb);
        for (i = 0; i < cam.columns; i++) {
            if (cam.mode == GREY_SCALE_MODE) {
                *out++ = luma(rgb);
            } else if (cam.mode == RGB_565_MODE) {
                unsigned int v = ((rgb[0] & 0xF8u) << 8) | ((rgb[1] & 0xFCu) << 3) | (rgb[2] >> 3);
                *out++ = (unsigned char)(v >> 8);
                *out++ = (unsigned char)(v & 0xFFu);
            } else {
                at_row(r, next);    /* the pair's other pixel: the same row */
                *out++ = chroma(rgb, next, i & 1);
                *out++ = luma(rgb);
            }
        }
    }
    cam.buffer = NULL;
    cam.ready = 1;
}

int e_poxxxx_is_img_ready(void)
{
    COST();
    if (cam.buffer != NULL && stub_now_cycles() >= cam.ready_at)
        take();
    return cam.ready;
}

/* The first ms m whose stub_camera_ms takes the frame coming: the cycle m
 * began at (stub_ms_cycles(m)) is past its ready time. */
long stub_camera_next_ms(void)
{
    long m;
    if (cam.buffer == NULL)
        return -1L;
    m = (long)(cam.ready_at * 1000ULL / STUB_FCY);
    while (stub_ms_cycles(m) < cam.ready_at)
        m++;
    return m;
}

void stub_camera_ms(long now_ms, long n)
{
    (void)now_ms;
    (void)n;
    if (cam.buffer != NULL && stub_now_cycles() >= cam.ready_at)
        take();
}

void stub_camera_reset(void)
{
    memset(&cam, 0, sizeof cam);
}
