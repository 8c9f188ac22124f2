/* Zero-length and zero-speed motions end at the next poll and fire the
 * stop_motor event once each; with no motion it never fires. */
#include "epuckrt.h"

int main(void)
{
    static param_start_straight zero_len = { 250, 0 };
    static param_start_straight zero_speed = { 0, 100 };
    static param_event_timer t10 = { 10 }, t20 = { 20 }, t30 = { 30 };
    int a_len = register_action(start_straight, &zero_len);
    int a_speed = register_action(start_straight, &zero_speed);
    int a_note = register_action(start_sensor, NULL);
    int a_exit = register_action(exit_main, NULL);
    int e;

    set_timer(NULL);
    e = register_event(event_stop_motor, NULL, a_note);
    set_event_repeat(e, 1);
    register_event(timer, &t10, a_len);
    register_event(timer, &t20, a_speed);
    register_event(timer, &t30, a_exit);
    mainloop();
    return 0;
}
