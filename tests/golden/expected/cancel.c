/*
 * cancel.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them, then mainloop().  The actions and events are
 * const tables registered at once (register_program), which the robot keeps
 * in program memory; the rules' sensor conditions are compiled into one
 * function.  Tables: 4 actions, 4 events.
 */
#include "utility.h"

/* cancel.epk:3: start_straight(200, 1 mm) (200 steps/s for 8 steps) */
static const param_straight_steps epk_p1_r2 = {200, 8};
/* cancel.epk:3: timer(100 ms) */
static const param_event_timer epk_when_r2 = {100L};
/* cancel.epk:4: timer(350 ms) */
static const param_event_timer epk_when_r3 = {350L};
/* cancel.epk:5: timer(1 s) */
static const param_event_timer epk_when_r4 = {1000L};

/* Event ids of the rules that `cancel` names. */
enum {
    epk_rule_tick = 1
};

/* cancel.epk:4: cancel tick */
static void epk_do_r3(void *epk_param)
{
    (void)epk_param;
    cancel_event(epk_rule_tick);
}

/* The actions, {function, parameter}: an action's id is its index. */
static const rt_action epk_action_table[] = {
    {set_timer, NULL},   /* 0: cancel.epk:2: set_timer */
    {straight_steps, &epk_p1_r2},   /* 1: cancel.epk:3: start_straight(200, 1 mm) */
    {epk_do_r3, NULL},   /* 2: cancel.epk:4: cancel tick */
    {exit_main, NULL},   /* 3: cancel.epk:5: exit_main */
};

/* The events, {function, parameter, action id, flags, memory, priority,
 * mode}: an event's id is its index, by priority, highest first, then in
 * file order (the order mainloop polls them in).  A NULL function is the rule's
 * condition in epk_event_conditions; memory is the event's slot in
 * epk_event_memory (timers keep their last firing); mode 0: in no mode,
 * always armed. */
static const rt_event epk_event_table[] = {
    /* 0: cancel.epk:2: on immediate do set_timer */
    {immediate, NULL, 0, 0, RT_NO_MEMORY, 0, 0},
    /* 1: cancel.epk:3: rule tick: on timer(100 ms) repeat do start_straight(200, 1 mm) */
    {timer, &epk_when_r2, 1, RT_REPEAT | RT_WAKE_AS_TIMER, 0, 0, 0},
    /* 2: cancel.epk:4: on timer(350 ms) do cancel tick */
    {timer, &epk_when_r3, 2, RT_WAKE_AS_TIMER, 1, 0, 0},
    /* 3: cancel.epk:5: on timer(1 s) do exit_main */
    {timer, &epk_when_r4, 3, RT_WAKE_AS_TIMER, 2, 0, 0},
};

/* What changes while the program runs, the only part in RAM. */
static unsigned epk_event_state[RT_STATE_WORDS(4, 4)];
static long epk_event_memory[3];

static const rt_program epk_program = {
    epk_action_table, 4, epk_event_table, 4,
    NULL, 0x00, epk_event_state, epk_event_memory,
    NULL
};

int main(void)
{
    (void)register_program(&epk_program);

    /* Names in the host harness's trace; without them on the robot (EPUCKRT_NO_NAMES). */
    name_action(0, "set_timer");
    name_action(1, "start_straight(200, 1 mm)");
    name_action(2, "cancel tick");
    name_action(3, "exit_main");
    name_event(0, "cancel.epk:2 on immediate");
    name_event(1, "cancel.epk:3 rule tick: on timer(100 ms) repeat");
    name_event(2, "cancel.epk:4 on timer(350 ms)");
    name_event(3, "cancel.epk:5 on timer(1 s)");

    mainloop();
    return 0;
}
