/*
 * cancel.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 4 actions, 4 events.
 */
#include "utility.h"

/* cancel.epk:3: start_straight(200, 1 mm) (200 steps/s for 8 steps) */
static param_straight_steps epk_p1_r2 = {200, 8};
/* cancel.epk:3: timer(100 ms) */
static param_event_timer epk_when_r2 = {100L};
/* cancel.epk:4: timer(350 ms) */
static param_event_timer epk_when_r3 = {350L};
/* cancel.epk:5: timer(1 s) */
static param_event_timer epk_when_r4 = {1000L};

/* Event ids of the rules that `cancel` names. */
static int epk_rule_tick;

/* cancel.epk:4: cancel tick */
static void epk_do_r3(void *epk_param)
{
    (void)epk_param;
    cancel_event(epk_rule_tick);
}

int main(void)
{
    int epk_a1, epk_a2, epk_a3, epk_a4;
    int epk_e1, epk_e2, epk_e3, epk_e4;

    /* cancel.epk:2: on immediate do set_timer */
    epk_a1 = register_action(set_timer, NULL);
    name_action(epk_a1, "set_timer");
    epk_e1 = register_event(immediate, NULL, epk_a1);
    name_event(epk_e1, "cancel.epk:2 on immediate");

    /* cancel.epk:3: rule tick: on timer(100 ms) repeat do start_straight(200, 1 mm) */
    epk_a2 = register_action(straight_steps, &epk_p1_r2);
    name_action(epk_a2, "start_straight(200, 1 mm)");
    epk_e2 = register_event(timer, &epk_when_r2, epk_a2);
    name_event(epk_e2, "cancel.epk:3 rule tick: on timer(100 ms) repeat");
    set_event_repeat(epk_e2, 1);
    epk_rule_tick = epk_e2;

    /* cancel.epk:4: on timer(350 ms) do cancel tick */
    epk_a3 = register_action(epk_do_r3, NULL);
    name_action(epk_a3, "cancel tick");
    epk_e3 = register_event(timer, &epk_when_r3, epk_a3);
    name_event(epk_e3, "cancel.epk:4 on timer(350 ms)");

    /* cancel.epk:5: on timer(1 s) do exit_main */
    epk_a4 = register_action(exit_main, NULL);
    name_action(epk_a4, "exit_main");
    epk_e4 = register_event(timer, &epk_when_r4, epk_a4);
    name_event(epk_e4, "cancel.epk:5 on timer(1 s)");

    mainloop();
    return 0;
}
