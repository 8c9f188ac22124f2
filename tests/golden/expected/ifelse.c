/*
 * ifelse.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them, then mainloop().  The actions and events are
 * const tables registered at once (register_program), which the robot keeps
 * in program memory; the rules' sensor conditions are compiled into one
 * function.  Tables: 4 actions, 4 events.
 */
#include "utility.h"

/* ifelse.epk:17: led_on(all) */
static const param_set_led epk_p1_r4 = {SET_LED_ALL, SET_LED_ON};
/* ifelse.epk:17: led_off(all) */
static const param_set_led epk_p2_r4 = {SET_LED_ALL, SET_LED_OFF};
/* ifelse.epk:7: start_curve(0 mm, 90 deg, 300) (left wheel -300 steps/s, right 300 steps/s, 323 steps of the outer wheel) */
static const param_curve_steps epk_p1_a_dodge = {-300, 300, 323};
/* ifelse.epk:7: start_curve(0 mm, -90 deg, 300) (left wheel 300 steps/s, right -300 steps/s, 323 steps of the outer wheel) */
static const param_curve_steps epk_p2_a_dodge = {300, -300, 323};
/* mode resting */
static const param_enter_mode epk_mode_resting = {1};
/* ifelse.epk:14: led_toggle(front) */
static const param_set_led epk_p1_r3 = {SET_LED_FRONT, SET_LED_TOGGLE};
/* ifelse.epk:14: timer(5 s) */
static const param_event_timer epk_when_r3 = {5000L};
/* ifelse.epk:11: led_on(body) */
static const param_set_led epk_p1_r2 = {SET_LED_BODY, SET_LED_ON};
/* ifelse.epk:12: set_speed(150, 150) */
static const param_set_speed epk_p2_r2 = {150, 150};
/* ifelse.epk:12: led_off(body) */
static const param_set_led epk_p3_r2 = {SET_LED_BODY, SET_LED_OFF};
/* ifelse.epk:13: set_speed(400, 400) */
static const param_set_speed epk_p4_r2 = {400, 400};
/* ifelse.epk:13: led_off(body) */
static const param_set_led epk_p5_r2 = {SET_LED_BODY, SET_LED_OFF};
/* ifelse.epk:10: every 20 ms */
static const param_event_every epk_when_r2 = {20L};

/* The variables (16-bit; their interval as the checker bounds it). */
static int epk_v_near = 0;   /* ifelse.epk:4: var near: 0..4095 */
static int epk_v_turns = 0;   /* ifelse.epk:5: var turns: 0..100 */

/* Event ids of the rules that `cancel` names. */
enum {
    epk_rule_look = 3
};

/* ifelse.epk:17: stop_motor, if turns > 10 { led_on(all) } else { led_off(all) } */
static void epk_do_r4(void *epk_param)
{
    (void)epk_param;
    stop_motor(NULL);
    if (epk_v_turns > 10) {
        action_set_led((void *)&epk_p1_r4);
    } else {
        action_set_led((void *)&epk_p2_r4);
    }
}

/* ifelse.epk:14: step 1 of 2: if near > NEAR { turns = clamp(turns + 1, 0, 100), dodge, if turns > 3 { cancel look, enter resting } } */
static void epk_step1_r3(void *epk_param)
{
    (void)epk_param;
    if (epk_v_near > 500) {
        rt_assign(&epk_v_turns, 1, rt_clamp(epk_v_turns + 1, 0, 100));
        if (epk_v_turns % 2 == 0) {
            curve_steps((void *)&epk_p1_a_dodge);
        } else {
            curve_steps((void *)&epk_p2_a_dodge);
        }
        if (epk_v_turns > 3) {
            cancel_event(epk_rule_look);
            action_enter_mode((void *)&epk_mode_resting);
        }
    }
}

/* ifelse.epk:9: start_sensor, set_timer */
static void epk_do_r1(void *epk_param)
{
    (void)epk_param;
    start_sensor(NULL);
    set_timer(NULL);
}

/* ifelse.epk:10: near = max(ir0, ir7), if near > 2000 { stop_motor, led_on(body) } else if near > NEAR { set_speed(150, 150), led_off(body) } else { set_speed(400, 400), led_off(body) } */
static void epk_do_r2(void *epk_param)
{
    (void)epk_param;
    rt_assign(&epk_v_near, 0, rt_max(rt_ir(0), rt_ir(7)));
    if (epk_v_near > 2000) {
        stop_motor(NULL);
        action_set_led((void *)&epk_p1_r2);
    } else if (epk_v_near > 500) {
        action_set_speed((void *)&epk_p2_r2);
        action_set_led((void *)&epk_p3_r2);
    } else {
        action_set_speed((void *)&epk_p4_r2);
        action_set_led((void *)&epk_p5_r2);
    }
}

/* ifelse.epk:14: if near > NEAR { turns = clamp(turns + 1, 0, 100), dodge, if turns > 3 { cancel look, enter resting } } then led_toggle(front) */
static const action epk_steps_r3[] = {
    {epk_step1_r3, NULL},
    {action_set_led, (void *)&epk_p1_r3},
};
static const param_sequence epk_seq_r3 = {epk_steps_r3, 2};
#ifndef EPUCKRT_NAMES_DROPPED
static const char *const epk_step_names_r3[] = {
    "if near > NEAR { turns = clamp(turns + 1, 0, 100), dodge, if turns > 3 { cancel look, enter resti...",
    "led_toggle(front)",
};
#endif

/* The actions, {function, parameter}: an action's id is its index. */
static const rt_action epk_action_table[] = {
    {epk_do_r4, NULL},   /* 0: ifelse.epk:17: stop_motor, if turns > 10 { led_on(all) } else { led_off(all) } */
    {run_sequence, &epk_seq_r3},   /* 1: ifelse.epk:14: if near > NEAR { turns = clamp(turns + 1, 0, 100), dodge, if turns > 3 { cancel lo... */
    {epk_do_r1, NULL},   /* 2: ifelse.epk:9: start_sensor, set_timer */
    {epk_do_r2, NULL},   /* 3: ifelse.epk:10: near = max(ir0, ir7), if near > 2000 { stop_motor, led_on(body) } else if near > N... */
};

/* The events, {function, parameter, action id, flags, memory, priority,
 * mode}: an event's id is its index, by priority, highest first, then in
 * file order (the order mainloop polls them in).  A NULL function is the rule's
 * condition in epk_event_conditions; memory is the event's slot in
 * epk_event_memory (timers keep their last firing); mode 0: in no mode,
 * always armed. */
static const rt_event epk_event_table[] = {
    /* 0: ifelse.epk:17: on enter priority 2 do stop_motor, if turns > 10 { led_on(all) } else { led_off(all) } (mode resting) */
    {event_enter_mode, NULL, 0, RT_WAKE_ON_CHANGE, 0, 2, 1},
    /* 1: ifelse.epk:14: on timer(5 s) repeat priority 1 do if near > NEAR { turns = clamp(turns + 1, 0, 100), dodge, if turns > 3 { cancel look, enter resting } } then led_toggle(front) */
    {timer, &epk_when_r3, 1, RT_REPEAT | RT_WAKE_AS_TIMER, 1, 1, 0},
    /* 2: ifelse.epk:9: on immediate do start_sensor, set_timer */
    {immediate, NULL, 2, 0, RT_NO_MEMORY, 0, 0},
    /* 3: ifelse.epk:10: rule look: every 20 ms do near = max(ir0, ir7), if near > 2000 { stop_motor, led_on(body) } else if near > NEAR { set_speed(150, 150), led_off(body) } else { set_speed(400, 400), led_off(body) } */
    {event_every, &epk_when_r2, 3, RT_REPEAT | RT_WAKE_AT_DEADLINE, 2, 0, 0},
};

/* What changes while the program runs, the only part in RAM. */
static unsigned epk_event_state[RT_STATE_WORDS(4, 4)];
static long epk_event_memory[3];

static const rt_program epk_program = {
    epk_action_table, 4, epk_event_table, 4,
    NULL, 0x00, epk_event_state, epk_event_memory,
    NULL
};

int main(void)
{
    (void)register_program(&epk_program);

    /* Names in the host harness's trace; without them on the robot (EPUCKRT_NO_NAMES). */
    name_action(0, "stop_motor, if turns > 10 { led_on(all) } else { led_off(all) }");
    name_action(1, "if near > NEAR { turns = clamp(turns + 1, 0, 100), dodge, if turns > 3 { cancel look, enter resti...");
    name_action(2, "start_sensor, set_timer");
    name_action(3, "near = max(ir0, ir7), if near > 2000 { stop_motor, led_on(body) } else if near > NEAR { set_speed...");
    name_event(0, "ifelse.epk:17 on enter priority 2");
    name_event(1, "ifelse.epk:14 on timer(5 s) repeat priority 1");
    name_event(2, "ifelse.epk:9 on immediate");
    name_event(3, "ifelse.epk:10 rule look: every 20 ms");
    name_steps(1, epk_step_names_r3, 2);

    /* the variables, for the trace */
    name_var(0, "near");
    name_var(1, "turns");

    /* the modes, for the trace */
    name_mode(1, "resting");
    enter_mode(1);   /* the initial mode, resting */

    mainloop();
    return 0;
}
