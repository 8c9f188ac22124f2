/*
 * rt_camera.c - the colour camera: the readings `seen(COLOUR)` and
 * `bearing(COLOUR)` (epuckrt.h), and the one colour classifier, rt_colour,
 * that every target shares.
 *
 * Below it, the e-puck library's camera API (camera/fast_2_timer/e_poxxxx.h):
 * on the e-puck the library's driver of its po3030/po6030/po8030, on the
 * e-puck2 the firmware's epuck1x layer over its po8030 and dcmi, on the host
 * host/camera.c (Enki's CircularCam in worlds).  It reads one subsampled
 * line across the field: RT_CAMERA_PIXELS pixels of RGB565 over 480 of the
 * sensor's pixels zoomed by 8 (60 degrees of the camera's field), 8 wide,
 * at the image's middle, along the sensor's axis that is horizontal on the
 * robot, as the library's e_poxxxx_get_orientation says (the e-puck's
 * camera is mounted one way or another from one hardware revision to the
 * next, GCtronic's EEPROM word says which): 0, the image 480 x 640, its
 * rows across (a column of 60 pixels, read right to left), 1, 640 x 480
 * (a row, left to right; the e-puck2's), 2, 640 x 480 upside down (a row,
 * right to left), as Aseba's e-puck target reads a row.  The first reading
 * of a poll takes the line if a capture is ready (and starts the next); the
 * line's pixels are classified once, when it is taken.
 */
#include "rt_clock.h"

#include "camera/fast_2_timer/e_poxxxx.h"

static char frame[2 * RT_CAMERA_PIXELS];    /* RGB565, two bytes a pixel, big-endian */
static int from_right;      /* the line's pixel 0 is its rightmost */
static unsigned char line[RT_CAMERA_PIXELS];    /* RT_NO_COLOUR or RT_RED..RT_MAGENTA */
static int started;
static unsigned long taken_in;  /* rt_poll_count of the last look */

/* The one classifier: 8-bit r, g, b to a colour.  Dark (the largest
 * component below 64) or grey (the spread between the largest and the
 * smallest below 35 % of the largest) is no colour; else the hue's sector
 * of 60 degrees: red around 0, yellow 60, green 120, cyan 180, blue 240,
 * magenta 300.  Whole-number arithmetic in long: the same on every target. */
int rt_colour(int r, int g, int b)
{
    long max = r, min = r, chroma, hue;

    if (g > max)
        max = g;
    if (b > max)
        max = b;
    if (g < min)
        min = g;
    if (b < min)
        min = b;
    chroma = max - min;
    if (max < 64L || chroma * 100L < max * 35L)
        return RT_NO_COLOUR;
    if (max == r)
        hue = 60L * (g - b) / chroma;
    else if (max == g)
        hue = 120L + 60L * (b - r) / chroma;
    else
        hue = 240L + 60L * (r - g) / chroma;
    if (hue < 0L)
        hue += 360L;
    if (hue >= 330L || hue < 30L)
        return RT_RED;
    return (int)((hue - 30L) / 60L) + RT_YELLOW;
}

static void look(void)
{
    int i;
    const unsigned char *px = (const unsigned char *)frame;

    if (!started) {
        int orientation;
        started = 1;
        e_poxxxx_init_cam();
        orientation = e_poxxxx_get_orientation();
        if (orientation == 0)       /* the rows across the field: a column */
            e_poxxxx_config_cam((ARRAY_WIDTH - 8) / 2, (ARRAY_HEIGHT - 8 * RT_CAMERA_PIXELS) / 2,
                                8, 8 * RT_CAMERA_PIXELS, 8, 8, RGB_565_MODE);
        else
            e_poxxxx_config_cam((ARRAY_WIDTH - 8 * RT_CAMERA_PIXELS) / 2, (ARRAY_HEIGHT - 8) / 2,
                                8 * RT_CAMERA_PIXELS, 8, 8, 8, RGB_565_MODE);
        from_right = orientation == 0 || orientation == 2;
        e_poxxxx_write_cam_registers();
        e_poxxxx_launch_capture(frame);
    }
    if (taken_in == rt_poll_count)
        return;
    taken_in = rt_poll_count;
    if (!e_poxxxx_is_img_ready())
        return;
    for (i = 0; i < RT_CAMERA_PIXELS; i++) {
        unsigned hi = px[2 * i], lo = px[2 * i + 1];
        line[from_right ? RT_CAMERA_PIXELS - 1 - i : i] =
            (unsigned char)rt_colour((int)(hi & 0xF8u), (int)(((hi & 7u) << 5) | ((lo >> 3) & 0x1Cu)),
                                     (int)((lo & 0x1Fu) << 3));
    }
    e_poxxxx_launch_capture(frame);
}

/* The widest run of `colour` in the line: its first pixel and its width. */
static int widest(int colour, int *start)
{
    int i, run = 0, best = 0;

    *start = 0;
    look();
    for (i = 0; i < RT_CAMERA_PIXELS; i++) {
        run = line[i] == colour ? run + 1 : 0;
        if (run > best) {
            best = run;
            *start = i - run + 1;
        }
    }
    return best;
}

int rt_seen(int colour)
{
    int start;
    return widest(colour, &start);
}

/* Pixel 0 is the leftmost; each covers one degree, pixel i's centre is at
 * 29.5 - i degrees (positive to the left). */
int rt_bearing(int colour)
{
    int start, width = widest(colour, &start);
    return width == 0 ? 0 : (RT_CAMERA_PIXELS - 2 * start - width) / 2;
}
