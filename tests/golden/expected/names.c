/*
 * names.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them, then mainloop().  The actions and events are
 * const tables registered at once (register_program), which the robot keeps
 * in program memory; the rules' sensor conditions are compiled into one
 * function.  Tables: 2 actions, 2 events.
 */
#include "utility.h"

/* names.epk:2: start_straight(100, 1 cm) (100 steps/s for 78 steps) */
static const param_straight_steps epk_p1_a_int = {100, 78};

/* Event ids of the rules that `cancel` names. */
enum {
    epk_rule_main = 0
};

/* names.epk:6: seq_a_x, cancel main */
static void epk_do_r2(void *epk_param)
{
    (void)epk_param;
    stop_motor(NULL);
    cancel_event(epk_rule_main);
}

/* names.epk:3: action register_action = int then exit_main */
static const action epk_steps_a_register_action[] = {
    {straight_steps, (void *)&epk_p1_a_int},
    {exit_main, NULL},
};
static const param_sequence epk_seq_a_register_action = {epk_steps_a_register_action, 2};
#ifndef EPUCKRT_NAMES_DROPPED
static const char *const epk_step_names_a_register_action[] = {
    "start_straight(100, 1 cm)",
    "exit_main",
};
#endif

/* The actions, {function, parameter}: an action's id is its index. */
static const rt_action epk_action_table[] = {
    {run_sequence, &epk_seq_a_register_action},   /* 0: names.epk:3: action register_action = int then exit_main */
    {epk_do_r2, NULL},   /* 1: names.epk:6: seq_a_x, cancel main */
};

/* The events, {function, parameter, action id, flags, memory, priority,
 * mode}: an event's id is its index, by priority, highest first, then in
 * file order (the order mainloop polls them in).  A NULL function is the rule's
 * condition in epk_event_conditions; memory is the event's slot in
 * epk_event_memory (timers keep their last firing); mode 0: in no mode,
 * always armed. */
static const rt_event epk_event_table[] = {
    /* 0: names.epk:5: rule main: on immediate do register_action */
    {immediate, NULL, 0, 0, RT_NO_MEMORY, 0, 0},
    /* 1: names.epk:6: rule while: on stop_motor repeat do seq_a_x, cancel main */
    {event_stop_motor, NULL, 1, RT_REPEAT | RT_WAKE_ON_CHANGE, RT_NO_MEMORY, 0, 0},
};

/* What changes while the program runs, the only part in RAM. */
static unsigned epk_event_state[RT_STATE_WORDS(2, 2)];

static const rt_program epk_program = {
    epk_action_table, 2, epk_event_table, 2,
    NULL, 0x00, epk_event_state, NULL,
    NULL
};

int main(void)
{
    (void)register_program(&epk_program);

    /* Names in the host harness's trace; without them on the robot (EPUCKRT_NO_NAMES). */
    name_action(0, "register_action");
    name_action(1, "seq_a_x, cancel main");
    name_event(0, "names.epk:5 rule main: on immediate");
    name_event(1, "names.epk:6 rule while: on stop_motor repeat");
    name_steps(0, epk_step_names_a_register_action, 2);

    mainloop();
    return 0;
}
