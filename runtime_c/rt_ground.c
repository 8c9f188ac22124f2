/*
 * rt_ground.c - GCtronic's ground-sensor module: the readings ground0
 * (left), ground1 (centre) and ground2 (right) of epuckrt.h, over the
 * e-puck2 firmware's ground API (src/sensors/ground.h: ground_start,
 * get_ground_prox), which every target provides: the e-puck2's firmware
 * (a thread of its reads the module 25 times a second), the e-puck's
 * ground_i2c.c (the module over the e-puck library's I2C protocol), the
 * host's host/stub_ground.c (a scenario's groundN lines; in a world,
 * Enki's ground sensors over the floor).  Each reading is taken at most
 * once per poll and kept within 0..4095, the interval the checker knows.
 */
#include "rt_clock.h"

#include "sensors/ground.h"

static int started;
static int values[3];
static unsigned valid;              /* bit n: ground n read in this poll */
static unsigned long poll_seen;

int rt_ground(int sensor)
{
    int v;

    if (sensor < 0 || sensor > 2)
        return 0;
    if (!started) {
        started = 1;
        ground_start();
    }
    if (poll_seen != rt_poll_count) {
        poll_seen = rt_poll_count;
        valid = 0;
    }
    if (!(valid & (1u << sensor))) {
        v = get_ground_prox((unsigned)sensor);
        values[sensor] = v < 0 ? 0 : v > RT_GROUND_MAX ? RT_GROUND_MAX : v;
        valid |= 1u << sensor;
    }
    return values[sensor];
}
