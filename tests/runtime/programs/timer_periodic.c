/* A repeating timer event fires every `time` ms of the timer; set_timer
 * restarts the phase.  The 5th tick calls exit_main from a user action. */
#include "epuckrt.h"

static int ticks;
static void tick(void *p)
{
    (void)p;
    if (++ticks == 5)
        exit_main(NULL);
}

int main(void)
{
    static param_event_timer period = { 100 }, restart = { 250 };
    int a_tick = register_action(tick, NULL);
    int a_set = register_action(set_timer, NULL);
    int e;

    name_action(a_tick, "tick");
    set_timer(NULL);
    e = register_event(timer, &period, a_tick);   /* 0 */
    set_event_repeat(e, 1);
    register_event(timer, &restart, a_set);       /* 1 */
    mainloop();
    return 0;
}
