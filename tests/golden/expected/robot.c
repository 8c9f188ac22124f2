/*
 * robot.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them, then mainloop().  The actions and events are
 * const tables registered at once (register_program), which the robot keeps
 * in program memory; the rules' sensor conditions are compiled into one
 * function.  Tables: 12 actions, 12 events.
 */
#include "utility.h"

/* robot.epk:8: start_straight(-500, 5 cm) (-500 steps/s for 388 steps) */
static const param_straight_steps epk_p1_r4 = {-500, 388};
/* robot.epk:8: tap(600) */
static const param_event_accel epk_when_r4 = {600};
/* robot.epk:7: start_curve(0 mm, 90 deg, 300) (left wheel -300 steps/s, right 300 steps/s, 323 steps of the outer wheel) */
static const param_curve_steps epk_p1_r3 = {-300, 300, 323};
/* robot.epk:5: led_on(led0) */
static const param_set_led epk_p1_r1 = {0, SET_LED_ON};
/* robot.epk:5: start_straight(300, 50 cm) (300 steps/s for 3882 steps) */
static const param_straight_steps epk_p2_r1 = {300, 3882};
/* robot.epk:6: start_straight(300, 50 cm) (300 steps/s for 3882 steps) */
static const param_straight_steps epk_p1_r2 = {300, 3882};
/* mode rest */
static const param_enter_mode epk_mode_rest = {2};
/* robot.epk:9: timer(60 s) */
static const param_event_timer epk_when_r5 = {60000L};
/* robot.epk:12: led_off(all) */
static const param_set_led epk_p1_r6 = {SET_LED_ALL, SET_LED_OFF};
/* robot.epk:12: led_on(body) */
static const param_set_led epk_p2_r6 = {SET_LED_BODY, SET_LED_ON};
/* robot.epk:12: play_sound(wouaaaaaaaah) */
static const param_play_sound epk_p3_r6 = {SOUND_WOUAAAAAAAAH};
/* mode explore */
static const param_enter_mode epk_mode_explore = {1};
/* robot.epk:13: remote(5) */
static const param_event_remote epk_when_r7 = {5};
/* robot.epk:14: remote(standby) */
static const param_event_remote epk_when_r8 = {12};
/* robot.epk:16: led_toggle(front) */
static const param_set_led epk_p1_r9 = {SET_LED_FRONT, SET_LED_TOGGLE};
/* robot.epk:16: clap(3000) */
static const param_event_clap epk_when_r9 = {3000};
/* robot.epk:17: play_sound(haa) */
static const param_play_sound epk_p1_r10 = {SOUND_HAA};
/* robot.epk:17: ambient(ir0 < 200) */
static const param_event_sensor epk_when_r10 = {{200, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF}, 0x01};
/* robot.epk:18: tilt(800) */
static const param_event_accel epk_when_r11 = {800};
/* robot.epk:19: selector(15) */
static const param_event_selector epk_when_r12 = {15};

/* robot.epk:5: start_sensor, set_timer, led_on(led0), start_straight(300, 50 cm) */
static void epk_do_r1(void *epk_param)
{
    (void)epk_param;
    start_sensor(NULL);
    set_timer(NULL);
    action_set_led((void *)&epk_p1_r1);
    straight_steps((void *)&epk_p2_r1);
}

/* robot.epk:12: stop_motor, led_off(all), led_on(body), play_sound(wouaaaaaaaah) */
static void epk_do_r6(void *epk_param)
{
    (void)epk_param;
    stop_motor(NULL);
    action_set_led((void *)&epk_p1_r6);
    action_set_led((void *)&epk_p2_r6);
    action_play_sound((void *)&epk_p3_r6);
}

/* The rules' sensor conditions, from this poll's proximity readings
 * epk_ir[0..7]: bit k % 16 of epk_c[k / 16] is event k's.  The runtime
 * calls it at most once per poll, while the sensors are on. */
static void epk_event_conditions(const int *epk_ir, unsigned *epk_c)
{
    const int epk_ir0 = epk_ir[0];
    const int epk_ir7 = epk_ir[7];

    epk_c[0] = 0;
    if (epk_ir0 > 500 || epk_ir7 > 500) epk_c[0] |= 0x0002u;   /* event 1: robot.epk:7 */
}

/* The actions, {function, parameter}: an action's id is its index. */
static const rt_action epk_action_table[] = {
    {straight_steps, &epk_p1_r4},   /* 0: robot.epk:8: start_straight(-500, 5 cm) */
    {curve_steps, &epk_p1_r3},   /* 1: robot.epk:7: start_curve(0 mm, 90 deg, 300) */
    {epk_do_r1, NULL},   /* 2: robot.epk:5: start_sensor, set_timer, led_on(led0), start_straight(300, 50 cm) */
    {straight_steps, &epk_p1_r2},   /* 3: robot.epk:6: start_straight(300, 50 cm) */
    {action_enter_mode, &epk_mode_rest},   /* 4: robot.epk:9: enter rest */
    {epk_do_r6, NULL},   /* 5: robot.epk:12: stop_motor, led_off(all), led_on(body), play_sound(wouaaaaaaaah) */
    {action_enter_mode, &epk_mode_explore},   /* 6: robot.epk:13: enter explore */
    {exit_main, NULL},   /* 7: robot.epk:14: exit_main */
    {action_set_led, &epk_p1_r9},   /* 8: robot.epk:16: led_toggle(front) */
    {action_play_sound, &epk_p1_r10},   /* 9: robot.epk:17: play_sound(haa) */
    {exit_main, NULL},   /* 10: robot.epk:18: exit_main */
    {exit_main, NULL},   /* 11: robot.epk:19: exit_main */
};

/* The events, {function, parameter, action id, flags, memory, priority,
 * mode}: an event's id is its index, by priority, highest first, then in
 * file order (the order mainloop polls them in).  A NULL function is the rule's
 * condition in epk_event_conditions; memory is the event's slot in
 * epk_event_memory (timers keep their last firing); mode 0: in no mode,
 * always armed. */
static const rt_event epk_event_table[] = {
    /* 0: robot.epk:8: rule escape: on tap(600) repeat priority urgent do start_straight(-500, 5 cm) (mode explore) */
    {event_tap, &epk_when_r4, 0, RT_REPEAT, 0, 3, 1},
    /* 1: robot.epk:7: rule avoid: on sensor(ir0 > 500, ir7 > 500) repeat priority 1 do start_curve(0 mm, 90 deg, 300) (mode explore) */
    {NULL, NULL, 1, RT_REPEAT | RT_HOLD_WHILE | RT_WAKE_ON_CHANGE, RT_NO_MEMORY, 1, 1},
    /* 2: robot.epk:5: on enter do start_sensor, set_timer, led_on(led0), start_straight(300, 50 cm) (mode explore) */
    {event_enter_mode, NULL, 2, RT_WAKE_ON_CHANGE, 1, 0, 1},
    /* 3: robot.epk:6: rule wander: on stop_motor repeat do start_straight(300, 50 cm) (mode explore) */
    {event_stop_motor, NULL, 3, RT_REPEAT | RT_WAKE_ON_CHANGE, RT_NO_MEMORY, 0, 1},
    /* 4: robot.epk:9: on timer(60 s) do enter rest (mode explore) */
    {timer, &epk_when_r5, 4, RT_WAKE_AS_TIMER, 2, 0, 1},
    /* 5: robot.epk:12: on enter do stop_motor, led_off(all), led_on(body), play_sound(wouaaaaaaaah) (mode rest) */
    {event_enter_mode, NULL, 5, RT_WAKE_ON_CHANGE, 3, 0, 2},
    /* 6: robot.epk:13: on remote(5) do enter explore (mode rest) */
    {event_remote, &epk_when_r7, 6, RT_WAKE_ON_CHANGE, 4, 0, 2},
    /* 7: robot.epk:14: on remote(standby) do exit_main (mode rest) */
    {event_remote, &epk_when_r8, 7, RT_WAKE_ON_CHANGE, 5, 0, 2},
    /* 8: robot.epk:16: on clap(3000) repeat do led_toggle(front) */
    {event_clap, &epk_when_r9, 8, RT_REPEAT | RT_WAKE_ON_CHANGE, 6, 0, 0},
    /* 9: robot.epk:17: on ambient(ir0 < 200) repeat do play_sound(haa) */
    {event_ambient, &epk_when_r10, 9, RT_REPEAT | RT_HOLD_WHILE | RT_WAKE_ON_CHANGE, 7, 0, 0},
    /* 10: robot.epk:18: on tilt(800) do exit_main */
    {event_tilt, &epk_when_r11, 10, 0, 8, 0, 0},
    /* 11: robot.epk:19: on selector(15) do exit_main */
    {event_selector, &epk_when_r12, 11, RT_WAKE_ON_CHANGE, 9, 0, 0},
};

/* What changes while the program runs, the only part in RAM. */
static unsigned epk_event_state[RT_STATE_WORDS(12, 12)];
static long epk_event_memory[10];

static const rt_program epk_program = {
    epk_action_table, 12, epk_event_table, 12,
    epk_event_conditions, 0x81, epk_event_state, epk_event_memory,
    NULL
};

int main(void)
{
    (void)register_program(&epk_program);

    /* Names in the host harness's trace; without them on the robot (EPUCKRT_NO_NAMES). */
    name_action(0, "start_straight(-500, 5 cm)");
    name_action(1, "start_curve(0 mm, 90 deg, 300)");
    name_action(2, "start_sensor, set_timer, led_on(led0), start_straight(300, 50 cm)");
    name_action(3, "start_straight(300, 50 cm)");
    name_action(4, "enter rest");
    name_action(5, "stop_motor, led_off(all), led_on(body), play_sound(wouaaaaaaaah)");
    name_action(6, "enter explore");
    name_action(7, "exit_main");
    name_action(8, "led_toggle(front)");
    name_action(9, "play_sound(haa)");
    name_action(10, "exit_main");
    name_action(11, "exit_main");
    name_event(0, "robot.epk:8 rule escape: on tap(600) repeat priority 3");
    name_event(1, "robot.epk:7 rule avoid: on sensor(ir0 > 500, ir7 > 500) repeat priority 1");
    name_event(2, "robot.epk:5 on enter");
    name_event(3, "robot.epk:6 rule wander: on stop_motor repeat");
    name_event(4, "robot.epk:9 on timer(60 s)");
    name_event(5, "robot.epk:12 on enter");
    name_event(6, "robot.epk:13 on remote(5)");
    name_event(7, "robot.epk:14 on remote(standby)");
    name_event(8, "robot.epk:16 on clap(3000) repeat");
    name_event(9, "robot.epk:17 on ambient(ir0 < 200) repeat");
    name_event(10, "robot.epk:18 on tilt(800)");
    name_event(11, "robot.epk:19 on selector(15)");

    /* the modes, for the trace */
    name_mode(1, "explore");
    name_mode(2, "rest");
    enter_mode(1);   /* the initial mode, explore */

    mainloop();
    return 0;
}
