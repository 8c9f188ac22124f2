/*
 * units.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them, then mainloop().  The actions and events are
 * const tables registered at once (register_program), which the robot keeps
 * in program memory; the rules' sensor conditions are compiled into one
 * function.  Tables: 3 actions, 3 events.
 */
#include "utility.h"

/* units.epk:4: start_straight(250, 100) (250 steps/s for 388 steps) */
static const param_straight_steps epk_p1_r1 = {250, 388};
/* units.epk:5: start_straight(100 mm/s, 5 cm) (388 steps/s for 194 steps) */
static const param_straight_steps epk_p2_r1 = {388, 194};
/* units.epk:6: start_straight(speed: 2 cm/s, distance: 0.01 m) (78 steps/s for 39 steps) */
static const param_straight_steps epk_p3_r1 = {78, 39};
/* units.epk:7: start_straight(distance: 40 steps, speed: -200 steps/s) (-200 steps/s for 40 steps) */
static const param_straight_steps epk_p4_r1 = {-200, 40};
/* units.epk:8: start_curve(radius: 10 cm, degrees: -45 deg, speed: 300) (left wheel 300 steps/s, right 174 steps/s, 386 steps of the outer wheel) */
static const param_curve_steps epk_p5_r1 = {300, 174, 386};
/* units.epk:10: timer(1500 ms) */
static const param_event_timer epk_when_r2 = {1500L};
/* units.epk:11: timer(2 s) */
static const param_event_timer epk_when_r3 = {2000L};

/* units.epk:4: start_straight(250, 100) then start_straight(100 mm/s, 5 cm) then start_straight(speed: 2 cm/s, distance: 0.01 m) then start_straight(distance: 40 steps, speed: -200 steps/s) then start_curve(radius: 10 cm, degrees: -45 deg, speed: 300) then set_timer */
static const action epk_steps_r1[] = {
    {straight_steps, (void *)&epk_p1_r1},
    {straight_steps, (void *)&epk_p2_r1},
    {straight_steps, (void *)&epk_p3_r1},
    {straight_steps, (void *)&epk_p4_r1},
    {curve_steps, (void *)&epk_p5_r1},
    {set_timer, NULL},
};
static const param_sequence epk_seq_r1 = {epk_steps_r1, 6};
#ifndef EPUCKRT_NAMES_DROPPED
static const char *const epk_step_names_r1[] = {
    "start_straight(250, 100)",
    "start_straight(100 mm/s, 5 cm)",
    "start_straight(speed: 2 cm/s, distance: 0.01 m)",
    "start_straight(distance: 40 steps, speed: -200 steps/s)",
    "start_curve(radius: 10 cm, degrees: -45 deg, speed: 300)",
    "set_timer",
};
#endif

/* The actions, {function, parameter}: an action's id is its index. */
static const rt_action epk_action_table[] = {
    {run_sequence, &epk_seq_r1},   /* 0: units.epk:4: start_straight(250, 100) then start_straight(100 mm/s, 5 cm) then start_straight(spe... */
    {exit_main, NULL},   /* 1: units.epk:10: exit_main */
    {exit_main, NULL},   /* 2: units.epk:11: exit_main */
};

/* The events, {function, parameter, action id, flags, memory, priority,
 * mode}: an event's id is its index, by priority, highest first, then in
 * file order (the order mainloop polls them in).  A NULL function is the rule's
 * condition in epk_event_conditions; memory is the event's slot in
 * epk_event_memory (timers keep their last firing); mode 0: in no mode,
 * always armed. */
static const rt_event epk_event_table[] = {
    /* 0: units.epk:4: on immediate do start_straight(250, 100) then start_straight(100 mm/s, 5 cm) then start_straight(speed: 2 cm/s, distance: 0.01 m) then start_straight(distance: 40 steps, speed: -200 steps/s) then start_curve(radius: 10 cm, degrees: -45 deg, speed: 300) then set_timer */
    {immediate, NULL, 0, 0, RT_NO_MEMORY, 0, 0},
    /* 1: units.epk:10: on timer(1500 ms) do exit_main */
    {timer, &epk_when_r2, 1, RT_WAKE_AS_TIMER, 0, 0, 0},
    /* 2: units.epk:11: on timer(2 s) do exit_main */
    {timer, &epk_when_r3, 2, RT_WAKE_AS_TIMER, 1, 0, 0},
};

/* What changes while the program runs, the only part in RAM. */
static unsigned epk_event_state[RT_STATE_WORDS(3, 3)];
static long epk_event_memory[2];

static const rt_program epk_program = {
    epk_action_table, 3, epk_event_table, 3,
    NULL, 0x00, epk_event_state, epk_event_memory,
    NULL
};

int main(void)
{
    /* the robot block: converts the runtime's millimetres and the simulated odometry */
    set_robot_geometry(257610L, 53000L, 1000L);
    (void)register_program(&epk_program);

    /* Names in the host harness's trace; without them on the robot (EPUCKRT_NO_NAMES). */
    name_action(0, "start_straight(250, 100) then start_straight(100 mm/s, 5 cm) then start_straight(speed: 2 cm/s, d...");
    name_action(1, "exit_main");
    name_action(2, "exit_main");
    name_event(0, "units.epk:4 on immediate");
    name_event(1, "units.epk:10 on timer(1500 ms)");
    name_event(2, "units.epk:11 on timer(2 s)");
    name_steps(0, epk_step_names_r1, 6);

    mainloop();
    return 0;
}
