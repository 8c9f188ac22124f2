/*
 * rt_odometry.c - the robot's geometry (set_robot_geometry: what converts
 * millimetres and degrees into steps) and the odometry that the language's
 * x, y and heading read.  Motion (rt_motion.c) gives it each poll's steps.
 * A layer of the core on rt_clock.c (rt_odometry.h); part of the runtime
 * behind epuckrt.h.
 */
#include "rt_odometry.h"

/* The geometry that converts millimetres and degrees (set_robot_geometry). */
long rt_geo_circumference_um = EPUCK_WHEEL_CIRCUMFERENCE_UM;
long rt_geo_axle_um = EPUCK_AXLE_UM;
long rt_geo_steps_per_rev = EPUCK_STEPS_PER_REV;

void set_robot_geometry(long wheel_circumference_um, long axle_um, long steps_per_rev)
{
    if (wheel_circumference_um <= 0 || wheel_circumference_um > EPUCK_MAX_GEOMETRY_UM
        || axle_um <= 0 || axle_um > EPUCK_MAX_GEOMETRY_UM
        || steps_per_rev <= 0 || steps_per_rev > EPUCK_MAX_STEPS_PER_REV)
        return;
    rt_geo_circumference_um = wheel_circumference_um;
    rt_geo_axle_um = axle_um;
    rt_geo_steps_per_rev = steps_per_rev;
    rt_geometry(wheel_circumference_um, axle_um, steps_per_rev);
}

/* ---- odometry ---------------------------------------------------------------------
 * From the wheels' steps alone, in integers, so that every target computes
 * the same pose.  The heading follows from the difference of the wheels'
 * total steps (no drift from rounding); the position is summed poll by
 * poll along the heading, in micrometres times 2^15. */

int rt_odometry_used;
static long total_left, total_right;
static long long pos_x, pos_y;          /* um * 32768 */
static unsigned theta;                  /* heading, 1/65536 turn (16 bits) */

/* sin of 0..90 degrees in 64 steps, times 32767 */
static const int quarter_sine[65] = {
    0, 804, 1608, 2410, 3212, 4011, 4808, 5602, 6393, 7179, 7962, 8739, 9512, 10278,
    11039, 11793, 12539, 13279, 14010, 14732, 15446, 16151, 16846, 17530, 18204, 18868,
    19519, 20159, 20787, 21403, 22005, 22594, 23170, 23731, 24279, 24811, 25329, 25832,
    26319, 26790, 27245, 27683, 28105, 28510, 28898, 29268, 29621, 29956, 30273, 30571,
    30852, 31113, 31356, 31580, 31785, 31971, 32137, 32285, 32412, 32521, 32609, 32678,
    32728, 32757, 32767
};

/* sin(angle * 2 pi / 65536) * 32767, interpolated in the table */
static long sine(unsigned angle)
{
    unsigned a = angle & 0xFFFFu;
    unsigned quadrant = a >> 14, within = a & 0x3FFFu, index, frac;
    long v;

    if (quadrant & 1u)
        within = 0x4000u - within;          /* 0x4000: the table's last entry */
    index = within >> 8;
    frac = within & 0xFFu;
    v = quarter_sine[index];
    if (index < 64)
        v += ((long)(quarter_sine[index + 1] - quarter_sine[index]) * (long)frac) / 256L;
    return quadrant >= 2 ? -v : v;
}

static unsigned heading_of(long diff)
{
    /* turns = diff * circumference / (steps_per_rev * axle * 2 pi), 2 pi = 710/113 */
    long long num = (long long)diff * rt_geo_circumference_um * 113LL;
    long long den = (long long)rt_geo_steps_per_rev * rt_geo_axle_um * 710LL;
    long long r = num % den;

    if (r < 0)
        r += den;
    while (den >= (1LL << 46)) {            /* so that r * 65536 fits */
        den /= 2;
        r /= 2;
    }
    return (unsigned)(((r * 65536LL) / den) & 0xFFFFLL);
}

void rt_use_odometry(void)
{
    rt_odometry_used = 1;
}

void rt_odometry(long dl, long dr)
{
    unsigned before = theta, mid;
    long long ds, scale;

    if (!rt_odometry_used || (dl == 0 && dr == 0))
        return;
    ds = (long long)(dl + dr) * rt_geo_circumference_um;    /* um * 2 * steps_per_rev */
    scale = 2LL * rt_geo_steps_per_rev;
    total_left += dl;
    total_right += dr;
    theta = heading_of(total_right - total_left);
    /* the heading half-way through the poll's move */
    mid = (before + (((theta - before) & 0xFFFFu) >= 0x8000u
                     ? 0x10000u - ((0x10000u - ((theta - before) & 0xFFFFu)) / 2u)
                     : ((theta - before) & 0xFFFFu) / 2u)) & 0xFFFFu;
    pos_x += ds * sine(mid + 0x4000u) / scale;
    pos_y += ds * sine(mid) / scale;
}

static int to_mm(long long q)
{
    long long mm = q / (32767LL * 1000LL);
    return mm < RT_INT_MIN ? RT_INT_MIN : mm > RT_INT_MAX ? RT_INT_MAX : (int)mm;
}

int rt_x_mm(void)
{
    return to_mm(pos_x);
}

int rt_y_mm(void)
{
    return to_mm(pos_y);
}

int rt_heading_deg(void)
{
    long deg = ((long)theta * 360L + 32768L) / 65536L;     /* 0..360 */
    return (int)(deg >= 180 ? deg - 360 : deg);
}
