/*
 * sequences.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 1 actions, 1 events.
 */
#include "utility.h"

/* sequences.epk:2: start_straight(500, 5 cm) (500 steps/s, 388 steps) */
static param_start_straight p1_a_forward = {500, 50, 388};
/* sequences.epk:3: start_curve(0 mm, 90 deg, 500) (outer wheel 500 steps/s for 323 steps, inner -500 steps/s) */
static param_start_curve p1_a_turn = {0, 90, 500, 323, -500};

/* sequences.epk:6: l_shape then set_timer, leg then exit_main - step 5: set_timer, start_straight(500, 5 cm) */
static void step5_r1(void *param)
{
    (void)param;
    set_timer(NULL);
    start_straight(&p1_a_forward);
}

/* sequences.epk:6: l_shape then set_timer, leg then exit_main */
static const action steps_r1[] = {
    {start_straight, &p1_a_forward},
    {start_curve, &p1_a_turn},
    {start_straight, &p1_a_forward},
    {start_curve, &p1_a_turn},
    {step5_r1, NULL},
    {start_curve, &p1_a_turn},
    {exit_main, NULL},
};
static param_sequence seq_r1 = {steps_r1, 7};

int main(void)
{
    int a1;
    int e1;

    /* sequences.epk:6: on immediate do l_shape then set_timer, leg then exit_main */
    a1 = register_action(run_sequence, &seq_r1);
    name_action(a1, "l_shape then set_timer, leg then exit_main");
    e1 = register_event(immediate, NULL, a1);
    name_event(e1, "sequences.epk:6 on immediate");

    mainloop();
    return 0;
}
