/*
 * epuckrt.c - the core of the event-driven runtime (Ochiai et al., sections
 * 3-4): the two fixed arrays and the static tables, registration, the
 * millisecond clock and the polling main loop (figure 4) with its walks.
 * Motion and the sequencer are rt_motion.c, the standard events, sensors and
 * devices rt_sensors.c, modes rt_modes.c; rt_internal.h is what they share.
 *
 * The hardware is reached only through the e-puck library API (the real
 * library on the robot, host/epuck_stub.c on a PC) and rt_platform.h.
 * Written for 16-bit int: every count of steps or milliseconds that can pass
 * 32767 is long; products that can pass 2^31 are long long.
 * docs/runtime.md describes the semantics implemented here.
 */
#include "rt_internal.h"

#if MAX_ACTIONS < 1 || MAX_EVENTS < 1
#error "MAX_ACTIONS and MAX_EVENTS must be at least 1"
#endif

/* ---- the two arrays (paper 4.1): ids are indices, slots never reused ---- */
static action actions[MAX_ACTIONS];
event rt_events[MAX_EVENTS];
static int n_actions;   /* slots used so far, cancelled ones included */
int rt_n_events;

/* Each array event's priority and mode (rt_internal.h). */
struct rt_event_ext rt_event_ext[MAX_EVENTS];
/* 1 once any event has a priority or a mode: the walk then goes by
 * priority levels (poll_ranked); 0: every priority is 0 and there are no
 * modes, and the walk is the plain one in id order. */
static int ranked;

/* ---- the static tables (register_program) ----------------------------------
 * Ids 0..s_actions-1 and 0..s_events-1 are the program's table entries; the
 * arrays' ids follow (array index + s_actions / s_events).  The program's
 * RAM state is seven bit planes of 16-bit words for the events (and one
 * for the actions), bit k % 16 of word k / 16
 * for entry k: */
const rt_program *rt_prog;      /* NULL: none registered */
static int s_actions;               /* its table sizes, 0 without one */
int rt_s_events;
static unsigned s_words;            /* RT_WORDS(s_events) */
static unsigned *action_off;        /* the action was cancelled */
unsigned *rt_ev_armed;          /* the event is armed (valid_flag) */
static unsigned *ev_repeat;         /* repeat_flag */
unsigned *rt_ev_latch;          /* compiled condition at its last poll */
static unsigned *ev_now;            /* compiled conditions of this poll */
static unsigned *ev_compiled;       /* the event is a compiled condition */
unsigned *rt_ev_dead;           /* cancel_event: not re-armed by enter_mode */
unsigned *rt_ev_hold;           /* holds the motors by its condition or guard */
static int conditions_valid;        /* ev_now holds this poll's conditions */


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

/* ---- millisecond clock ---------------------------------------------------
 * A 1 ms e-puck agenda (cycle 10 x 0.1 ms) counts; it runs in the Timer2
 * interrupt on the robot, hence volatile.  Unsigned so that the increment
 * never overflows a signed type. */
static volatile unsigned long ms_ticks;

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

int rt_initialised;
static int remote_wanted;       /* an event_remote was registered */
int rt_remote_started;      /* e_init_remote_control() has run */
int rt_accel_wanted;             /* an event_tap or event_tilt was registered */

static void remote_start(void)
{
    if (remote_wanted && rt_initialised && !rt_remote_started) {
        rt_remote_started = 1;
        e_init_remote_control();
    }
}

static void rt_init(void)
{
    if (rt_initialised)
        return;
    rt_initialised = 1;
    /* the agenda variant's start-up order, then the A/D scan (Webots'
     * e-puck cross-compilation layer does the same) */
    e_init_port();
    e_start_agendas_processing();
    e_init_motors();
    e_init_ad_scan(ALL_ADC);
    (void)e_activate_agenda(rt_clock_tick, 10);
    rt_platform_init();
    remote_start();     /* only for programs that use the remote control */
}

/* ---- state of the standard actions and events --------------------------- */

int rt_exit_requested;      /* set by exit_main, checked by mainloop */
unsigned rt_stir;           /* counts what a poll can change (rt_internal.h) */
int rt_looping;             /* mainloop is polling */
int rt_current_action_id = -1;  /* the action being run by mainloop */
int rt_current_event_id = -1;   /* the event whose action runs (-1: none) */
int rt_current_rearmed;         /* its action entered its mode again: it stays armed */
int rt_firing_event = -1;       /* the event whose action mainloop runs (-1: none) */
int rt_polled_event = -1;       /* the event whose function was called last */

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
    if (f == event_remote) {
        remote_wanted = 1;
        remote_start();
    }
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
        BIT_SET(rt_ev_dead, event_id);
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
            BIT_SET(ev_repeat, event_id);
        else
            BIT_CLEAR(ev_repeat, event_id);
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
            ranked = 1;
    }
}

void set_event_mode(int event_id, int mode)
{
    if (event_id >= rt_s_events && event_ok(event_id) && mode >= 0) {
        rt_event_ext[event_id - rt_s_events].mode = mode;
        if (mode != 0)
            ranked = 1;
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
    ev_repeat = rt_ev_armed + words_e;
    rt_ev_latch = ev_repeat + words_e;
    ev_now = rt_ev_latch + words_e;
    ev_compiled = ev_now + words_e;
    rt_ev_dead = ev_compiled + words_e;
    rt_ev_hold = rt_ev_dead + words_e;
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
            BIT_SET(ev_repeat, k);
        if (e->event_function == NULL)
            BIT_SET(ev_compiled, k);
        if (e->memory != RT_NO_MEMORY)
            p->memory[e->memory] = 0;
        /* epuckc numbers the events by priority, highest first: the table's
         * order is then the walk's, sixteen at a time; another order needs
         * the walk by levels */
        if (e->priority < 0 || (k > 0 && e->priority > p->events[k - 1].priority))
            ranked = 1;
        if (e->event_function == event_remote)
            remote_wanted = 1;
        if (e->event_function == event_tap || e->event_function == event_tilt)
            rt_accel_wanted = 1;
        rt_new_event(k, e->event_function);
    }
    if (p->order != NULL)
        ranked = 1;
    remote_start();
    rt_prog = p;
    s_actions = p->n_actions;
    rt_s_events = p->n_events;
    s_words = (unsigned)words_e;
    return 0;
}

void action_exit_main(void *param)
{
    (void)param;
    rt_exit_requested = 1;
}

/* ---- the paper's short spellings -------------------------------------------- */

void start_straight(void *param) { action_start_straight(param); }
void start_curve(void *param) { action_start_curve(param); }
void straight_steps(void *param) { action_straight_steps(param); }
void curve_steps(void *param) { action_curve_steps(param); }
void stop_motor(void *param) { action_stop_motor(param); }
void set_timer(void *param) { action_set_timer(param); }
void reset_timer(void *param) { action_reset_timer(param); }
void start_sensor(void *param) { action_start_sensor(param); }
void stop_sensor(void *param) { action_stop_sensor(param); }
void exit_main(void *param) { action_exit_main(param); }
void run_sequence(void *param) { action_run_sequence(param); }
void sensor(void *param, void *status) { event_sensor(param, status); }
void timer(void *param, void *status) { event_timer(param, status); }
void immediate(void *param, void *status) { event_immediate(param, status); }

/* ---- main loop (paper figure 4) ---------------------------------------------- */

static void run_action(int action_id)
{
    int previous = rt_current_action_id;
    action_func f;
    void *param;

    if (!action_ok(action_id))
        return;     /* cancelled: the event fires but runs nothing */
    if (action_id < s_actions) {
        f = rt_prog->actions[action_id].action_function;
        param = (void *)rt_prog->actions[action_id].action_param;
    } else {
        f = actions[action_id - s_actions].action_function;
        param = actions[action_id - s_actions].action_param;
    }
    rt_trace_action(action_id, -1, 0);
    rt_current_action_id = action_id;
    f(param);
    rt_current_action_id = previous;
}

/* A table event occurred: trace it, run its action, disarm it unless it
 * repeats. */
/* A one-shot event is disarmed after its action, unless the action entered
 * the event's mode again: entering a mode re-arms all of its events, the
 * one whose action entered it too (rt_current_rearmed, set by enter_mode). */
static void fire_static(int id)
{
    rt_stir++;
    rt_trace_event(id);
    rt_current_event_id = id;
    rt_firing_event = id;
    rt_current_rearmed = 0;
    run_action(rt_prog->events[id].action_id);
    rt_current_event_id = -1;
    rt_firing_event = -1;
    if (!BIT_GET(ev_repeat, id) && !rt_current_rearmed)
        BIT_CLEAR(rt_ev_armed, id);
}

/* ~0u while the sensors are on (this poll's compiled conditions are then
 * in ev_now, computed at the first call of the poll), 0 while they are off:
 * a mask for ev_now. */
static unsigned conditions_mask(void)
{
    if (rt_prog->conditions == NULL
            || (!rt_sensors_on && !(rt_prog->sensors & RT_CONDITIONS_ALWAYS)))
        return 0;
    if (!conditions_valid) {
        if (rt_sensors_on)
            rt_read_prox(rt_prog->sensors);
        rt_prog->conditions(rt_sensors_on ? rt_prox : NULL, ev_now);
        conditions_valid = 1;
    }
    return ~0u;
}

/* The condition in this poll of an RT_HOLD_WHILE event with a function
 * (1 for the other kinds): what the function leaves in a copy of its
 * status's memory (the condition, for event_sensor, event_ambient and
 * rt_when; with the memory at 1 no edge occurs, so a guard is not
 * evaluated). */
static int function_condition_now(int id)
{
    event_status st;
    event_func f;
    void *param;

    if (rt_hold_kind(id) != RT_HOLD_WHILE)
        return 1;
    if (id < rt_s_events) {
        f = rt_prog->events[id].event_function;
        param = (void *)rt_prog->events[id].event_param;
    } else {
        f = rt_events[id - rt_s_events].event_function;
        param = rt_events[id - rt_s_events].event_param;
    }
    st.occurred = 0;
    st.memory = 1;
    f(param, &st);
    return st.memory != 0;
}

/* Before the walk of each poll while some event holds the motors by its
 * condition or guard (rt_holds): a condition that became false lets go (a
 * guard lets go in rt_guard).  A compiled condition's is its bit of this
 * poll, sixteen events a word; an event function's, function_condition_now.
 * One-shot rules that fired and disarmed are followed as well. */
void rt_holds_update(void)
{
    int left = rt_holds, id;   /* the holders not met yet: none after the last */
    unsigned w;

    for (w = 0; w < s_words && left > 0; w++) {
        unsigned held = rt_ev_hold[w] & WORD_MASK, rest, drop;
        if (held == 0)
            continue;
        /* compiled conditions: their bits of this poll, sixteen at once */
        drop = held & ev_compiled[w] & ~(conditions_mask() & ev_now[w]);
        rest = held & ~ev_compiled[w];
        for (; held != 0; held &= held - 1u)
            left--;
        rt_ev_hold[w] &= ~drop;
        for (; drop != 0; drop &= drop - 1u)
            rt_holds--;
        for (id = (int)(w * 16u); rest != 0; rest >>= 1, id++) {
            if ((rest & 1u) && !function_condition_now(id))
                rt_hold_release(id);
        }
    }
    for (id = rt_s_events; left > 0 && id < rt_s_events + rt_n_events; id++) {
        if (rt_event_ext[id - rt_s_events].hold) {
            left--;
            if (!function_condition_now(id))
                rt_hold_release(id);
        }
    }
}

/* Polls a table event that is not a compiled condition. */
static void poll_static_function(int id)
{
    const rt_event *e = &rt_prog->events[id];
    event_status st;

    st.occurred = 0;
    st.memory = e->memory != RT_NO_MEMORY ? rt_prog->memory[e->memory] : 0;
    rt_polled_event = id;
    e->event_function((void *)e->event_param, &st);
    if (e->memory != RT_NO_MEMORY)
        rt_prog->memory[e->memory] = st.memory;
    if (st.occurred)
        fire_static(id);
}

/* Phase (5) for the table's events, sixteen at a time: a word whose armed
 * events are all compiled conditions that do not become true only has its
 * latches updated; the others are polled one by one in index order, and
 * the word re-read after each, since an action may change the sensors or
 * cancel events.  Returns 1 when exit_main ran. */
static int poll_static(void)
{
    unsigned w;
    unsigned *armed = rt_ev_armed, *latch = rt_ev_latch, *compiled = ev_compiled, *now = ev_now;
    unsigned on = conditions_mask();

    for (w = 0; w < s_words; w++) {
        unsigned todo = armed[w];       /* armed and not polled yet */
        while (todo != 0) {
            unsigned comp = todo & compiled[w];
            unsigned cond = now[w] & comp & on;
            unsigned pick = (cond & ~latch[w]) | (todo & ~comp);
            unsigned low, below;
            int k;

            if (pick == 0) {
                /* no event of the word occurs: the latches follow */
                latch[w] = (latch[w] & ~comp) | cond;
                break;
            }
            for (k = 0; !((pick >> k) & 1u); k++)
                ;
            low = BIT_OF(k);
            below = low - 1u;
            latch[w] = (latch[w] & ~(comp & below)) | (cond & below);
            if (comp & low) {
                latch[w] |= low;        /* the condition became true */
                fire_static((int)(w * 16u) + k);
            } else {
                poll_static_function((int)(w * 16u) + k);
            }
            if (rt_exit_requested)
                return 1;
            on = conditions_mask();     /* the action may have started the sensors */
            todo = armed[w] & ~(low | below) & WORD_MASK;
        }
    }
    return 0;
}

/* An array event occurred: trace it, run its action, disarm it unless it
 * repeats. */
static void fire_dynamic(int i)
{
    event *e = &rt_events[i];

    rt_stir++;
    rt_trace_event(rt_s_events + i);
    rt_current_event_id = rt_s_events + i;
    rt_firing_event = rt_current_event_id;
    rt_current_rearmed = 0;
    run_action(e->action_id);
    rt_current_event_id = -1;
    rt_firing_event = -1;
    if (!e->repeat_flag && !rt_current_rearmed)
        e->valid_flag = 0;
}

/* ---- the walk by priority levels (ranked: priorities or modes in use) ---- */

/* A mode's events are polled only while it is the current mode, and not in
 * the poll that entered it. */
static int mode_ok(int mode)
{
    return mode == 0 || (mode == rt_current_mode && !rt_mode_entered_in_poll);
}

static int static_armed(int k)
{
    return BIT_GET(rt_ev_armed, k) && mode_ok(rt_prog->events[k].mode);
}

static int dynamic_armed(int i)
{
    return rt_events[i].valid_flag && rt_events[i].event_function != NULL
           && mode_ok(rt_event_ext[i].mode);
}

/* Polls one table event (the ranked walk's, one at a time). */
static void poll_static_one(int k)
{
    int cond, was;

    if (!BIT_GET(ev_compiled, k)) {
        poll_static_function(k);
        return;
    }
    cond = (conditions_mask() & ev_now[k >> 4] & BIT_OF(k)) != 0;
    was = BIT_GET(rt_ev_latch, k);
    if (cond)
        BIT_SET(rt_ev_latch, k);
    else
        BIT_CLEAR(rt_ev_latch, k);
    if (cond && !was)
        fire_static(k);
}

/* The highest priority below `below` (any, when !bounded) among the armed
 * array events; 0 when there is none. */
static int next_dynamic_level(int bounded, int below, int *level)
{
    int i, found = 0;

    for (i = 0; i < rt_n_events; i++) {
        int p = rt_event_ext[i].priority;
        if ((bounded && p >= below) || !dynamic_armed(i))
            continue;
        if (!found || p > *level)
            *level = p;
        found = 1;
    }
    return found;
}

/* The same among all the armed events, the table's too. */
static int next_level(int bounded, int below, int *level)
{
    int i, found = next_dynamic_level(bounded, below, level);

    for (i = 0; i < rt_s_events; i++) {
        int p = rt_prog->events[i].priority;
        if ((bounded && p >= below) || !static_armed(i))
            continue;
        if (!found || p > *level)
            *level = p;
        found = 1;
    }
    return found;
}

/* Polls the armed array events of priority `level`, in id order. */
static int poll_dynamic_level(int level)
{
    int i;

    /* n_events is re-read: an action may register events, polled at once */
    for (i = 0; i < rt_n_events; i++) {
        event *e = &rt_events[i];
        if (rt_event_ext[i].priority != level || !dynamic_armed(i))
            continue;
        e->status.occurred = 0;
        rt_polled_event = rt_s_events + i;
        e->event_function(e->event_param, &e->status);
        if (e->status.occurred)
            fire_dynamic(i);
        if (rt_exit_requested)
            return 1;
    }
    return 0;
}

/* The ranked walk over the table's order (rt_program.order): one pass
 * over the table, the array events of each level after the table's. */
static int poll_ordered(void)
{
    const int *order = rt_prog->order;
    int j = 0, level = 0, bounded = 0;

    for (;;) {
        int dynamic = rt_n_events > 0 && next_dynamic_level(bounded, level, &level);
        if (j < rt_s_events && (!dynamic || rt_prog->events[order[j]].priority > level))
            level = rt_prog->events[order[j]].priority;
        else if (!dynamic)
            return 0;
        for (; j < rt_s_events && rt_prog->events[order[j]].priority == level; j++) {
            if (static_armed(order[j])) {
                poll_static_one(order[j]);
                if (rt_exit_requested)
                    return 1;
            }
        }
        if (rt_n_events > 0 && poll_dynamic_level(level))
            return 1;
        bounded = 1;
    }
}

/* The poll after a mode was entered starts with the mode's `on enter`
 * events, whatever their priority: the mode's other rules then see what
 * its entry set up (a timer set, a LED lit).  In id order (the table's,
 * then the arrays'); an `on enter` that enters a mode again ends the walk
 * of this poll.  Returns 1 when exit_main ran. */
static int poll_enter_events(void)
{
    int i, mode = rt_current_mode;

    rt_mode_entry_pending = 0;
    for (i = 0; i < rt_s_events && !rt_mode_entered_in_poll; i++) {
        if (rt_prog->events[i].event_function == event_enter_mode && static_armed(i)) {
            poll_static_one(i);
            if (rt_exit_requested)
                return 1;
        }
    }
    for (i = 0; i < rt_n_events && !rt_mode_entered_in_poll; i++) {
        if (rt_events[i].event_function == event_enter_mode && dynamic_armed(i)
                && rt_event_ext[i].mode == mode) {
            rt_events[i].status.occurred = 0;
            rt_polled_event = rt_s_events + i;
            rt_events[i].event_function(rt_events[i].event_param, &rt_events[i].status);
            if (rt_events[i].status.occurred)
                fire_dynamic(i);
            if (rt_exit_requested)
                return 1;
        }
    }
    return 0;
}

/* Phase (5) with priorities or modes: the armed events (in no mode or in
 * the current one), highest priority first, in id order within a priority
 * (the table's, then the arrays'); the levels are re-read after each, since
 * an action may arm, disarm or register events.  Without the table's order
 * the table is scanned once per level.  Returns 1 when exit_main ran. */
static int poll_ranked(void)
{
    int i, level = 0, more;

    rt_mode_entered_in_poll = 0;
    if (rt_mode_entry_pending && poll_enter_events())
        return 1;
    if (rt_holds > 0)
        rt_holds_update();
    if (rt_prog != NULL && rt_prog->order != NULL)
        return poll_ordered();
    more = next_level(0, 0, &level);
    while (more) {
        for (i = 0; i < rt_s_events; i++) {
            if (rt_prog->events[i].priority == level && static_armed(i)) {
                poll_static_one(i);
                if (rt_exit_requested)
                    return 1;
            }
        }
        if (poll_dynamic_level(level))
            return 1;
        more = next_level(1, level, &level);
    }
    return 0;
}

/* Phase (5): poll the armed events; without priorities and modes in index
 * order: the table's, then the registered ones.  Returns 1 when exit_main
 * ran. */
unsigned long rt_poll_count;
void (*rt_device_poll)(void);
int (*rt_device_idle)(void);

static int poll_events(void)
{
    int i;

    conditions_valid = 0;
    rt_prox_valid = 0;
    rt_poll_count++;
    if (rt_device_poll != NULL)
        rt_device_poll();
    if (rt_sensors_starting) {  /* start_sensor of an earlier poll */
        rt_sensors_starting = 0;
        rt_sensors_on = 1;
    }            /* the other readings are read anew (rt_lang.c) */
    if (rt_mode_arm_pending && rt_prog != NULL)
        rt_mode_arm();
    if (ranked)
        return poll_ranked();
    rt_mode_entered_in_poll = 0;
    if (rt_mode_entry_pending && poll_enter_events())
        return 1;
    if (rt_holds > 0)
        rt_holds_update();
    if (rt_prog != NULL && poll_static())
        return 1;
    /* n_events is re-read: an action may register events, polled at once */
    for (i = 0; i < rt_n_events; i++) {
        event *e = &rt_events[i];
        if (!e->valid_flag || e->event_function == NULL)
            continue;
        e->status.occurred = 0;
        rt_polled_event = rt_s_events + i;
        e->event_function(e->event_param, &e->status);
        if (e->status.occurred)
            fire_dynamic(i);
        if (rt_exit_requested)
            return 1;
    }
    return 0;
}

void mainloop(void)
{
    rt_init();
    rt_exit_requested = 0;
    if (rt_mode_trace_pending) {
        rt_mode_trace_pending = 0;
        rt_trace_mode(rt_current_mode);
    }
    rt_motors_retrace();            /* a motion that main started */
    rt_last_left = e_get_steps_left();
    rt_last_right = e_get_steps_right();
    rt_looping = 1;
    for (;;) {
        RT_TRACE_POLL_END();        /* the robot's trace: the LEDs the poll changed */
        rt_platform_idle();         /* (1) wait for / advance time by 1 ms */
        RT_TRACE_POLL();            /* the robot's trace: its link (without it, nothing) */
        rt_motion_update();            /* (2) */
        rt_sequence_advance();         /* (3) */
        if (rt_exit_requested)
            break;
        rt_stop_sample = rt_seen_moving && !rt_motion.active;    /* (4) */
        rt_seen_moving = rt_motion.active;
        if (rt_accel_wanted)
            rt_accel_sample();
        if (poll_events())          /* (5) */
            break;
        rt_motors_changed();        /* holds end in the poll too */
    }
    /* exit_main: stop at once */
    rt_looping = 0;
    rt_motion.active = 0;
    rt_wheels(0, 0);
    rt_seq = NULL;
    rt_seq_waiting = 0;
    rt_seq_delay = 0;
    rt_seen_moving = 0;
    rt_holds_release(-1);
    rt_motors_changed();
    rt_exit_requested = 0;
    rt_prox_valid = 0;
    rt_trace_exit();
}
