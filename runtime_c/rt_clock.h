/*
 * rt_clock.h - the bottom of the runtime's core (rt_clock.c): the
 * millisecond clock (rt_platform.h), the count of polls, whether the
 * runtime has started the library, and the hook of a device that works at
 * every poll.  Every other core file builds on it; it builds on none.
 */
#ifndef RT_CLOCK_H
#define RT_CLOCK_H

#include "rt_internal.h"

extern int rt_initialised;   /* the library is initialised (mainloop's start) */
extern unsigned long rt_poll_count;   /* polls so far: readings are read once in each */
/* A device that works at every poll (rt_comm.c: its transmitter and
 * receiver) sets this at its first use; the poll calls it first.  NULL:
 * none, and the core links without the device's files. */
extern void (*rt_device_poll)(void);
/* Set with it: 1 when the device's poll would change nothing while the
 * inputs stay as they are (rt_idle.c); NULL: unknown. */
extern int (*rt_device_idle)(void);

#endif
