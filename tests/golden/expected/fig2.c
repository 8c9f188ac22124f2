/*
 * fig2.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them, then mainloop().  The actions and events are
 * const tables registered at once (register_program), which the robot keeps
 * in program memory; the rules' sensor conditions are compiled into one
 * function.  Tables: 2 actions, 2 events.
 */
#include "utility.h"

/* fig2.epk:3: start_straight(speed: 250 steps/s, distance: 100 mm) (250 steps/s for 776 steps) */
static const param_straight_steps epk_p1_a_go = {250, 776};

/* The actions, {function, parameter}: an action's id is its index. */
static const rt_action epk_action_table[] = {
    {straight_steps, &epk_p1_a_go},   /* 0: fig2.epk:3: action go = start_straight(speed: 250 steps/s, distance: 100 mm) */
    {exit_main, NULL},   /* 1: fig2.epk:4: action quit = exit_main */
};

/* The events, {function, parameter, action id, flags, memory, priority,
 * mode}: an event's id is its index, by priority, highest first, then in
 * file order (the order mainloop polls them in).  A NULL function is the rule's
 * condition in epk_event_conditions; memory is the event's slot in
 * epk_event_memory (timers keep their last firing); mode 0: in no mode,
 * always armed. */
static const rt_event epk_event_table[] = {
    /* 0: fig2.epk:6: on immediate do go */
    {immediate, NULL, 0, 0, RT_NO_MEMORY, 0, 0},
    /* 1: fig2.epk:7: on stop_motor do quit */
    {event_stop_motor, NULL, 1, RT_WAKE_ON_CHANGE, RT_NO_MEMORY, 0, 0},
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
    name_action(0, "go");
    name_action(1, "quit");
    name_event(0, "fig2.epk:6 on immediate");
    name_event(1, "fig2.epk:7 on stop_motor");

    mainloop();
    return 0;
}
