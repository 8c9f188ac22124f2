/* reset_timer stops the timer: timer events cannot fire any more; the run
 * ends at the time limit (EPUCK_TIME_LIMIT_MS=1000, exit status 3). */
#include "epuckrt.h"

int main(void)
{
    static param_event_timer period = { 100 }, stop = { 150 };
    int a_note = register_action(start_sensor, NULL);
    int a_reset = register_action(reset_timer, NULL);
    int e;

    set_timer(NULL);
    e = register_event(timer, &period, a_note);
    set_event_repeat(e, 1);
    register_event(timer, &stop, a_reset);
    mainloop();
    return 0;
}
