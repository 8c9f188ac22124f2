/*
 * warnings.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them, then mainloop().  The actions and events are
 * const tables registered at once (register_program), which the robot keeps
 * in program memory; the rules' sensor conditions are compiled into one
 * function.  Tables: 2 actions, 2 events.
 */
#include "utility.h"

/* warnings.epk:4: timer(1 s) */
static const param_event_timer epk_when_r1 = {1000L};
/* warnings.epk:5: start_straight(200, 1 cm) (200 steps/s for 78 steps) */
static const param_straight_steps epk_p1_r2 = {200, 78};

/* The actions, {function, parameter}: an action's id is its index. */
static const rt_action epk_action_table[] = {
    {exit_main, NULL},   /* 0: warnings.epk:4: exit_main */
    {straight_steps, &epk_p1_r2},   /* 1: warnings.epk:5: start_straight(200, 1 cm) */
};

/* The events, {function, parameter, action id, flags, memory, priority,
 * mode}: an event's id is its index, by priority, highest first, then in
 * file order (the order mainloop polls them in).  A NULL function is the rule's
 * condition in epk_event_conditions; memory is the event's slot in
 * epk_event_memory (timers keep their last firing); mode 0: in no mode,
 * always armed. */
static const rt_event epk_event_table[] = {
    /* 0: warnings.epk:4: on timer(1 s) do exit_main */
    {timer, &epk_when_r1, 0, RT_WAKE_AS_TIMER, 0, 0, 0},
    /* 1: warnings.epk:5: on immediate do start_straight(200, 1 cm) */
    {immediate, NULL, 1, 0, RT_NO_MEMORY, 0, 0},
};

/* What changes while the program runs, the only part in RAM. */
static unsigned epk_event_state[RT_STATE_WORDS(2, 2)];
static long epk_event_memory[1];

static const rt_program epk_program = {
    epk_action_table, 2, epk_event_table, 2,
    NULL, 0x00, epk_event_state, epk_event_memory,
    NULL
};

int main(void)
{
    (void)register_program(&epk_program);

    /* Names in the host harness's trace; without them on the robot (EPUCKRT_NO_NAMES). */
    name_action(0, "exit_main");
    name_action(1, "start_straight(200, 1 cm)");
    name_event(0, "warnings.epk:4 on timer(1 s)");
    name_event(1, "warnings.epk:5 on immediate");

    mainloop();
    return 0;
}
