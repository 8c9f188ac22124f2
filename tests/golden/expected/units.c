/*
 * units.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 3 actions, 3 events.
 */
#include "utility.h"

/* units.epk:4: start_straight(250, 100) (250 steps/s for 388 steps) */
static param_straight_steps epk_p1_r1 = {250, 388};
/* units.epk:5: start_straight(100 mm/s, 5 cm) (388 steps/s for 194 steps) */
static param_straight_steps epk_p2_r1 = {388, 194};
/* units.epk:6: start_straight(speed: 2 cm/s, distance: 0.01 m) (78 steps/s for 39 steps) */
static param_straight_steps epk_p3_r1 = {78, 39};
/* units.epk:7: start_straight(distance: 40 steps, speed: -200 steps/s) (-200 steps/s for 40 steps) */
static param_straight_steps epk_p4_r1 = {-200, 40};
/* units.epk:8: start_curve(radius: 10 cm, degrees: -45 deg, speed: 300) (left wheel 300 steps/s, right 174 steps/s, 386 steps of the outer wheel) */
static param_curve_steps epk_p5_r1 = {300, 174, 386};
/* units.epk:10: timer(1500 ms) */
static param_event_timer epk_when_r2 = {1500L};
/* units.epk:11: timer(2 s) */
static param_event_timer epk_when_r3 = {2000L};

/* units.epk:4: start_straight(250, 100) then start_straight(100 mm/s, 5 cm) then start_straight(speed: 2 cm/s, distance: 0.01 m) then start_straight(distance: 40 steps, speed: -200 steps/s) then start_curve(radius: 10 cm, degrees: -45 deg, speed: 300) then set_timer */
static const action epk_steps_r1[] = {
    {straight_steps, &epk_p1_r1},
    {straight_steps, &epk_p2_r1},
    {straight_steps, &epk_p3_r1},
    {straight_steps, &epk_p4_r1},
    {curve_steps, &epk_p5_r1},
    {set_timer, NULL},
};
static param_sequence epk_seq_r1 = {epk_steps_r1, 6};

int main(void)
{
    int epk_a1, epk_a2, epk_a3;
    int epk_e1, epk_e2, epk_e3;

    /* the robot block: converts the runtime's millimetres and the simulated odometry */
    set_robot_geometry(257610L, 53000L, 1000L);

    /* units.epk:4: on immediate do start_straight(250, 100) then start_straight(100 mm/s, 5 cm) then start_straight(speed: 2 cm/s, distance: 0.01 m) then start_straight(distance: 40 steps, speed: -200 steps/s) then start_curve(radius: 10 cm, degrees: -45 deg, speed: 300) then set_timer */
    epk_a1 = register_action(run_sequence, &epk_seq_r1);
    name_action(epk_a1, "start_straight(250, 100) then start_straight(100 mm/s, 5 cm) then start_straight(speed: 2 cm/s, d...");
    epk_e1 = register_event(immediate, NULL, epk_a1);
    name_event(epk_e1, "units.epk:4 on immediate");

    /* units.epk:10: on timer(1500 ms) do exit_main */
    epk_a2 = register_action(exit_main, NULL);
    name_action(epk_a2, "exit_main");
    epk_e2 = register_event(timer, &epk_when_r2, epk_a2);
    name_event(epk_e2, "units.epk:10 on timer(1500 ms)");

    /* units.epk:11: on timer(2 s) do exit_main */
    epk_a3 = register_action(exit_main, NULL);
    name_action(epk_a3, "exit_main");
    epk_e3 = register_event(timer, &epk_when_r3, epk_a3);
    name_event(epk_e3, "units.epk:11 on timer(2 s)");

    mainloop();
    return 0;
}
