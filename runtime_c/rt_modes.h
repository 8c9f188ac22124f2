/*
 * rt_modes.h - modes (rt_modes.c), for the walk: the state of the current
 * mode is the registry's (rt_registry.h).  Builds on rt_motion.h.
 */
#ifndef RT_MODES_H
#define RT_MODES_H

#include "rt_motion.h"

/* At the start of the poll after an entry: the current mode's table events
 * are armed again. */
void rt_mode_arm(void);
/* mainloop starts: traces a mode entered before it */
void rt_modes_loop_start(void);

#endif
