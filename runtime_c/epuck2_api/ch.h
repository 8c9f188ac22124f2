/*
 * ch.h - declarations only: the few ChibiOS calls of platform_epuck2.c, with
 * ChibiOS's names and types (RT 17/18, as GCtronic's e-puck2_main-processor
 * firmware ships it in its ChibiOS submodule), so that the platform layer
 * compiles against the project's own headers (tests, CI). A real build
 * (`epuckc build --target epuck2`) uses the firmware's ChibiOS instead.
 */
#ifndef EPUCKRT_EPUCK2_API_CH_H
#define EPUCKRT_EPUCK2_API_CH_H

#include <stdint.h>

#ifndef CH_CFG_ST_FREQUENCY
#define CH_CFG_ST_FREQUENCY 10000       /* the firmware's chconf.h: 10 kHz ticks */
#endif

typedef uint32_t systime_t;

#define MS2ST(msec) ((systime_t)((((uint32_t)(msec)) * ((uint32_t)CH_CFG_ST_FREQUENCY) + 999UL) / 1000UL))

systime_t chVTGetSystemTime(void);
systime_t chThdSleepUntilWindowed(systime_t prev, systime_t next);

#endif
