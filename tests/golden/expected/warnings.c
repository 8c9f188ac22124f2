/*
 * warnings.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 2 actions, 2 events.
 */
#include "utility.h"

/* warnings.epk:4: timer(1 s) */
static param_event_timer epk_when_r1 = {1000L};
/* warnings.epk:5: start_straight(200, 1 cm) (200 steps/s for 78 steps) */
static param_straight_steps epk_p1_r2 = {200, 78};

int main(void)
{
    int epk_a1, epk_a2;
    int epk_e1, epk_e2;

    /* warnings.epk:4: on timer(1 s) do exit_main */
    epk_a1 = register_action(exit_main, NULL);
    name_action(epk_a1, "exit_main");
    epk_e1 = register_event(timer, &epk_when_r1, epk_a1);
    name_event(epk_e1, "warnings.epk:4 on timer(1 s)");

    /* warnings.epk:5: on immediate do start_straight(200, 1 cm) */
    epk_a2 = register_action(straight_steps, &epk_p1_r2);
    name_action(epk_a2, "start_straight(200, 1 cm)");
    epk_e2 = register_event(immediate, NULL, epk_a2);
    name_event(epk_e2, "warnings.epk:5 on immediate");

    mainloop();
    return 0;
}
