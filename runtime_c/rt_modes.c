/*
 * rt_modes.c - modes (extension): entering a mode, what it re-arms and
 * disarms, and the `on enter` event.  Part of the runtime behind epuckrt.h;
 * see epuckrt.c.
 */
#include "rt_internal.h"

/* Modes: the current one (0: none), entries so far, and whether a mode was
 * entered during this poll's walk (then no mode's event fires until the
 * next poll). */
int rt_current_mode;
int rt_mode_entered_in_poll;
int rt_mode_entry_pending;           /* its `on enter` events go first */
int rt_mode_trace_pending;      /* enter_mode before mainloop */
int rt_mode_arm_pending;        /* the current mode's table events wait to be armed */

/* At the start of the poll after an entry: the current mode's table events
 * are re-armed as at registration (their latch and memory too); those
 * cancelled with cancel_event are gone for good. */
void rt_mode_arm(void)
{
    int i, mode = rt_current_mode;

    rt_mode_arm_pending = 0;
    for (i = 0; i < rt_s_events; i++) {
        const rt_event *e = &rt_prog->events[i];
        if (e->mode == mode && mode != 0 && !BIT_GET(rt_ev_dead, i)) {
            BIT_SET(rt_ev_armed, i);
            BIT_CLEAR(rt_ev_latch, i);
            if (e->memory != RT_NO_MEMORY)
                rt_prog->memory[e->memory] = 0;
        }
    }
}

/* ---- extension: modes ---------------------------------------------------------- */

void enter_mode(int mode)
{
    int i, left = rt_current_mode;

    if (mode <= 0)
        return;
    rt_current_mode = mode;
    /* No event of any mode fires in the rest of this poll: the table's are
     * disarmed now, and the new mode's armed at the next poll
     * (rt_mode_arm), so that the poll's walk needs no mode test. */
    for (i = 0; i < rt_s_events; i++) {
        if (rt_prog->events[i].mode != 0)
            BIT_CLEAR(rt_ev_armed, i);
    }
    rt_mode_arm_pending = 1;
    for (i = 0; i < rt_n_events; i++) {
        if (rt_event_ext[i].mode == mode && rt_events[i].event_function != NULL) {
            rt_events[i].valid_flag = 1;
            rt_events[i].status.occurred = 0;
            rt_events[i].status.memory = 0;
        }
    }
    if (rt_current_event_id >= 0 && rt_event_mode(rt_current_event_id) == mode)
        rt_current_rearmed = 1;     /* the rule entering its own mode again */
    rt_mode_entry_pending = 1;
    if (!rt_initialised) {
        rt_mode_trace_pending = 1;     /* traced when mainloop starts */
        return;
    }
    rt_mode_entered_in_poll = 1;
    rt_trace_mode(mode);
    if (left == 0)
        return;
    /* what the rules of the mode left were doing with the motors ends */
    rt_holds_release(left);
    if (rt_seq != NULL && rt_seq_event_id >= 0 && rt_event_mode(rt_seq_event_id) == left) {
        rt_seq_generation++;
        rt_seq = NULL;
        rt_seq_waiting = 0;
        rt_seq_delay = 0;
    }
    if (rt_motion.active && rt_motion.owner >= 0 && rt_event_mode(rt_motion.owner) == left) {
        /* stopped without a stop_motor event: the motion did not end, its
         * mode did (the new mode's stop_motor rules must not take it for
         * the end of a motion of theirs) */
        rt_motion.active = 0;
        rt_seen_moving = 0;
        rt_wheels(0, 0);
        rt_motors_changed();
    }
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
