/* The stop_motor action ends a motion: the stop_motor event fires at the
 * next poll. */
#include "epuckrt.h"

int main(void)
{
    static param_start_straight go = { 500, 1000 };
    static param_event_timer t500 = { 500 };
    int a_go = register_action(start_straight, &go);
    int a_stop = register_action(stop_motor, NULL);
    int a_exit = register_action(exit_main, NULL);

    set_timer(NULL);
    register_event(immediate, NULL, a_go);
    register_event(event_timer, &t500, a_stop);
    register_event(event_stop_motor, NULL, a_exit);
    mainloop();
    return 0;
}
