/*
 * rt_clock.c - the millisecond clock of the runtime (rt_platform.h), the
 * count of polls, and the device hook (rt_clock.h).  The first layer of the
 * core: it calls nothing of the others.  Part of the runtime behind
 * epuckrt.h; docs/runtime.md shows the layers.
 */
#include "rt_clock.h"

/* A 1 ms e-puck agenda (cycle 10 x 0.1 ms) counts; it runs in the Timer2
 * interrupt on the robot, hence volatile.  Unsigned so that the increment
 * never overflows a signed type. */
static volatile unsigned long ms_ticks;

int rt_initialised;
unsigned long rt_poll_count;
void (*rt_device_poll)(void);
int (*rt_device_idle)(void);

void rt_clock_tick(void)
{
    ms_ticks++;
}

void rt_clock_ticks(long k)
{
    ms_ticks += (unsigned long)k;
}

long rt_millis(void)
{
    unsigned long a, b;
    /* A 32-bit read is two 16-bit reads on the dsPIC: the interrupt may
     * change the value in between, so read until two reads agree. */
    do {
        a = ms_ticks;
        b = ms_ticks;
    } while (a != b);
    /* 30 bits: callers may add 1 and subtract without overflowing a 32-bit
     * long.  Wraps after 12.4 days. */
    return (long)(a & 0x3FFFFFFFUL);
}
