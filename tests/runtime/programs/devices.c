/* LEDs, sound, selector, microphones, accelerometer, remote control and
 * ambient light through the e-puck library API, simulated by the stub. */
#include "epuckrt.h"

static param_set_led body_on = { SET_LED_BODY, SET_LED_ON };
static param_set_led ring_toggle = { SET_LED_ALL, SET_LED_TOGGLE };
static param_set_led led3_on = { 3, SET_LED_ON };
static param_set_led front_toggle = { SET_LED_FRONT, SET_LED_TOGGLE };
static param_play_sound ouah = { SOUND_OUAH };
static param_play_sound bad_sound = { 7 };
static param_event_selector sel5 = { 5 };
static param_event_clap loud = { 2000 };
static param_event_accel knock = { 500 }, lean = { 300 };
static param_event_remote mute = { 13 }, seven = { 7 };
static param_event_sensor dark = { { SENSOR_OFF, SENSOR_OFF, 1000, SENSOR_OFF, SENSOR_OFF,
                                     SENSOR_OFF, SENSOR_OFF, SENSOR_OFF }, 0 };
static param_event_timer end = { 3000 };

static void named(int e, const char *name)
{
    name_event(e, name);
}

int main(void)
{
    int a_body = register_action(action_set_led, &body_on);
    int a_ring = register_action(action_set_led, &ring_toggle);
    int a_led3 = register_action(action_set_led, &led3_on);
    int a_front = register_action(action_set_led, &front_toggle);
    int a_ouah = register_action(action_play_sound, &ouah);
    int a_bad = register_action(action_play_sound, &bad_sound);
    int a_exit = register_action(exit_main, NULL);
    int e;

    named(register_event(immediate, NULL, a_body), "start");
    named(register_event(immediate, NULL, a_bad), "bad sound");
    e = register_event(event_selector, &sel5, a_ring);
    named(e, "selector 5");
    set_event_repeat(e, 1);
    named(register_event(event_clap, &loud, a_ouah), "clap");
    e = register_event(event_tap, &knock, a_front);
    named(e, "tap");
    set_event_repeat(e, 1);
    named(register_event(event_tilt, &lean, a_led3), "tilt");
    e = register_event(event_remote, &mute, a_front);
    named(e, "mute");
    set_event_repeat(e, 1);
    named(register_event(event_remote, &seven, a_ouah), "seven");
    named(register_event(event_ambient, &dark, a_ring), "dark");
    named(register_event(timer, &end, a_exit), "end");
    set_timer(NULL);
    mainloop();
    return 0;
}
