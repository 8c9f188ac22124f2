/*
 * events.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 5 actions, 5 events.
 */
#include "utility.h"

/* events.epk:3: start_straight(300, 1 cm) (300 steps/s, 78 steps) */
static param_start_straight p1_r2 = {300, 10, 78};
/* events.epk:3: sensor(ir2 > 1000, ir5 < 20) */
static param_event_sensor when_r2 = {{SENSOR_OFF, SENSOR_OFF, 1000, SENSOR_OFF, SENSOR_OFF, 20, SENSOR_OFF, SENSOR_OFF}, 0x20};
/* events.epk:5: timer(400 ms) */
static param_event_timer when_r4 = {400L};
/* events.epk:6: event_timer(time: 3 s) */
static param_event_timer when_r5 = {3000L};

/* events.epk:2: start_sensor, set_timer */
static void do_r1(void *param)
{
    (void)param;
    start_sensor(NULL);
    set_timer(NULL);
}

/* events.epk:4: reset_timer, set_timer */
static void do_r3(void *param)
{
    (void)param;
    reset_timer(NULL);
    set_timer(NULL);
}

/* events.epk:6: stop_motor, exit_main */
static void do_r5(void *param)
{
    (void)param;
    stop_motor(NULL);
    exit_main(NULL);
}

int main(void)
{
    int a1, a2, a3, a4, a5;
    int e1, e2, e3, e4, e5;

    /* events.epk:2: on immediate do start_sensor, set_timer */
    a1 = register_action(do_r1, NULL);
    name_action(a1, "start_sensor, set_timer");
    e1 = register_event(immediate, NULL, a1);
    name_event(e1, "events.epk:2 on immediate");

    /* events.epk:3: rule near: on sensor(ir2 > 1000, ir5 < 20) repeat do start_straight(300, 1 cm) */
    a2 = register_action(start_straight, &p1_r2);
    name_action(a2, "start_straight(300, 1 cm)");
    e2 = register_event(sensor, &when_r2, a2);
    name_event(e2, "events.epk:3 rule near: on sensor(ir2 > 1000, ir5 < 20) repeat");
    set_event_repeat(e2, 1);

    /* events.epk:4: rule moved: on stop_motor repeat do reset_timer, set_timer */
    a3 = register_action(do_r3, NULL);
    name_action(a3, "reset_timer, set_timer");
    e3 = register_event(event_stop_motor, NULL, a3);
    name_event(e3, "events.epk:4 rule moved: on stop_motor repeat");
    set_event_repeat(e3, 1);

    /* events.epk:5: on timer(400 ms) repeat do stop_sensor */
    a4 = register_action(stop_sensor, NULL);
    name_action(a4, "stop_sensor");
    e4 = register_event(timer, &when_r4, a4);
    name_event(e4, "events.epk:5 on timer(400 ms) repeat");
    set_event_repeat(e4, 1);

    /* events.epk:6: on event_timer(time: 3 s) do stop_motor, exit_main */
    a5 = register_action(do_r5, NULL);
    name_action(a5, "stop_motor, exit_main");
    e5 = register_event(timer, &when_r5, a5);
    name_event(e5, "events.epk:6 on event_timer(time: 3 s)");

    mainloop();
    return 0;
}
