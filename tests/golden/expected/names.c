/*
 * names.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 2 actions, 2 events.
 */
#include "utility.h"

/* names.epk:2: start_straight(100, 1 cm) (100 steps/s for 78 steps) */
static param_straight_steps epk_p1_a_int = {100, 78};

/* Event ids of the rules that `cancel` names. */
static int epk_rule_main;

/* names.epk:6: seq_a_x, cancel main */
static void epk_do_r2(void *epk_param)
{
    (void)epk_param;
    stop_motor(NULL);
    cancel_event(epk_rule_main);
}

/* names.epk:3: action register_action = int then exit_main */
static const action epk_steps_a_register_action[] = {
    {straight_steps, &epk_p1_a_int},
    {exit_main, NULL},
};
static param_sequence epk_seq_a_register_action = {epk_steps_a_register_action, 2};

int main(void)
{
    int epk_a1, epk_a2;
    int epk_e1, epk_e2;

    /* names.epk:5: rule main: on immediate do register_action */
    epk_a1 = register_action(run_sequence, &epk_seq_a_register_action);
    name_action(epk_a1, "register_action");
    epk_e1 = register_event(immediate, NULL, epk_a1);
    name_event(epk_e1, "names.epk:5 rule main: on immediate");
    epk_rule_main = epk_e1;

    /* names.epk:6: rule while: on stop_motor repeat do seq_a_x, cancel main */
    epk_a2 = register_action(epk_do_r2, NULL);
    name_action(epk_a2, "seq_a_x, cancel main");
    epk_e2 = register_event(event_stop_motor, NULL, epk_a2);
    name_event(epk_e2, "names.epk:6 rule while: on stop_motor repeat");
    set_event_repeat(epk_e2, 1);

    mainloop();
    return 0;
}
