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
static const param_event_timer when_r1 = {1000L};
/* warnings.epk:5: start_straight(200, 1 cm) (200 steps/s, 78 steps) */
static const param_start_straight p1_r2 = {200, 10, 78};

/* The actions, {function, parameter}: an action's id is its index. */
static const rt_action action_table[] = {
    {exit_main, NULL},   /* 0: warnings.epk:4: exit_main */
    {start_straight, &p1_r2},   /* 1: warnings.epk:5: start_straight(200, 1 cm) */
};

/* The events, {function, parameter, action id, flags, memory, priority,
 * mode}: an event's id is its index.  A NULL function is the rule's
 * condition in event_conditions; memory is the event's slot in event_memory
 * (timers keep their last firing); mode 0: in no mode, always armed. */
static const rt_event event_table[] = {
    /* 0: warnings.epk:4: on timer(1 s) do exit_main */
    {timer, &when_r1, 0, 0, 0, 0, 0},
    /* 1: warnings.epk:5: on immediate do start_straight(200, 1 cm) */
    {immediate, NULL, 1, 0, RT_NO_MEMORY, 0, 0},
};

/* What changes while the program runs, the only part in RAM. */
static unsigned event_state[RT_STATE_WORDS(2, 2)];
static long event_memory[1];

static const rt_program event_program = {
    action_table, 2, event_table, 2,
    NULL, 0x00, event_state, event_memory
};

int main(void)
{
    (void)register_program(&event_program);

    /* Names in the host harness's trace; without them on the robot (EPUCKRT_NO_NAMES). */
    name_action(0, "exit_main");
    name_action(1, "start_straight(200, 1 cm)");
    name_event(0, "warnings.epk:4 on timer(1 s)");
    name_event(1, "warnings.epk:5 on immediate");

    mainloop();
    return 0;
}
