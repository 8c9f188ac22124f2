/*
 * events.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them, then mainloop().  The actions and events are
 * const tables registered at once (register_program), which the robot keeps
 * in program memory; the rules' sensor conditions are compiled into one
 * function.  Tables: 5 actions, 5 events.
 */
#include "utility.h"

/* events.epk:3: start_straight(300, 1 cm) (300 steps/s for 78 steps) */
static const param_straight_steps epk_p1_r2 = {300, 78};
/* events.epk:5: timer(400 ms) */
static const param_event_timer epk_when_r4 = {400L};
/* events.epk:6: event_timer(time: 3 s) */
static const param_event_timer epk_when_r5 = {3000L};

/* events.epk:2: start_sensor, set_timer */
static void epk_do_r1(void *epk_param)
{
    (void)epk_param;
    start_sensor(NULL);
    set_timer(NULL);
}

/* events.epk:4: reset_timer, set_timer */
static void epk_do_r3(void *epk_param)
{
    (void)epk_param;
    reset_timer(NULL);
    set_timer(NULL);
}

/* events.epk:6: stop_motor, exit_main */
static void epk_do_r5(void *epk_param)
{
    (void)epk_param;
    stop_motor(NULL);
    exit_main(NULL);
}

/* The rules' sensor conditions, from this poll's proximity readings
 * epk_ir[0..7]: bit k % 16 of epk_c[k / 16] is event k's.  The runtime
 * calls it at most once per poll, while the sensors are on. */
static void epk_event_conditions(const int *epk_ir, unsigned *epk_c)
{
    const int epk_ir2 = epk_ir[2];
    const int epk_ir5 = epk_ir[5];

    epk_c[0] = 0;
    if (epk_ir2 > 1000 || epk_ir5 < 20) epk_c[0] |= 0x0002u;   /* event 1: events.epk:3 */
}

/* The actions, {function, parameter}: an action's id is its index. */
static const rt_action epk_action_table[] = {
    {epk_do_r1, NULL},   /* 0: events.epk:2: start_sensor, set_timer */
    {straight_steps, &epk_p1_r2},   /* 1: events.epk:3: start_straight(300, 1 cm) */
    {epk_do_r3, NULL},   /* 2: events.epk:4: reset_timer, set_timer */
    {stop_sensor, NULL},   /* 3: events.epk:5: stop_sensor */
    {epk_do_r5, NULL},   /* 4: events.epk:6: stop_motor, exit_main */
};

/* The events, {function, parameter, action id, flags, memory, priority,
 * mode}: an event's id is its index, by priority, highest first, then in
 * file order (the order mainloop polls them in).  A NULL function is the rule's
 * condition in epk_event_conditions; memory is the event's slot in
 * epk_event_memory (timers keep their last firing); mode 0: in no mode,
 * always armed. */
static const rt_event epk_event_table[] = {
    /* 0: events.epk:2: on immediate do start_sensor, set_timer */
    {immediate, NULL, 0, 0, RT_NO_MEMORY, 0, 0},
    /* 1: events.epk:3: rule near: on sensor(ir2 > 1000, ir5 < 20) repeat do start_straight(300, 1 cm) */
    {NULL, NULL, 1, RT_REPEAT | RT_HOLD_WHILE | RT_WAKE_ON_CHANGE, RT_NO_MEMORY, 0, 0},
    /* 2: events.epk:4: rule moved: on stop_motor repeat do reset_timer, set_timer */
    {event_stop_motor, NULL, 2, RT_REPEAT | RT_WAKE_ON_CHANGE, RT_NO_MEMORY, 0, 0},
    /* 3: events.epk:5: on timer(400 ms) repeat do stop_sensor */
    {timer, &epk_when_r4, 3, RT_REPEAT | RT_WAKE_AS_TIMER, 0, 0, 0},
    /* 4: events.epk:6: on event_timer(time: 3 s) do stop_motor, exit_main */
    {timer, &epk_when_r5, 4, RT_WAKE_AS_TIMER, 1, 0, 0},
};

/* What changes while the program runs, the only part in RAM. */
static unsigned epk_event_state[RT_STATE_WORDS(5, 5)];
static long epk_event_memory[2];

static const rt_program epk_program = {
    epk_action_table, 5, epk_event_table, 5,
    epk_event_conditions, 0x24, epk_event_state, epk_event_memory,
    NULL
};

int main(void)
{
    (void)register_program(&epk_program);

    /* Names in the host harness's trace; without them on the robot (EPUCKRT_NO_NAMES). */
    name_action(0, "start_sensor, set_timer");
    name_action(1, "start_straight(300, 1 cm)");
    name_action(2, "reset_timer, set_timer");
    name_action(3, "stop_sensor");
    name_action(4, "stop_motor, exit_main");
    name_event(0, "events.epk:2 on immediate");
    name_event(1, "events.epk:3 rule near: on sensor(ir2 > 1000, ir5 < 20) repeat");
    name_event(2, "events.epk:4 rule moved: on stop_motor repeat");
    name_event(3, "events.epk:5 on timer(400 ms) repeat");
    name_event(4, "events.epk:6 on event_timer(time: 3 s)");

    mainloop();
    return 0;
}
