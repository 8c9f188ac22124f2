/*
 * rt_registry.c - what is registered (Ochiai et al., section 4.1): the two
 * fixed arrays and the static tables of a compiled program, registration and
 * cancellation (paper table 1), each event's priority, mode and hold, the
 * current mode, who holds the motors by a condition, and which event's
 * action runs now.  The layer of the core on rt_sensors.c and rt_clock.c;
 * motion, the language, modes and the walk build on it (rt_registry.h).
 * Part of the runtime behind epuckrt.h; docs/runtime.md shows the layers.
 */
#include "rt_registry.h"

#if MAX_ACTIONS < 1 || MAX_EVENTS < 1
#error "MAX_ACTIONS and MAX_EVENTS must be at least 1"
#endif

/* ---- the two arrays (paper 4.1): ids are indices, slots never reused ---- */
static action actions[MAX_ACTIONS];
event rt_events[MAX_EVENTS];
static int n_actions;   /* slots used so far, cancelled ones included */
int rt_n_events;

/* Each array event's priority, mode and hold (rt_registry.h). */
struct rt_event_ext rt_event_ext[MAX_EVENTS];
/* 1 once any event has a priority or a mode: the walk then goes by
 * priority levels (poll_ranked); 0: every priority is 0 and there are no
 * modes, and the walk is the plain one in id order. */
int rt_ranked;

/* ---- the static tables (register_program) ----------------------------------
 * Ids 0..s_actions-1 and 0..s_events-1 are the program's table entries; the
 * arrays' ids follow (array index + s_actions / s_events).  The program's
 * RAM state is seven bit planes of 16-bit words for the events (and one
 * for the actions), bit k % 16 of word k / 16
 * for entry k: */
const rt_program *rt_prog;      /* NULL: none registered */
static int s_actions;               /* its table sizes, 0 without one */
int rt_s_events;
unsigned rt_s_words;               /* RT_WORDS(s_events) */
static unsigned *action_off;        /* the action was cancelled */
unsigned *rt_ev_armed;          /* the event is armed (valid_flag) */
unsigned *rt_ev_repeat;            /* repeat_flag */
unsigned *rt_ev_latch;          /* compiled condition at its last poll */
unsigned *rt_ev_now;               /* compiled conditions of this poll */
unsigned *rt_ev_compiled;          /* the event is a compiled condition */
static unsigned *ev_dead;           /* cancel_event: not re-armed by enter_mode */
unsigned *rt_ev_hold;           /* holds the motors by its condition or guard */

/* An event's priority and mode, by id (table or array). */
int rt_event_priority(int id)
{
    return id < rt_s_events ? rt_prog->events[id].priority : rt_event_ext[id - rt_s_events].priority;
}

int rt_event_mode(int id)
{
    return id < rt_s_events ? rt_prog->events[id].mode : rt_event_ext[id - rt_s_events].mode;
}

/* How an event's rule holds the motors it commanded (docs/runtime.md,
 * "Holding the motors"): the table entry's flags say it; a compiled
 * condition, event_sensor and event_ambient are conditions on either path. */
int rt_hold_kind(int id)
{
    event_func f;
    unsigned flags = 0;

    if (id < rt_s_events) {
        f = rt_prog->events[id].event_function;
        flags = rt_prog->events[id].flags;
        if (f == NULL)
            return RT_HOLD_WHILE;
    } else {
        f = rt_events[id - rt_s_events].event_function;
    }
    if (flags & RT_HOLD_GUARD)
        return RT_HOLD_GUARD;
    if ((flags & RT_HOLD_WHILE) || f == event_sensor || f == sensor || f == event_ambient)
        return RT_HOLD_WHILE;
    return 0;
}

/* ---- what runs now (the walk sets it; motion, modes and the language read it) ---- */

int rt_exit_requested;      /* set by exit_main, checked by mainloop */
unsigned rt_stir;           /* counts what a poll can change (rt_registry.h) */
int rt_looping;             /* mainloop is polling */
int rt_current_action_id = -1;  /* the action being run by mainloop */
int rt_current_event_id = -1;   /* the event whose action runs (-1: none) */
int rt_current_rearmed;         /* its action entered its mode again: it stays armed */
int rt_firing_event = -1;       /* the event whose action mainloop runs (-1: none) */
int rt_polled_event = -1;       /* the event whose function was called last */

/* The current mode (0: none) and what its entry left to do (rt_modes.c
 * enters modes; the registry arms a new table's events by it). */
int rt_current_mode;
int rt_mode_entered_in_poll;
int rt_mode_entry_pending;      /* its `on enter` events go first */
int rt_mode_arm_pending;        /* the current mode's table events wait to be armed */

/* ---- holding the motors (docs/runtime.md, "Holding the motors") ----------
 * An event holds the motors while its bounded motion runs (rt_motion.owner),
 * while its sequence is in progress (rt_motion.c's seq_event_id), and, for
 * a condition (RT_HOLD_WHILE) or a guarded periodic rule (RT_HOLD_GUARD)
 * that commanded them when it fired, while its condition stays true or
 * until a period whose guard is false: its hold bit (a table event's plane,
 * an array event's rt_event_ext).  rt_holds counts the bits, so that a
 * program that holds nothing by a condition pays nothing for them. */
int rt_holds;

static int hold_bit(int id)
{
    return id < rt_s_events ? BIT_GET(rt_ev_hold, id) : rt_event_ext[id - rt_s_events].hold;
}

void rt_hold_put(int id, int on)
{
    if (hold_bit(id) == on)
        return;
    if (id >= rt_s_events)
        rt_event_ext[id - rt_s_events].hold = on;
    else if (on)
        BIT_SET(rt_ev_hold, id);
    else
        BIT_CLEAR(rt_ev_hold, id);
    rt_holds += on ? 1 : -1;
    rt_stir++;
}

void rt_hold_release(int id)
{
    if (rt_holds > 0 && id >= 0 && id < rt_s_events + rt_n_events)
        rt_hold_put(id, 0);
}

void rt_holds_release(int mode)
{
    int id;

    for (id = 0; rt_holds > 0 && id < rt_s_events + rt_n_events; id++) {
        if (mode < 0 || rt_event_mode(id) == mode)
            rt_hold_put(id, 0);
    }
}

/* The first event from `id` on whose hold bit is set, or -1: the table's a
 * word at a time (epuckc numbers the events by priority, highest first, so
 * the holders, of high priority, come first), then the arrays'. */
int rt_next_holder(int id)
{
    while (id < rt_s_events) {
        unsigned w = rt_ev_hold[id >> 4] & WORD_MASK & ~(BIT_OF(id) - 1u);
        if (w != 0) {
            int k = 0;
            while (!((w >> k) & 1u))
                k++;
            return (id & ~15) + k;
        }
        id = (id | 15) + 1;
    }
    for (; id < rt_s_events + rt_n_events; id++) {
        if (rt_event_ext[id - rt_s_events].hold)
            return id;
    }
    return -1;
}

/* ---- paper table 1 -------------------------------------------------------- */

static int action_ok(int id)
{
    if (id >= 0 && id < s_actions)
        return !BIT_GET(action_off, id);
    id -= s_actions;
    return id >= 0 && id < n_actions && actions[id].action_function != NULL;
}

/* A registered event that was not cancelled (it may have fired and disarmed). */
static int event_ok(int id)
{
    if (id >= 0 && id < rt_s_events)
        return 1;   /* table events stay registered: cancel_event disarms them */
    id -= rt_s_events;
    return id >= 0 && id < rt_n_events && rt_events[id].event_function != NULL;
}

int register_action(action_func f, void *action_param)
{
    int id;
    if (f == NULL || n_actions >= MAX_ACTIONS)
        return -1;
    id = n_actions++;
    actions[id].action_function = f;
    actions[id].action_param = action_param;
    rt_new_action(s_actions + id, f);
    return s_actions + id;
}

int register_event(event_func f, void *event_param, int action_id)
{
    int id;
    event *e;
    if (f == NULL || rt_n_events >= MAX_EVENTS || !action_ok(action_id))
        return -1;
    id = rt_n_events++;
    e = &rt_events[id];
    e->event_function = f;
    e->event_param = event_param;
    e->action_id = action_id;
    e->valid_flag = 1;
    e->repeat_flag = 0;
    e->status.occurred = 0;
    e->status.memory = 0;
    rt_event_ext[id].priority = 0;
    rt_event_ext[id].mode = 0;
    rt_event_ext[id].hold = 0;
    if (f == event_remote)
        rt_remote_want();
    if (f == event_tap || f == event_tilt)
        rt_accel_wanted = 1;
    rt_new_event(rt_s_events + id, f);
    return rt_s_events + id;
}

void cancel_action(int action_id)
{
    if (!action_ok(action_id))
        return;
    if (action_id < s_actions) {
        BIT_SET(action_off, action_id);
        return;
    }
    /* A NULL function marks the slot cancelled; it is never reused. */
    action_id -= s_actions;
    actions[action_id].action_function = NULL;
    actions[action_id].action_param = NULL;
}

void cancel_event(int event_id)
{
    if (!event_ok(event_id))
        return;
    rt_hold_release(event_id);
    if (event_id < rt_s_events) {
        BIT_CLEAR(rt_ev_armed, event_id);
        BIT_SET(ev_dead, event_id);
        return;
    }
    event_id -= rt_s_events;
    rt_events[event_id].valid_flag = 0;
    rt_events[event_id].event_function = NULL;
}

void set_event_repeat(int event_id, int repeat)
{
    if (!event_ok(event_id))
        return;
    if (event_id < rt_s_events) {
        if (repeat)
            BIT_SET(rt_ev_repeat, event_id);
        else
            BIT_CLEAR(rt_ev_repeat, event_id);
        return;
    }
    rt_events[event_id - rt_s_events].repeat_flag = repeat != 0;
}

/* Priorities and modes of the arrays' events; a table event's are in its
 * rt_event (these ignore table ids). */
void set_event_priority(int event_id, int priority)
{
    if (event_id >= rt_s_events && event_ok(event_id)) {
        rt_event_ext[event_id - rt_s_events].priority = priority;
        if (priority != 0)
            rt_ranked = 1;
    }
}

void set_event_mode(int event_id, int mode)
{
    if (event_id >= rt_s_events && event_ok(event_id) && mode >= 0) {
        rt_event_ext[event_id - rt_s_events].mode = mode;
        if (mode != 0)
            rt_ranked = 1;
    }
}

void disarm_event(int event_id)
{
    if (!event_ok(event_id))
        return;
    rt_hold_release(event_id);
    if (event_id < rt_s_events)
        BIT_CLEAR(rt_ev_armed, event_id);
    else
        rt_events[event_id - rt_s_events].valid_flag = 0;
}

void (name_mode)(int mode, const char *name)
{
    if (mode > 0)
        rt_name_mode(mode, name);
}

/* Parenthesised: epuckrt.h may define them as macros (EPUCKRT_NO_NAMES). */
void (name_action)(int action_id, const char *name)
{
    if (action_id >= 0 && action_id < s_actions + n_actions)
        rt_name_action(action_id, name);
}

void (name_steps)(int action_id, const char *const *names, int count)
{
    if (action_id >= 0 && action_id < s_actions + n_actions && names != NULL && count > 0)
        rt_name_steps(action_id, names, count);
}

void (name_event)(int event_id, const char *name)
{
    if (event_id >= 0 && event_id < rt_s_events + rt_n_events)
        rt_name_event(event_id, name);
}

int register_program(const rt_program *p)
{
    int k, words_a, words_e;

    if (p == NULL || rt_prog != NULL || n_actions != 0 || rt_n_events != 0
            || p->n_actions < 0 || p->n_events < 0 || p->state == NULL
            || (p->n_actions > 0 && p->actions == NULL)
            || (p->n_events > 0 && p->events == NULL))
        return -1;
    for (k = 0; k < p->n_actions; k++) {
        if (p->actions[k].action_function == NULL)
            return -1;
    }
    for (k = 0; k < p->n_events; k++) {
        const rt_event *e = &p->events[k];
        if (e->action_id < 0 || e->action_id >= p->n_actions
                || (e->event_function == NULL && p->conditions == NULL)
                || (e->memory != RT_NO_MEMORY && (e->memory < 0 || p->memory == NULL))
                || e->mode < 0)
            return -1;
    }
    /* the order, strictly increasing by (priority downwards, id): then it
     * holds every event once */
    for (k = 0; p->order != NULL && k < p->n_events; k++) {
        int id = p->order[k], before;
        if (id < 0 || id >= p->n_events)
            return -1;
        if (k > 0) {
            before = p->order[k - 1];
            if (p->events[before].priority < p->events[id].priority
                    || (p->events[before].priority == p->events[id].priority && before >= id))
                return -1;
        }
    }
    words_a = RT_WORDS(p->n_actions);
    words_e = RT_WORDS(p->n_events);
    action_off = p->state;
    rt_ev_armed = action_off + words_a;
    rt_ev_repeat = rt_ev_armed + words_e;
    rt_ev_latch = rt_ev_repeat + words_e;
    rt_ev_now = rt_ev_latch + words_e;
    rt_ev_compiled = rt_ev_now + words_e;
    ev_dead = rt_ev_compiled + words_e;
    rt_ev_hold = ev_dead + words_e;
    for (k = 0; k < words_a + 7 * words_e; k++)
        p->state[k] = 0;
    for (k = 0; k < p->n_actions; k++)
        rt_new_action(k, p->actions[k].action_function);
    for (k = 0; k < p->n_events; k++) {
        const rt_event *e = &p->events[k];
        /* a mode's events are armed when it is entered (rt_mode_arm) */
        if (e->mode == 0 || (e->mode == rt_current_mode && !rt_mode_arm_pending))
            BIT_SET(rt_ev_armed, k);
        if (e->flags & RT_REPEAT)
            BIT_SET(rt_ev_repeat, k);
        if (e->event_function == NULL)
            BIT_SET(rt_ev_compiled, k);
        if (e->memory != RT_NO_MEMORY)
            p->memory[e->memory] = 0;
        /* epuckc numbers the events by priority, highest first: the table's
         * order is then the walk's, sixteen at a time; another order needs
         * the walk by levels */
        if (e->priority < 0 || (k > 0 && e->priority > p->events[k - 1].priority))
            rt_ranked = 1;
        if (e->event_function == event_remote)
            rt_remote_want();
        if (e->event_function == event_tap || e->event_function == event_tilt)
            rt_accel_wanted = 1;
        rt_new_event(k, e->event_function);
    }
    if (p->order != NULL)
        rt_ranked = 1;
    rt_prog = p;
    s_actions = p->n_actions;
    rt_s_events = p->n_events;
    rt_s_words = (unsigned)words_e;
    return 0;
}

/* The function and parameter of a registered action that was not
 * cancelled; 0 (and nothing set) for a cancelled or unknown id. */
int rt_action_of(int id, action_func *f, void **param)
{
    if (!action_ok(id))
        return 0;
    if (id < s_actions) {
        *f = rt_prog->actions[id].action_function;
        *param = (void *)rt_prog->actions[id].action_param;
    } else {
        *f = actions[id - s_actions].action_function;
        *param = actions[id - s_actions].action_param;
    }
    return 1;
}

/* ---- arming by mode (rt_modes.c enters modes) -------------------------------- */

/* The table's events of every mode are disarmed (an entry: none of them
 * fires in the rest of the poll). */
void rt_disarm_table_modes(void)
{
    int i;

    for (i = 0; i < rt_s_events; i++) {
        if (rt_prog->events[i].mode != 0)
            BIT_CLEAR(rt_ev_armed, i);
    }
}

/* The table's events of `mode` are re-armed as at registration (their latch
 * and memory too); those cancelled with cancel_event are gone for good. */
void rt_arm_table_mode(int mode)
{
    int i;

    for (i = 0; i < rt_s_events; i++) {
        const rt_event *e = &rt_prog->events[i];
        if (e->mode == mode && mode != 0 && !BIT_GET(ev_dead, i)) {
            BIT_SET(rt_ev_armed, i);
            BIT_CLEAR(rt_ev_latch, i);
            if (e->memory != RT_NO_MEMORY)
                rt_prog->memory[e->memory] = 0;
        }
    }
}

/* The arrays' events of `mode` that were not cancelled are armed, their
 * status as at registration. */
void rt_arm_array_mode(int mode)
{
    int i;

    for (i = 0; i < rt_n_events; i++) {
        if (rt_event_ext[i].mode == mode && rt_events[i].event_function != NULL) {
            rt_events[i].valid_flag = 1;
            rt_events[i].status.occurred = 0;
            rt_events[i].status.memory = 0;
        }
    }
}
