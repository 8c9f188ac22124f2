/*
 * cancel.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 4 actions, 4 events.
 */
#include "utility.h"

/* cancel.epk:3: start_straight(200, 1 mm) (200 steps/s, 8 steps) */
static param_start_straight p1_r2 = {200, 1, 8};
/* cancel.epk:3: timer(100 ms) */
static param_event_timer when_r2 = {100L};
/* cancel.epk:4: timer(350 ms) */
static param_event_timer when_r3 = {350L};
/* cancel.epk:5: timer(1 s) */
static param_event_timer when_r4 = {1000L};

/* Event ids of the rules that `cancel` names. */
static int rule_tick;

/* cancel.epk:4: cancel tick */
static void do_r3(void *param)
{
    (void)param;
    cancel_event(rule_tick);
}

int main(void)
{
    int a1, a2, a3, a4;
    int e1, e2, e3, e4;

    /* cancel.epk:2: on immediate do set_timer */
    a1 = register_action(set_timer, NULL);
    name_action(a1, "set_timer");
    e1 = register_event(immediate, NULL, a1);
    name_event(e1, "cancel.epk:2 on immediate");

    /* cancel.epk:3: rule tick: on timer(100 ms) repeat do start_straight(200, 1 mm) */
    a2 = register_action(start_straight, &p1_r2);
    name_action(a2, "start_straight(200, 1 mm)");
    e2 = register_event(timer, &when_r2, a2);
    name_event(e2, "cancel.epk:3 rule tick: on timer(100 ms) repeat");
    set_event_repeat(e2, 1);
    rule_tick = e2;

    /* cancel.epk:4: on timer(350 ms) do cancel tick */
    a3 = register_action(do_r3, NULL);
    name_action(a3, "cancel tick");
    e3 = register_event(timer, &when_r3, a3);
    name_event(e3, "cancel.epk:4 on timer(350 ms)");

    /* cancel.epk:5: on timer(1 s) do exit_main */
    a4 = register_action(exit_main, NULL);
    name_action(a4, "exit_main");
    e4 = register_event(timer, &when_r4, a4);
    name_event(e4, "cancel.epk:5 on timer(1 s)");

    mainloop();
    return 0;
}
