/*
 * warnings.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 2 actions, 2 events.
 */
#include "utility.h"

/* warnings.epk:4: timer(1 s) */
static param_event_timer when_r1 = {1000L};
/* warnings.epk:5: start_straight(200, 1 cm) (200 steps/s, 78 steps) */
static param_start_straight p1_r2 = {200, 10, 78};

int main(void)
{
    int a1, a2;
    int e1, e2;

    /* warnings.epk:4: on timer(1 s) do exit_main */
    a1 = register_action(exit_main, NULL);
    name_action(a1, "exit_main");
    e1 = register_event(timer, &when_r1, a1);
    name_event(e1, "warnings.epk:4 on timer(1 s)");

    /* warnings.epk:5: on immediate do start_straight(200, 1 cm) */
    a2 = register_action(start_straight, &p1_r2);
    name_action(a2, "start_straight(200, 1 cm)");
    e2 = register_event(immediate, NULL, a2);
    name_event(e2, "warnings.epk:5 on immediate");

    mainloop();
    return 0;
}
