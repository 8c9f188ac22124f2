/*
 * fig2.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 2 actions, 2 events.
 */
#include "utility.h"

/* fig2.epk:3: start_straight(speed: 250 steps/s, distance: 100 mm) (250 steps/s, 776 steps) */
static param_start_straight p1_a_go = {250, 100, 776};

int main(void)
{
    int a1, a2;
    int e1, e2;

    /* fig2.epk:6: on immediate do go */
    a1 = register_action(start_straight, &p1_a_go);
    name_action(a1, "go");
    e1 = register_event(immediate, NULL, a1);
    name_event(e1, "fig2.epk:6 on immediate");

    /* fig2.epk:7: on stop_motor do quit */
    a2 = register_action(exit_main, NULL);
    name_action(a2, "quit");
    e2 = register_event(event_stop_motor, NULL, a2);
    name_event(e2, "fig2.epk:7 on stop_motor");

    mainloop();
    return 0;
}
