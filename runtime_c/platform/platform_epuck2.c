/*
 * platform_epuck2.c - the runtime's platform layer on the e-puck2
 * (STM32F407 under ChibiOS, GCtronic's e-puck2_main-processor firmware,
 * whose src/epuck1x layer offers the e-puck library's API).
 *
 * Two things differ from the e-puck (platform_robot.c):
 * - The poll is paced by ChibiOS: rt_platform_idle sleeps until the next
 *   1 ms deadline (chThdSleepUntilWindowed) and never spins, so that the
 *   firmware's threads that read the sensors and drive the motors run
 *   between two polls, whatever the runtime thread's priority.
 * - The epuck1x layer's agendas do nothing (there is no Timer2 to run
 *   them), so the runtime's millisecond clock is kept here: after each
 *   sleep, rt_clock_tick is called once for every millisecond of ChibiOS's
 *   system time since mainloop started (more than once after a poll that
 *   overran its millisecond).
 * The trace hooks (none) and the seed of `random` are platform_robot.c's,
 * built with EPUCKRT_EPUCK2 beside this file.
 */
#include "ch.h"
#include "rt_platform.h"

static systime_t counted;        /* system time the clock has counted up to */
static systime_t due;            /* the next poll's deadline */

void rt_platform_init(void)
{
    counted = chVTGetSystemTime();
    due = counted;
}

void rt_platform_idle(void)
{
    systime_t previous = due, now;
    unsigned long ms;

    due += MS2ST(1);
    /* sleeps until `due`; returns at once when `due` is already past */
    chThdSleepUntilWindowed(previous, due);
    now = chVTGetSystemTime();
    if ((systime_t)(now - due) >= (systime_t)MS2ST(1)
            && (systime_t)(now - due) < (systime_t)MS2ST(60000))
        due = now;          /* the poll overran: the next deadline counts from now */
    /* the clock: one tick per whole millisecond since it last counted
     * (differences of systime_t, so its wrapping does not matter) */
    ms = (unsigned long)((systime_t)(now - counted) / MS2ST(1));
    counted += (systime_t)(ms * MS2ST(1));
    while (ms-- > 0)
        rt_clock_tick();
}
