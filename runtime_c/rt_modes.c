/*
 * rt_modes.c - modes (extension): entering a mode, what it re-arms and
 * disarms, and the `on enter` event.  The current mode, and whether a mode
 * was entered during this poll's walk (then no mode's event fires until the
 * next poll), are the registry's (rt_registry.h).  A layer of the core on
 * rt_motion.c (rt_modes.h); part of the runtime behind epuckrt.h.
 */
#include "rt_modes.h"

static int trace_pending;       /* enter_mode before mainloop */

/* At the start of the poll after an entry: the current mode's table events
 * are re-armed as at registration (their latch and memory too); those
 * cancelled with cancel_event are gone for good. */
void rt_mode_arm(void)
{
    rt_mode_arm_pending = 0;
    rt_arm_table_mode(rt_current_mode);
}

/* mainloop starts: a mode entered before it is traced now. */
void rt_modes_loop_start(void)
{
    if (trace_pending) {
        trace_pending = 0;
        rt_trace_mode(rt_current_mode);
    }
}

/* ---- extension: modes ---------------------------------------------------------- */

void enter_mode(int mode)
{
    int left = rt_current_mode;

    if (mode <= 0)
        return;
    rt_current_mode = mode;
    /* No event of any mode fires in the rest of this poll: the table's are
     * disarmed now, and the new mode's armed at the next poll
     * (rt_mode_arm), so that the poll's walk needs no mode test. */
    rt_disarm_table_modes();
    rt_mode_arm_pending = 1;
    rt_arm_array_mode(mode);
    if (rt_current_event_id >= 0 && rt_event_mode(rt_current_event_id) == mode)
        rt_current_rearmed = 1;     /* the rule entering its own mode again */
    rt_mode_entry_pending = 1;
    if (!rt_initialised) {
        trace_pending = 1;     /* traced when mainloop starts */
        return;
    }
    rt_mode_entered_in_poll = 1;
    rt_trace_mode(mode);
    if (left == 0)
        return;
    /* what the rules of the mode left were doing with the motors ends */
    rt_holds_release(left);
    rt_motion_leave_mode(left);
}

void action_enter_mode(void *param)
{
    const param_enter_mode *p = (const param_enter_mode *)param;

    if (p != NULL)
        enter_mode(p->mode);
}

/* Occurs at its first poll after it was (re-)armed: mode entries reset
 * status->memory to 0. */
void event_enter_mode(void *param, void *status)
{
    event_status *st = (event_status *)status;

    (void)param;
    st->occurred = st->memory == 0;
    st->memory = 1;
}
