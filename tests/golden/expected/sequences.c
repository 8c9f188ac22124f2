/*
 * sequences.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 1 actions, 1 events.
 */
#include "utility.h"

/* sequences.epk:2: start_straight(500, 5 cm) (500 steps/s for 388 steps) */
static param_straight_steps epk_p1_a_forward = {500, 388};
/* sequences.epk:3: start_curve(0 mm, 90 deg, 500) (left wheel -500 steps/s, right 500 steps/s, 323 steps of the outer wheel) */
static param_curve_steps epk_p1_a_turn = {-500, 500, 323};

/* sequences.epk:6: step 5 of 7: set_timer, start_straight(500, 5 cm) */
static void epk_step5_r1(void *epk_param)
{
    (void)epk_param;
    set_timer(NULL);
    straight_steps(&epk_p1_a_forward);
}

/* sequences.epk:6: l_shape then set_timer, leg then exit_main */
static const action epk_steps_r1[] = {
    {straight_steps, &epk_p1_a_forward},
    {curve_steps, &epk_p1_a_turn},
    {straight_steps, &epk_p1_a_forward},
    {curve_steps, &epk_p1_a_turn},
    {epk_step5_r1, NULL},
    {curve_steps, &epk_p1_a_turn},
    {exit_main, NULL},
};
static param_sequence epk_seq_r1 = {epk_steps_r1, 7};

int main(void)
{
    int epk_a1;
    int epk_e1;

    /* sequences.epk:6: on immediate do l_shape then set_timer, leg then exit_main */
    epk_a1 = register_action(run_sequence, &epk_seq_r1);
    name_action(epk_a1, "l_shape then set_timer, leg then exit_main");
    epk_e1 = register_event(immediate, NULL, epk_a1);
    name_event(epk_e1, "sequences.epk:6 on immediate");

    mainloop();
    return 0;
}
