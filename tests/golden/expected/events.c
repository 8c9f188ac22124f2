/*
 * events.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 5 actions, 5 events.
 */
#include "utility.h"

/* events.epk:3: start_straight(300, 1 cm) (300 steps/s for 78 steps) */
static param_straight_steps epk_p1_r2 = {300, 78};
/* events.epk:3: sensor(ir2 > 1000, ir5 < 20) */
static param_event_sensor epk_when_r2 = {{SENSOR_OFF, SENSOR_OFF, 1000, SENSOR_OFF, SENSOR_OFF, 20, SENSOR_OFF, SENSOR_OFF}, 0x20};
/* events.epk:5: timer(400 ms) */
static param_event_timer epk_when_r4 = {400L};
/* events.epk:6: event_timer(time: 3 s) */
static param_event_timer epk_when_r5 = {3000L};

/* events.epk:2: start_sensor, set_timer */
static void epk_do_r1(void *epk_param)
{
    (void)epk_param;
    start_sensor(NULL);
    set_timer(NULL);
}

/* events.epk:4: reset_timer, set_timer */
static void epk_do_r3(void *epk_param)
{
    (void)epk_param;
    reset_timer(NULL);
    set_timer(NULL);
}

/* events.epk:6: stop_motor, exit_main */
static void epk_do_r5(void *epk_param)
{
    (void)epk_param;
    stop_motor(NULL);
    exit_main(NULL);
}

int main(void)
{
    int epk_a1, epk_a2, epk_a3, epk_a4, epk_a5;
    int epk_e1, epk_e2, epk_e3, epk_e4, epk_e5;

    /* events.epk:2: on immediate do start_sensor, set_timer */
    epk_a1 = register_action(epk_do_r1, NULL);
    name_action(epk_a1, "start_sensor, set_timer");
    epk_e1 = register_event(immediate, NULL, epk_a1);
    name_event(epk_e1, "events.epk:2 on immediate");

    /* events.epk:3: rule near: on sensor(ir2 > 1000, ir5 < 20) repeat do start_straight(300, 1 cm) */
    epk_a2 = register_action(straight_steps, &epk_p1_r2);
    name_action(epk_a2, "start_straight(300, 1 cm)");
    epk_e2 = register_event(sensor, &epk_when_r2, epk_a2);
    name_event(epk_e2, "events.epk:3 rule near: on sensor(ir2 > 1000, ir5 < 20) repeat");
    set_event_repeat(epk_e2, 1);

    /* events.epk:4: rule moved: on stop_motor repeat do reset_timer, set_timer */
    epk_a3 = register_action(epk_do_r3, NULL);
    name_action(epk_a3, "reset_timer, set_timer");
    epk_e3 = register_event(event_stop_motor, NULL, epk_a3);
    name_event(epk_e3, "events.epk:4 rule moved: on stop_motor repeat");
    set_event_repeat(epk_e3, 1);

    /* events.epk:5: on timer(400 ms) repeat do stop_sensor */
    epk_a4 = register_action(stop_sensor, NULL);
    name_action(epk_a4, "stop_sensor");
    epk_e4 = register_event(timer, &epk_when_r4, epk_a4);
    name_event(epk_e4, "events.epk:5 on timer(400 ms) repeat");
    set_event_repeat(epk_e4, 1);

    /* events.epk:6: on event_timer(time: 3 s) do stop_motor, exit_main */
    epk_a5 = register_action(epk_do_r5, NULL);
    name_action(epk_a5, "stop_motor, exit_main");
    epk_e5 = register_event(timer, &epk_when_r5, epk_a5);
    name_event(epk_e5, "events.epk:6 on event_timer(time: 3 s)");

    mainloop();
    return 0;
}
