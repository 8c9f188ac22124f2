/*
 * names.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 2 actions, 2 events.
 */
#include "utility.h"

/* names.epk:2: start_straight(100, 1 cm) (100 steps/s, 78 steps) */
static param_start_straight p1_a_int = {100, 10, 78};

/* Event ids of the rules that `cancel` names. */
static int rule_main;

/* names.epk:6: seq_a_x, cancel main */
static void do_r2(void *param)
{
    (void)param;
    stop_motor(NULL);
    cancel_event(rule_main);
}

/* names.epk:3: action register_action = int then exit_main */
static const action steps_a_register_action[] = {
    {start_straight, &p1_a_int},
    {exit_main, NULL},
};
static param_sequence seq_a_register_action = {steps_a_register_action, 2};

int main(void)
{
    int a1, a2;
    int e1, e2;

    /* names.epk:5: rule main: on immediate do register_action */
    a1 = register_action(run_sequence, &seq_a_register_action);
    name_action(a1, "register_action");
    e1 = register_event(immediate, NULL, a1);
    name_event(e1, "names.epk:5 rule main: on immediate");
    rule_main = e1;

    /* names.epk:6: rule while: on stop_motor repeat do seq_a_x, cancel main */
    a2 = register_action(do_r2, NULL);
    name_action(a2, "seq_a_x, cancel main");
    e2 = register_event(event_stop_motor, NULL, a2);
    name_event(e2, "names.epk:6 rule while: on stop_motor repeat");
    set_event_repeat(e2, 1);

    mainloop();
    return 0;
}
