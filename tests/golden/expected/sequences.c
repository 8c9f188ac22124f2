/*
 * sequences.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them, then mainloop().  The actions and events are
 * const tables registered at once (register_program), which the robot keeps
 * in program memory; the rules' sensor conditions are compiled into one
 * function.  Tables: 1 actions, 1 events.
 */
#include "utility.h"

/* sequences.epk:2: start_straight(500, 5 cm) (500 steps/s for 388 steps) */
static const param_straight_steps epk_p1_a_forward = {500, 388};
/* sequences.epk:3: start_curve(0 mm, 90 deg, 500) (left wheel -500 steps/s, right 500 steps/s, 323 steps of the outer wheel) */
static const param_curve_steps epk_p1_a_turn = {-500, 500, 323};

/* sequences.epk:6: step 5 of 7: set_timer, start_straight(500, 5 cm) */
static void epk_step5_r1(void *epk_param)
{
    (void)epk_param;
    set_timer(NULL);
    straight_steps((void *)&epk_p1_a_forward);
}

/* sequences.epk:6: l_shape then set_timer, leg then exit_main */
static const action epk_steps_r1[] = {
    {straight_steps, (void *)&epk_p1_a_forward},
    {curve_steps, (void *)&epk_p1_a_turn},
    {straight_steps, (void *)&epk_p1_a_forward},
    {curve_steps, (void *)&epk_p1_a_turn},
    {epk_step5_r1, NULL},
    {curve_steps, (void *)&epk_p1_a_turn},
    {exit_main, NULL},
};
static const param_sequence epk_seq_r1 = {epk_steps_r1, 7};
#ifndef EPUCKRT_NAMES_DROPPED
static const char *const epk_step_names_r1[] = {
    "start_straight(500, 5 cm)",
    "start_curve(0 mm, 90 deg, 500)",
    "start_straight(500, 5 cm)",
    "start_curve(0 mm, 90 deg, 500)",
    "set_timer, start_straight(500, 5 cm)",
    "start_curve(0 mm, 90 deg, 500)",
    "exit_main",
};
#endif

/* The actions, {function, parameter}: an action's id is its index. */
static const rt_action epk_action_table[] = {
    {run_sequence, &epk_seq_r1},   /* 0: sequences.epk:6: l_shape then set_timer, leg then exit_main */
};

/* The events, {function, parameter, action id, flags, memory, priority,
 * mode}: an event's id is its index, by priority, highest first, then in
 * file order (the order mainloop polls them in).  A NULL function is the rule's
 * condition in epk_event_conditions; memory is the event's slot in
 * epk_event_memory (timers keep their last firing); mode 0: in no mode,
 * always armed. */
static const rt_event epk_event_table[] = {
    /* 0: sequences.epk:6: on immediate do l_shape then set_timer, leg then exit_main */
    {immediate, NULL, 0, 0, RT_NO_MEMORY, 0, 0},
};

/* What changes while the program runs, the only part in RAM. */
static unsigned epk_event_state[RT_STATE_WORDS(1, 1)];

static const rt_program epk_program = {
    epk_action_table, 1, epk_event_table, 1,
    NULL, 0x00, epk_event_state, NULL,
    NULL
};

int main(void)
{
    (void)register_program(&epk_program);

    /* Names in the host harness's trace; without them on the robot (EPUCKRT_NO_NAMES). */
    name_action(0, "l_shape then set_timer, leg then exit_main");
    name_event(0, "sequences.epk:6 on immediate");
    name_steps(0, epk_step_names_r1, 7);

    mainloop();
    return 0;
}
