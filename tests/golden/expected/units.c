/*
 * units.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 3 actions, 3 events.
 */
#include "utility.h"

/* units.epk:4: start_straight(250, 100) (250 steps/s, 388 steps) */
static param_start_straight p1_r1 = {250, 100, 388};
/* units.epk:5: start_straight(100 mm/s, 5 cm) (388 steps/s, 194 steps) */
static param_start_straight p2_r1 = {388, 50, 194};
/* units.epk:6: start_straight(speed: 2 cm/s, distance: 0.01 m) (78 steps/s, 39 steps) */
static param_start_straight p3_r1 = {78, 10, 39};
/* units.epk:7: start_straight(distance: 40 steps, speed: -200 steps/s) (-200 steps/s, 40 steps) */
static param_start_straight p4_r1 = {-200, 10, 40};
/* units.epk:8: start_curve(radius: 10 cm, degrees: -45 deg, speed: 300) (outer wheel 300 steps/s for 386 steps, inner 174 steps/s) */
static param_start_curve p5_r1 = {100, -45, 300, 386, 174};
/* units.epk:10: timer(1500 ms) */
static param_event_timer when_r2 = {1500L};
/* units.epk:11: timer(2 s) */
static param_event_timer when_r3 = {2000L};

/* units.epk:4: start_straight(250, 100) then start_straight(100 mm/s, 5 cm) then start_straight(speed: 2 cm/s, distance: 0.01 m) then start_straight(distance: 40 steps, speed: -200 steps/s) then start_curve(radius: 10 cm, degrees: -45 deg, speed: 300) then set_timer */
static const action steps_r1[] = {
    {start_straight, &p1_r1},
    {start_straight, &p2_r1},
    {start_straight, &p3_r1},
    {start_straight, &p4_r1},
    {start_curve, &p5_r1},
    {set_timer, NULL},
};
static param_sequence seq_r1 = {steps_r1, 6};

int main(void)
{
    int a1, a2, a3;
    int e1, e2, e3;

    /* the robot block: converts the runtime's millimetres and the simulated odometry */
    set_robot_geometry(257610L, 53000L, 1000L);

    /* units.epk:4: on immediate do start_straight(250, 100) then start_straight(100 mm/s, 5 cm) then start_straight(speed: 2 cm/s, distance: 0.01 m) then start_straight(distance: 40 steps, speed: -200 steps/s) then start_curve(radius: 10 cm, degrees: -45 deg, speed: 300) then set_timer */
    a1 = register_action(run_sequence, &seq_r1);
    name_action(a1, "start_straight(250, 100) then start_straight(100 mm/s, 5 cm) then start_straight(speed: 2 cm/s, d...");
    e1 = register_event(immediate, NULL, a1);
    name_event(e1, "units.epk:4 on immediate");

    /* units.epk:10: on timer(1500 ms) do exit_main */
    a2 = register_action(exit_main, NULL);
    name_action(a2, "exit_main");
    e2 = register_event(timer, &when_r2, a2);
    name_event(e2, "units.epk:10 on timer(1500 ms)");

    /* units.epk:11: on timer(2 s) do exit_main */
    a3 = register_action(exit_main, NULL);
    name_action(a3, "exit_main");
    e3 = register_event(timer, &when_r3, a3);
    name_event(e3, "units.epk:11 on timer(2 s)");

    mainloop();
    return 0;
}
