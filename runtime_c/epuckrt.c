/*
 * epuckrt.c - the walk of the event-driven runtime (Ochiai et al., section
 * 4): the runtime's start and the polling main loop (figure 4), with its
 * walks over the events, plain or by priority levels, and exit_main.  The
 * top of the core: what is registered is rt_registry.c, motion and the
 * sequencer rt_motion.c, modes rt_modes.c, the standard events and sensors
 * rt_sensors.c, the clock rt_clock.c (rt_internal.h shows the layers).
 *
 * The hardware is reached only through the e-puck library API (the real
 * library on the robot, host/epuck_stub.c on a PC) and rt_platform.h.
 * Written for 16-bit int: every count of steps or milliseconds that can pass
 * 32767 is long; products that can pass 2^31 are long long.
 * docs/runtime.md describes the semantics implemented here.
 */
#include "rt_modes.h"

static int conditions_valid;        /* rt_ev_now holds this poll's conditions */

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
    rt_remote_start();     /* only for programs that use the remote control */
}

void action_exit_main(void *param)
{
    (void)param;
    rt_exit_requested = 1;
}

void exit_main(void *param) { action_exit_main(param); }

/* ---- main loop (paper figure 4) ---------------------------------------------- */

static void run_action(int action_id)
{
    int previous = rt_current_action_id;
    action_func f;
    void *param;

    if (!rt_action_of(action_id, &f, &param))
        return;     /* cancelled: the event fires but runs nothing */
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
    if (!BIT_GET(rt_ev_repeat, id) && !rt_current_rearmed)
        BIT_CLEAR(rt_ev_armed, id);
}

/* ~0u while the sensors are on (this poll's compiled conditions are then
 * in rt_ev_now, computed at the first call of the poll), 0 while they are off:
 * a mask for rt_ev_now. */
static unsigned conditions_mask(void)
{
    if (rt_prog->conditions == NULL
            || (!rt_sensors_on && !(rt_prog->sensors & RT_CONDITIONS_ALWAYS)))
        return 0;
    if (!conditions_valid) {
        if (rt_sensors_on)
            rt_read_prox(rt_prog->sensors);
        rt_prog->conditions(rt_sensors_on ? rt_prox : NULL, rt_ev_now);
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
static void holds_update(void)
{
    int left = rt_holds, id;   /* the holders not met yet: none after the last */
    unsigned w;

    for (w = 0; w < rt_s_words && left > 0; w++) {
        unsigned held = rt_ev_hold[w] & WORD_MASK, rest, drop;
        if (held == 0)
            continue;
        /* compiled conditions: their bits of this poll, sixteen at once */
        drop = held & rt_ev_compiled[w] & ~(conditions_mask() & rt_ev_now[w]);
        rest = held & ~rt_ev_compiled[w];
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
    unsigned *armed = rt_ev_armed, *latch = rt_ev_latch, *compiled = rt_ev_compiled, *now = rt_ev_now;
    unsigned on = conditions_mask();

    for (w = 0; w < rt_s_words; w++) {
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

/* ---- the walk by priority levels (rt_ranked: priorities or modes in use) ---- */

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

/* Polls one table event (the rt_ranked walk's, one at a time). */
static void poll_static_one(int k)
{
    int cond, was;

    if (!BIT_GET(rt_ev_compiled, k)) {
        poll_static_function(k);
        return;
    }
    cond = (conditions_mask() & rt_ev_now[k >> 4] & BIT_OF(k)) != 0;
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

/* The rt_ranked walk over the table's order (rt_program.order): one pass
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
        holds_update();
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
    if (rt_ranked)
        return poll_ranked();
    rt_mode_entered_in_poll = 0;
    if (rt_mode_entry_pending && poll_enter_events())
        return 1;
    if (rt_holds > 0)
        holds_update();
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
    rt_modes_loop_start();          /* a mode that main entered */
    rt_motors_retrace();            /* a motion that main started */
    rt_motion_loop_start();
    rt_looping = 1;
    for (;;) {
        RT_TRACE_POLL_END();        /* the robot's trace: the LEDs the poll changed */
        rt_platform_idle();         /* (1) wait for / advance time by 1 ms */
        RT_TRACE_POLL();            /* the robot's trace: its link (without it, nothing) */
        rt_motion_update();            /* (2) */
        rt_sequence_advance();         /* (3) */
        if (rt_exit_requested)
            break;
        rt_stop_sample = rt_motion_stop_sample();       /* (4) */
        if (rt_accel_wanted)
            rt_accel_sample();
        if (poll_events())          /* (5) */
            break;
        rt_motors_changed();        /* holds end in the poll too */
    }
    /* exit_main: stop at once */
    rt_looping = 0;
    rt_motion_halt();
    rt_holds_release(-1);
    rt_motors_changed();
    rt_exit_requested = 0;
    rt_prox_valid = 0;
    rt_trace_exit();
}
