/* A user action that stops and starts a new motion in the same poll: no
 * stop_motor event between them; it fires once, when the new one ends. */
#include "epuckrt.h"

static param_start_straight go = { 500, 1000 };
static param_straight_steps short_go = { 1000, 10 };

static void swap(void *p)
{
    (void)p;
    stop_motor(NULL);
    straight_steps(&short_go);
}

int main(void)
{
    static param_event_timer t500 = { 500 };
    int a_go = register_action(start_straight, &go);
    int a_swap = register_action(swap, NULL);
    int a_exit = register_action(exit_main, NULL);

    name_action(a_swap, "swap");
    set_timer(NULL);
    register_event(immediate, NULL, a_go);
    register_event(event_timer, &t500, a_swap);
    register_event(event_stop_motor, NULL, a_exit);
    mainloop();
    return 0;
}
