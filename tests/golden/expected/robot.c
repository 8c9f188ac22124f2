/*
 * robot.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 12 actions, 12 events.
 */
#include "utility.h"

/* robot.epk:5: led_on(led0) */
static param_set_led p1_r1 = {0, SET_LED_ON};
/* robot.epk:5: start_straight(300, 50 cm) (300 steps/s, 3882 steps) */
static param_start_straight p2_r1 = {300, 500, 3882};
/* robot.epk:6: start_straight(300, 50 cm) (300 steps/s, 3882 steps) */
static param_start_straight p1_r2 = {300, 500, 3882};
/* robot.epk:7: start_curve(0 mm, 90 deg, 300) (outer wheel 300 steps/s for 323 steps, inner -300 steps/s) */
static param_start_curve p1_r3 = {0, 90, 300, 323, -300};
/* robot.epk:7: sensor(ir0 > 500, ir7 > 500) */
static param_event_sensor when_r3 = {{500, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, 500}, 0x00};
/* robot.epk:8: start_straight(-500, 5 cm) (-500 steps/s, 388 steps) */
static param_start_straight p1_r4 = {-500, 50, 388};
/* robot.epk:8: tap(600) */
static param_event_accel when_r4 = {600};
/* mode rest */
static param_enter_mode mode_rest = {2};
/* robot.epk:9: timer(60 s) */
static param_event_timer when_r5 = {60000L};
/* robot.epk:12: led_off(all) */
static param_set_led p1_r6 = {SET_LED_ALL, SET_LED_OFF};
/* robot.epk:12: led_on(body) */
static param_set_led p2_r6 = {SET_LED_BODY, SET_LED_ON};
/* robot.epk:12: play_sound(wouaaaaaaaah) */
static param_play_sound p3_r6 = {SOUND_WOUAAAAAAAAH};
/* mode explore */
static param_enter_mode mode_explore = {1};
/* robot.epk:13: remote(5) */
static param_event_remote when_r7 = {5};
/* robot.epk:14: remote(standby) */
static param_event_remote when_r8 = {12};
/* robot.epk:16: led_toggle(front) */
static param_set_led p1_r9 = {SET_LED_FRONT, SET_LED_TOGGLE};
/* robot.epk:16: clap(3000) */
static param_event_clap when_r9 = {3000};
/* robot.epk:17: play_sound(haa) */
static param_play_sound p1_r10 = {SOUND_HAA};
/* robot.epk:17: ambient(ir0 < 200) */
static param_event_sensor when_r10 = {{200, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF}, 0x01};
/* robot.epk:18: tilt(800) */
static param_event_accel when_r11 = {800};
/* robot.epk:19: selector(15) */
static param_event_selector when_r12 = {15};

/* robot.epk:5: start_sensor, set_timer, led_on(led0), start_straight(300, 50 cm) */
static void do_r1(void *param)
{
    (void)param;
    start_sensor(NULL);
    set_timer(NULL);
    action_set_led(&p1_r1);
    start_straight(&p2_r1);
}

/* robot.epk:12: stop_motor, led_off(all), led_on(body), play_sound(wouaaaaaaaah) */
static void do_r6(void *param)
{
    (void)param;
    stop_motor(NULL);
    action_set_led(&p1_r6);
    action_set_led(&p2_r6);
    action_play_sound(&p3_r6);
}

int main(void)
{
    int a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12;
    int e1, e2, e3, e4, e5, e6, e7, e8, e9, e10, e11, e12;

    /* the modes, for the trace */
    name_mode(1, "explore");
    name_mode(2, "rest");

    /* robot.epk:5: on enter do start_sensor, set_timer, led_on(led0), start_straight(300, 50 cm) */
    a1 = register_action(do_r1, NULL);
    name_action(a1, "start_sensor, set_timer, led_on(led0), start_straight(300, 50 cm)");
    e1 = register_event(event_enter_mode, NULL, a1);
    name_event(e1, "robot.epk:5 on enter");
    set_event_mode(e1, 1);  /* mode explore */

    /* robot.epk:6: rule wander: on stop_motor repeat do start_straight(300, 50 cm) */
    a2 = register_action(start_straight, &p1_r2);
    name_action(a2, "start_straight(300, 50 cm)");
    e2 = register_event(event_stop_motor, NULL, a2);
    name_event(e2, "robot.epk:6 rule wander: on stop_motor repeat");
    set_event_repeat(e2, 1);
    set_event_mode(e2, 1);  /* mode explore */

    /* robot.epk:7: rule avoid: on sensor(ir0 > 500, ir7 > 500) repeat priority 1 do start_curve(0 mm, 90 deg, 300) */
    a3 = register_action(start_curve, &p1_r3);
    name_action(a3, "start_curve(0 mm, 90 deg, 300)");
    e3 = register_event(sensor, &when_r3, a3);
    name_event(e3, "robot.epk:7 rule avoid: on sensor(ir0 > 500, ir7 > 500) repeat priority 1");
    set_event_repeat(e3, 1);
    set_event_priority(e3, 1);
    set_event_mode(e3, 1);  /* mode explore */

    /* robot.epk:8: rule escape: on tap(600) repeat priority urgent do start_straight(-500, 5 cm) */
    a4 = register_action(start_straight, &p1_r4);
    name_action(a4, "start_straight(-500, 5 cm)");
    e4 = register_event(event_tap, &when_r4, a4);
    name_event(e4, "robot.epk:8 rule escape: on tap(600) repeat priority 3");
    set_event_repeat(e4, 1);
    set_event_priority(e4, 3);
    set_event_mode(e4, 1);  /* mode explore */

    /* robot.epk:9: on timer(60 s) do enter rest */
    a5 = register_action(action_enter_mode, &mode_rest);
    name_action(a5, "enter rest");
    e5 = register_event(timer, &when_r5, a5);
    name_event(e5, "robot.epk:9 on timer(60 s)");
    set_event_mode(e5, 1);  /* mode explore */

    /* robot.epk:12: on enter do stop_motor, led_off(all), led_on(body), play_sound(wouaaaaaaaah) */
    a6 = register_action(do_r6, NULL);
    name_action(a6, "stop_motor, led_off(all), led_on(body), play_sound(wouaaaaaaaah)");
    e6 = register_event(event_enter_mode, NULL, a6);
    name_event(e6, "robot.epk:12 on enter");
    set_event_mode(e6, 2);  /* mode rest */

    /* robot.epk:13: on remote(5) do enter explore */
    a7 = register_action(action_enter_mode, &mode_explore);
    name_action(a7, "enter explore");
    e7 = register_event(event_remote, &when_r7, a7);
    name_event(e7, "robot.epk:13 on remote(5)");
    set_event_mode(e7, 2);  /* mode rest */

    /* robot.epk:14: on remote(standby) do exit_main */
    a8 = register_action(exit_main, NULL);
    name_action(a8, "exit_main");
    e8 = register_event(event_remote, &when_r8, a8);
    name_event(e8, "robot.epk:14 on remote(standby)");
    set_event_mode(e8, 2);  /* mode rest */

    /* robot.epk:16: on clap(3000) repeat do led_toggle(front) */
    a9 = register_action(action_set_led, &p1_r9);
    name_action(a9, "led_toggle(front)");
    e9 = register_event(event_clap, &when_r9, a9);
    name_event(e9, "robot.epk:16 on clap(3000) repeat");
    set_event_repeat(e9, 1);

    /* robot.epk:17: on ambient(ir0 < 200) repeat do play_sound(haa) */
    a10 = register_action(action_play_sound, &p1_r10);
    name_action(a10, "play_sound(haa)");
    e10 = register_event(event_ambient, &when_r10, a10);
    name_event(e10, "robot.epk:17 on ambient(ir0 < 200) repeat");
    set_event_repeat(e10, 1);

    /* robot.epk:18: on tilt(800) do exit_main */
    a11 = register_action(exit_main, NULL);
    name_action(a11, "exit_main");
    e11 = register_event(event_tilt, &when_r11, a11);
    name_event(e11, "robot.epk:18 on tilt(800)");

    /* robot.epk:19: on selector(15) do exit_main */
    a12 = register_action(exit_main, NULL);
    name_action(a12, "exit_main");
    e12 = register_event(event_selector, &when_r12, a12);
    name_event(e12, "robot.epk:19 on selector(15)");

    enter_mode(1);   /* the initial mode, explore */
    mainloop();
    return 0;
}
