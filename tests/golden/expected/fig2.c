/*
 * fig2.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 2 actions, 2 events.
 */
#include "utility.h"

/* fig2.epk:3: start_straight(speed: 250 steps/s, distance: 100 mm) (250 steps/s for 776 steps) */
static param_straight_steps epk_p1_a_go = {250, 776};

int main(void)
{
    int epk_a1, epk_a2;
    int epk_e1, epk_e2;

    /* fig2.epk:6: on immediate do go */
    epk_a1 = register_action(straight_steps, &epk_p1_a_go);
    name_action(epk_a1, "go");
    epk_e1 = register_event(immediate, NULL, epk_a1);
    name_event(epk_e1, "fig2.epk:6 on immediate");

    /* fig2.epk:7: on stop_motor do quit */
    epk_a2 = register_action(exit_main, NULL);
    name_action(epk_a2, "quit");
    epk_e2 = register_event(event_stop_motor, NULL, epk_a2);
    name_event(epk_e2, "fig2.epk:7 on stop_motor");

    mainloop();
    return 0;
}
